// What `simsols campaign` writes once its tests have run (see
// cmd_campaign.cpp), in OUT:
//   summary.csv, summary.md   one row per test: the peak (the first peak of
//                             tau/sigma), the largest tau/sigma, the residual
//                             (mean over the last 20 % of the shear), the
//                             dilatancy, the normal-stress band (its RMS,
//                             valid or not), tau/sigma at rest
//   d<size>mm_stress.png, d<size>mm_dilation.png   the curves of each size
//   mohr_coulomb.png, mohr_coulomb_residual.png    the envelopes
// The envelopes are fitted per bead size for the peak and for the residual
// strength over the valid tests (ShearSummary::valid), with c, phi, their standard errors and the number of points
// (two points: the exact line, said so; fit_mohr_coulomb in shear_analysis.h).
#pragma once

#include <string>
#include <vector>

#include "solver/apparatus/shear_box/shear_programme.h"

namespace simsols {

struct CampaignEntry {
  double d_mm = 0, s_kpa = 0;
  int layers = 0, beads = 0;
  std::vector<ShearRow> rows;
  ShearSummary summary;
};

void write_campaign_report(const std::string& out_dir, const std::string& base_name,
                           const std::vector<double>& sizes_mm,
                           const std::vector<CampaignEntry>& entries, double wall_seconds);

// "phi = 35.2 +- 0.4 deg, c = 1.1 +- 2.0 kPa (4 points, R^2 = 0.9991)" or,
// for two points, "... (2 points: the line through them, no error estimate)".
std::string describe_fit(const MohrCoulomb& fit);

}  // namespace simsols
