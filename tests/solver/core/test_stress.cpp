// The Love-Weber stress (solver/core/stress.h) against hand computations.
//
// Theory. A contact c between bead a and partner b carries the force f on a
// (from b) along the branch l from a's centre to b's centre (or to the
// wall's contact point). Over a slab z in [z_lo, z_hi] of horizontal area A
//   sigma_ij = -(1/V) sum_c w_c f_i l_j,   V = A (z_hi - z_lo),
// w_c the fraction of l's length inside the slab (compression positive).
//   - Two beads pressed along n with Hertz force F (f = -F n, l = L n) and
//     the slab holding the whole branch: sigma = F L n n^T / V.
//   - A slab crossed by the branch, inside its z-span: w = (z_hi - z_lo) /
//     (L n_z), so sigma_ij = F n_i n_j / (A n_z); the column sigma_iz =
//     F n_i / A is the force per area carried across a horizontal plane.
//   - A column of beads resting on a floor: in equilibrium the contact below
//     bead k carries the weight of bead k and of every bead above it, so a
//     thin slab between two centres measures sigma_zz = (weight above) / A.
// Hertz (contact_model.h): F = 4/3 E* sqrt(R*) d^{3/2}, R* = R/2 for two
// equal beads, R for a bead on a wall of the same material.
#include <cmath>

#include "solver/core/stress.h"
#include "solver/scene/clump.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

constexpr double kR = 1e-3;
constexpr double kArea = 4 * kR * kR;  // a column's share of a square packing

// The kernels of test_guard and test_determinism (friction, rolling
// resistance, damping, gravity, walls): one build shared.
Scene stress_scene(double floor_z) {
  Scene s = empty_scene(Precision::Double, glass(0.5, 0.3, 5e-5));
  s.effects.gravity = {0, 0, -9.81};
  s.walls = {plane("floor", {0, 0, floor_z}, {0, 0, 1})};
  return s;
}

double hertz(const Scene& s, double rstar, double overlap) {
  return 4.0 / 3.0 * e_star(s.materials[0]) * std::sqrt(rstar) * std::pow(overlap, 1.5);
}

// Every component against the expected tensor, relative to its largest.
void expect_tensor(const Tensor3& got, const Tensor3& want, double rel) {
  double scale = 0;
  for (const auto& row : want)
    for (double v : row) scale = std::max(scale, std::fabs(v));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(got[i][j], want[i][j], rel * scale) << "component " << i << j;
}

// Two beads overlapping by d = 1e-7 m along an oblique n, at rest: the forces
// of the first step are Hertz at the placed overlap (no dashpot, no tangential
// spring yet), and the step moves the beads by ~1e-10 m (1e-7 of L).
TEST(LoveWeber, PressedPairMatchesHandComputation) {
  Scene s = stress_scene(-1);
  const double d = 1e-7, L = 2 * kR - d;
  const Vec3 n{1.0 / 3, 2.0 / 3, 2.0 / 3};
  const Vec3 xa{0, 0, 0}, xb{L * n[0], L * n[1], L * n[2]};
  s.particles = {sphere(kR, xa), sphere(kR, xb)};
  const double F = hertz(s, kR / 2, d);
  Simulation sim(default_device(), s);
  sim.advance(1);

  Tensor3 whole{}, crossed{};
  const double V = kArea * 1.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      whole[i][j] = F * L * n[i] * n[j] / V;
      crossed[i][j] = F * n[i] * n[j] / (kArea * n[2]);
    }
  // achieved 8e-8 of the largest component (the branch read after the
  // step's motion); crossed: 9e-12 (the branch's length cancels)
  expect_tensor(love_weber_slab(sim, -0.5, 0.5, kArea), whole, 1e-6);
  const double lz = L * n[2];
  expect_tensor(love_weber_slab(sim, 0.3 * lz, 0.5 * lz, kArea), crossed, 1e-10);
  const Tensor3 above = love_weber_slab(sim, 1.01 * lz, 1.2 * lz, kArea);
  for (const auto& row : above)
    for (double v : row) EXPECT_EQ(v, 0) << "a slab no branch crosses carries nothing";
}

