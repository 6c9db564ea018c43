#include "solver/apparatus/specimen/grading.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "solver/common/number_text.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kCurvePoints = 400;
constexpr int kSampleBins = 2000;

[[noreturn]] void refuse(const std::string& field, const std::string& message) {
  throw GradingError(field, message);
}

void require(bool ok, const std::string& field, double value, const std::string& allowed) {
  if (!ok) refuse(field, shortest_number(value) + " is out of range, allowed " + allowed);
}

// `points` sizes log-spaced over [lo, hi] with passing f(d), scaled to [0, 1].
template <class F>
GradingCurve tabulate(double lo, double hi, F f) {
  GradingCurve c;
  const double f_lo = f(lo), f_hi = f(hi);
  for (int k = 0; k <= kCurvePoints; ++k) {
    const double d = k == kCurvePoints ? hi : lo * std::pow(hi / lo, double(k) / kCurvePoints);
    c.size.push_back(d);
    c.passing.push_back(std::clamp((f(d) - f_lo) / (f_hi - f_lo), 0.0, 1.0));
  }
  return c;
}

GradingCurve lognormal(const Grading& g, double d50) {
  require(g.sigma > 0 && g.sigma <= 2, "sigma", g.sigma, "(0, 2]");
  const double lo = g.d_min > 0 ? g.d_min : d50 * std::exp(-2.5 * g.sigma);
  const double hi = g.d_max > 0 ? g.d_max : d50 * std::exp(2.5 * g.sigma);
  require(lo < d50, "d_min", lo, "(0, D50 = " + shortest_number(d50) + ")");
  require(hi > d50, "d_max", hi, "(D50 = " + shortest_number(d50) + ", inf)");
  return tabulate(lo, hi, [&](double d) {
    return 0.5 * std::erfc(-(std::log(d / d50)) / (g.sigma * std::sqrt(2.0)));
  });
}

GradingCurve sieve(const Grading& g) {
  const size_t n = g.sizes.size();
  if (n < 2 || g.passing.size() != n)
    refuse("sizes", "a sieve curve needs two or more sizes and as many passing values (" +
                        std::to_string(n) + " sizes, " + std::to_string(g.passing.size()) +
                        " passing)");
  GradingCurve c;
  for (size_t i = 0; i < n; ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    require(g.sizes[i] > 0 && (i == 0 || g.sizes[i] > g.sizes[i - 1]), "sizes" + at, g.sizes[i],
            i == 0 ? "(0, inf) m" : "(sizes[" + std::to_string(i - 1) + "], inf): increasing");
    const double low = i == 0 ? 0 : g.passing[i - 1];
    require(g.passing[i] >= low && g.passing[i] <= 100, "passing" + at, g.passing[i],
            "[" + shortest_number(low) + ", 100] %, non-decreasing");
    c.size.push_back(g.sizes[i]);
    c.passing.push_back(g.passing[i] / 100);
  }
  require(c.passing.front() == 0, "passing[0]", g.passing.front(),
          "0 %: the curve starts at its smallest size (the cut-off)");
  require(c.passing.back() == 1, "passing[" + std::to_string(n - 1) + "]", g.passing.back(),
          "100 %: the curve ends at its largest size");
  return c;
}

double uniform01(std::mt19937_64& engine) {
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

}  // namespace

double GradingCurve::passing_at(double d) const {
  if (d <= size.front()) return d < size.front() ? 0 : passing.front();
  if (d >= size.back()) return 1;
  const size_t i = std::upper_bound(size.begin(), size.end(), d) - size.begin() - 1;
  const double t = std::log(d / size[i]) / std::log(size[i + 1] / size[i]);
  return passing[i] + t * (passing[i + 1] - passing[i]);
}

double GradingCurve::size_at(double p) const {
  if (p <= passing.front()) return size.front();
  if (p >= passing.back()) return size.back();
  const size_t i = std::lower_bound(passing.begin(), passing.end(), p) - passing.begin();
  const double t = (p - passing[i - 1]) / (passing[i] - passing[i - 1]);
  return size[i - 1] * std::pow(size[i] / size[i - 1], t);
}

