// The accuracy study: what each accuracy choice costs in time.
//
// A case is a set of numerical settings (StudySettings). Each case is
// measured two ways:
//   contact checks  single contacts with analytic answers, error against
//                   theory: Hertz impact (max overlap, max force, contact
//                   time; Johnson 1985, sec. 11.4), restitution of a damped
//                   impact, and the time a sliding sphere takes to roll
//                   (t = 2 v0 / (7 mu g)); all with the case's settings on
//                   the paper's glass (E scaled with the case)
//   shear test      the paper's 6.35 mm / 160 kPa direct shear test on two
//                   specimens (StudySpecimen): peak and residual friction
//                   angles and the maximum dilatancy angle, error against
//                   that specimen's reference case (its most accurate
//                   settings)
// plus the wall time and particle-steps per second of the shear test.
// A case whose run breaks (NaN, beads out of the box, a neighbour list
// outrun, an impact that never ends) is reported as failed, not as a number.
//
// The sweep varies one knob at a time around a baseline, then a few useful
// combinations (presets in study.cpp): time step (fraction of the Rayleigh
// step, up to and beyond the limit), precision, stiffness scaling, shear
// speed (inertial number), neighbour skin, and the optional effects.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/core/cl_device.h"
#include "solver/scene/scene.h"

namespace simsols {

// The study's specimens of the paper's 6.35 mm beads:
//   Layered  Table 1's 4 layers of 9 x 9 in the paper's box, each layer
//            shifted by the seed: a near-crystal whose peak is a geometric
//            event (the layers' climb) and whose post-peak response is a
//            sequence of collapses and jams.
//   Poured   the same beads rained in at random (the seed places them) in a
//            box StudyPreset::poured_box_scale times as long and wide,
//            4 layers' worth of beads: a random packing whose post-peak
//            response averages over the many contacts of its shear plane.
enum class StudySpecimen : std::uint8_t { Layered, Poured };
inline constexpr StudySpecimen kStudySpecimens[] = {StudySpecimen::Layered, StudySpecimen::Poured};
inline const char* specimen_name(StudySpecimen s) {
  return s == StudySpecimen::Poured ? "poured" : "layered";
}
inline std::optional<StudySpecimen> parse_specimen(const std::string& name) {
  if (name == "layered") return StudySpecimen::Layered;
  if (name == "poured") return StudySpecimen::Poured;
  return std::nullopt;
}

struct StudySettings {
  std::string knob = "baseline";  // the knob this case varies ("reference", "combo", ...)
  std::string label;              // e.g. "dt 0.10"
  double dt_fraction = 0.25;
  Precision precision = Precision::Float;
  double stiffness_scale = 1;     // Young's moduli x this
  double inertial_number = 8e-4;
  double skin_factor = 0.1;       // neighbour skin / bead diameter
  bool rolling = true, damping = true;
  // The ensemble member: the specimen's preparation seed, and a
  // displacement of one bead (bead 0, along x, in bead diameters) that
  // makes a twin differing from its member only at round-off.
  // The move is made before the preparation, or with perturb_at_shear once
  // the specimen is consolidated, as its shearing starts.
  int seed = 1;
  double perturbation = 0;
  bool perturb_at_shear = false;
  StudySpecimen specimen = StudySpecimen::Layered;
  // Same settings on the same specimen, any member.
  bool same_setting(const StudySettings& o) const {
    return specimen == o.specimen && knob == o.knob && label == o.label;
  }
};

struct ContactErrors {
  bool ok = false;
  std::string failure;
  double overlap = 0, force = 0, duration = 0, restitution = 0, rolling = 0;  // % vs theory
  double worst() const;
};

struct ShearResult {
  bool ok = false;
  std::string failure;
  double peak_angle = 0, residual_angle = 0, dilatancy_angle = 0;  // deg
  double wall_seconds = 0, particle_steps_per_second = 0;
  long long steps = 0, list_builds = 0;
  int particles = 0;
  bool interrupted = false;  // stopped by ShearCaseControl::stop_requested (checkpointed)
  // tau/sigma against the displacement (mm), one point per row: where a
  // member and its round-off twin part
  std::vector<double> curve_mm, curve_ratio;
};

struct StudyCase {
  StudySettings settings;
  ContactErrors contact;
  ShearResult shear;
  // % against the reference case's shear result (absolute difference of
  // angles relative to the reference angle)
  std::optional<double> peak_error, residual_error, dilatancy_error;
};

struct StudyPreset {
  std::string name;
  double diameter_mm = 6.35, stress_kpa = 160, displacement_mm = 3;
  int rows = 150;
  int layers = 0;     // 0 = Table 1
  bool shear = true;  // false: contact checks only
  int ensemble = 1;   // members per setting (seeds 1..ensemble)
  // The poured specimen's box: the paper's box x this, length and width
  // (docs/accuracy.md says why); its settling time under gravity: the
  // rain falls three specimen heights (0.12 s), then the platen brings the
  // load on what still rolls.
  double poured_box_scale = 2;
  double poured_settle_time = 0.15;  // s
  // Each specimen's settings, its reference first (knob "reference").
  std::vector<StudySettings> cases;
};

// "full", "quick" (default) or "ci"; nullopt for other names. `ensemble`
// > 0 replaces the preset's ensemble size. Both specimens; the poured one's
// sweep is the layered one's most telling settings.
std::optional<StudyPreset> study_preset(const std::string& name, int ensemble = 0);
// The runs of a study: each setting's members (seeds 1..ensemble), each
// specimen's reference first, then its round-off twin (seed 1, one bead
// moved by kRoundOffPerturbation d before the preparation; knob
// kTwinKnob), then the specimen's other settings', and last, for the
// poured specimen, a second twin moved as shearing starts (kShearTwinKnob:
// a pour amplifies the first move into another packing).
constexpr double kRoundOffPerturbation = 1e-9;  // bead diameters
constexpr const char* kTwinKnob = "round-off";
constexpr const char* kShearTwinKnob = "round-off at shear";
std::vector<StudySettings> study_runs(const StudyPreset& preset,
                                      const std::vector<StudySettings>& settings);

// On `device`; the
// study's workers (--jobs) each pass their own context and queue.
ContactErrors run_contact_checks(const StudySettings& s, std::shared_ptr<Device> device);
// Where a shear case may be stopped and continued (study_state.h): polled
// between chunks; when it answers true the case's state goes to
// `checkpoint` and the result comes back with `interrupted`. A case whose
// `checkpoint` exists when it starts continues from it.
struct ShearCaseControl {
  std::function<bool()> stop_requested;
  std::string checkpoint;
  std::shared_ptr<Device> device;  // where the case runs (required)
};
ShearResult run_shear_case(const StudyPreset& preset, const StudySettings& s,
                           const ShearCaseControl& control = {});
// Fills each run's errors against the mean of its specimen's reference's
// members (knob "reference"), in %.
void compare_to_reference(std::vector<StudyCase>& cases);

std::string study_csv(const std::vector<StudyCase>& cases);
// error-vs-time chart per knob, the Pareto front, summary.md
void write_study_outputs(const std::string& dir, const StudyPreset& preset,
                         const std::vector<StudyCase>& cases);

}  // namespace simsols
