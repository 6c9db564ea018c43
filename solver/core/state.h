// State: everything that changes during a run, as device buffers.
//
// MuJoCo's mjData to the Model's mjModel. Struct of arrays, split into hot
// per-particle records read every step (pos, vel, omega, force, torque) and
// colder ones (neighbour lists, grid, wall slots, reduction scratch).
// Records pack a constant into the spare 4th lane so one load serves the
// contact loop: pos = (x, radius), vel = (v, mass), omega = (w, material).
// pos_lo is the float-run compensation term (see kernels/common.cl).
//
// Memory is linear in N: per particle a fixed number of records, per
// listed pair one upper and one lower list slot (neighbors.cl, sliced
// lists) and per wall near a particle one wall slot (walls.cl), both grown
// when a rebuild needs more, with 1/16 to spare; the grid hash table has
// N to 2N buckets.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "solver/core/cl_device.h"
#include "solver/core/model.h"
#include "solver/core/periodic_box.h"

namespace simsols {

struct Buffer {
  ClMem mem;
  size_t bytes = 0;
  cl_mem get() const { return mem.get(); }
};

// A wall's force control as the servo_walls kernel reads it (walls.cl):
// (target, gain, max_speed, on) and (1/T_i, 1/mass, 0, 0).
std::array<double, 8> servo_record(const WallServo& servo);
// 1/J of a wall free to tilt while `servo` drives it (a dead weight on a
// rectangle with Wall::tilts), else 0: the wall is held at its tilt.
double tilt_inverse_inertia(const Wall& wall, const WallServo& servo);

class State {
 public:
  explicit State(const Model& model);

  // hot, per particle
  Buffer pos, pos_lo, vel, omega, force, torque;
  // neighbour lists, sliced (neighbors.cl). Per particle: the list length
  // (nbr_count) and its upper part's (nbr_upper, partners above its index);
  // per slice, where its upper and lower blocks start (up_off, lo_off, one
  // more entry: the totals). Per upper slot (up_slots of them): the partner
  // (nbr), the contact's history (spring, HIST planes of up_slots records)
  // and the partner's share of the last step (share: a force record and a
  // torque record side by side; it holds the previous lists during a
  // rebuild). Per lower slot (lo_slots): the upper slot where the partner's
  // share waits (mirror; the rebuild puts the partner's id there first).
  // old_up_off: the previous upper lists' offsets, which a rebuild carries
  // the history over from (the rest of the previous lists waits in `share`:
  // list_scratch()).
  Buffer pos_build, nbr_count, nbr_upper, up_off, lo_off, nbr, spring, share, mirror;
  Buffer old_up_off;
  // grid
  Buffer bucket, slot, cell_count, cell_start, sorted, chunk_sum;
  // walls: current reference point (+ float compensation; point.w: travel
  // since the last list build), velocity; per particle the walls it touched
  // last step (bit w of wall_touch) and the walls within radius + skin at
  // the last list build (bit w of wall_near: the broad phase, walls.cl); a
  // slot per (particle, near wall), sliced as the lists are (wall_off, per
  // slice and the total): its history (wall_spring, HIST planes of
  // wall_slots records) and the force on the wall (wall_force).
  // old_wall_off: the previous layout's offsets, which a rebuild carries the
  // slots over from (the rest waits in `share`: wall_scratch()).
  Buffer wall_point, wall_point_lo, wall_vel, wall_touch, wall_near, wall_off, wall_spring,
      wall_force;
  Buffer old_wall_off;
  // servo walls: per wall servo_record() (below), set by the scene and changed at run time (set_servo); and what the servo saw:
  // (F last step, sum of F since the last read, integral velocity, steps)
  // wall_mean: per wall the force summed over steps (xyz) and the steps (w),
  // kept when the kernels have servo walls (read_wall_means)
  Buffer servo, wall_reaction, wall_mean;
  // walls that may tilt (Wall::tilts, HAS_TILT): per wall (tilt in rad,
  // its rate in rad/s, 1/J while free to turn or 0, the beads' moment last
  // step in N m), walls.cl; zeros and unread without such a wall
  Buffer wall_turn;
  bool tilting = false;  // the kernels have tilting walls (wall_turn is state)
  // a membrane (scene.h, Membrane; membrane.cl): its record of three real4
  // (pressure, held, stiffness, rest lengths, dashpots, lattice), set at run
  // time (Simulation::set_membrane), state; and each bead's bond and
  // pressure force of this step (scratch). Stand-ins without a membrane.
  Buffer membrane, membrane_force;
  int membrane_beads = 0;
  // flags: FLAG_SLOTS ints, their slots named in solver/kernels/layout.h
  // (list rebuild needed, longest list asked for, max |v|^2 since the last
  // check, late, the runaway mark of guard.h).
  // groups_done: finish_particles' count of its work groups done, 0 between
  // launches (integrate.cl, SERVO_IN_FINISH), apart from flags' cache line
  Buffer flags, groups_done, obs_partial, wall_partial;
  static constexpr int kNoRunaway = 0x7fffffff;  // flags[4] when no particle is marked
  // contacts of each particle in the last step (force.w, kept by integrate):
  // the rolling cap's divisor (forces.cl). Derived from `force`, so not
  // saved: derive_state() rebuilds it after a load.
  Buffer touching;
  // clumps (clumps.cl): per clump its centroid (relative to the origin, +
  // float compensation), orientation (body to scene, x y z w), velocity and
  // angular momentum (scene frame, half-step); one-record stand-ins
  // without clumps.
  Buffer clump_pos, clump_pos_lo, clump_quat, clump_vel, clump_mom;
  // the periodic cell's record (layout.h CELL_*, periodic.cl; zeros and
  // unread without one) and the host's mirror of it (periodic_box.h)
  Buffer cell;
  CellNow cell_now;

