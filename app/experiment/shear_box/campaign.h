// A campaign: the reference paper's programme of direct shear tests, bead
// sizes (its Table 1) x normal stresses, or any subset, any sizes and
// stresses, run one after the other into one folder.
//
// Every test runs from a base scene with specimen.diameter, specimen.layers
// (Table 1, or a given count) and normal_stress replaced, in
// OUT/d<size>mm_<stress>kPa/ (shear_run.h). Resumable: a test whose
// summary.txt exists is not rerun (its rows are analysed again), an
// interrupted one continues from its checkpoint. Afterwards, per bead size,
// the curves of its stresses on common axes (the paper's Figures 3-7), the
// Mohr-Coulomb envelopes of the peak and residual strengths, and
// OUT/summary.csv / .md (campaign_report.h).
//
// plan_campaign() checks everything and builds every scene before anything
// runs; run_campaign() runs what is left, with progress over the whole
// programme.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/experiment/campaign_loop.h"
#include "app/experiment/shear_box/shear_run.h"
#include "solver/core/cl_device.h"
#include "solver/apparatus/run_profile.h"
#include "solver/scene/scene.h"

namespace simsols {

struct CampaignSpec {
  std::vector<double> sizes_mm{2.38125, 3.175, 3.96875, 4.7625, 6.35};
  std::vector<double> stresses_kpa{50, 160, 280, 400};
  int layers = 0;                        // 0 = Table 1
  std::optional<Precision> precision;    // nullopt = the base scene's
  double displacement_mm = 0;            // 0 = the base scene's
  // Specimens per size and stress: the base's seed and the next ones. The
  // first keeps the test's plain folder name, the others add _s<seed>.
  int seeds = 1;
  const RunProfile* profile = nullptr;   // nullptr = paper (run_profile.h)
};

struct CampaignTest {
  double d_mm = 0, s_kpa = 0;
  std::int64_t seed = 0;  // its specimen's
  Scene scene;
  std::filesystem::path dir;
  double cost = 0;  // estimated particle-steps
  ShearRunResult result;
};

// The tests of `spec` from `base` (named `base_name` in messages), in
// OUT/<scene name>/. Throws UsageError naming the flag (--sizes,
// --stresses, --layers, --displacement) or SceneError naming the base.
std::vector<CampaignTest> plan_campaign(const Scene& base, const std::string& base_name,
                                        const CampaignSpec& spec, const std::string& out_dir);

// A shear test finished earlier in `dir`, read back (its rows analysed
// again with today's analysis; summary.txt and plots rewritten when that
// differs). `title` heads its plots.
ShearRunResult finished_shear_test(const std::filesystem::path& dir, const std::string& title);
// A test just run by `run_shear`, its rows and summary replaced by what
// finished_shear_test reads back from its folder (the CSV's digits): a
// report is then the same whether its tests ran here or were collected.
ShearRunResult run_shear_test(const Scene& scene, const ProgrammeRunOptions& options,
                              const std::string& title);


// Runs the tests not finished yet (keeping the results of those that are),
// printing one line per test; then writes the report into `out_dir`
// unless interrupted.
CampaignOutcome run_campaign(std::vector<CampaignTest>& tests, const std::string& base_name,
                             const CampaignSpec& spec, const std::string& out_dir,
                             const CampaignRun& run);

}  // namespace simsols
