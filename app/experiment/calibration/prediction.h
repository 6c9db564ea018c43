// `simsols predict`: tests run with a calibrated material on several
// specimens, drawn as a band, with the measured curve over it when one is
// given (docs/calibration.md).
//
// Each test of the prediction file (calibration_spec.h) runs with the
// calibrated values and its own keys set, on `specimens` specimens (the
// kind's seed key = 2001, 2002, ...: specimens no calibration ran), into OUT/<test>/s<seed>/. The band of each
// y is the specimens' mean and standard deviation, their least and largest
// value, at `points` x's (over the measured range when there is a
// measurement, else over the range every specimen reached). For each
// specimen the y's peak (of its curve averaged over a twentieth of the x
// range, so one row's tooth is not the peak), the x at the peak and the y
// at each `at` are kept, so a prediction states a scalar with its
// interval. Resumable like
// the calibration.
#pragma once

#include <string>
#include <vector>

#include "app/experiment/calibration/calibration.h"

namespace simsols {

struct PredictedCurve {
  std::string test, quantity, unit, x_quantity, x_unit;  // units: the test's columns'
  std::vector<double> x, mean, sd, lo, hi, measured;  // SI; measured NaN without data
  // Half the 95 % prediction interval of one more specimen, t(n-1) sd
  // sqrt(1 + 1/n): where a measurement of the same test should fall.
  std::vector<double> half_width;
  std::vector<double> peak, x_at_peak;                // per specimen, SI
  std::vector<std::vector<double>> at;                // [at index][specimen], SI
  // Against the measurement (NaN without one): the r.m.s. of mean - measured,
  // the r.m.s. of the specimens' sd, and the share of the measured points
  // inside the prediction interval (a point the band does not reach counts
  // as outside).
  double rms_error = NAN, rms_sd = NAN, inside = NAN;
};

struct PredictionResult {
  bool interrupted = false;
  std::string interrupted_dir;
  bool ended = false;  // on a cluster: the job written or a task run, no result
  std::vector<PredictedCurve> curves;         // per test, per y
  std::vector<std::vector<Curve>> specimens;  // per test, per specimen
  std::vector<Curve> measured;                // per test; empty without data
  double seconds = 0;
};

PredictionResult run_prediction(const PredictionSpec& spec, const CalibrationOptions& options);

// OUT/band_<test>_<quantity>.csv (x, mean, sd, lo, hi, measured in the
// test's units), predict_<test>_<quantity>.png, specimens.csv (each
// specimen's peak, x at the peak and y at each `at`), prediction.csv (per
// test and y: the specimens' mean of those with Student's 95 % interval,
// and the error against the measurement), summary.txt last.
void write_prediction_report(const PredictionSpec& spec, const PredictionResult& result,
                             const std::string& out_dir);

}  // namespace simsols
