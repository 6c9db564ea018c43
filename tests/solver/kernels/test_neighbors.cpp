// Contact detection (grid + Verlet lists): the contact history survives
// every list rebuild, and memory grows linearly with N.
#include <cmath>
#include <cstdio>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

// A frictional, rolling-resistant heap sliding down onto a floor: tangential
// springs are loaded all the time.
Scene sliding_heap(Precision p, double skin) {
  Scene s = empty_scene(p, soft(0.6, 0.4, 1e-4));
  s.effects.gravity = {2.0, 0, -9.81};  // tilted gravity: contacts slide and roll
  const double R = 1e-3, spacing = 2e-3;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        s.particles.push_back(sphere(R, {(i + 0.5 * (k % 2)) * spacing, (j + 0.5 * (k % 2)) * spacing,
                                         R + k * 0.7072 * spacing},  // layers just touching
                                     {0.02, 0, 0}));
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  s.numerics.skin = skin;
  return s;
}

class Neighbors : public PrecisionTest {};

TEST_P(Neighbors, HistorySurvivesListRebuilds) {
  // Same scene with a generous skin (few rebuilds) and a tiny one (a rebuild
  // every few steps). Non-touching list entries contribute exact zeros and
  // lists are sorted, so if every spring is carried over the two runs agree
  // bit for bit.
  Simulation few(default_device(), sliding_heap(GetParam(), 4e-4));
  Simulation many(default_device(), sliding_heap(GetParam(), 2e-7));
  few.advance(5000);
  many.advance(5000);
  std::printf("[measure] %s list builds: %lld (skin 0.4 mm) vs %lld (skin 0.2 um)\n",
              precision_name(GetParam()), static_cast<long long>(few.state().list_builds),
              static_cast<long long>(many.state().list_builds));
  EXPECT_GT(many.state().list_builds, 20 * few.state().list_builds);
  // (with a 0.2 um skin a bead can cross skin/4 in one step, so the late
  // counter may tick there; the bit-exact comparison below is the real test)
  EXPECT_EQ(few.state().late_builds, 0);
  const ParticleSnapshot a = few.snapshot(), b = many.snapshot();
  EXPECT_GT(few.observe().contacts, 144) << "the heap must be in contact";
  for (size_t i = 0; i < a.position.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(a.position[i][c], b.position[i][c]) << "particle " << i;
      ASSERT_EQ(a.angular_velocity[i][c], b.angular_velocity[i][c]) << "particle " << i;
    }
}

TEST_P(Neighbors, WallSlotsSurviveRebuildsInTheSharesGrownForThem) {
  // Two touching beads in a corner (a floor and two side walls), thrown
  // spinning out of it along the floor with gravity pulling them back: they
  // slide and roll against the floor and the end wall, each with up to three
  // loaded wall springs, and one pair between them. During a rebuild the previous wall slots wait in `share`
  // (State::wall_scratch), which the shares of one pair leave too small: it
  // grows for them. With a tiny skin (a rebuild every few steps) the run
  // matches one with a generous skin bit for bit.
  auto corner = [&](double skin) {
    Scene s = empty_scene(GetParam(), soft(0.6, 0.4, 1e-4));
    s.effects.gravity = {-3.0, -3.0, -9.81};
    const double R = 1e-3, r = R * (1 - 1e-4);
    s.particles = {sphere(R, {r, r, r}, {0.05, 0, 0}, {0, 0, 30}),
                   sphere(R, {r, r + 2 * r, r}, {0.05, 0, 0}, {0, 0, 30})};
    s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), plane("side", {0, 0, 0}, {1, 0, 0}),
               plane("end", {0, 0, 0}, {0, 1, 0})};
    s.numerics.skin = skin;
    return s;
  };
  Simulation few(default_device(), corner(4e-4));
  Simulation many(default_device(), corner(2e-7));
  few.advance(5000);
  many.advance(5000);
  const State& st = many.state();
  std::printf("[measure] %s list builds: %lld (skin 0.4 mm) vs %lld (skin 0.2 um); wall slots "
              "%d, share %zu B of which shares %zu B\n",
              precision_name(GetParam()), static_cast<long long>(few.state().list_builds),
              static_cast<long long>(st.list_builds), st.wall_slots, st.share.bytes,
              st.share_bytes(many.model()));
  EXPECT_GT(st.list_builds, 20 * few.state().list_builds);
  EXPECT_GT(st.share.bytes, st.share_bytes(many.model())) << "share never grew for the walls";
  const ParticleSnapshot a = few.snapshot(), b = many.snapshot();
  EXPECT_LT(std::abs(a.angular_velocity[0][2]), 29.0) << "the wall contacts must have slowed the spin";
  for (size_t i = 0; i < a.position.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(a.position[i][c], b.position[i][c]) << "particle " << i;
      ASSERT_EQ(a.angular_velocity[i][c], b.angular_velocity[i][c]) << "particle " << i;
    }
}

