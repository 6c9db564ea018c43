// The triaxial analysis across tests: the envelope tangent to Mohr
// circles, the critical state line, and triaxial.csv read back.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "solver/apparatus/triaxial/triaxial_analysis.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;

// sigma_1 on the Mohr-Coulomb failure line (c, phi) for a given sigma_3.
double sigma1_at_failure(double sigma3, double c, double phi_deg) {
  const double n = std::tan(kPi / 4 + phi_deg * kPi / 360);
  return sigma3 * n * n + 2 * c * n;
}

TEST(TriaxialAnalysis, EnvelopeTangentToCirclesOnAKnownLine) {
  const double c = 12e3, phi = 31.5;
  std::vector<double> s1, s3{50e3, 100e3, 200e3, 400e3};
  for (double x : s3) s1.push_back(sigma1_at_failure(x, c, phi));
  const MohrCoulomb m = fit_mohr_circles(s1, s3);
  EXPECT_EQ(m.points, 4);
  EXPECT_NEAR(m.phi_deg, phi, 1e-9);
  EXPECT_NEAR(m.cohesion, c, 1e-6);
  EXPECT_NEAR(m.r2, 1, 1e-12);
  EXPECT_NEAR(m.phi_se_deg, 0, 1e-9);
  // Every circle touches the line: the centre's distance to it is the radius.
  for (size_t i = 0; i < s3.size(); ++i) {
    const double centre = 0.5 * (s1[i] + s3[i]), radius = 0.5 * (s1[i] - s3[i]);
    const double distance = (m.cohesion + m.tan_phi * centre) / std::sqrt(1 + m.tan_phi * m.tan_phi);
    EXPECT_NEAR(distance, radius, 1e-6 * radius);
  }
}

TEST(TriaxialAnalysis, EnvelopeErrorsGrowWithScatterAndTwoCirclesAreExact) {
  std::vector<double> s3{50e3, 100e3, 200e3}, s1;
  const double bump[] = {1.03, 0.97, 1.01};
  for (size_t i = 0; i < s3.size(); ++i) s1.push_back(sigma1_at_failure(s3[i], 0, 30) * bump[i]);
  const MohrCoulomb m = fit_mohr_circles(s1, s3);
  EXPECT_GT(m.phi_se_deg, 0.05);
  EXPECT_LT(std::fabs(m.phi_deg - 30), 3 * m.phi_se_deg + 0.5);
  const MohrCoulomb two = fit_mohr_circles({s1[0], s1[1]}, {s3[0], s3[1]});
  EXPECT_TRUE(two.exact);
  EXPECT_TRUE(std::isnan(two.phi_se_deg));
  EXPECT_EQ(fit_mohr_circles({s1[0]}, {s3[0]}).points, 1);
}

TEST(TriaxialAnalysis, CriticalStateLineOnKnownPoints) {
  std::vector<double> p{40e3, 90e3, 250e3, 700e3}, e;
  for (double x : p) e.push_back(0.82 - 0.015 * std::log(x / 1e3));
  const CriticalStateLine c = fit_critical_state_line(p, e);
  EXPECT_EQ(c.points, 4);
  EXPECT_NEAR(c.gamma, 0.82, 1e-12);
  EXPECT_NEAR(c.lambda, 0.015, 1e-12);
  EXPECT_NEAR(c.r2, 1, 1e-12);
}

