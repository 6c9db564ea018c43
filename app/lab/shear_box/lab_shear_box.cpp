// The direct shear test in the lab (lab_apparatus.h): apply the normal
// stress (settle, consolidate under the servo platen), hold, shear.
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/experiment/shear_box/shear_plots.h"
#include "app/lab/lab_apparatus.h"
#include "solver/apparatus/shear_box/shear_analysis.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

class LabShearBox : public LabApparatus {
 public:
  explicit LabShearBox(Simulation& sim) : test_(sim) { test_.hold_before_shear(true); }

  const char* kind() const override { return "shear_box"; }
  LoadingProgramme& programme() override { return test_; }

  LabStage stage(bool started) const override {
    if (test_.done()) return LabStage::Done;
    if (test_.phase() == ShearPhase::Shear) return LabStage::Running;
    if (test_.ready_to_shear()) return LabStage::Loaded;
    return started ? LabStage::Loading : LabStage::Prepared;
  }
  const char* stage_text(LabStage s) const override {
    switch (s) {
      case LabStage::Loading: return "applying the normal stress";
      case LabStage::Loaded: return "normal stress applied";
      case LabStage::Running: return "shearing";
      case LabStage::Done: return "shear finished";
      default: return to_string(s);
    }
  }
  bool holding() const override { return test_.ready_to_shear(); }

  const char* load_label() const override { return "Apply normal stress"; }
  const char* start_label() const override { return "Start shear"; }
  std::string begin_loading() override { return {}; }
  std::string start(LabStage s) override {
    if (s != LabStage::Loaded && s != LabStage::Loading) return "apply the normal stress first";
    test_.start_shear();  // at once when consolidated, else as soon as it is
    return {};
  }

  std::vector<LabSetting> settings() const override {
    return {{"stress", "normal stress", "kPa", test_.normal_stress() * 1e-3},
            {"speed", "shear speed", "mm/s", test_.shear_speed() * 1e3}};
  }
  std::string set(const std::string& key, double value, Scene& scene) override {
    if (key == "stress") {
      if (!(value > 0) || value > 1e6) return "normal stress must be in (0, 1e6] kPa";
      if (ShearBox* b = scene.apparatus_as<ShearBox>()) b->normal_stress = value * 1e3;
      test_.set_normal_stress(value * 1e3);
      return {};
    }
    if (key == "speed") {
      if (!(value > 0) || value > 1000) return "shear speed must be in (0, 1000] mm/s";
      test_.set_shear_speed(value * 1e-3);
      return {};
    }
    return unknown_setting(*this, key);
  }

  std::size_t rows() const override { return test_.rows().size(); }
  double inertial_number() const override {
    return test_.rows().empty() ? 0 : test_.rows().back().inertial_number;
  }
  std::string progress_text() const override {
    if (test_.rows().empty()) return {};
    const ShearRow& r = test_.rows().back();
    char buf[160];
    std::snprintf(buf, sizeof buf, "dx = %.3f mm, σ = %.1f kPa, τ = %.1f kPa (%zu rows)",
                  r.displacement * 1e3, r.sigma * 1e-3, r.tau * 1e-3, test_.rows().size());
    return buf;
  }
  std::string warning() const override {
    const double i = inertial_number();
    if (i <= kQuasiStaticInertialNumber) return {};
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "I = %.2g > %.0e: the shear is no longer quasi-static; lower the shear speed "
                  "(the summary will say quasi_static = no)",
                  i, kQuasiStaticInertialNumber);
    return buf;
  }
  std::string state_lines() override {
    std::ostringstream o;
    o.precision(10);
    o << "rows = " << test_.rows().size() << "\n";
    o << "sigma_target_kpa = " << test_.normal_stress() * 1e-3 << "\n";
    o << "shear_speed_mm_s = " << test_.shear_speed() * 1e3 << "\n";
    if (!test_.rows().empty()) {
      const ShearRow& r = test_.rows().back();
      o << "displacement_mm = " << r.displacement * 1e3 << "\nsigma_kpa = " << r.sigma * 1e-3
        << "\ntau_kpa = " << r.tau * 1e-3 << "\ninertial_number = " << r.inertial_number << "\n";
    }
    return o.str();
  }
  std::vector<LabPlot> live_plots() const override;
  void export_results(const std::string& dir, const std::string& title) override {
    write_file_atomic(dir + "/shear.csv", shear_rows_csv(test_.rows()));
    write_file_atomic(dir + "/summary.txt", shear_summary_text(test_.summary()));
    write_shear_plots(dir, title, test_.rows(), test_.summary());
  }

 private:
  ShearProgramme test_;
};

// tau/sigma, tau, sigma with its target and the dilation against the
// displacement, the peak as in the summaries: the first peak of tau/sigma
// (shear_analysis.h).
std::vector<LabPlot> LabShearBox::live_plots() const {
  const char* dx = "horizontal displacement (mm)";
  LabPlot ratio{"stress ratio", dx, "τ/σ (-)"};
  LabPlot tau{"shear stress", dx, "τ (kPa)"};
  LabPlot sigma{"normal stress", dx, "σ (kPa)"};
  LabPlot dil{"dilation", dx, "vertical displacement (mm)"};
  ratio.measures("displacement", 1e3, "stress_ratio", 1);
  tau.measures("displacement", 1e3, "shear_stress", 1e-3);
  dil.measures("displacement", 1e3, "dilation", 1e3);
  if (test_.normal_stress() > 0) sigma.target = test_.normal_stress() * 1e-3;
  for (const ShearRow& r : test_.rows()) {
    sigma.x.push_back(r.displacement * 1e3);
    sigma.y.push_back(r.sigma * 1e-3);
    ratio.x.push_back(r.displacement * 1e3);
    ratio.y.push_back(r.sigma > 0 ? r.tau / r.sigma : 0);
    tau.x.push_back(r.displacement * 1e3);
    tau.y.push_back(r.tau * 1e-3);
    dil.x.push_back(r.displacement * 1e3);
    dil.y.push_back(r.dilation * 1e3);
  }
  const FirstPeak first = peak_of(test_.rows(), test_.normal_stress(), test_.bead_diameter());
  if (first.row >= 0) ratio.peak = tau.peak = std::size_t(first.row);
  return {ratio, tau, sigma, dil};
}

}  // namespace

std::unique_ptr<LabApparatus> make_lab_shear_box(Simulation& sim) {
  return std::make_unique<LabShearBox>(sim);
}

}  // namespace simsols