GradingCurve grading_curve(const Grading& g, double d50) {
  switch (g.law) {
    case Grading::Law::Single: return {{d50 * (1 - 1e-9), d50}, {0, 1}};
    case Grading::Law::LogNormal: return lognormal(g, d50);
    case Grading::Law::Uniform:
      require(g.d_min > 0, "d_min", g.d_min, "(0, d_max) m");
      require(g.d_max > g.d_min, "d_max", g.d_max, "(d_min, inf) m");
      return tabulate(g.d_min, g.d_max, [](double d) { return d; });
    case Grading::Law::Fuller:
      require(g.d_min > 0, "d_min", g.d_min, "(0, d_max) m");
      require(g.d_max > g.d_min, "d_max", g.d_max, "(d_min, inf) m");
      require(g.exponent > 0 && g.exponent <= 1.5, "exponent", g.exponent, "(0, 1.5]");
      return tabulate(g.d_min, g.d_max, [&](double d) { return std::pow(d, g.exponent); });
    case Grading::Law::Sieve: return sieve(g);
  }
  return {};
}

GradingCurve measured_curve(const std::vector<double>& diameters) {
  std::vector<double> d = diameters;
  std::sort(d.begin(), d.end());
  double total = 0;
  for (double x : d) total += x * x * x;
  GradingCurve c;
  c.size.push_back(d.front() * (1 - 1e-9));
  c.passing.push_back(0);
  double sum = 0;
  for (double x : d) {
    sum += x * x * x;
    if (x == c.size.back()) c.passing.back() = sum / total;
    else {
      c.size.push_back(x);
      c.passing.push_back(sum / total);
    }
  }
  c.passing.back() = 1;
  return c;
}

GradingStats grading_stats(const GradingCurve& c) {
  GradingStats s;
  s.d10 = c.size_at(0.1);
  s.d30 = c.size_at(0.3);
  s.d50 = c.size_at(0.5);
  s.d60 = c.size_at(0.6);
  s.cu = s.d60 / s.d10;
  s.cc = s.d30 * s.d30 / (s.d10 * s.d60);
  return s;
}

double sampling_error(const std::vector<double>& diameters, const GradingCurve& curve, double p) {
  double sum = 0, sum2 = 0;
  for (double d : diameters) {
    const double m = d * d * d;
    sum += m;
    sum2 += m * m;
  }
  const double n_eff = sum * sum / sum2;
  const double h = 0.02;
  const double slope = (curve.size_at(std::min(1.0, p + h)) - curve.size_at(std::max(0.0, p - h))) /
                       (std::min(1.0, p + h) - std::max(0.0, p - h));
  return slope * std::sqrt(p * (1 - p) / n_eff);
}

std::vector<double> sample_diameters(const GradingCurve& curve, double solid_volume,
                                     std::uint64_t seed) {
  const double lo = curve.size.front(), hi = curve.size.back();
  std::vector<double> edge(kSampleBins + 1), cdf(kSampleBins + 1, 0.0);
  for (int k = 0; k <= kSampleBins; ++k) edge[k] = lo * std::pow(hi / lo, double(k) / kSampleBins);
  for (int k = 0; k < kSampleBins; ++k) {
    const double mass = curve.passing_at(edge[k + 1]) - curve.passing_at(edge[k]);
    const double mid = std::sqrt(edge[k] * edge[k + 1]);
    cdf[k + 1] = cdf[k] + std::max(0.0, mass) / (mid * mid * mid);
  }
  std::mt19937_64 engine(seed);
  std::vector<double> out;
  double volume = 0;
  while (volume < solid_volume) {
    const double u = uniform01(engine) * cdf.back();
    const size_t k = std::min<size_t>(
        kSampleBins - 1, std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin() - 1);
    const double d = edge[k] * std::pow(edge[k + 1] / edge[k], uniform01(engine));
    out.push_back(d);
    volume += kPi / 6 * d * d * d;
  }
  return out;
}

std::string grading_report(const GradingCurve& asked, const std::vector<double>& diameters) {
  const GradingCurve got = measured_curve(diameters);
  const GradingStats a = grading_stats(asked), g = grading_stats(got);
  std::string out;
  char buf[200];
  const struct {
    const char* name;
    double p, asked, got;
  } rows[] = {{"D10", 0.1, a.d10, g.d10}, {"D30", 0.3, a.d30, g.d30}, {"D50", 0.5, a.d50, g.d50},
              {"D60", 0.6, a.d60, g.d60}};
  for (const auto& r : rows) {
    std::snprintf(buf, sizeof buf, "%s_mm = %.5g  # asked %.5g, sampling error %.2g\n", r.name,
                  r.got * 1e3, r.asked * 1e3, sampling_error(diameters, asked, r.p) * 1e3);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "Cu = %.4g  # asked %.4g\nCc = %.4g  # asked %.4g\n", g.cu, a.cu,
                g.cc, a.cc);
  out += buf;
  return out;
}

}  // namespace simsols
