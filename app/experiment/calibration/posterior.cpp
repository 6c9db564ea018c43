#include "app/experiment/calibration/posterior.h"

#include <algorithm>
#include <boost/random/sobol.hpp>
#include <cmath>
#include <nlopt.hpp>
#include <numeric>
#include <random>

namespace simsols {

namespace {

// Samples of the posterior: enough for 2 % quantiles in each dimension.
int sample_count(int parameters) { return 4096 * parameters; }

// The weighted q-quantile of `v` (weights `w`, normalised).
double quantile(const Eigen::VectorXd& v, const Eigen::VectorXd& w, double q) {
  std::vector<int> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return v(a) < v(b); });
  double sum = 0;
  for (int i : order)
    if ((sum += w(i)) >= q) return v(i);
  return v(order.back());
}

Estimate estimate(const CalibrationParameter& p, const Eigen::VectorXd& u,
                  const Eigen::VectorXd& w, double best_u) {
  Eigen::VectorXd v(u.size());
  for (int i = 0; i < u.size(); ++i) v(i) = p.value(u(i));
  Estimate e;
  e.best = p.value(best_u);
  e.mean = w.dot(v);
  e.sd = std::sqrt(std::max(0.0, w.dot(v.cwiseProduct(v)) - e.mean * e.mean));
  e.lo95 = quantile(v, w, 0.025);
  e.hi95 = quantile(v, w, 0.975);
  return e;
}

// The mode: NLopt's bounded simplex (Subplex) on -log L from the best sample.
Eigen::VectorXd mode(const Comparison& c, const Surrogate& s, const Eigen::VectorXd& start) {
  struct Data {
    const Comparison& c;
    const Surrogate& s;
  } data{c, s};
  const auto objective = [](const std::vector<double>& x, std::vector<double>&, void* d) {
    const Data& dd = *static_cast<const Data*>(d);
    return -log_likelihood(dd.c, dd.s, Eigen::Map<const Eigen::VectorXd>(x.data(), x.size()));
  };
  const unsigned n = static_cast<unsigned>(start.size());
  nlopt::opt opt(nlopt::LN_SBPLX, n);
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_min_objective(objective, &data);
  opt.set_xtol_abs(1e-7);
  opt.set_maxeval(4000);
  std::vector<double> x(start.data(), start.data() + n);
  double f = 0;
  try {
    opt.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {  // x is still the best found
  }
  return Eigen::Map<Eigen::VectorXd>(x.data(), n);
}

}  // namespace

std::vector<double> curve_misfits(const Comparison& c, const Eigen::VectorXd& y,
                                  const Eigen::VectorXd& surrogate_error) {
  // Each curve's variance, pooled over its points (one s for the curve: a
  // point where every source of error happens to be small, the elastic
  // start, must not outweigh the rest), and its squared misses. A value
  // that cannot be predicted (NaN: not reached, or fitted exactly, with no
  // error to say) and a point the replicates did not all reach are left out.
  std::vector<double> var(c.curves, 0.0), miss(c.curves, 0.0);
  std::vector<int> count(c.curves, 0);
  for (int f = 0; f < y.size(); ++f) {
    const double e = surrogate_error(f), seed = c.seed_scatter(f);
    if (!std::isfinite(y(f)) || !std::isfinite(e) || !std::isfinite(seed)) continue;
    const int k = c.curve_of[f];
    var[k] += c.scatter(f) * c.scatter(f) + seed * seed + e * e;
    miss[k] += (y(f) - c.measured(f)) * (y(f) - c.measured(f));
    ++count[k];
  }
  std::vector<double> d(c.curves, NAN);
  for (int k = 0; k < c.curves; ++k)
    if (count[k] > 0) d[k] = miss[k] / std::max(var[k], 1e-300);
  return d;
}

double log_likelihood(const Comparison& c, const Surrogate& s, const Eigen::VectorXd& u) {
  const std::vector<double> d = curve_misfits(c, s.predict(u), s.loo_error());
  // One observation per test: its curves (of one specimen) averaged.
  std::vector<double> sum(c.tests, 0.0);
  std::vector<int> n(c.tests, 0);
  for (int k = 0; k < c.curves; ++k)
    if (std::isfinite(d[k])) sum[c.test_of[k]] += d[k], ++n[c.test_of[k]];
  double total = 0;
  for (int t = 0; t < c.tests; ++t)
    if (n[t] > 0) total += sum[t] / n[t];
  return -0.5 * total;
}

