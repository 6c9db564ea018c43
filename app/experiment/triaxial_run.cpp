#include "app/experiment/triaxial_run.h"

#include <cstdio>
#include <filesystem>

#include "app/experiment/triaxial_plots.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

// The triaxial test's part of the run: triaxial.csv, the plots, summary.txt.
class TriaxialOutputs : public ProgrammeOutputs {
 public:
  explicit TriaxialOutputs(TriaxialTest& test) : test_(test) {}
  LoadingProgramme& programme() override { return test_; }
  void save_rows(const fs::path& dir) override {
    write_file_atomic((dir / "triaxial.csv").string(), triaxial_rows_csv(test_.rows()));
  }
  std::string describe() override {
    char buf[128];
    std::snprintf(buf, sizeof buf, "axial strain rate %.3g 1/s, five servo plates",
                  test_.strain_rate());
    return buf;
  }
  void write_results(Simulation& sim, const fs::path& dir, double wall_seconds) override {
    TriaxialSummary summary = test_.summary();
    summary.wall_seconds = wall_seconds;
    write_particles_vtk((dir / "particles_final.vtk").string(), sim.snapshot(), sim.time());
    write_triaxial_plots(dir.string(), sim.scene().name, test_.rows(), summary);
    write_file_atomic((dir / "summary.txt").string(), triaxial_summary_text(summary));
  }

 private:
  TriaxialTest& test_;
};

TriaxialRunResult drive(Simulation& sim, TriaxialTest& test, const ProgrammeRunOptions& opt,
                         double wall_before) {
  TriaxialOutputs outputs(test);
  TriaxialRunResult r;
  r.state = drive_programme(sim, outputs, opt, wall_before);
  r.rows = test.rows();
  r.summary = test.summary();
  r.summary.wall_seconds = r.state.wall_seconds;
  return r;
}

}  // namespace

TriaxialRunResult resume_triaxial(std::unique_ptr<Simulation> sim, const std::string& state,
                                    const ProgrammeRunOptions& opt) {
  if (!sim->scene().triaxial)
    throw SceneError("bad_checkpoint", (fs::path(opt.out_dir) / "checkpoint.bin").string(), 0,
                     "--resume", "the checkpoint is not a triaxial test");
  TriaxialTest test(*sim);
  restore_programme(test, state, opt.out_dir);
  std::fprintf(stderr, "[%s] resumed at %s\n", opt.label.c_str(),
               where_programme_is(*sim, test).c_str());
  return drive(*sim, test, opt, driver_wall_seconds(state));
}

TriaxialRunResult run_triaxial(const Scene& scene, const ProgrammeRunOptions& opt) {
  if (opt.resume) {
    std::string state;
    auto sim = load_run_checkpoint(opt, &state);
    return resume_triaxial(std::move(sim), state, opt);
  }
  Simulation sim(opt.device, scene);
  TriaxialTest test(sim);
  start_run_folder(scene, opt.out_dir);
  return drive(sim, test, opt, 0);
}

}  // namespace simsols
