// Rolling slot "spring_dashpot" (Ai et al. 2011, model C; contact_law.cl):
// an elastic-plastic rolling spring with history and a dashpot.
//   - a sphere given a roll on a plane stops, about where the plastic
//     (fully mobilised) torque mu_r F_n stops it: s = 7 R v0^2 / (10 mu_r g)
//     (within 0.5 %: the elastic and damped phases are short);
//   - the rolling torque, recovered every step from the particle's torque
//     less the tangential force's moment, never exceeds mu_r F_n;
//   - it comes to rest (no creep, no chatter) and stays there;
//   - a steady moment below the limit (a slope) holds it at rest, at any
//     time step.
// Float and double.
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/core/observe.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

class RollingSpring : public PrecisionTest {};

TEST_P(RollingSpring, RollingSphereStopsAndTorqueStaysBelowThePlasticLimit) {
  const double R = 0.05, v0 = 0.5, mu_r = 1e-3, g = 9.81;
  const Material m = soft(0.5, 0.5, mu_r);
  Scene s = empty_scene(GetParam(), m);
  s.effects.gravity = {0, 0, -g};
  s.effects.rolling = RollingModel::SpringDashpot;
  Particle p = sphere(R, {0, 0, R}, {v0, 0, 0}, {0, v0 / R, 0});
  const double k = 4.0 / 3.0 * e_star(m) * std::sqrt(R);
  p.position[2] = R - std::pow(mass(s, p) * g / k, 2.0 / 3.0);
  s.particles = {p};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  Simulation sim(default_device(), s);
  ASSERT_TRUE(sim.model().config().rolling_spring);
  EXPECT_EQ(sim.model().config().history_planes(), 2);

  const double a_theory = 5 * mu_r * g / (7 * R);
  const double t_theory = v0 / a_theory;
  double worst = 0, stop_x = -1;
  int checked = 0;
  while (sim.time() < 1.5 * t_theory) {
    sim.advance(1);
    if (sim.steps() % 7 != 0) continue;  // every 7th step (each one read is slow)
    const ParticleSnapshot q = sim.snapshot();
    const std::vector<double> t = read_reals(sim.model(), sim.state().torque, 4);
    const Vec3& f = q.force[0];
    if (f[2] <= 0) continue;
    const double lever = R - 0.5 * (R - q.position[0][2]);
    // T = lever (n x F_t) + M, n = (0, 0, -1): n x F_t = (F_y, -F_x, 0)
    const double mx = t[0] - lever * f[1], my = t[1] + lever * f[0], mz = t[2];
    const double ratio = std::hypot(mx, my, mz) / (mu_r * f[2]);
    worst = std::max(worst, ratio);
    ++checked;
    if (std::fabs(q.velocity[0][0]) < 1e-5 * v0 && stop_x < 0) stop_x = q.position[0][0];
    if (stop_x > 0 && sim.time() > 1.1 * t_theory) break;
  }
  const double s_theory = 7 * R * v0 * v0 / (10 * mu_r * g);
  ASSERT_GT(stop_x, 0) << "did not stop within 1.5 x the plastic-torque time";
  report("stopping distance (m)", stop_x, s_theory);
  report("largest rolling torque / (mu_r F_n)", worst, 1.0);
  EXPECT_NEAR(stop_x / s_theory, 1.0, 0.005);  // achieved -0.045 % (double), -0.039 % (float)
  EXPECT_GT(checked, 1000);
  EXPECT_LE(worst, 1.0 + (GetParam() == Precision::Float ? 1e-4 : 1e-9));
  EXPECT_GT(worst, 0.99) << "the rolling phase must reach the plastic limit";
  // the elastic rolling torque relaxes (a small rock back), then at rest
  sim.advance(20000);
  const double x0 = sim.snapshot().position[0][0];
  sim.advance(20000);
  const ParticleSnapshot q = sim.snapshot();
  EXPECT_LT(std::fabs(q.position[0][0] - x0), 1e-6 * R);
  EXPECT_LT(std::fabs(q.angular_velocity[0][1]), 1e-4 * v0 / R);
}

// A steady moment below the limit: a sphere at rest on a slope of
// tan(theta) = mu_r / (2 R) (gravity tilted over a level floor) carries
// the moment m g sin(theta) R, half the plastic limit mu_r m g cos(theta).
// Model C's elastic torque balances it: the sphere stays where it is, at
// a quarter and at a tenth of the Rayleigh step alike. The constant
// torque law returns at most I* w / dt below its limit, so there a steady
// moment is balanced only by a rolling speed that scales with dt: its
// creep is printed beside (issue of the rolling law's default,
// docs/model.md), not asserted.
TEST_P(RollingSpring, ASteadyMomentBelowTheLimitHoldsWhateverTheTimeStep) {
  const double R = 0.05, mu_r = 1e-3, g = 9.81;
  const double tan_theta = mu_r / (2 * R), theta = std::atan(tan_theta);
  const Material m = soft(0.5, 0.5, mu_r);
  for (const RollingModel model : {RollingModel::SpringDashpot, RollingModel::ConstantTorque}) {
    for (const double dt_fraction : {0.25, 0.1}) {
      Scene s = empty_scene(GetParam(), m);
      s.effects.gravity = {g * std::sin(theta), 0, -g * std::cos(theta)};
      s.effects.rolling = model;
      s.numerics.dt_fraction = dt_fraction;
      Particle p = sphere(R, {0, 0, R}, {0, 0, 0}, {0, 0, 0});
      const double k = 4.0 / 3.0 * e_star(m) * std::sqrt(R);
      p.position[2] = R - std::pow(mass(s, p) * g * std::cos(theta) / k, 2.0 / 3.0);
      s.particles = {p};
      s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
      Simulation sim(default_device(), s);
      // 1.5 s for the start to die out (the rolling spring's swing,
      // damped), then 1 s measured, whatever the step
      sim.advance(static_cast<std::int64_t>(std::ceil(1.5 / sim.dt())));
      const double x0 = sim.snapshot().position[0][0], t0 = sim.time();
      sim.advance(static_cast<std::int64_t>(std::ceil(1.0 / sim.dt())));
      const double creep = (sim.snapshot().position[0][0] - x0) / (sim.time() - t0);  // m/s
      std::printf("[measure] %s, dt %.2f of Rayleigh (%.3g s): creep under half the rolling "
                  "limit %.3g m/s\n",
                  model == RollingModel::SpringDashpot ? "spring_dashpot" : "constant_torque",
                  dt_fraction, sim.dt(), creep);
      // what it moves in the second measured: 1.4e-9 m in double (the
      // start's last swing), 1.7e-8 m in float (rounding), where
      // constant_torque rolls 1.0e-5 m at the smaller step, 2.6e-5 m at
      // the larger
      const double tolerance = (GetParam() == Precision::Float ? 5e-6 : 3e-7) * R;
      if (model == RollingModel::SpringDashpot) {
        EXPECT_LT(std::fabs(creep) * (sim.time() - t0), tolerance) << "dt fraction " << dt_fraction;
      }
    }
  }
}

SIMSOLS_BOTH_PRECISIONS(RollingSpring);

}  // namespace
}  // namespace simsols::testing
