// The triaxial campaign's report over several specimens
// (app/experiment/triaxial/triaxial_campaign_report.h): each specimen's
// envelope is fitted to its own Mohr circles and the strength is the mean
// of the specimens' fits with Student's interval; one specimen reports its
// fit's standard errors. The tests' circles and critical states are given
// exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "app/experiment/shear_box/study_stats.h"
#include "app/experiment/triaxial/triaxial_campaign_report.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// A test whose circles touch tau = sigma tan(phi) (c = 0) at the peak and
// tau = sigma tan(phi - 5 deg) at the critical state, which lies on
// e = gamma - lambda ln(p' / 1 kPa).
TriaxialCampaignEntry entry(double s3_kpa, std::int64_t seed, double phi_deg, double gamma,
                            double lambda) {
  TriaxialCampaignEntry e;
  e.s_kpa = s3_kpa;
  e.seed = seed;
  e.beads = 588;
  const auto sigma1 = [&](double phi) {
    const double s = std::sin(phi * kPi / 180);
    return s3_kpa * 1e3 * (1 + s) / (1 - s);
  };
  TriaxialSummary& s = e.summary;
  s.confining_stress = s3_kpa * 1e3;
  s.peak_angle = phi_deg;
  s.peak_sigma3 = s.critical_sigma3 = s3_kpa * 1e3;
  s.peak_sigma1 = sigma1(phi_deg);
  s.critical_angle = phi_deg - 5;
  s.critical_sigma1 = sigma1(phi_deg - 5);
  s.critical_p = (s.critical_sigma1 + 2 * s.critical_sigma3) / 3;
  s.critical_void_ratio = gamma - lambda * std::log(s.critical_p * 1e-3);
  for (int i = 0; i < 3; ++i) {
    TriaxialRow r;
    r.axial_strain = 0.01 * i;
    r.p = s.critical_p;
    r.q = 0.5 * r.p;
    r.void_ratio = s.critical_void_ratio;
    e.rows.push_back(r);
  }
  return e;
}

std::string slurp(const fs::path& p) { return read_text(p.string()); }  // output.h

// envelopes.csv's row for `strength`, split at the commas.
std::vector<std::string> row(const std::string& csv, const std::string& strength) {
  std::stringstream in(csv);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(strength + ",", 0) == 0) {
      std::vector<std::string> cells;
      std::stringstream l(line);
      std::string cell;
      while (std::getline(l, cell, ',')) cells.push_back(cell);
      return cells;
    }
  return {};
}

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(TriaxialCampaignReport, SeveralSpecimensGiveTheMeanOfTheirFitsWithStudentsInterval) {
  const double phis[3] = {14, 16, 21}, lambdas[3] = {0.01, 0.02, 0.03};
  std::vector<TriaxialCampaignEntry> entries;
  for (int k = 0; k < 3; ++k)
    for (double s3 : {50.0, 100.0, 200.0}) entries.push_back(entry(s3, k + 1, phis[k], 0.8, lambdas[k]));
  const fs::path out = fresh("simsols_triaxial_report");
  write_triaxial_campaign_report(out.string(), "base.toml", entries, 1);
  const std::string env = slurp(out / "envelopes.csv");
  const Interval peak = mean_ci95({14, 16, 21}), critical = mean_ci95({9, 11, 16});
  const std::vector<std::string> p = row(env, "peak"), c = row(env, "critical");
  ASSERT_EQ(p.size(), 7u) << env;
  ASSERT_EQ(c.size(), 7u) << env;
  EXPECT_EQ(p[1], "3");
  EXPECT_NEAR(std::stod(p[2]), peak.mean, 1e-5);  // each specimen's fit is exact here
  EXPECT_NEAR(std::stod(p[3]), peak.half_width, 1e-5);
  EXPECT_NEAR(std::stod(p[4]), 0, 1e-5);
  EXPECT_EQ(p[6], "ci95");
  EXPECT_NEAR(std::stod(c[2]), critical.mean, 1e-5);
  EXPECT_NEAR(std::stod(c[3]), critical.half_width, 1e-5);
  const std::string md = slurp(out / "summary.md");
  EXPECT_NE(md.find("mean of 3 specimens' fits"), std::string::npos) << md;
  EXPECT_NE(md.find("λ = 0.02000 ± "), std::string::npos) << md;  // the lines' mean
  const std::string csv = slurp(out / "summary.csv");
  EXPECT_EQ(csv.rfind("sigma3_kPa,seed,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n200,3,588,"), std::string::npos) << csv;
  fs::remove_all(out);
}

TEST(TriaxialCampaignReport, OneSpecimenReportsItsFitsStandardErrors) {
  std::vector<TriaxialCampaignEntry> entries;
  for (double s3 : {50.0, 100.0, 200.0}) entries.push_back(entry(s3, 7, 18, 0.8, 0.02));
  const fs::path out = fresh("simsols_triaxial_report_one");
  write_triaxial_campaign_report(out.string(), "base.toml", entries, 1);
  const std::vector<std::string> p = row(slurp(out / "envelopes.csv"), "peak");
  ASSERT_EQ(p.size(), 7u);
  EXPECT_EQ(p[1], "1");
  EXPECT_NEAR(std::stod(p[2]), 18, 1e-5);
  EXPECT_EQ(p[6], "se");
  EXPECT_NE(slurp(out / "summary.md").find("one specimen: its fit's standard errors"),
            std::string::npos);
  fs::remove_all(out);
}

}  // namespace
}  // namespace simsols
