// Test 2: the simulated coefficient of restitution equals the input at the
// default time step (0.15 of the Rayleigh step), for the paper's glass
// (d = 2.38125 mm), sphere-sphere and sphere-wall:
//   - head-on impacts, e = 0.01 (the smallest a scene may ask for) ... 1, at
//     0.1, 1 and 10 m/s;
//   - the worst case (e = 0.05 at 10 m/s, the fewest steps per contact) with
//     the contact starting anywhere within a step;
//   - oblique impacts that slide throughout the contact: the normal
//     restitution, and against the rigid-body impulse theory (the normal
//     impulse (1 + e) m* v_n sets the tangential one, mu times it) the
//     rebound spin and tangential velocity.
// Theory: the restitution of the Hertz contact with a d^{1/4} dashpot
// depends on gamma alone (docs/model.md); impulse theory of frictional
// impacts: Brach, "Mechanical Impact Dynamics" (1991), ch. 3.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "solver/common/number_text.h"
#include "solver/scene/contact_model.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

constexpr double kR = 2.38125e-3 / 2;
constexpr double kSpeeds[] = {0.1, 1.0, 10.0};

// |measured / e - 1| allowed at the default step: about ten times the
// largest error measured there (docs/validation.md: 0.27 % at e = 0.01,
// 0.11 % at 0.3, 0.03 % at 0.5 and 0.87, 0.014 % at 1), never more than the
// 1 % promised.
double tolerance(double e) { return e < 0.4 ? 0.01 : e < 0.99 ? 0.004 : 0.002; }

// Advances until the bodies have touched and separated again.
void run_impact(Simulation& sim) {
  if (!advance_through_contact(sim, 0, 200000)) FAIL() << "contact never ended";
}

// Two beads closing head-on at v; the surfaces `gap` apart. Returns the
// measured restitution (separation speed / approach speed). The default
// step unless told.
double pair_restitution(Precision p, double e, double v, double gap,
                        double dt_fraction = Numerics{}.dt_fraction) {
  Scene s = empty_scene(p, glass(e));
  s.numerics.dt_fraction = dt_fraction;
  s.particles = {sphere(kR, {-kR - gap / 2, 0, 0}, {v / 2, 0, 0}),
                 sphere(kR, {kR + gap / 2, 0, 0}, {-v / 2, 0, 0})};
  Simulation sim(default_device(), s);
  run_impact(sim);
  EXPECT_EQ(sim.state().late_builds, 0);
  const ParticleSnapshot q = sim.snapshot();
  return (q.velocity[1][0] - q.velocity[0][0]) / v;
}

// A bead falling onto a plane at v from `gap` above it (no gravity).
double wall_restitution(Precision p, double e, double v, double gap,
                        double dt_fraction = Numerics{}.dt_fraction) {
  Scene s = empty_scene(p, glass(e));
  s.numerics.dt_fraction = dt_fraction;
  s.particles = {sphere(kR, {0, 0, kR + gap}, {0, 0, -v})};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  Simulation sim(default_device(), s);
  run_impact(sim);
  return sim.snapshot().velocity[0][2] / v;
}

using Param = std::tuple<Precision, double>;  // precision, e

class Restitution : public ::testing::TestWithParam<Param> {};

struct RestitutionName {
  std::string operator()(const ::testing::TestParamInfo<Param>& info) const {
    const double e = std::get<1>(info.param);
    return std::string(precision_name(std::get<0>(info.param))) + "_e" +
           std::to_string(int(std::lround(e * 100)));
  }
};

TEST_P(Restitution, SphereSphere) {
  const auto [precision, e] = GetParam();
  for (double v : kSpeeds) {
    const double measured = pair_restitution(precision, e, v, 2e-6);
    report("restitution at " + shortest_number(v) + " m/s", measured, e);
    EXPECT_NEAR(measured / e, 1.0, tolerance(e)) << "v = " << v << " m/s, measured e = " << measured;
  }
}

TEST_P(Restitution, SphereWall) {
  const auto [precision, e] = GetParam();
  for (double v : kSpeeds) {
    const double measured = wall_restitution(precision, e, v, 1e-6);
    report("restitution at " + shortest_number(v) + " m/s", measured, e);
    EXPECT_NEAR(measured / e, 1.0, tolerance(e)) << "v = " << v << " m/s, measured e = " << measured;
  }
}

