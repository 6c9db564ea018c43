#include <cstdio>

#include "app/cli/campaign/campaign_command.h"
#include "app/cli/commands.h"
#include "app/experiment/shear_box/campaign.h"
#include "solver/io/scene_toml.h"

namespace simsols {

// The paper's programme (Table 1's sizes x the stresses) in a shear box.
int shear_box_campaign(const CampaignOptions& opt, const Scene& base, const std::string& base_name) {
  if (opt.inertial_given)
    throw UsageError("not_applicable", "--inertial-numbers",
                     "is a periodic cell's flag; a shear campaign varies --sizes, --stresses and "
                     "--seeds");
  const Preparation& prep = base.specimen()->preparation;
  const auto refuse = [&](const char* field, const char* how) {
    throw SceneError("not_applicable", base_name, 0,
                     std::string("shear_box.specimen.preparation.") + field,
                     std::string("a shear campaign pours a new specimen for each size; ") + how);
  };
  if (prep.relative_density)
    refuse("relative_density",
           "give the preparation friction instead (simsols run finds it: its scene.resolved.toml)");
  if (prep.expansion)
    refuse("expansion", "grow one with simsols run and campaign over its scene.resolved.toml's "
                        "sizes by hand");
  if (prep.tamping_layers)
    refuse("tamping_layers", "tamp one with simsols run and campaign over its "
                             "scene.resolved.toml's sizes by hand");
  CampaignSpec spec;
  spec.sizes_mm = opt.sizes_mm;
  spec.stresses_kpa = opt.stresses_kpa;
  spec.layers = opt.layers;
  spec.precision = precision_flag(opt.precision);
  spec.profile = &run_profile(opt.profile);
  spec.displacement_mm = opt.displacement_mm;
  spec.seeds = opt.seeds_given ? opt.seeds : 1;
  std::vector<CampaignTest> tests = plan_campaign(base, base_name, spec, opt.out_dir);

  InterruptScope interrupt;
  CampaignRun run = campaign_run(opt.cluster, opt.out_dir, interrupt.stop_function(), opt.quiet);
  if (emit_or_check_plan(opt.cluster, "campaign", opt.command_line, opt.out_dir,
                         cluster_tests(tests)))
    return 0;
  if (!run.collect) run.device = open_command_device();
  const CampaignOutcome outcome = run_campaign(tests, base_name, spec, opt.out_dir, run);
  if (outcome.interrupted) {
    const CampaignTest& t = tests[outcome.interrupted_test];
    return report_interrupted(outcome.interrupted_test, tests.size(), t.scene.name, t.dir,
                              interrupt);
  }
  return report_done(opt, run, tests.size(), run.only ? tests[*run.only].scene.name : "", "tests");
}

}  // namespace simsols
