// Tests of the sphere filler (grain_fill.h) and the shape templates
// (grain_templates.h): the distance transform against Pythagoras, the
// filler against solids whose best spheres are known, the shapes' voxel
// volumes against their closed forms, and the fidelity rising with the
// spheres allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/scene/clump.h"
#include "solver/scene/grain_fill.h"
#include "solver/scene/grain_templates.h"

namespace simsols {
namespace {

// A cube grid of n cells of edge h centred on the origin, inside where
// `inside` says.
template <class F>
VoxelBody grid(int n, double h, F&& inside) {
  VoxelBody b;
  b.nx = b.ny = b.nz = n;
  b.cell = h;
  b.origin = {-0.5 * n * h, -0.5 * n * h, -0.5 * n * h};
  b.inside.resize(static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) b.inside[b.index(i, j, k)] = inside(b.centre(i, j, k));
  return b;
}

double cells(const VoxelBody& b) {
  double n = 0;
  for (auto f : b.inside) n += f;
  return n * b.cell * b.cell * b.cell;
}

TEST(DistanceTransform, IsTheEuclideanDistanceToTheNearestCell) {
  VoxelBody b;
  b.nx = 9, b.ny = 7, b.nz = 5, b.cell = 0.5;
  b.inside.assign(9 * 7 * 5, 0);
  b.inside[b.index(1, 2, 3)] = 1;
  b.inside[b.index(7, 6, 0)] = 1;
  const std::vector<double> d = distance_to(b, true);
  for (int k = 0; k < b.nz; ++k)
    for (int j = 0; j < b.ny; ++j)
      for (int i = 0; i < b.nx; ++i) {
        const double a = std::hypot(i - 1, j - 2, k - 3), c = std::hypot(i - 7, j - 6, k - 0);
        EXPECT_NEAR(d[b.index(i, j, k)], 0.5 * std::min(a, c), 1e-12) << i << " " << j << " " << k;
      }
  b.inside.assign(b.inside.size(), 0);
  EXPECT_TRUE(std::isinf(distance_to(b, true)[0]));
}

TEST(GrainFill, OneSphereFillsABall) {
  // A ball of radius 1 on 0.05 cells: the filler's sphere is the ball less
  // half a cell at most, centred on the cell at the origin.
  const VoxelBody ball = grid(49, 0.05, [](const Vec3& x) { return norm(x) <= 1; });
  FillOptions o;
  o.max_spheres = 1;
  const FillResult f = fill_with_spheres(ball, o);
  ASSERT_EQ(f.spheres.size(), 1u);
  EXPECT_LT(norm(f.spheres[0].centre), 0.5 * 0.05 * std::sqrt(3.0) + 1e-12);
  EXPECT_NEAR(f.spheres[0].radius, 1 - 0.025, 0.05);
  EXPECT_GT(f.coverage, 0.85);  // (0.95)^3 of the cells, less the centre's offset
}

TEST(GrainFill, TwoSpheresRecoverADimer) {
  // The union of two unit balls 1.2 apart: two spheres, one near each centre.
  const VoxelBody dimer = grid(65, 0.05, [](const Vec3& x) {
    return norm(sub(x, {-0.6, 0, 0})) <= 1 || norm(sub(x, {0.6, 0, 0})) <= 1;
  });
  FillOptions o;
  o.max_spheres = 2;
  o.coverage = 1;
  const FillResult f = fill_with_spheres(dimer, o);
  ASSERT_EQ(f.spheres.size(), 2u);
  const double x0 = f.spheres[0].centre[0], x1 = f.spheres[1].centre[0];
  EXPECT_NEAR(std::min(x0, x1), -0.6, 0.06);
  EXPECT_NEAR(std::max(x0, x1), 0.6, 0.06);
  EXPECT_GT(f.coverage, 0.9);
}

TEST(GrainFill, CoverageRisesWithTheSpheresAllowedAndStopsAtTheTarget) {
  GrainShape s;
  s.form = GrainForm::Sand;
  s.aspect_ratio = 1.4;
  s.angularity = 0.6;
  const VoxelBody body = shape_body(s);
  double last = 0;
  for (int n : {2, 4, 8, 16, 32}) {
    FillOptions o;
    o.max_spheres = n;
    o.coverage = 1;
    const FillResult f = fill_with_spheres(body, o);
    EXPECT_EQ(static_cast<int>(f.spheres.size()), n);
    EXPECT_GT(f.coverage, last) << n;
    last = f.coverage;
  }
  EXPECT_GT(last, 0.85);  // 0.885 measured with 32 spheres
  FillOptions o;
  o.max_spheres = 64;
  o.coverage = 0.8;
  const FillResult f = fill_with_spheres(body, o);
  EXPECT_GE(f.coverage, 0.8);
  EXPECT_LT(f.spheres.size(), 32u);
}

TEST(GrainFill, RefusesOptionsOutOfRangeAndAnEmptySolid) {
  const VoxelBody ball = grid(16, 0.1, [](const Vec3& x) { return norm(x) <= 0.5; });
  FillOptions o;
  o.max_spheres = 65;
  EXPECT_THROW(fill_with_spheres(ball, o), std::invalid_argument);
  o = {};
  o.coverage = 0;
  EXPECT_THROW(fill_with_spheres(ball, o), std::invalid_argument);
  o = {};
  o.min_radius_ratio = 1.5;
  EXPECT_THROW(fill_with_spheres(ball, o), std::invalid_argument);
  const VoxelBody empty = grid(8, 0.1, [](const Vec3&) { return false; });
  EXPECT_THROW(fill_with_spheres(empty, {}), std::invalid_argument);
}

// Volume of |x/a|^n + |y/b|^n + |z/c|^n <= 1: 8 a b c G(1+1/n)^3 / G(1+3/n).
double superellipsoid_volume(double a, double b, double c, double n) {
  return 8 * a * b * c * std::pow(std::tgamma(1 + 1 / n), 3) / std::tgamma(1 + 3 / n);
}

TEST(GrainTemplates, SmoothFormsHaveTheirSuperellipsoidVolume) {
  // Voxel volume errors measured at 96 cells: 3e-4 to 4.6e-3 (the boxy
  // forms have faces along the grid, so they alias); allowed 1e-2.
  for (double angularity : {0.0, 0.5, 1.0}) {
    GrainShape s;
    s.resolution = 96;
    s.angularity = angularity;
    s.aspect_ratio = 2;
    const double n = 2 + 8 * angularity;
    s.form = GrainForm::Elongated;
    EXPECT_NEAR(cells(shape_body(s)) / superellipsoid_volume(1, 0.5, 0.5, n), 1, 1e-2) << angularity;
    s.form = GrainForm::Flat;
    EXPECT_NEAR(cells(shape_body(s)) / superellipsoid_volume(1, 1, 0.5, n), 1, 1e-2) << angularity;
  }
}

TEST(GrainTemplates, ASharpTetrahedronHasItsVolumeAndRoundingRemovesSome) {
  GrainShape s;
  s.form = GrainForm::Tetrahedral;
  s.resolution = 96;
  s.angularity = 1;  // no rounding: circumradius 1, edge sqrt(8/3), V = edge^3 / (6 sqrt 2)
  const double edge = std::sqrt(8.0 / 3.0), exact = edge * edge * edge / (6 * std::sqrt(2.0));
  const double sharp = cells(shape_body(s));
  EXPECT_NEAR(sharp / exact, 1, 4e-3);  // 4e-4 measured at 96 cells
  s.angularity = 0;
  const double round = cells(shape_body(s));
  EXPECT_LT(round, 0.97 * sharp);
  EXPECT_GT(round, 0.5 * sharp);
}

TEST(GrainTemplates, AGrainHasTheDiameterAskedAndIsRepeatable) {
  GrainShape s;
  s.form = GrainForm::Sand;
  s.seed = 3;
  TemplateFit fit;
  const Grain a = grain_from_solid("a", shape_body(s), {}, 1e-3, &fit);
  const Grain b = grain_from_solid("b", shape_body(s), {}, 1e-3);
  ASSERT_EQ(a.spheres, b.spheres);
  GrainBody body = grain_body(a);
  EXPECT_NEAR(volume_equivalent_diameter(body), 1e-3, 1e-12);
  EXPECT_LT(norm(body.mass.centroid), 1e-12);
  EXPECT_EQ(fit.spheres, static_cast<int>(a.spheres.size()));
  EXPECT_NEAR(fit.volume_ratio, fit.coverage, 0.05);  // inscribed spheres: the two agree
  s.seed = 4;
  EXPECT_NE(grain_from_solid("c", shape_body(s), {}, 1e-3).spheres, a.spheres);
}

TEST(GrainTemplates, AnElongatedGrainIsLongerThanWideByItsAspectRatio) {
  // Its principal moments order its axes; the extent of the spheres along
  // the longest axis over the shortest is the aspect ratio, to the fill's
  // fidelity (16 spheres: within 15 %).
  for (double ratio : {1.5, 3.0}) {
    GrainShape s;
    s.aspect_ratio = ratio;
    const Grain g = grain_from_solid("rod", shape_body(s), {}, 1e-3);
    double lo[3] = {1, 1, 1}, hi[3] = {-1, -1, -1};
    for (const auto& sp : g.spheres)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], sp[a] - sp[3]), hi[a] = std::max(hi[a], sp[a] + sp[3]);
    EXPECT_NEAR((hi[0] - lo[0]) / (hi[1] - lo[1]), ratio, 0.15 * ratio) << ratio;
    EXPECT_NEAR((hi[1] - lo[1]) / (hi[2] - lo[2]), 1, 0.05) << ratio;
  }
}

TEST(GrainTemplates, RefusesShapesOutOfRange) {
  GrainShape s;
  s.aspect_ratio = 0.5;
  EXPECT_THROW(shape_body(s), std::invalid_argument);
  s = {};
  s.angularity = 2;
  EXPECT_THROW(shape_body(s), std::invalid_argument);
  s = {};
  s.resolution = 8;
  EXPECT_THROW(shape_body(s), std::invalid_argument);
}

}  // namespace
}  // namespace simsols
