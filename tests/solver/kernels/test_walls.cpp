// Walls and positions: finite rectangles act like planes inside their edges
// and not beyond; walls move with their prescribed velocity; float runs keep
// slow motions far from the origin (compensated positions).
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "solver/io/checkpoint.h"

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

Wall rectangle(Vec3 centre, double half_u, double half_v) {
  Wall w;
  w.name = "plate";
  w.shape = WallShape::Rectangle;
  w.point = centre;
  w.normal = {0, 0, 1};
  w.axis_u = {1, 0, 0};
  w.half_u = half_u;
  w.half_v = half_v;
  return w;
}

// Peak force of a 1 m/s frictionless drop on the given wall.
double peak_force(Precision p, const Wall& wall, double x) {
  Scene s = empty_scene(p, glass(0.87));
  const double R = 1e-3;
  s.particles = {sphere(R, {x, 0, R + 1e-7}, {0, 0, -1})};
  s.walls = {wall};
  Simulation sim(default_device(), s);
  double peak = 0;
  for (int i = 0; i < 2000; ++i) {
    sim.advance(1);
    peak = std::max(peak, std::fabs(sim.snapshot().force[0][2]));
  }
  return peak;
}

class Walls : public PrecisionTest {};

TEST_P(Walls, RectangleActsLikeAPlaneInsideItsEdges) {
  const double flat = peak_force(GetParam(), plane("floor", {0, 0, 0}, {0, 0, 1}), 0);
  const double inside = peak_force(GetParam(), rectangle({0, 0, 0}, 0.01, 0.01), 0.005);
  const double beyond = peak_force(GetParam(), rectangle({0, 0, 0}, 0.01, 0.01), 0.0115);
  std::printf("[measure] %s peak force: plane %.6g N, rectangle %.6g N, past the edge %.3g N\n",
              precision_name(GetParam()), flat, inside, beyond);
  EXPECT_GT(flat, 0);
  EXPECT_NEAR(inside / flat, 1.0, 1e-6);
  EXPECT_EQ(beyond, 0.0) << "a sphere 0.5 mm past the edge must miss the plate";
}

TEST_P(Walls, MovingWallFollowsItsVelocity) {
  // A floor rising at 1 mm/s carries a resting sphere with it.
  Scene s = empty_scene(GetParam(), glass(0.5, 0.3));
  s.effects.gravity = {0, 0, -9.81};
  const double R = 1e-3;
  s.particles = {sphere(R, {0, 0, R}, {0, 0, 0})};
  Wall floor = plane("floor", {0, 0, 0}, {0, 0, 1});
  floor.velocity = {0, 0, 1e-3};
  s.walls = {floor};
  Simulation sim(default_device(), s);
  sim.advance(20000);
  const double t = sim.time();
  const double wall_z = wall_points(sim.model(), sim.state())[0][2];
  const ParticleSnapshot p = sim.snapshot();
  report("wall height (m)", wall_z, 1e-3 * t);
  EXPECT_NEAR(wall_z, 1e-3 * t, 1e-6 * 1e-3 * t);
  EXPECT_NEAR(p.velocity[0][2], 1e-3, 2e-5) << "the sphere rides on the rising floor";
  EXPECT_NEAR(p.position[0][2] - wall_z, R, 1e-3 * R);
}

TEST_P(Walls, SlowMotionFarFromTheOriginIsNotLost) {
  // Two spheres 0.2 m apart, so each sits 0.1 m from the float frame's
  // origin, where a float step is 7.5e-9 m. One drifts at 1 mm/s, i.e.
  // 1e-10 m per step: without compensation it would not move at all.
  Scene s = empty_scene(GetParam(), glass());
  const double R = 1e-3;
  s.particles = {sphere(R, {-0.1, 0, 0}), sphere(R, {0.1, 0, 0}, {1e-3, 0, 0})};
  s.numerics.dt = 1e-7;
  Simulation sim(default_device(), s);
  const double x0 = sim.snapshot().position[1][0];
  sim.advance(10000);
  const double moved = sim.snapshot().position[1][0] - x0;
  report("drift over 1e4 steps of 1e-10 m (m)", moved, 1e-6);
  EXPECT_NEAR(moved, 1e-6, 1e-6 * 1e-4);
}

