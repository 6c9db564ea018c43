// Tests of the TOML scene loader, the writer and
// validate_scene(). Malformed scenes live in assets/tests/bad_scenes/, one
// case per file, each starting with "# expect: <code> [<field>]".
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

#include "solver/common/number_text.h"
#include "solver/scene/contact_model.h"
#include "solver/common/errors.h"
#include "solver/core/cl_program.h"
#include "solver/core/simulation.h"
#include "solver/io/scene_toml.h"
#include "tests/solver/io/scene_fixtures.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
using namespace simsols::test;

fs::path assets_dir() {
  if (const char* env = std::getenv("SIMSOLS_ASSETS"); env && *env) return env;
  return fs::path(SIMSOLS_SOURCE_DIR) / "assets";
}

// Runs `f`, expecting a SceneError; returns it.
template <class F>
SceneError expect_error(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError thrown";
  return SceneError("none", "", 0, "", "");
}

// ---------------------------------------------------------------------------
// Valid scenes.

TEST(SceneToml, MinimalExampleGetsDefaults) {
  const fs::path path = assets_dir() / "scenes" / "example_minimal.toml";
  const Scene s = load_scene(path.string());
  EXPECT_EQ(s.name, "example_minimal");
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.source_path, path.string());
  EXPECT_NE(s.source_text.find("example_minimal"), std::string::npos);

  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "glass");
  EXPECT_EQ(s.materials[0].young_modulus, 6.3e10);
  EXPECT_EQ(s.materials[0].density, 2500.0);
  EXPECT_EQ(s.materials[0].sliding_friction, 0.0);
  EXPECT_EQ(s.materials[0].rolling_friction, 0.0);
  EXPECT_TRUE(s.pair_overrides.empty());

  ASSERT_EQ(s.particles.size(), 2u);
  EXPECT_EQ(s.particles[1].position, (Vec3{0.003, 0, 0.005}));
  EXPECT_EQ(s.particles[1].velocity, (Vec3{0, 0, 0}));
  EXPECT_EQ(s.particles[1].angular_velocity, (Vec3{0, 0, 0}));

  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_EQ(s.walls[0].name, "wall0");
  EXPECT_EQ(s.walls[0].shape, WallShape::Plane);
  EXPECT_EQ(s.walls[0].velocity, (Vec3{0, 0, 0}));

  EXPECT_EQ(s.effects.gravity, (Vec3{0, 0, -9.81}));
  EXPECT_TRUE(s.has_gravity());
  EXPECT_EQ(s.effects.damping, DampingModel::Viscous);
  EXPECT_EQ(s.effects.tangential, TangentialModel::Mindlin);
  EXPECT_EQ(s.effects.rolling, RollingModel::ConstantTorque);
  EXPECT_EQ(s.effects.cohesion, CohesionModel::None);
  EXPECT_EQ(s.effects.fluid, FluidModel::None);

  EXPECT_EQ(s.numerics.precision, Precision::Double);
  EXPECT_EQ(s.numerics.dt, 0.0);
  EXPECT_EQ(s.numerics.dt_fraction, 0.15);
  EXPECT_FALSE(s.numerics.force_dt);
  EXPECT_EQ(s.numerics.duration, 0.01);
  EXPECT_EQ(s.numerics.skin, 0.0);
  EXPECT_EQ(s.numerics.neighbor_capacity, 0);

  EXPECT_EQ(s.outputs.series_interval, 0.0);
  EXPECT_EQ(s.outputs.dump_interval, 0.0);
  EXPECT_EQ(s.outputs.checkpoint_interval, 0.0);
  EXPECT_TRUE(s.outputs.dump_csv && s.outputs.dump_vtk);
}

const char* kFullScene = R"(# Every field set.
[scene]
name = "full"
description = "all \"fields\"\nset"

[[materials]]
name = "glass"
young_modulus = 63000000000        # an integer where a float is expected
poisson_ratio = 0.23
density = 2500.5
restitution = 0.9
sliding_friction = 0.3
rolling_friction = 1e-5

