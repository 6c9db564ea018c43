// The oedometer test's pictures (render/plot/chart.h rasterises them):
//   e_log_sigma.png   void ratio vs vertical stress on a log axis, the end of
//                     each load step marked (loading and unloading branches),
//                     with Cc and Cs in the legend; the path between the ends
//                     (every row) drawn faintly
//   k0.png            K0 = sigma'_h / sigma'_v at the end of each step vs
//                     sigma'_v, with Jaky's 1 - sin(phi') when phi' is given
//   settlement.png    vertical strain vs time, the dial-gauge record of
//                     each increment
#pragma once

#include <string>
#include <vector>

#include "solver/apparatus/oedometer/oedometer_analysis.h"

namespace simsols {

void write_oedometer_plots(const std::string& dir, const std::string& title,
                           const std::vector<OedometerRow>& rows, const OedometerSummary& summary);

}  // namespace simsols
