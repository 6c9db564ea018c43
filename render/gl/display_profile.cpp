// Display profiles (assets/displays/*.toml): reading one, and the built-in
// ones. A profile is read in one pass that notes every problem (an unknown
// section or key, a wrong type, a value out of range) and reports them all
// together; a bad field keeps its default meanwhile.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/gl/alioscopy.h"
#include "solver/common/did_you_mean.h"

namespace simsols::render {

DisplayProfileError::DisplayProfileError(std::string f, std::vector<FileProblem> all)
    : std::runtime_error(describe_problems(f, all)), file(std::move(f)), problems(std::move(all)) {}

namespace {

const std::vector<std::string> kSections = {"display", "rig"};
const std::vector<std::string> kDisplayKeys = {"name",  "width",    "height",    "views",
                                               "phase", "reversed", "flip_slant"};
const std::vector<std::string> kRigKeys = {"view_scale", "interaxial_ratio", "interaxial", "focus",
                                           "nearest_views"};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string join(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}

class ProfileReader {
 public:
  explicit ProfileReader(const toml::table& root) : root_(root) {}

  DisplayProfile read() {
    check_keys("", root_, kSections);
    check_keys("display", table("display"), kDisplayKeys);
    check_keys("rig", table("rig"), kRigKeys);
    DisplayProfile p;
    string("name", p.name);
    integer("width", p.width, 1, 16384);
    integer("height", p.height, 1, 16384);
    integer("views", p.views, 8, 8);
    integer("phase", p.phase, 0, 7);
    boolean("display", "reversed", p.reversed);
    boolean("display", "flip_slant", p.flip_slant);
    number("view_scale", p.view_scale, 0, 1, true);
    number("interaxial_ratio", p.interaxial_ratio, 0, 1, true);
    number("interaxial", p.interaxial, 0, 10, false);
    number("focus", p.focus, 0, 1e4, false);
    boolean("rig", "nearest_views", p.nearest_views);
    return p;
  }

  std::vector<FileProblem> problems;

 private:
  void note(const char* code, const toml::node& n, const std::string& field,
            const std::string& message) {
    problems.push_back({code, static_cast<int>(n.source().begin.line), field, message});
  }

  // The section's table; an empty one when absent or not a table (noted).
  const toml::table& table(const char* section) {
    static const toml::table kEmpty;
    const toml::node* n = root_.get(section);
    if (!n) return kEmpty;
    if (!n->is_table()) {
      note("wrong_type", *n, section, std::string("must be a table [") + section + "]");
      return kEmpty;
    }
    return *n->as_table();
  }

  void check_keys(const std::string& section, const toml::table& t,
                  const std::vector<std::string>& allowed) {
    for (const auto& [k, v] : t) {
      const std::string key(k.str());
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      note("unknown_key", v, section.empty() ? key : section + "." + key,
           (section.empty() ? "unknown section '" : "unknown key '") + key + "'" +
               did_you_mean(key, allowed) + "; allowed: " + join(allowed));
    }
  }

  const toml::node* get(const char* section, const char* key) {
    const toml::table* t = root_.get(section) ? root_.get(section)->as_table() : nullptr;
    return t ? t->get(key) : nullptr;
  }

  void string(const char* key, std::string& dst) {
    const toml::node* n = get("display", key);
    if (!n) return;
    if (!n->is_string()) return note("wrong_type", *n, std::string("display.") + key, "must be a string");
    dst = *n->value<std::string>();
  }

  void integer(const char* key, int& dst, int lo, int hi) {
    const std::string field = std::string("display.") + key;
    const toml::node* n = get("display", key);
    if (!n) return;
    if (!n->is_integer()) return note("wrong_type", *n, field, "must be an integer");
    const std::int64_t v = *n->value<std::int64_t>();
    if (v < lo || v > hi)
      return note("out_of_range", *n, field,
                  std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                      std::to_string(hi) + "]");
    dst = int(v);
  }

  void boolean(const char* section, const char* key, bool& dst) {
    const toml::node* n = get(section, key);
    if (!n) return;
    if (!n->is_boolean())
      return note("wrong_type", *n, std::string(section) + "." + key, "must be true or false");
    dst = *n->value<bool>();
  }

  void number(const char* key, double& dst, double lo, double hi, bool open_lo) {
    const std::string field = std::string("rig.") + key;
    const toml::node* n = get("rig", key);
    if (!n) return;
    const auto v = n->value<double>();
    if (!v) return note("wrong_type", *n, field, "must be a number");
    if (!std::isfinite(*v) || (open_lo ? *v <= lo : *v < lo) || *v > hi)
      return note("out_of_range", *n, field,
                  num(*v) + " is outside " + (open_lo ? "(" : "[") + num(lo) + ", " + num(hi) + "]");
    dst = *v;
  }

  const toml::table& root_;
};

}  // namespace

DisplayProfile parse_display_profile(std::string_view text, const std::string& name) {
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw DisplayProfileError(name, {{"syntax", static_cast<int>(e.source().begin.line), "",
                                      "TOML syntax error: " + std::string(e.description())}});
  }
  ProfileReader reader(root);
  DisplayProfile p = reader.read();
  if (!reader.problems.empty()) throw DisplayProfileError(name, std::move(reader.problems));
  return p;
}

DisplayProfile load_display_profile(const std::string& path) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!std::filesystem::is_regular_file(path, ec) || !in)
    throw DisplayProfileError(path, {{"io", 0, "", "cannot read the display profile"}});
  std::ostringstream text;
  text << in.rdbuf();
  return parse_display_profile(text.str(), path);
}

}  // namespace simsols::render
