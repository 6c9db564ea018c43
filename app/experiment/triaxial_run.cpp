#include "app/experiment/triaxial_run.h"
#include "app/experiment/test_title.h"

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
    write_triaxial_plots(dir.string(), test_title(sim.scene()), test_.rows(), summary);
    write_file_atomic((dir / "summary.txt").string(), triaxial_summary_text(summary));
  }

 private:
  TriaxialTest& test_;
};

bool has_triaxial(const Scene& scene) { return scene.triaxial.has_value(); }

}  // namespace

TriaxialRunResult resume_triaxial(std::unique_ptr<Simulation> sim, const std::string& state,
                                 const ProgrammeRunOptions& opt) {
  return resume_apparatus_test<TriaxialTest, TriaxialOutputs>(std::move(sim), state, opt, has_triaxial,
                                                          "a triaxial test");
}

TriaxialRunResult run_triaxial(const Scene& scene, const ProgrammeRunOptions& opt) {
  return run_apparatus_test<TriaxialTest, TriaxialOutputs>(scene, opt, has_triaxial, "a triaxial test");
}

}  // namespace simsols
