// Pipeline: one DEM step as named stages over (Model, State), in order.
//
//   detect_contacts   rebuild grid + neighbour lists when a particle or a
//                     wall has moved more than skin/4 (springs carried
//                     over; the walls near each particle kept with them;
//                     a periodic cell's particles first wrapped into it)
//                                               grid.cl, neighbors.cl, walls.cl
//   contact_forces    particle-particle forces and torques, each pair once
//                                                                  forces.cl
//   membrane_forces   per membrane bead: its bonds and the cell pressure;
//                     returns early without a membrane          membrane.cl
//   finish_particles  per particle, one launch: the partners' shares
//                     collected, wall contacts (near walls only), leapfrog
//                     kick-drift                forces.cl, walls.cl, integrate.cl
//   move_clumps       per clump: the members' forces summed onto the rigid
//                     body, which moves and turns (leapfrog, NO_SQUISH
//                     rotation) and carries its members; returns early
//                     without clumps                               clumps.cl
//   move_walls        servo walls set their velocity from the summed wall
//                     reaction, every wall advances; returns early when the
//                     scene has no walls, and on CPUs, where the last work
//                     group of finish_particles does it
//                     (KernelConfig::servo_in_finish)       reduce.cl, walls.cl
//   move_cell         a periodic cell deforms with its velocity gradient
//                     (host only: the record the kernels read); returns
//                     early without one          periodic_box.h, periodic.cl
//
// step() runs the seven in this order: two kernel launches per step on CPUs,
// three or four on GPUs, one more with clumps, one more with a membrane
// (plus a list build now and then).
// Stages only enqueue kernels on the device's in-order queue;
// detect_contacts reads the flags back every few steps (check_interval).
// Reductions for observables are in observe.h.
#pragma once

#include "solver/core/model.h"
#include "solver/core/periodic_box.h"
#include "solver/core/state.h"

namespace simsols {

void detect_contacts(const Model& model, State& state);
// The lists and wall slots rebuilt at the start of the next step (after a
// host write they no longer cover: a wall moved by a jump, radii scaled),
// through the device's rebuild flag, which checkpoints keep. Not at once:
// until that step the last step's contact forces (share, wall_force) stay
// readable, with the lists they were computed on.
void request_rebuild(const Model& model, State& state);
void contact_forces(const Model& model, State& state);
void membrane_forces(const Model& model, State& state);
void finish_particles(const Model& model, State& state);
void move_clumps(const Model& model, State& state);
void move_walls(const Model& model, State& state);

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
int wall_chunks(const State& state);  // chunks of kWallChunk particles

}  // namespace simsols
