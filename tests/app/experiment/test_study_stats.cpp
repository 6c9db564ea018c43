// The accuracy study's ensemble statistics (app/experiment/shear_box/study_stats.h): Student's
// interval of a mean and Welch's interval of a difference, against table
// values, and the coverage of the 95 % interval over many samples.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "app/experiment/shear_box/study_stats.h"

using namespace simsols;

// Table values of t(0.975, dof) (any statistics handbook).
TEST(StudyStats, StudentQuantilesMatchTheTable) {
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.975, 4), 2.7764, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.975, 8), 2.3060, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.975, 30), 2.0423, 1e-4);
}

TEST(StudyStats, MeanIntervalIsStudents) {
  const Interval m = mean_ci95({1, 2, 3, 4, 5});
  EXPECT_DOUBLE_EQ(m.mean, 3);
  EXPECT_NEAR(m.sd, std::sqrt(2.5), 1e-12);
  EXPECT_NEAR(m.half_width, 2.7764451 * std::sqrt(2.5) / std::sqrt(5.0), 1e-6);
  EXPECT_TRUE(m.significant());  // 3 +- 1.96
  EXPECT_FALSE(mean_ci95({-1, 0, 1.5}).significant());
  const Interval one = mean_ci95({7});
  EXPECT_EQ(one.n, 1);
  EXPECT_TRUE(std::isnan(one.half_width));
  EXPECT_FALSE(one.significant());
}

// Equal sizes and variances: Welch's degrees of freedom are 2 (n - 1).
TEST(StudyStats, DifferenceIntervalIsWelchs) {
  const Interval d = difference_ci95({1, 2, 3, 4, 5}, {11, 12, 13, 14, 15});
  EXPECT_DOUBLE_EQ(d.mean, -10);
  EXPECT_NEAR(d.sd, 1.0, 1e-12);  // sqrt(2.5/5 + 2.5/5)
  EXPECT_NEAR(d.half_width, 2.3060041, 1e-6);
  EXPECT_TRUE(d.significant());
  // unequal variances: fewer degrees of freedom than n_a + n_b - 2
  const Interval u = difference_ci95({0, 0.1, -0.1, 0.05}, {0, 2, -2, 1, -1, 0.5});
  const double va = mean_ci95({0, 0.1, -0.1, 0.05}).sd, vb = mean_ci95({0, 2, -2, 1, -1, 0.5}).sd;
  const double se = std::sqrt(va * va / 4 + vb * vb / 6);
  EXPECT_GT(u.half_width, student_t_quantile(0.975, 8) * se);  // dof < 8
  EXPECT_LT(u.half_width, student_t_quantile(0.975, 4) * se);  // dof > 4 (vb dominates: ~5)
  EXPECT_FALSE(u.significant());
  // exact ensembles: an exact difference; one run: unknown
  EXPECT_EQ(difference_ci95({2, 2}, {1, 1}).half_width, 0.0);
  EXPECT_TRUE(difference_ci95({2, 2}, {1, 1}).significant());
  EXPECT_TRUE(std::isnan(difference_ci95({2}, {1, 1.5}).half_width));
}

// Coverage: over 4000 samples of 5 normal values, the 95 % interval holds
// the true mean in 95 % of them (binomial sd 0.34 %; bound 1 %, three of them).
TEST(StudyStats, IntervalCoversTheTrueMean95PercentOfTheTime) {
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> normal(10.0, 2.0);
  int covered = 0;
  const int samples = 4000;
  for (int k = 0; k < samples; ++k) {
    std::vector<double> x(5);
    for (double& v : x) v = normal(rng);
    const Interval m = mean_ci95(x);
    covered += (m.lo() <= 10.0 && 10.0 <= m.hi()) ? 1 : 0;
  }
  const double rate = double(covered) / samples;
  std::printf("[measure] coverage of the 95 %% interval, n = 5: %.4f over %d samples\n", rate,
              samples);
  EXPECT_NEAR(rate, 0.95, 0.01);
}
