#include "solver/apparatus/run_profile.h"

#include <algorithm>
#include <cmath>

#include "solver/apparatus/registry.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

// The fast profile's levers, each measured against the paper profile on
// the same specimens (docs/accuracy.md, "The fast profile").
constexpr RunProfile kProfiles[] = {
    {"paper", "the scene's own settings (the paper's: dt 0.25 x Rayleigh, E as given, I 8e-4)",
     1, 0, 0, 0},
    // the stiffness lever stays off: E x 0.1 moved the 3.97 mm peaks by -8 deg
    {"fast", "dt 0.5 x Rayleigh and I 2e-3, E as given: the shear box only", 1, 400, 0.5, 2e-3},
};

}  // namespace

std::span<const RunProfile> run_profiles() { return kProfiles; }

const RunProfile& run_profile(const std::string& name) {
  std::string names;
  for (const RunProfile& p : kProfiles) {
    if (name == p.name) return p;
    names += (names.empty() ? "" : ", ") + std::string(p.name);
  }
  throw UsageError("bad_enum", "--profile", "'" + name + "' is not a profile; the profiles: " + names);
}

double stiffness_number(const Material& m, double sigma) {
  const double e_star = m.young_modulus / (2 * (1 - m.poisson_ratio * m.poisson_ratio));
  return std::pow(e_star / sigma, 2.0 / 3.0);
}

ProfileApplied apply_profile(Scene& scene, const RunProfile& p, const std::string& scene_name) {
  ProfileApplied out;
  const ApparatusKind* kind = apparatus_kind(scene);
  const Specimen* specimen = scene.specimen();
  const bool measured = kind && kind->profile_stress && kind->set_inertial_number && specimen;
  const auto kappa = [&] {
    return measured ? stiffness_number(scene.materials.at(specimen->material), kind->profile_stress(scene))
                    : 0.0;
  };
  if (!measured && !p.neutral())
    throw SceneError("not_applicable", scene_name, 0, "apparatus",
                     std::string("the '") + p.name +
                         "' profile is measured on the direct shear box only "
                         "(docs/accuracy.md); use --profile paper for this apparatus");
  double scale = p.stiffness_scale;
  // kappa scales as scale^(2/3): the softest scale that keeps the floor
  if (p.kappa_floor > 0 && measured)
    scale = std::min(1.0, std::max(scale, std::pow(p.kappa_floor / kappa(), 1.5)));
  for (Material& m : scene.materials) m.young_modulus *= scale;
  if (p.dt_fraction > 0) {
    scene.numerics.dt_fraction = p.dt_fraction;
    scene.numerics.dt = 0;
  }
  if (p.inertial_number > 0) kind->set_inertial_number(scene, p.inertial_number);
  out.stiffness_scale = scale;
  out.kappa = kappa();
  return out;
}

}  // namespace simsols
