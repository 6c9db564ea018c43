#include "app/experiment/calibration/calibration_report.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include <toml++/toml.h>

#include "render/plot/chart.h"
#include "solver/common/atomic_file.h"
#include "solver/io/output.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

std::string g(double v) { return format_number("%.6g", v); }

void write_parameters(const CalibrationSpec& spec, const CalibrationResult& r, const fs::path& dir) {
  std::ostringstream o;
  o << "parameter,key,scale,min,max,calibrated,mean,sd,lo95,hi95\n";
  for (size_t j = 0; j < spec.parameters.size(); ++j) {
    const CalibrationParameter& p = spec.parameters[j];
    const Estimate& e = r.posterior.estimates[j];
    o << p.name << ',' << p.key << ',' << (p.log_scale ? "log" : "linear") << ',' << g(p.min)
      << ',' << g(p.max) << ',' << g(r.calibrated[j]) << ',' << g(e.mean) << ',' << g(e.sd)
      << ',' << g(e.lo95) << ',' << g(e.hi95) << '\n';
  }
  write_file_atomic((dir / "parameters.csv").string(), o.str());
}

void write_curves(const CalibrationResult& r, const fs::path& dir) {
  std::ostringstream o;
  o << "target,quantity,unit,points,rms_misfit,seed_scatter,measured_scatter,misfit_D\n";
  for (const CurveFit& c : r.curves)
    o << c.target << ',' << c.quantity << ',' << c.unit << ',' << c.points << ','
      << g(c.rms_misfit) << ',' << g(c.seed_scatter) << ','
      << (std::isfinite(c.measured_scatter) ? g(c.measured_scatter) : "") << ',' << g(c.misfit)
      << '\n';
  write_file_atomic((dir / "curves.csv").string(), o.str());
}

void write_design(const CalibrationSpec& spec, const CalibrationResult& r, const fs::path& dir) {
  std::ostringstream o;
  o << "round,design,target";
  for (const CalibrationParameter& p : spec.parameters) o << ',' << p.name;
  o << ",quantity,unit,rms_misfit\n";
  for (const DesignRow& d : r.design) {
    const CalibrationTarget* t = nullptr;
    for (const CalibrationTarget& c : spec.targets)
      if (c.name == d.target) t = &c;
    for (size_t j = 0; j < d.rms.size(); ++j) {
      o << d.round << ',' << d.design << ',' << d.target;
      for (double v : d.parameters) o << ',' << g(v);
      o << ',' << t->y[j].quantity << ',' << t->y[j].unit << ',' << g(d.rms[j]) << '\n';
    }
  }
  write_file_atomic((dir / "design.csv").string(), o.str());
}

toml::table column_table(const CurveColumn& c) {
  toml::table t{{"column", c.column}, {"unit", c.unit}, {"quantity", c.quantity}};
  if (c.scatter) t.insert("scatter", *c.scatter);
  return t;
}

// The calibrated values, and the measured curves they were fitted to (as
// the calibration file's targets, paths relative to the folder, as
// read_calibrated_measured resolves them): the lab draws them.
void write_calibrated(const CalibrationSpec& spec, const CalibrationResult& r, const fs::path& dir) {
  const auto here = [&](const std::string& p) {
    return fs::absolute(p).lexically_relative(fs::absolute(dir)).string();
  };
  toml::table values;
  for (size_t j = 0; j < spec.parameters.size(); ++j)
    values.insert(spec.parameters[j].key, r.calibrated[j]);
  toml::array measured;
  for (const CalibrationTarget& t : spec.targets) {
    toml::table set, m{{"name", t.name},
                       {"scene", here(t.scene)},
                       {"data", here(t.data)},
                       {"x", column_table(t.x)}};
    if (!t.where.empty()) m.insert("where", t.where);
    if (t.zero_at) m.insert("zero_at", *t.zero_at);
    for (const auto& [key, v] : t.set) set.insert(key, v);
    if (!set.empty()) m.insert("set", set);
    toml::array ys;
    for (const CurveColumn& y : t.y) ys.push_back(column_table(y));
    m.insert("y", ys);
    measured.push_back(m);
  }
  const toml::table doc{{"calibrated", values}, {"measured", measured}};
  std::ostringstream o;
  o << "# " << spec.name << ": calibrated by `simsols calibrate " << spec.path << "`\n"
    << "# [calibrated]: the replicates' values (intervals in parameters.csv); [[measured]]: the\n"
    << "# curves they were fitted to (the calibration's targets)\n"
    << doc << '\n';
  write_file_atomic((dir / "calibrated.toml").string(), o.str());
}

void write_summary(const CalibrationSpec& spec, const CalibrationResult& r, const fs::path& dir) {
  std::ostringstream o;
  o << "calibration = " << spec.name << "\nsimulations = " << r.simulations
    << "\neffective_samples = " << g(r.posterior.effective_samples) << '\n';
  for (size_t j = 0; j < spec.parameters.size(); ++j) {
    const Estimate& e = r.posterior.estimates[j];
    const std::string& n = spec.parameters[j].name;
    o << n << " = " << g(r.calibrated[j]) << '\n' << n << "_mean = " << g(e.mean) << '\n'
      << n << "_sd = " << g(e.sd) << '\n' << n << "_lo95 = " << g(e.lo95) << '\n'
      << n << "_hi95 = " << g(e.hi95) << '\n';
  }
  for (const CurveFit& c : r.curves)
    o << c.target << '.' << c.quantity << "_rms_misfit = " << g(c.rms_misfit) << '\n'
      << c.target << '.' << c.quantity << "_seed_scatter = " << g(c.seed_scatter) << '\n';
  for (const std::string& w : calibration_warnings(r)) o << "warning = " << w << '\n';
  o << "wall_seconds = " << g(r.seconds) << '\n';
  write_file_atomic((dir / "summary.txt").string(), o.str());
}

}  // namespace

std::vector<std::string> calibration_warnings(const CalibrationResult& r) {
  std::vector<std::string> w;
  double d = 0;
  int n = 0;
  for (const CurveFit& c : r.curves)
    if (std::isfinite(c.misfit)) d += c.misfit, ++n;
  if (n > 0 && d / n > 4)
    w.push_back("the curves' mean misfit D is " + g(d / n) +
                " (1: within the known errors): the model does not reproduce them, and the "
                "intervals hold only for the best it can do");
  if (r.posterior.effective_samples < 100)
    w.push_back("the posterior rests on " + g(r.posterior.effective_samples) +
                " effective samples: its quantiles are rough");
  for (size_t j = 0; j < r.calibrated.size(); ++j) {
    const Estimate& e = r.posterior.estimates[j];
    if (r.calibrated[j] < e.lo95 || r.calibrated[j] > e.hi95)
      w.push_back("parameter " + std::to_string(j + 1) + "'s calibrated value " + g(r.calibrated[j]) +
                  " lies outside the final 95 % interval (the specimens' scatter moved it)");
  }
  return w;
}

void write_calibration_report(const CalibrationSpec& spec, const CalibrationResult& r,
                              const std::string& out_dir) {
  const fs::path dir = out_dir;
  write_parameters(spec, r, dir);
  write_curves(r, dir);
  write_design(spec, r, dir);
  write_calibrated(spec, r, dir);
  write_calibration_plots(spec, r, out_dir);
  write_summary(spec, r, dir);
}

}  // namespace simsols
