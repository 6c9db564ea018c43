// Test 5: conservation.
//  - An oblique, spinning, frictional, damped pair collision conserves linear
//    and angular momentum to round-off (forces and torques are exactly
//    antisymmetric: each side computes the contact from its own view).
//  - An elastic (e = 1), frictionless gas of 1000 spheres in a box keeps its
//    energy (kinetic + elastic contact energy) within 0.1% over 1e5 steps.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {


class Conservation : public PrecisionTest {};

TEST_P(Conservation, PairCollisionConservesMomentum) {
  Scene s = empty_scene(GetParam(), glass(0.5, 0.3, 1e-4));
  const double R = 2.38125e-3 / 2;
  // off-centre impact with spins: normal, tangential and rolling laws all act
  s.particles = {sphere(R, {-R - 1e-6, -0.4 * R, 0.1 * R}, {0.7, 0.05, 0}, {30, -50, 80}),
                 sphere(R, {R + 1e-6, 0.4 * R, 0}, {-0.5, 0, 0.02}, {-20, 10, 40})};
  Simulation sim(default_device(), s);
  sim.advance(1);
  const Observables before = sim.observe();
  int touching_steps = 0;
  for (int i = 0; i < 3000; ++i) {
    sim.advance(1);
    touching_steps += sim.snapshot().contacts[0] > 0;
  }
  const Observables after = sim.observe();
  ASSERT_GT(touching_steps, 10) << "the spheres must collide";
  // kinetic energy was dissipated: the laws did act
  EXPECT_LT(after.kinetic(), 0.95 * before.kinetic());
  const double m = mass(s, s.particles[0]);
  const double p_scale = m * 1.0;
  const double l_scale = m * 1.0 * R + 0.4 * m * R * R * 100;
  const double tol = GetParam() == Precision::Double ? 1e-12 : 2e-5;
  const double dp = norm(sub(after.momentum, before.momentum)) / p_scale;
  const double dl = norm(sub(after.angular_momentum, before.angular_momentum)) / l_scale;
  std::printf("[measure] %s pair collision: relative change of momentum %.3g, angular momentum %.3g\n",
              precision_name(GetParam()), dp, dl);
  EXPECT_LT(dp, tol);
  EXPECT_LT(dl, tol);
}

// Deterministic pseudo-random numbers in [-1, 1) for initial velocities.
double hash_uniform(std::uint64_t i) {
  std::uint64_t z = i * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

TEST_P(Conservation, ElasticGasKeepsEnergy) {
  Scene s = empty_scene(GetParam(), glass(1.0, 0.0, 0.0));
  const double R = 1e-3, spacing = 3.4e-3;
  const int side = 10;
  const double L = side * spacing;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) {
        const std::uint64_t id = (i * side + j) * side + k;
        s.particles.push_back(sphere(R, {(i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing},
                                     {hash_uniform(3 * id), hash_uniform(3 * id + 1),
                                      hash_uniform(3 * id + 2)}));
      }
  s.walls = {plane("x0", {0, 0, 0}, {1, 0, 0}), plane("x1", {L, 0, 0}, {-1, 0, 0}),
             plane("y0", {0, 0, 0}, {0, 1, 0}), plane("y1", {0, L, 0}, {0, -1, 0}),
             plane("z0", {0, 0, 0}, {0, 0, 1}), plane("z1", {0, 0, L}, {0, 0, -1})};
  Simulation sim(default_device(), s);
  EXPECT_FALSE(sim.model().config().friction || sim.model().config().damping ||
               sim.model().config().rolling || sim.model().config().gravity)
      << "effects a scene does not use are compiled out";
  const double e0 = sim.observe().total_energy();
  double worst = 0;
  double contacts = 0;
  for (int block = 0; block < 100; ++block) {
    sim.advance(1000);
    const Observables o = sim.observe();
    worst = std::max(worst, std::fabs(o.total_energy() / e0 - 1.0));
    contacts += o.contacts;
  }
  std::printf("[measure] %s elastic gas, 1000 spheres, 1e5 steps: max |E/E0 - 1| = %.3g, "
              "%lld list builds, mean contacts per sample %.1f\n",
              precision_name(GetParam()), worst,
              static_cast<long long>(sim.state().list_builds), contacts / 100);
  EXPECT_GT(contacts, 0) << "the gas must collide";
  EXPECT_EQ(sim.state().late_builds, 0) << "lists must never go stale between checks";
  EXPECT_LT(worst, 1e-3);
}

SIMSOLS_BOTH_PRECISIONS(Conservation);

}  // namespace
}  // namespace simsols::testing
