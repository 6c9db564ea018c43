#include <cstdio>

#include "app/cli/campaign/campaign_command.h"
#include "app/cli/commands.h"
#include "app/experiment/specimen_report.h"
#include "app/experiment/triaxial/triaxial_campaign.h"
#include "solver/io/scene_toml.h"

namespace simsols {

// The triaxial tests at several confining stresses, on one prepared
// specimen, or on each of --seeds specimens.
int triaxial_campaign(const CampaignOptions& opt, const Scene& given, const std::string& base_name) {
  Scene base = given;
  for (const auto& [given, flag] : {std::pair{opt.sizes_given, "--sizes"},
                                    {opt.layers_given, "--layers"},
                                    {opt.displacement_given, "--displacement"},
                                    {opt.inertial_given, "--inertial-numbers"}})
    if (given)
      throw UsageError("not_applicable", flag,
                       "is not a triaxial campaign's flag; a triaxial campaign varies --stresses "
                       "(sigma_3) and --seeds");
  TriaxialCampaignSpec spec;
  if (opt.stresses_given) spec.stresses_kpa = opt.stresses_kpa;
  spec.seeds = opt.seeds_given ? opt.seeds : 1;
  spec.precision = precision_flag(opt.precision);
  refuse_profile(opt, base_name);
  InterruptScope interrupt;
  CampaignRun run = campaign_run(opt.cluster, opt.out_dir, interrupt.stop_function(), opt.quiet);
  const Specimen* specimen = base.specimen();
  const bool searches = specimen && (specimen->preparation.relative_density ||
                                     specimen->preparation.void_ratio ||
                                     specimen->preparation.tamping_layers > 0 ||
                                     specimen->preparation.expansion);
  if (searches && spec.seeds > 1)
    throw SceneError("not_applicable", base_name, 0, "triaxial.specimen.preparation",
                     "--seeds needs a specimen each campaign prepares by itself (pour or layers); "
                     "prepare each seed's scene with simsols run and campaign over its "
                     "scene.resolved.toml");
  if (searches && (opt.cluster.emitting() || run.only || run.collect))
    throw SceneError("not_applicable", base_name, 0, "triaxial.specimen.preparation",
                     "a cluster campaign needs its specimen prepared once first: run the base "
                     "with simsols run and campaign over its scene.resolved.toml");
  if (!opt.cluster.emitting() && !run.collect) run.device = open_command_device();
  // every test shears the same poured specimen: one search for its density
  if (searches) {
    const auto line = [&](const std::string& l) {
      if (!opt.quiet) std::fprintf(stderr, "[prepare] %s\n", l.c_str());
    };
    try {
      prepare_to_relative_density(base, run.device, opt.out_dir,
                                  PrepLog(line, interrupt.stop_function()));
    } catch (const PreparationStopped& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return interrupt.exit_status();
    }
  }
  std::vector<TriaxialCampaignTest> tests =
      plan_triaxial_campaign(base, base_name, spec, opt.out_dir);
  if (emit_or_check_plan(opt.cluster, "campaign", opt.command_line, opt.out_dir,
                         cluster_tests(tests)))
    return 0;
  const CampaignOutcome outcome = run_triaxial_campaign(tests, base_name, opt.out_dir, run);
  if (outcome.interrupted) {
    const TriaxialCampaignTest& t = tests[outcome.interrupted_test];
    return report_interrupted(outcome.interrupted_test, tests.size(), t.scene.name, t.dir,
                              interrupt);
  }
  return report_done(opt, run, tests.size(), run.only ? tests[*run.only].scene.name : "",
                     "triaxial tests");
}

}  // namespace simsols
