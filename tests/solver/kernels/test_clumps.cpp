// Clumps on the device (kernels/clumps.cl): a free asymmetric body keeps
// its angular momentum and energy and shows the intermediate-axis
// instability (while spin about the major axis is stable), its members
// move rigidly and never touch each other, a clump lying on a plane stays
// there, and a checkpoint resumes it bit for bit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "solver/apparatus/oedometer/oedometer_programme.h"
#include "solver/apparatus/cell/platen_servo.h"
#include "solver/io/checkpoint.h"
#include "solver/io/scene_toml.h"
#include "solver/scene/clump.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

const char* kLump = R"(
[[materials]]
name = "glass"
young_modulus = 62.784e9
poisson_ratio = 0.2
density = 2230
restitution = 0.5
sliding_friction = 0.3
rolling_friction = 0

[[grains]]
name = "lump"
spheres = [[0, 0, 0, 1e-3], [1.3e-3, 0, 0, 0.7e-3], [0.2e-3, 0.9e-3, 0.3e-3, 0.5e-3]]
)";

Grain lump() {
  return {"lump", {{0, 0, 0, 1e-3}, {1.3e-3, 0, 0, 0.7e-3}, {0.2e-3, 0.9e-3, 0.3e-3, 0.5e-3}}, ""};
}

std::string vec(const Vec3& v) {
  char b[120];
  std::snprintf(b, sizeof b, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
  return b;
}

// One free lump spinning at `spin` rad/s about its principal axis `axis`,
// nudged 1 % of that towards the other two; no gravity.
std::string free_lump(int axis, double spin, const std::string& precision) {
  const GrainBody b = grain_body(lump());
  Vec3 w{};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) w[a] += spin * (k == axis ? 1 : 1e-2) * b.mass.axes[k][a];
  return std::string(kLump) + R"(
[[clumps]]
grain = "lump"
material = "glass"
position = [0, 0, 0]
angular_velocity = )" + vec(w) + R"(

[effects]
gravity = [0, 0, 0]

[numerics]
precision = ")" + precision + R"("
duration = 1
)";
}

// The body-frame angular velocity about principal axis k.
double body_spin(const ClumpState& c, const GrainBody& b, double rho, int k) {
  const Vec3 lb = quat_rotate({c.orientation[0], -c.orientation[1], -c.orientation[2],
                               -c.orientation[3]}, c.angular_momentum);
  return lb[k] / (rho * b.mass.principal[k]);
}

TEST(Clumps, AFreeBodyKeepsItsMomentumAndFlipsAboutItsIntermediateAxis) {
  const GrainBody b = grain_body(lump());
  const double spin = 5000;
  for (int axis : {1, 2}) {
    const Scene scene = parse_scene(free_lump(axis, spin, "double"), "lump.toml");
    ASSERT_EQ(scene.particles.size(), 3u);
    Simulation sim(default_device(), scene);
    const ClumpState c0 = sim.clumps().at(0);
    const double l0 = norm(c0.angular_momentum), e0 = c0.kinetic_energy;
    double worst_l = 0, worst_e = 0, lowest = 1e9;
    const int chunks = 300;
    const std::int64_t per = std::llround(0.012 / chunks / sim.dt());
    for (int k = 0; k < chunks; ++k) {
      sim.advance(per);
      const ClumpState c = sim.clumps().at(0);
      worst_l = std::max(worst_l, std::abs(norm(c.angular_momentum) / l0 - 1));
      worst_e = std::max(worst_e, std::abs(c.kinetic_energy / e0 - 1));
      lowest = std::min(lowest, body_spin(c, b, 2230, axis) / spin);
    }
    std::printf("[measure] spin about principal axis %d: |L| within %.2e, energy within %.2e, "
                "lowest spin about it %.3f of the start (%lld steps)\n",
                axis, worst_l, worst_e, lowest, static_cast<long long>(sim.steps()));
    EXPECT_LT(worst_l, 1e-11);
    EXPECT_LT(worst_e, 2e-8);
    if (axis == 1)
      EXPECT_LT(lowest, -0.9);  // the intermediate axis turned over
    else
      EXPECT_GT(lowest, 0.99);  // the major axis holds
    // the members kept their places in the body and met no force
    const ParticleSnapshot p = sim.snapshot();
    const ClumpState c = sim.clumps().at(0);
    for (size_t i = 0; i < 3; ++i) {
      const Vec3 want = quat_rotate(c.orientation, b.offsets[i]);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(p.position[i][a] - c.position[a], want[a], 1e-12);
      EXPECT_EQ(norm(p.force[i]), 0);
    }
  }
}

