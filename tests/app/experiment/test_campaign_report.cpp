// The shear campaign's report over several specimens
// (app/experiment/shear_box/campaign_report.h): the ensemble of each size
// and stress, and the envelopes fitted per specimen and averaged with
// Student's interval, on tests whose strengths are given exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>

#include "app/experiment/shear_box/campaign_report.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// A test whose peak lies on tau = c + sigma tan(phi) (residual: half of it).
CampaignEntry entry(double s_kpa, std::int64_t seed, double phi_deg, double c_kpa, bool valid = true) {
  CampaignEntry e;
  e.d_mm = 6.35;
  e.s_kpa = s_kpa;
  e.seed = seed;
  e.layers = 4;
  e.beads = 324;
  ShearSummary& s = e.summary;
  s.normal_stress_target = s_kpa * 1e3;
  s.peak_tau = (c_kpa + s_kpa * std::tan(phi_deg * kPi / 180)) * 1e3;
  s.peak_angle = std::atan(s.peak_tau / s.normal_stress_target) * 180 / kPi;
  s.residual_tau = 0.5 * s.peak_tau;
  s.residual_angle = std::atan(s.residual_tau / s.normal_stress_target) * 180 / kPi;
  s.valid = valid;
  for (int i = 0; i < 3; ++i) {
    ShearRow r;
    r.displacement = 1e-4 * i;
    r.sigma = s.normal_stress_target;
    r.tau = s.peak_tau * i / 2;
    e.rows.push_back(r);
  }
  return e;
}

std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  for (std::stringstream h(line); std::getline(h, line, ',');) head.push_back(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream cells(line);
    for (const std::string& key : head) std::getline(cells, row[key], ',');
    rows.push_back(row);
  }
  return rows;
}

TEST(CampaignReport, EnvelopesAreFittedPerSpecimenAndAveraged) {
  const fs::path out = fs::temp_directory_path() / ("campaign_report_" + std::to_string(getpid()));
  fs::create_directories(out);
  // three specimens on exact lines (phi 30, 32, 34 deg; c 0, 1, 2 kPa); a
  // fourth whose 100 kPa test lost its load: left out, and with one valid
  // stress it has no envelope of its own
  std::vector<CampaignEntry> tests;
  const double phi[] = {30, 32, 34}, c[] = {0, 1, 2};
  for (int k = 0; k < 3; ++k)
    for (double s : {100.0, 200.0}) tests.push_back(entry(s, k + 1, phi[k], c[k]));
  tests.push_back(entry(100, 4, 60, 50, false));
  tests.push_back(entry(200, 4, 20, 0));
  write_campaign_report(out.string(), "base.toml", {6.35}, tests, 1);

  // Student's interval over three fits: t(0.975, 2) = 4.303 x sd / sqrt(3)
  const double t = 4.302652729911275;
  const auto env = read_csv(out / "envelopes.csv");
  ASSERT_EQ(env.size(), 2u);
  EXPECT_EQ(env[0].at("strength"), "peak");
  EXPECT_EQ(env[0].at("specimens"), "3");
  EXPECT_NEAR(std::stod(env[0].at("phi_deg")), 32, 1e-4);
  EXPECT_NEAR(std::stod(env[0].at("phi_spread_deg")), t * 2 / std::sqrt(3.0), 1e-4);
  EXPECT_NEAR(std::stod(env[0].at("c_kPa")), 1, 1e-4);
  EXPECT_NEAR(std::stod(env[0].at("c_spread_kPa")), t * 1 / std::sqrt(3.0), 1e-4);
  EXPECT_EQ(env[0].at("spread"), "ci95");

  // the ensemble at 100 kPa: the three valid tests only
  const auto ens = read_csv(out / "ensemble.csv");
  ASSERT_EQ(ens.size(), 2u);
  EXPECT_EQ(ens[0].at("specimens"), "3");
  EXPECT_EQ(ens[1].at("specimens"), "4");
  std::vector<double> angles;
  for (int k = 0; k < 3; ++k) angles.push_back(tests[2 * k].summary.peak_angle);
  const double mean = (angles[0] + angles[1] + angles[2]) / 3;
  double ss = 0;
  for (double a : angles) ss += (a - mean) * (a - mean);
  EXPECT_NEAR(std::stod(ens[0].at("peak_friction_angle_deg")), mean, 1e-5);
  EXPECT_NEAR(std::stod(ens[0].at("peak_ci95")), t * std::sqrt(ss / 2) / std::sqrt(3.0), 1e-5);
  // every test listed, with its seed
  EXPECT_EQ(read_csv(out / "summary.csv").size(), 8u);
  fs::remove_all(out);
}

TEST(CampaignReport, OneSpecimenGivesItsFitsStandardError) {
  const fs::path out = fs::temp_directory_path() / ("campaign_report1_" + std::to_string(getpid()));
  fs::create_directories(out);
  std::vector<CampaignEntry> tests;
  for (double s : {50.0, 100.0, 200.0}) tests.push_back(entry(s, 1, 30, 0));
  tests[1].summary.peak_tau += 1e3;  // off the line: a standard error > 0
  write_campaign_report(out.string(), "base.toml", {6.35}, tests, 1);
  const auto env = read_csv(out / "envelopes.csv");
  ASSERT_EQ(env.size(), 2u);
  EXPECT_EQ(env[0].at("specimens"), "1");
  EXPECT_EQ(env[0].at("spread"), "se");
  EXPECT_GT(std::stod(env[0].at("phi_spread_deg")), 0);
  fs::remove_all(out);
}

}  // namespace
}  // namespace simsols