namespace {

// Samples of [lo, hi] (a Sobol sequence) and their normalised weights.
void weigh(const Comparison& c, const Surrogate& s, const Eigen::VectorXd& lo,
           const Eigen::VectorXd& hi, Posterior& p) {
  const int np = static_cast<int>(lo.size());
  p.u = sobol_designs(np, sample_count(np));
  for (int i = 0; i < p.u.rows(); ++i)
    p.u.row(i) = (lo + p.u.row(i).transpose().cwiseProduct(hi - lo)).transpose();
  Eigen::VectorXd logl(p.u.rows());
  for (int i = 0; i < p.u.rows(); ++i) logl(i) = log_likelihood(c, s, p.u.row(i).transpose());
  p.weight = (logl.array() - logl.maxCoeff()).exp().matrix();
  p.weight /= p.weight.sum();
  p.effective_samples = 1.0 / p.weight.squaredNorm();
}

}  // namespace

Posterior posterior(const CalibrationSpec& spec, const Comparison& c, const Surrogate& s) {
  const int np = static_cast<int>(spec.parameters.size());
  Posterior p;
  weigh(c, s, Eigen::VectorXd::Zero(np), Eigen::VectorXd::Ones(np), p);
  // A narrow posterior holds few of the ranges' samples: sample again the
  // box around every sample of weight above 1e-8 of the largest, widened by
  // one spacing of the first samples (the prior is uniform there too, and
  // the mass outside is below 1e-8 of the peak's).
  if (p.effective_samples < 1000) {
    const double spacing = std::pow(double(p.u.rows()), -1.0 / np);
    Eigen::VectorXd lo = Eigen::VectorXd::Ones(np), hi = Eigen::VectorXd::Zero(np);
    for (int i = 0; i < p.u.rows(); ++i)
      if (p.weight(i) > 1e-8 * p.weight.maxCoeff()) {
        lo = lo.cwiseMin(p.u.row(i).transpose());
        hi = hi.cwiseMax(p.u.row(i).transpose());
      }
    weigh(c, s, (lo.array() - spacing).max(0.0).matrix(), (hi.array() + spacing).min(1.0).matrix(), p);
  }
  Eigen::Index top = 0;
  p.weight.maxCoeff(&top);
  p.best_u = mode(c, s, p.u.row(top).transpose());
  for (int j = 0; j < np; ++j)
    p.estimates.push_back(estimate(spec.parameters[j], p.u.col(j), p.weight, p.best_u(j)));
  return p;
}

Eigen::MatrixXd draw_designs(const Posterior& p, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int np = static_cast<int>(p.u.cols());
  Eigen::VectorXd sd(np);
  for (int j = 0; j < np; ++j) {
    const double mean = p.weight.dot(p.u.col(j));
    sd(j) = std::sqrt(std::max(0.0, p.weight.dot(p.u.col(j).cwiseProduct(p.u.col(j))) - mean * mean));
  }
  Eigen::MatrixXd out(n, np);
  const double start = std::uniform_real_distribution<double>(0, 1.0 / n)(rng);
  double cumulative = 0;
  int i = 0;
  for (int k = 0; k < n; ++k) {
    const double target = start + double(k) / n;
    while (i + 1 < p.weight.size() && cumulative + p.weight(i) < target) cumulative += p.weight(i++);
    for (int j = 0; j < np; ++j) {
      const double step = std::normal_distribution<double>(0, 0.5 * sd(j) + 1e-3)(rng);
      out(k, j) = std::clamp(p.u(i, j) + step, 0.0, 1.0);
    }
  }
  return out;
}

Eigen::MatrixXd sobol_designs(int parameters, int n) {
  boost::random::sobol engine(static_cast<std::size_t>(parameters));
  const double scale = std::ldexp(1.0, -64);
  Eigen::MatrixXd out(n, parameters);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < parameters; ++j)
      out(i, j) = std::fmod(static_cast<double>(engine()) * scale + 0.5 / n, 1.0);
  return out;
}

}  // namespace simsols