TEST(TriaxialAnalysis, RowsReadBackAsWritten) {
  TriaxialRow r;
  r.time = 0.125;
  r.step = 123456;
  r.axial_strain = 0.0123;
  r.volumetric_strain = -0.0045;
  r.sigma_x = 100e3;
  r.sigma_y = 101e3;
  r.sigma_z = 250e3;
  r.p = 150.333e3;
  r.q = 149.5e3;
  r.friction_angle = 24.5;
  r.void_ratio = 0.61;
  r.coordination = 5.2;
  r.lw_x = 99e3;
  r.lw_y = 102e3;
  r.lw_z = 248e3;
  r.lw_gap = 0.013;
  r.fabric_anisotropy = 0.21;
  r.kinetic_energy = 1.5e-7;
  r.inertial_number = 4e-4;
  r.membrane_axial = 5.25e3;
  r.membrane_shell = 4.5e3;
  const std::vector<TriaxialRow> back = parse_triaxial_rows_csv(triaxial_rows_csv({r, r}));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].step, r.step);
  EXPECT_DOUBLE_EQ(back[1].sigma_z, r.sigma_z);
  EXPECT_DOUBLE_EQ(back[1].volumetric_strain, r.volumetric_strain);
  EXPECT_DOUBLE_EQ(back[1].inertial_number, r.inertial_number);
  EXPECT_DOUBLE_EQ(back[1].membrane_axial, r.membrane_axial);
  EXPECT_DOUBLE_EQ(back[1].membrane_shell, r.membrane_shell);
  EXPECT_EQ(triaxial_rows_csv(back), triaxial_rows_csv({r, r}));
  // a file from before the membrane's columns: read, with zeros there
  std::string older = triaxial_rows_csv({r});
  older.replace(older.find(",membrane_axial_kPa,membrane_shell_kPa"), 38, "");
  older.replace(older.rfind(",5.25,4.5"), 9, "");  // kPa
  const std::vector<TriaxialRow> old_rows = parse_triaxial_rows_csv(older);
  ASSERT_EQ(old_rows.size(), 1u);
  EXPECT_DOUBLE_EQ(old_rows[0].sigma_z, r.sigma_z);
  EXPECT_EQ(old_rows[0].membrane_axial, 0);
  std::string bad = triaxial_rows_csv({r});
  bad.replace(bad.rfind("0.61"), 4, "x.61");
  try {
    parse_triaxial_rows_csv(bad);
    FAIL() << "a bad number was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("row 1, column void_ratio"), std::string::npos) << e.what();
  }
}

TEST(TriaxialAnalysis, PeakAndCriticalCirclesFromThePlates) {
  std::vector<TriaxialRow> rows(10);
  for (int i = 0; i < 10; ++i) {
    TriaxialRow& r = rows[i];
    r.axial_strain = 0.01 * i;
    r.sigma_x = r.sigma_y = 100e3;
    r.sigma_z = i == 4 ? 300e3 : 100e3 + 20e3 * std::min(i, 3);
    r.p = (r.sigma_x + r.sigma_y + r.sigma_z) / 3;
    r.q = r.sigma_z - r.sigma_x;
    r.friction_angle = mobilised_friction_angle(r.sigma_x, r.sigma_y, r.sigma_z);
  }
  TriaxialSummary s;
  analyse_triaxial_rows(rows, s);
  EXPECT_DOUBLE_EQ(s.peak_sigma1, 300e3);
  EXPECT_DOUBLE_EQ(s.peak_sigma3, 100e3);
  EXPECT_NEAR(s.peak_angle, 30, 1e-9);  // sin(phi) = 200 / 400
  EXPECT_DOUBLE_EQ(s.critical_sigma1, 160e3);  // rows 8 and 9 (eps_a >= 0.8 x 0.09)
  EXPECT_DOUBLE_EQ(s.critical_sigma3, 100e3);
}

// A jamming event: three rows (0.2 % of axial strain) far above a plateau
// of rows 0.1 % apart. It is the largest angle, not the peak, which is the
// plateau's.
TEST(TriaxialAnalysis, AJammingSpikeIsTheLargestAngleNotThePeak) {
  std::vector<TriaxialRow> rows(120);
  for (int i = 0; i < 120; ++i) {
    TriaxialRow& r = rows[i];
    r.axial_strain = 0.001 * i;
    r.sigma_x = r.sigma_y = 100e3;
    const double plateau = 100e3 + std::min(i, 20) * 5e3 + (i % 2 ? 2e3 : -2e3);
    r.sigma_z = i >= 60 && i < 63 ? 400e3 : plateau;
    r.p = (r.sigma_x + r.sigma_y + r.sigma_z) / 3;
    r.q = r.sigma_z - r.sigma_x;
    r.friction_angle = mobilised_friction_angle(r.sigma_x, r.sigma_y, r.sigma_z);
  }
  TriaxialSummary s;
  analyse_triaxial_rows(rows, s);
  EXPECT_NEAR(s.max_angle, std::asin(300.0 / 500) * 180 / 3.14159265358979323846, 1e-9);
  EXPECT_NEAR(s.max_axial_strain, 0.060, 1e-12);
  // The plateau: sigma_1 200 +- 2 kPa; its median 200 kPa (sin phi = 1/3).
  EXPECT_NEAR(s.peak_sigma1, 202e3, 2.5e3);
  EXPECT_LT(s.peak_angle, 20.0);
  EXPECT_GT(s.peak_angle, 19.0);
}

}  // namespace
}  // namespace simsols
