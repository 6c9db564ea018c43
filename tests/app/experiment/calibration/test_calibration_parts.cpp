// The calibration's parts without a simulation: the CSV reader, scene keys,
// the calibration file's checks, the surrogate and the posterior on
// functions whose answer is known.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/experiment/calibration/calibration_spec.h"
#include "app/experiment/calibration/curves.h"
#include "app/experiment/calibration/posterior.h"
#include "app/experiment/calibration/scene_keys.h"
#include "app/experiment/calibration/surrogate.h"
#include "solver/common/csv_table.h"
#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"

#ifndef SIMSOLS_ASSETS_DIR
#error "SIMSOLS_ASSETS_DIR must name the assets folder"
#endif

namespace simsols {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(SIMSOLS_ASSETS_DIR) + "/tests/periodic_triaxial_small.toml";

fs::path fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() /
                     ("simsols_calibration_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(CsvTable, ReadsAroundCommentsAndNamesABadCell) {
  const CsvTable t = parse_csv("# source\nx,y\n1,2\n\n# more\n3,abc\n", "f.csv");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.column("y"), 1);
  EXPECT_EQ(t.lines[1], 6);
  EXPECT_EQ(t.number(0, 1), 2);
  try {
    t.number(1, 1);
    FAIL() << "abc is not a number";
  } catch (const ReadError& e) {
    EXPECT_NE(std::string(e.what()).find("f.csv:6: column 'y'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_csv("x,y\n1\n", "g.csv"), ReadError);
}

TEST(SceneKeys, SetsAMaterialByNameAndATableKey) {
  const Scene s = scene_with(kScene, {{"materials.beads.sliding_friction", 0.42, false},
                                      {"periodic_cell.seed", 7, true}});
  EXPECT_DOUBLE_EQ(s.materials.at(0).sliding_friction, 0.42);
  try {
    scene_with(kScene, {{"materials.glass.sliding_friction", 0.4, false}});
    FAIL() << "the scene has no material called glass";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "bad_key");
    EXPECT_EQ(e.field, "materials.glass.sliding_friction");
  }
  // A value out of the scene's range is the scene reader's error, as usual.
  EXPECT_THROW(scene_with(kScene, {{"materials.beads.poisson_ratio", 0.7, false}}), SceneError);
}

TEST(SceneKeys, SetsACalibratedMaterialOnASceneAlreadyRead) {
  Scene s = read_scene(kScene);
  const std::vector<std::string> not_set = set_material_values(
      s, {{"materials.beads.rolling_friction", 2e-5}, {"materials.beads.young_modulus", 1e9},
          {"periodic_cell.preparation_friction", 0.1}, {"materials.sand.density", 2650}});
  EXPECT_DOUBLE_EQ(s.materials.at(0).rolling_friction, 2e-5);
  EXPECT_DOUBLE_EQ(s.materials.at(0).young_modulus, 1e9);
  EXPECT_EQ(not_set, (std::vector<std::string>{"periodic_cell.preparation_friction",
                                               "materials.sand.density"}));
}

TEST(CalibrationSpec, ReportsEveryBadFieldWithItsName) {
  const fs::path d = fresh("spec");
  write(d / "m.csv", "# measured\neps_pct,eta\n0,0\n5,1.2\n");
  fs::copy_file(kScene, d / "scene.toml");
  const std::string good_target =
      "[[targets]]\nname = \"t\"\nscene = \"scene.toml\"\ndata = \"m.csv\"\n"
      "x = { column = \"eps_pct\", unit = \"%\", quantity = \"axial_strain\" }\n";
  write(d / "bad.toml",
        "[calibration]\nbudget = 3\n[[parameters]]\nname = \"mu\"\nkey = \"materials.beads.sliding_friction\"\n"
        "min = 0.5\nmax = 0.1\n" + good_target +
        "[[targets.y]]\ncolumn = \"eta\"\nunit = \"kPa\"\nquantity = \"stress_ratio\"\n");
  try {
    read_calibration((d / "bad.toml").string());
    FAIL() << "max below min";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field, "parameters[0].max");
    EXPECT_EQ(e.code, "out_of_range");
  }
  write(d / "unit.toml",
        "[[parameters]]\nname = \"mu\"\nkey = \"materials.beads.sliding_friction\"\nmin = 0.1\nmax = 0.5\n" + good_target +
            "[[targets.y]]\ncolumn = \"eta\"\nunit = \"kPa\"\nquantity = \"stress_ratio\"\n");
  try {
    read_calibration((d / "unit.toml").string());
    FAIL() << "kPa is not a unit of a stress ratio";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "bad_unit");
    EXPECT_EQ(e.field, "targets[0].y[0].unit");
  }
  write(d / "quantity.toml",
        "[[parameters]]\nname = \"mu\"\nkey = \"materials.beads.sliding_friction\"\nmin = 0.1\nmax = 0.5\n" + good_target +
            "[[targets.y]]\ncolumn = \"eta\"\nunit = \"-\"\nquantity = \"dilation\"\n");
  try {
    read_calibration((d / "quantity.toml").string());
    FAIL() << "a periodic cell measures no dilation";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "bad_enum");
    EXPECT_NE(e.message.find("stress_ratio"), std::string::npos) << e.message;
  }
  write(d / "ok.toml",
        "[[parameters]]\nname = \"mu\"\nkey = \"materials.beads.sliding_friction\"\nmin = 0.1\nmax = 0.5\n" + good_target +
            "[[targets.y]]\ncolumn = \"eta\"\nunit = \"-\"\nquantity = \"stress_ratio\"\n");
  CalibrationSpec s = read_calibration((d / "ok.toml").string());
  const Curve m = measured_curve(s.targets.at(0));
  ASSERT_EQ(m.x.size(), 2u);
  EXPECT_DOUBLE_EQ(m.x[1], 0.05);  // % to a strain
  EXPECT_DOUBLE_EQ(m.y[0][1], 1.2);
  s.targets[0].zero_at = 2.5;  // % : every y from its value half way, 0.6
  const Curve r = measured_curve(s.targets[0]);
  EXPECT_DOUBLE_EQ(r.y[0][0], -0.6);
  EXPECT_DOUBLE_EQ(r.y[0][1], 0.6);
}

