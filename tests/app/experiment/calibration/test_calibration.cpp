// The calibration recovers what made its target: a periodic-cell triaxial
// test run by the program itself with mu_s = 0.3 on one specimen (seed 7)
// is the "measurement"; the calibration, told only the range [0.1, 0.6]
// and given other specimens (seed 1 for the design, 1001.. for the
// replicates), must find mu_s with 0.3 inside its 95 % interval and the
// interval well inside the range. A second call on the same folder keeps
// every simulation and gives the same answer (a resumed calibration); a
// call with another range is refused instead of mixing the folder's tests in.
#include <gtest/gtest.h>

#include <unistd.h>

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
  run.out_dir = (d / "truth").string();
  run.quiet = true;
  run_scene_test(scene_with(kScene, {{"materials.beads.sliding_friction", 0.3, false},
                                     {"periodic_cell.seed", 7, true}}),
                 run, [](const std::string&) {});
  std::ofstream(d / "calibration.toml")
      << "[calibration]\nname = \"recovery\"\nbudget = 8\nrounds = 2\nreplicates = 3\npoints = 10\n"
         "[[parameters]]\nname = \"mu_s\"\nkey = \"materials.beads.sliding_friction\"\n"
         "min = 0.1\nmax = 0.6\n"
         "[[targets]]\nname = \"truth\"\nscene = \"" + kScene + "\"\ndata = \"truth/cell.csv\"\n"
         "where = \"stage=1\"\n"
         "x = { column = \"strain\", unit = \"-\", quantity = \"axial_strain\" }\n"
         "[[targets.y]]\ncolumn = \"stress_ratio\"\nunit = \"-\"\nquantity = \"stress_ratio\"\n"
         "[[targets.y]]\ncolumn = \"volumetric_strain\"\nunit = \"-\"\nquantity = \"volumetric_strain\"\n";
  const CalibrationSpec spec = read_calibration((d / "calibration.toml").string());
  CalibrationOptions o;
  o.device = run.device;
  o.out_dir = (d / "out").string();
  o.quiet = true;
  const CalibrationResult r = run_calibration(spec, o);
  ASSERT_FALSE(r.interrupted);
  ASSERT_EQ(r.calibrated.size(), 1u);
  const Estimate& e = r.posterior.estimates[0];
  // Measured: 0.282 with 95 % 0.226 .. 0.362 (width 0.14 of the range's 0.5).
  EXPECT_LT(e.lo95, 0.3);
  EXPECT_GT(e.hi95, 0.3);
  EXPECT_LT(e.hi95 - e.lo95, 0.3) << "the measurement narrows the range";
  EXPECT_NEAR(r.calibrated[0], 0.3, 0.1);
  ASSERT_EQ(r.curves.size(), 2u);
  // The stress ratio's misfit is of the order of one specimen's scatter
  // (measured 0.057 against 0.056), not of the range's effect (~0.3).
  EXPECT_LT(r.curves[0].rms_misfit, 3 * r.curves[0].seed_scatter);
  EXPECT_EQ(r.simulations, 11);
  write_calibration_report(spec, r, o.out_dir);
  EXPECT_TRUE(fs::exists(d / "out" / "calibrated.toml"));
  EXPECT_TRUE(fs::exists(d / "out" / "fit_truth_stress_ratio.png"));

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
