// simsols campaign: the reference paper's programme of direct shear tests,
// 5 bead sizes (its Table 1) x 4 normal stresses (50, 160, 280, 400 kPa),
// or any subset, any sizes and stresses (app/experiment/campaign.h); on a
// triaxial base scene, its test at several confining stresses
// (app/experiment/triaxial_campaign.h).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/cluster_flags.h"
#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/experiment/campaign.h"
#include "app/experiment/paper_tests.h"
#include "app/experiment/specimen_report.h"
#include "app/experiment/triaxial_campaign.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

struct CampaignOptions {
  std::string base;  // empty = the built-in shear_box.toml (kDefaultSceneName)
  std::string out_dir;
  std::vector<double> sizes_mm{2.38125, 3.175, 3.96875, 4.7625, 6.35};
  std::vector<double> stresses_kpa{50, 160, 280, 400};
  int layers = 0;  // 0 = Table 1
  std::string precision;
  double displacement_mm = 0;  // 0 = the base scene's
  bool quiet = false;
  // Flags given on the command line (the triaxial campaign refuses the
  // shear box's and has its own default stresses).
  bool sizes_given = false, stresses_given = false, layers_given = false,
       displacement_given = false;
  ClusterFlags cluster;
  std::vector<std::string> command_line;  // plans the same tests again (given_args)
};

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

// The triaxial tests at several confining stresses, on one prepared specimen.
int triaxial_campaign(const CampaignOptions& opt, const Scene& given, const std::string& base_name) {
  Scene base = given;
  for (const auto& [given, flag] : {std::pair{opt.sizes_given, "--sizes"},
                                    {opt.layers_given, "--layers"},
                                    {opt.displacement_given, "--displacement"}})
    if (given)
      throw UsageError("not_applicable", flag,
                       "is a shear-box flag; a triaxial campaign varies --stresses (sigma_3)");
  TriaxialCampaignSpec spec;
  if (opt.stresses_given) spec.stresses_kpa = opt.stresses_kpa;
  spec.precision = precision_flag(opt.precision);
  InterruptScope interrupt;
  CampaignRun run = campaign_run(opt.cluster, opt.out_dir, interrupt.stop_function(), opt.quiet);
  const Specimen* specimen = base.specimen();
  const bool searches = specimen && (specimen->preparation.relative_density ||
                                     specimen->preparation.void_ratio ||
                                     specimen->preparation.tamping_layers > 0 ||
                                     specimen->preparation.expansion);
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

// The paper's programme (Table 1's sizes x the stresses) in a shear box.
int shear_campaign(const CampaignOptions& opt, const Scene& base, const std::string& base_name) {
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
  spec.displacement_mm = opt.displacement_mm;
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

// The campaigns, one for each apparatus kind that has one (registry.h's
// names); the base scene's kind picks it.
struct CampaignKind {
  const char* kind;
  int (*run)(const CampaignOptions& opt, const Scene& base, const std::string& base_name);
};
constexpr CampaignKind kCampaigns[] = {{"shear_box", shear_campaign},
                                       {"triaxial", triaxial_campaign}};

int campaign(const CampaignOptions& opt) {
  // Everything is checked and every scene built before anything runs.
  const std::string base_name = opt.base.empty() ? kDefaultSceneName : opt.base;
  const Scene base = opt.base.empty() ? default_shear_base() : load_scene(opt.base);
  const ApparatusKind& kind = required_apparatus_kind(base);
  if (const CampaignKind* c = entry_for_kind<CampaignKind>(kCampaigns, kind.name))
    return c->run(opt, base, base_name);
  std::string names;
  for (const CampaignKind& c : kCampaigns) names += (names.empty() ? "" : ", ") + std::string(c.kind);
  throw SceneError("not_applicable", base_name, 0, kind.name,
                   std::string(kind.test_noun) + " has no campaign over stresses (a scene's own "
                   "programme runs it); the campaigns take: " + names);
}

}  // namespace

CommandRunner add_campaign_command(CLI::App& app) {
  auto opt = std::make_shared<CampaignOptions>();
  CLI::App* cmd = app.add_subcommand(
      "campaign",
      "Run the paper's direct shear programme (5 sizes x 4 stresses), or a triaxial test at "
      "several confining stresses; resumable");
  cmd->add_option("base", opt->base,
                  "Base scene: a shear box (default: the built-in shear_box.toml) or a triaxial "
                  "cell");
  cmd->add_option("--out,-o", opt->out_dir, "Output folder (rerun to resume)");
  CLI::Option* sizes =
      cmd->add_option("--sizes", opt->sizes_mm, "Bead diameters in mm (default: Table 1)")
          ->delimiter(',');
  CLI::Option* stresses =
      cmd->add_option("--stresses", opt->stresses_kpa,
                      "Normal stresses in kPa (default 50,160,280,400), or a triaxial "
                      "campaign's confining stresses (default 50,100,200)")
          ->delimiter(',');
  CLI::Option* layers =
      cmd->add_option("--layers", opt->layers, "Layers for every size (default: Table 1)");
  cmd->add_option("--precision", opt->precision, "float or double (default: the base scene's)");
  CLI::Option* displacement =
      cmd->add_option("--displacement", opt->displacement_mm,
                      "Horizontal displacement to shear, mm (default: the base scene's)");
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress lines");
  add_cluster_flags(cmd, opt->cluster);
  return [=] {
    if (!opt->cluster.collect.empty())
      return collect_from_manifest(opt->cluster, "campaign", add_campaign_command);
    if (opt->out_dir.empty())
      throw UsageError("missing_field", "--out", "give an output folder (rerun to resume)");
    opt->sizes_given = sizes->count() > 0;
    opt->stresses_given = stresses->count() > 0;
    opt->layers_given = layers->count() > 0;
    opt->displacement_given = displacement->count() > 0;
    opt->command_line = given_args(cmd, {"base", "--out"});
    return campaign(*opt);
  };
}

}  // namespace simsols
