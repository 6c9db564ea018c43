#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/experiment/calibration/calibration_report.h"
#include "render/plot/chart.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

plot::Series curve_series(const std::string& label, const Curve& c, size_t j, double x_unit,
                          double y_unit) {
  plot::Series s;
  s.label = label;
  for (size_t i = 0; i < c.x.size(); ++i) {
    s.x.push_back(c.x[i] / x_unit);
    s.y.push_back(c.y[j][i] / y_unit);
  }
  return s;
}

std::string axis(const CurveColumn& c) {
  return c.quantity + " (" + (c.unit == "-" ? std::string("–") : c.unit) + ")";
}

void write_fit(const CalibrationSpec& spec, const CalibrationResult& r, size_t t, size_t j,
               const fs::path& dir) {
  const CalibrationTarget& target = spec.targets[t];
  const double xu = unit_factor(target.x.unit)->first, yu = unit_factor(target.y[j].unit)->first;
  plot::Chart c;
  c.title = spec.name + ", " + target.name + ": measured and calibrated";
  c.x_label = axis(target.x);
  c.y_label = axis(target.y[j]);
  plot::Series m = curve_series("measured", r.measured[t], j, xu, yu);
  m.line = false;
  m.markers = true;
  c.series.push_back(m);
  for (size_t k = 0; k < r.replicates[t].size(); ++k) {
    plot::Series s = curve_series(k == 0 ? "simulated, " + std::to_string(r.replicates[t].size()) +
                                               " specimens"
                                         : "",
                                  r.replicates[t][k], j, xu, yu);
    s.color = plot::palette_color(1);
    c.series.push_back(s);
  }
  // The measured range, not the simulations' longer travel.
  c.x_min = std::min(0.0, m.x.front());
  c.x_max = *std::max_element(m.x.begin(), m.x.end());
  plot::write_chart_png(c, (dir / ("fit_" + target.name + "_" + target.y[j].quantity + ".png")).string());
}

void write_marginal(const CalibrationSpec& spec, const CalibrationResult& r, size_t j,
                    const fs::path& dir) {
  const CalibrationParameter& p = spec.parameters[j];
  constexpr int kBins = 40;
  std::vector<double> mass(kBins, 0.0);
  const double lo = r.posterior.u.col(j).minCoeff(), hi = r.posterior.u.col(j).maxCoeff();
  const double width = std::max(hi - lo, 1e-12);
  for (int i = 0; i < r.posterior.u.rows(); ++i)
    mass[std::min(kBins - 1, int((r.posterior.u(i, j) - lo) / width * kBins))] += r.posterior.weight(i);
  plot::Chart c;
  c.title = spec.name + ": posterior of " + p.name;
  c.x_label = p.name + (p.log_scale ? " (log scale)" : "");
  c.y_label = "Probability per bin";
  c.x_log = p.log_scale;
  plot::Series s;
  s.label = p.name;
  for (int b = 0; b < kBins; ++b) {
    s.x.push_back(p.value(lo + width * (b + 0.5) / kBins));
    s.y.push_back(mass[b]);
  }
  c.series.push_back(s);
  c.markers.push_back({r.calibrated[j], 0, "calibrated"});
  c.legend = false;
  plot::write_chart_png(c, (dir / ("posterior_" + p.name + ".png")).string());
}

}  // namespace

void write_calibration_plots(const CalibrationSpec& spec, const CalibrationResult& r,
                             const std::string& out_dir) {
  const fs::path dir = out_dir;
  for (size_t t = 0; t < spec.targets.size(); ++t)
    for (size_t j = 0; j < spec.targets[t].y.size(); ++j) write_fit(spec, r, t, j, dir);
  for (size_t j = 0; j < spec.parameters.size(); ++j) write_marginal(spec, r, j, dir);
}

}  // namespace simsols
