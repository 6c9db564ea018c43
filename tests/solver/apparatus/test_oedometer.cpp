// The oedometer (oedometer.h), its loading programme (oedometer_programme.h) and
// analysis (oedometer_analysis.h): the scene table, the indices on curves
// with known slopes, and a small poured specimen loaded and unloaded on the
// device, whose force balance, compression and resumption are checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "solver/apparatus/oedometer/oedometer.h"
#include "solver/apparatus/oedometer/oedometer_programme.h"
#include "solver/common/errors.h"
#include "solver/io/checkpoint.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

using testing::expect_scene_error;

constexpr double kD = 6.35e-3;

// A ring 6.5 d square (36 beads a layer) with three layers poured in, the
// paper's glass; `extra` goes into [oedometer].
std::string oedometer_toml(const std::string& extra = "",
                           const std::string& steps = "[25e3, 100e3, 400e3, 100e3]") {
  return testing::glass_toml() + R"(
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
density = 7850
restitution = 0.87
sliding_friction = 0
rolling_friction = 0

[oedometer]
length = 41.275e-3
width = 41.275e-3
load_steps = )" + steps + R"(
settle_time = 0.3
)" + extra + R"(
[oedometer.specimen]
method = "pour"
material = "glass"
diameter = 6.35e-3
layers = 3
seed = 4

[numerics]
precision = "double"
dt_fraction = 0.25
duration = 1
)";
}

TEST(OedometerScene, SixWallsAroundThePouredSpecimen) {
  const Scene s = parse_scene(oedometer_toml(), "oed.toml");
  ASSERT_TRUE(s.apparatus_as<Oedometer>());
  const Oedometer& o = *s.apparatus_as<Oedometer>();
  EXPECT_EQ(s.particles.size(), 108u);
  ASSERT_EQ(s.walls.size(), size_t(kOedometerWalls));
  EXPECT_EQ(s.walls[o.first_wall + kOedPlaten].name, "platen");
  EXPECT_TRUE(s.walls[o.first_wall + kOedPlaten].servo.enabled);
  double top = 0;
  for (const Particle& p : s.particles) top = std::max(top, p.position[2] + p.radius);
  EXPECT_GT(s.walls[o.first_wall + kOedPlaten].point[2], top);
  EXPECT_GT(s.walls[o.first_wall + kOedX0].half_v * 2, top) << "the sides reach above the beads";
  EXPECT_EQ(oedometer_peak_step(o), 2);
}

TEST(OedometerScene, RoundTripRebuildsTheSameApparatus) {
  const Scene a = parse_scene(oedometer_toml("friction_angle = 21"), "a.toml");
  const Scene b = parse_scene(to_toml(a), "b.toml");
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t w = 0; w < a.walls.size(); ++w) EXPECT_EQ(a.walls[w].point, b.walls[w].point);
  EXPECT_EQ(a.apparatus_as<Oedometer>()->load_steps, b.apparatus_as<Oedometer>()->load_steps);
  EXPECT_EQ(b.apparatus_as<Oedometer>()->friction_angle, 21);
  EXPECT_EQ(to_toml(a), to_toml(b));
}

TEST(OedometerScene, BadValuesNameTheFieldAndRange) {
  expect_scene_error(oedometer_toml("", "[25e3]"), "out_of_range", "oedometer.load_steps");
  expect_scene_error(oedometer_toml("", "[25e3, -1]"), "out_of_range",
                     "oedometer.load_steps[1]");
  expect_scene_error(oedometer_toml("", "[25e3, \"a\"]"), "wrong_type", "oedometer.load_steps");
  expect_scene_error(oedometer_toml("step_time = 0"), "out_of_range", "oedometer.step_time");
  expect_scene_error(oedometer_toml("friction_angle = 90"), "out_of_range",
                     "oedometer.friction_angle");
  std::string narrow = oedometer_toml();
  narrow.replace(narrow.find("length = 41.275e-3"), 18, "length = 1e-3");
  expect_scene_error(narrow, "out_of_range", "oedometer.specimen.diameter");
  expect_scene_error(oedometer_toml("colour = 1"), "unknown_key", "oedometer.colour");
  expect_scene_error(oedometer_toml() + "\n[shear_box]\n[shear_box.specimen]\nmethod = \"pour\"\n"
                                  "material = \"glass\"\ndiameter = 6.35e-3\nlayers = 1\n",
               "conflicting_keys", "oedometer");
}