// A flat grain of three equal spheres lying on a plane under gravity:
// once its elastic bounce has died out it stays, neither sliding nor
// turning.
TEST(Clumps, AClumpAtRestOnAPlaneStaysAtRest) {
  const std::string text = std::string(kLump) + R"(
[[grains]]
name = "tripod"
spheres = [[0, 0, 0, 0.5e-3], [0.8e-3, 0, 0, 0.5e-3], [0.4e-3, 0.69282e-3, 0, 0.5e-3]]

[[clumps]]
grain = "tripod"
material = "glass"
position = [0, 0, 0.5e-3]

[[walls]]
name = "floor"
material = "glass"
point = [0, 0, 0]
normal = [0, 0, 1]

[numerics]
precision = "double"
duration = 1
)";
  const Scene scene = parse_scene(text, "rest.toml");
  Simulation sim(default_device(), scene);
  sim.advance(std::llround(0.005 / sim.dt()));  // settles onto the plane
  const ClumpState a = sim.clumps().at(0);
  sim.advance(std::llround(0.005 / sim.dt()));
  const ClumpState z = sim.clumps().at(0);
  double turned = 0;
  for (int k = 1; k < 4; ++k) turned = std::max(turned, std::abs(z.orientation[k] - a.orientation[k]));
  const double moved = norm({z.position[0] - a.position[0], z.position[1] - a.position[1],
                             z.position[2] - a.position[2]});
  std::printf("[measure] a tripod at rest for 5 ms: moved %.2e m, turned %.2e, speed %.2e m/s, "
              "height %.6e m\n",
              moved, turned, norm(z.velocity), z.position[2]);
  EXPECT_LT(moved, 1e-18);
  EXPECT_LT(turned, 1e-15);
  EXPECT_LT(norm(z.velocity), 1e-11);
  EXPECT_GT(z.position[2], 0.49e-3);  // it lies on the plane, not through it
  EXPECT_LT(z.position[2], 0.5e-3);
}

// An axle rolling down a slope: two wheels (radius R, on the y axis)
// and four smaller spheres off the axis inside the wheels' reach (so only
// the wheels touch the plane). Rolling without slip under gravity,
//   a = g sin(theta) / (1 + I_yy / (M R^2)),
// with M and I_yy those of the union (clump.h), not a sphere's 2/5: here
// I_yy / (M R^2) = 0.392, which gives an acceleration 0.59 % above a
// sphere's; measured within 5e-7 of it. No rolling resistance; friction 0.3 holds the wheels from
// slipping (the least needed is tan(theta) / (1 + M R^2 / I_yy) = 0.10).
TEST(Clumps, AnAxleRollsDownASlopeAsItsInertiaSays) {
  const double R = 1e-3, theta = 20 * 3.14159265358979323846 / 180, g = 9.81;
  const Grain axle = {"axle",
                      {{0, -1.5 * R, 0, R}, {0, 1.5 * R, 0, R}, {0.5 * R, 0, 0, 0.45 * R},
                       {-0.5 * R, 0, 0, 0.45 * R}, {0, 0, 0.5 * R, 0.45 * R}, {0, 0, -0.5 * R, 0.45 * R}},
                      ""};
  std::string rows;
  for (const auto& q : axle.spheres) {
    char row[160];
    std::snprintf(row, sizeof row, "%s[%.17g, %.17g, %.17g, %.17g]", rows.empty() ? "" : ", ", q[0], q[1], q[2],
                  q[3]);
    rows += row;
  }
  const Vec3 n{std::sin(theta), 0, std::cos(theta)};  // the slope's normal; downhill is +x
  const std::string text = std::string(kLump) + "\n[[grains]]\nname = \"axle\"\nspheres = [" + rows + R"(]

[[clumps]]
grain = "axle"
material = "glass"
position = )" + vec(scale(R, n)) + R"(

[[walls]]
name = "slope"
material = "glass"
point = [0, 0, 0]
normal = )" + vec(n) + R"(

[numerics]
precision = "double"
duration = 1
)";
  const Scene scene = parse_scene(text, "slope.toml");
  const GrainBody body = grain_body(scene.grains[1]);
  const double ratio = body.mass.inertia[1][1] / (body.mass.volume * R * R);
  const double want = g * std::sin(theta) / (1 + ratio);
  Simulation sim(default_device(), scene);
  const Vec3 down{std::cos(theta), 0, -std::sin(theta)};
  sim.advance(std::llround(0.002 / sim.dt()));  // the first contact's bounce dies out
  const ClumpState a = sim.clumps().at(0);
  const double t0 = sim.time();
  sim.advance(std::llround(0.005 / sim.dt()));
  const ClumpState b = sim.clumps().at(0);
  const double got = (dot(b.velocity, down) - dot(a.velocity, down)) / (sim.time() - t0);
  const double slip = dot(b.velocity, down) - R * b.angular_velocity[1];  // rolling: v = R omega_y
  std::printf("[measure] axle on a 20 deg slope: I/(M R^2) = %.4f, a = %.6f m/s^2 against %.6f "
              "(%.2e off; a sphere's would be %.6f), slip %.2e m/s\n",
              ratio, got, want, got / want - 1, g * std::sin(theta) / 1.4, slip);
  EXPECT_LT(ratio, 0.395);  // the test tells this body from a sphere
  EXPECT_NEAR(got / want, 1, 5e-6);
  EXPECT_LT(std::abs(slip), 1e-5 * dot(b.velocity, down));  // achieved 1e-6
}

