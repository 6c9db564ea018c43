#include "solver/io/toml_reader.h"

#include <limits>

#include "solver/common/number_text.h"

namespace simsols::scene_toml {

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string item(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string num(double v) { return shortest_number(v); }

std::string join(const std::vector<std::string>& words, bool quoted) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += ", ";
    out += quoted ? "\"" + w + "\"" : w;
  }
  return out;
}

const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

int line_of(const toml::source_region& r) { return static_cast<int>(r.begin.line); }

Vec3 normalized(const Vec3& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n == 0 || !std::isfinite(n) || std::abs(n - 1) <= 4 * std::numeric_limits<double>::epsilon())
    return v;
  return {v[0] / n, v[1] / n, v[2] / n};
}

}  // namespace simsols::scene_toml
