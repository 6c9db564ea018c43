// The campaign command's pieces every kind's campaign shares: its options
// as read from the command line (cmd_campaign.cpp) and its closing lines.
// Each kind that has a campaign has its file here (shear_box_campaign.cpp,
// triaxial_campaign.cpp), listed in cmd_campaign.cpp's table.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/cluster_flags.h"
#include "app/cli/interrupt.h"
#include "app/experiment/campaign_loop.h"
#include "solver/scene/scene.h"

namespace simsols {

struct CampaignOptions;
// --profile other than paper on a campaign it was not measured for.
void refuse_profile(const CampaignOptions& opt, const std::string& base_name);

struct CampaignOptions {
  std::string base;  // empty = the built-in shear_box.toml (kDefaultSceneName)
  std::string out_dir;
  std::vector<double> sizes_mm{2.38125, 3.175, 3.96875, 4.7625, 6.35};
  std::vector<double> stresses_kpa{50, 160, 280, 400};
  int layers = 0;  // 0 = Table 1
  std::string precision;
  std::string profile = "paper";  // --profile (run_profile.h)
  double displacement_mm = 0;  // 0 = the base scene's
  std::vector<double> inertial_numbers;  // a periodic cell's; empty = the base scene's
  int seeds = 3;  // specimens per point (a shear campaign: 1 unless given)
  bool quiet = false;
  // Flags given on the command line (the triaxial campaign refuses the
  // shear box's and has its own default stresses).
  bool sizes_given = false, stresses_given = false, layers_given = false,
       displacement_given = false, inertial_given = false, seeds_given = false;
  ClusterFlags cluster;
  std::vector<std::string> command_line;  // plans the same tests again (given_args)
};

// What a campaign run with the cluster flags says at its end; 0.
int report_done(const CampaignOptions& opt, const CampaignRun& run, size_t count,
                const std::string& name_of_only, const char* what);

// What an interrupted campaign says; the interrupt's exit status.
int report_interrupted(size_t k, size_t count, const std::string& name,
                       const std::filesystem::path& dir, const InterruptScope& interrupt);

// Each kind's campaign: the base scene's tests, planned, run (or emitted
// as a cluster's array) and reported; the command's exit status.
int shear_box_campaign(const CampaignOptions& opt, const Scene& base, const std::string& base_name);
int triaxial_campaign(const CampaignOptions& opt, const Scene& base, const std::string& base_name);
int periodic_cell_campaign(const CampaignOptions& opt, const Scene& base, const std::string& base_name);

}  // namespace simsols