[[materials]]
name = "steel"
young_modulus = 2.1e11
poisson_ratio = 0.3
density = 7800
restitution = 0.8
sliding_friction = 0.2
rolling_friction = 0

[[interactions]]
materials = ["glass", "steel"]
restitution = 0.7
sliding_friction = 0.25

[[particles]]
material = "steel"
radius = 0.002
position = [0.1, 0.2, 0.3]
velocity = [1, -2, 3.5]
angular_velocity = [0, 10, 0]

[[walls]]
name = "floor"
type = "plane"
material = "steel"
point = [0, 0, 0]
normal = [0, 0, 2]                 # normalised on load
velocity = [0, 0, 0.1]

[[walls]]
name = "plate"
type = "rectangle"
material = "glass"
point = [0, 0, 1]
normal = [0, 0, -1]
axis_u = [0, 3, 0]
half_u = 0.5
half_v = 0.25

[effects]
gravity = [0, -9.81, 0]
damping = false
tangential_friction = false
rolling_friction = false

[numerics]
precision = "float"
dt = 1e-7
dt_fraction = 0.2
force_dt = false
duration = 2
skin = 0.0001
neighbor_capacity = 64

[output]
series_interval = 0.001
dump_interval = 0.1
checkpoint_interval = 0.5
dump_csv = false
dump_vtk = false
)";

TEST(SceneToml, FullSceneReadsEveryField) {
  const Scene s = parse_scene(kFullScene, "full.toml");
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.description, "all \"fields\"\nset");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].young_modulus, 6.3e10);
  EXPECT_EQ(s.materials[0].density, 2500.5);
  EXPECT_EQ(s.materials[0].sliding_friction, 0.3);
  EXPECT_EQ(s.materials[0].rolling_friction, 1e-5);
  EXPECT_EQ(s.material_index("steel"), 1);
  EXPECT_EQ(s.material_index("wood"), -1);

  ASSERT_EQ(s.pair_overrides.size(), 1u);
  EXPECT_EQ(s.pair_overrides[0].material_a, 0);
  EXPECT_EQ(s.pair_overrides[0].material_b, 1);
  EXPECT_EQ(s.pair_overrides[0].restitution, 0.7);
  EXPECT_EQ(s.pair_overrides[0].sliding_friction, 0.25);
  EXPECT_FALSE(s.pair_overrides[0].rolling_friction.has_value());

  ASSERT_EQ(s.particles.size(), 1u);
  EXPECT_EQ(s.particles[0].material, 1);
  EXPECT_EQ(s.particles[0].radius, 0.002);
  EXPECT_EQ(s.particles[0].velocity, (Vec3{1, -2, 3.5}));
  EXPECT_EQ(s.particles[0].angular_velocity, (Vec3{0, 10, 0}));

  ASSERT_EQ(s.walls.size(), 2u);
  EXPECT_EQ(s.walls[0].name, "floor");
  EXPECT_EQ(s.walls[0].normal, (Vec3{0, 0, 1}));
  EXPECT_EQ(s.walls[0].velocity, (Vec3{0, 0, 0.1}));
  EXPECT_EQ(s.walls[1].shape, WallShape::Rectangle);
  EXPECT_EQ(s.walls[1].material, 0);
  EXPECT_EQ(s.walls[1].axis_u, (Vec3{0, 1, 0}));
  EXPECT_EQ(s.walls[1].half_u, 0.5);
  EXPECT_EQ(s.walls[1].half_v, 0.25);

  EXPECT_EQ(s.effects.gravity, (Vec3{0, -9.81, 0}));
  // the older boolean keys: false means "none"
  EXPECT_EQ(s.effects.damping, DampingModel::None);
  EXPECT_EQ(s.effects.tangential, TangentialModel::None);
  EXPECT_EQ(s.effects.rolling, RollingModel::None);

  EXPECT_EQ(s.numerics.precision, Precision::Float);
  EXPECT_EQ(s.numerics.dt, 1e-7);
  EXPECT_EQ(s.numerics.dt_fraction, 0.2);
  EXPECT_EQ(s.numerics.duration, 2.0);
  EXPECT_EQ(s.numerics.skin, 1e-4);
  EXPECT_EQ(s.numerics.neighbor_capacity, 64);

  EXPECT_EQ(s.outputs.series_interval, 0.001);
  EXPECT_EQ(s.outputs.dump_interval, 0.1);
  EXPECT_EQ(s.outputs.checkpoint_interval, 0.5);
  EXPECT_FALSE(s.outputs.dump_csv || s.outputs.dump_vtk);
}

