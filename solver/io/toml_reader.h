// Reading TOML scene tables: typed access to one table with its dotted path.
//
// A Reader wraps one toml++ table and the dotted path it has in the file
// ("walls[1].servo"). Its constructor notes every key outside the table's
// allowed list (unknown_key, with "did you mean"); its accessors check types
// and finiteness and fail with the field's path and line. Problems that let
// the reading go on are collected in the shared Context and reported
// together with the first one that stops it (a SceneError listing them all).
// The per-table readers (scene_tables.h) are written with it.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "solver/common/did_you_mean.h"
#include "solver/common/errors.h"
#include "solver/scene/choices.h"
#include "solver/scene/scene.h"

namespace simsols::scene_toml {

// "path.key" ("key" at the top level), "path[i]".
std::string child(const std::string& path, std::string_view key);
std::string item(const std::string& path, size_t i);
// Shortest round-trip text of a number.
std::string num(double v);
// "a, b" or "\"a\", \"b\"".
std::string join(const std::vector<std::string>& words, bool quoted);
// "a table", "a string", ... for type errors.
const char* type_name(const toml::node& n);
int line_of(const toml::source_region& r);
// Divides by the length unless the vector is zero or already unit (so a
// written and re-read unit vector keeps its exact bits).
Vec3 normalized(const Vec3& v);

// What every Reader needs besides its table: the file, and the problems
// that let the reading go on (unknown keys), reported together with the
// first one that stops it, or at the end.
struct Context {
  std::string file;
  std::vector<SceneProblem> found;

  void note(const std::string& code, int line, const std::string& field,
            const std::string& message) {
    found.push_back({code, line, field, message});
  }
  [[noreturn]] void fail(const std::string& code, int line, const std::string& field,
                         const std::string& message) {
    note(code, line, field, message);
    throw SceneError(file, found);
  }
  void throw_if_any() const {
    if (!found.empty()) throw SceneError(file, found);
  }
};

class Reader {
 public:
  // Notes every key outside `allowed` (unknown_key); the reading goes on.
  Reader(const toml::table& table, std::string path, Context& ctx, std::vector<std::string> allowed)
      : table_(table), path_(std::move(path)), ctx_(ctx), allowed_(std::move(allowed)) {
    for (auto&& [key, node] : table_) {
      if (std::find(allowed_.begin(), allowed_.end(), key.str()) != allowed_.end()) continue;
      ctx_.note("unknown_key", line_of(key.source()), child(path_, key.str()),
                "unknown key '" + std::string(key.str()) + "'" +
                    did_you_mean(key.str(), allowed_) +
                    "; allowed keys: " + join(allowed_, false));
    }
  }

  std::string field(std::string_view key) const { return child(path_, key); }
  Context& context() const { return ctx_; }
  // The sub-table at `key` (empty when absent), read with its own keys.
  Reader sub(std::string_view key, std::vector<std::string> allowed) const {
    return Reader(table(key), field(key), ctx_, std::move(allowed));
  }
  bool has(std::string_view key) const { return table_.contains(key); }
  bool is_boolean(std::string_view key) const {
    const toml::node* n = get(key);
    return n && n->is_boolean();
  }

  [[noreturn]] void fail(const std::string& code, std::string_view key,
                         const std::string& message) const {
    const toml::node* n = table_.get(key);
    ctx_.fail(code, line_of(n ? n->source() : table_.source()), field(key), message);
  }

  void check_range(std::string_view key, double v, bool ok, const std::string& allowed) const {
    if (!ok) fail("out_of_range", key, num(v) + " is out of range, allowed " + allowed);
  }

  // Keys allowed by the table kind but not by its `type` (noted, as unknown keys).
  void forbid(const std::vector<std::string>& keys, const std::string& reason) const {
    for (const std::string& k : keys)
      if (has(k))
        ctx_.note("unknown_key", line_of(table_.get(k)->source()), field(k),
                  "unknown key '" + k + "': " + reason);
  }

