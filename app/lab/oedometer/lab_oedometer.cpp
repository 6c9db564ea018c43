// The oedometer in the lab (lab_apparatus.h): "start load programme"
// settles the beads, then the servo platen brings each load step on and
// holds it until the specimen is in equilibrium, step after step, by itself;
// the operator pauses and resumes it and watches the steps end.
#include <cstdio>
#include <sstream>

#include "app/experiment/oedometer/oedometer_plots.h"
#include "app/lab/lab_apparatus.h"
#include "solver/apparatus/oedometer/oedometer_programme.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

class LabOedometer : public LabApparatus {
 public:
  explicit LabOedometer(Simulation& sim) : test_(sim), steps_(sim.scene().apparatus_as<Oedometer>()->load_steps) {}

  const char* kind() const override { return "oedometer"; }
  LoadingProgramme& programme() override { return test_; }

  LabStage stage(bool started) const override {
    switch (test_.stage()) {
      case OedometerProgramme::Stage::Done: return LabStage::Done;
      case OedometerProgramme::Stage::Load: return LabStage::Running;
      default: return started ? LabStage::Loading : LabStage::Prepared;
    }
  }
  const char* stage_text(LabStage s) const override {
    switch (s) {
      case LabStage::Loading: return "settling under gravity";
      case LabStage::Running: return "load programme";
      case LabStage::Done: return "load programme finished";
      default: return to_string(s);
    }
  }
  bool holding() const override { return false; }

  const char* load_label() const override { return nullptr; }
  const char* start_label() const override { return "Start load programme"; }
  std::string begin_loading() override {
    return "the oedometer has no separate loading: 'start' runs its load programme (settle, "
           "then the load steps)";
  }
  std::string start(LabStage s) override {
    return s == LabStage::Prepared ? "" : "the load programme has already started";
  }

  std::vector<LabSetting> settings() const override { return {}; }
  std::string set(const std::string& key, double, Scene&) override {
    return unknown_setting(*this, key);
  }

  std::size_t rows() const override { return test_.rows().size(); }
  double inertial_number() const override { return 0; }
  std::string progress_text() const override;
  std::string state_lines() override;
  std::vector<LabPlot> live_plots() const override;
  void export_results(const std::string& dir, const std::string& title) override {
    const OedometerSummary s = test_.summary();
    write_file_atomic(dir + "/oedometer.csv", oedometer_rows_csv(test_.rows()));
    write_oedometer_plots(dir, title, test_.rows(), s);
    write_file_atomic(dir + "/summary.txt", oedometer_summary_text(s));
  }

 private:
  // The steps ended so far, and how many of them in equilibrium.
  std::pair<int, int> steps_ended() const {
    int ended = 0, equilibrium = 0;
    for (const OedometerRow& r : test_.rows()) {
      ended += r.end_of_step != 0;
      equilibrium += r.end_of_step == 1;
    }
    return {ended, equilibrium};
  }

  OedometerProgramme test_;
  std::vector<double> steps_;  // Pa, the scene's load steps
};

// The current step, its target and reaction, how close it is to
// equilibrium, and the steps ended so far.
std::string LabOedometer::progress_text() const {
  const auto [ended, equilibrium] = steps_ended();
  char buf[300];
  if (test_.stage() != OedometerProgramme::Stage::Load) {
    std::snprintf(buf, sizeof buf, "%zu load steps; %d ended, %d of them in equilibrium",
                  steps_.size(), ended, equilibrium);
    return buf;
  }
  const int k = test_.load_step();
  const double top = test_.rows().empty() ? 0 : test_.rows().back().sigma_top;
  std::snprintf(buf, sizeof buf,
                "load step %d of %zu: %.0f kPa, platen %.1f kPa\n"
                "equilibrium checks passed %d of 2; steps ended %d (%d in equilibrium)",
                k + 1, steps_.size(), steps_[std::size_t(k)] * 1e-3, top * 1e-3,
                test_.equilibrium_checks(), ended, equilibrium);
  return buf;
}

std::string LabOedometer::state_lines() {
  const auto [ended, equilibrium] = steps_ended();
  std::ostringstream o;
  o.precision(10);
  o << "rows = " << test_.rows().size() << "\nload_step = " << test_.load_step() + 1
    << "\nload_steps = " << steps_.size() << "\nsigma_target_kpa = "
    << steps_[std::size_t(test_.load_step())] * 1e-3
    << "\nequilibrium_checks = " << test_.equilibrium_checks() << "\nsteps_ended = " << ended
    << "\nsteps_in_equilibrium = " << equilibrium << "\n";
  if (!test_.rows().empty()) {
    const OedometerRow& r = test_.rows().back();
    o << "sigma_top_kpa = " << r.sigma_top * 1e-3 << "\nvoid_ratio = " << r.void_ratio
      << "\nk0 = " << r.k0 << "\n";
  }
  return o.str();
}

// The compression curve e - log sigma'_v (every row) and the load
// programme as it runs (the platen's stress against time).
std::vector<LabPlot> LabOedometer::live_plots() const {
  LabPlot e{"e – log σ′v", "σ′v (kPa, log)", "void ratio e"};
  LabPlot load{"load programme", "time (s)", "σ′v at the platen (kPa)"};
  e.x_log = true;
  e.measures("vertical_stress", 1e-3, "void_ratio", 1);
  for (const OedometerRow& r : test_.rows()) {
    if (r.sigma_top > 0) {
      e.x.push_back(r.sigma_top * 1e-3);
      e.y.push_back(r.void_ratio);
    }
    load.x.push_back(r.time);
    load.y.push_back(r.sigma_top * 1e-3);
  }
  return {e, load};
}

}  // namespace

std::unique_ptr<LabApparatus> make_lab_oedometer(Simulation& sim) {
  return std::make_unique<LabOedometer>(sim);
}

}  // namespace simsols
