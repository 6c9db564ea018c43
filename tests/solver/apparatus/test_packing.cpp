// A prepared specimen's packing (solver/apparatus/specimen/packing.h) and the
// preparation keys that make it (scene.h, Preparation): exact solid
// volumes and fabric on lattices, the pour's rain, the settling friction
// switched on the device and back, and bad keys refused by field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solver/apparatus/specimen/packing.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Packing, SphereSegmentsAreExact) {
  const double r = 2e-3, full = 4 * kPi / 3 * r * r * r;
  EXPECT_NEAR(sphere_volume_between(0, r, -1, 1), full, 1e-15 * full);
  EXPECT_NEAR(sphere_volume_between(0, r, 0, 1), full / 2, 1e-15 * full);
  // a cap of height h: pi h^2 (3r - h) / 3
  const double h = 0.5e-3;
  EXPECT_NEAR(sphere_volume_between(0, r, r - h, 1), kPi * h * h * (3 * r - h) / 3, 1e-14 * full);
  EXPECT_EQ(sphere_volume_between(0, r, 3e-3, 4e-3), 0);
}

// A simple cubic lattice of n layers in a box it fills: the slab below the
// top less one diameter holds n - 1 whole layers, solid fraction pi/6; six
// contacts per inner bead along the axes, an isotropic fabric; only the
// vertical contacts, a = 15/2 (every normal along z).
TEST(Packing, ACubicLatticeHasItsTextbookVoidRatioAndFabric) {
  const int n = 4;
  const double d = 1e-3, side = n * d;
  ContactSample s;
  auto at = [&](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        s.beads.position.push_back({(i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d});
        s.beads.radius.push_back(d / 2);
      }
  ContactSample vertical = s;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n) s.contacts.push_back({at(i, j, k), at(i + 1, j, k), {}});
        if (j + 1 < n) s.contacts.push_back({at(i, j, k), at(i, j + 1, k), {}});
        if (k + 1 < n) {
          s.contacts.push_back({at(i, j, k), at(i, j, k + 1), {}});
          vertical.contacts.push_back({at(i, j, k), at(i, j, k + 1), {}});
        }
      }
  const Packing p = measure_packing(s, side, side, 0);
  EXPECT_NEAR(p.slab_height, (n - 1) * d, 1e-15);
  EXPECT_NEAR(p.solid_fraction, kPi / 6, 1e-12);
  EXPECT_NEAR(p.void_ratio, 6 / kPi - 1, 1e-12);
  EXPECT_NEAR(p.bulk_void_ratio, 6 / kPi - 1, 1e-12);  // the lattice fills the box to its top
  EXPECT_NEAR(p.height, n * d, 1e-15);
  EXPECT_EQ(p.grains, n * n * n);
  EXPECT_NEAR(p.grain_coordination, 2.0 * 3 * n * n * (n - 1) / (n * n * n), 1e-12);
  for (double f : p.fabric) EXPECT_NEAR(f, 1.0 / 3, 1e-12);
  EXPECT_NEAR(p.fabric_anisotropy, 0, 1e-12);
  EXPECT_NEAR(measure_packing(vertical, side, side, 0).fabric_anisotropy, 7.5, 1e-12);
  EXPECT_NEAR(fabric_anisotropy(vertical), 7.5, 1e-12);
}

// The same lattice as grains of two beads side by side along x (member
// contacts are never listed): 32 dimers, 64 distinct neighbouring pairs
// though the y and z neighbours touch by two member contacts each, so 4
// grains per grain; the floor's 16 bead contacts are 8 grain contacts.
// The slab leaves out one dimer's length (2 d) below the top.
TEST(Packing, GrainsOfSeveralBeadsCountTheirContactsOnce) {
  const int n = 4;
  const double d = 1e-3, side = n * d;
  ContactSample s;
  GrainMap map;
  auto at = [&](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        s.beads.position.push_back({(i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d});
        s.beads.radius.push_back(d / 2);
        map.share.push_back(1);
        map.grain.push_back(at(i, j, k) / 2);
      }
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n && i % 2 == 1) s.contacts.push_back({at(i, j, k), at(i + 1, j, k), {}});
        if (j + 1 < n) s.contacts.push_back({at(i, j, k), at(i, j + 1, k), {}});
        if (k + 1 < n) s.contacts.push_back({at(i, j, k), at(i, j, k + 1), {}});
        if (k == 0) s.contacts.push_back({at(i, j, k), -1, {}});
      }
  const Packing p = measure_packing(s, side, side, 0, map);
  EXPECT_EQ(p.beads, 64);
  EXPECT_EQ(p.grains, 32);
  EXPECT_NEAR(p.grain_coordination, 4.0, 1e-12);
  EXPECT_NEAR(p.coordination, (2.0 * 64 + 8) / 32, 1e-12);
  EXPECT_NEAR(p.slab_height, 2 * d, 1e-15);
  EXPECT_NEAR(p.void_ratio, 6 / kPi - 1, 1e-12);
  map.share.assign(64, 0.5);  // members overlapping to half their volume
  EXPECT_NEAR(measure_packing(s, side, side, 0, map).bulk_void_ratio, 12 / kPi - 1, 1e-12);
}

