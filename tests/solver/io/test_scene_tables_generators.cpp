// Tests of the scene generators (solver/io/scene_tables_generators.cpp):
// lattices, jitter and random insertion, as a scene file asks for them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "solver/io/scene_toml.h"
#include "tests/solver/io/scene_fixtures.h"

namespace simsols {
namespace {

using namespace simsols::test;

// ---------------------------------------------------------------------------
// Generators.

std::string lattice(const std::string& extra) {
  return std::string(kGlass) + R"(
[[generators]]
type = "lattice"
material = "glass"
radius = 0.001
min = [0, 0, 0]
max = [0.006, 0.006, 0.006]
)" + extra +
         kDuration;
}

double min_distance(const Scene& s) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < s.particles.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      const Vec3 &a = s.particles[i].position, &b = s.particles[j].position;
      d = std::min(d, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  return d;
}

TEST(SceneGenerators, CubicLatticeFillsTheBox) {
  const Scene s = parse_scene(lattice("velocity = [0, 0, -1]\n"), "l.toml");
  ASSERT_EQ(s.particles.size(), 27u);  // centres at 1, 3, 5 mm on each axis
  EXPECT_EQ(s.particles[0].position, (Vec3{0.001, 0.001, 0.001}));
  EXPECT_NEAR(s.particles[26].position[0], 0.005, 1e-15);
  EXPECT_EQ(s.particles[5].velocity, (Vec3{0, 0, -1}));
  EXPECT_NEAR(min_distance(s), 0.002, 1e-12);
}

TEST(SceneGenerators, CountLimitsTheLattice) {
  EXPECT_EQ(parse_scene(lattice("count = 10\n"), "l.toml").particles.size(), 10u);
}

TEST(SceneGenerators, HexagonalLatticeIsCloserPackedThanCubic) {
  const std::string box = R"(
[[generators]]
type = "lattice"
material = "glass"
radius = 0.001
min = [0, 0, 0]
max = [0.02, 0.02, 0.02]
)";
  const Scene cubic = parse_scene(std::string(kGlass) + box + kDuration, "c.toml");
  const Scene hex = parse_scene(
      std::string(kGlass) + box + "arrangement = \"hexagonal\"\n" + kDuration, "h.toml");
  EXPECT_EQ(cubic.particles.size(), 1000u);
  EXPECT_GT(hex.particles.size(), cubic.particles.size() * 11 / 10);  // 1.41 in an infinite box
  EXPECT_NEAR(min_distance(hex), 0.002, 1e-12);
  for (const Particle& p : hex.particles)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(p.position[k], 0.001 - 1e-12);
      EXPECT_LE(p.position[k], 0.019 + 1e-12);
    }
}

TEST(SceneGenerators, JitterIsDeterministicAndBounded) {
  const std::string text = lattice("spacing = 0.0025\njitter = 0.0002\nseed = 7\n");
  const Scene a = parse_scene(text, "j.toml"), b = parse_scene(text, "j.toml");
  expect_same_scene(a, b);
  const Scene other =
      parse_scene(lattice("spacing = 0.0025\njitter = 0.0002\nseed = 8\n"), "j.toml");
  EXPECT_NE(a.particles[0].position, other.particles[0].position);
  EXPECT_GE(min_distance(a), 0.0025 - 2 * std::sqrt(3.0) * 0.0002);
}

TEST(SceneGenerators, RandomInsertionPlacesNonOverlappingSpheres) {
  const Scene s =
      parse_scene(random_generator("radius_min = 0.0005\nradius_max = 0.001", 500, 3), "r.toml");
  ASSERT_EQ(s.particles.size(), 501u);
  for (size_t i = 1; i < s.particles.size(); ++i) {
    const Particle& p = s.particles[i];
    EXPECT_GE(p.radius, 0.0005);
    EXPECT_LE(p.radius, 0.001);
    EXPECT_GE(p.position[0] - p.radius, -0.01);
    EXPECT_LE(p.position[2] + p.radius, 0.02);
  }
  for (size_t i = 0; i < s.particles.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      const Particle &a = s.particles[i], &b = s.particles[j];
      const double d = std::hypot(a.position[0] - b.position[0], a.position[1] - b.position[1],
                                  a.position[2] - b.position[2]);
      ASSERT_GE(d, a.radius + b.radius) << i << " " << j;
    }
}

TEST(SceneGenerators, RandomInsertionIsDeterministic) {
  const std::string text = random_generator("radius = 0.0007", 200, 42);
  expect_same_scene(parse_scene(text, "r.toml"), parse_scene(text, "r.toml"));
  const Scene other = parse_scene(random_generator("radius = 0.0007", 200, 43), "r.toml");
  EXPECT_NE(parse_scene(text, "r.toml").particles[1].position, other.particles[1].position);
}

}  // namespace
}  // namespace simsols
