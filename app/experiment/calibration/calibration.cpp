#include "app/experiment/calibration/calibration.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/experiment/calibration/scene_keys.h"
#include "app/experiment/calibration/test_batch.h"
#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

constexpr int kFirstReplicateSeed = 1001;

// What every round compares against: the measured curves, where they are
// compared, and each target's test.
struct Problem {
  const CalibrationSpec& spec;
  std::vector<Curve> measured;
  std::vector<std::vector<double>> points;  // per target
  std::vector<const ApparatusKind*> kinds;  // per target
  std::vector<double> cost;                 // particle-steps of a target's test
  Comparison comparison;
  int values = 0;                           // F: all targets' compared values
};

Problem make_problem(const CalibrationSpec& spec) {
  Problem p{spec, {}, {}, {}, {}, {}, 0};
  for (const CalibrationTarget& t : spec.targets) {
    p.measured.push_back(measured_curve(t));
    p.points.push_back(comparison_points(p.measured.back(), spec.points));
    Scene scene = read_scene(t.scene);
    p.kinds.push_back(&required_apparatus_kind(scene));
    place_scene(scene);
    p.cost.push_back(expected_particle_steps(scene));
  }
  std::vector<double> m, s;
  for (size_t t = 0; t < spec.targets.size(); ++t)
    for (size_t j = 0; j < spec.targets[t].y.size(); ++j) {
      const CurveColumn& y = spec.targets[t].y[j];
      const double unit = unit_factor(y.unit)->first;
      for (double x : p.points[t]) {
        m.push_back(value_at(p.measured[t].x, p.measured[t].y[j], x));
        s.push_back(y.scatter.value_or(0) * unit);
        p.comparison.curve_of.push_back(p.comparison.curves);
      }
      p.comparison.test_of.push_back(static_cast<int>(t));
      ++p.comparison.curves;
    }
  p.comparison.tests = static_cast<int>(spec.targets.size());
  p.values = static_cast<int>(m.size());
  p.comparison.measured = Eigen::Map<Eigen::VectorXd>(m.data(), p.values);
  p.comparison.scatter = Eigen::Map<Eigen::VectorXd>(s.data(), p.values);
  p.comparison.seed_scatter = Eigen::VectorXd::Zero(p.values);
  return p;
}

using CalibrationRun = BatchTest;

// A design's test: the target's keys, then the parameters' values.
std::vector<SceneValue> values_of(const Problem& p, size_t target, const Eigen::VectorXd& u,
                                  int seed) {
  KeyValues parameters;
  for (size_t j = 0; j < p.spec.parameters.size(); ++j)
    parameters.emplace_back(p.spec.parameters[j].key, p.spec.parameters[j].value(u(j)));
  return test_values(p.spec.targets[target].set, parameters, p.kinds[target]->seed_key, seed);
}

std::vector<CalibrationRun> make_runs(const Problem& p, const Eigen::MatrixXd& designs,
                                      const fs::path& root, const std::string& round, int seed) {
  std::vector<CalibrationRun> runs;
  for (int i = 0; i < designs.rows(); ++i)
    for (size_t t = 0; t < p.spec.targets.size(); ++t) {
      CalibrationRun r;
      const std::string folder = seed > 0 ? round : round + "_" + std::to_string(i);
      r.scene = scene_with(p.spec.targets[t].scene, values_of(p, t, designs.row(i).transpose(), seed));
      r.scene.name += "_" + p.spec.targets[t].name + "_" + folder;
      r.dir = root / "runs" / folder / p.spec.targets[t].name;
      r.cost = p.cost[t];
      r.target = t;
      r.design = i;
      runs.push_back(std::move(r));
    }
  return runs;
}

// Runs (or keeps) every test of the batch `runs`; true when the command
// ends there (interrupted, or on a cluster).
bool run_all(std::vector<CalibrationRun>& runs, const std::string& batch, double later_cost,
             const CalibrationOptions& o, CalibrationResult& result) {
  const BatchOutcome out = run_batch(
      runs, later_cost, {o.device, o.quiet, o.stop_requested, "calibration tests", batch, o.cluster});
  result.seconds += out.seconds;
  result.interrupted = out.interrupted;
  result.interrupted_dir = out.interrupted_dir;
  result.ended = out.ended;
  return out.interrupted || out.ended;
}

