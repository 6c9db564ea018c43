#include "app/experiment/calibration/prediction.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <filesystem>

#include "app/experiment/calibration/scene_keys.h"
#include "app/experiment/calibration/test_batch.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

// Specimens no calibration ran: its designs use the scene's seed, its
// replicates 1001 on.
constexpr int kFirstSeed = 2001;

std::vector<BatchTest> prediction_tests(const PredictionSpec& spec, const fs::path& root) {
  const std::vector<std::pair<std::string, double>> calibrated = read_calibrated(spec.calibrated);
  std::vector<BatchTest> tests;
  for (size_t t = 0; t < spec.tests.size(); ++t) {
    const CalibrationTarget& test = spec.tests[t];
    Scene base = read_scene(test.scene);
    const ApparatusKind& kind = required_apparatus_kind(base);
    place_scene(base);
    const double cost = expected_particle_steps(base);
    for (int k = 1; k <= spec.specimens; ++k) {
      const int seed = kFirstSeed + k - 1;  // the test's own keys over the calibrated values
      BatchTest b{scene_with(test.scene, test_values(calibrated, test.set, kind.seed_key, seed)),
                  root / test.name / ("s" + std::to_string(seed)), cost, t, k};
      b.scene.name += "_" + test.name + "_s" + std::to_string(seed);
      tests.push_back(std::move(b));
    }
  }
  return tests;
}

// y averaged over the rows within a twentieth of the x range on either
// side of each: a small specimen's curve has teeth (the collapse of one
// force chain) that a peak taken row by row would pick.
std::vector<double> running_mean(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.empty()) return {};
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double half = 0.5 * (*hi - *lo) / 20;
  std::vector<double> out(y.size());
  for (size_t i = 0; i < y.size(); ++i) {
    double sum = 0;
    int n = 0;
    for (size_t k = 0; k < y.size(); ++k)
      if (std::abs(x[k] - x[i]) <= half && std::isfinite(y[k])) sum += y[k], ++n;
    out[i] = n ? sum / n : NAN;
  }
  return out;
}

// Where a band is drawn: over the measured range, else over what every
// specimen reached.
std::vector<double> band_points(const PredictionSpec& spec, const Curve& measured,
                                const std::vector<Curve>& specimens) {
  if (!measured.x.empty()) return comparison_points(measured, spec.points);
  Curve reach;
  reach.x = {specimens.front().x.front(), INFINITY};
  for (const Curve& c : specimens)
    reach.x[1] = std::min(reach.x[1], *std::max_element(c.x.begin(), c.x.end()));
  return comparison_points(reach, spec.points);
}

PredictedCurve predicted_curve(const PredictionSpec& spec, size_t t, size_t j,
                               const Curve& measured, const std::vector<Curve>& specimens) {
  const CalibrationTarget& test = spec.tests[t];
  PredictedCurve p;
  p.test = test.name;
  p.quantity = test.y[j].quantity;
  p.unit = test.y[j].unit;
  p.x_unit = test.x.unit;
  p.x_quantity = test.x.quantity;
  p.x = band_points(spec, measured, specimens);
  const double n = double(specimens.size());
  // A new specimen's 95 % prediction interval: mean +- t sd sqrt(1 + 1/n).
  const double half = boost::math::quantile(complement(boost::math::students_t(n - 1), 0.025)) *
                      std::sqrt(1 + 1 / n);
  double err = 0, var = 0, inside = 0, compared = 0, measured_points = 0;
  for (double x : p.x) {
    double sum = 0, sq = 0, lo = INFINITY, hi = -INFINITY;
    for (const Curve& c : specimens) {
      const double v = value_at(c.x, c.y[j], x);
      sum += v;
      sq += v * v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    const double mean = sum / n, sd = std::sqrt(std::max(0.0, (sq - n * mean * mean) / (n - 1)));
    const double m = measured.x.empty() ? NAN : value_at(measured.x, measured.y[j], x);
    p.mean.push_back(mean);
    p.sd.push_back(sd);
    p.lo.push_back(lo);
    p.hi.push_back(hi);
    p.measured.push_back(m);
    p.half_width.push_back(half * sd);
    if (!std::isfinite(m)) continue;
    ++measured_points;  // a point the band does not reach counts as outside
    if (!std::isfinite(mean) || !std::isfinite(sd)) continue;
    err += (mean - m) * (mean - m);
    var += sd * sd;
    inside += std::abs(mean - m) <= half * sd ? 1 : 0;
    ++compared;
  }
  if (compared > 0) {
    p.rms_error = std::sqrt(err / compared);
    p.rms_sd = std::sqrt(var / compared);
    p.inside = inside / measured_points;
  }
  const double xu = unit_factor(test.x.unit)->first;
  p.at.resize(spec.at.size());
  for (const Curve& c : specimens) {
    const std::vector<double> smooth = running_mean(c.x, c.y[j]);
    const auto top = std::max_element(smooth.begin(), smooth.end());
    p.peak.push_back(top == smooth.end() ? NAN : *top);
    p.x_at_peak.push_back(top == smooth.end() ? NAN : c.x[size_t(top - smooth.begin())]);
    for (size_t a = 0; a < spec.at.size(); ++a) p.at[a].push_back(value_at(c.x, c.y[j], spec.at[a] * xu));
  }
  return p;
}

}  // namespace

PredictionResult run_prediction(const PredictionSpec& spec, const CalibrationOptions& o) {
  PredictionResult r;
  for (const CalibrationTarget& t : spec.tests)  // a bad measured file is named before anything runs
    r.measured.push_back(t.data.empty() ? Curve{} : measured_curve(t));
  std::vector<BatchTest> tests = prediction_tests(spec, o.out_dir);
  const BatchOutcome out = run_batch(
      tests, 0, {o.device, o.quiet, o.stop_requested, "prediction tests", "tests", o.cluster});
  r.seconds = out.seconds;
  r.interrupted = out.interrupted;
  r.interrupted_dir = out.interrupted_dir;
  r.ended = out.ended;
  if (r.interrupted || r.ended) return r;
  r.specimens.resize(spec.tests.size());
  for (const BatchTest& b : tests) {
    const ApparatusKind& kind = required_apparatus_kind(b.scene);
    r.specimens[b.target].push_back(simulated_curve(spec.tests[b.target], kind, b.dir.string()));
  }
  for (size_t t = 0; t < spec.tests.size(); ++t) {
    for (size_t j = 0; j < spec.tests[t].y.size(); ++j)
      r.curves.push_back(predicted_curve(spec, t, j, r.measured[t], r.specimens[t]));
  }
  return r;
}

}  // namespace simsols
