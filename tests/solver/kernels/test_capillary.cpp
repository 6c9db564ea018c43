// Cohesion slot (cohesion = "capillary"): liquid bridges between beads.
//   - force against separation: pairs of beads held at fixed surface
//     separations s (one step from rest) feel the attraction of the
//     Rabinovich et al. (2005) law, evaluated here in its published form
//     (with the immersion height d_sp), to 1e-4 of the contact value in
//     float and 1e-9 in double; an overlapping pair adds Hertz to F(0);
//   - bridges rupture at s_rup = (1 + theta/2) V^(1/3) (Lian et al. 1993):
//     just inside it the force is positive, just outside it is exactly 0;
//   - the wet shear box: a small specimen of 6.35 mm beads sheared dry and
//     wet at three normal stresses; the Mohr-Coulomb fit of the peaks gives
//     an apparent cohesion c > 0 wet and about 0 dry.
#include <cmath>
#include <numbers>

#include "solver/scene/contact_model.h"
#include "solver/apparatus/shear_box/shear_box.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kModelTension = 5.0;  // N/m, see small_wet_box
constexpr double kWetShear = 0.6e-3;   // m of shear per test

// Rabinovich et al. (2005), two equal spheres of radius R, separation D.
double rabinovich(double D, double R, double gamma, double theta, double V) {
  if (D <= 0) return 2 * kPi * R * gamma * std::cos(theta);
  const double dsp = D / 2 * (-1 + std::sqrt(1 + 2 * V / (kPi * R * D * D)));
  return 2 * kPi * R * gamma * std::cos(theta) / (1 + D / (2 * dsp));
}

class Capillary : public PrecisionTest {};

TEST_P(Capillary, ForceFollowsTheLawAndRupturesAtTheRuptureDistance) {
  const double R = 1e-3, V = 1e-12, theta = 0.2, gamma = 0.072;
  const double s_rup = (1 + theta / 2) * std::cbrt(V);
  Scene s = empty_scene(GetParam(), glass(0.87, 0.3, 0));
  s.effects.cohesion = CohesionModel::Capillary;
  s.effects.capillary = {gamma, theta, V};
  // separations: a sweep up to the rupture distance, just inside and just
  // outside it, and one overlapping pair
  std::vector<double> gaps;
  for (int k = 0; k <= 20; ++k) gaps.push_back(s_rup * k / 20.0 * 0.999);
  gaps.push_back(s_rup * (1 - 1e-3));
  gaps.push_back(s_rup * (1 + 1e-3));
  gaps.push_back(s_rup * 1.5);
  gaps.push_back(-1e-4 * R);
  for (size_t k = 0; k < gaps.size(); ++k) {  // pairs 10 mm apart along y
    const double y = 10e-3 * k;
    s.particles.push_back(sphere(R, {0, y, 0}));
    s.particles.push_back(sphere(R, {2 * R + gaps[k], y, 0}));
  }
  Simulation sim(default_device(), s);
  ASSERT_TRUE(sim.model().config().capillary);
  EXPECT_GE(sim.model().skin(), 2 * s_rup);
  sim.advance(1);
  const ParticleSnapshot q = sim.snapshot();
  const double f0 = rabinovich(0, R, gamma, theta, V);
  const double tol = (GetParam() == Precision::Double ? 1e-9 : 1e-4) * f0;
  const double kn = 4.0 / 3.0 * e_star(s.materials[0]) * std::sqrt(R / 2);
  for (size_t k = 0; k < gaps.size(); ++k) {
    const double gap = gaps[k];
    double expected = gap < s_rup ? rabinovich(gap, R, gamma, theta, V) : 0;
    if (gap < 0) expected -= kn * std::pow(-gap, 1.5);  // Hertz pushes i away (-x)
    const Vec3& f = q.force[2 * k];
    SCOPED_TRACE("s / s_rup = " + std::to_string(gap / s_rup));
    // the overlap of 1e-7 m is resolved to ~1e-3 of itself in float (model.md)
    const double rel = gap < 0 && GetParam() == Precision::Float ? 5e-3 : 1e-6;
    EXPECT_NEAR(f[0], expected, tol + rel * std::fabs(expected));
    EXPECT_NEAR(f[1], 0, tol);
    EXPECT_NEAR(q.force[2 * k + 1][0], -f[0], tol);  // action and reaction
    if (k % 5 == 0 && gap >= 0 && gap < s_rup)
      report("capillary force (N) at s/s_rup = " + std::to_string(gap / s_rup), f[0], expected);
  }
  EXPECT_GT(q.force[2 * 21][0], 0) << "just inside the rupture distance";
  EXPECT_EQ(q.force[2 * 22][0], 0) << "just outside the rupture distance";
  EXPECT_EQ(q.force[2 * 23][0], 0);
}