// The complete example of docs/scene-format.md (its first ```toml block).
TEST(SceneToml, DocumentationExampleIsValid) {
  const fs::path doc = assets_dir().parent_path() / "docs" / "scene-format.md";
  std::ifstream in(doc);
  ASSERT_TRUE(in) << doc;
  std::stringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  const size_t begin = text.find("```toml\n");
  ASSERT_NE(begin, std::string::npos);
  const size_t end = text.find("```", begin + 8);
  const Scene s = parse_scene(text.substr(begin + 8, end - begin - 8), doc.string());
  EXPECT_EQ(s.name, "drop");
  EXPECT_GT(s.particles.size(), 200u);
  EXPECT_EQ(s.walls.size(), 2u);
}

TEST(SceneToml, ZeroGravityMeansNoGravity) {
  const Scene s = parse_scene(
      std::string(kGlass) + kOneParticle + kDuration + "[effects]\ngravity = [0, 0, 0]\n",
      "g.toml");
  EXPECT_FALSE(s.has_gravity());
}

TEST(SceneToml, ForceDtAcceptsLargeStep) {
  const std::string base = std::string(kGlass) + kOneParticle;
  const Scene s =
      parse_scene(base + "[numerics]\nduration = 0.01\ndt = 1e-3\nforce_dt = true\n", "f.toml");
  EXPECT_EQ(s.numerics.dt, 1e-3);
  EXPECT_GT(s.numerics.dt, kMaxDtFraction * rayleigh_time_step(s));
  const SceneError e = expect_error(
      [&] { parse_scene(base + "[numerics]\nduration = 0.01\ndt = 1e-3\n", "f.toml"); });
  EXPECT_EQ(e.code, "dt_above_limit");
  EXPECT_NE(
      std::string(e.what()).find(shortest_number(kMaxDtFraction * rayleigh_time_step(s))),
      std::string::npos)
      << e.what();
}

TEST(SceneToml, InlineTablesAreArraysOfTables) {
  // Root keys come before the first [table] header.
  const Scene s = parse_scene(
      std::string(
          "particles = [{material = \"glass\", radius = 0.001, position = [0, 0, 0]},\n"
          "             {material = \"glass\", radius = 0.001, position = [0.01, 0, 0]}]\n") +
          kGlass + kDuration,
      "inline.toml");
  EXPECT_EQ(s.particles.size(), 2u);
}

// ---------------------------------------------------------------------------
// Errors: locations and messages.

TEST(SceneToml, ErrorMessageNamesFileLineFieldAndRange) {
  const std::string text = std::string("# line 1\n") + R"([[materials]]
name = "glass"
young_modulus = 6.3e10
poisson_ratio = 0.7
density = 2500
restitution = 0.9
)" + kOneParticle + kDuration;
  const SceneError e = expect_error([&] { parse_scene(text, "scene.toml"); });
  EXPECT_EQ(e.code, "out_of_range");
  EXPECT_EQ(e.file, "scene.toml");
  EXPECT_EQ(e.line, 5);
  EXPECT_EQ(e.field, "materials[0].poisson_ratio");
  EXPECT_STREQ(
      e.what(),
      "scene.toml:5: field 'materials[0].poisson_ratio': 0.7 is out of range, allowed [0, 0.5)");
}

