// Test 4: rolling friction. A sphere rolling on a plane under the constant
// rolling torque mu_r F_n decelerates at a = 5 mu_r g / (7 R) and stops after
// s = 7 R v0^2 / (10 mu_r g) (within 5%). A sphere at rest on a plane stays
// at rest: no drift over 1e5 steps.
#include <cmath>
#include <cstdio>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

Scene sphere_on_floor(Precision precision, const Material& m, double R, double v0) {
  const double g = 9.81;
  Scene s = empty_scene(precision, m);
  s.effects.gravity = {0, 0, -g};
  Particle p = sphere(R, {0, 0, R}, {v0, 0, 0}, {0, v0 / R, 0});
  const double k = 4.0 / 3.0 * e_star(m) * std::sqrt(R);
  p.position[2] = R - std::pow(mass(s, p) * g / k, 2.0 / 3.0);
  s.particles = {p};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  return s;
}

class RollingFriction : public PrecisionTest {};

TEST_P(RollingFriction, StopsWhereTheoryPredicts) {
  const double R = 0.05, v0 = 0.5, mu_r = 1e-3, g = 9.81;
  Simulation sim(default_device(), sphere_on_floor(GetParam(), soft(0.5, 0.5, mu_r), R, v0));
  const double a = 5 * mu_r * g / (7 * R);
  const double s_theory = v0 * v0 / (2 * a);
  const double t_theory = v0 / a;
  double stop_x = -1;
  while (sim.time() < 1.5 * t_theory) {
    sim.advance(100);
    const ParticleSnapshot q = sim.snapshot();
    if (std::fabs(q.velocity[0][0]) < 1e-5 * v0) {
      stop_x = q.position[0][0];
      break;
    }
  }
  ASSERT_GT(stop_x, 0) << "did not stop within 1.5 x the theoretical time";
  report("stopping distance (m)", stop_x, s_theory);
  report("stopping time (s)", sim.time(), t_theory);
  // tolerances about ten times the errors achieved (distance 0.02 %, time
  // 0.35 %: the stop is seen at the first step with the bead at rest)
  EXPECT_NEAR(stop_x / s_theory, 1.0, 0.005) << "stopped at " << stop_x << " m, theory " << s_theory;
  EXPECT_NEAR(sim.time() / t_theory, 1.0, 0.035);
}

TEST_P(RollingFriction, SphereAtRestStaysAtRest) {
  // Starts with a residual roll of 0.1 mm/s (round-off-sized motion is the
  // hard case for a constant torque: it must stop it, then hold it without
  // chatter around w = 0 or creep).
  const double R = 0.05;
  Simulation sim(default_device(), sphere_on_floor(GetParam(), soft(0.5, 0.5, 1e-3), R, 1e-4));
  sim.advance(2000);  // stops within a few steps; let the normal transient die out
  const ParticleSnapshot a = sim.snapshot();
  sim.advance(100000);
  const ParticleSnapshot b = sim.snapshot();
  const double dx = b.position[0][0] - a.position[0][0];
  const double dy = b.position[0][1] - a.position[0][1];
  std::printf("[measure] resting sphere over 1e5 steps: drift %.3g m, |w| %.3g rad/s\n",
              std::hypot(dx, dy), std::fabs(b.angular_velocity[0][1]));
  EXPECT_LT(std::hypot(dx, dy), 1e-9 * R) << "horizontal drift " << dx << ", " << dy;
  EXPECT_NEAR(b.position[0][2], a.position[0][2], 1e-7 * R);
  for (int c = 0; c < 3; ++c) EXPECT_LT(std::fabs(b.angular_velocity[0][c]), 1e-9);
}

SIMSOLS_BOTH_PRECISIONS(RollingFriction);

}  // namespace
}  // namespace simsols::testing
