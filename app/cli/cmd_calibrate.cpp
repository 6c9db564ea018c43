// simsols calibrate: a material's parameters fitted to measured curves
// (app/experiment/calibration/calibration.h, docs/calibration.md); and
// simsols predict: tests run with the calibrated material on several
// specimens, as a band (prediction.h).
//
//   simsols calibrate CALIBRATION.toml --out DIR [-q] [--emit slurm | --task K | --collect DIR]
//   simsols predict PREDICTION.toml --out DIR [-q] [--emit slurm | --task K | --collect DIR]
//
// On a Slurm cluster each batch of tests (a calibration's round, its
// replicates; a prediction's tests) is a job array, and the job that
// collects one writes and submits the next (test_batch.h, docs/cluster.md).
// The calibration file names the parameters with their ranges, the
// measured curves with the test of each, and the budget; the prediction
// file the calibrated values and the tests. Everything is read and
// checked before a simulation runs. Rerunning the same command continues
// an interrupted one (Ctrl-C: exit 130).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/cli/cluster_flags.h"
#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/experiment/calibration/calibration.h"
#include "app/experiment/calibration/calibration_report.h"
#include "app/experiment/calibration/prediction.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

struct CalibrateOptions {
  std::string file, out_dir;
  bool quiet = false;
  ClusterFlags cluster;
  std::vector<std::string> command_line;  // for a cluster job (given_args)
};

// What the command says when a cluster run ends it before the report.
void print_ended(const ClusterFlags& f, const std::string& what) {
  if (f.task >= 0)
    std::printf("%s: task %lld done; the collecting job goes on when every task has\n",
                what.c_str(), f.task);
  else if (f.collecting)
    std::printf("%s: a batch collected; the next batch's job is written (above)\n", what.c_str());
}

void print_result(const CalibrationSpec& spec, const CalibrationResult& r, const std::string& out) {
  std::printf("calibration %s: %d simulations, %.0f s now\n", spec.name.c_str(), r.simulations,
              r.seconds);
  for (size_t j = 0; j < spec.parameters.size(); ++j) {
    const Estimate& e = r.posterior.estimates[j];
    std::printf("  %s = %.4g  (posterior mean %.4g, sd %.3g, 95 %% %.4g .. %.4g)\n",
                spec.parameters[j].name.c_str(), r.calibrated[j], e.mean, e.sd, e.lo95, e.hi95);
  }
  for (const CurveFit& c : r.curves)
    std::printf("  %s %s: r.m.s. misfit %.4g %s, one specimen's scatter %.4g %s\n",
                c.target.c_str(), c.quantity.c_str(), c.rms_misfit, c.unit.c_str(),
                c.seed_scatter, c.unit.c_str());
  for (const std::string& w : calibration_warnings(r)) std::printf("  warning: %s\n", w.c_str());
  std::printf("  results in %s (parameters.csv, curves.csv, calibrated.toml, fit_*.png)\n",
              out.c_str());
}

// The folder, the cluster's view of the batches and the device of a run:
// the cluster flags checked first (a cluster run needs --out), the device
// opened only where tests run here (not to emit or collect a job).
struct BatchRun {
  std::string out;
  BatchCluster cluster;
  std::shared_ptr<Device> device;
};

BatchRun batch_run(const CalibrateOptions& opt, const std::string& command,
                   const std::string& default_out) {
  const bool on_cluster = opt.cluster.emitting() || opt.cluster.task >= 0;
  BatchRun b;
  b.out = opt.out_dir.empty() ? default_out : opt.out_dir;
  b.cluster = batch_cluster(opt.cluster, command, opt.command_line, on_cluster ? opt.out_dir : b.out);
  std::filesystem::create_directories(b.out);
  if (b.cluster.mode == BatchCluster::Mode::here || b.cluster.mode == BatchCluster::Mode::task)
    b.device = open_command_device();
  return b;
}

// The exit status of a run that ends before its report: stopped (Ctrl-C, or
// the scheduler's signal before a time limit), or a cluster step; nullopt
// when the report is to be written.
std::optional<int> ended_early(bool interrupted, bool ended, const std::string& stopped_in,
                               const ClusterFlags& f, const std::string& what,
                               const InterruptScope& interrupt) {
  if (interrupted) {
    std::printf("%s interrupted in %s: the same command continues it\n", what.c_str(),
                stopped_in.c_str());
    return interrupt.exit_status();
  }
  if (ended) {
    print_ended(f, what);
    return 0;
  }
  if (f.task >= 0) {  // an array task writes no report
    std::printf("%s: every batch has finished; nothing is left for task %lld\n", what.c_str(),
                f.task);
    return 0;
  }
  return std::nullopt;
}

