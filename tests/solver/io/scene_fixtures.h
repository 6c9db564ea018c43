// Scene fixtures shared by the scene-file tests (test_scene_toml,
// test_scene_tables_generators, and test_stability's refused inputs):
// minimal TOML pieces and a bit-exact comparison of two scenes.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <string>

#include "solver/scene/scene.h"

namespace simsols::test {

inline constexpr const char* kGlass = R"(
[[materials]]
name = "glass"
young_modulus = 6.3e10
poisson_ratio = 0.23
density = 2500
restitution = 0.9
)";

inline constexpr const char* kOneParticle = R"(
[[particles]]
material = "glass"
radius = 0.001
position = [0, 0, 0.005]
)";

inline constexpr const char* kDuration = R"(
[numerics]
duration = 0.01
)";

inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

inline void expect_same(const Vec3& a, const Vec3& b, const std::string& what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_TRUE(same_bits(a[k], b[k])) << what << "[" << k << "]: " << a[k] << " vs " << b[k];
}

inline void expect_same(double a, double b, const std::string& what) {
  EXPECT_TRUE(same_bits(a, b)) << what << ": " << a << " vs " << b;
}

inline void expect_same(const std::optional<double>& a, const std::optional<double>& b,
                 const std::string& what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) expect_same(*a, *b, what);
}

// Bit-exact comparison of everything but source_path / source_text.
inline void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const Material &x = a.materials[i], &y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    expect_same(x.young_modulus, y.young_modulus, "young_modulus");
    expect_same(x.poisson_ratio, y.poisson_ratio, "poisson_ratio");
    expect_same(x.density, y.density, "density");
    expect_same(x.restitution, y.restitution, "restitution");
    expect_same(x.sliding_friction, y.sliding_friction, "sliding_friction");
    expect_same(x.rolling_friction, y.rolling_friction, "rolling_friction");
  }
  ASSERT_EQ(a.pair_overrides.size(), b.pair_overrides.size());
  for (size_t i = 0; i < a.pair_overrides.size(); ++i) {
    const PairOverride &x = a.pair_overrides[i], &y = b.pair_overrides[i];
    EXPECT_EQ(x.material_a, y.material_a);
    EXPECT_EQ(x.material_b, y.material_b);
    expect_same(x.restitution, y.restitution, "pair restitution");
    expect_same(x.sliding_friction, y.sliding_friction, "pair sliding_friction");
    expect_same(x.rolling_friction, y.rolling_friction, "pair rolling_friction");
    expect_same(x.liquid_volume, y.liquid_volume, "pair liquid_volume");
    expect_same(x.contact_angle, y.contact_angle, "pair contact_angle");
  }
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (size_t i = 0; i < a.particles.size(); ++i) {
    const Particle &x = a.particles[i], &y = b.particles[i];
    EXPECT_EQ(x.material, y.material);
    expect_same(x.radius, y.radius, "radius");
    expect_same(x.position, y.position, "position");
    expect_same(x.velocity, y.velocity, "velocity");
    expect_same(x.angular_velocity, y.angular_velocity, "angular_velocity");
  }
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t i = 0; i < a.walls.size(); ++i) {
    const Wall &x = a.walls[i], &y = b.walls[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.shape, y.shape);
    EXPECT_EQ(x.material, y.material);
    expect_same(x.point, y.point, "point");
    expect_same(x.normal, y.normal, "normal");
    expect_same(x.velocity, y.velocity, "wall velocity");
    if (x.shape == WallShape::Rectangle) {
      expect_same(x.axis_u, y.axis_u, "axis_u");
      expect_same(x.half_u, y.half_u, "half_u");
      expect_same(x.half_v, y.half_v, "half_v");
    }
  }
  expect_same(a.effects.gravity, b.effects.gravity, "gravity");
  EXPECT_EQ(a.effects.damping, b.effects.damping);
  EXPECT_EQ(a.effects.tangential, b.effects.tangential);
  EXPECT_EQ(a.effects.rolling, b.effects.rolling);
  expect_same(a.effects.rolling_damping, b.effects.rolling_damping, "rolling_damping");
  EXPECT_EQ(a.effects.cohesion, b.effects.cohesion);
  expect_same(a.effects.capillary.liquid_volume, b.effects.capillary.liquid_volume, "liquid_volume");
  expect_same(a.effects.capillary.contact_angle, b.effects.capillary.contact_angle, "contact_angle");
  expect_same(a.effects.capillary.surface_tension, b.effects.capillary.surface_tension,
              "surface_tension");
  EXPECT_EQ(a.effects.fluid, b.effects.fluid);
  expect_same(a.effects.fluid_params.density, b.effects.fluid_params.density, "fluid density");
  expect_same(a.effects.fluid_params.viscosity, b.effects.fluid_params.viscosity, "viscosity");
  expect_same(a.effects.fluid_params.velocity, b.effects.fluid_params.velocity, "fluid velocity");
  EXPECT_EQ(a.numerics.precision, b.numerics.precision);
  expect_same(a.numerics.dt, b.numerics.dt, "dt");
  expect_same(a.numerics.dt_fraction, b.numerics.dt_fraction, "dt_fraction");
  EXPECT_EQ(a.numerics.force_dt, b.numerics.force_dt);
  expect_same(a.numerics.duration, b.numerics.duration, "duration");
  expect_same(a.numerics.skin, b.numerics.skin, "skin");
  EXPECT_EQ(a.numerics.neighbor_capacity, b.numerics.neighbor_capacity);
  expect_same(a.outputs.series_interval, b.outputs.series_interval, "series_interval");
  expect_same(a.outputs.dump_interval, b.outputs.dump_interval, "dump_interval");
  expect_same(a.outputs.checkpoint_interval, b.outputs.checkpoint_interval, "checkpoint_interval");
  EXPECT_EQ(a.outputs.dump_csv, b.outputs.dump_csv);
  EXPECT_EQ(a.outputs.dump_vtk, b.outputs.dump_vtk);
}

// A scene of one particle and a random generator of `count` spheres of
// `radius` (a TOML line or two) with `seed`.
inline std::string random_generator(const std::string& radius, int count, int seed) {
  return std::string(kGlass) + kOneParticle + R"(
[[generators]]
type = "random"
material = "glass"
)" + radius +
         "\nmin = [-0.01, -0.01, 0]\nmax = [0.01, 0.01, 0.02]\ncount = " + std::to_string(count) +
         "\nseed = " + std::to_string(seed) + "\n" + kDuration;
}

}  // namespace simsols::test
