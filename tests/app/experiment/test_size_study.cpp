// The size study (app/experiment/size_study.h): the registry's resize of
// each apparatus, the plan's sizes and seeds, the bulk value read back from
// a periodic-cell campaign's table, the means and the size from which an
// apparatus stays within 1° of the bulk, and a small study run end to end
// and kept when run again.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "app/experiment/periodic_cell/cell_campaign.h"
#include "app/experiment/size_study.h"
#include "solver/apparatus/cell/cell_walls.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
const std::string kScenes = SIMSOLS_ASSETS_DIR "/scenes/";

Scene scene(const std::string& name) { return read_scene(kScenes + name); }

TEST(SizeStudy, ResizeScalesTheWidthsTheLayersAndTheTravel) {
  Scene s = scene("shear_box_poured.toml");
  const ApparatusKind& kind = required_apparatus_kind(s);
  const ApparatusCell before = *s.cell();
  EXPECT_NEAR(cell_size_ratio(s), 60.07 / 6.35, 1e-12);
  const double travel = s.apparatus_as<ShearBox>()->shear_displacement;
  kind.resize(s, 2, 2);
  EXPECT_DOUBLE_EQ(s.cell()->length, 2 * before.length);
  EXPECT_DOUBLE_EQ(s.cell()->width, 2 * before.width);
  EXPECT_EQ(s.cell()->specimen.layers, 2 * before.specimen.layers);
  EXPECT_DOUBLE_EQ(s.apparatus_as<ShearBox>()->shear_displacement, 2 * travel);
  EXPECT_NEAR(cell_size_ratio(s), 2 * 60.07 / 6.35, 1e-12);
  Scene fixed = scene("shear_box_poured.toml");
  kind.resize(fixed, 1.5, 1);
  EXPECT_EQ(fixed.cell()->specimen.layers, before.specimen.layers);
  Scene t = scene("triaxial.toml");
  required_apparatus_kind(t).resize(t, 1.5, 1.5);
  EXPECT_EQ(t.cell()->specimen.layers, 18);  // 12 x 1.5
  EXPECT_THROW(kind.resize(t, 0, 1), SceneError);
  EXPECT_EQ(required_apparatus_kind(scene("periodic_cell.toml")).resize, nullptr);
}

TEST(SizeStudy, ThePlanRefusesWhatItCannotResize) {
  SizeStudySpec spec;
  EXPECT_THROW(plan_size_study(scene("periodic_cell.toml"), "cell.toml", spec, "out"), SceneError);
  EXPECT_THROW(plan_size_study(load_scene(kScenes + "shear_box_poured.toml"), "placed.toml", spec, "out"),
               SceneError);
  spec.scales = {1, 7};
  try {
    plan_size_study(scene("shear_box_poured.toml"), "poured.toml", spec, "out");
    FAIL() << "a scale of 7 was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--scales"), std::string::npos) << e.what();
  }
}

TEST(SizeStudy, ThePlanPlacesEachSizeAndSeedApart) {
  SizeStudySpec spec;
  spec.scales = {1, 1.5};
  spec.seeds = 2;
  const std::vector<SizeTest> tests = plan_size_study(scene("shear_box_poured.toml"), "poured.toml", spec, "out");
  ASSERT_EQ(tests.size(), 4u);
  EXPECT_EQ(tests[0].scene.particles.size(), 324u);  // 4 layers of 9 x 9
  EXPECT_EQ(tests[2].scene.particles.size(), 1176u);  // 6 layers of 14 x 14
  EXPECT_EQ(tests[1].seed, tests[0].seed + 1);
  EXPECT_NE(tests[0].scene.particles[0].position, tests[1].scene.particles[0].position);
  EXPECT_EQ(tests[3].dir, fs::path("out") / "x1.5_s2");
  EXPECT_FALSE(tests[0].scene.outputs.dump_vtk);
}

