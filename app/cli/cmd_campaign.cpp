// simsols campaign: the reference paper's programme of direct shear tests,
// 5 bead sizes (its Table 1) x 4 normal stresses (50, 160, 280, 400 kPa),
// or any subset, any sizes and stresses; on a triaxial base scene, its
// test at several confining stresses. Each kind's campaign is in
// campaign/ (campaign_command.h), listed in the table below.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/campaign/campaign_command.h"
#include "app/cli/commands.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

// The campaigns, one for each apparatus kind that has one (registry.h's
// names); the base scene's kind picks it.
struct CampaignKind {
  const char* kind;
  int (*run)(const CampaignOptions& opt, const Scene& base, const std::string& base_name);
};
constexpr CampaignKind kCampaigns[] = {{"shear_box", shear_box_campaign},
                                       {"triaxial", triaxial_campaign},
                                       {"periodic_cell", periodic_cell_campaign}};

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
      "Run the paper's direct shear programme (5 sizes x 4 stresses), a triaxial test at "
      "several confining stresses, or a periodic cell at several pressures and inertial numbers; "
      "resumable");
  cmd->add_option("base", opt->base,
                  "Base scene: a shear box (default: the built-in shear_box.toml) or a triaxial "
                  "cell");
  cmd->add_option("--out,-o", opt->out_dir, "Output folder (rerun to resume)");
  CLI::Option* sizes =
      cmd->add_option("--sizes", opt->sizes_mm, "Bead diameters in mm (default: Table 1)")
          ->delimiter(',');
  CLI::Option* stresses =
      cmd->add_option("--stresses", opt->stresses_kpa,
                      "Normal stresses in kPa (default 50,160,280,400), a triaxial "
                      "campaign's confining stresses (default 50,100,200) or a periodic cell's "
                      "pressures (default: the base scene's)")
          ->delimiter(',');
  CLI::Option* layers =
      cmd->add_option("--layers", opt->layers, "Layers for every size (default: Table 1)");
  cmd->add_option("--precision", opt->precision, "float or double (default: the base scene's)");
  cmd->add_option("--profile", opt->profile,
                  "paper (the base scene's settings, default) or fast (shear box: dt 0.5 x "
                  "Rayleigh, I 2e-3; docs/accuracy.md)");
  CLI::Option* displacement =
      cmd->add_option("--displacement", opt->displacement_mm,
                      "Horizontal displacement to shear, mm (default: the base scene's)");
  CLI::Option* inertial =
      cmd->add_option("--inertial-numbers", opt->inertial_numbers,
                      "A periodic cell's inertial numbers (default: the base scene's)")
          ->delimiter(',');
  CLI::Option* seeds = cmd->add_option(
      "--seeds", opt->seeds,
      "Specimens per point: the base's seed and the next (a periodic cell: default 3; a shear "
      "or triaxial campaign: default 1, its strengths then an example, not an ensemble)");
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
    opt->inertial_given = inertial->count() > 0;
    opt->seeds_given = seeds->count() > 0;
    opt->command_line = given_args(cmd, {"base", "--out"});
    return campaign(*opt);
  };
}

}  // namespace simsols
