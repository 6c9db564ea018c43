// Pipeline: one DEM step as named stages over (Model, State), in order.
//
//   detect_contacts  rebuild grid + neighbour lists when a particle has moved
//                    more than skin/2 (springs carried over)   grid.cl, neighbors.cl
//   contact_forces   particle-particle forces and torques      forces.cl
//   wall_forces      particle-wall forces; returns early when
//                    the scene has no walls                     walls.cl
//   integrate        leapfrog kick-drift; servo walls set their
//                    velocity from the wall reaction; walls advanced  integrate.cl, walls.cl
//
// step() runs the four in this order. Stages only enqueue kernels on the
// device's in-order queue; detect_contacts reads one flag back per step.
// Reductions for observables are in observe.h.
#pragma once

#include "model.h"
#include "state.h"

namespace simsols {

void detect_contacts(const Model& model, State& state, bool force_rebuild = false);
void contact_forces(const Model& model, State& state);
void wall_forces(const Model& model, State& state);
void integrate(const Model& model, State& state);

void step(const Model& model, State& state);

// Recomputes what the state derives from its saved buffers (the contact
// counts of the last step, State::touching) after they were written
// wholesale: a checkpoint loaded, the guard's copy restored.
void derive_state(const Model& model, State& state);

// Enqueues the per-wall sums of the forces particles exert on walls into
// state.wall_partial (walls x chunks of kWallChunk particles, each summed in
// index order); returns the number of chunks.
inline constexpr int kWallChunk = 128;
size_t reduce_wall_forces(const Model& model, State& state);

}  // namespace simsols