SIMSOLS_BOTH_PRECISIONS(Capillary);

// Per material pair: [[interactions]] overrides volume and angle for its
// pair only; the pair table carries gamma cos(theta), V and s_rup.
TEST(CapillaryPairs, InteractionsOverrideVolumeAndAnglePerPair) {
  Scene s = empty_scene(Precision::Double, glass());
  Material steel = glass();
  steel.name = "steel";
  s.materials.push_back(steel);
  s.effects.cohesion = CohesionModel::Capillary;
  s.effects.capillary = {0.072, 0.1, 1e-12};
  PairOverride o;
  o.material_a = 0;
  o.material_b = 1;
  o.liquid_volume = 8e-12;
  o.contact_angle = 0.6;
  s.pair_overrides = {o};
  const PairTable t = make_pair_table(s);
  EXPECT_DOUBLE_EQ(t.at(0, 0).capillary_tension, 0.072 * std::cos(0.1));
  EXPECT_DOUBLE_EQ(t.at(0, 0).rupture_distance, 1.05 * 1e-4);
  EXPECT_DOUBLE_EQ(t.at(0, 1).capillary_tension, 0.072 * std::cos(0.6));
  EXPECT_DOUBLE_EQ(t.at(1, 0).liquid_volume, 8e-12);
  EXPECT_NEAR(t.at(1, 0).rupture_distance, 1.3 * 2e-4, 1e-18);
  EXPECT_DOUBLE_EQ(t.at(1, 1).liquid_volume, 1e-12);
  EXPECT_NEAR(s.rupture_distance(), 2.6e-4, 1e-18);  // the largest: sets the skin
}

// A small specimen of the paper's 6.35 mm beads (5 x 5 per layer, 4 layers).
// With water (2 pi R gamma = 1.4 mN per bridge) the apparent cohesion would
// be of order 0.1 kPa, below the scatter of a 100-bead specimen at the
// stresses where the servo and the test are validated (>= 20 kPa); the test
// uses a strongly cohesive model liquid, gamma = 5 N/m (0.1 N per bridge,
// about a tenth of sigma d^2 at 20 kPa), to show the mechanism.
// Layered (Table 1 method): this 5 x 5 specimen shears along a nearly flat
// plane (tau/sigma ~ 0.03), so its peaks are deterministic and the small
// cohesion stands out; a poured specimen's peaks scatter by more than the
// cohesion (docs/model.md).
Scene small_wet_box(double sigma, bool wet) {
  const double d = 6.35e-3;
  Scene s = small_shear_box(wet ? "wet_box" : "dry_box", sigma, kWetShear);
  s.apparatus_as<ShearBox>()->rows = 60;
  if (wet) {
    s.effects.cohesion = CohesionModel::Capillary;
    // 1e-3 of a bead's volume per bridge (pendular state)
    s.effects.capillary = {kModelTension, 0, 1e-3 * kPi / 6 * d * d * d};
  }
  validate_scene(s, s.name);
  return s;
}

TEST(WetShearBox, WetSpecimenHasAnApparentCohesion) {
  const std::vector<double> sigmas = {20e3, 40e3, 60e3};
  MohrCoulomb fit[2];
  for (int wet = 0; wet < 2; ++wet) {
    std::vector<double> sig, tau;
    for (const double sigma : sigmas) {
      Simulation sim(default_device(), small_wet_box(sigma, wet));
      ShearProgramme test(sim);
      while (!test.done()) test.advance(1 << 20);
      const ShearSummary& r = test.summary();
      sig.push_back(sigma);
      tau.push_back(r.peak_tau);
      std::printf("[measure] %s sigma %.0f Pa: peak tau %.1f Pa (tau/sigma %.3f at %.2f mm)\n",
                  wet ? "wet" : "dry", sigma, r.peak_tau, r.peak_ratio, r.peak_displacement * 1e3);
    }
    fit[wet] = fit_mohr_coulomb(sig, tau);
    std::printf("[measure] %s envelope: c = %.1f Pa, phi = %.2f deg, r2 = %.4f\n",
                wet ? "wet" : "dry", fit[wet].cohesion, fit[wet].phi_deg, fit[wet].r2);
  }
  EXPECT_GT(fit[1].cohesion, 20);  // Pa
  EXPECT_LT(std::fabs(fit[0].cohesion), 0.25 * fit[1].cohesion);
  EXPECT_NEAR(fit[1].phi_deg, fit[0].phi_deg, 0.5);  // the bridges add a cohesion, not friction
}

}  // namespace
}  // namespace simsols::testing