// Two template grains of overlapping spheres (the "sand" form, 8
// spheres) dropped onto each other on a frictionless floor, no friction
// anywhere, restitution 0.5: kinetic plus gravitational energy can only
// fall, though up to 8 x 8 member pairs may touch at once when two such
// grains meet (measured: never above its start; 38 % lost in 30 ms).
TEST(Clumps, TemplateGrainsCollideWithoutGainingEnergy) {
  const std::string text = R"(
[[materials]]
name = "glass"
young_modulus = 62.784e9
poisson_ratio = 0.2
density = 2230
restitution = 0.5

[[grains]]
name = "sand"
shape = "sand"
aspect_ratio = 1.4
angularity = 0.6
diameter = 3e-3
max_spheres = 8

[[clumps]]
grain = "sand"
material = "glass"
position = [0, 0, 2.5e-3]
orientation = [0.9, 0.1, 0.3, 0.2]

[[clumps]]
grain = "sand"
material = "glass"
position = [0.4e-3, 0.3e-3, 6.5e-3]
orientation = [0.2, 0.7, 0.1, 0.4]
velocity = [0, 0, -0.5]

[[walls]]
name = "floor"
material = "glass"
point = [0, 0, 0]
normal = [0, 0, 1]

[numerics]
precision = "double"
duration = 1
)";
  const Scene scene = parse_scene(text, "sand.toml");
  const double mass = 2230 * grain_body(scene.grains[0]).mass.volume;
  Simulation sim(default_device(), scene);
  const auto energy = [&] {  // kinetic + gravitational (J)
    double e = 0;
    for (const ClumpState& c : sim.clumps()) e += c.kinetic_energy + mass * 9.81 * c.position[2];
    return e;
  };
  const double e0 = energy();
  double rise = 0;
  for (int k = 0; k < 60; ++k) {  // 30 ms: the fall, the impacts, the rest
    sim.advance(std::llround(0.0005 / sim.dt()));
    rise = std::max(rise, energy() - e0);
  }
  double ke = 0;
  for (const ClumpState& c : sim.clumps()) ke += c.kinetic_energy;
  std::printf("[measure] two sand grains: dt %.3e s, energy %.3e J at the start, largest rise %.3e J, "
              "lost %.3e J, kinetic at the end %.3e J\n",
              sim.dt(), e0, rise, e0 - energy(), ke);
  EXPECT_LE(rise, 1e-6 * e0);
}

// Restitution of grains against a single sphere's (low restitution, where
// the dashpot matters most). A rod of two overlapping spheres meets the
// floor, or another rod end-on, with one member each: the contact must stop
// the whole grain, so its dashpot sees the grain's mass, and the rod
// rebounds as a sphere of the same radius does (Hertz with this dashpot
// gives a restitution independent of the mass and the speed). With the
// member's share of the mass it would rebound too fast.
std::string rods(bool pair, bool rod) {
  std::string t = R"(
[[materials]]
name = "glass"
young_modulus = 62.784e9
poisson_ratio = 0.2
density = 2230
restitution = 0.1

[[grains]]
name = "rod"
spheres = [[-0.6e-3, 0, 0, 1e-3], [0.6e-3, 0, 0, 1e-3]]

[effects]
gravity = [0, 0, 0]

[numerics]
precision = "double"
duration = 1
)";
  const double reach = rod ? 1.6e-3 : 1e-3;  // centre to the contact end
  const auto body = [&](double x, double v) {
    if (rod)
      return "\n[[clumps]]\ngrain = \"rod\"\nmaterial = \"glass\"\nposition = [" + std::to_string(x) +
             ", 0, 0]\nvelocity = [" + std::to_string(v) + ", 0, 0]\n";
    return "\n[[particles]]\nmaterial = \"glass\"\nradius = 1e-3\nposition = [" + std::to_string(x) +
           ", 0, 0]\nvelocity = [" + std::to_string(v) + ", 0, 0]\n";
  };
  if (pair) return t + body(-reach - 0.1e-3, 0.5) + body(reach + 0.1e-3, -0.5);
  return t + body(reach + 0.1e-3, -0.5) +
         "\n[[walls]]\nname = \"floor\"\nmaterial = \"glass\"\npoint = [0, 0, 0]\nnormal = [1, 0, 0]\n";
}

