// The triaxial test's pictures (render/plot/chart.h rasterises them):
//   stress_ratio.png   q/p' vs axial strain, peak and critical state marked
//   deviator.png       q (kPa) vs axial strain, with p'
//   volumetric.png     volumetric strain vs axial strain (compression up)
//   e_log_p.png        void ratio vs p' on a log axis: the path to the
//                      critical state
#pragma once

#include <string>
#include <vector>

#include "solver/apparatus/triaxial/triaxial_analysis.h"

namespace simsols {

void write_triaxial_plots(const std::string& dir, const std::string& title,
                          const std::vector<TriaxialRow>& rows, const TriaxialSummary& summary);

}  // namespace simsols
