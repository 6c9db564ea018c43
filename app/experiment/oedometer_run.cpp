#include "app/experiment/oedometer_run.h"

#include <cstdio>
#include <filesystem>

#include "app/experiment/oedometer_plots.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

// The oedometer's part of the run: oedometer.csv, the plots, summary.txt.
class OedometerOutputs : public ProgrammeOutputs {
 public:
  explicit OedometerOutputs(OedometerTest& test) : test_(test) {}
  LoadingProgramme& programme() override { return test_; }
  void save_rows(const fs::path& dir) override {
    write_file_atomic((dir / "oedometer.csv").string(), oedometer_rows_csv(test_.rows()));
  }
  std::string describe() override {
    char buf[128];
    std::snprintf(buf, sizeof buf, "servo gain %.3g m/(s N), integral time %.3g s (first step)",
                  test_.servo_gain(), test_.servo_integral_time());
    return buf;
  }
  void write_results(Simulation& sim, const fs::path& dir, double wall_seconds) override {
    OedometerSummary summary = test_.summary();
    summary.wall_seconds = wall_seconds;
    write_particles_vtk((dir / "particles_final.vtk").string(), sim.snapshot(), sim.time());
    write_oedometer_plots(dir.string(), sim.scene().name, test_.rows(), summary);
    write_file_atomic((dir / "summary.txt").string(), oedometer_summary_text(summary));
  }

 private:
  OedometerTest& test_;
};

OedometerRunResult drive(Simulation& sim, OedometerTest& test, const ProgrammeRunOptions& opt,
                         double wall_before) {
  OedometerOutputs outputs(test);
  OedometerRunResult r;
  r.state = drive_programme(sim, outputs, opt, wall_before);
  r.rows = test.rows();
  r.summary = test.summary();
  r.summary.wall_seconds = r.state.wall_seconds;
  return r;
}

}  // namespace

OedometerRunResult resume_oedometer(std::unique_ptr<Simulation> sim, const std::string& state,
                                    const ProgrammeRunOptions& opt) {
  if (!sim->scene().oedometer)
    throw SceneError("bad_checkpoint", (fs::path(opt.out_dir) / "checkpoint.bin").string(), 0,
                     "--resume", "the checkpoint is not an oedometer test");
  OedometerTest test(*sim);
  restore_programme(test, state, opt.out_dir);
  std::fprintf(stderr, "[%s] resumed at %s\n", opt.label.c_str(),
               where_programme_is(*sim, test).c_str());
  return drive(*sim, test, opt, driver_wall_seconds(state));
}

OedometerRunResult run_oedometer(const Scene& scene, const ProgrammeRunOptions& opt) {
  if (opt.resume) {
    std::string state;
    auto sim = load_run_checkpoint(opt, &state);
    return resume_oedometer(std::move(sim), state, opt);
  }
  Simulation sim(opt.device, scene);
  OedometerTest test(sim);
  start_run_folder(scene, opt.out_dir);
  return drive(sim, test, opt, 0);
}

}  // namespace simsols
