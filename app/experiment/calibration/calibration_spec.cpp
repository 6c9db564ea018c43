#include "app/experiment/calibration/calibration_spec.h"

#include <cmath>
#include <filesystem>

#include "app/experiment/calibration/scene_keys.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"
#include "solver/io/toml_reader.h"

namespace simsols {

namespace fs = std::filesystem;
using scene_toml::Context;
using scene_toml::Reader;

double CalibrationParameter::value(double u) const {
  return log_scale ? std::exp(std::log(min) + u * (std::log(max) - std::log(min)))
                   : min + u * (max - min);
}

double CalibrationParameter::unit_of(double v) const {
  return log_scale ? (std::log(v) - std::log(min)) / (std::log(max) - std::log(min))
                   : (v - min) / (max - min);
}

int CalibrationSpec::round_size(int r) const {
  return budget / rounds + (r < budget % rounds ? 1 : 0);
}

std::optional<std::pair<double, std::string>> unit_factor(const std::string& unit) {
  static const std::pair<const char*, std::pair<double, const char*>> kUnits[] = {
      {"-", {1, ""}},          {"%", {0.01, ""}},       {"Pa", {1, "stress"}},
      {"kPa", {1e3, "stress"}}, {"MPa", {1e6, "stress"}}, {"m", {1, "length"}},
      {"mm", {1e-3, "length"}}};
  for (const auto& [name, f] : kUnits)
    if (unit == name) return std::make_pair(f.first, std::string(f.second));
  return std::nullopt;
}

namespace {

const std::vector<std::string> kTargetKeys = {"name", "scene", "data", "where", "set",
                                              "zero_at", "x", "y"};
const std::vector<std::string> kUnitNames = {"-", "%", "Pa", "kPa", "MPa", "m", "mm"};

std::string resolve(const std::string& base, const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() ? p : (fs::path(base).parent_path() / path).lexically_normal().string();
}

CalibrationParameter read_parameter(const Reader& r) {
  CalibrationParameter p;
  p.name = r.string("name");
  p.key = r.string("key");
  p.min = r.number("min");
  p.max = r.number("max");
  p.log_scale = r.choice("scale", "linear", {"linear", "log"}) == "log";
  r.check_range("max", p.max, p.max > p.min, "(min, inf): above min = " + scene_toml::num(p.min));
  if (p.log_scale) r.check_range("min", p.min, p.min > 0, "(0, inf) on a log scale");
  return p;
}

// A column's unit and quantity, checked against the quantities of the
// target's apparatus (`kind`, null when its scene could not be read).
CurveColumn read_column(const Reader& r, const ApparatusKind* kind) {
  CurveColumn c;
  c.column = r.string("column");
  c.unit = r.choice("unit", kUnitNames);
  c.quantity = r.string("quantity");
  c.scatter = r.optional_number("scatter");
  if (c.scatter) r.check_range("scatter", *c.scatter, *c.scatter >= 0, "[0, inf)");
  if (!kind) return c;
  std::vector<std::string> names;
  for (const CurveQuantity& q : kind->curves) {
    names.push_back(q.name);
    if (c.quantity != q.name) continue;
    if (unit_factor(c.unit)->second != unit_factor(q.unit)->second)
      r.fail("bad_unit", "unit", "'" + c.unit + "' is not a unit of " + c.quantity +
                                     " (measured in " + q.unit + " by " + kind->test_noun + ")");
    return c;
  }
  r.fail("bad_enum", "quantity",
         "'" + c.quantity + "' is not measured by " + kind->test_noun + "; allowed values: " +
             scene_toml::join(names, true));
}

// A [[targets]] table, or a prediction's [[tests]] (data optional).
CalibrationTarget read_target(const Reader& r, const std::string& file, bool data_required = true) {
  CalibrationTarget t;
  t.name = r.string("name");
  t.scene = resolve(file, r.string("scene"));
  t.data = data_required || r.has("data") ? resolve(file, r.string("data")) : "";
  t.where = r.string("where", "");
  t.zero_at = r.optional_number("zero_at");
  if (!t.where.empty() && t.where.find('=') == std::string::npos)
    r.fail("bad_value", "where", "'" + t.where + "' is not of the form column=value");
  for (const char* k : {"scene", "data"})
    if ((k[0] == 's' || !t.data.empty()) && !fs::exists(k[0] == 's' ? t.scene : t.data))
      r.fail("missing_file", k, "'" + (k[0] == 's' ? t.scene : t.data) + "' does not exist");
  for (auto&& [key, node] : r.table("set")) {  // scene keys: checked when they are set
    if (!node.is_number())
      r.context().fail("wrong_type", scene_toml::line_of(node.source()),
                       scene_toml::child(r.field("set"), key.str()), "expected a number");
    t.set.emplace_back(std::string(key.str()), *node.value<double>());
  }
  const ApparatusKind* kind = apparatus_kind(read_scene(t.scene));
  if (!kind) r.fail("no_apparatus", "scene", "'" + t.scene + "' has no apparatus: no test to run");
  const std::vector<std::string> keys = {"column", "unit", "quantity", "scatter"};
  t.x = read_column(r.sub("x", keys), kind);
  const std::vector<const toml::table*> ys = r.tables("y");
  for (size_t i = 0; i < ys.size(); ++i)
    t.y.push_back(read_column(Reader(*ys[i], scene_toml::item(r.field("y"), i), r.context(), keys),
                              kind));
  if (t.y.empty()) r.fail("missing_key", "y", "a target compares at least one [[targets.y]]");
  return t;
}

// Two entries with the same `what` (a folder's name, a scene key) would
// overwrite each other: refused naming the second.
template <class T, class Key>
void check_unique(const std::vector<T>& v, const char* table, const char* what, Key key,
                  const std::string& path) {
  for (size_t i = 0; i < v.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (key(v[i]) == key(v[j]))
        throw SceneError("duplicate", path, 0, scene_toml::item(table, i) + "." + what,
                         "'" + key(v[i]) + "' is also " + scene_toml::item(table, j) + "'s");
}

// Every target's scene with every parameter at its minimum, then at its
// maximum: a key the scene does not have, or a range its reader refuses,
// is reported before anything runs (SceneError naming the scene and key).
void check_ranges(const CalibrationSpec& s) {
  for (const CalibrationTarget& t : s.targets)
    for (double u : {0.0, 1.0}) {
      std::vector<SceneValue> values;
      for (const auto& [key, v] : t.set) values.push_back({key, v, false});
      for (const CalibrationParameter& p : s.parameters) values.push_back({p.key, p.value(u), false});
      scene_with(t.scene, values);
    }
}

}  // namespace

CalibrationSpec read_calibration(const std::string& path) {
  const toml::table doc = parse_toml_file(path);
  Context ctx{path, {}};
  CalibrationSpec s;
  s.path = path;
  const Reader top(doc, "", ctx, {"calibration", "parameters", "targets"});
  const Reader c = top.sub("calibration", {"name", "budget", "rounds", "replicates", "points"});
  s.name = c.string("name", fs::path(path).stem().string());
  s.budget = static_cast<int>(c.optional_integer("budget").value_or(s.budget));
  s.rounds = static_cast<int>(c.optional_integer("rounds").value_or(s.rounds));
  s.replicates = static_cast<int>(c.optional_integer("replicates").value_or(s.replicates));
  s.points = static_cast<int>(c.optional_integer("points").value_or(s.points));
  c.check_range("rounds", s.rounds, s.rounds >= 1 && s.rounds <= 10, "[1, 10]");
  c.check_range("replicates", s.replicates, s.replicates >= 2 && s.replicates <= 100, "[2, 100]");
  c.check_range("points", s.points, s.points >= 2 && s.points <= 200, "[2, 200]");
  const std::vector<const toml::table*> ps = top.tables("parameters");
  for (size_t i = 0; i < ps.size(); ++i)
    s.parameters.push_back(read_parameter(
        Reader(*ps[i], scene_toml::item("parameters", i), ctx, {"name", "key", "min", "max", "scale"})));
  if (s.parameters.empty() || s.parameters.size() > 6)
    ctx.fail("out_of_range", 0, "parameters",
             std::to_string(s.parameters.size()) + " parameters, allowed [1, 6]");
  const int least = 2 * s.rounds + 2 * static_cast<int>(s.parameters.size());
  c.check_range("budget", s.budget, s.budget >= least && s.budget <= 10000,
                "[" + std::to_string(least) + ", 10000] (2 per round and 2 per parameter at least)");
  const std::vector<const toml::table*> ts = top.tables("targets");
  for (size_t i = 0; i < ts.size(); ++i)
    s.targets.push_back(read_target(Reader(*ts[i], scene_toml::item("targets", i), ctx,
                                           kTargetKeys),
                                    path));
  if (s.targets.empty()) ctx.fail("missing_key", 0, "targets", "at least one [[targets]]");
  ctx.throw_if_any();
  check_unique(s.parameters, "parameters", "key", [](const auto& p) { return p.key; }, path);
  check_unique(s.targets, "targets", "name", [](const auto& t) { return t.name; }, path);
  check_ranges(s);
  return s;
}

std::vector<std::pair<std::string, double>> read_calibrated(const std::string& path) {
  const toml::table doc = parse_toml_file(path);
  Context ctx{path, {}};
  const Reader top(doc, "", ctx, {"calibrated", "measured"});
  std::vector<std::pair<std::string, double>> out;
  for (auto&& [key, node] : top.table("calibrated")) {
    if (!node.is_number())
      ctx.fail("wrong_type", scene_toml::line_of(node.source()),
               scene_toml::child("calibrated", key.str()), "expected a number");
    out.emplace_back(std::string(key.str()), *node.value<double>());
  }
  if (out.empty()) ctx.fail("missing_key", 0, "calibrated", "no calibrated values ([calibrated])");
  ctx.throw_if_any();
  return out;
}

std::vector<CalibrationTarget> read_calibrated_measured(const std::string& path) {
  const toml::table doc = parse_toml_file(path);
  Context ctx{path, {}};
  const Reader top(doc, "", ctx, {"calibrated", "measured"});
  std::vector<CalibrationTarget> out;
  const std::vector<const toml::table*> ms = top.tables("measured");
  for (size_t i = 0; i < ms.size(); ++i)
    out.push_back(read_target(Reader(*ms[i], scene_toml::item("measured", i), ctx,
                                     kTargetKeys),
                              path));
  ctx.throw_if_any();
  return out;
}

PredictionSpec read_prediction(const std::string& path) {
  const toml::table doc = parse_toml_file(path);
  Context ctx{path, {}};
  PredictionSpec s;
  s.path = path;
  const Reader top(doc, "", ctx, {"prediction", "tests"});
  const Reader p = top.sub("prediction", {"name", "calibrated", "specimens", "points", "at"});
  s.name = p.string("name", fs::path(path).stem().string());
  s.calibrated = resolve(path, p.string("calibrated"));
  if (!fs::exists(s.calibrated))
    p.fail("missing_file", "calibrated", "'" + s.calibrated + "' does not exist");
  s.specimens = static_cast<int>(p.optional_integer("specimens").value_or(s.specimens));
  s.points = static_cast<int>(p.optional_integer("points").value_or(s.points));
  p.check_range("specimens", s.specimens, s.specimens >= 2 && s.specimens <= 100, "[2, 100]");
  p.check_range("points", s.points, s.points >= 2 && s.points <= 1000, "[2, 1000]");
  s.at = p.numbers("at", {});
  const std::vector<const toml::table*> ts = top.tables("tests");
  for (size_t i = 0; i < ts.size(); ++i)
    s.tests.push_back(read_target(Reader(*ts[i], scene_toml::item("tests", i), ctx,
                                         kTargetKeys),
                                  path, false));
  if (s.tests.empty()) ctx.fail("missing_key", 0, "tests", "at least one [[tests]]");
  ctx.throw_if_any();
  check_unique(s.tests, "tests", "name", [](const auto& t) { return t.name; }, path);
  return s;
}

}  // namespace simsols
