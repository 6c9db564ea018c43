// Grading: a specimen's sizes from a grading curve, as a laboratory states
// them: the mass fraction passing each sieve size (docs/specimens.md).
//
// The curve is a law or a sieve table (Grading, scene.h), turned into a
// table of (size, passing) points, increasing in both, from 0 to 1;
// between points passing is linear in log(size), as a semi-log sieve plot
// draws it. The laws:
//   uniform    passing linear in d between d_min and d_max (mass uniform);
//   lognormal  ln d normal by mass, median D50 = specimen.diameter, standard
//              deviation sigma, cut at d_min and d_max (default
//              D50 e^(-/+ 2.5 sigma)) and renormalised;
//   fuller     the Fuller-Talbot curve P = (d / d_max)^n, its fines below
//              d_min cut off: P = (d^n - d_min^n) / (d_max^n - d_min^n);
//   sieve      the table as given (% passing from 0 to 100).
//
// Sampling: the specimen is a list of diameters drawn one by one until
// their volume reaches the target. A sieve curve counts mass, so a size is
// drawn with the number weight dP(d) / d^3, over 2 000 log-spaced bins
// (within a bin, log-uniform). Seeded: the same seed gives the same sizes
// on every platform.
//
// Statistics: D10, D30, D50, D60, C_u = D60 / D10 and C_c = D30^2 /
// (D10 D60) of a curve, and of the drawn sizes' own mass curve. The
// sampling error of a drawn D_p: the mass-weighted empirical curve's
// standard error at p, sqrt(p (1 - p) / n_eff) with n_eff = (sum m)^2 /
// sum m^2, carried to size through the curve's local slope.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "solver/scene/scene.h"

namespace simsols {

struct GradingCurve {
  std::vector<double> size;     // m, increasing
  std::vector<double> passing;  // mass fraction, from 0 to 1, non-decreasing
  double passing_at(double d) const;
  double size_at(double p) const;  // D_p (p in [0, 1])
};

// A grading that cannot be: `field` under the grading table ("d_max",
// "passing[3]"), what() the value and the allowed range.
struct GradingError : std::invalid_argument {
  GradingError(std::string f, const std::string& message)
      : std::invalid_argument(message), field(std::move(f)) {}
  std::string field;
};

// The curve of `g` for a specimen of reference diameter `d50` (the
// lognormal law's median). Throws GradingError.
GradingCurve grading_curve(const Grading& g, double d50);

// The drawn sizes' mass curve (the empirical sieve curve).
GradingCurve measured_curve(const std::vector<double>& diameters);

struct GradingStats {
  double d10 = 0, d30 = 0, d50 = 0, d60 = 0;  // m
  double cu = 0, cc = 0;
};
GradingStats grading_stats(const GradingCurve& c);

// The standard error (m) of D_p of `diameters` (see above), through the
// slope of `curve` at p.
double sampling_error(const std::vector<double>& diameters, const GradingCurve& curve, double p);

// Diameters drawn from `curve` until their volume reaches `solid_volume`.
std::vector<double> sample_diameters(const GradingCurve& curve, double solid_volume,
                                     std::uint64_t seed);

// "D50 = 2.012 mm (asked 2.000, sampling error 0.011)" lines, one per
// statistic, for the run's grading.txt.
std::string grading_report(const GradingCurve& asked, const std::vector<double>& diameters);

}  // namespace simsols
