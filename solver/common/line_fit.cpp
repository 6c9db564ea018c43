#include "solver/common/line_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simsols {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit f;
  const size_t n = std::min(x.size(), y.size());
  f.points = static_cast<int>(n);
  if (n < 2) return f;
  double sx = 0, sy = 0;
  for (size_t i = 0; i < n; ++i) {
    sx += x[i];
    sy += y[i];
  }
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, ss_tot = 0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    ss_tot += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0) return f;
  f.fitted = true;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  double ss_res = 0;
  for (size_t i = 0; i < n; ++i) {
    const double e = y[i] - (f.intercept + f.slope * x[i]);
    ss_res += e * e;
  }
  f.r2 = ss_tot > 0 ? 1 - ss_res / ss_tot : 1;
  if (n == 2) {
    f.slope_se = f.intercept_se = std::numeric_limits<double>::quiet_NaN();
    return f;
  }
  const double s2 = ss_res / double(n - 2);
  f.slope_se = std::sqrt(s2 / sxx);
  f.intercept_se = std::sqrt(s2 * (1.0 / n + mx * mx / sxx));
  return f;
}

}  // namespace simsols