TEST(Curves, ValueAtFollowsTheFirstBranchThatReachesX) {
  const std::vector<double> x{0, 1, 2, 1, 0}, y{0, 10, 20, 5, 0};  // load, then unload
  EXPECT_DOUBLE_EQ(value_at(x, y, 1.5), 15);
  EXPECT_TRUE(std::isnan(value_at(x, y, 2.5)));
}

// y = a quadratic of two parameters, known exactly.
Eigen::VectorXd truth(const Eigen::VectorXd& u) {
  Eigen::VectorXd y(3);
  y << 1 + 2 * u(0) - u(1), 0.5 + u(0) * u(0) + 0.3 * u(1), 2 - u(0) * u(1) + 2 * u(1) * u(1);
  return y;
}

TEST(Surrogate, FitsAQuadraticExactlyAndSeesNoise) {
  const Eigen::MatrixXd u = sobol_designs(2, 14);
  Eigen::MatrixXd y(u.rows(), 3);
  for (int i = 0; i < u.rows(); ++i) y.row(i) = truth(u.row(i).transpose()).transpose();
  const Surrogate s(u, y);
  EXPECT_EQ(s.terms(), 6);
  const Eigen::Vector2d at(0.31, 0.77);
  EXPECT_LT((s.predict(at) - truth(at)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT(s.loo_error().maxCoeff(), 1e-10);
  Eigen::MatrixXd noisy = y;
  for (int i = 0; i < u.rows(); ++i) noisy(i, 0) += (i % 2 ? 0.05 : -0.05);
  const Surrogate n(u, noisy);
  EXPECT_GT(n.loo_error()(0), 0.02);  // the noise's 0.05, less what the fit absorbs
  EXPECT_LT(n.loo_error()(1), 1e-10);
}

TEST(Posterior, FindsTheParametersOfAKnownResponseWithAnHonestInterval) {
  const Eigen::MatrixXd u = sobol_designs(2, 14);
  Eigen::MatrixXd y(u.rows(), 3);
  for (int i = 0; i < u.rows(); ++i) y.row(i) = truth(u.row(i).transpose()).transpose();
  const Eigen::Vector2d u_true(0.6, 0.35);
  Comparison c;
  c.measured = truth(u_true);
  c.scatter = Eigen::VectorXd::Constant(3, 0.02);
  c.seed_scatter = Eigen::VectorXd::Zero(3);
  c.curve_of = {0, 1, 2};
  c.test_of = {0, 1, 2};
  c.curves = 3;
  c.tests = 3;
  CalibrationSpec spec;
  spec.parameters = {{"a", "a", 0, 1, false}, {"b", "b", 10, 1000, true}};
  const Posterior p = posterior(spec, c, Surrogate(u, y));
  EXPECT_NEAR(p.best_u(0), u_true(0), 1e-4);
  EXPECT_NEAR(p.best_u(1), u_true(1), 1e-4);
  EXPECT_NEAR(p.estimates[1].best, spec.parameters[1].value(0.35), 1e-3 * 100);
  for (int j = 0; j < 2; ++j) {
    const double v = spec.parameters[j].value(u_true(j));
    EXPECT_LT(p.estimates[j].lo95, v);
    EXPECT_GT(p.estimates[j].hi95, v);
  }
  // The scatter of 0.02 in values of slope ~2 leaves about 0.01 in u.
  EXPECT_LT(p.estimates[0].sd, 0.05);
  EXPECT_GT(p.estimates[0].sd, 0.002);
  EXPECT_GT(p.effective_samples, 50);
}

}  // namespace
}  // namespace simsols
