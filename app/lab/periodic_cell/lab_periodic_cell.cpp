// The periodic cell in the lab (lab_apparatus.h): "start" runs its
// programme by itself, the gas compressed to the pressure, then the test
// (simple shear, a triaxial path); the operator pauses and resumes it and
// watches the stress ratio, the solid fraction and the coordination.
#include <cstdio>
#include <sstream>

#include "app/experiment/periodic_cell/cell_plots.h"
#include "app/lab/lab_apparatus.h"
#include "solver/apparatus/periodic_cell/cell_programme.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

class LabPeriodicCell : public LabApparatus {
 public:
  explicit LabPeriodicCell(Simulation& sim) : test_(sim) {}

  const char* kind() const override { return "periodic_cell"; }
  LoadingProgramme& programme() override { return test_; }

  LabStage stage(bool started) const override {
    switch (test_.stage()) {
      case CellProgramme::Stage::Done: return LabStage::Done;
      case CellProgramme::Stage::Test: return LabStage::Running;
      default: return started ? LabStage::Loading : LabStage::Prepared;
    }
  }
  const char* stage_text(LabStage s) const override {
    switch (s) {
      case LabStage::Loading: return "compressing the gas";
      case LabStage::Running: return "testing";
      case LabStage::Done: return "test finished";
      default: return to_string(s);
    }
  }
  bool holding() const override { return false; }

  const char* load_label() const override { return nullptr; }
  const char* start_label() const override { return "Start compression and test"; }
  std::string begin_loading() override {
    return "the periodic cell has no separate loading: 'start' compresses the gas, then tests it";
  }
  std::string start(LabStage s) override { return s == LabStage::Prepared ? "" : "the test has already started"; }

  std::vector<LabSetting> settings() const override { return {}; }
  std::string set(const std::string& key, double, Scene&) override { return unknown_setting(*this, key); }

  std::size_t rows() const override { return test_.rows().size(); }
  double inertial_number() const override {
    return test_.rows().empty() ? 0 : test_.rows().back()[kColInertial];
  }
  std::string progress_text() const override {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s\nstrain %.3f of %.3g", test_.caption().c_str(), test_.strain(),
                  test_.end_strain());
    return buf;
  }
  std::string state_lines() override {
    std::ostringstream o;
    o.precision(10);
    o << "rows = " << test_.rows().size() << "\nstage = " << test_.stage_name() << "\nstrain = " << test_.strain()
      << "\n";
    if (!test_.rows().empty()) {
      const CellRow& r = test_.rows().back();
      o << "stress_ratio = " << r[kColRatio] << "\nsolid_fraction = " << r[kColPhi] << "\ncoordination = " << r[kColZ]
        << "\np_kpa = " << r[kColP] << "\n";
    }
    return o.str();
  }
  std::vector<LabPlot> live_plots() const override;
  void export_results(const std::string& dir, const std::string& title) override {
    const CellSummary s = test_.summary();
    write_file_atomic(dir + "/cell.csv", cell_rows_csv(test_.rows()));
    write_cell_plots(dir, title, test_.rows(), s);
    write_file_atomic(dir + "/summary.txt", cell_summary_text(s));
  }

 private:
  CellProgramme test_;
};

// The stress ratio, solid fraction and coordination against the test's
// strain (the compression's rows against its volumetric strain first).
std::vector<LabPlot> LabPeriodicCell::live_plots() const {
  const bool testing = test_.stage() != CellProgramme::Stage::Compress;
  const char* x = testing ? "strain" : "volumetric strain (compression)";
  LabPlot ratio{testing ? "stress ratio" : "pressure", x, testing ? "τ/σ or q/p" : "p (kPa)"};
  LabPlot phi{"solid fraction", x, "Φ"};
  LabPlot z{"coordination", x, "Z"};
  if (testing) ratio.measures("axial_strain", 1, "stress_ratio", 1);
  for (const CellRow& r : test_.rows()) {
    if ((r[kColStage] == 1) != testing) continue;
    const double at = testing ? r[kColStrain] : r[kColVolumetric];
    ratio.x.push_back(at), ratio.y.push_back(testing ? r[kColRatio] : r[kColP]);
    phi.x.push_back(at), phi.y.push_back(r[kColPhi]);
    z.x.push_back(at), z.y.push_back(r[kColZ]);
  }
  return {ratio, phi, z};
}

}  // namespace

std::unique_ptr<LabApparatus> make_lab_periodic_cell(Simulation& sim) {
  return std::make_unique<LabPeriodicCell>(sim);
}

}  // namespace simsols
