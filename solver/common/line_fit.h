// The least-squares line y = a + b x through points, with the standard
// errors of its slope and intercept and R^2: the one fit behind the shear
// campaign's Mohr-Coulomb envelope, the triaxial envelope tangent to Mohr
// circles and its critical state line, and the oedometer's Cc and Cs.
#pragma once

#include <vector>

namespace simsols {

struct LineFit {
  double intercept = 0, slope = 0;
  double r2 = 0;
  int points = 0;
  bool fitted = false;  // two or more points with distinct x
  // One standard error each; NaN with two points (the line through them).
  double slope_se = 0, intercept_se = 0;
};

// Over the first min(x.size(), y.size()) points.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace simsols
