// What the calibration concludes from its simulations: the likelihood of a
// parameter set given the measured curves, the posterior over the ranges,
// the most likely set, and the next round's designs drawn from it.
//
// The model of the error. At comparison point k of a curve, the simulated
// value S_k(u) (the surrogate's) misses the measured m_k. The error it may
// have is s_k^2 = scatter^2 + seed_k^2 + surrogate_k^2: the measurement's
// scatter (given by the user, or 0), the specimens' seed-to-seed standard
// deviation (from the replicates, 0 before them) and the surrogate's
// leave-one-out error. The points of one curve are not independent (a
// specimen that is stronger is stronger all along), and the curves of one
// test are of one specimen, so each test counts as one observation:
//   D_curve = mean_k (S_k - m_k)^2 / mean_k s_k^2   (the variance pooled
//             over the curve, so no point where every error is small, the
//             elastic start, outweighs the rest),
//   log L(u) = -1/2 sum over tests of (mean of the test's D_curve).
// The prior is uniform over the ranges (in log for a log-scale
// parameter). The posterior is sampled by weighting a Sobol sequence of
// the ranges (importance sampling from the prior); when that leaves fewer
// than 1000 effective samples, a second sequence covers the box that
// holds the first one's weight and the weights are taken again there. The
// effective sample size is reported.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "app/experiment/calibration/calibration_spec.h"
#include "app/experiment/calibration/surrogate.h"

namespace simsols {

// The compared values, flattened: value f belongs to curve curve_of[f],
// curve k to test test_of[k].
struct Comparison {
  Eigen::VectorXd measured;      // m_f, SI
  Eigen::VectorXd scatter;       // the measurement's standard deviation, SI (0 when not given)
  Eigen::VectorXd seed_scatter;  // the specimens', SI (0 until the replicates ran)
  std::vector<int> curve_of;
  std::vector<int> test_of;
  int curves = 0;
  int tests = 0;
};

// log L(u) of the surrogate's prediction at u, as above.
double log_likelihood(const Comparison& c, const Surrogate& s, const Eigen::VectorXd& u);
// Each curve's misfit D of values `y` (the same order as c.measured), NaN
// for a curve none of whose points can be compared.
std::vector<double> curve_misfits(const Comparison& c, const Eigen::VectorXd& y,
                                  const Eigen::VectorXd& surrogate_error);

struct Estimate {
  double best = 0;  // the most likely value (the posterior's mode, NLopt on log L)
  double mean = 0, sd = 0, lo95 = 0, hi95 = 0;
};

struct Posterior {
  Eigen::MatrixXd u;        // samples (M x P), scaled
  Eigen::VectorXd weight;   // normalised
  Eigen::VectorXd best_u;   // the mode, scaled
  std::vector<Estimate> estimates;  // per parameter, in its own unit
  double effective_samples = 0;
};

Posterior posterior(const CalibrationSpec& spec, const Comparison& c, const Surrogate& s);

// n designs for the next round: the posterior's samples drawn by their
// weights (systematic resampling), each moved by a normal step of half the
// posterior's standard deviation in u, kept in [0, 1]; reproducible from
// `seed`.
Eigen::MatrixXd draw_designs(const Posterior& p, int n, std::uint64_t seed);

// The first round's n designs: a Sobol sequence over [0, 1]^P shifted by
// half a step, so no design sits on a range's end.
Eigen::MatrixXd sobol_designs(int parameters, int n);

}  // namespace simsols
