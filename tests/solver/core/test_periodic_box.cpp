// The periodic cell (solver/core/periodic_box.h, kernels/periodic.cl): the
// host's minimum images and tilt folding against brute force, and pairs of
// spheres that collide across the cell's faces against the same pair
// colliding in open space (no cell). In a cell sheared with a velocity
// gradient L whose square is zero (simple shear), the SLLOD equations the
// kernels integrate are Newton's for the total velocity u + L (x - c0), so
// the two runs must follow the same relative motion to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/core/periodic_box.h"
#include "solver/core/simulation.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

using testing::empty_scene;
using testing::sphere;

constexpr double kR = 0.5e-3;

Material beads() {
  Material m;
  m.name = "beads";
  m.young_modulus = 0.5e9;
  m.poisson_ratio = 0.2;
  m.density = 2500;
  m.restitution = 0.5;
  m.sliding_friction = 0.3;
  m.rolling_friction = 0;
  return m;
}

// An upper-triangular cell with random edges and tilts up to half an edge.
Mat3 random_cell(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> len(1, 2), tilt(-0.5, 0.5);
  const double lx = len(rng), ly = len(rng), lz = len(rng);
  return {lx, tilt(rng) * lx, tilt(rng) * lx, 0, ly, tilt(rng) * ly, 0, 0, lz};
}

TEST(PeriodicBox, MinimumImageFindsTheNearestImage) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> shift(-3, 3);
  double worst = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Mat3 h = random_cell(rng);
    const Vec3 w = cell_widths(h);
    const double reach = 0.49 * std::min({w[0], w[1], w[2]});
    Vec3 d{u(rng), u(rng), u(rng)};
    d = scale(reach * std::abs(u(rng)) / norm(d), d);  // |d| below half the thinnest width
    const Vec3 image = apply3(h, {double(shift(rng)), double(shift(rng)), double(shift(rng))});
    const Vec3 found = min_image(h, {d[0] + image[0], d[1] + image[1], d[2] + image[2]});
    worst = std::max(worst, norm(sub(found, d)));
  }
  EXPECT_LT(worst, 1e-13);
}

TEST(PeriodicBox, FoldingTheTiltsKeepsTheLattice) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> big(-2.5, 2.5);
  for (int trial = 0; trial < 500; ++trial) {
    Mat3 h = random_cell(rng);
    h[1] = big(rng) * h[0], h[2] = big(rng) * h[0], h[5] = big(rng) * h[4];
    const Mat3 f = fold_tilts(h);
    EXPECT_LE(std::abs(f[1]), 0.5 * f[0] * (1 + 1e-12));
    EXPECT_LE(std::abs(f[2]), 0.5 * f[0] * (1 + 1e-12));
    EXPECT_LE(std::abs(f[5]), 0.5 * f[4] * (1 + 1e-12));
    // the same lattice: each basis an integer unimodular combination of the other's
    const Mat3 n = mul3(inverse3(h), f);
    for (double x : n) EXPECT_NEAR(x, std::nearbyint(x), 1e-9);
    EXPECT_NEAR(std::abs(det3(n)), 1, 1e-9);
  }
}

// What the pair does: the separation from 1 to 2 (nearest image) and the
// total relative velocity v2 - v1, and 1's spin.
struct PairMotion {
  Vec3 d, v, w;
};

PairMotion motion_in_cell(Simulation& sim) {
  const ParticleSnapshot q = download(sim.model(), sim.state());
  const CellNow& c = sim.state().cell_now;
  const Vec3 d = min_image(c.h, sub(q.position[1], q.position[0]));
  // u are relative to the flow: the image at d moves at L d relative to the flow at 1
  const Vec3 flow = apply3(c.grad, d);
  const Vec3 v = sub(q.velocity[1], q.velocity[0]);
  return {d, {v[0] + flow[0], v[1] + flow[1], v[2] + flow[2]}, q.angular_velocity[0]};
}

PairMotion motion_in_space(Simulation& sim) {
  const ParticleSnapshot q = download(sim.model(), sim.state());
  return {sub(q.position[1], q.position[0]), sub(q.velocity[1], q.velocity[0]), q.angular_velocity[0]};
}