// A design's compared values (F), its tests' curves read back.
Eigen::VectorXd design_values(const Problem& p, const std::vector<CalibrationRun>& runs, int design,
                              std::vector<Curve>* curves) {
  Eigen::VectorXd v(p.values);
  int f = 0;
  for (const CalibrationRun& r : runs) {
    if (r.design != design) continue;
    Curve c;
    try {
      c = simulated_curve(p.spec.targets[r.target], *p.kinds[r.target], r.dir.string());
    } catch (const ReadError& e) {  // a test that measured nothing: no values, not an end
      std::fprintf(stderr, "[calibrate] %s: %s; its values are left out\n", r.dir.c_str(), e.what());
      c.y.resize(p.spec.targets[r.target].y.size());
    }
    for (const std::vector<double>& y : c.y)
      for (double x : p.points[r.target]) v(f++) = value_at(c.x, y, x);
    if (curves) curves->push_back(c);
  }
  return v;
}

}  // namespace

namespace {

// The design's rows of the design table: each target's r.m.s. misfit per y.
void record_design(const Problem& p, const std::string& round, int design,
                   const Eigen::VectorXd& u, const Eigen::VectorXd& values,
                   std::vector<DesignRow>& out) {
  int f = 0;
  for (size_t t = 0; t < p.spec.targets.size(); ++t) {
    DesignRow row{round, design, p.spec.targets[t].name, {}, {}};
    for (size_t j = 0; j < p.spec.parameters.size(); ++j)
      row.parameters.push_back(p.spec.parameters[j].value(u(j)));
    for (const CurveColumn& y : p.spec.targets[t].y) {
      double sum = 0;
      int n = 0;
      for (size_t k = 0; k < p.points[t].size(); ++k, ++f)
        if (std::isfinite(values(f))) {
          sum += std::pow(values(f) - p.comparison.measured(f), 2);
          ++n;
        }
      row.rms.push_back(n ? std::sqrt(sum / n) / unit_factor(y.unit)->first : NAN);
    }
    out.push_back(std::move(row));
  }
}

void append_row(Eigen::MatrixXd& m, const Eigen::VectorXd& row) {
  m.conservativeResize(m.rows() + 1, row.size());
  m.row(m.rows() - 1) = row.transpose();
}

void print_round(const CalibrationSpec& spec, const std::string& what, const Posterior& post) {
  std::fprintf(stderr, "[calibrate] %s:", what.c_str());
  for (size_t j = 0; j < spec.parameters.size(); ++j) {
    const Estimate& e = post.estimates[j];
    std::fprintf(stderr, " %s = %.4g (95 %% %.4g .. %.4g)", spec.parameters[j].name.c_str(),
                 e.best, e.lo95, e.hi95);
  }
  std::fprintf(stderr, ", effective samples %.0f\n", post.effective_samples);
}

// The replicates' seed-to-seed scatter (into the comparison) and each
// curve's fit of their mean.
void measure_replicates(Problem& p, const std::vector<Eigen::VectorXd>& reps,
                        CalibrationResult& result) {
  // Mean and standard deviation over the replicates that reached each
  // point; NaN where fewer than two did.
  Eigen::VectorXd mean(p.values);
  for (int f = 0; f < p.values; ++f) {
    double sum = 0, sq = 0;
    int n = 0;
    for (const Eigen::VectorXd& r : reps)
      if (std::isfinite(r(f))) sum += r(f), sq += r(f) * r(f), ++n;
    mean(f) = n > 0 ? sum / n : NAN;
    p.comparison.seed_scatter(f) =
        n >= 2 ? std::sqrt(std::max(0.0, (sq - n * mean(f) * mean(f)) / (n - 1))) : NAN;
  }
  const std::vector<double> d =
      curve_misfits(p.comparison, mean, Eigen::VectorXd::Zero(p.values));
  int f = 0, curve = 0;
  for (size_t t = 0; t < p.spec.targets.size(); ++t)
    for (const CurveColumn& y : p.spec.targets[t].y) {
      const double unit = unit_factor(y.unit)->first;
      CurveFit c{p.spec.targets[t].name, y.quantity, y.unit, 0, 0, 0,
                 y.scatter ? *y.scatter : NAN, d[curve++]};
      double miss = 0, scatter = 0;
      for (size_t k = 0; k < p.points[t].size(); ++k, ++f)
        if (std::isfinite(mean(f)) && std::isfinite(p.comparison.seed_scatter(f))) {
          miss += std::pow(mean(f) - p.comparison.measured(f), 2);
          scatter += std::pow(p.comparison.seed_scatter(f), 2);
          ++c.points;
        }
      c.rms_misfit = c.points ? std::sqrt(miss / c.points) / unit : NAN;
      c.seed_scatter = c.points ? std::sqrt(scatter / c.points) / unit : NAN;
      result.curves.push_back(c);
    }
}

}  // namespace