std::string poured(const std::string& preparation) {
  return testing::glass_toml("0.3") + R"(
[oedometer]
length = 33.46e-3
width = 33.40e-3
load_steps = [25e3, 50e3]

[oedometer.specimen]
method = "pour"
material = "glass"
diameter = 3e-3
layers = 4
seed = 3

[oedometer.specimen.preparation]
)" + preparation + R"(
[numerics]
duration = 1
)";
}

// The rain: every bead starts at the speed of a free fall from the drop
// height, inside a column whose solid fraction is the intensity.
TEST(Packing, ThePourRainsFromItsDropHeightAtItsIntensity) {
  const Scene s = parse_scene(poured("drop_height = 0.05\nintensity = 0.2\n"), "rain.toml");
  double solid = 0, top = 0;
  for (const Particle& b : s.particles) {
    EXPECT_NEAR(b.velocity[2], -std::sqrt(2 * 9.81 * 0.05), 1e-12);
    EXPECT_EQ(b.velocity[0], 0);
    solid += 4 * kPi / 3 * std::pow(b.radius, 3);
    top = std::max(top, b.position[2] + b.radius);
  }
  const double column = solid / (0.2 * 33.46e-3 * 33.40e-3);
  EXPECT_LE(top, column);
  EXPECT_GT(top, 0.9 * column);  // the column is used up to its top
  // the scene's own gravity, whichever table comes first in the file
  const Scene moon = parse_scene(poured("drop_height = 0.05\n") + "\n[effects]\ngravity = [0, 0, -1.62]\n", "moon.toml");
  EXPECT_NEAR(moon.particles[0].velocity[2], -std::sqrt(2 * 1.62 * 0.05), 1e-12);
  testing::expect_scene_error(poured("drop_height = 0.05\n") + "\n[effects]\ngravity = [0, 0, 0]\n",
                              "conflicting_keys", "oedometer.specimen.preparation.drop_height");
  const Scene plain = parse_scene(poured(""), "plain.toml");
  EXPECT_EQ(plain.particles.size(), s.particles.size());
  for (const Particle& b : plain.particles) EXPECT_EQ(b.velocity[2], 0);
}

// The override reaches the kernels' pair table and leaves it as it was.
TEST(Packing, PreparationFrictionIsSwitchedOnTheDeviceAndBack) {
  const Scene s = parse_scene(poured("friction = 0\n"), "lubricated.toml");
  Simulation a(default_device(), s), b(default_device(), s);
  a.override_friction(Model::FrictionOverride{0.0, std::nullopt, std::nullopt});
  a.override_friction(std::nullopt);  // back to the materials'
  a.advance(20000);
  b.advance(20000);
  EXPECT_EQ(a.hash(), b.hash());
  Simulation c(default_device(), s);
  c.override_friction(Model::FrictionOverride{0.0, 0.0, std::nullopt});
  c.advance(20000);
  EXPECT_NE(c.hash(), b.hash());  // the beads met with other friction
}

// The resolved scene keeps the settling friction and the index void
// ratios (a run resumed from it settles the same way).
TEST(Packing, TheResolvedSceneKeepsThePreparation) {
  const Scene a = parse_scene(poured("friction = 0.125\nrolling_friction = 1e-4\ne_min = 0.6\ne_max = 0.9\n"),
                              "prep.toml");
  const Scene b = parse_scene(to_toml(a), "resolved.toml");
  const Preparation& p = b.apparatus_as<Oedometer>()->specimen.preparation;
  EXPECT_EQ(p.friction, 0.125);
  EXPECT_EQ(p.rolling_friction, 1e-4);
  EXPECT_EQ(p.e_min, 0.6);
  EXPECT_EQ(p.e_max, 0.9);
  EXPECT_EQ(b.particles.size(), a.particles.size());
}

TEST(Packing, BadPreparationsAreRefusedByField) {
  using testing::expect_scene_error;
  const std::string f = "oedometer.specimen.preparation.";
  expect_scene_error(poured("friction = -0.1\n"), "out_of_range", f + "friction");
  expect_scene_error(poured("relative_density = 1.2\n"), "out_of_range", f + "relative_density");
  expect_scene_error(poured("relative_density = 0.5\nfriction = 0.1\n"), "conflicting_keys",
                     f + "relative_density");
  expect_scene_error(poured("e_min = 0.6\n"), "missing_field", f + "e_max");
  expect_scene_error(poured("e_min = 0.6\ne_max = 0.5\n"), "out_of_range", f + "e_max");
  expect_scene_error(poured("intensity = 0.6\n"), "out_of_range", f + "intensity");
  expect_scene_error(poured("drop_height = -1\n"), "out_of_range", f + "drop_height");
  expect_scene_error(poured("density = 0.5\n"), "unknown_key", f + "density");
}

}  // namespace
}  // namespace simsols
