// Grading curves (solver/apparatus/specimen/grading.h): the laws against their
// formulas, sizes drawn to a curve within their sampling error, the same
// seed giving the same sizes, bad curves refused by field, and a graded
// pour that settles (in float: the case that once met a negative overlap).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/apparatus/specimen/grading.h"
#include "solver/apparatus/oedometer/oedometer_programme.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;

Grading law(Grading::Law l, double d_min = 0, double d_max = 0) {
  Grading g;
  g.law = l;
  g.d_min = d_min;
  g.d_max = d_max;
  return g;
}

TEST(Grading, LawsFollowTheirFormulas) {
  const GradingCurve u = grading_curve(law(Grading::Law::Uniform, 1e-3, 3e-3), 0);
  for (double p : {0.1, 0.3, 0.5, 0.6, 0.9}) EXPECT_NEAR(u.size_at(p), 1e-3 + 2e-3 * p, 1e-8);
  Grading f = law(Grading::Law::Fuller, 0.5e-3, 8e-3);
  f.exponent = 0.45;
  const GradingCurve fc = grading_curve(f, 0);
  for (double p : {0.1, 0.3, 0.5, 0.6, 0.9}) {
    const double lo = std::pow(0.5e-3, 0.45), hi = std::pow(8e-3, 0.45);
    EXPECT_NEAR(fc.size_at(p), std::pow(lo + p * (hi - lo), 1 / 0.45), 3e-5 * fc.size_at(p));  // 400 points: 2.6e-6
  }
  Grading ln = law(Grading::Law::LogNormal);
  ln.sigma = 0.3;
  const GradingCurve lc = grading_curve(ln, 2e-3);
  EXPECT_NEAR(lc.size_at(0.5), 2e-3, 1e-9);
  // D84 = D50 e^sigma, shifted a little by the cut at +-2.5 sigma
  EXPECT_NEAR(lc.size_at(0.8413), 2e-3 * std::exp(0.3), 2e-3 * 0.01);
  Grading sv = law(Grading::Law::Sieve);
  sv.sizes = {0.5e-3, 1e-3, 2e-3, 4e-3};
  sv.passing = {0, 20, 70, 100};
  const GradingCurve sc = grading_curve(sv, 0);
  EXPECT_DOUBLE_EQ(sc.size_at(0.2), 1e-3);
  EXPECT_NEAR(sc.size_at(0.45), std::sqrt(2) * 1e-3, 1e-12);  // halfway on the log axis
  const GradingStats st = grading_stats(sc);
  EXPECT_NEAR(st.cu, st.d60 / st.d10, 1e-12);
}

// Sizes drawn to a lognormal curve: each D_p within three of its stated
// sampling errors of the asked one, and the errors honest (not vast).
TEST(Grading, DrawnSizesMatchTheCurveWithinTheirSamplingError) {
  Grading g = law(Grading::Law::LogNormal);
  g.sigma = 0.35;
  const GradingCurve asked = grading_curve(g, 1e-3);
  const double volume = 20000 * kPi / 6 * 1e-9;  // about 20 000 beads of D50
  const std::vector<double> d = sample_diameters(asked, volume, 7);
  const GradingStats a = grading_stats(asked), got = grading_stats(measured_curve(d));
  double worst = 0;
  for (const auto& [p, want, have] : {std::tuple{0.1, a.d10, got.d10}, {0.3, a.d30, got.d30},
                                      {0.5, a.d50, got.d50}, {0.6, a.d60, got.d60}}) {
    const double err = sampling_error(d, asked, p);
    worst = std::max(worst, std::fabs(have - want) / err);
    EXPECT_LT(err, 0.01 * want);
    EXPECT_LT(std::fabs(have - want), 3 * err) << "D" << 100 * p;
  }
  std::printf("[measure] %zu beads drawn: D_p off by at most %.2f sampling errors; Cu %.4f "
              "(asked %.4f), Cc %.4f (asked %.4f)\n",
              d.size(), worst, got.cu, a.cu, got.cc, a.cc);
  EXPECT_EQ(sample_diameters(asked, volume, 7), d);
  EXPECT_NE(sample_diameters(asked, volume, 8), d);
}