  int n = 0;             // particles
  int clumps = 0;        // rigid clumps of particles
  int slices = 0;        // list slices of KernelConfig::slice particles
  int up_slots = 0;      // allocated upper list slots (the history planes' stride)
  int lo_slots = 0;      // allocated lower list slots
  int wall_slots = 0;    // allocated wall slots (the wall history planes' stride)
  std::uint32_t table = 0;   // grid hash buckets (power of two)
  std::uint32_t chunks = 256, chunk_len = 0;

  std::int64_t step = 0;
  double time = 0;
  std::int64_t list_builds = 0;
  std::int64_t next_check = 0;   // step at which detect_contacts next reads the flags
  std::int64_t late_builds = 0;  // checks that found a particle beyond skin/2 (should stay 0)
  bool fault_seen = false;       // a list check found the runaway mark set (guard.h)

  size_t device_bytes() const;
  // Every buffer, named (device_bytes() is their sum).
  std::vector<std::pair<std::string, const Buffer*>> all_buffers() const;

  // Named dynamic buffers and their sizes, for checkpoints (fixed order).
  std::vector<std::pair<std::string, Buffer*>> dynamic_buffers();

  // Reallocates the current upper lists (nbr, spring) with `slots` slots;
  // the previous lists, held in `share`, are kept for the rebuild, which
  // then calls upper_scratch().
  void grow_upper(const Model& model, int slots);
  // share sized for up_slots.
  void upper_scratch(const Model& model);
  // The part of `share` that holds the last step's shares (two records per
  // upper slot; the buffer may be larger, for list_scratch()).
  size_t share_bytes(const Model& model) const {
    return std::max<size_t>(16, size_t(up_slots) * 2 * 4 * model.real_size());
  }

  // The previous lists and wall slots during a rebuild (pipeline.cpp), as
  // views into `share`, whose contents are dead between steps (a step's
  // pair kernel writes them before its finishing kernel reads them): no
  // second copy of the lists stays allocated. Each view has its buffer's
  // size now, at the device's base alignment; share grows, contents lost,
  // when they do not fit. A rebuild copies into the views, then lays out
  // the new lists and slots from them.
  struct ListScratch {
    Buffer hist, nbr, upper;  // spring, nbr, nbr_upper
  };
  struct WallScratch {
    Buffer near, spring, force;  // wall_near, wall_spring, wall_force
  };
  ListScratch list_scratch(const Model& model);
  WallScratch wall_scratch(const Model& model);
  // Reallocates the lower lists (mirror) with `slots` slots.
  void grow_lower(const Model& model, int slots);
  // Reallocates all slot buffers, zeroed, with the given capacities.
  void resize_lists(const Model& model, int up, int lo);
  size_t spring_bytes(const Model& model) const;
  // Reallocates the wall slots (wall_spring, wall_force), zeroed, with
  // `slots` slots (a rebuild's previous layout waits in wall_scratch()).
  void grow_walls(const Model& model, int slots);
  void resize_walls(const Model& model, int slots) { grow_walls(model, slots); }
  // The list and wall capacities of a saved state (a checkpoint, the
  // guard's copy): reallocates, zeroed, the buffers whose capacity differs.
  void resize_slots(const Model& model, int up, int lo, int walls) {
    if (up != up_slots || lo != lo_slots) resize_lists(model, up, lo);
    if (walls != wall_slots) resize_walls(model, walls);
  }

 private:
  Buffer make(Device& d, size_t bytes, const void* init = nullptr);
  // Consecutive views of `share` of these sizes (list_scratch()).
  std::vector<Buffer> share_views(const Model& model, std::initializer_list<size_t> sizes);
  // The constructor's parts, in its order. The particle records from the
  // scene; returns the largest |v|^2 at the start (the first list check's).
  float make_particles(const Model& model);
  // Empty lists: per-particle lengths, slice offsets, the initial slots.
  void make_lists(const Model& model);
  void make_grid(Device& d);
  // The walls' points and velocities, their per-particle masks, no slots.
  void make_walls(const Model& model);
  // The servo records (servo_record) and the readings.
  void make_servo(const Model& model);
  void make_flags(const Model& model, float v2_start);
  // touching, the observables' and the walls' reduction partials.
  void make_step_scratch(const Model& model);
  // The clumps' bodies from the scene.
  void make_clumps(const Model& model);
  // The periodic cell's record from the scene's (zeros without one).
  void make_cell(const Model& model);
  void make_membrane(const Model& model);
};

// Slot k of particle i's list given its slice offsets: SLOT in common.cl.
inline size_t list_slot(const std::vector<std::uint32_t>& off, int slice, int i, int k) {
  return off[i / slice] + size_t(k) * slice + i % slice;
}

// Component c (0..3) of slot `slot`'s record in a plane of list-slot records
// (spring): SLOT_REAL in common.cl (a slice's records by component).
inline size_t slot_real(size_t slot, int slice, int c) {
  return slot / slice * 4 * slice + size_t(c) * slice + slot % slice;
}

}  // namespace simsols
