// The triaxial test in the lab (lab_apparatus.h): "Apply σ₃" settles the
// beads and consolidates them isotropically, then the five servo plates
// (or, in the membrane cell, the platen and the membrane) hold σ₃
// (TriaxialProgramme::hold_when_consolidated) until "start compression";
// σ₃ and the strain rate can be changed at any stage, the cell (rigid
// plates or a membrane) before the specimen is prepared again.
#include <cstdio>
#include <optional>
#include <sstream>

#include "app/experiment/triaxial/triaxial_plots.h"
#include "app/lab/lab_apparatus.h"
#include "solver/apparatus/triaxial/triaxial_programme.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

class LabTriaxial : public LabApparatus {
 public:
  explicit LabTriaxial(Simulation& sim) : sim_(sim), test_(sim) { test_.hold_when_consolidated(true); }

  const char* kind() const override { return "triaxial"; }
  LoadingProgramme& programme() override { return test_; }

  LabStage stage(bool started) const override {
    switch (test_.stage()) {
      case TriaxialProgramme::Stage::Done: return LabStage::Done;
      case TriaxialProgramme::Stage::Compress: return LabStage::Running;
      default: break;
    }
    if (test_.consolidated_now()) return LabStage::Loaded;
    return started ? LabStage::Loading : LabStage::Prepared;
  }
  const char* stage_text(LabStage s) const override {
    switch (s) {
      case LabStage::Loading:
        return test_.stage() == TriaxialProgramme::Stage::Settle ? "settling under gravity"
                                                            : "consolidating to σ₃";
      case LabStage::Loaded: return "consolidated, σ₃ held";
      case LabStage::Running: return "compressing";
      case LabStage::Done: return "compression finished";
      default: return to_string(s);
    }
  }
  bool holding() const override { return test_.consolidated_now() && test_.holding(); }

  const char* load_label() const override { return "Apply σ₃ (consolidate)"; }
  const char* start_label() const override { return "Start compression"; }
  std::string begin_loading() override { return {}; }
  std::string start(LabStage s) override {
    if (s == LabStage::Loaded) {
      test_.start_compression();
      return {};
    }
    if (s == LabStage::Loading) {  // compress as soon as consolidated
      test_.hold_when_consolidated(false);
      return {};
    }
    return s == LabStage::Prepared ? "apply σ₃ first (consolidate)"
                                   : "the compression has already started";
  }

  std::vector<LabSetting> settings() const override {
    return {{"stress", "σ₃", "kPa", test_.confining_stress() * 1e-3},
            {"rate", "axial strain rate", "1/s", test_.strain_rate()}};
  }
  std::string set(const std::string& key, double value, Scene& scene) override {
    if (key == "stress") {
      if (!(value > 0) || value > 1e6) return "σ₃ must be in (0, 1e6] kPa";
      if (Triaxial* t = scene.apparatus_as<Triaxial>()) t->confining_stress = value * 1e3;
      test_.set_confining_stress(value * 1e3);
      return {};
    }
    if (key == "rate") {
      if (!(value > 0) || value > 100) return "the axial strain rate must be in (0, 100] 1/s";
      test_.set_strain_rate(value);
      return {};
    }
    return unknown_setting(*this, key);
  }

  std::vector<LabChoice> choices(const Scene& scene) const override {
    const Triaxial* t = scene.apparatus_as<Triaxial>();
    const auto cells = simsols::choices<Triaxial::Cell>();  // the scene's own names for them
    int current = 0;
    for (size_t k = 0; k < cells.size(); ++k)
      if (t && cells[k].value == t->cell) current = static_cast<int>(k);
    return {{"cell", "cell", choice_names<Triaxial::Cell>(), current}};
  }
  std::string choose(const std::string& key, const std::string& option, Scene& scene) override;

  std::size_t rows() const override { return test_.rows().size(); }
  double inertial_number() const override {
    return test_.rows().empty() ? 0 : test_.rows().back().inertial_number;
  }
  std::string progress_text() const override;
  std::string state_lines() override;
  std::vector<LabPlot> live_plots() const override;
  void export_results(const std::string& dir, const std::string& title) override {
    const TriaxialSummary s = test_.summary();
    write_file_atomic(dir + "/triaxial.csv", triaxial_rows_csv(test_.rows()));
    write_triaxial_plots(dir, title, test_.rows(), s);
    write_file_atomic(dir + "/summary.txt", triaxial_summary_text(s));
  }

 private:
  Simulation& sim_;
  TriaxialProgramme test_;
};

