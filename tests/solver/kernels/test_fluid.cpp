// Fluid slot (fluid = "drag", integrate.cl): drag force, buoyancy and drag
// moment on beads in a still or uniformly moving Newtonian fluid.
//   - a glass bead settling from rest in a viscous liquid reaches the
//     terminal velocity of the drag law (Schiller-Naumann with buoyancy),
//     solved here independently by bisection: within 2 %;
//   - in a moving fluid without gravity a bead is carried up to the fluid's
//     velocity;
//   - a spinning bead's spin decays as exp(-k t), k = pi mu d^3 / I.
// Float and double.
#include <cmath>
#include <numbers>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 2e-3;         // bead diameter, m
constexpr double kRhoP = 2500;      // glass, kg/m^3
constexpr double kRhoF = 1260;      // glycerol, kg/m^3
constexpr double kMu = 1.41;        // glycerol at 20 C, Pa s
constexpr double kG = 9.81;

// Schiller-Naumann correction f = C_d Re / 24.
double correction(double re) { return re < 1000 ? 1 + 0.15 * std::pow(re, 0.687) : 0.44 * re / 24; }

// Terminal speed: (rho_p - rho_f) V g = 3 pi mu d v f(Re(v)), by bisection.
double terminal_speed(double d, double rho_p, double rho_f, double mu) {
  const double weight = (rho_p - rho_f) * kPi / 6 * d * d * d * kG;
  double lo = 0, hi = 100;
  for (int k = 0; k < 200; ++k) {
    const double v = 0.5 * (lo + hi);
    const double drag = 3 * kPi * mu * d * v * correction(rho_f * v * d / mu);
    (drag > weight ? hi : lo) = v;
  }
  return 0.5 * (lo + hi);
}

Scene bead_in_fluid(Precision p, double mu, Vec3 gravity, Vec3 u, Vec3 omega) {
  Material m = glass(0.87, 0.3, 0);
  m.density = kRhoP;
  Scene s = empty_scene(p, m);
  s.effects.gravity = gravity;
  s.effects.fluid = FluidModel::Drag;
  s.effects.fluid_params = {kRhoF, mu, u};
  s.particles = {sphere(kD / 2, {0, 0, 0}, {}, omega)};
  s.numerics.dt = std::min(2e-5, kRhoP * kD * kD / (18 * mu) / 400);  // tau / 400
  s.numerics.force_dt = true;
  return s;
}

class FluidDrag : public PrecisionTest {};

TEST_P(FluidDrag, SettlingBeadReachesTheTerminalVelocity) {
  // glycerol (Re ~ 0.01, Stokes) and a 50x thinner liquid (Re ~ 5, where
  // the Schiller-Naumann correction is 30 %)
  for (const double mu : {kMu, kMu / 50}) {
    Simulation sim(default_device(), bead_in_fluid(GetParam(), mu, {0, 0, -kG}, {}, {}));
    ASSERT_TRUE(sim.model().config().fluid);
    const double vt = terminal_speed(kD, kRhoP, kRhoF, mu);
    const double tau = kRhoP * kD * kD / (18 * mu);  // Stokes relaxation time
    const double re = kRhoF * vt * kD / mu;
    sim.advance(static_cast<std::int64_t>(std::ceil(10 * tau / sim.dt())));
    const double v = -sim.snapshot().velocity[0][2];
    report("terminal velocity (m/s), Re = " + std::to_string(re), v, vt);
    EXPECT_NEAR(v / vt, 1.0, 0.02) << "mu = " << mu << " Pa s, Re = " << re;
    // and the law is not plain Stokes once Re is not small
    const double stokes = (kRhoP - kRhoF) * kG * kD * kD / (18 * mu);
    if (re > 1) {
      EXPECT_LT(v / stokes, 0.9) << "Stokes " << stokes << " m/s";
    }
  }
}

TEST_P(FluidDrag, MovingFluidCarriesTheBead) {
  const Vec3 u{0.01, -0.02, 0.005};
  Simulation sim(default_device(), bead_in_fluid(GetParam(), kMu, {0, 0, 0}, u, {}));
  const double tau = kRhoP * kD * kD / (18 * kMu);
  sim.advance(static_cast<std::int64_t>(std::ceil(15 * tau / sim.dt())));
  const Vec3 v = sim.snapshot().velocity[0];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], u[c], 1e-3 * std::fabs(u[1])) << "component " << c;
}

TEST_P(FluidDrag, SpinDecaysAtTheDragMomentRate) {
  const Vec3 w0{0, 0, 100};
  const double mass = kRhoP * kPi / 6 * kD * kD * kD;
  const double k = kPi * (kMu / 10) * kD * kD * kD / (0.1 * mass * kD * kD);  // I = m d^2 / 10
  Scene s = bead_in_fluid(GetParam(), kMu / 10, {0, 0, 0}, {}, w0);
  // the moment is explicit (half-step spin): the decay rate is k (1 + k dt / 2)
  s.numerics.dt = 1e-3 / k;
  Simulation sim(default_device(), s);
  for (const double kt : {0.5, 1.0, 2.0}) {
    sim.advance(static_cast<std::int64_t>(std::llround(kt / k / sim.dt())) - sim.steps());
    const double w = sim.snapshot().angular_velocity[0][2];
    report("spin w/w0 at k t = " + std::to_string(kt), w / w0[2], std::exp(-k * sim.time()));
    EXPECT_NEAR(w / w0[2], std::exp(-k * sim.time()), 0.002 * std::exp(-k * sim.time()));
  }
  EXPECT_EQ(sim.snapshot().velocity[0], (Vec3{0, 0, 0}));  // a spin alone makes no force
}

SIMSOLS_BOTH_PRECISIONS(FluidDrag);

}  // namespace
}  // namespace simsols::testing
