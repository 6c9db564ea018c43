// simsols calibrate: a material's parameters fitted to measured curves
// (app/experiment/calibration/calibration.h, docs/calibration.md).
//
//   simsols calibrate CALIBRATION.toml --out DIR [-q]
//
// The calibration file names the parameters with their ranges, the
// measured curves with the test of each, and the budget. Everything is
// read and checked before a simulation runs. Rerunning the same command
// continues an interrupted calibration (Ctrl-C: exit 130).
#include <cstdio>
#include <filesystem>

#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/experiment/calibration/calibration.h"
#include "app/experiment/calibration/calibration_report.h"

namespace simsols {
namespace {

struct CalibrateOptions {
  std::string file, out_dir;
  bool quiet = false;
};

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
  std::printf("  results in %s (parameters.csv, curves.csv, calibrated.toml, fit_*.png)\n",
              out.c_str());
}

int calibrate(const CalibrateOptions& opt) {
  const CalibrationSpec spec = read_calibration(opt.file);
  const std::string out = opt.out_dir.empty() ? "out/calibrate-" + spec.name : opt.out_dir;
  std::filesystem::create_directories(out);
  InterruptScope interrupt;
  CalibrationOptions o;
  o.device = open_command_device();
  o.out_dir = out;
  o.quiet = opt.quiet;
  o.stop_requested = interrupt.stop_function();
  const CalibrationResult r = run_calibration(spec, o);
  if (r.interrupted) {
    std::printf("calibration interrupted in %s: the same command continues it\n",
                r.interrupted_dir.c_str());
    return interrupt.exit_status();
  }
  write_calibration_report(spec, r, out);
  print_result(spec, r, out);
  return 0;
}

}  // namespace

CommandRunner add_calibrate_command(CLI::App& app) {
  auto opt = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit a material's parameters to measured curves (direct shear, triaxial, oedometer), with "
      "their uncertainty; resumable");
  cmd->add_option("calibration", opt->file, "Calibration file (TOML, docs/calibration.md)")
      ->required();
  cmd->add_option("--out,-o", opt->out_dir,
                  "Output folder (default out/calibrate-<name>; rerun to resume)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  return [opt] { return calibrate(*opt); };
}

}  // namespace simsols
