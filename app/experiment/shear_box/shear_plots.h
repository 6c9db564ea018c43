// The direct shear test's pictures, drawn like the reference paper's
// Figures 3-7 (render/plot/chart.h rasterises them to PNG):
//   one test:      shear_stress.png   tau (kPa) vs horizontal displacement (mm), the peak
//                                     (first peak) marked, and a later maximum, labelled so
//                  shear_ratio.png    tau/sigma vs horizontal displacement
//                  dilation.png       vertical vs horizontal displacement (dilation up)
//   a bead size:   <size>_stress.png / <size>_dilation.png, one curve per normal stress
//   the envelopes: mohr_coulomb.png, mohr_coulomb_residual.png: peak and
//                  residual tau vs sigma with the fitted lines
#pragma once

#include <string>
#include <vector>

#include "solver/apparatus/shear_box/shear_programme.h"

namespace simsols {

void write_shear_plots(const std::string& dir, const std::string& title,
                       const std::vector<ShearRow>& rows, const ShearSummary& summary);

struct ShearCurve {
  std::string label;  // e.g. "160 kPa"
  std::vector<ShearRow> rows;
  ShearSummary summary;
};
// Curves of one bead size on common axes: tau and dilation vs displacement.
void write_size_plots(const std::string& stress_png, const std::string& dilation_png,
                      const std::string& title, const std::vector<ShearCurve>& curves);

struct EnvelopeSeries {
  std::string label;                  // bead size
  std::vector<double> sigma, tau;     // Pa: the peaks, or the residuals
  double cohesion = 0, tan_phi = 0;   // fitted tau = c + sigma tan(phi)
};
// `which`: "peak" or "residual", in the title and the axis.
void write_envelope_plot(const std::string& png, const std::string& which,
                         const std::vector<EnvelopeSeries>& sizes);

}  // namespace simsols