TEST_P(Walls, ServoPlatenHoldsItsTargetForce) {
  // A platen above a sphere resting on a floor, asked for 1 N: it comes down
  // at its speed cap, then holds 1 N; the floor carries 1 N + the weight.
  const Material m = soft(0.5, 0.3, 0.0);
  Scene s = empty_scene(GetParam(), m);
  s.effects.gravity = {0, 0, -9.81};
  const double R = 5e-3, target = 1.0;
  s.particles = {sphere(R, {0, 0, R})};
  Wall platen = plane("platen", {0, 0, 2 * R + 1e-4}, {0, 0, -1});
  platen.servo.enabled = true;
  platen.servo.target_force = target;
  platen.servo.gain = 0.015;  // m/(s N): ~1 ms response on this contact
  platen.servo.max_speed = 0.05;
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), platen};
  Simulation sim(default_device(), s);
  EXPECT_TRUE(sim.model().config().servo);
  sim.advance(6000);
  double f_min = 1e9, f_max = 0, floor_sum = 0;
  const int samples = 100;
  for (int i = 0; i < samples; ++i) {
    sim.advance(20);
    const std::vector<WallReaction> w = sim.wall_reactions();
    const double f = w[1].force[2];  // the particle pushes the platen up
    f_min = std::min(f_min, f);
    f_max = std::max(f_max, f);
    floor_sum += -w[0].force[2];
  }
  const double weight = mass(s, s.particles[0]) * 9.81;
  report("platen force, min (N)", f_min, target);
  report("platen force, max (N)", f_max, target);
  report("floor force, mean (N)", floor_sum / samples, target + weight);
  EXPECT_NEAR(f_min / target, 1.0, 0.01);
  EXPECT_NEAR(f_max / target, 1.0, 0.01);
  EXPECT_NEAR(floor_sum / samples / (target + weight), 1.0, 0.01);
  EXPECT_LT(wall_points(sim.model(), sim.state())[1][2], 2 * R) << "the platen came down";
}

// A rigid group (walls.cl): a plate resting on a sphere follows a leader
// plate that touches nothing, a dead weight of 1 N along its normal (-z).
// The member's load is the leader's reaction: the sphere carries 1 N and
// both plates move together. With a stop short of the sphere the group
// halts at the stop, untouched.
struct GroupRun {
  double member_force = 0, floor_force = 0, weight = 0, member_travel = 0, leader_travel = 0;
};

GroupRun run_group(Precision p, double stop) {
  Scene s = empty_scene(p, soft(0.5, 0.3, 0.0));
  s.effects.gravity = {0, 0, -9.81};
  const double R = 5e-3;
  s.particles = {sphere(R, {0, 0, R})};
  Wall member = rectangle({0, 0, 2 * R + 2e-4}, 2 * R, 2 * R);
  member.normal = {0, 0, -1};
  Wall leader = rectangle({0.1, 0, 0.05}, 0.01, 0.01);
  leader.normal = {0, 0, -1};
  leader.servo.enabled = true;
  leader.servo.target_force = 1.0;
  leader.servo.mass = 0.01;
  leader.servo.stop = stop;
  member.servo.leader = 2;
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), member, leader};
  Simulation sim(default_device(), s);
  sim.advance(40000);
  GroupRun out;
  const int samples = 200;
  for (int i = 0; i < samples; ++i) {
    sim.advance(20);
    const std::vector<WallReaction> w = sim.wall_reactions();
    out.member_force += w[1].force[2] / samples;
    out.floor_force += -w[0].force[2] / samples;
  }
  const auto at = wall_points(sim.model(), sim.state());
  out.member_travel = at[1][2] - s.walls[1].point[2];
  out.leader_travel = at[2][2] - s.walls[2].point[2];
  out.weight = mass(s, s.particles[0]) * 9.81;
  return out;
}

TEST_P(Walls, RigidGroupCarriesItsLeadersLoad) {
  const GroupRun g = run_group(GetParam(), 0);
  report("member plate force, mean (N)", g.member_force, 1.0);
  report("floor force, mean (N)", g.floor_force, 1.0 + g.weight);
  report("member travel - leader travel (m)", g.member_travel - g.leader_travel, 0);
  EXPECT_NEAR(g.member_force, 1.0, 0.01);
  EXPECT_NEAR(g.floor_force / (1.0 + g.weight), 1.0, 0.01);
  EXPECT_LT(g.member_travel, -2e-4) << "the member came down onto the sphere";
  EXPECT_NEAR(g.member_travel, g.leader_travel, 1e-9);
}

TEST_P(Walls, RigidGroupHaltsAtItsStop) {
  const GroupRun g = run_group(GetParam(), 1e-4);  // half the way to the sphere
  report("leader travel (m)", -g.leader_travel, 1e-4);
  // The stop reads the wall's float position at 0.05 m, where a float's
  // step is 3.7e-9 m (2.4e-9 m seen); double lands on it.
  const double tol = GetParam() == Precision::Float ? 2.5e-8 : 1e-12;
  EXPECT_NEAR(-g.leader_travel, 1e-4, tol);
  EXPECT_NEAR(g.member_travel, g.leader_travel, 1e-9);
  EXPECT_EQ(g.member_force, 0.0) << "stopped short of the sphere";
}

