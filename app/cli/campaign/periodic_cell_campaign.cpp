#include <cstdio>

#include "app/cli/campaign/campaign_command.h"
#include "app/cli/commands.h"
#include "app/experiment/periodic_cell/cell_campaign.h"

namespace simsols {

// The periodic cell's test at several pressures and inertial numbers, on
// several specimens each.
int periodic_cell_campaign(const CampaignOptions& opt, const Scene& base, const std::string& base_name) {
  for (const auto& [given, flag] : {std::pair{opt.sizes_given, "--sizes"},
                                    {opt.layers_given, "--layers"},
                                    {opt.displacement_given, "--displacement"}})
    if (given)
      throw UsageError("not_applicable", flag,
                       "is a shear-box flag; a periodic-cell campaign varies --stresses (the pressure), "
                       "--inertial-numbers and --seeds");
  CellCampaignSpec spec;
  if (opt.stresses_given) spec.pressures_kpa = opt.stresses_kpa;
  spec.inertial_numbers = opt.inertial_numbers;
  spec.seeds = opt.seeds;
  spec.precision = precision_flag(opt.precision);
  refuse_profile(opt, base_name);
  std::vector<CellCampaignTest> tests = plan_cell_campaign(base, base_name, spec, opt.out_dir);
  InterruptScope interrupt;
  CampaignRun run = campaign_run(opt.cluster, opt.out_dir, interrupt.stop_function(), opt.quiet);
  if (emit_or_check_plan(opt.cluster, "campaign", opt.command_line, opt.out_dir, cluster_tests(tests)))
    return 0;
  if (!run.collect) run.device = open_command_device();
  const CampaignOutcome outcome = run_cell_campaign(tests, opt.out_dir, run);
  if (outcome.interrupted) {
    const CellCampaignTest& t = tests[outcome.interrupted_test];
    return report_interrupted(outcome.interrupted_test, tests.size(), t.scene.name, t.dir, interrupt);
  }
  return report_done(opt, run, tests.size(), run.only ? tests[*run.only].scene.name : "",
                     "periodic-cell tests");
}

}  // namespace simsols
