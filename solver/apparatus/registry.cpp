// The table of apparatus kinds (registry.h): one entry per kind, in the
// order of the Apparatus variant.
#include "solver/apparatus/registry.h"

#include <cstdio>
#include <variant>

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/oedometer/oedometer.h"
#include "solver/apparatus/oedometer/oedometer_programme.h"
#include "solver/apparatus/periodic_cell/cell_programme.h"
#include "solver/apparatus/periodic_cell/periodic_cell.h"
#include "solver/apparatus/shear_box/shear_box.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "solver/apparatus/triaxial/triaxial.h"
#include "solver/apparatus/triaxial/triaxial_programme.h"
#include "solver/scene/contact_model.h"

namespace simsols {
namespace {

template <class Programme>
std::unique_ptr<ApparatusProgramme> make(Simulation& sim) {
  return std::make_unique<Programme>(sim);
}

std::string kpa(const char* symbol, double pascals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s = %.3g kPa", symbol, pascals * 1e-3);
  return buf;
}

std::string shear_box_stress(const Scene& s) {
  return kpa("σ", s.apparatus_as<ShearBox>()->normal_stress);
}
std::string triaxial_stress(const Scene& s) {
  return kpa("σ₃", s.apparatus_as<Triaxial>()->confining_stress);
}
std::string cell_stress(const Scene& s) {
  return kpa("p", s.apparatus_as<PeriodicCell>()->pressure);
}
std::string no_stress(const Scene&) { return {}; }

constexpr HeadlineResult kShearHeadlines[] = {
    {"peak_friction_angle_deg", "φ_peak (°)", BulkMatch::None},
    {"residual_friction_angle_deg", "φ_res (°)", BulkMatch::PlaneAngle},
    {"max_dilatancy_angle_deg", "ψ_max (°)", BulkMatch::None}};
constexpr HeadlineResult kOedometerHeadlines[] = {
    {"k0_normally_consolidated", "K0 (NC)", BulkMatch::None},
    {"implied_friction_angle_deg", "φ' from K0, Jaky (°)", BulkMatch::MobilisedAngle},
    {"side_friction_share", "side friction (share of the load)", BulkMatch::None},
    {"compression_index_cc", "Cc", BulkMatch::None}};
constexpr HeadlineResult kTriaxialHeadlines[] = {
    {"peak_friction_angle_deg", "φ_peak (°)", BulkMatch::None},
    {"critical_friction_angle_deg", "φ_cs (°)", BulkMatch::MobilisedAngle},
    {"max_dilatancy_angle_deg", "ψ_max (°)", BulkMatch::None}};
constexpr HeadlineResult kCellHeadlines[] = {
    {"stress_ratio", "τ/σ", BulkMatch::None},
    {"friction_angle_deg", "φ_mob (°)", BulkMatch::None},
    {"solid_fraction", "Φ", BulkMatch::None}};

constexpr CurveQuantity kShearCurves[] = {
    {"displacement", "displacement_mm", "mm"}, {"stress_ratio", "tau_over_sigma", "-"},
    {"shear_stress", "tau_kPa", "kPa"},        {"dilation", "dilation_mm", "mm"},
    {"normal_stress", "sigma_kPa", "kPa"}};
constexpr CurveQuantity kOedometerCurves[] = {
    {"vertical_stress", "sigma_top_kPa", "kPa"}, {"void_ratio", "void_ratio", "-"},
    {"horizontal_stress", "sigma_h_kPa", "kPa"}, {"k0", "k0", "-"}};
constexpr CurveQuantity kTriaxialCurves[] = {
    {"axial_strain", "axial_strain", "-"}, {"volumetric_strain", "volumetric_strain", "-"},
    {"stress_ratio", "q_over_p", "-"},     {"deviator_stress", "q_kPa", "kPa"},
    {"mean_stress", "p_kPa", "kPa"},       {"void_ratio", "void_ratio", "-"}};
constexpr CurveQuantity kCellCurves[] = {
    {"axial_strain", "strain", "-"},       {"shear_strain", "strain", "-"},
    {"volumetric_strain", "volumetric_strain", "-"}, {"stress_ratio", "stress_ratio", "-"},
    {"deviator_stress", "q_kPa", "kPa"},   {"mean_stress", "p_kPa", "kPa"},
    {"void_ratio", "void_ratio", "-"},     {"vertical_stress", "sigma_zz_kPa", "kPa"}};
const ApparatusKind kKinds[] = {
    {"shear_box", "Direct shear", "a direct shear test", "shear", kShearBoxWalls,
     "settle,consolidate,shear", build_shear_box, make<ShearProgramme>, shear_box_stress,
     check_shear_box_specimen_top, resize_shear_box, kShearHeadlines, shear_box_expected_time,
     shear_box_profile_stress, set_shear_box_inertial_number, kShearCurves, nullptr,
     "shear_box.specimen.seed"},
    {"oedometer", "Oedometer", "an oedometer test", "oedometer", kOedometerWalls, "settle,load",
     build_oedometer, make<OedometerProgramme>, no_stress, nullptr, resize_cell,
     kOedometerHeadlines, oedometer_expected_time, nullptr, nullptr, kOedometerCurves, nullptr,
     "oedometer.specimen.seed"},
    {"triaxial", "Triaxial", "a triaxial test", "triaxial", kTriaxialWalls,
     "settle,consolidate,compress", build_triaxial, make<TriaxialProgramme>, triaxial_stress,
     nullptr, resize_cell, kTriaxialHeadlines, triaxial_expected_time, nullptr, nullptr,
     kTriaxialCurves, nullptr, "triaxial.specimen.seed"},
    {"periodic_cell", "Periodic cell", "a periodic-cell test", "cell", 0, "compress,test",
     build_periodic_cell, make<CellProgramme>, cell_stress, nullptr, nullptr, kCellHeadlines,
     periodic_cell_expected_time, nullptr, nullptr, kCellCurves, "stage=1", "periodic_cell.seed"},
};
static_assert(std::size(kKinds) + 1 == std::variant_size_v<Apparatus>,
              "one registry entry per alternative of Scene::apparatus");
static_assert(std::is_same_v<std::variant_alternative_t<1, Apparatus>, ShearBox> &&
                  std::is_same_v<std::variant_alternative_t<2, Apparatus>, Oedometer> &&
                  std::is_same_v<std::variant_alternative_t<3, Apparatus>, Triaxial> &&
                  std::is_same_v<std::variant_alternative_t<4, Apparatus>, PeriodicCell>,
              "the registry's order is the variant's");

}  // namespace

std::span<const ApparatusKind> apparatus_kinds() { return kKinds; }

const ApparatusKind* apparatus_kind(const Scene& scene) {
  const std::size_t i = scene.apparatus.index();
  return i == 0 ? nullptr : &kKinds[i - 1];
}

const ApparatusKind* find_apparatus_kind(std::string_view name) {
  for (const ApparatusKind& k : kKinds)
    if (name == k.name) return &k;
  return nullptr;
}

std::string apparatus_names(std::string_view separator) {
  std::string out;
  for (const ApparatusKind& k : kKinds) {
    if (!out.empty()) out += separator;
    out += k.name;
  }
  return out;
}

bool has_stage(const ApparatusKind& kind, std::string_view stage) {
  if (stage == kPreparedStage) return true;
  std::string_view rest = kind.stages;
  while (!rest.empty()) {
    const size_t comma = rest.find(',');
    if (rest.substr(0, comma) == stage) return !stage.empty();
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return false;
}

const ApparatusKind& required_apparatus_kind(const Scene& scene) {
  const ApparatusKind* kind = apparatus_kind(scene);
  if (!kind)
    throw SceneError("no_apparatus", scene.source_path.empty() ? scene.name : scene.source_path,
                     0, "apparatus",
                     "the scene has no apparatus (one of the tables " + apparatus_names(", ") +
                         "): no test to run");
  return *kind;
}

double expected_particle_steps(const Scene& scene) {
  return double(scene.particles.size()) * required_apparatus_kind(scene).expected_time(scene) /
         effective_time_step(scene);
}

std::unique_ptr<ApparatusProgramme> make_programme(Simulation& sim) {
  return required_apparatus_kind(sim.scene()).make_programme(sim);
}

}  // namespace simsols
