#include "app/cli/campaign/campaign_command.h"

#include <cstdio>

#include "solver/common/errors.h"
#include "solver/apparatus/run_profile.h"

namespace simsols {

// What a campaign run with the cluster flags says at its end; 0.
int report_done(const CampaignOptions& opt, const CampaignRun& run, size_t count,
                const std::string& name_of_only, const char* what) {
  if (run.only)
    std::printf("campaign task %zu of %zu done: %s in %s\n", *run.only, count,
                name_of_only.c_str(), opt.out_dir.c_str());
  else
    std::printf("campaign %s: %zu %s in %s (summary.md, summary.csv, *.png)\n",
                run.collect ? "collected" : "done", count, what, opt.out_dir.c_str());
  return 0;
}

int report_interrupted(size_t k, size_t count, const std::string& name,
                       const std::filesystem::path& dir, const InterruptScope& interrupt) {
  std::printf("campaign interrupted in test %zu/%zu (%s): its checkpoint and rows are in %s; "
              "%zu of %zu tests finished. Resume with the same command.\n",
              k + 1, count, name.c_str(), dir.string().c_str(), k, count);
  return interrupt.exit_status();
}

void refuse_profile(const CampaignOptions& opt, const std::string& base_name) {
  if (run_profile(opt.profile).neutral()) return;
  throw UsageError("not_applicable", "--profile",
                   "'" + opt.profile + "' is measured on the direct shear box only "
                   "(docs/accuracy.md); " + base_name + " is another apparatus: use --profile paper");
}

}  // namespace simsols