  double number(std::string_view key) const { return to_number(key, require(key)); }
  double number(std::string_view key, double fallback) const {
    const toml::node* n = get(key);
    return n ? to_number(key, *n) : fallback;
  }
  std::optional<double> optional_number(std::string_view key) const {
    const toml::node* n = get(key);
    return n ? std::optional<double>(to_number(key, *n)) : std::nullopt;
  }

  // An array of numbers, e.g. load_steps = [25e3, 50e3]; `fallback` when absent.
  std::vector<double> numbers(std::string_view key, const std::vector<double>& fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    const toml::array* a = as_array(key, *n);
    std::vector<double> out;
    for (size_t k = 0; k < a->size(); ++k) {
      const toml::node& e = *a->get(k);
      if (!e.is_integer() && !e.is_floating_point())
        fail("wrong_type", key,
             "element " + std::to_string(k) + " is " + type_name(e) + ", expected a number");
      out.push_back(to_number(key, e));
    }
    return out;
  }

  // An array of `width`-number arrays, e.g. spheres = [[0, 0, 0, 1e-3], ...].
  std::vector<std::vector<double>> rows(std::string_view key, size_t width) const {
    const toml::array* a = as_array(key, require(key));
    std::vector<std::vector<double>> out;
    for (size_t k = 0; k < a->size(); ++k) {
      const toml::node& row = *a->get(k);
      const toml::array* r = row.as_array();
      if (!r || r->size() != width)
        fail("bad_vector", key,
             "element " + std::to_string(k) + " is not an array of " + std::to_string(width) +
                 " numbers");
      out.emplace_back();
      for (size_t c = 0; c < width; ++c) {
        const toml::node& e = *r->get(c);
        if (!e.is_integer() && !e.is_floating_point())
          fail("wrong_type", key,
               "element " + std::to_string(k) + "[" + std::to_string(c) + "] is " + type_name(e) +
                   ", expected a number");
        out.back().push_back(to_number(key, e));
      }
    }
    return out;
  }

  std::optional<std::int64_t> optional_integer(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_integer())
      fail("wrong_type", key, std::string("expected an integer, got ") + type_name(*n));
    return n->as_integer()->get();
  }
  std::int64_t integer(std::string_view key) const {
    require(key);
    return *optional_integer(key);
  }

