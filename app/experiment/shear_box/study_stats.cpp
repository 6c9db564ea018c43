#include "app/experiment/shear_box/study_stats.h"

#include <boost/math/distributions/students_t.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

namespace simsols {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Moments {
  double mean = 0, var = 0;  // sample variance (n - 1)
  int n = 0;
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  m.n = static_cast<int>(x.size());
  if (m.n == 0) return m;
  for (double v : x) m.mean += v;
  m.mean /= m.n;
  if (m.n < 2) return m;
  for (double v : x) m.var += (v - m.mean) * (v - m.mean);
  m.var /= m.n - 1;
  return m;
}

}  // namespace

bool Interval::significant() const {
  return std::isfinite(half_width) && (lo() > 0 || hi() < 0);
}

double student_t_quantile(double p, double dof) {
  return boost::math::quantile(boost::math::students_t_distribution<double>(dof), p);
}

Interval mean_ci95(const std::vector<double>& x) {
  const Moments m = moments(x);
  Interval r;
  r.mean = m.mean;
  r.n = m.n;
  r.sd = std::sqrt(m.var);
  r.half_width = m.n < 2 ? kNaN : student_t_quantile(0.975, m.n - 1) * r.sd / std::sqrt(m.n);
  return r;
}

Interval difference_ci95(const std::vector<double>& a, const std::vector<double>& b) {
  const Moments ma = moments(a), mb = moments(b);
  Interval r;
  r.mean = ma.mean - mb.mean;
  r.n = std::min(ma.n, mb.n);
  if (ma.n < 2 || mb.n < 2) {  // a single run has no known spread
    r.half_width = kNaN;
    return r;
  }
  const double va = ma.var / ma.n, vb = mb.var / mb.n, se2 = va + vb;
  r.sd = std::sqrt(se2);
  if (se2 == 0) {  // both ensembles exact: so is the difference
    r.half_width = 0;
    return r;
  }
  const double dof = se2 * se2 / (va * va / (ma.n - 1) + vb * vb / (mb.n - 1));
  r.half_width = student_t_quantile(0.975, dof) * std::sqrt(se2);
  return r;
}

}  // namespace simsols
