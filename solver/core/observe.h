// Observe: what a run measures, read back from the device.
//
// observe() sums per-particle observables with a device reduction in a fixed
// order (deterministic) and adds the group partials in double on the host.
// wall_reactions() gives the force the particles exert on each wall.
// download() copies the particle state to the host (for dumps, tests and
// the renderer's host path); state_hash() hashes the raw dynamic buffers
// bit for bit.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "solver/core/model.h"
#include "solver/core/state.h"

namespace simsols {

struct Observables {
  double kinetic_translational = 0;  // J, at synchronized velocities v_n
  double kinetic_rotational = 0;     // J
  double elastic_energy = 0;         // J, 2/5 K_n d^{5/2} summed over contacts
  double gravitational_energy = 0;   // J, -m g.x relative to the scene origin
  double contacts = 0;               // sum over particles of touching partners (pairs twice, walls once)
  double particles = 0;
  Vec3 momentum{};                   // kg m/s
  Vec3 angular_momentum{};           // kg m^2/s, about the scene origin
  double kinetic() const { return kinetic_translational + kinetic_rotational; }
  double total_energy() const { return kinetic() + elastic_energy + gravitational_energy; }
};

struct WallReaction {
  Vec3 force{};  // N, exerted by the particles on the wall
  int contacts = 0;
};

// Reads `count` reals (float or double on the device) from element `first`
// of a buffer, as doubles.
std::vector<double> read_reals(const Model& model, const Buffer& buffer, size_t count,
                               size_t first = 0);

// A clump's rigid-body state (clumps.cl): centroid (absolute, m),
// orientation (body to scene, w x y z), velocity and angular momentum
// (scene frame; the half-step values of the leapfrog), and its kinetic
// energy from them, 1/2 M V^2 + 1/2 sum L_b,k^2 / I_k.
struct ClumpState {
  Vec3 position{};
  std::array<double, 4> orientation{1, 0, 0, 0};
  Vec3 velocity{}, angular_momentum{};
  Vec3 angular_velocity{};  // rad/s, scene frame
  double kinetic_energy = 0;
};
std::vector<ClumpState> clump_states(const Model& model, State& state);

Observables observe(const Model& model, State& state);
std::vector<WallReaction> wall_reactions(const Model& model, State& state);
// Current position of each wall's reference point (absolute, m).
std::vector<Vec3> wall_points(const Model& model, State& state);

struct ParticleSnapshot {
  std::vector<Vec3> position;          // absolute, m
  std::vector<Vec3> velocity;          // m/s (half-step velocities of the leapfrog)
  std::vector<Vec3> angular_velocity;  // rad/s
  std::vector<Vec3> force;             // N, last contact + wall force
  std::vector<double> radius;          // m
  std::vector<int> material;
  std::vector<int> contacts;           // touching neighbours + walls
};

ParticleSnapshot download(const Model& model, State& state);

// Every touching contact of the last force evaluation: bead pairs once
// (a < b) and bead-wall contacts (b = -1 - wall index). `force` is what b
// exerts on a. Used by the stress measurement and the force-chain view.
struct ContactForce {
  int a = 0, b = 0;
  Vec3 force{};
};
std::vector<ContactForce> contact_list(const Model& model, State& state);

// The upper parts of the neighbour lists (the pairs each particle owns,
// neighbors.cl), read back: lengths, slice offsets, partners.
struct UpperLists {
  int slice = 1;
  std::vector<int> upper;               // per particle
  std::vector<std::uint32_t> off;       // per slice, + the total
  std::vector<int> nbr;                 // per upper slot
  size_t slot(int i, int k) const { return list_slot(off, slice, i, k); }
  // component c of a slot's record in a history plane (spring)
  size_t real_at(size_t slot, int c) const { return slot_real(slot, slice, c); }
};
UpperLists read_upper_lists(const Model& model, State& state);

// The wall slots' layout (walls.cl), read back: which walls are near each
// particle, and where their slots lie. Only for scenes with walls.
struct WallSlots {
  int slice = 1;
  std::vector<int> mask;                // per particle, bit w: wall w near
  std::vector<std::uint32_t> off;       // per slice, + the total
  bool near(int i, int w) const { return (mask[i] >> w) & 1; }
  size_t slot(int i, int w) const {
    return list_slot(off, slice, i, std::popcount(unsigned(mask[i]) & ((1u << w) - 1)));
  }
};
WallSlots read_wall_slots(const Model& model, State& state);

// FNV-1a over the dynamic buffers (positions, velocities, springs, lists...).
std::uint64_t state_hash(const Model& model, State& state);

}  // namespace simsols