  bool boolean(std::string_view key, bool fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_boolean())
      fail("wrong_type", key, std::string("expected a boolean, got ") + type_name(*n));
    return n->as_boolean()->get();
  }

  std::string string(std::string_view key) const { return to_string(key, require(key)); }
  std::string string(std::string_view key, const std::string& fallback) const {
    const toml::node* n = get(key);
    return n ? to_string(key, *n) : fallback;
  }

  // A string that must be one of `values` (bad_enum otherwise).
  std::string choice(std::string_view key, const std::vector<std::string>& values) const {
    return checked_choice(key, string(key), values);
  }
  std::string choice(std::string_view key, const std::string& fallback,
                     const std::vector<std::string>& values) const {
    return checked_choice(key, string(key, fallback), values);
  }

  // An enumerated choice (choices.h): its name at `key`, or `fallback`.
  template <class E>
  E choice(std::string_view key, E fallback) const {
    const std::string name = checked_choice(key, string(key, choice_name(fallback)), choice_names<E>());
    return *parse_choice<E>(name);
  }

  Vec3 vec3(std::string_view key) const { return to_vec3(key, require(key)); }
  Vec3 vec3(std::string_view key, const Vec3& fallback) const {
    const toml::node* n = get(key);
    return n ? to_vec3(key, *n) : fallback;
  }

  // Index of the material named by the string at `key`.
  int material(std::string_view key, const Scene& scene) const {
    return material_index(key, string(key), scene);
  }

  // Exactly two material names, e.g. materials = ["glass", "steel"].
  std::pair<int, int> material_pair(std::string_view key, const Scene& scene) const {
    const toml::array* a = as_array(key, require(key));
    if (a->size() != 2)
      fail("bad_vector", key,
           "has " + std::to_string(a->size()) + " elements, expected 2 material names");
    return {material_index(key, to_string(key, *a->get(0)), scene),
            material_index(key, to_string(key, *a->get(1)), scene)};
  }

  // The sub-table at `key`; an empty table when absent.
  const toml::table& table(std::string_view key) const {
    static const toml::table kEmpty;
    const toml::node* n = get(key);
    if (!n) return kEmpty;
    if (!n->is_table())
      fail("wrong_type", key,
           std::string("expected a table [") + std::string(key) + "], got " + type_name(*n));
    return *n->as_table();
  }

  // The tables of an array of tables ([[key]] or key = [{...}]); empty when absent.
  std::vector<const toml::table*> tables(std::string_view key) const {
    std::vector<const toml::table*> out;
    const toml::node* n = get(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a)
      fail("wrong_type", key,
           "expected an array of tables [[" + std::string(key) + "]], got " + type_name(*n));
    for (size_t i = 0; i < a->size(); ++i) {
      const toml::node& e = *a->get(i);
      if (!e.is_table())
        ctx_.fail("wrong_type", line_of(e.source()), item(field(key), i),
                  std::string("expected a table, got ") + type_name(e));
      out.push_back(e.as_table());
    }
    return out;
  }

 private:
  std::string checked_choice(std::string_view key, const std::string& v,
                             const std::vector<std::string>& values) const {
    if (std::find(values.begin(), values.end(), v) == values.end())
      fail("bad_enum", key, "'" + v + "' is not allowed; allowed values: " + join(values, true));
    return v;
  }
  const toml::node* get(std::string_view key) const { return table_.get(key); }

  const toml::node& require(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) fail("missing_field", key, "required field '" + std::string(key) + "' is missing");
    return *n;
  }

  double to_number(std::string_view key, const toml::node& n) const {
    if (n.is_integer()) return static_cast<double>(n.as_integer()->get());
    if (!n.is_floating_point())
      fail("wrong_type", key, std::string("expected a number, got ") + type_name(n));
    const double v = n.as_floating_point()->get();
    if (!std::isfinite(v)) fail("not_finite", key, num(v) + " is not a finite number");
    return v;
  }

  std::string to_string(std::string_view key, const toml::node& n) const {
    if (!n.is_string())
      fail("wrong_type", key, std::string("expected a string, got ") + type_name(n));
    return n.as_string()->get();
  }

  const toml::array* as_array(std::string_view key, const toml::node& n) const {
    if (!n.is_array())
      fail("wrong_type", key, std::string("expected an array, got ") + type_name(n));
    return n.as_array();
  }

  Vec3 to_vec3(std::string_view key, const toml::node& n) const {
    const toml::array* a = as_array(key, n);
    if (a->size() != 3)
      fail("bad_vector", key,
           "has " + std::to_string(a->size()) + " elements, expected 3 numbers [x, y, z]");
    Vec3 v{};
    for (size_t k = 0; k < 3; ++k) {
      const toml::node& e = *a->get(k);
      if (e.is_integer()) {
        v[k] = static_cast<double>(e.as_integer()->get());
      } else if (e.is_floating_point()) {
        v[k] = e.as_floating_point()->get();
        if (!std::isfinite(v[k]))
          fail("not_finite", key,
               "component " + std::to_string(k) + " is " + num(v[k]) + ", not a finite number");
      } else {
        fail("bad_vector", key,
             "component " + std::to_string(k) + " is " + type_name(e) + ", expected a number");
      }
    }
    return v;
  }

  int material_index(std::string_view key, const std::string& name, const Scene& scene) const {
    const int i = scene.material_index(name);
    if (i >= 0) return i;
    std::vector<std::string> names;
    for (const Material& m : scene.materials) names.push_back(m.name);
    fail("unknown_material", key,
         "material '" + name + "' is not defined; defined materials: " +
             (names.empty() ? std::string("none") : join(names, true)));
  }

  const toml::table& table_;
  std::string path_;
  Context& ctx_;
  std::vector<std::string> allowed_;
};

}  // namespace simsols::scene_toml