TEST_P(Neighbors, ListsGrowOnOverflowWithoutChangingResults) {
  // 4 slots per particle overflow at once in this heap (up to ~10
  // neighbours within the skin): the lists grow and the run matches a roomy
  // one bit for bit.
  Scene tight = sliding_heap(GetParam(), 4e-4);
  tight.numerics.neighbor_capacity = 4;
  Scene roomy = sliding_heap(GetParam(), 4e-4);
  roomy.numerics.neighbor_capacity = 64;
  Simulation a(default_device(), tight), b(default_device(), roomy);
  a.advance(500);
  b.advance(500);
  EXPECT_GT(a.state().up_slots, a.state().n * 2);  // grown beyond the 2 per part reserved
  const ParticleSnapshot pa = a.snapshot(), pb = b.snapshot();
  for (size_t i = 0; i < pa.position.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(pa.position[i][c], pb.position[i][c]) << i;
}

TEST_P(Neighbors, ListMemoryFollowsThePairs) {
  // A 16^3 simple cubic lattice of touching beads: 3 * 16^2 * 15 pairs
  // within the skin (the diagonals lie beyond it). Each pair takes one upper
  // slot (its owner's) and one lower slot; slices add padding only where
  // their beads' lists differ in length (the lattice's faces), and the
  // buffers keep 1/16 to spare.
  const int side = 16;
  const double R = 1e-3, a = 2 * R * (1 - 1e-4);
  Scene s = empty_scene(GetParam(), glass());
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) s.particles.push_back(sphere(R, {i * a, j * a, k * a}));
  Simulation sim(default_device(), s);
  sim.advance(2);
  const double pairs = 3.0 * side * side * (side - 1);
  const State& st = sim.state();
  std::printf("[measure] %s: %.0f pairs, %d upper and %d lower slots\n",
              precision_name(GetParam()), pairs, st.up_slots, st.lo_slots);
  EXPECT_GE(st.up_slots, pairs);
  EXPECT_LE(st.up_slots, 1.2 * pairs);
  EXPECT_GE(st.lo_slots, pairs);
  EXPECT_LE(st.lo_slots, 1.2 * pairs);
  EXPECT_EQ(st.wall_slots, 0);  // no walls
}

TEST_P(Neighbors, MemoryGrowsLinearly) {
  auto bytes_per_particle = [&](int side) {
    Scene s = empty_scene(GetParam(), glass());
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j)
        for (int k = 0; k < side; ++k)
          s.particles.push_back(sphere(1e-3, {i * 2.5e-3, j * 2.5e-3, k * 2.5e-3}));
    Simulation sim(default_device(), s);
    sim.advance(2);
    return double(sim.state().device_bytes()) / s.particles.size();
  };
  const double small = bytes_per_particle(10), large = bytes_per_particle(40);  // 1e3, 6.4e4
  std::printf("[measure] %s device bytes per particle: %.0f (N=1000), %.0f (N=64000)\n",
              precision_name(GetParam()), small, large);
  EXPECT_NEAR(large / small, 1.0, 0.1);
}

SIMSOLS_BOTH_PRECISIONS(Neighbors);

}  // namespace
}  // namespace simsols::testing
