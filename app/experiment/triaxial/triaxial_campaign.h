// A triaxial campaign: the same specimen consolidated to several confining
// stresses sigma_3 and compressed, one test after the other into one
// folder, then the strength read across them as a laboratory reads it;
// with `seeds` > 1, the same again on further specimens (the base's
// specimen seed and the next ones), and the strength as the mean of the
// specimens' envelopes with its 95 % interval.
//
// Every test runs from the base scene with [triaxial] confining_stress
// replaced, in OUT/s3_<stress>kPa/ (the first specimen) or
// OUT/s3_<stress>kPa_s<seed>/ (the others; apparatus_run.h), each
// specimen's tests from the same bead positions. Resumable as the shear campaign is (campaign.h): a test whose
// summary.txt exists is kept (its rows analysed again), an interrupted one
// continues from its checkpoint. Afterwards (triaxial_campaign_report.h):
// the curves on common axes, the Mohr circles at the peak and at the
// critical state with the envelopes tangent to them, the critical state
// line in e-log p', and OUT/summary.csv / .md.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/experiment/campaign_loop.h"
#include "app/experiment/apparatus_run.h"
#include "solver/apparatus/triaxial/triaxial_programme.h"

namespace simsols {

struct TriaxialCampaignSpec {
  std::vector<double> stresses_kpa{50, 100, 200};  // sigma_3
  std::optional<Precision> precision;              // nullopt = the base scene's
  int seeds = 1;                                   // specimens, [1, 100]
};

using TriaxialRunResult = TestRunResult<TriaxialProgramme>;

struct TriaxialCampaignTest {
  double s_kpa = 0;
  std::int64_t seed = 0;  // its specimen's
  Scene scene;
  std::filesystem::path dir;
  double cost = 0;  // estimated particle-steps
  TriaxialRunResult result;
};

// The tests of `spec` from `base` (named `base_name` in messages). Throws
// UsageError naming the flag or SceneError naming the base.
std::vector<TriaxialCampaignTest> plan_triaxial_campaign(const Scene& base,
                                                         const std::string& base_name,
                                                         const TriaxialCampaignSpec& spec,
                                                         const std::string& out_dir);

// A triaxial test finished earlier in `dir`, read back (its rows analysed
// again with today's analysis; summary.txt and plots rewritten when that
// differs), as finished_shear_test (campaign.h) reads a shear test.
// `title` heads its plots; the confining stress is in Pa.
TriaxialRunResult finished_triaxial_test(const std::filesystem::path& dir,
                                         const std::string& title, double confining_stress);
// A test just run by run_triaxial, its rows and summary replaced by what
// finished_triaxial_test reads back from its folder (the CSV's digits): a
// report is then the same whether its tests ran here or were collected.
TriaxialRunResult run_triaxial_test(const Scene& scene, const ProgrammeRunOptions& options,
                                    const std::string& title);

// Runs the tests not finished yet, one line per test, then writes the
// report into `out_dir` unless interrupted.
CampaignOutcome run_triaxial_campaign(std::vector<TriaxialCampaignTest>& tests,
                                      const std::string& base_name, const std::string& out_dir,
                                      const CampaignRun& run);

}  // namespace simsols