// The restitution of the collision: the bodies' separation speed after it
// over their approach speed before (1 m/s).
double rebound(bool pair, bool rod) {
  Simulation sim(default_device(), parse_scene(rods(pair, rod), "rods.toml"));
  sim.advance(std::llround(1e-3 / sim.dt()));  // 0.2 ms to meet, ~10 us in contact
  std::vector<double> v;
  if (rod) {
    for (const ClumpState& c : sim.clumps()) v.push_back(c.velocity[0]);
  } else {
    for (const Vec3& u : sim.snapshot().velocity) v.push_back(u[0]);
  }
  return pair ? (v[1] - v[0]) / 1.0 : v[0] / 0.5;
}

TEST(Clumps, AGrainReboundsWithItsMaterialsRestitution) {
  const double wall_sphere = rebound(false, false), wall_rod = rebound(false, true);
  const double pair_sphere = rebound(true, false), pair_rod = rebound(true, true);
  std::printf("[measure] restitution 0.1: sphere on a wall %.6f, rod %.6f; sphere pair %.6f, "
              "rod pair %.6f\n",
              wall_sphere, wall_rod, pair_sphere, pair_rod);
  EXPECT_GT(wall_sphere, 0.05);  // it rebounded
  EXPECT_NEAR(wall_rod, wall_sphere, 2.5e-4);  // achieved 1.4e-5
  EXPECT_NEAR(pair_rod, pair_sphere, 2.5e-4);  // achieved 2.2e-5 (0.06 with the members' masses)
}

TEST(Clumps, ACheckpointResumesAClumpBitForBit) {
  const Scene scene = parse_scene(free_lump(1, 2000, "float"), "lump.toml");
  Simulation a(default_device(), scene);
  a.advance(500);
  // one file per process: ctest runs the GPU form beside this one
  const std::string path =
      (std::filesystem::temp_directory_path() / ("simsols_clump_" + std::to_string(::getpid()) + ".bin"))
          .string();
  save_checkpoint(a, path);
  a.advance(500);
  std::unique_ptr<Simulation> b = load_checkpoint(default_device(), path);
  b->advance(500);
  EXPECT_EQ(a.hash(), b->hash());
  EXPECT_EQ(a.clumps().at(0).orientation, b->clumps().at(0).orientation);
  std::filesystem::remove(path);
}

TEST(Clumps, TheResolvedSceneRebuildsTheSameClumps) {
  const Scene a = parse_scene(free_lump(1, 2000, "double"), "lump.toml");
  const Scene b = parse_scene(to_toml(a), "resolved.toml");
  ASSERT_EQ(b.particles.size(), a.particles.size());
  ASSERT_EQ(b.clumps.size(), 1u);
  for (size_t i = 0; i < a.particles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(b.particles[i].position[k], a.particles[i].position[k]);
      EXPECT_EQ(b.particles[i].velocity[k], a.particles[i].velocity[k]);
    }
  testing::expect_scene_error(std::string(kLump) + "[[clumps]]\ngrain = \"rock\"\nmaterial = \"glass\"\nposition = [0, 0, 0]\n",
                              "unknown_grain", "clumps[0].grain");
}