// e = 0 cannot be simulated (docs/model.md, "Normal force"): the message
// names the file, the line, the field and the allowed range, and says why.
TEST(SceneToml, RestitutionBelowTheMinimumIsRefusedWithTheReason) {
  for (const char* e : {"0", "0.005"}) {
    const std::string text = std::string(R"([[materials]]
name = "glass"
young_modulus = 6.3e10
poisson_ratio = 0.2
density = 2500
restitution = )") + e + "\n" + kOneParticle + kDuration;
    const SceneError err = expect_error([&] { parse_scene(text, "scene.toml"); });
    EXPECT_EQ(err.code, "out_of_range");
    EXPECT_EQ(err.line, 6);
    EXPECT_EQ(err.field, "materials[0].restitution");
    EXPECT_STREQ(err.what(),
                 (std::string("scene.toml:6: field 'materials[0].restitution': ") + e +
                  " is out of range, allowed [0.01, 1] (the Hertz contact with its d^{1/4} "
                  "dashpot always rebounds: e = 0 would need infinite damping, and below 0.01 a "
                  "fast contact lasts too few time steps for e to come out as asked)")
                     .c_str());
  }
  const std::string lowest = std::string(R"([[materials]]
name = "glass"
young_modulus = 6.3e10
poisson_ratio = 0.2
density = 2500
restitution = 0.01
)") + kOneParticle + kDuration;
  EXPECT_EQ(parse_scene(lowest, "scene.toml").materials[0].restitution, 0.01);
}

TEST(SceneToml, UnknownKeySuggestsAndListsAllowedKeys) {
  const std::string text =
      std::string(kGlass) + kOneParticle + "[numerics]\nduration = 1\ndt_fractoin = 0.1\n";
  const SceneError e = expect_error([&] { parse_scene(text, "typo.toml"); });
  EXPECT_EQ(e.code, "unknown_key");
  EXPECT_EQ(e.field, "numerics.dt_fractoin");
  EXPECT_GT(e.line, 0);
  const std::string what = e.what();
  EXPECT_NE(what.find("did you mean 'dt_fraction'"), std::string::npos) << what;
  EXPECT_NE(what.find("neighbor_capacity"), std::string::npos) << what;
}

TEST(SceneToml, SyntaxErrorHasLine) {
  const SceneError e =
      expect_error([] { parse_scene("[numerics]\nduration = 1\nskin = = 2\n", "bad.toml"); });
  EXPECT_EQ(e.code, "syntax");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.field, "");
}

TEST(SceneToml, GeneratedParticleErrorsPointAtTheGenerator) {
  const std::string text = std::string(kGlass) + kOneParticle + R"(
[[generators]]
type = "lattice"
material = "glass"
radius = 0.001
min = [-0.004, -0.004, 0]
max = [0.004, 0.004, 0.008]
)" + kDuration;
  const SceneError e = expect_error([&] { parse_scene(text, "gen.toml"); });
  EXPECT_EQ(e.code, "overlapping_particles");
  EXPECT_EQ(e.field, "generators[0]");
  EXPECT_EQ(e.line, 14);  // the [[generators]] header
  EXPECT_NE(std::string(e.what()).find("generated particle"), std::string::npos) << e.what();
}

TEST(SceneToml, MissingFileIsAnIoError) {
  const SceneError e = expect_error([] { load_scene("/nonexistent/dir/scene.toml"); });
  EXPECT_EQ(e.code, "io");
  EXPECT_EQ(e.file, "/nonexistent/dir/scene.toml");
}

// Reads "# expect: <code> [<field>]" from the first line.
std::pair<std::string, std::string> expectation(const fs::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  std::istringstream words(first);
  std::string hash, tag, code, field;
  words >> hash >> tag >> code >> field;
  EXPECT_EQ(hash + " " + tag, "# expect:") << file;
  return {code, field};
}

TEST(SceneToml, BadScenesFailWithTheExpectedCodeAndField) {
  const fs::path dir = assets_dir() / "tests" / "bad_scenes";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  EXPECT_GE(files.size(), 18u);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const auto [code, field] = expectation(file);
    const SceneError e = expect_error([&] { load_scene(file.string()); });
    EXPECT_EQ(e.code, code) << e.what();
    EXPECT_EQ(e.field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos) << e.what();
  }
}

