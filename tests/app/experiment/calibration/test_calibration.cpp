// The calibration recovers what made its targets: periodic-cell triaxial
// tests run by the program itself with mu_s = 0.3 on two specimens (seeds
// 7 and 8) are the "measurements"; the calibration, told only the range
// [0.1, 0.6] and given other specimens (seed 1 for the design, 1001.. for
// the replicates), must find mu_s with 0.3 inside its 95 % interval and
// the interval well inside the range. A second call on the same folder keeps
// every simulation and gives the same answer (a resumed calibration); a
// call with another range is refused instead of mixing the folder's tests in.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/experiment/apparatus_run.h"
#include "app/experiment/calibration/calibration.h"
#include "app/experiment/calibration/calibration_report.h"
#include "app/experiment/calibration/scene_keys.h"
#include "solver/common/errors.h"
#include "tests/support/test_support.h"

#ifndef SIMSOLS_ASSETS_DIR
#error "SIMSOLS_ASSETS_DIR must name the assets folder"
#endif

namespace simsols {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(SIMSOLS_ASSETS_DIR) + "/tests/periodic_triaxial_small.toml";

TEST(Calibration, RecoversTheFrictionOfItsOwnTargetWithinItsInterval) {
  const fs::path d = fs::temp_directory_path() / ("simsols_calibration_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  ProgrammeRunOptions run;
  run.device = default_device();
  run.quiet = true;
  std::string targets;
  for (int seed : {7, 8}) {  // two specimens measured, as a laboratory tests two
    const std::string name = "truth" + std::to_string(seed);
    run.out_dir = (d / name).string();
    run_scene_test(scene_with(kScene, {{"materials.beads.sliding_friction", 0.3, false},
                                       {"periodic_cell.seed", double(seed), true}}),
                   run, [](const std::string&) {});
    targets += "[[targets]]\nname = \"" + name + "\"\nscene = \"" + kScene + "\"\ndata = \"" +
               name + "/cell.csv\"\nwhere = \"stage=1\"\n"
               "x = { column = \"strain\", unit = \"-\", quantity = \"axial_strain\" }\n"
               "[[targets.y]]\ncolumn = \"stress_ratio\"\nunit = \"-\"\nquantity = \"stress_ratio\"\n"
               "[[targets.y]]\ncolumn = \"volumetric_strain\"\nunit = \"-\"\n"
               "quantity = \"volumetric_strain\"\n";
  }
  std::ofstream(d / "calibration.toml")
      << "[calibration]\nname = \"recovery\"\nbudget = 6\nrounds = 2\nreplicates = 3\npoints = 10\n"
         "[[parameters]]\nname = \"mu_s\"\nkey = \"materials.beads.sliding_friction\"\n"
         "min = 0.1\nmax = 0.6\n" << targets;
  const CalibrationSpec spec = read_calibration((d / "calibration.toml").string());
  CalibrationOptions o;
  o.device = run.device;
  o.out_dir = (d / "out").string();
  o.quiet = true;
  const CalibrationResult r = run_calibration(spec, o);
  ASSERT_FALSE(r.interrupted);
  ASSERT_EQ(r.calibrated.size(), 1u);
  const Estimate& e = r.posterior.estimates[0];
  // Measured: 0.307 with 95 % 0.213 .. 0.463 (width 0.25 of the range's 0.5).
  EXPECT_LT(e.lo95, 0.3);
  EXPECT_GT(e.hi95, 0.3);
  EXPECT_LT(e.hi95 - e.lo95, 0.4) << "the measurements narrow the range";
  EXPECT_NEAR(r.calibrated[0], 0.3, 0.1);
  ASSERT_EQ(r.curves.size(), 4u);
  std::printf("mu_s = %.4f, 95 %% %.4f .. %.4f; stress ratio misfit %.4f, scatter %.4f\n",
              r.calibrated[0], e.lo95, e.hi95, r.curves[0].rms_misfit, r.curves[0].seed_scatter);
  // The stress ratio's misfit is of the order of one specimen's scatter
  // (measured 0.034 against 0.064), not of the range's effect (~0.3).
  EXPECT_LT(r.curves[0].rms_misfit, 3 * r.curves[0].seed_scatter);
  EXPECT_EQ(r.simulations, 18);
  write_calibration_report(spec, r, o.out_dir);
  EXPECT_TRUE(fs::exists(d / "out" / "calibrated.toml"));
  EXPECT_TRUE(fs::exists(d / "out" / "fit_truth7_stress_ratio.png"));

  const CalibrationResult again = run_calibration(spec, o);
  EXPECT_EQ(again.seconds, 0) << "every simulation kept";
  EXPECT_DOUBLE_EQ(again.calibrated[0], r.calibrated[0]);
  // Another range asks for other tests: the kept ones are refused, not mixed in.
  CalibrationSpec other = spec;
  other.parameters[0].max = 0.7;
  try {
    run_calibration(other, o);
    FAIL() << "the folder's tests were run with another range";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "stale_run");
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace simsols
