#include "solver/apparatus/cell/stage_checks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace simsols {

bool settled_under_gravity(Simulation& sim, const SpecimenStats& stats, double elapsed,
                           double cap) {
  if (elapsed >= cap) return true;
  if (sim.scene().has_gravity() && elapsed < 2e-3) return false;
  const Observables o = sim.observe();
  const double scale = stats.count * stats.bead_mass * 9.81 * stats.diameter;
  return o.kinetic() < 1e-4 * scale;
}

void preparation_friction(Simulation& sim, const Specimen& specimen, bool settling) {
  const Preparation& p = specimen.preparation;
  if (!p.settles_differently()) return;
  if (!settling) return sim.override_friction(std::nullopt);
  sim.override_friction(Model::FrictionOverride{p.friction, p.rolling_friction});
}

double rms_bead_speed(const Observables& o, const SpecimenStats& stats) {
  return std::sqrt(2 * o.kinetic_translational / (stats.count * stats.bead_mass));
}

int platen_wall(const Scene& s) {
  for (size_t w = 0; w < s.walls.size(); ++w)
    if (s.walls[w].name == "platen") return static_cast<int>(w);
  throw std::logic_error("the apparatus has no platen");
}

double specimen_top(Simulation& sim) {
  const ParticleSnapshot snap = sim.snapshot();
  double top = 0;
  const size_t beads = sim.scene().specimen_count();  // not a waiting membrane's
  for (size_t i = 0; i < beads; ++i) top = std::max(top, snap.position[i][2] + snap.radius[i]);
  return top;
}

void lower_platen_onto_specimen(Simulation& sim, int platen, double clearance) {
  Vec3 p = sim.wall_point(platen);
  p[2] = std::min(p[2], specimen_top(sim) + clearance);
  sim.set_wall_point(platen, p);
}

}  // namespace simsols
