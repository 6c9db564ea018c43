// A clump's mass properties (solver/scene/clump.h): the union of its
// spheres, integrated, against closed forms. Two equal overlapping spheres
// along x: the union's volume is two spheres less their lens, and every
// section across the axis is a single disk, the larger of the two, so the
// moments are 1D polynomial integrals. Slicing is along z, so the slices
// exercise the union of two crossing disks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/scene/clump.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Clump, DiskUnionsAreExact) {
  const std::vector<Disk> one = {{0.3, -0.2, 1.5}};
  const DiskUnionMoments m = disk_union_moments(one);
  EXPECT_NEAR(m.area, kPi * 2.25, 1e-13);
  EXPECT_NEAR(m.x, 0.3 * kPi * 2.25, 1e-13);
  EXPECT_NEAR(m.xx, kPi * 2.25 * (2.25 / 4 + 0.09), 1e-13);
  // two unit disks at distance d: 2 pi - the lens 2 acos(d/2) - d/2 sqrt(4 - d^2)
  const double d = 1.2;
  const std::vector<Disk> two = {{0, 0, 1}, {d, 0, 1}};
  const double lens = 2 * std::acos(d / 2) - d / 2 * std::sqrt(4 - d * d);
  EXPECT_NEAR(disk_union_moments(two).area, 2 * kPi - lens, 1e-13);
  EXPECT_NEAR(disk_union_moments(two).x / disk_union_moments(two).area, d / 2, 1e-13);
  // a disk inside another, and twins, count once
  const std::vector<Disk> nested = {{0, 0, 2}, {0.5, 0, 1}, {0, 0, 2}};
  EXPECT_NEAR(disk_union_moments(nested).area, 4 * kPi, 1e-12);
}

// Union of two unit spheres at +-c on x (c < 1), about its centre, per unit
// density: V, I_xx (axial) and I_yy (transverse), from sections across x.
struct TwoSpheres {
  double volume, axial, transverse;
};
TwoSpheres two_spheres(double c) {
  // section radius^2 at x >= 0 (the nearer sphere is the one at +c):
  // rho^2 = 1 - (x - c)^2, x in [0, c + 1]; by symmetry double the half.
  // Integrals of x^k rho^2 and rho^4 over [0, c + 1] (polynomials).
  auto integrate = [c](auto f) {
    // Gauss-Legendre on a polynomial of degree <= 6: 4 points are exact
    const double n[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                         0.8611363115940526};
    const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                         0.3478548451374538};
    const double half = 0.5 * (c + 1);
    double s = 0;
    for (int k = 0; k < 4; ++k) s += w[k] * half * f(half * (n[k] + 1));
    return 2 * s;
  };
  auto rho2 = [c](double x) { return 1 - (x - c) * (x - c); };
  TwoSpheres t;
  t.volume = integrate([&](double x) { return kPi * rho2(x); });
  t.axial = integrate([&](double x) { return kPi / 2 * rho2(x) * rho2(x); });
  t.transverse = integrate([&](double x) { return kPi / 4 * rho2(x) * rho2(x) + x * x * kPi * rho2(x); });
  return t;
}

TEST(Clump, TwoOverlappingSpheresMatchTheirClosedForm) {
  const double c = 0.4;  // centres 0.8 apart: a deep overlap
  const std::vector<ClumpSphere> s = {{{1 - c, 2, 3}, 1}, {{1 + c, 2, 3}, 1}};
  const MassProperties m = union_mass_properties(s);
  const TwoSpheres want = two_spheres(c);
  // the lens: two caps of height h = 1 - c, pi h^2 (3 - h) / 3 each
  const double h = 1 - c;
  EXPECT_NEAR(want.volume, 2 * 4 * kPi / 3 - 2 * kPi * h * h * (3 - h) / 3, 1e-13);
  const double ev = std::abs(m.volume / want.volume - 1);
  const double ea = std::abs(m.inertia[0][0] / want.axial - 1);
  const double et = std::abs(m.inertia[1][1] / want.transverse - 1);
  std::printf("[measure] two spheres: relative errors volume %.2e, axial %.2e, transverse %.2e\n",
              ev, ea, et);
  EXPECT_LT(ev, 1e-8);
  EXPECT_LT(ea, 1e-8);
  EXPECT_LT(et, 1e-8);
  EXPECT_NEAR(m.inertia[2][2], m.inertia[1][1], 1e-8 * want.transverse);
  EXPECT_NEAR(m.centroid[0], 1, 1e-10);
  EXPECT_NEAR(m.centroid[1], 2, 1e-10);
  EXPECT_NEAR(m.centroid[2], 3, 1e-10);
  EXPECT_NEAR(m.inertia[0][1], 0, 1e-9);
  // the sum of the spheres (no overlap correction) is measurably different
  EXPECT_GT(2 * 4 * kPi / 3 / m.volume - 1, 0.1);
  // principal: the axial moment is the smallest, along x
  EXPECT_NEAR(m.principal[0], want.axial, 1e-8 * want.axial);
  EXPECT_NEAR(std::abs(m.axes[0][0]), 1, 1e-9);
}

TEST(Clump, OneSphereAndTwoApartAreTextbook) {
  const std::vector<ClumpSphere> one = {{{0.1, 0.2, 0.3}, 0.5}};
  const MassProperties a = union_mass_properties(one);
  const double v = 4 * kPi / 3 * 0.125, i = 0.4 * v * 0.25;
  EXPECT_NEAR(a.volume, v, 1e-14);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.principal[k], i, 1e-14);
  // two unit spheres 3 apart on z: parallel axes, 2 (2/5 V) + 2 V 1.5^2
  const std::vector<ClumpSphere> apart = {{{0, 0, 0}, 1}, {{0, 0, 3}, 1}};
  const MassProperties b = union_mass_properties(apart);
  const double v1 = 4 * kPi / 3;
  EXPECT_NEAR(b.volume, 2 * v1, 1e-12);
  EXPECT_NEAR(b.inertia[2][2], 2 * 0.4 * v1, 1e-12);
  EXPECT_NEAR(b.inertia[0][0], 2 * 0.4 * v1 + 2 * v1 * 2.25, 1e-11);
}

// A rotated clump has the same principal moments, and its axes rotate.
TEST(Clump, PrincipalMomentsAreFrameFree) {
  std::vector<ClumpSphere> s = {{{0, 0, 0}, 1}, {{1.2, 0, 0}, 0.8}, {{0.3, 0.9, 0.2}, 0.6}};
  const MassProperties a = union_mass_properties(s);
  const double t = 0.7, co = std::cos(t), si = std::sin(t);
  for (ClumpSphere& p : s) {  // about y
    const Vec3 q = p.centre;
    p.centre = {co * q[0] + si * q[2], q[1], -si * q[0] + co * q[2]};
  }
  const MassProperties b = union_mass_properties(s);
  EXPECT_NEAR(b.volume, a.volume, 1e-8 * a.volume);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(b.principal[k], a.principal[k], 1e-7 * a.principal[2]);
  EXPECT_LT(a.principal[0], a.principal[1]);
  EXPECT_LT(a.principal[1], a.principal[2]);
  const Vec3& e = a.axes[0];
  const Vec3 rotated = {co * e[0] + si * e[2], e[1], -si * e[0] + co * e[2]};
  EXPECT_NEAR(std::abs(dot(rotated, b.axes[0])), 1, 1e-7);
}

}  // namespace
}  // namespace simsols