// A bead pressed into the floor: the branch runs from its centre down to the
// contact point, R - d long, and the wall pushes it up with Hertz (R* = R).
TEST(LoveWeber, BeadOnWallMatchesHandComputation) {
  Scene s = stress_scene(0);
  const double d = 1e-7, L = kR - d;
  s.particles = {sphere(kR, {0, 0, L})};
  const double F = hertz(s, kR, d);
  Simulation sim(default_device(), s);
  sim.advance(1);
  Tensor3 want{};
  // achieved 1.1e-7 and 9e-13 of sigma_zz
  want[2][2] = F * L / (kArea * 2 * L);  // slab [0, 2L]: w = 1
  expect_tensor(love_weber_slab(sim, 0, 2 * L, kArea), want, 1e-6);
  want[2][2] = F / kArea;  // slab inside the branch
  expect_tensor(love_weber_slab(sim, 0.25 * L, 0.5 * L, kArea), want, 1e-11);
}

// Three beads stacked on the floor, dropped from touching and left to settle
// (restitution 0.5, 30000 steps of 0.18 us); in equilibrium the contacts
// carry 3, 2 and 1 weights.
TEST(LoveWeber, ColumnUnderGravityCarriesTheWeightAbove) {
  Scene s = stress_scene(0);
  for (int k = 0; k < 3; ++k) s.particles.push_back(sphere(kR, {0, 0, kR * (1 + 2 * k)}));
  const double w = mass(s, s.particles[0]) * 9.81;
  Simulation sim(default_device(), s);
  sim.advance(30000);
  const ParticleSnapshot q = sim.snapshot();
  const double z0 = q.position[0][2], z1 = q.position[1][2], z2 = q.position[2][2];
  auto szz = [&](double lo, double hi) { return love_weber_slab(sim, lo, hi, kArea)[2][2]; };
  const double tol = 1e-6;  // of the weight per area; achieved 7e-8 (what is left of the settling)
  EXPECT_NEAR(szz(0.2 * z0, 0.8 * z0) * kArea / w, 3, tol);
  EXPECT_NEAR(szz(z0 + 0.1 * kR, z1 - 0.1 * kR) * kArea / w, 2, tol);
  EXPECT_NEAR(szz(z1 + 0.1 * kR, z2 - 0.1 * kR) * kArea / w, 1, tol);
  // floor to the top centre: the planes' mean of 3, 2 and 1 weights
  const double mean = (3 * z0 + 2 * (z1 - z0) + (z2 - z1)) / z2;
  EXPECT_NEAR(szz(0, z2) * kArea / w, mean, tol);
  const Tensor3 all = love_weber_slab(sim, 0, z2, kArea);
  EXPECT_EQ(all[0][0], 0);  // the column is exactly vertical
  EXPECT_EQ(all[0][2], 0);
  EXPECT_EQ(all[2][0], 0);
}

// Two upright dimers (two touching spheres each, a rigid grain) stacked on
// the floor and settled as the bead column above. A grain's branch
// vectors run from its centroid: the floor contact from A's centroid (2R)
// down to the floor, the grains' contact from A's centroid to B's (6R).
// Between the centroids the planes carry B's weight, above A's centroid
// and below it both grains' weights: a slab in (2R, 6R) reads B's weight
// per area, one in (0, 2R) both. Branch vectors between the member
// spheres (3R to 5R) would read B's weight over only the part of the slab
// they cross: 0.56 of it for the slab below.
TEST(LoveWeber, StackedGrainsCarryTheWeightAboveThroughTheirCentroids) {
  Scene s = stress_scene(0);
  s.grains = {{"dimer", {{0, 0, -kR, kR}, {0, 0, kR, kR}}, ""}};
  const GrainBody body = grain_body(s.grains[0]);
  for (double z : {2 * kR, 6 * kR}) {
    Clump c;
    c.position = {0, 0, z};
    add_clump(s, c, body);
  }
  const double w = 2 * mass(s, s.particles[0]) * 9.81;  // one grain: the union of two touching spheres
  Simulation sim(default_device(), s);
  sim.advance(30000);
  const std::vector<ClumpState> g = sim.clumps();
  const double za = g[0].position[2], zb = g[1].position[2];
  auto szz = [&](double lo, double hi) { return love_weber_slab(sim, lo, hi, kArea)[2][2]; };
  const double tol = 5e-9;  // of the weight per area; achieved 4e-10
  EXPECT_NEAR(szz(za + 0.1 * kR, zb - 0.1 * kR) * kArea / w, 1, tol);
  EXPECT_NEAR(szz(0.1 * za, 0.9 * za) * kArea / w, 2, tol);
  const Tensor3 all = love_weber_slab(sim, 0, zb, kArea);
  EXPECT_NEAR(all[0][2], 0, 1e-12 * all[2][2]);  // a vertical column: 1e-49 Pa from the quaternions' rounding
}

}  // namespace
}  // namespace simsols::testing
