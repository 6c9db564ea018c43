// Test 1: Hertz impact against contact mechanics (elastic, frictionless).
// Two glass spheres R = 10 mm closing at 20 m/s (E = 48 GPa, nu = 0.2,
// rho = 2800), and the same sphere hitting a plane wall of the same material.
// Theory (Johnson, Contact Mechanics, sec. 11.4):
//   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5}
//   F_max     = 4/3 E* sqrt(R*) delta_max^{3/2}
//   t_c       = 2 (delta_max / v) sqrt(pi) Gamma(7/5) / Gamma(9/10)  (= 2.943 delta_max/v)
#include <algorithm>
#include <cmath>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

struct Impact {
  double max_overlap = 0, max_force = 0, duration = 0;
};

struct Theory {
  double max_overlap, max_force, duration;
};

Theory hertz_theory(double mstar, double rstar, double estar, double v) {
  const double k = 4.0 / 3.0 * estar * std::sqrt(rstar);
  const double d = std::pow(15.0 * mstar * v * v / (16.0 * estar * std::sqrt(rstar)), 0.4);
  const double c = std::sqrt(std::numbers::pi) * std::tgamma(1.4) / std::tgamma(0.9);
  return {d, k * std::pow(d, 1.5), 2.0 * c * d / v};
}

Material hertz_material() {
  Material m;
  m.name = "glass48";
  m.young_modulus = 48e9;
  m.poisson_ratio = 0.2;
  m.density = 2800;
  m.restitution = 1.0;
  return m;
}

// Steps until the bodies separate; measures overlap (from positions), force
// and contact time. `overlap` maps a snapshot to the current overlap.
template <typename OverlapFn>
Impact measure(Simulation& sim, OverlapFn overlap) {
  Impact r;
  bool touched = false;
  for (int i = 0; i < 200000; ++i) {
    sim.advance(1);
    const ParticleSnapshot s = sim.snapshot();
    const double f = std::sqrt(s.force[0][0] * s.force[0][0] + s.force[0][1] * s.force[0][1] +
                               s.force[0][2] * s.force[0][2]);
    if (s.contacts[0] > 0) {
      touched = true;
      r.duration += sim.dt();
    } else if (touched) {
      break;
    }
    r.max_force = std::max(r.max_force, f);
    r.max_overlap = std::max(r.max_overlap, overlap(s));
  }
  return r;
}

// Measured against theory, each within 2 %.
void expect_hertz(const Impact& r, const Theory& th) {
  report("max overlap (m)", r.max_overlap, th.max_overlap);
  report("max force (N)", r.max_force, th.max_force);
  report("contact duration (s)", r.duration, th.duration);
  // tolerances about ten times the errors achieved: peak overlap and force
  // within 5e-6 of Hertz, the duration 0.06 % short (it is counted in whole
  // steps)
  EXPECT_NEAR(r.max_overlap / th.max_overlap, 1.0, 1e-4) << r.max_overlap << " vs " << th.max_overlap;
  EXPECT_NEAR(r.max_force / th.max_force, 1.0, 1e-4) << r.max_force << " vs " << th.max_force;
  EXPECT_NEAR(r.duration / th.duration, 1.0, 0.006) << r.duration << " vs " << th.duration;
}

class HertzImpact : public PrecisionTest {};

TEST_P(HertzImpact, SphereSphereMatchesTheory) {
  const Material m = hertz_material();
  Scene s = empty_scene(GetParam(), m);
  const double R = 0.01, v = 20.0;
  s.particles = {sphere(R, {-R - 1e-5, 0, 0}, {v / 2, 0, 0}), sphere(R, {R + 1e-5, 0, 0}, {-v / 2, 0, 0})};
  const double m1 = mass(s, s.particles[0]);
  const Theory th = hertz_theory(m1 / 2, R / 2, e_star(m), v);
  s.numerics.dt = th.duration / 487.3;  // not commensurate with t_c
  Simulation sim(default_device(), s);
  const Impact r = measure(sim, [&](const ParticleSnapshot& p) {
    const double dx = p.position[1][0] - p.position[0][0];
    return 2 * R - std::fabs(dx);
  });
  expect_hertz(r, th);
  // elastic: the pair separates at the closing speed
  const ParticleSnapshot p = sim.snapshot();
  EXPECT_NEAR((p.velocity[1][0] - p.velocity[0][0]) / v, 1.0, 0.01);
}

TEST_P(HertzImpact, SphereWallMatchesTheory) {
  const Material m = hertz_material();
  Scene s = empty_scene(GetParam(), m);
  const double R = 0.01, v = 20.0;
  s.particles = {sphere(R, {0, 0, R + 1e-5}, {0, 0, -v})};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  const Theory th = hertz_theory(mass(s, s.particles[0]), R, e_star(m), v);
  s.numerics.dt = th.duration / 487.3;  // not commensurate with t_c
  Simulation sim(default_device(), s);
  const Impact r = measure(sim, [&](const ParticleSnapshot& p) { return R - p.position[0][2]; });
  expect_hertz(r, th);
  // elastic: the sphere rebounds at its impact speed
  EXPECT_NEAR(sim.snapshot().velocity[0][2] / v, 1.0, 0.01);
}

SIMSOLS_BOTH_PRECISIONS(HertzImpact);

}  // namespace
}  // namespace simsols::testing
