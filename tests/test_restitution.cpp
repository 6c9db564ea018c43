// Test 2: the simulated coefficient of restitution equals the input
// (0.87 and 0.5) at impact speeds 0.1, 1 and 10 m/s, within 2%, with the
// default time step. Sphere-sphere (paper's glass, d = 2.38125 mm) and
// sphere-wall.
#include <cmath>
#include <tuple>

#include "test_support.h"

namespace simsols::testing {
namespace {

using Param = std::tuple<Precision, double, double>;  // precision, e, speed

class Restitution : public ::testing::TestWithParam<Param> {};

struct RestitutionName {
  std::string operator()(const ::testing::TestParamInfo<Param>& info) const {
    const Precision p = std::get<0>(info.param);
    const double e = std::get<1>(info.param), v = std::get<2>(info.param);
    return std::string(precision_name(p)) + "_e" + std::to_string(int(std::lround(e * 100))) +
           "_v" + std::to_string(int(std::lround(v * 1000))) + "mm_s";
  }
};

// Advances until the bodies have touched and separated again.
void run_impact(Simulation& sim) {
  if (!advance_through_contact(sim, 0, 100000)) FAIL() << "contact never ended";
}

TEST_P(Restitution, SphereSphere) {
  const auto [precision, e, v] = GetParam();
  Scene s = empty_scene(precision, glass(e));
  const double R = 2.38125e-3 / 2;
  const double gap = 1e-6;
  s.particles = {sphere(R, {-R - gap, 0, 0}, {v / 2, 0, 0}), sphere(R, {R + gap, 0, 0}, {-v / 2, 0, 0})};
  Simulation sim(default_device(), s);
  run_impact(sim);
  const ParticleSnapshot p = sim.snapshot();
  const double measured = (p.velocity[1][0] - p.velocity[0][0]) / v;
  report("restitution", measured, e);
  EXPECT_NEAR(measured / e, 1.0, 0.02) << "measured e = " << measured;
  EXPECT_EQ(sim.state().late_builds, 0);
}

TEST_P(Restitution, SphereWall) {
  const auto [precision, e, v] = GetParam();
  Scene s = empty_scene(precision, glass(e));
  const double R = 2.38125e-3 / 2;
  s.particles = {sphere(R, {0, 0, R + 1e-6}, {0, 0, -v})};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  Simulation sim(default_device(), s);
  run_impact(sim);
  const double measured = sim.snapshot().velocity[0][2] / v;
  report("restitution", measured, e);
  EXPECT_NEAR(measured / e, 1.0, 0.02) << "measured e = " << measured;
}

INSTANTIATE_TEST_SUITE_P(, Restitution,
                         ::testing::Combine(::testing::Values(Precision::Float, Precision::Double),
                                            ::testing::Values(0.87, 0.5),
                                            ::testing::Values(0.1, 1.0, 10.0)),
                         RestitutionName());

}  // namespace
}  // namespace simsols::testing
