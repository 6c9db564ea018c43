// Ensemble statistics of the accuracy study: a result is the mean of an
// ensemble of runs with its 95 % confidence interval, and a setting's
// error is the difference of two ensemble means with its own interval.
//
// The interval of a mean is Student's: mean ± t(0.975, n − 1) s / √n, s
// the sample standard deviation. The interval of a difference of two means
// with unequal variances is Welch's: se = √(s_a²/n_a + s_b²/n_b) with the
// Welch–Satterthwaite degrees of freedom (s_a²/n_a + s_b²/n_b)² /
// ((s_a²/n_a)²/(n_a − 1) + (s_b²/n_b)²/(n_b − 1)). A difference is
// significant when its interval excludes zero. One run has no spread: its
// interval is unknown (NaN) and never significant; two exact ensembles (no
// spread at all) have an exact difference (half width 0).
// The t quantiles come from Boost.Math.
#pragma once

#include <vector>

namespace simsols {

struct Interval {
  double mean = 0;
  double half_width = 0;  // of the 95 % interval; NaN when unknown
  int n = 0;              // runs behind it
  double sd = 0;          // sample standard deviation (of a difference: its standard error)
  double lo() const { return mean - half_width; }
  double hi() const { return mean + half_width; }
  // The interval excludes zero (a known interval only).
  bool significant() const;
};

// The mean of `x` with its 95 % interval; n = 0 gives a zero mean.
Interval mean_ci95(const std::vector<double>& x);
// mean(a) − mean(b) with Welch's 95 % interval.
Interval difference_ci95(const std::vector<double>& a, const std::vector<double>& b);
// Student's t quantile: P(T < t) = p with `dof` degrees of freedom (> 0).
double student_t_quantile(double p, double dof);

}  // namespace simsols