std::string oedometer_toml(const std::string& grading, const std::string& diameter = "diameter = 3e-3\n") {
  return testing::glass_toml("0.3") + R"(
[oedometer]
length = 33.46e-3
width = 33.40e-3
load_steps = [25e3, 50e3]
settle_time = 0.06
step_time = 0.01

[oedometer.specimen]
method = "pour"
material = "glass"
)" + diameter + R"(layers = 2
seed = 3

[oedometer.specimen.grading]
)" + grading + R"(
[numerics]
precision = "float"
duration = 1
)";
}

TEST(Grading, BadCurvesAreRefusedByField) {
  using testing::expect_scene_error;
  expect_scene_error(oedometer_toml("law = \"uniform\"\nd_min = 2e-3\nd_max = 1e-3\n", ""),
                     "out_of_range", "oedometer.specimen.grading.d_max");
  expect_scene_error(oedometer_toml("law = \"sieve\"\nsizes = [1e-3, 2e-3]\npassing = [10, 100]\n", ""),
                     "out_of_range", "oedometer.specimen.grading.passing[0]");
  expect_scene_error(oedometer_toml("law = \"sieve\"\nsizes = [2e-3, 1e-3]\npassing = [0, 100]\n", ""),
                     "out_of_range", "oedometer.specimen.grading.sizes[1]");
  expect_scene_error(oedometer_toml("law = \"uniform\"\nd_min = 1e-3\nd_max = 2e-3\n"),
                     "conflicting_keys", "oedometer.specimen.diameter");
  expect_scene_error(oedometer_toml("law = \"lognormal\"\nsigma = 3\n"), "out_of_range",
                     "oedometer.specimen.grading.sigma");
  expect_scene_error(oedometer_toml("law = \"single\"\nsigma = 0.2\n"), "unknown_key",
                     "oedometer.specimen.grading.sigma");
  expect_scene_error(oedometer_toml("law = \"gravel\"\n"), "bad_enum",
                     "oedometer.specimen.grading.law");
}

// A graded pour in float: no two beads overlap as placed, the specimen
// holds the asked solid volume, and it settles and takes its first load
// step without a runaway (float rounding once gave a barely touching pair
// a negative overlap, and the Hertz law's square root a NaN).
TEST(Grading, AGradedPourSettlesInFloat) {
  const Scene scene =
      parse_scene(oedometer_toml("law = \"lognormal\"\nsigma = 0.3\n"), "graded.toml");
  const std::vector<Particle>& b = scene.particles;
  double solid = 0, smallest = 1, largest = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    solid += kPi / 6 * std::pow(2 * b[i].radius, 3);
    smallest = std::min(smallest, 2 * b[i].radius);
    largest = std::max(largest, 2 * b[i].radius);
    for (size_t j = i + 1; j < b.size(); ++j) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(b[i].position[k] - b[j].position[k], 2);
      ASSERT_GE(std::sqrt(d2), b[i].radius + b[j].radius) << i << " " << j;
    }
  }
  const double want = 11 * 11 * 2 * kPi / 6 * 27e-9;  // 2 layers of 11 x 11 beads of 3 mm
  EXPECT_GE(solid, want);
  EXPECT_LT(solid, want + kPi / 6 * std::pow(largest, 3));
  Simulation sim(default_device(), scene);
  OedometerProgramme test(sim);
  // to its first load step's row (throws RunawayError on a NaN)
  while (!test.done() && test.rows().empty()) test.advance(1 << 14);
  std::printf("[measure] graded pour: %zu beads of %.3f to %.3f mm settled and first loaded in %lld "
              "steps (float)\n",
              b.size(), 1e3 * smallest, 1e3 * largest, static_cast<long long>(sim.steps()));
  EXPECT_FALSE(test.rows().empty());
}

}  // namespace
}  // namespace simsols
