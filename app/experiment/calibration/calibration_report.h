// What `simsols calibrate` writes into its folder, beside runs/:
//   parameters.csv     each parameter: its range, the calibrated value (the
//                      replicates'), the posterior's mean, standard
//                      deviation and 95 % interval
//   curves.csv         each measured curve at the calibrated values: the
//                      r.m.s. misfit of the replicates' mean, the
//                      specimens' own scatter (one specimen's standard
//                      deviation: no misfit can be resolved below it), the
//                      measurement's scatter when given, in its unit
//   design.csv         every simulation: round, design, target, the
//                      parameters, and a row per curve with its r.m.s.
//                      misfit
//   calibrated.toml    the calibrated values by scene key ([calibrated]),
//                      what `simsols predict` and the lab read
//   fit_<target>_<quantity>.png   the measured curve over the replicates
//   posterior_<parameter>.png     the parameter's marginal posterior
//   summary.txt        the same in key = value lines (written last)
#pragma once

#include <string>
#include <vector>

#include "app/experiment/calibration/calibration.h"

namespace simsols {

// What a reader of the result must know: a misfit D far above 1 at the
// calibrated values (the model does not reproduce the curves within the
// errors it knows of, and the intervals hold only if it did), a posterior
// resting on few effective samples, a calibrated value outside the final
// 95 % interval. Printed by the command, written into summary.txt.
std::vector<std::string> calibration_warnings(const CalibrationResult& result);

void write_calibration_report(const CalibrationSpec& spec, const CalibrationResult& result,
                              const std::string& out_dir);
// The fit_*.png and posterior_*.png of the list above.
void write_calibration_plots(const CalibrationSpec& spec, const CalibrationResult& result,
                             const std::string& out_dir);

}  // namespace simsols