CalibrationResult run_calibration(const CalibrationSpec& spec, const CalibrationOptions& o) {
  Problem p = make_problem(spec);
  CalibrationResult result;
  result.measured = p.measured;
  double per_design = 0;
  for (double c : p.cost) per_design += c;
  const fs::path root = o.out_dir;
  Eigen::MatrixXd u_all(0, spec.parameters.size()), y_all(0, p.values);
  Posterior post;
  for (int r = 0; r < spec.rounds; ++r) {
    const int n = spec.round_size(r);
    const Eigen::MatrixXd designs = r == 0 ? sobol_designs(int(spec.parameters.size()), n)
                                           : draw_designs(post, n, std::uint64_t(r));
    const std::string round = "round" + std::to_string(r);
    std::vector<CalibrationRun> runs = make_runs(p, designs, root, round, 0);
    const double later = per_design * (spec.budget - u_all.rows() - n + spec.replicates);
    if (run_all(runs, round, later, o, result)) return result;
    for (int i = 0; i < n; ++i) {
      const Eigen::VectorXd v = design_values(p, runs, i, nullptr);
      append_row(u_all, designs.row(i).transpose());
      append_row(y_all, v);
      record_design(p, std::to_string(r), i, designs.row(i).transpose(), v, result.design);
    }
    post = posterior(spec, p.comparison, Surrogate(u_all, y_all));
    if (!o.quiet) print_round(spec, "round " + std::to_string(r + 1) + "/" + std::to_string(spec.rounds), post);
  }
  const Eigen::VectorXd best = post.best_u;
  std::vector<std::vector<CalibrationRun>> batch;  // per replicate
  std::vector<CalibrationRun> all;
  for (int k = 0; k < spec.replicates; ++k) {
    batch.push_back(make_runs(p, best.transpose(), root, "replicate" + std::to_string(k),
                              kFirstReplicateSeed + k));
    all.insert(all.end(), batch.back().begin(), batch.back().end());
  }
  if (run_all(all, "replicates", 0, o, result)) return result;
  std::vector<Eigen::VectorXd> reps;
  result.replicates.resize(spec.targets.size());
  for (int k = 0; k < spec.replicates; ++k) {
    const std::vector<CalibrationRun>& runs = batch[k];
    std::vector<Curve> curves;
    reps.push_back(design_values(p, runs, 0, &curves));
    for (size_t t = 0; t < curves.size(); ++t) result.replicates[t].push_back(curves[t]);
    record_design(p, "replicate", k, best, reps.back(), result.design);
  }
  measure_replicates(p, reps, result);
  result.posterior = posterior(spec, p.comparison, Surrogate(u_all, y_all));
  for (size_t j = 0; j < spec.parameters.size(); ++j)
    result.calibrated.push_back(spec.parameters[j].value(best(j)));
  result.simulations = static_cast<int>((u_all.rows() + spec.replicates) * spec.targets.size());
  if (!o.quiet) print_round(spec, "with the specimens' scatter", result.posterior);
  return result;
}

}  // namespace simsols