// Every scene shipped in assets/scenes and its subfolders loads (templates
// filled, specimens placed): a scene edited without its loader, or the
// reverse, fails here. The GPU-sized scenes (*_large) are left to their
// measurement.
TEST(SceneToml, EveryShippedSceneLoads) {
  const fs::path dir = assets_dir() / "scenes";
  int scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    const std::string name = fs::relative(entry.path(), dir).string();
    if (name.find("_large") != std::string::npos) continue;  // GPU-sized: docs/specimens.md measures it
    SCOPED_TRACE(name);
    EXPECT_NO_THROW({
      const auto t0 = std::chrono::steady_clock::now();
      const Scene s = load_scene(entry.path().string());
      EXPECT_FALSE(s.particles.empty());
      std::printf("[measure] %s: %zu spheres, loaded in %.2f s\n", name.c_str(), s.particles.size(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    });
    ++scenes;
  }
  EXPECT_GE(scenes, 16);
}

// Reading only reads: a shipped scene read keeps its generators and its
// apparatus as descriptions (no sphere generated, no apparatus wall), and
// is checked as far as that goes; placed, it is the scene load_scene gives,
// bit for bit, and it compiles the same kernels as when it was only read
// (what `simsols run --explain` prints), and written and read back it is
// unchanged. The GPU-sized scenes are read only.
TEST(SceneToml, ReadingOnlyReadsAndPlacingGivesTheLoadedScene) {
  const auto device = Device::open(EngineOptions{});
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(assets_dir() / "scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const auto t0 = std::chrono::steady_clock::now();
    Scene read = read_scene(entry.path().string());
    const double read_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[measure] %s: read in %.3f s, %zu explicit spheres, %zu generators\n",
                name.c_str(), read_s, read.particles.size(), read.generators.size());
    EXPECT_EQ(read.placed(), read.generators.empty() && !read.has_apparatus());
    if (read.cell() != nullptr) {
      EXPECT_TRUE(read.apparatus_pending);
      for (const Wall& w : read.walls) EXPECT_FALSE(w.servo.enabled) << w.name;
    }
    if (name.find("_large") != std::string::npos) continue;  // placing it is a GPU-sized job
    const std::string read_options = make_kernel_config(read, *device).build_options();
    const size_t explicit_spheres = read.particles.size();
    place_scene(read);
    EXPECT_TRUE(read.placed());
    EXPECT_GE(read.particles.size(), explicit_spheres);
    EXPECT_EQ(make_kernel_config(read, *device).build_options(), read_options);
    EXPECT_EQ(to_toml(read), to_toml(load_scene(entry.path().string())));
    // written and read back, the placed scene is the same to the last bit
    // (poured clumps' orientations included; a grain's origin is a comment,
    // not read back)
    const auto data = [](const std::string& toml) {
      std::istringstream in(toml);
      std::string out;
      for (std::string line; std::getline(in, line);)
        if (line.rfind("# ", 0) != 0) out += line + "\n";
      return out;
    };
    EXPECT_EQ(data(to_toml(parse_scene(to_toml(read), name + " (written)"))), data(to_toml(read)));
    ++scenes;
  }
  EXPECT_GE(scenes, 11);
}

// A scene read but not placed cannot be written nor simulated: what it
// would lose (its generators, its apparatus) is refused, not dropped.
TEST(SceneToml, AReadSceneIsPlacedBeforeItIsWrittenOrSimulated) {
  Scene read = read_scene((assets_dir() / "scenes" / "default.toml").string());
  ASSERT_FALSE(read.placed());
  EXPECT_THROW(to_toml(read), std::logic_error);
  EXPECT_THROW(Simulation(Device::open(EngineOptions{}), read), std::logic_error);
  place_scene(read);
  const std::string once = to_toml(read);
  place_scene(read);  // nothing left to place
  EXPECT_EQ(to_toml(read), once);
}

