// What the loading programmes share between their stages: the end of
// settling, the beads' speed for the equilibrium criteria, and the platen
// lowered onto a settled specimen. One spelling for the shear test, the
// oedometer and the triaxial test (their headers state the criteria).
#pragma once

#include "solver/apparatus/cell/platen_servo.h"
#include "solver/core/simulation.h"

namespace simsols {

// Settling has ended after `elapsed` seconds: at `cap`, or once the beads'
// kinetic energy is below 1e-4 N m g d (not in the first 2 ms under
// gravity, while the beads are still falling from rest).
bool settled_under_gravity(Simulation& sim, const SpecimenStats& stats, double elapsed, double cap);

// The specimen's preparation friction (scene.h, Preparation) on while it
// settles, the materials' own once it has: call at every change of stage.
// Nothing is written for a specimen that settles with its own friction.
void preparation_friction(Simulation& sim, const Specimen& specimen, bool settling);

// The beads' RMS translational speed (m/s).
double rms_bead_speed(const Observables& o, const SpecimenStats& stats);

// The height of the highest bead's top (m; 0 without beads).
double specimen_top(Simulation& sim);

// The apparatus' platen: the wall named "platen" (throws without one).
int platen_wall(const Scene& scene);

// Moves the platen (a wall whose normal points down) to `clearance` above
// the highest bead, never up.
void lower_platen_onto_specimen(Simulation& sim, int platen, double clearance);

}  // namespace simsols
