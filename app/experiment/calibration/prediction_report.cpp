#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "app/experiment/calibration/prediction.h"
#include "render/plot/chart.h"
#include "solver/common/atomic_file.h"
#include "solver/io/output.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

std::string g(double v) { return std::isfinite(v) ? format_number("%.6g", v) : ""; }

double factor(const std::string& unit) { return unit_factor(unit)->first; }

// Mean and Student's 95 % half-interval of `v`.
std::pair<double, double> mean_interval(const std::vector<double>& v) {
  const double n = double(v.size());
  double sum = 0, sq = 0;
  for (double x : v) sum += x;
  const double mean = sum / n;
  for (double x : v) sq += (x - mean) * (x - mean);
  if (v.size() < 2) return {mean, NAN};
  const boost::math::students_t t(n - 1);
  return {mean, boost::math::quantile(complement(t, 0.025)) * std::sqrt(sq / (n - 1) / n)};
}

void write_band(const PredictedCurve& c, const fs::path& dir) {
  const double xu = factor(c.x_unit), yu = factor(c.unit);
  std::ostringstream o;
  o << "# " << c.test << ": " << c.quantity << " predicted, the specimens' mean, standard deviation, "
    << "least and largest; x in " << c.x_unit << ", y in " << c.unit << "\n";
  o << "x,mean,sd,lo,hi,prediction_half_width,measured\n";
  for (size_t i = 0; i < c.x.size(); ++i)
    o << g(c.x[i] / xu) << ',' << g(c.mean[i] / yu) << ',' << g(c.sd[i] / yu) << ','
      << g(c.lo[i] / yu) << ',' << g(c.hi[i] / yu) << ',' << g(c.half_width[i] / yu) << ','
      << g(c.measured[i] / yu) << '\n';
  write_file_atomic((dir / ("band_" + c.test + "_" + c.quantity + ".csv")).string(), o.str());
}

void write_plot(const PredictionSpec& spec, const PredictedCurve& c, const fs::path& dir) {
  const double xu = factor(c.x_unit), yu = factor(c.unit);
  plot::Chart chart;
  chart.title = spec.name + ", " + c.test + ": predicted" + (std::isfinite(c.rms_error) ? " and measured" : "");
  chart.x_label = c.x_quantity + " (" + (c.x_unit == "-" ? std::string("–") : c.x_unit) + ")";
  chart.y_label = c.quantity + " (" + (c.unit == "-" ? std::string("–") : c.unit) + ")";
  plot::Series mean, lo, hi, meas;
  mean.label = "mean of " + std::to_string(spec.specimens) + " specimens";
  lo.label = "95 % prediction interval";
  meas.label = "measured";
  for (size_t i = 0; i < c.x.size(); ++i) {
    const double x = c.x[i] / xu;
    mean.x.push_back(x);
    mean.y.push_back(c.mean[i] / yu);
    lo.x.push_back(x);
    lo.y.push_back((c.mean[i] - c.half_width[i]) / yu);
    hi.x.push_back(x);
    hi.y.push_back((c.mean[i] + c.half_width[i]) / yu);
    meas.x.push_back(x);
    meas.y.push_back(c.measured[i] / yu);
  }
  lo.dashed = hi.dashed = true;
  lo.color = hi.color = mean.color = plot::palette_color(1);
  meas.line = false;
  meas.markers = true;
  meas.color = plot::palette_color(0);
  chart.series = {mean, lo, hi};
  if (std::isfinite(c.rms_error)) chart.series.push_back(meas);
  plot::write_chart_png(chart, (dir / ("predict_" + c.test + "_" + c.quantity + ".png")).string());
}

void write_tables(const PredictionSpec& spec, const PredictionResult& r, const fs::path& dir) {
  std::ostringstream per, all;
  per << "test,quantity,unit,x_unit,specimen,peak,x_at_peak";
  all << "test,quantity,unit,x_unit,specimens,peak_mean,peak_ci95,x_at_peak_mean,x_at_peak_ci95";
  for (double a : spec.at) per << ",at_" << g(a), all << ",at_" << g(a) << "_mean,at_" << g(a) << "_ci95";
  per << '\n';
  all << ",rms_error,rms_sd,inside_prediction_interval\n";
  for (const PredictedCurve& c : r.curves) {
    const double xu = factor(c.x_unit), yu = factor(c.unit);
    const std::string head = c.test + ',' + c.quantity + ',' + c.unit + ',' + c.x_unit + ',';
    for (size_t k = 0; k < c.peak.size(); ++k) {
      per << head << k + 1 << ',' << g(c.peak[k] / yu) << ',' << g(c.x_at_peak[k] / xu);
      for (const std::vector<double>& a : c.at) per << ',' << g(a[k] / yu);
      per << '\n';
    }
    const auto [pm, pi] = mean_interval(c.peak);
    const auto [xm, xi] = mean_interval(c.x_at_peak);
    all << head << c.peak.size() << ',' << g(pm / yu) << ',' << g(pi / yu) << ',' << g(xm / xu)
        << ',' << g(xi / xu);
    for (const std::vector<double>& a : c.at) {
      const auto [am, ai] = mean_interval(a);
      all << ',' << g(am / yu) << ',' << g(ai / yu);
    }
    all << ',' << g(c.rms_error / yu) << ',' << g(c.rms_sd / yu) << ',' << g(c.inside) << '\n';
  }
  write_file_atomic((dir / "specimens.csv").string(), per.str());
  write_file_atomic((dir / "prediction.csv").string(), all.str());
}

}  // namespace

void write_prediction_report(const PredictionSpec& spec, const PredictionResult& r,
                             const std::string& out_dir) {
  const fs::path dir = out_dir;
  for (const PredictedCurve& c : r.curves) {
    write_band(c, dir);
    write_plot(spec, c, dir);
  }
  write_tables(spec, r, dir);
  std::ostringstream s;
  s << "prediction = " << spec.name << "\ncalibrated = " << spec.calibrated
    << "\nspecimens = " << spec.specimens << "\ntests = " << spec.tests.size()
    << "\nwall_seconds = " << g(r.seconds) << '\n';
  write_file_atomic((dir / "summary.txt").string(), s.str());
}

}  // namespace simsols
