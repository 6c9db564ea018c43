// The registry of apparatus: every kind the laboratory has, in one table.
//
// A scene holds at most one apparatus (Scene::apparatus, a variant whose
// alternatives follow this table's order). Everything that must tell the
// kinds apart asks this table instead of testing the scene's fields: the
// runs (which test to drive), the titles of plots, the preparation (which
// cell to settle in), the lab, Python and the scene reader's "one apparatus"
// rule. Front ends see a kind only through its entry; what a test does is
// behind ApparatusProgramme (apparatus.h).
//
// A new apparatus (docs/architecture.md, "How to add … An apparatus"):
// its description struct in scene.h and the Apparatus variant, a folder of
// its own beside shear_box/ (geometry, loading programme, analysis), one
// entry here, its table (reader and writer, one file) in solver/io; its
// plots (app/experiment/apparatus_report.cpp) and its bench in the lab
// (app/lab/lab_apparatus.cpp) are optional.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "solver/apparatus/apparatus.h"
#include "solver/common/errors.h"
#include "solver/core/simulation.h"
#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// A headline result of a kind's test: a key of its summary.txt (the size
// study reads them back, app/experiment/size_study.h), and the periodic
// cell's bulk value it is an estimate of: none, the stress ratio on the
// horizontal plane as an angle atan(tau/sigma) (what a shear box reports),
// or the mobilised angle asin((s1 - s3)/(s1 + s3)) (a triaxial cell's).
enum class BulkMatch { None, PlaneAngle, MobilisedAngle };
struct HeadlineResult {
  const char* key;     // "residual_friction_angle_deg"
  const char* symbol;  // "φ_res (°)"
  BulkMatch bulk;
};

// A quantity of a kind's rows file that a measured curve can be compared
// with (a calibration's targets, app/experiment/calibration): the name a
// target gives it, the column that holds it and that column's unit ("-",
// "kPa", "mm"). Signs follow the rows file: compression positive.
struct CurveQuantity {
  const char* name;    // "axial_strain"
  const char* column;  // "strain"
  const char* unit;
};

struct ApparatusKind {
  const char* name;       // its scene table and its key everywhere: "shear_box"
  const char* title;      // the test in a plot's title: "Direct shear"
  const char* test_noun;  // in sentences: "a direct shear test"
  const char* label;      // progress lines' prefix: "shear"
  int walls;              // how many walls it adds, from its first_wall
  const char* stages;     // its programme's stages in order: "settle,consolidate,shear"
  // Its walls and specimen placed from the description in the scene (the
  // automatic values resolved); a problem with its field, or nothing.
  std::optional<SceneIssue> (*build)(Scene& scene);
  // Its loading programme on `sim` (whose scene holds this kind).
  std::unique_ptr<ApparatusProgramme> (*make_programme)(Simulation& sim);
  // The stress a title quotes ("σ = 160 kPa"), or "".
  std::string (*stress_words)(const Scene& scene);
  // Checks the apparatus against a prepared specimen (tamped, grown) whose
  // highest grain's top is at `top` (m): a problem, or nothing; nullptr
  // when the kind has nothing to check (the shear box: its shear plane).
  std::optional<SceneIssue> (*check_specimen_top)(const Scene& scene, double top);
  // Scales the apparatus of a scene not yet placed for a size study: its
  // lengths across by `across`, its specimen's height (layers) by
  // `height`, and what the test travels with them; nullptr when the kind
  // has no walls to move apart (the periodic cell: it is the bulk).
  void (*resize)(Scene& scene, double across, double height);
  // The results a study reports of its tests, in order.
  std::span<const HeadlineResult> headlines;
  // The time (s) its programme is expected to simulate on a placed scene:
  // the stages' allowances or travel at their rates. Times the beads over
  // the time step, the particle-steps campaigns weigh their ETAs and a
  // cluster's time limits with.
  double (*expected_time)(const Scene& scene);
  // The run profiles' levers on the test (run_profile.h): the stress a
  // profile's stiffness number is taken at (Pa), and setting the test's
  // target inertial number (its speed, where the scene does not fix it);
  // nullptr where only the paper profile was measured.
  double (*profile_stress)(const Scene& scene) = nullptr;
  void (*set_inertial_number)(Scene& scene, double inertial_number) = nullptr;
  // Its rows' quantities a measured curve can be compared with; the rows
  // that belong to the test proper, as "column=value" ("stage=1"), or
  // nullptr for every row; the scene's key (a dotted TOML path) of the
  // specimen's random seed, which a calibration's replicates change.
  std::span<const CurveQuantity> curves = {};
  const char* curve_rows = nullptr;
  const char* seed_key = nullptr;
};

// Particle-steps of the scene's test (placed): its beads times its kind's
// expected_time over the effective time step.
double expected_particle_steps(const Scene& scene);

// The kinds, in the order of the Apparatus variant's alternatives after
// std::monostate.
std::span<const ApparatusKind> apparatus_kinds();
// The kind of the scene's apparatus; nullptr when it has none.
const ApparatusKind* apparatus_kind(const Scene& scene);
// The kind called `name`; nullptr when there is none.
const ApparatusKind* find_apparatus_kind(std::string_view name);
// The kinds' names joined by `separator`: "shear_box|oedometer|triaxial".
std::string apparatus_names(std::string_view separator);
// Where every test can stop before its own stages: its specimen placed
// and prepared, nothing loaded yet (`--stop-at prepared`).
inline constexpr const char* kPreparedStage = "prepared";
// True when `stage` is one of the kind's stages, or kPreparedStage.
bool has_stage(const ApparatusKind& kind, std::string_view stage);

// The kind of the scene's apparatus; SceneError (no_apparatus) naming the
// scene when it has none.
const ApparatusKind& required_apparatus_kind(const Scene& scene);
// The entry of a layer's own table for the kinds (the io readers, the
// plots, the lab's benches: structs with a `kind` name, at most one per
// kind) for the kind called `kind`; nullptr when it has none.
template <class Entry>
const Entry* entry_for_kind(std::span<const Entry> table, std::string_view kind) {
  for (const Entry& e : table)
    if (kind == e.kind) return &e;
  return nullptr;
}

// The scene's test on `sim`; SceneError as above when it has no apparatus.
std::unique_ptr<ApparatusProgramme> make_programme(Simulation& sim);

}  // namespace simsols