INSTANTIATE_TEST_SUITE_P(, Restitution,
                         ::testing::Combine(::testing::Values(Precision::Float, Precision::Double),
                                            ::testing::Values(0.01, 0.05, 0.1, 0.3, 0.5, 0.87,
                                                              1.0)),
                         RestitutionName());

// The contact starts at any point of a step: 8 starting gaps spread over one
// step's travel. Before the dashpot's impulse was counted from the first
// touch, this alone moved e = 0.05 by up to 12 % at this speed.
class RestitutionPhase : public PrecisionTest {};

TEST_P(RestitutionPhase, AnyStartWithinAStep) {
  const double e = 0.05, v = 10.0;
  Scene probe = empty_scene(GetParam(), glass(e));
  probe.particles = {sphere(kR, {0, 0, 0})};
  const double dt = effective_time_step(probe);
  ASSERT_DOUBLE_EQ(dt, 0.15 * rayleigh_time_step(probe)) << "the default step";
  double lo = 1, hi = -1;
  for (int k = 0; k < 8; ++k) {
    const double travel = (2 + k / 8.0) * v * dt;  // two steps and a fraction of one
    const double pair = pair_restitution(GetParam(), e, v, travel) / e - 1;
    const double wall = wall_restitution(GetParam(), e, v, travel) / e - 1;
    lo = std::min({lo, pair, wall});
    hi = std::max({hi, pair, wall});
    EXPECT_NEAR(pair, 0, tolerance(e)) << "pair, gap " << travel;
    EXPECT_NEAR(wall, 0, tolerance(e)) << "wall, gap " << travel;
  }
  std::printf("[measure] e = 0.05 at 10 m/s, 8 starting phases, pair and wall: error %+.3f%% to %+.3f%%\n",
              100 * lo, 100 * hi);
}

SIMSOLS_BOTH_PRECISIONS(RestitutionPhase);

// Coarser steps than the default (numerics.dt_fraction 0.3 and 0.5, the
// largest allowed without force_dt): the error grows as dt^2 and most at
// 10 m/s with strong damping, where a contact lasts fewest steps
// (docs/validation.md). Bounds: the measured errors, rounded up.
TEST(RestitutionCoarseStep, ErrorGrowsWithTheStep) {
  struct Bound { double fraction, bound; };
  for (const Bound b : {Bound{0.3, 0.02}, Bound{0.5, 0.06}}) {
    double worst = 0;
    for (double e : {0.05, 0.1, 0.3, 0.5, 0.87})
      for (double v : {0.1, 10.0}) {
        const double pair = pair_restitution(Precision::Float, e, v, 2e-6, b.fraction) / e - 1;
        const double wall = wall_restitution(Precision::Float, e, v, 1e-6, b.fraction) / e - 1;
        std::printf("[measure] dt %.2f dt_R, e = %.2f at %4.1f m/s: sphere-sphere %+.3f%%, "
                    "sphere-wall %+.3f%%\n", b.fraction, e, v, 100 * pair, 100 * wall);
        worst = std::max({worst, std::fabs(pair), std::fabs(wall)});
      }
    EXPECT_LT(worst, b.bound) << "dt_fraction " << b.fraction;
  }
}

// Oblique impacts that slide throughout the contact (the tangential speed of
// the contact point stays above 0: v_t > 7/2 mu (1 + e) v_n for a bead on a
// wall, and for two equal beads with the pair's relative v_n and v_t).
// Rigid-body impulse theory, J_n = (1 + e) m* v_n and J_t = mu J_n, gives
//   bead on a wall:  v_t' = v_t - mu (1 + e) v_n,   w' R = 5/2 mu (1 + e) v_n
//   two equal beads: each bead's v_t changes by mu (1 + e) v_n / 2 and its
//                    spin by 5/4 mu (1 + e) v_n / R, the same for both
// (v_n, v_t: the approach velocity, normal and tangential).
struct Oblique {
  double normal, tangential, spin;  // v_n' / v_n; v_t' and w' R over the theory's
};

