// A calibration as the user writes it (docs/calibration.md): the
// parameters to fit with their ranges, the measured curves with the test
// that should reproduce each, and the budget of simulations.
//
//   [calibration]   budget, rounds, replicates, points (per curve)
//   [[parameters]]  name, key (the scene key it sets, a dotted path:
//                   "materials.sand.sliding_friction" picks the material
//                   called sand), min, max, scale ("linear" | "log")
//   [[targets]]     name, scene (the test), data (the measured CSV),
//                   where ("column=value": the rows kept), set (scene
//                   keys fixed for this target alone), zero_at (every y
//                   relative to its value at this x), x and [[targets.y]]:
//                   column, unit and quantity (what the apparatus
//                   measures, registry.h CurveQuantity), y's scatter
//
// read_calibration() checks every field (ranges, units against the
// quantity's dimension, files present, the quantity known to the scene's
// apparatus) and reports all problems with file, line and field
// (SceneError). Paths are relative to the calibration file.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace simsols {

struct CalibrationParameter {
  std::string name;  // a label: "mu_s"
  std::string key;   // the scene key it sets
  double min = 0, max = 1;
  bool log_scale = false;
  // The value at u in [0, 1] of its range (linear, or linear in log).
  double value(double u) const;
  double unit_of(double value) const;  // the inverse
};

// One measured column and what it is: its unit's factor to SI.
struct CurveColumn {
  std::string column;    // in the measured CSV
  std::string unit;      // "-", "%", "Pa", "kPa", "MPa", "m", "mm"
  std::string quantity;  // the apparatus' name for it (CurveQuantity::name)
  std::optional<double> scatter;  // in `unit`: the measurement's standard deviation
};

struct CalibrationTarget {
  std::string name;
  std::string scene;  // path, resolved against the calibration file
  std::string data;   // path, ditto
  std::string where;  // "column=value", or ""
  std::vector<std::pair<std::string, double>> set;  // scene keys for this target alone
  // When set: every y is taken relative to its value at this x (in x's
  // unit), on the measured and the simulated curve alike: curves compared
  // from a state both reach (an oedometer's strain from its first load).
  std::optional<double> zero_at;
  CurveColumn x;
  std::vector<CurveColumn> y;
};

struct CalibrationSpec {
  std::string path;  // the file
  std::string name;
  int budget = 16;      // simulations of the design, all rounds
  int rounds = 2;       // the first over the ranges, the next ones from the posterior
  int replicates = 3;   // specimens at the calibrated values
  int points = 12;      // of each curve compared
  std::vector<CalibrationParameter> parameters;
  std::vector<CalibrationTarget> targets;
  // The simulations of round r (0-based): the budget split evenly, the
  // first rounds taking the remainder.
  int round_size(int r) const;
};

// The unit's factor to SI and its dimension ("", "stress", "length");
// nullopt when the unit is not one of those listed above.
std::optional<std::pair<double, std::string>> unit_factor(const std::string& unit);

CalibrationSpec read_calibration(const std::string& path);

// A prediction (`simsols predict`, prediction.h): tests run with a
// calibrated material on several specimens.
//   [prediction]  calibrated (a calibration's calibrated.toml), specimens,
//                 points (of each band), at (x's, in the tests' x unit,
//                 where every y is reported per specimen)
//   [[tests]]     as a calibration's [[targets]], with data optional: a
//                 measured curve, when given, is drawn over the band and
//                 the prediction's error against it reported
struct PredictionSpec {
  std::string path, name, calibrated;
  int specimens = 5;
  int points = 40;
  std::vector<double> at;
  std::vector<CalibrationTarget> tests;  // data "" when none
};
PredictionSpec read_prediction(const std::string& path);

// The [calibrated] values of a calibration's calibrated.toml, by scene key.
std::vector<std::pair<std::string, double>> read_calibrated(const std::string& path);
// Its [[measured]] curves (the calibration's targets); none in a file
// written by hand.
std::vector<CalibrationTarget> read_calibrated_measured(const std::string& path);

}  // namespace simsols
