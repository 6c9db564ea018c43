#include "app/experiment/shear_run.h"
#include "app/experiment/test_title.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "app/experiment/shear_plots.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

// The shear test's part of the run: shear.csv, the plots, summary.txt.
class ShearOutputs : public ProgrammeOutputs {
 public:
  explicit ShearOutputs(ShearTest& test) : test_(test) {}
  LoadingProgramme& programme() override { return test_; }
  void save_rows(const fs::path& dir) override {
    write_file_atomic((dir / "shear.csv").string(), shear_rows_csv(test_.rows()));
  }
  std::string describe() override {
    char buf[128];
    std::snprintf(buf, sizeof buf, "servo gain %.3g m/(s N), integral time %.3g s",
                  test_.servo_gain(), test_.servo_integral_time());
    return buf;
  }
  void on_measuring(const std::string& label) override {
    std::fprintf(stderr,
                 "%s[%s] shearing at %.4g mm/s (inertial number %.2g at the start; target "
                 "< 1e-3), specimen height %.2f mm\n",
                 isatty(fileno(stderr)) ? "\r" : "", label.c_str(), test_.shear_speed() * 1e3,
                 test_.inertial_number(), test_.summary().specimen_height * 1e3);
  }
  void write_results(Simulation& sim, const fs::path& dir, double wall_seconds) override {
    ShearSummary summary = test_.summary();
    summary.wall_seconds = wall_seconds;
    write_shear_plots(dir.string(), test_title(sim.scene()), test_.rows(), summary);
    write_file_atomic((dir / "summary.txt").string(), shear_summary_text(summary));
  }

 private:
  ShearTest& test_;
};

ShearRunResult drive(Simulation& sim, ShearTest& test, const ShearRunOptions& opt,
                     double wall_before) {
  ShearOutputs outputs(test);
  const ProgrammeRunState state = drive_programme(sim, outputs, opt, wall_before);
  ShearRunResult result;
  result.rows = test.rows();
  result.summary = test.summary();
  result.summary.wall_seconds = state.wall_seconds;
  result.finished = state.finished;
  result.interrupted = state.interrupted;
  result.steps = state.steps;
  result.particles = state.particles;
  result.dt = state.dt;
  return result;
}

}  // namespace

std::string where_test_is(const Simulation& sim, const ShearTest& test) {
  const double dx = test.rows().empty() ? 0 : test.rows().back().displacement;
  char buf[160];
  std::snprintf(buf, sizeof buf, "step %lld, t = %.6g s, %s, dx = %.3f mm (%zu rows)",
                static_cast<long long>(sim.steps()), sim.time(), phase_name(test.phase()),
                dx * 1e3, test.rows().size());
  return buf;
}

ShearRunResult resume_shear(std::unique_ptr<Simulation> sim, const std::string& state,
                            const ShearRunOptions& opt) {
  const std::string ck = (fs::path(opt.out_dir) / "checkpoint.bin").string();
  if (!sim->scene().shear_box)
    throw SceneError("bad_checkpoint", ck, 0, "--resume", "the checkpoint is not a shear test");
  ShearTest test(*sim);
  restore_programme(test, state, opt.out_dir);
  std::fprintf(stderr, "[%s] resumed at %s\n", opt.label.c_str(), where_test_is(*sim, test).c_str());
  return drive(*sim, test, opt, driver_wall_seconds(state));
}

ShearRunResult run_shear(const Scene& scene, const ShearRunOptions& opt) {
  if (opt.resume) {
    std::string state;
    auto sim = load_run_checkpoint(opt, &state);
    return resume_shear(std::move(sim), state, opt);
  }
  Simulation sim(opt.device, scene);
  ShearTest test(sim);
  start_run_folder(scene, opt.out_dir);
  return drive(sim, test, opt, 0);
}

}  // namespace simsols
