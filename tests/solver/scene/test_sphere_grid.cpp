// The host's sphere grid (solver/scene/sphere_grid.h): over a box it keeps
// dense cell lists, without one it hashes its cells; either way a query
// finds exactly the stored spheres a brute-force search finds, for cells
// one largest diameter wide (any_near) and for cells of the mean diameter
// with the reach a graded sphere needs (any_within).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "solver/scene/sphere_grid.h"

namespace simsols {
namespace {

struct Sphere {
  Vec3 c;
  double r;
};

// Lognormal-like radii from 0.1 to 0.75 mm in a 10 x 10 x 20 mm box.
std::vector<Sphere> graded_cloud(int n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> x(0, 10e-3), z(0, 20e-3);
  std::lognormal_distribution<double> radius(std::log(0.25e-3), 0.3);
  std::vector<Sphere> s;
  for (int i = 0; i < n; ++i) s.push_back({{x(g), x(g), z(g)}, std::clamp(radius(g), 0.1e-3, 0.75e-3)});
  return s;
}

std::set<int> touching(const std::vector<Sphere>& s, const Vec3& c, double r) {
  std::set<int> out;
  for (size_t j = 0; j < s.size(); ++j) {
    const double dx = c[0] - s[j].c[0], dy = c[1] - s[j].c[1], dz = c[2] - s[j].c[2];
    if (dx * dx + dy * dy + dz * dz < (r + s[j].r) * (r + s[j].r)) out.insert(int(j));
  }
  return out;
}

TEST(SphereGrid, DenseAndHashedFindWhatBruteForceFinds) {
  const std::vector<Sphere> s = graded_cloud(3000, 7);
  double r_max = 0, r_mean = 0;
  for (const Sphere& a : s) r_max = std::max(r_max, a.r), r_mean += a.r / s.size();
  SphereGrid dense_wide(2 * r_max, s.size(), {0, 0, 0}, {10e-3, 10e-3, 20e-3});
  SphereGrid dense_fine(2 * r_mean, s.size(), {0, 0, 0}, {10e-3, 10e-3, 20e-3});
  SphereGrid hashed_fine(2 * r_mean, s.size());
  EXPECT_TRUE(dense_wide.dense() && dense_fine.dense());
  EXPECT_FALSE(hashed_fine.dense());
  for (size_t i = 0; i < s.size(); ++i) {
    dense_wide.insert(int(i), s[i].c);
    dense_fine.insert(int(i), s[i].c);
    hashed_fine.insert(int(i), s[i].c);
  }
  std::mt19937 g(11);
  std::uniform_real_distribution<double> x(-1e-3, 11e-3), z(-1e-3, 21e-3);  // some outside the box
  int found = 0;
  for (int q = 0; q < 400; ++q) {
    const Vec3 c{x(g), x(g), z(g)};
    const double r = 0.1e-3 + 0.65e-3 * (q % 7) / 6;
    const std::set<int> want = touching(s, c, r);
    found += int(want.size());
    for (const SphereGrid* grid : {&dense_wide, &dense_fine, &hashed_fine}) {
      std::set<int> got;
      const bool any = grid->any_within(c, r + r_max, [&](int j) {
        const std::set<int> one = touching({s[size_t(j)]}, c, r);
        if (!one.empty()) got.insert(j);
        return false;
      });
      EXPECT_FALSE(any);
      EXPECT_EQ(got, want) << "query " << q;
      const bool hit = grid->any_within(c, r + r_max, [&](int j) { return want.count(j) > 0; });
      EXPECT_EQ(hit, !want.empty());
    }
    std::set<int> near;  // cells one largest diameter wide: the 27 around suffice
    dense_wide.for_each_near(c, [&](int j) {
      if (!touching({s[size_t(j)]}, c, r).empty()) near.insert(j);
    });
    EXPECT_EQ(near, want) << "query " << q;
  }
  EXPECT_GT(found, 100);  // the queries do meet spheres
}

// A box far larger than its spheres need falls back to hashed cells.
TEST(SphereGrid, ASparseBoxIsHashed) {
  SphereGrid g(1e-3, 10, {0, 0, 0}, {1, 1, 1});
  EXPECT_FALSE(g.dense());
  g.insert(0, {0.5, 0.5, 0.5});
  EXPECT_TRUE(g.any_near({0.5004, 0.5, 0.5}, [](int i) { return i == 0; }));
}

}  // namespace
}  // namespace simsols
