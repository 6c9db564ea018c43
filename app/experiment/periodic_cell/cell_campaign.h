// A periodic-cell campaign: the base scene's test at several pressures and
// inertial numbers, each on several specimens (seeds), one test after the
// other into one folder, then the steady values read across them with
// their spread between specimens: mu(I), Phi(I) and Z(I) curves.
//
// Every test runs from the base scene with [periodic_cell] pressure,
// inertial_number and seed replaced (a new gas for each seed), in
// OUT/p<P>kPa_I<I>_s<seed>/ (apparatus_run.h). Resumable as the other
// campaigns are (campaign_loop.h); a cluster's array runs one test per task.
// Afterwards: OUT/tests.csv (one row per test), OUT/summary.csv and .md (one
// row per pressure and inertial number: the mean over the specimens of their
// steady values, with the 95 % Student interval between specimens; NaN for
// one specimen) and OUT/mu_I.png, OUT/phi_I.png.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/experiment/apparatus_run.h"
#include "app/experiment/campaign_loop.h"
#include "solver/apparatus/periodic_cell/cell_programme.h"

namespace simsols {

struct CellCampaignSpec {
  std::vector<double> pressures_kpa;     // empty: the base scene's
  std::vector<double> inertial_numbers;  // empty: the base scene's
  int seeds = 3;                         // specimens per point: the base's seed and the next ones
  std::optional<Precision> precision;
};

using CellRunResult = TestRunResult<CellProgramme>;

struct CellCampaignTest {
  double p_kpa = 0, inertial = 0;
  std::int64_t seed = 0;
  Scene scene;
  std::filesystem::path dir;
  double cost = 0;  // estimated particle-steps
  CellRunResult result;
};

// The tests of `spec` from `base` (named `base_name` in messages). Throws
// UsageError naming the flag or SceneError naming the base.
std::vector<CellCampaignTest> plan_cell_campaign(const Scene& base, const std::string& base_name,
                                                 const CellCampaignSpec& spec,
                                                 const std::string& out_dir);

// Runs the tests not finished yet, then writes the report unless interrupted.
CampaignOutcome run_cell_campaign(std::vector<CellCampaignTest>& tests, const std::string& out_dir,
                                  const CampaignRun& run);

// One row of points.csv: a pressure and inertial number over its specimens.
struct CellPoint {
  double p_kpa = 0, inertial = 0;
  int specimens = 0;
  double mu = 0, mu_ci = 0, phi = 0, phi_ci = 0, z = 0, z_ci = 0, ev = 0, ev_ci = 0;
  double angle = 0, angle_ci = 0;  // mobilised friction angle, deg
};
std::vector<CellPoint> cell_points(const std::vector<CellCampaignTest>& tests);
std::string cell_points_csv(const std::vector<CellPoint>& points);
std::string cell_points_markdown(const std::vector<CellPoint>& points);

}  // namespace simsols
