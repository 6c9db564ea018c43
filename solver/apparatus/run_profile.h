// Run profiles: named sets of numerical settings a user picks at the edge
// (`--profile` of run and campaign, the lab's panel) instead of setting
// each lever by hand.
//
// `paper` changes nothing: the scene's own settings (the paper's, for the
// shipped scenes). `fast` trades steps for a stated, measured accuracy
// (docs/accuracy.md, "The fast profile"). A profile has three levers DEM
// practice uses for quasi-static tests:
//   stiffness  every Young's modulus x stiffness_scale, but never below the
//              stiffness number kappa = (E* / sigma)^(2/3) >= kappa_floor,
//              E* = E / (2 (1 - nu^2)) of the grains and sigma the test's
//              normal stress: the overlaps stay small against d (the
//              Rayleigh step grows as 1/sqrt(E));
//   time step  dt_fraction of the Rayleigh step;
//   speed      the shear box's target inertial number.
// `fast` uses the last two; E x 0.1 was measured and left out (it moved
// the layered 3.97 mm specimens' peaks by -8 deg).
// The levers' effects were measured on the direct shear box only: a kind
// offers a profile through its registry entry's profile_stress and
// set_inertial_number (registry.h), and a profile other than `paper`
// refuses a scene whose kind has none (the error names the profile).
#pragma once

#include <span>
#include <string>

#include "solver/scene/scene.h"

namespace simsols {

struct RunProfile {
  const char* name;
  const char* summary;
  double stiffness_scale;  // 1 = the scene's
  double kappa_floor;      // 0 = none
  double dt_fraction;      // 0 = the scene's
  double inertial_number;  // shear box target; 0 = the scene's
  // No lever moves anything (`paper`): it applies to any scene.
  bool neutral() const { return stiffness_scale == 1 && dt_fraction == 0 && inertial_number == 0; }
};

// The profiles, `paper` (the default) first.
std::span<const RunProfile> run_profiles();
// The profile called `name`; throws UsageError naming --profile and the
// choices when there is none.
const RunProfile& run_profile(const std::string& name);

// What a profile did to one scene.
struct ProfileApplied {
  double stiffness_scale = 1;  // applied (the floor may have raised it)
  double kappa = 0;            // at the scene's normal stress, after
};

// Applies `p` to `scene` (a kind with the profile levers; `paper` applies
// to any scene).
// Throws SceneError naming the scene's apparatus when `p` does not apply.
ProfileApplied apply_profile(Scene& scene, const RunProfile& p, const std::string& scene_name);

// kappa = (E* / sigma)^(2/3) of material m under sigma (Pa).
double stiffness_number(const Material& m, double sigma);

}  // namespace simsols
