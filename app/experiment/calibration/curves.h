// The curves a calibration compares: a target's measurement read from its
// CSV, a finished run's read from its rows file, both in SI units, and the
// points along x where the two are compared.
#pragma once

#include <string>
#include <vector>

#include "app/experiment/calibration/calibration_spec.h"
#include "solver/apparatus/registry.h"

namespace simsols {

// x and the target's y's (y[j] is target.y[j]), SI, in the rows' order.
struct Curve {
  std::vector<double> x;
  std::vector<std::vector<double>> y;
};

// The target's measurement: the rows its `where` keeps, its columns
// converted to SI. SceneError naming the data file and the column when a
// column is missing or a cell is not a number; when no row is kept.
Curve measured_curve(const CalibrationTarget& target);

// The curve of the test finished in `dir` (the kind's rows file, the rows
// of its curve_rows, the columns of the target's quantities). ReadError
// when the file or a column is missing.
Curve simulated_curve(const CalibrationTarget& target, const ApparatusKind& kind,
                      const std::string& dir);

// y at x, linear between the two rows of the first segment that reaches x
// (the rows in their order: a loading branch before an unloading one);
// NaN when no segment does.
double value_at(const std::vector<double>& xs, const std::vector<double>& ys, double x);

// Where a curve is compared: `points` x's evenly over the measured range,
// from its first row's x (left out: every curve starts there) to the
// largest.
std::vector<double> comparison_points(const Curve& measured, int points);

}  // namespace simsols
