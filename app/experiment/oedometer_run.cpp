#include "app/experiment/oedometer_run.h"
#include "app/experiment/test_title.h"

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
    write_oedometer_plots(dir.string(), test_title(sim.scene()), test_.rows(), summary);
    write_file_atomic((dir / "summary.txt").string(), oedometer_summary_text(summary));
  }

 private:
  OedometerTest& test_;
};

bool has_oedometer(const Scene& scene) { return scene.oedometer.has_value(); }

}  // namespace

OedometerRunResult resume_oedometer(std::unique_ptr<Simulation> sim, const std::string& state,
                                 const ProgrammeRunOptions& opt) {
  return resume_apparatus_test<OedometerTest, OedometerOutputs>(std::move(sim), state, opt, has_oedometer,
                                                          "an oedometer test");
}

OedometerRunResult run_oedometer(const Scene& scene, const ProgrammeRunOptions& opt) {
  return run_apparatus_test<OedometerTest, OedometerOutputs>(scene, opt, has_oedometer, "an oedometer test");
}

}  // namespace simsols