TEST(OedometerAnalysis, IndicesAreTheSlopesOfStraightLines) {
  EXPECT_NEAR(compression_index({100e3, 200e3, 400e3}, {0.8, 0.8 - 0.1 * std::log10(2.0),
                                                        0.8 - 0.1 * std::log10(4.0)}),
              0.1, 1e-12);
  // Steps 25..800 kPa on e = 1 - 0.2 log10(s/25 kPa), unloading on a slope
  // of 0.05; K0 0.5 loading, 0.8 at the end.
  const std::vector<double> load = {25e3, 50e3, 100e3, 200e3, 400e3, 800e3, 100e3, 25e3};
  std::vector<OedometerRow> rows;
  const double e_peak = 1 - 0.2 * std::log10(32.0);
  for (size_t i = 0; i < load.size(); ++i) {
    OedometerRow r;
    r.time = 0.01 * double(i + 1);
    r.load_step = int(i) + 1;
    r.sigma_target = r.sigma_top = load[i];
    r.void_ratio = i <= 5 ? 1 - 0.2 * std::log10(load[i] / 25e3)
                          : e_peak + 0.05 * std::log10(800e3 / load[i]);
    r.k0 = i <= 5 ? 0.5 : 0.8;
    r.end_of_step = 1;
    rows.push_back(r);
  }
  const OedometerSummary s = analyse_oedometer(rows, 5, 30);
  EXPECT_NEAR(s.cc, 0.2, 1e-12);
  EXPECT_EQ(s.cc_points, 4);  // from the third step: 100..800 kPa
  EXPECT_NEAR(s.cs, 0.05, 1e-12);
  EXPECT_EQ(s.cs_points, 3);  // 800, 100, 25
  EXPECT_NEAR(s.k0_nc, 0.5, 1e-12);
  EXPECT_NEAR(s.k0_end, 0.8, 1e-12);
  EXPECT_NEAR(s.ocr_end, 32, 1e-12);
  EXPECT_NEAR(s.jaky_k0, 0.5, 1e-12);  // 1 - sin 30 deg
  EXPECT_NEAR(s.implied_friction_angle, 30, 1e-9);
  EXPECT_TRUE(s.valid);
  // unloading recovered 0.05 of the 0.2 per decade: three quarters plastic
  EXPECT_NEAR(s.plastic_share, 0.75, 1e-12);
  EXPECT_TRUE(s.virgin);
  // Mayne & Kulhawy with phi' = 30 deg: 0.5 OCR^0.5, 1.414 at OCR 8 and
  // 2.828 at OCR 32, where 0.8 is measured
  EXPECT_NEAR(s.steps[6].ocr, 8, 1e-12);
  EXPECT_NEAR(s.steps[6].mayne_kulhawy_k0, 0.5 * std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(s.steps[7].mayne_kulhawy_k0, 0.5 * std::sqrt(32.0), 1e-12);
  EXPECT_NEAR(s.mayne_kulhawy_worst, 1 - 0.8 / (0.5 * std::sqrt(32.0)), 1e-12);
  EXPECT_DOUBLE_EQ(s.steps[3].mayne_kulhawy_k0, 0.0);  // loading: none
  const std::vector<OedometerRow> back = parse_oedometer_rows_csv(oedometer_rows_csv(rows));
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_NEAR(back[3].void_ratio, rows[3].void_ratio, 1e-8);
}

// Runs the programme to the end; with `save_in_step` > 0 it also writes a
// checkpoint to `path` at that load step's second row (and goes on). The
// final state's hash in `*hash`.
std::vector<OedometerRow> run(Simulation& sim, OedometerProgramme& test, int save_in_step,
                              const std::string& path, std::uint64_t* hash) {
  while (!test.done()) {
    test.advance(1 << 20);
    const auto& rows = test.rows();
    const auto in_step = std::count_if(rows.begin(), rows.end(), [&](const OedometerRow& r) {
      return r.load_step == save_in_step;
    });
    if (save_in_step > 0 && in_step == 2) {
      save_checkpoint(sim, path, test.save_state());
      save_in_step = 0;
    }
  }
  *hash = sim.hash();
  return test.rows();
}

TEST(OedometerProgramme, LoadsAndUnloadsInEquilibriumAndResumesExactly) {
  const Scene scene = parse_scene(oedometer_toml("step_time = 0.2"), "oed.toml");
  std::uint64_t hash = 0, hash_resumed = 0;
  // The run writes a checkpoint two rows into its last step (the unloading)
  // and goes straight on to the end.
  const std::string path =
      (std::filesystem::temp_directory_path() / ("oed_" + std::to_string(getpid()) + ".bin")).string();
  std::vector<OedometerRow> rows;
  {
    Simulation sim(default_device(), scene);
    OedometerProgramme test(sim);
    rows = run(sim, test, 4, path, &hash);
  }
  const OedometerSummary s = analyse_oedometer(rows, 2, 0);
  ASSERT_EQ(s.steps.size(), 4u);
  const Oedometer& o = *scene.apparatus_as<Oedometer>();
  const double weight = scene.total_mass() * 9.81 / oedometer_area(o);
  for (size_t i = 0; i < rows.size(); ++i) {
    const OedometerRow& r = rows[i];
    if (r.end_of_step == 0) continue;
    std::printf("[measure] step %d: sigma_top %.2f kPa (target %.0f), base - top - weight %.3f "
                "kPa, e = %.5f, K0 = %.3f (x %.3f, y %.3f), held %.1f ms\n",
                r.load_step, r.sigma_top * 1e-3, r.sigma_target * 1e-3,
                (r.sigma_base - r.sigma_top - weight) * 1e-3, r.void_ratio, r.k0,
                r.sigma_hx / (0.5 * (r.sigma_top + r.sigma_base)),
                r.sigma_hy / (0.5 * (r.sigma_top + r.sigma_base)), s.steps[r.load_step - 1].duration * 1e3);
    EXPECT_EQ(r.end_of_step, 1) << "step " << r.load_step << " not in equilibrium";
    EXPECT_NEAR(r.sigma_top, r.sigma_target, 0.01 * r.sigma_target);
    // Frictionless sides: the floor carries the platen's load and the weight.
    // Measured within 4e-5 of sigma_top (double precision, 108 beads).
    EXPECT_NEAR(r.sigma_base, r.sigma_top + weight, 4e-4 * r.sigma_top);
    EXPECT_GT(r.k0, 0.2);
    EXPECT_LT(r.k0, 1.5);
  }
  EXPECT_LT(s.steps[1].void_ratio, s.steps[0].void_ratio);
  EXPECT_LT(s.steps[2].void_ratio, s.steps[1].void_ratio);
  EXPECT_GT(s.steps[3].void_ratio, s.steps[2].void_ratio) << "unloading swells";
  EXPECT_GT(s.cc, 0);
  EXPECT_GT(s.cs, 0);
  std::printf("[measure] Cc %.5f, Cs %.5f, K0 %.3f, side friction %.5f\n", s.cc, s.cs, s.k0_nc,
              s.side_friction);
  // Resumed from the checkpoint taken in the unloading step: the same rows
  // and the same final state as the run that went straight on.
  ASSERT_TRUE(std::filesystem::exists(path)) << "no checkpoint in the unloading step";
  std::string state;
  auto again = load_checkpoint(default_device(), path, &state);
  std::filesystem::remove(path);
  OedometerProgramme resumed(*again);
  resumed.restore_state(state);
  EXPECT_EQ(oedometer_rows_csv(run(*again, resumed, 0, path, &hash_resumed)),
            oedometer_rows_csv(rows));
  EXPECT_EQ(hash_resumed, hash);
}

}  // namespace
}  // namespace simsols
