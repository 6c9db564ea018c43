// What `simsols campaign` writes once its tests have run (see
// cmd_campaign.cpp), in OUT:
//   summary.csv, summary.md   one row per test (size, stress, seed): the
//                             peak (the first peak of the smoothed tau/sigma),
//                             the largest tau/sigma, the residual (at the
//                             critical state, or the last 20 % flagged), the
//                             dilatancy and Taylor's energy check, the
//                             normal-stress band (valid or not), tau/sigma at rest
//   ensemble.csv              per size and stress, over the valid specimens (seeds):
//                             the means of the strengths with their 95 %
//                             Student intervals
//   envelopes.csv             per size, the Mohr-Coulomb envelopes
//   d<size>mm_stress.png, d<size>mm_dilation.png   the curves of each size
//                             (the first specimen's)
//   mohr_coulomb.png, mohr_coulomb_residual.png    the envelopes
// The envelopes (fit_mohr_coulomb in shear_analysis.h) are fitted per bead
// size for the peak and for the residual strength, over the valid tests
// (ShearSummary::valid). With several specimens, each specimen's envelope
// over its stresses is fitted, and phi and c are the means of those fits
// with their 95 % Student intervals over the specimens: the stresses of one
// seed start from the same placement, so their points are not independent,
// while the specimens are. With one specimen: that specimen's fit, with the
// standard errors of the least squares (an example, not a strength).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/shear_box/shear_programme.h"

namespace simsols {

struct CampaignEntry {
  double d_mm = 0, s_kpa = 0;
  std::int64_t seed = 0;  // its specimen's
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

// An envelope over specimens from each specimen's own fit (each with two
// or more points): one fit's phi and c with their standard errors, or the
// mean of the fits' phi and c with its 95 % Student interval. The shear
// and the triaxial campaigns report their envelopes with it.
struct SpecimensEnvelope {
  int specimens = 0;
  double phi_deg = 0, phi_spread_deg = 0, c_kpa = 0, c_spread_kpa = 0;
  double mean_r2 = 0;
  bool ci95() const { return specimens > 1; }  // else the spreads are one fit's standard errors
};
SpecimensEnvelope specimens_envelope(const std::vector<MohrCoulomb>& fits);

}  // namespace simsols