TEST(SizeStudy, TheBulkValueIsTheCellCampaignsTable) {
  CellPoint p;
  p.p_kpa = 160, p.inertial = 1e-3, p.specimens = 3;
  p.mu = 0.1878, p.mu_ci = 0.0309, p.angle = 11.25, p.angle_ci = 1.06;
  const fs::path dir = fs::temp_directory_path() / "simsols_size_bulk";
  fs::create_directories(dir);
  write_file_atomic((dir / "summary.csv").string(), cell_points_csv({p}));
  const BulkValue b = read_bulk_value((dir / "summary.csv").string());
  const double deg = 180 / std::numbers::pi;
  EXPECT_NEAR(b.plane.mean, std::atan(0.1878) * deg, 1e-4);
  EXPECT_NEAR(b.plane.half_width, 0.5 * (std::atan(0.2187) - std::atan(0.1569)) * deg, 1e-4);
  EXPECT_NEAR(b.mobilised.mean, 11.25, 1e-9);
  EXPECT_EQ(b.specimens, 3);
  std::ofstream((dir / "other.csv").string()) << "p_kPa,inertial_number\n160,0.001\n";
  try {
    read_bulk_value((dir / "other.csv").string());
    FAIL() << "a table without the columns was read";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("specimens"), std::string::npos) << e.what();
  }
}

// Sizes whose means approach 10 from above: within 1 degree from the
// third size on; the intervals are Student's over the specimens.
TEST(SizeStudy, TheSizeWithinOneDegreeIsWhereTheMeansStayWithinIt) {
  const ApparatusKind& kind = *find_apparatus_kind("shear_box");
  const double means[] = {14, 12, 10.8, 10.3};
  std::vector<SizeTest> tests;
  for (int k = 0; k < 4; ++k)
    for (double offset : {-0.2, 0.0, 0.2}) {
      SizeTest t;
      t.scale = 1 + k, t.ratio = 9.5 * (1 + k);
      for (const HeadlineResult& h : kind.headlines) t.results[h.key] = means[k] + offset;
      t.results["wall_seconds"] = 10;
      tests.push_back(t);
    }
  const std::vector<SizePoint> points = size_points(kind, tests);
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points[1].specimens, 3);
  EXPECT_NEAR(points[1].values[1].mean, 12, 1e-12);
  EXPECT_NEAR(points[1].values[1].half_width, 4.302653 * 0.2 / std::sqrt(3.0), 1e-5);
  EXPECT_DOUBLE_EQ(ratio_within(points, 1, {10, 0.5, 3}, 1.0), 28.5);
  EXPECT_TRUE(std::isnan(ratio_within(points, 1, {5, 0.5, 3}, 1.0)));
  BulkValue bulk;
  bulk.plane = {10, 0.5, 3};
  bulk.mobilised = {11, 0.5, 3};
  const std::string md = size_summary_markdown(kind, points, bulk);
  EXPECT_NE(md.find("from L/d = 28.5 on."), std::string::npos) << md;
  bulk.plane.half_width = 1.5;  // the differences' intervals now wider than 1 degree
  EXPECT_NE(size_summary_markdown(kind, points, bulk).find("more specimens would tell"), std::string::npos);
}

// Two specimens of a thin box sheared 0.3 mm: the study writes its tables,
// and run again keeps the finished tests with the same results.
TEST(SizeStudy, ASmallStudyRunsAndIsKeptWhenRunAgain) {
  Scene base = scene("shear_box_poured.toml");
  ShearBox& box = *base.apparatus_as<ShearBox>();
  box.specimen.layers = 2;
  box.shear_displacement = 0.3e-3;
  box.settle_time = 0.05;
  box.rows = 30;
  SizeStudySpec spec;
  spec.scales = {1};
  spec.seeds = 2;
  const fs::path out = fs::temp_directory_path() / "simsols_size_study";
  fs::remove_all(out);
  std::vector<SizeTest> tests = plan_size_study(base, "thin.toml", spec, out.string());
  CampaignRun run;
  run.device = default_device();
  run.quiet = true;
  ASSERT_FALSE(run_size_study(tests, std::nullopt, "thin", out.string(), run).interrupted);
  for (const char* f : {"tests.csv", "summary.csv", "summary.md", "size_residual_friction_angle_deg.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const double first = tests[1].results.at("residual_friction_angle_deg");
  std::printf("[measure] thin box, 0.3 mm: phi_res %.3f and %.3f deg\n",
              tests[0].results.at("residual_friction_angle_deg"), first);
  EXPECT_TRUE(std::isfinite(first));
  std::vector<SizeTest> again = plan_size_study(base, "thin.toml", spec, out.string());
  const CampaignOutcome o = run_size_study(again, std::nullopt, "thin", out.string(), run);
  EXPECT_LT(o.seconds, 1.0);  // nothing run: both kept
  EXPECT_EQ(again[1].results.at("residual_friction_angle_deg"), first);
}

}  // namespace
}  // namespace simsols