// The cell of the next prepare: a membrane holds the sides at σ₃, so it
// runs the constant-σ₃ path only (as `simsols run` refuses the others).
std::string LabTriaxial::choose(const std::string& key, const std::string& option, Scene& scene) {
  if (key != "cell") return LabApparatus::choose(key, option, scene);
  Triaxial* t = scene.apparatus_as<Triaxial>();
  if (!t || scene.placed()) return "cell: this scene's cell is built already; open it again to change it";
  const std::optional<Triaxial::Cell> cell = parse_choice<Triaxial::Cell>(option);
  if (!cell) return "cell " + option + ": the cell is " + choice_names_joined<Triaxial::Cell>();
  if (*cell == Triaxial::Cell::Membrane && t->path != Triaxial::Path::ConstantSigma3)
    return "cell " + option + ": a membrane holds σ₃ constant; this scene's path is another "
           "([triaxial] path, docs/triaxial.md)";
  t->cell = *cell;
  return {};
}

// Before compression: the plates at the last equilibrium check; then the
// last row.
std::string LabTriaxial::progress_text() const {
  char buf[240];
  if (test_.rows().empty()) {
    const auto s = test_.checked_stress();
    std::snprintf(buf, sizeof buf,
                  "plates at the last check: %.1f, %.1f, %.1f kPa (p′ = %.1f kPa)\n"
                  "consolidated at σ₃ = %.0f kPa: %s",
                  s[0] * 1e-3, s[1] * 1e-3, s[2] * 1e-3, (s[0] + s[1] + s[2]) / 3 * 1e-3,
                  test_.confining_stress() * 1e-3, test_.consolidated_now() ? "yes" : "not yet");
    return buf;
  }
  const TriaxialRow& r = test_.rows().back();
  std::snprintf(buf, sizeof buf,
                // short lines: the panel wraps a long one at any '.', inside a number
                "ε_a = %.3f %%, q = %.1f kPa\np′ = %.1f kPa, ε_v = %.3f %%\ne = %.4f\n"
                "%zu rows, I = %.2g",
                100 * r.axial_strain, r.q * 1e-3, r.p * 1e-3, 100 * r.volumetric_strain,
                r.void_ratio, test_.rows().size(), r.inertial_number);
  return buf;
}

std::string LabTriaxial::state_lines() {
  std::ostringstream o;
  o.precision(10);
  const Triaxial* t = sim_.scene().apparatus_as<Triaxial>();
  o << "cell = " << choice_name(t ? t->cell : Triaxial::Cell::Rigid) << "\n";
  o << "rows = " << test_.rows().size() << "\nsigma3_target_kpa = "
    << test_.confining_stress() * 1e-3 << "\nstrain_rate = " << test_.strain_rate()
    << "\nconsolidated = " << (test_.consolidated_now() ? 1 : 0) << "\n";
  if (test_.stage() != TriaxialProgramme::Stage::Settle) {
    const TriaxialProgramme::AtRest a = test_.at_rest();  // the last equilibrium check
    o << "p_kpa = " << a.p * 1e-3 << "\nsigma_x_kpa = " << a.stress[0] * 1e-3
      << "\nsigma_y_kpa = " << a.stress[1] * 1e-3 << "\nsigma_z_kpa = " << a.stress[2] * 1e-3
      << "\nvoid_ratio_at_rest = " << a.void_ratio << "\n";
  }
  if (!test_.rows().empty()) {
    const TriaxialRow& r = test_.rows().back();
    o << "axial_strain = " << r.axial_strain << "\nvolumetric_strain = " << r.volumetric_strain
      << "\nq_kpa = " << r.q * 1e-3 << "\np_row_kpa = " << r.p * 1e-3
      << "\nvoid_ratio = " << r.void_ratio << "\ninertial_number = " << r.inertial_number << "\n";
  }
  return o.str();
}

// q and eps_v against eps_a, and the path in e - log p'.
std::vector<LabPlot> LabTriaxial::live_plots() const {
  LabPlot q{"deviator stress", "axial strain (%)", "q (kPa)"};
  LabPlot v{"volumetric strain", "axial strain (%)", "ε_v (%), compression +"};
  LabPlot e{"e – log p′", "p′ (kPa, log)", "void ratio e"};
  e.x_log = true;
  q.measures("axial_strain", 100, "deviator_stress", 1e-3);
  v.measures("axial_strain", 100, "volumetric_strain", 100);
  e.measures("mean_stress", 1e-3, "void_ratio", 1);
  for (const TriaxialRow& r : test_.rows()) {
    q.x.push_back(100 * r.axial_strain);
    q.y.push_back(r.q * 1e-3);
    v.x.push_back(100 * r.axial_strain);
    v.y.push_back(100 * r.volumetric_strain);
    e.x.push_back(r.p * 1e-3);
    e.y.push_back(r.void_ratio);
  }
  return {q, v, e};
}

}  // namespace

std::unique_ptr<LabApparatus> make_lab_triaxial(Simulation& sim) {
  return std::make_unique<LabTriaxial>(sim);
}

}  // namespace simsols