// A pour of clumps into the oedometer: as many grains as hold the solid
// volume asked, placed apart and turned at random; in float they settle
// and take their load steps without a runaway, and the test's solid
// volume counts each union once. Large, soft grains keep it short.
TEST(Clumps, APourOfClumpsSettlesAndTakesItsLoad) {
  const Grain big = {"big", {{0, 0, 0, 3e-3}, {3.9e-3, 0, 0, 2.1e-3}, {0.6e-3, 2.7e-3, 0.9e-3, 1.5e-3}}, ""};
  const std::string text = R"(
[[materials]]
name = "soft"
young_modulus = 1e9
poisson_ratio = 0.2
density = 2230
restitution = 0.5
sliding_friction = 0.3
rolling_friction = 0

[[grains]]
name = "big"
spheres = [[0, 0, 0, 3e-3], [3.9e-3, 0, 0, 2.1e-3], [0.6e-3, 2.7e-3, 0.9e-3, 1.5e-3]]

[oedometer]
length = 30e-3
width = 30e-3
load_steps = [25e3, 50e3]
settle_time = 0.3
step_time = 0.02

[oedometer.specimen]
method = "pour"
material = "soft"
grain = "big"
layers = 3
seed = 3

[numerics]
precision = "float"
duration = 1
)";
  const Scene scene = parse_scene(text, "lumps.toml");
  const GrainBody b = grain_body(big);
  const double d_eq = std::cbrt(6 / 3.14159265358979323846 * b.mass.volume);
  ASSERT_FALSE(scene.clumps.empty());
  EXPECT_EQ(scene.particles.size(), 3 * scene.clumps.size());
  const int per_layer = static_cast<int>(std::floor(30e-3 / (d_eq * (1 + 1e-6))));
  EXPECT_EQ(static_cast<int>(scene.clumps.size()), per_layer * per_layer * 3);
  const SpecimenStats stats = specimen_stats(scene, 0);
  EXPECT_NEAR(stats.volume, scene.clumps.size() * b.mass.volume, 1e-12 * stats.volume);
  Simulation sim(default_device(), scene);
  OedometerProgramme test(sim);
  while (!test.done()) test.advance(1 << 16);  // throws RunawayError on a NaN
  const std::vector<OedometerRow>& rows = test.rows();
  ASSERT_FALSE(rows.empty());
  std::printf("[measure] %zu grains (d_eq %.3f mm) poured, settled and loaded in %lld steps (float): "
              "e = %.3f at %.0f kPa\n",
              scene.clumps.size(), d_eq * 1e3, static_cast<long long>(sim.steps()),
              rows.back().void_ratio, rows.back().sigma_top * 1e-3);
  EXPECT_GT(rows.back().void_ratio, 0.2);
  EXPECT_LT(rows.back().void_ratio, 1.5);
}

// A graded pour of grains: each grain scaled to a size drawn from the
// curve (its volume-equivalent diameter), the solid volume the asked one
// to within one grain, no two bounding spheres overlapping, and the
// resolved scene keeps the scales.
TEST(Clumps, AGradedPourScalesEachGrainToItsDrawnSize) {
  const std::string text = std::string(kLump) + R"(
[triaxial]
length = 30e-3
width = 30e-3

[triaxial.specimen]
method = "pour"
material = "glass"
grain = "lump"
diameter = 2.5e-3
layers = 3
seed = 5

[triaxial.specimen.grading]
law = "lognormal"
sigma = 0.3

[numerics]
duration = 1
)";
  const Scene scene = parse_scene(text, "graded_lumps.toml");
  const GrainBody unit = grain_body(lump());
  const double d_eq = std::cbrt(6 / 3.14159265358979323846 * unit.mass.volume);
  double solid = 0, smallest = 1e9, largest = 0;
  for (const Clump& c : scene.clumps) {
    const double d = d_eq * c.scale;
    solid += unit.mass.volume * std::pow(c.scale, 3);
    smallest = std::min(smallest, d);
    largest = std::max(largest, d);
    for (int k = 0; k < c.count; ++k)
      EXPECT_NEAR(scene.particles[c.first + k].radius, unit.radii[k] * c.scale, 1e-15);
  }
  const int per_layer = static_cast<int>(std::floor(30e-3 / (2.5e-3 * (1 + 1e-6))));
  const double want = per_layer * per_layer * 3 * 3.14159265358979323846 / 6 * std::pow(2.5e-3, 3);
  std::printf("[measure] %zu graded grains of %.2f to %.2f mm (volume-equivalent)\n",
              scene.clumps.size(), smallest * 1e3, largest * 1e3);
  EXPECT_GE(solid, want);
  EXPECT_LT(solid, want + unit.mass.volume * std::pow(largest / d_eq, 3));
  EXPECT_LT(smallest, 0.8 * 2.5e-3);
  EXPECT_GT(largest, 1.25 * 2.5e-3);
  EXPECT_NEAR(specimen_stats(scene, 0).volume, solid, 1e-12 * solid);
  const Scene again = parse_scene(to_toml(scene), "resolved.toml");
  ASSERT_EQ(again.clumps.size(), scene.clumps.size());
  for (size_t i = 0; i < scene.particles.size(); ++i)
    EXPECT_EQ(again.particles[i].radius, scene.particles[i].radius);
}

}  // namespace
}  // namespace simsols
