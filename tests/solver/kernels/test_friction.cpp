// Test 3: sliding to rolling. A sphere launched without spin on a plane with
// friction mu slides, decelerating at mu g while its spin grows at
// 5 mu g / (2 R); it rolls without slipping from t* = 2 v0 / (7 mu g) on, at
// v* = 5/7 v0. Both within 2%.
#include <cmath>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

class SlidingToRolling : public PrecisionTest {};

TEST_P(SlidingToRolling, ReachesFiveSeventhsAtTheoryTime) {
  const double mu = 0.5, R = 0.05, v0 = 2.0, g = 9.81;
  const Material m = soft(0.5, mu, 0.0);
  Scene s = empty_scene(GetParam(), m);
  s.effects.gravity = {0, 0, -g};
  Particle p = sphere(R, {0, 0, R}, {v0, 0, 0});
  // start at the static overlap so no normal oscillation disturbs the test
  const double k = 4.0 / 3.0 * e_star(m) * std::sqrt(R);
  p.position[2] = R - std::pow(mass(s, p) * g / k, 2.0 / 3.0);
  s.particles = {p};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  Simulation sim(default_device(), s);

  const double t_theory = 2 * v0 / (7 * mu * g);
  double t_roll = -1, v_roll = 0, prev_slip = v0, prev_t = 0;
  while (sim.time() < 2 * t_theory) {
    sim.advance(1);
    const ParticleSnapshot q = sim.snapshot();
    const double slip = q.velocity[0][0] - q.angular_velocity[0][1] * R;
    if (slip <= 1e-3 * v0) {  // interpolate the zero crossing of the slip
      const double f = (prev_slip - 1e-3 * v0) / (prev_slip - slip);
      t_roll = prev_t + f * (sim.time() - prev_t);
      v_roll = q.velocity[0][0];
      break;
    }
    prev_slip = slip;
    prev_t = sim.time();
  }
  ASSERT_GT(t_roll, 0) << "never reached rolling";
  report("time to rolling (s)", t_roll, t_theory);
  report("rolling speed (m/s)", v_roll, 5.0 / 7.0 * v0);
  EXPECT_NEAR(t_roll / t_theory, 1.0, 0.02) << "t* = " << t_roll << " s, theory " << t_theory;
  EXPECT_NEAR(v_roll / (5.0 / 7.0 * v0), 1.0, 0.02) << "v* = " << v_roll;
  // and keeps rolling without slipping
  sim.advance(200);
  const ParticleSnapshot q = sim.snapshot();
  EXPECT_NEAR(q.velocity[0][0], q.angular_velocity[0][1] * R, 1e-3 * v0);
}

SIMSOLS_BOTH_PRECISIONS(SlidingToRolling);

}  // namespace
}  // namespace simsols::testing