Oblique wall_oblique(Precision p, double e, double mu, double v, double angle) {
  const double vn = v * std::cos(angle), vt = v * std::sin(angle), jt = mu * (1 + e) * vn;
  EXPECT_GT(vt, 3.5 * jt) << "sliding throughout";
  Scene s = empty_scene(p, glass(e, mu, 0));
  s.particles = {sphere(kR, {0, 0, kR + 1e-6}, {vt, 0, -vn})};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  Simulation sim(default_device(), s);
  run_impact(sim);
  const ParticleSnapshot q = sim.snapshot();
  return {q.velocity[0][2] / vn, q.velocity[0][0] / (vt - jt),
          q.angular_velocity[0][1] * kR / (2.5 * jt)};
}

Oblique pair_oblique(Precision p, double e, double mu, double v, double angle) {
  const double vn = v * std::cos(angle), vt = v * std::sin(angle), jt = mu * (1 + e) * vn;
  EXPECT_GT(vt, 3.5 * jt) << "sliding throughout";
  Scene s = empty_scene(p, glass(e, mu, 0));
  s.particles = {sphere(kR, {-kR - 1e-6, 0, 0}, {vn / 2, vt / 2, 0}),
                 sphere(kR, {kR + 1e-6, 0, 0}, {-vn / 2, -vt / 2, 0})};
  Simulation sim(default_device(), s);
  run_impact(sim);
  const ParticleSnapshot q = sim.snapshot();
  EXPECT_NEAR(q.angular_velocity[1][2] / q.angular_velocity[0][2], 1, 1e-6) << "equal spins";
  return {(q.velocity[1][0] - q.velocity[0][0]) / vn, q.velocity[0][1] / (vt / 2 - jt / 2),
          -q.angular_velocity[0][2] * kR / (1.25 * jt)};
}

void report_oblique(const std::string& what, double e, const Oblique& o) {
  const std::string at = " (" + what + ", e = " + shortest_number(e) + ")";
  report("normal restitution" + at, o.normal, e);
  report("tangential velocity / theory" + at, o.tangential, 1);
  report("spin w R / theory" + at, o.spin, 1);
}

class ObliqueImpact : public PrecisionTest {};

// 70 degrees from the normal at 1 m/s, mu = 0.3, e from 0.1 to 1: while it
// slides the spring carries mu F_n and the dashpot's share is dissipated
// (contact_law.cl), so the tangential impulse is mu J_n at every e. The spin
// follows the lever arm R - d/2 of the law, 4e-4 below R here.
TEST_P(ObliqueImpact, BeadOnAWall) {
  const double angle = 70 * std::numbers::pi / 180;
  for (double e : {0.1, 0.3, 0.5, 0.7, 0.87, 0.98, 1.0}) {
    const Oblique o = wall_oblique(GetParam(), e, 0.3, 1.0, angle);
    report_oblique("wall", e, o);
    EXPECT_NEAR(o.normal / e, 1, tolerance(e)) << "e = " << e;
    EXPECT_NEAR(o.tangential, 1, 1e-3) << "e = " << e;
    EXPECT_NEAR(o.spin, 1, 0.005) << "e = " << e;
  }
}

// 45 degrees at 0.1 m/s, mu = 0.1: the line of centres turns during the
// contact (by v_t t_c / 2R = 3e-4 rad), which the impulse theory ignores;
// that is the 0.1-0.3 % left, even without damping.
TEST_P(ObliqueImpact, TwoBeads) {
  const double angle = 45 * std::numbers::pi / 180;
  for (double e : {0.87, 1.0}) {
    const Oblique o = pair_oblique(GetParam(), e, 0.1, 0.1, angle);
    report_oblique("pair", e, o);
    EXPECT_NEAR(o.normal / e, 1, 0.01) << "e = " << e;
    EXPECT_NEAR(o.tangential, 1, 0.01) << "e = " << e;
    EXPECT_NEAR(o.spin, 1, 0.01) << "e = " << e;
  }
}

SIMSOLS_BOTH_PRECISIONS(ObliqueImpact);

}  // namespace
}  // namespace simsols::testing
