// What a triaxial campaign writes once its tests have run
// (triaxial_campaign.h), in OUT:
//   summary.csv, summary.md   one row per test (sigma_3): e after
//                             consolidation, the peak (angle, q/p', axial
//                             strain, s_1 and s_3) and the critical state
//                             (angle, e, p'), the dilatancy, the wall vs
//                             internal stress gap; then the envelopes and
//                             the critical state line with their errors
//   stress_ratio.png, volumetric.png   the curves of every test on common axes
//   mohr_peak.png, mohr_critical.png   the Mohr circles with the envelope
//                                      tangent to them (equal axis scales)
//   csl.png                            e-log p' paths, critical states, the line
// The fits are in triaxial_analysis.h (fit_mohr_circles,
// fit_critical_state_line); two tests give the line through them, said so.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/triaxial/triaxial_analysis.h"

namespace simsols {

struct TriaxialCampaignEntry {
  double s_kpa = 0;
  std::int64_t seed = 0;  // its specimen's
  int beads = 0;
  std::vector<TriaxialRow> rows;
  TriaxialSummary summary;
};

void write_triaxial_campaign_report(const std::string& out_dir, const std::string& base_name,
                                    const std::vector<TriaxialCampaignEntry>& entries,
                                    double wall_seconds);

}  // namespace simsols