// A cap free to tilt (Wall::tilts): a dead-weight plate of 1 N let down on
// two spheres of different sizes 2a apart on a floor turns until it rests
// on both: its tilt is the slope of the line through their tops, and the
// beads' moment on it vanishes. The same plate held (a PI servo: no dead
// weight, so 1/J = 0) stays level on the larger sphere.
struct CapRun {
  double tilt = 0, slope = 0, moment = 0, rate = 0;
  double overlap[2] = {0, 0};  // each sphere's overlap with the cap on the host's geometry (m)
};

CapRun run_cap(Precision p, double r_left, double r_right, bool dead_weight) {
  Simulation sim(default_device(), tilting_cap_scene(p, r_left, r_right, dead_weight));
  EXPECT_TRUE(sim.model().config().tilt);
  sim.advance(60000);
  CapRun out;
  const int samples = 100;
  for (int i = 0; i < samples; ++i) {
    sim.advance(20);
    out.moment += sim.wall_tilt(1).moment / samples;
  }
  const Simulation::Tilt t = sim.wall_tilt(1);
  out.tilt = t.angle;
  out.rate = t.rate;
  // The plane tangent to both spheres: at tilt t the contact lies r/cos t
  // above a centre, so tan t (x2 - x1) = z2 - z1 + (r2 - r1) / cos t.
  const ParticleSnapshot q = sim.snapshot();
  const double dx = q.position[1][0] - q.position[0][0];
  const double dz = q.position[1][2] - q.position[0][2];
  for (int i = 0; i < 20; ++i)
    out.slope = std::atan((dz + (r_right - r_left) / std::cos(out.slope)) / dx);
  const Wall now = tilted_wall(sim.scene().walls[1], t.angle);
  const Vec3 at = wall_points(sim.model(), sim.state())[1];
  for (int k = 0; k < 2; ++k)
    out.overlap[k] = q.radius[k] - wall_distance(now, at, q.position[k]);
  return out;
}

TEST_P(Walls, DeadWeightCapTiltsToRestOnBothBeads) {
  // av = normal x axis_u = -y: a positive tilt raises the cap towards +x
  const double a = 10e-3;
  for (const auto& [left, right] : {std::pair{5e-3, 4e-3}, std::pair{4e-3, 5e-3}}) {
    const CapRun c = run_cap(GetParam(), left, right, true);
    report("cap tilt (rad)", c.tilt, c.slope);
    report("beads' moment on the cap (N m)", c.moment, 0);
    // measured: 2.7e-4 rad from atan((r2 - r1) / a) (the tangent plane
    // touches the spheres off their tops), 5.7e-6 rad from the tangent
    // plane through the centres as they sit (the overlaps), moment 1.3e-8
    // N m in float (0 in double) against F a = 1e-2 N m
    EXPECT_NEAR(c.tilt, std::atan((right - left) / a), 3e-3) << "near the bare geometry";
    EXPECT_NEAR(c.tilt, c.slope, 6e-5) << "tangent to both spheres";
    EXPECT_LT(std::fabs(c.moment), 1e-7) << "moment balance about the centre";
    // the host's tilted_wall is the kernels' cap: each sphere touches it by
    // its contact's overlap (7.4e-6 m seen), where a cap turned the wrong
    // way or not at all would miss one by ~2 mm
    for (double overlap : c.overlap) {
      EXPECT_GT(overlap, 0.0);
      EXPECT_LT(overlap, 1e-4);
    }
  }
}

TEST_P(Walls, HeldCapStaysLevel) {
  const CapRun c = run_cap(GetParam(), 5e-3, 4e-3, false);
  EXPECT_EQ(c.tilt, 0.0);
  EXPECT_EQ(c.rate, 0.0);
  EXPECT_EQ(c.moment, 0.0) << "a held cap sums no moment";
}

// The tilt is state: a checkpoint taken while the cap turns resumes it bit
// for bit, and the scene it stores keeps the wall's `tilts`.
TEST_P(Walls, TiltingCapResumesFromACheckpoint) {
  Simulation a(default_device(), tilting_cap_scene(GetParam(), 5e-3, 4e-3, true));
  a.advance(4000);
  // one file per precision and process: ctest runs them (and the GPU form) side by side
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("simsols_cap_" + std::string(precision_name(GetParam())) + "_" +
                             std::to_string(::getpid()) + ".bin"))
                               .string();
  save_checkpoint(a, path);
  a.advance(2000);
  std::unique_ptr<Simulation> b = load_checkpoint(default_device(), path);
  b->advance(2000);
  EXPECT_NE(a.wall_tilt(1).rate, 0.0) << "checkpointed while turning";
  EXPECT_EQ(a.hash(), b->hash());
  EXPECT_EQ(a.wall_tilt(1).angle, b->wall_tilt(1).angle);
  EXPECT_EQ(a.wall_tilt(1).rate, b->wall_tilt(1).rate);
  std::filesystem::remove(path);
}

SIMSOLS_BOTH_PRECISIONS(Walls);

}  // namespace
}  // namespace simsols::testing