// Runs a pair in a cube of side `side` sheared at `gamma_dot` (v_x =
// gamma_dot z), particle 2 at x2 (its image at x2 - lattice in open space),
// and the twin in open space; returns the largest difference of the
// separations (relative to the radius) and of the velocities (relative to
// the largest relative speed) over `steps` steps.
std::pair<double, double> twin_difference(Vec3 x1, Vec3 x2, Vec3 lattice, Vec3 u2, double side,
                                          double gamma_dot, int steps, bool* contact,
                                          int* folds = nullptr, double dt_fraction = 0.15) {
  Scene cell = empty_scene(Precision::Double, beads());
  cell.numerics.dt_fraction = dt_fraction;
  cell.particles = {sphere(kR, x1), sphere(kR, x2, u2)};
  cell.periodic = PeriodicBox{{side, 0, 0, 0, side, 0, 0, 0, side}, {0, 0, 0}};
  Simulation a(default_device(), cell);
  a.set_cell_gradient({0, 0, gamma_dot, 0, 0, 0, 0, 0, 0});
  // the twin: 2's image beside 1, both moving with the flow's total velocity
  Scene space = empty_scene(Precision::Double, beads());
  space.numerics.dt_fraction = dt_fraction;
  const Vec3 x2i = sub(x2, lattice);
  space.particles = {sphere(kR, x1, {gamma_dot * x1[2], 0, 0}),
                     sphere(kR, x2i, {u2[0] + gamma_dot * x2i[2], u2[1], u2[2]})};
  Simulation b(default_device(), space);
  double dd = 0, dv = 0, vmax = 1e-30;
  double tilt_before = 0;
  const int every = steps / 600;
  for (int k = 0; k < steps; k += every) {
    a.advance(every);
    b.advance(every);
    const PairMotion pa = motion_in_cell(a), pb = motion_in_space(b);
    if (norm(pb.d) > 0.4 * side) continue;  // the nearest image is another one now
    dd = std::max(dd, norm(sub(pa.d, pb.d)) / kR);
    dv = std::max(dv, norm(sub(pa.v, pb.v)));
    dv = std::max(dv, norm(sub(pa.w, pb.w)) * kR);
    vmax = std::max(vmax, norm(pb.v));
    if (contact) *contact = *contact || norm(pb.d) < 2 * kR;
    const double tilt = a.state().cell_now.h[2];
    if (folds && tilt < tilt_before) ++*folds;
    tilt_before = tilt;
  }
  return {dd, dv / vmax};
}

TEST(PeriodicPair, CollidesAcrossAFaceAsInOpenSpace) {
  const double side = 12 * kR;
  // 2 lies across the x face from 1, closing in and sliding past
  bool contact = false;
  const auto [dd, dv] = twin_difference({0.3 * kR, 6 * kR, 6 * kR}, {side - 2.1 * kR, 6.2 * kR, 6.1 * kR},
                                        {side, 0, 0}, {0.2, 0.01, -0.01}, side, 0, 3000, &contact);
  EXPECT_TRUE(contact);
  testing::report("separation error / R", dd, 0);
  testing::report("velocity error / |v|", dv, 0);
  EXPECT_LT(dd, 1e-11);
  EXPECT_LT(dv, 1e-9);
}

// The cell and open space differ by one thing: the contact sees the image's
// velocity relative to the flow at the present separation, L d_n, where the
// twin's half-step velocities carry L d_(n-1). The difference is of order
// gamma_dot dt and must halve with the time step.
TEST(PeriodicPair, TheShearedImageMovesWithTheCell) {
  const double side = 12 * kR;
  // 2 lies across the z face, at rest in the flow: the shear brings its
  // image against 1 at gamma_dot * 1.95 R; the tilt passes half an edge
  // (a fold) during the run
  const Vec3 x1{6 * kR, 6 * kR, 0.2 * kR}, x2{6.6 * kR, 6.1 * kR, side - 1.75 * kR};
  std::pair<double, double> err[2];
  for (int half = 0; half < 2; ++half) {
    int folds = 0;
    bool contact = false;
    err[half] = twin_difference(x1, x2, {0, 0, side}, {0, 0, 0}, side, 150, 6000 << half,
                                &contact, &folds, 0.15 / (1 << half));
    EXPECT_TRUE(contact);
    EXPECT_GE(folds, 1);
  }
  testing::report("separation error / R", err[0].first, 0);
  testing::report("velocity error / |v|", err[0].second, 0);
  testing::report("separation error ratio, dt / (dt/2)", err[0].first / err[1].first, 2);
  testing::report("velocity error ratio, dt / (dt/2)", err[0].second / err[1].second, 2);
  EXPECT_LT(err[0].first, 4e-5);
  EXPECT_LT(err[0].second, 4e-4);
  EXPECT_NEAR(err[0].first / err[1].first, 2, 0.05);
  EXPECT_NEAR(err[0].second / err[1].second, 2, 0.05);
}

}  // namespace
}  // namespace simsols