int calibrate(const CalibrateOptions& opt) {
  const CalibrationSpec spec = read_calibration(opt.file);
  const BatchRun b = batch_run(opt, "calibrate", "out/calibrate-" + spec.name);
  InterruptScope interrupt;
  const CalibrationOptions o{b.device, b.out, opt.quiet, interrupt.stop_function(), &b.cluster};
  const CalibrationResult r = run_calibration(spec, o);
  if (const auto status = ended_early(r.interrupted, r.ended, r.interrupted_dir, opt.cluster,
                                      "calibration " + spec.name, interrupt))
    return *status;
  write_calibration_report(spec, r, b.out);
  print_result(spec, r, b.out);
  return 0;
}

void print_prediction(const PredictionSpec& spec, const PredictionResult& r, const std::string& out) {
  std::printf("prediction %s: %zu tests x %d specimens, %.0f s now\n", spec.name.c_str(),
              spec.tests.size(), spec.specimens, r.seconds);
  for (const PredictedCurve& c : r.curves) {
    const double u = unit_factor(c.unit)->first;
    double peak = 0;
    for (double p : c.peak) peak += p / double(c.peak.size());
    std::printf("  %s %s: peak %.4g %s (mean of the specimens)", c.test.c_str(), c.quantity.c_str(),
                peak / u, c.unit.c_str());
    if (std::isfinite(c.rms_error))
      std::printf(", r.m.s. error %.4g against a band sd of %.4g, %.0f %% of the measured points "
                  "inside the 95 %% prediction interval", c.rms_error / u, c.rms_sd / u, 100 * c.inside);
    std::printf("\n");
  }
  std::printf("  results in %s (prediction.csv, specimens.csv, band_*.csv, predict_*.png)\n",
              out.c_str());
}

int predict(const CalibrateOptions& opt) {
  const PredictionSpec spec = read_prediction(opt.file);
  const BatchRun b = batch_run(opt, "predict", "out/predict-" + spec.name);
  InterruptScope interrupt;
  const CalibrationOptions o{b.device, b.out, opt.quiet, interrupt.stop_function(), &b.cluster};
  const PredictionResult r = run_prediction(spec, o);
  if (const auto status = ended_early(r.interrupted, r.ended, r.interrupted_dir, opt.cluster,
                                      "prediction " + spec.name, interrupt))
    return *status;
  write_prediction_report(spec, r, b.out);
  print_prediction(spec, r, b.out);
  return 0;
}

}  // namespace

CommandRunner add_predict_command(CLI::App& app) {
  auto opt = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "predict",
      "Run tests with a calibrated material on several specimens: bands, with the measured curve "
      "and the error when given; resumable");
  cmd->add_option("prediction", opt->file, "Prediction file (TOML, docs/calibration.md)");
  cmd->add_option("--out,-o", opt->out_dir,
                  "Output folder (default out/predict-<name>; rerun to resume)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  add_cluster_flags(cmd, opt->cluster);
  return [opt, cmd] {
    if (!opt->cluster.collect.empty())
      return collect_from_manifest(opt->cluster, "predict", add_predict_command);
    if (opt->file.empty()) throw UsageError("missing_field", "PREDICTION", "give the prediction file");
    opt->command_line = given_args(cmd, {"prediction", "--out"});
    return predict(*opt);
  };
}

CommandRunner add_calibrate_command(CLI::App& app) {
  auto opt = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit a material's parameters to measured curves (direct shear, triaxial, oedometer), with "
      "their uncertainty; resumable");
  cmd->add_option("calibration", opt->file, "Calibration file (TOML, docs/calibration.md)");
  cmd->add_option("--out,-o", opt->out_dir,
                  "Output folder (default out/calibrate-<name>; rerun to resume)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  add_cluster_flags(cmd, opt->cluster);
  return [opt, cmd] {
    if (!opt->cluster.collect.empty())
      return collect_from_manifest(opt->cluster, "calibrate", add_calibrate_command);
    if (opt->file.empty()) throw UsageError("missing_field", "CALIBRATION", "give the calibration file");
    opt->command_line = given_args(cmd, {"calibration", "--out"});
    return calibrate(*opt);
  };
}

}  // namespace simsols