// A generator that cannot be met is found when the scene is placed, and
// named at its line in the file as it was when reading placed it.
TEST(SceneToml, APlacementProblemIsAtItsGeneratorsLine) {
  const std::string text =
      "[[materials]]\nname = \"glass\"\nyoung_modulus = 1e9\npoisson_ratio = 0.2\n"
      "density = 2500\nrestitution = 0.9\n\n"
      "[[generators]]\ntype = \"random\"\nmaterial = \"glass\"\nradius = 0.1\n"
      "min = [0, 0, 0]\nmax = [1, 1, 1]\ncount = 10\n\n"
      "[[generators]]\ntype = \"random\"\nmaterial = \"glass\"\nradius = 0.1\n"
      "min = [0, 0, 0]\nmax = [1, 1, 1]\ncount = 80\nseed = 3\n\n"
      "[numerics]\nduration = 0.1\n";
  Scene read = read_scene_text(text, "crowded.toml");  // 90 spheres fill 0.38 of the box: allowed
  EXPECT_EQ(read.generators.size(), 2u);
  EXPECT_TRUE(read.particles.empty());
  try {
    place_scene(read);
    ADD_FAILURE() << "90 spheres of 0.1 m placed at random in a 1 m box";
  } catch (const SceneError& e) {
    ASSERT_EQ(e.problems.size(), 1u);
    EXPECT_EQ(e.field, "generators[1].count");
    EXPECT_EQ(e.line, 22);
    EXPECT_NE(std::string(e.what()).find("crowded.toml:22"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(read.placed());  // left as it was read
  EXPECT_EQ(read.generators.size(), 2u);
  EXPECT_TRUE(read.particles.empty());
}

// ---------------------------------------------------------------------------
// Round trip.

Scene awkward_scene() {
  Scene s;
  s.name = "round \"trip\"\t\\ é";
  s.description = "line one\nline two";
  s.materials.push_back({"glass", 6.3e10, 0.23, 2500.0 / 3.0, 0.1 + 0.2, 1.0 / 3.0, 1e-300});
  s.materials.push_back({"steel", 2.0000000000000004e11, 0.29999999999999999, 7800, 1, 0, 5e-324});
  PairOverride o;
  o.material_a = 1;
  o.material_b = 0;
  o.rolling_friction = std::numbers::pi * 1e-6;
  o.liquid_volume = 1e-15 / 3;
  o.contact_angle = 0.7;
  s.pair_overrides.push_back(o);
  for (int i = 0; i < 20; ++i) {
    Particle p;
    p.material = i % 2;
    p.radius = 0.001 * (1 + i / 7.0);
    p.position = {i * 0.01 + 0.1, -0.0, std::sqrt(2.0) * i};
    p.velocity = {i % 3 == 0 ? -0.0 : 1.0 / (i + 1), 0, 1e20};
    p.angular_velocity = {0, i * std::numbers::e, 0};
    s.particles.push_back(p);
  }
  Wall plane;
  plane.name = "tilted";
  plane.normal = {0, 0.6, 0.8};
  plane.point = {0.1, 0.2, -1.0 / 3.0};
  s.walls.push_back(plane);
  Wall rect;
  rect.name = "lid";
  rect.shape = WallShape::Rectangle;
  rect.material = 1;
  const double c = 1 / std::sqrt(2.0);
  rect.normal = {c, 0, -c};
  rect.axis_u = {c, 0, c};
  rect.point = {0, 0, 10};
  rect.half_u = 0.1;
  rect.half_v = 1.0 / 7.0;
  rect.velocity = {0, 0, -0.01};
  s.walls.push_back(rect);
  s.effects.gravity = {0.1, -0.2, -9.80665};
  s.effects.damping = DampingModel::None;
  s.effects.tangential = TangentialModel::Mindlin;
  s.effects.rolling = RollingModel::SpringDashpot;
  s.effects.rolling_damping = 1.0 / 3.0;
  s.effects.cohesion = CohesionModel::Capillary;
  s.effects.capillary = {0.0728, 0.1 / 3, 1e-15 / 7};
  s.effects.fluid = FluidModel::Drag;
  s.effects.fluid_params = {1260, 1.412, {0.01 / 3, 0, -1e-3}};
  s.numerics = {Precision::Float, 1.0 / 3.0 * 1e-7, 0.123456789, true, 12.5, 1e-4 / 3, 48};
  s.outputs = {1.0 / 300, 0.1, 0.7, false, true};
  return s;
}

TEST(SceneToml, RoundTripIsBitExact) {
  const Scene s = awkward_scene();
  ASSERT_NO_THROW(validate_scene(s, "code"));
  const std::string text = to_toml(s);
  Scene back;
  ASSERT_NO_THROW(back = parse_scene(text, "roundtrip.toml")) << text;
  expect_same_scene(s, back);
  EXPECT_EQ(back.source_text, text);
  EXPECT_EQ(to_toml(back), text);
}

TEST(SceneToml, RoundTripOfLoadedAndGeneratedScenes) {
  for (const std::string& text :
       {std::string(kFullScene),
        random_generator("radius_min = 0.0005\nradius_max = 0.001", 300, 5)}) {
    const Scene s = parse_scene(text, "in.toml");
    expect_same_scene(s, parse_scene(to_toml(s), "out.toml"));
  }
}

// ---------------------------------------------------------------------------
// validate_scene on scenes built in code.

TEST(ValidateScene, AcceptsAValidSceneAndReportsTheFirstProblem) {
  Scene s = awkward_scene();
  EXPECT_NO_THROW(validate_scene(s, "code"));

  s.walls[0].normal = {0, 0, 2};  // not unit: code-built scenes are not normalised
  SceneError e = expect_error([&] { validate_scene(s, "code"); });
  EXPECT_EQ(e.code, "bad_vector");
  EXPECT_EQ(e.field, "walls[0].normal");
  EXPECT_EQ(e.file, "code");
  EXPECT_EQ(e.line, 0);

  s = awkward_scene();
  s.particles[3].material = 5;
  e = expect_error([&] { validate_scene(s, "code"); });
  EXPECT_EQ(e.code, "unknown_material");
  EXPECT_EQ(e.field, "particles[3].material");

  s = awkward_scene();
  s.particles[4].position = s.particles[2].position;
  e = expect_error([&] { validate_scene(s, "code"); });
  EXPECT_EQ(e.code, "overlapping_particles");
  EXPECT_EQ(e.field, "particles[4]");

  s = awkward_scene();
  s.numerics.duration = std::numeric_limits<double>::quiet_NaN();
  e = expect_error([&] { validate_scene(s, "code"); });
  EXPECT_EQ(e.code, "not_finite");
  EXPECT_EQ(e.field, "numerics.duration");
}

TEST(ValidateScene, WallsFacingEachOtherNeedRoomForAParticle) {
  Scene s = awkward_scene();
  Wall floor, ceiling;
  floor.name = "floor";
  ceiling.name = "ceiling";
  ceiling.normal = {0, 0, -1};
  ceiling.point = {0, 0, 0.0025};  // smallest particle diameter is 0.002
  s.walls = {floor, ceiling};
  s.particles[0].position[2] = 0.0012;  // between the two (not inside the floor)
  EXPECT_NO_THROW(validate_scene(s, "code"));
  s.walls[1].point[2] = 0.0015;
  const SceneError e = expect_error([&] { validate_scene(s, "code"); });
  EXPECT_EQ(e.code, "overlapping_walls");
  EXPECT_EQ(e.field, "walls[1]");
}

TEST(ValidateScene, TouchingParticlesWithinOnePercentAreAccepted) {
  Scene s = awkward_scene();
  s.particles.resize(2);
  s.particles[0].radius = s.particles[1].radius = 0.001;
  s.particles[0].position = {0, 0, 0};
  s.particles[1].position = {0.002 - 0.009e-3, 0, 0};  // overlap 0.9% of the radius
  EXPECT_NO_THROW(validate_scene(s, "code"));
  s.particles[1].position = {0.002 - 0.011e-3, 0, 0};
  EXPECT_EQ(expect_error([&] { validate_scene(s, "code"); }).code, "overlapping_particles");
}

TEST(SceneToml, ServoWallReadsAndRoundTrips) {
  const std::string text = R"(
[[materials]]
name = "glass"
young_modulus = 6e10
poisson_ratio = 0.2
density = 2500
restitution = 0.9

[[particles]]
material = "glass"
radius = 0.001
position = [0, 0, 0.001]

[[walls]]
name = "platen"
material = "glass"
point = [0, 0, 0.01]
normal = [0, 0, -1]
servo = { target_force = 2.5, gain = 0.01, max_speed = 0.02 }

[numerics]
duration = 0.01
)";
  const Scene a = parse_scene(text, "servo.toml");
  ASSERT_EQ(a.walls.size(), 1u);
  EXPECT_TRUE(a.walls[0].servo.enabled);
  EXPECT_EQ(a.walls[0].servo.target_force, 2.5);
  EXPECT_EQ(a.walls[0].servo.gain, 0.01);
  EXPECT_EQ(a.walls[0].servo.max_speed, 0.02);
  const Scene b = parse_scene(to_toml(a), "round_trip.toml");
  EXPECT_TRUE(b.walls[0].servo.enabled);
  EXPECT_EQ(b.walls[0].servo.target_force, 2.5);
  EXPECT_EQ(b.walls[0].servo.gain, 0.01);
  EXPECT_EQ(b.walls[0].servo.max_speed, 0.02);
}

// The measured glass scene is the default experiment with only the beads'
// material changed, to the medians of the shipped VSSUQ measurements
// (assets/materials/glass_beads_vssuq.csv) rounded to three digits.
TEST(SceneToml, MeasuredGlassIsTheDefaultWithTheMeasuredMedians) {
  std::map<std::string, std::vector<double>> values;
  std::ifstream in(assets_dir() / "materials" / "glass_beads_vssuq.csv");
  std::string line, header;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) { header += line; continue; }
    std::stringstream ss(line);
    std::string quantity, index, value;
    if (std::getline(ss, quantity, ',') && std::getline(ss, index, ',') &&
        std::getline(ss, value) && quantity != "quantity")
      values[quantity].push_back(std::stod(value));
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  ASSERT_EQ(values["mupp_glass-glass"].size(), 78u);
  ASSERT_EQ(values["epp_glass-glass"].size(), 24u);
  const Scene m = load_scene((assets_dir() / "scenes" / "shear_box_glass_measured.toml").string());
  const Scene p = load_scene((assets_dir() / "scenes" / "shear_box.toml").string());
  const Material& glass = m.materials[m.material_index("glass")];
  EXPECT_NEAR(glass.sliding_friction, median(values["mupp_glass-glass"]), 5e-4);
  EXPECT_NEAR(glass.restitution, median(values["epp_glass-glass"]), 5e-4);
  EXPECT_NE(header.find("median 2508"), std::string::npos) << "the density the CSV quotes";
  EXPECT_EQ(glass.density, 2508);
  // the rest is the paper's: E, nu, mu_r, the steel, the box, the specimen
  const Material& paper = p.materials[p.material_index("glass")];
  EXPECT_EQ(glass.young_modulus, paper.young_modulus);
  EXPECT_EQ(glass.poisson_ratio, paper.poisson_ratio);
  EXPECT_EQ(glass.rolling_friction, paper.rolling_friction);
  const Material& steel = m.materials[m.material_index("steel")];
  const Material& paper_steel = p.materials[p.material_index("steel")];
  EXPECT_EQ(steel.sliding_friction, paper_steel.sliding_friction);
  EXPECT_EQ(steel.restitution, paper_steel.restitution);
  EXPECT_EQ(steel.young_modulus, paper_steel.young_modulus);
  ASSERT_EQ(m.particles.size(), p.particles.size());
  for (size_t i = 0; i < m.particles.size(); ++i)
    ASSERT_EQ(m.particles[i].position, p.particles[i].position) << "bead " << i;
  EXPECT_EQ(m.walls.size(), p.walls.size());
  // the rolling law: Ai et al.'s model C for the real material, the
  // paper's constant torque (its eq. 1) for the reproduction
  EXPECT_EQ(m.effects.rolling, RollingModel::SpringDashpot);
  EXPECT_EQ(p.effects.rolling, RollingModel::ConstantTorque);
}

}  // namespace
}  // namespace simsols
