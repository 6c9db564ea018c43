// The accuracy study's ensembles (app/experiment/shear_box/study_ensemble.h): a setting's
// members are summarised as means with intervals, its error against the
// reference is significant only when the interval excludes zero, round-off
// twins are no setting, and two curves separate where they first differ by
// more than the threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/common/errors.h"
#include "app/experiment/shear_box/accuracy_table.h"
#include "solver/io/output.h"
#include "app/experiment/shear_box/study_ensemble.h"

using namespace simsols;

namespace {

StudyCase run(const char* knob, const char* label, int seed, double peak, double residual = 10,
              double dilatancy = 30, StudySpecimen specimen = StudySpecimen::Layered) {
  StudyCase c;
  c.settings.specimen = specimen;
  c.settings.knob = knob;
  c.settings.label = label;
  c.settings.seed = seed;
  c.shear.ok = true;
  c.shear.peak_angle = peak;
  c.shear.residual_angle = residual;
  c.shear.dilatancy_angle = dilatancy;
  c.shear.wall_seconds = 10 * seed;
  return c;
}

}  // namespace

TEST(StudyEnsemble, SettingsAreMeansWithIntervalsAndSignificantErrors) {
  std::vector<StudyCase> runs = {
      run("reference", "ref", 1, 35.10, 10, 30), run("reference", "ref", 2, 35.20, 14, 31),
      run("reference", "ref", 3, 35.15, 6, 29),
      run("round-off", "ref (round-off twin)", 1, 35.11, 20, 30),
      run("time step", "dt 0.5", 1, 35.60, 9, 30), run("time step", "dt 0.5", 2, 35.70, 15, 31),
      run("time step", "dt 0.5", 3, 35.65, 8, 29),
      run("time step", "dt 0.3", 1, 35.00, 12, 30), run("time step", "dt 0.3", 2, 35.30, 9, 30),
      run("time step", "dt 0.3", 3, 35.20, 11, 30)};
  runs.push_back(run("time step", "dt 2", 1, 0));
  runs.back().shear.ok = false;
  runs.back().shear.failure = "NaN";
  const std::vector<SettingSummary> s = summarise_settings(runs);
  ASSERT_EQ(s.size(), 4u);  // the twin is not a setting
  EXPECT_EQ(s[0].settings.label, "ref");
  EXPECT_EQ(s[0].runs, 3);
  EXPECT_NEAR(s[0].peak.mean, 35.15, 1e-12);
  EXPECT_NEAR(s[0].peak.half_width, 4.3027 * 0.05 / std::sqrt(3.0), 1e-4);  // t(0.975, 2)
  ASSERT_TRUE(s[0].peak_error);
  EXPECT_NEAR(s[0].peak_error->mean, 0, 1e-12);
  EXPECT_FALSE(s[0].peak_error->significant());
  // 0.5 deg above the reference, spread 0.05: significant
  EXPECT_NEAR(s[1].peak_error->mean, 0.5, 1e-12);
  EXPECT_TRUE(s[1].peak_error->significant());
  // the residuals scatter by several degrees: the same difference is not
  EXPECT_FALSE(s[1].residual_error->significant());
  // dt 0.3: mean 35.1667 against 35.15, within the spread
  EXPECT_FALSE(s[2].peak_error->significant());
  EXPECT_EQ(s[3].failed, 1);
  EXPECT_EQ(s[3].failure, "NaN");
  EXPECT_EQ(s[3].peak.n, 0);
  const std::string csv = ensemble_csv(s);
  EXPECT_NE(csv.find("\"dt 0.5\""), std::string::npos);
  EXPECT_NE(csv.find(",yes,"), std::string::npos);
  // every row has the header's number of fields
  const auto fields = [](const std::string& line) { return std::count(line.begin(), line.end(), ','); };
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  while (std::getline(in, line)) EXPECT_EQ(fields(line), fields(header)) << line;
}

// Paired errors: the specimens scatter by 5 deg, but each moves by
// 0.5 +- 0.05 deg under the setting: the same seeds resolve that, where
// Welch's interval of the two means (half width ~ 13 deg) cannot.
TEST(StudyEnsemble, ErrorsArePairedOnTheSameSeeds) {
  const double ref[] = {30, 35, 40, 33}, moved[] = {0.45, 0.55, 0.5, 0.5};
  std::vector<StudyCase> runs;
  for (int k = 0; k < 4; ++k) runs.push_back(run("reference", "ref", k + 1, ref[k]));
  for (int k = 0; k < 4; ++k) runs.push_back(run("stiffness", "E x 0.1", k + 1, ref[k] + moved[k]));
  runs.push_back(run("stiffness", "E x 0.01", 1, 30.5));  // one pair only: Welch's, unknown
  const std::vector<SettingSummary> s = summarise_settings(runs);
  ASSERT_EQ(s.size(), 3u);
  ASSERT_TRUE(s[1].peak_error);
  EXPECT_NEAR(s[1].peak_error->mean, 0.5, 1e-12);
  EXPECT_NEAR(s[1].peak_error->half_width, 3.1824 * 0.0408248 / 2, 1e-4);  // t(0.975, 3) sd / sqrt 4
  EXPECT_TRUE(s[1].peak_error->significant());
  const Interval welch = difference_ci95({30.45, 35.55, 40.5, 33.5}, {30, 35, 40, 33});
  EXPECT_FALSE(welch.significant());
  EXPECT_TRUE(std::isnan(s[2].peak_error->half_width));
}

TEST(StudyEnsemble, TwinsSeparateWhereTheCurvesFirstDifferBeyondTheThreshold) {
  ShearResult a, b;
  for (int i = 0; i < 10; ++i) {
    a.curve_mm.push_back(0.1 * i);
    b.curve_mm.push_back(0.1 * i);
    a.curve_ratio.push_back(0.5);
    b.curve_ratio.push_back(i < 6 ? 0.5 + 0.001 * i : 0.45);  // 0.005 apart at 5, 0.05 at 6
  }
  const std::optional<double> at = separation_mm(a, b, 0.02);
  ASSERT_TRUE(at);
  EXPECT_NEAR(*at, 0.6, 1e-12);
  EXPECT_FALSE(separation_mm(a, a, 0.02));
  std::vector<StudyCase> runs = {run("reference", "ref", 1, 35.1),
                                 run("round-off", "ref (round-off twin)", 1, 35.3)};
  runs[0].shear.curve_mm = a.curve_mm;
  runs[0].shear.curve_ratio = a.curve_ratio;
  runs[1].shear.curve_mm = b.curve_mm;
  runs[1].shear.curve_ratio = b.curve_ratio;
  EXPECT_FALSE(measure_chaos(runs, StudySpecimen::Poured).measured);
  const Chaos c = measure_chaos(runs, StudySpecimen::Layered);
  EXPECT_TRUE(c.measured);
  ASSERT_TRUE(c.separation);
  EXPECT_NEAR(*c.separation, 0.6, 1e-12);
  EXPECT_NEAR(c.largest_difference, 0.05, 1e-12);
  EXPECT_NEAR(c.peak_difference, 0.2, 1e-12);
}

// ensemble.csv back into the tables: the same table as from the summaries.
TEST(StudyEnsemble, EnsembleCsvRoundTripsToTheSameTable) {
  std::vector<StudyCase> runs = {run("reference", "ref", 1, 35.10), run("reference", "ref", 2, 35.20),
                                 run("time step", "dt 0.5", 1, 35.60), run("time step", "dt 0.5", 2, 35.70)};
  runs.push_back(run("time step", "dt 2", 1, 0));
  runs.back().shear.ok = false;
  runs.back().shear.failure = "runaway, at step 12";
  runs.push_back(run("reference", "ref", 1, 20.0, 16, 10, StudySpecimen::Poured));
  runs.push_back(run("reference", "ref", 2, 21.0, 17, 11, StudySpecimen::Poured));
  const std::vector<SettingSummary> s = summarise_settings(runs);
  const std::vector<SettingSummary> back = parse_ensemble_csv(ensemble_csv(s));
  ASSERT_EQ(back.size(), s.size());
  for (StudySpecimen k : kStudySpecimens)
    EXPECT_EQ(ensemble_table_md(back, k), ensemble_table_md(s, k));
  EXPECT_EQ(back[2].failure, "runaway, at step 12");
  EXPECT_EQ(back[3].settings.specimen, StudySpecimen::Poured);
  // the poured table holds its own rows only, the layered one its own
  EXPECT_EQ(ensemble_table_md(s, StudySpecimen::Poured).find("dt 0.5"), std::string::npos);
  EXPECT_NE(ensemble_table_md(s, StudySpecimen::Layered).find("dt 0.5"), std::string::npos);
  EXPECT_THROW(parse_ensemble_csv("knob,label\n"), ReadError);  // columns missing
}

// One source for every table: docs/accuracy.md holds the table that
// `simsols study table` prints from the shipped assets/accuracy/ensemble.csv,
// and the lab's embedded table is that file.
TEST(StudyEnsemble, DocsAndLabTablesAreTheShippedCsv) {
  const std::string csv = read_text(SIMSOLS_SOURCE_DIR "/assets/accuracy/ensemble.csv");
  const std::string docs = read_text(SIMSOLS_SOURCE_DIR "/docs/accuracy.md");
  ASSERT_FALSE(csv.empty());
  const std::vector<SettingSummary> shipped = parse_ensemble_csv(csv);
  const std::vector<SettingSummary>& lab = accuracy_table();
  for (StudySpecimen k : kStudySpecimens) {
    EXPECT_NE(docs.find(ensemble_table_md(shipped, k)), std::string::npos)
        << "docs/accuracy.md does not hold the " << specimen_name(k)
        << " table of assets/accuracy/ensemble.csv; regenerate it with: simsols study table "
           "--from assets/accuracy/ensemble.csv";
    EXPECT_EQ(ensemble_table_md(lab, k), ensemble_table_md(shipped, k))
        << "the lab's embedded table is not the shipped CSV (reconfigure the build)";
    const SettingSummary* base = expected_accuracy(0.25, Precision::Float, k);
    ASSERT_NE(base, nullptr) << specimen_name(k);
    EXPECT_EQ(base->settings.dt_fraction, 0.25);
    EXPECT_EQ(base->settings.specimen, k);
    EXPECT_NE(expected_accuracy_text(*base).find("phi_peak"), std::string::npos);
  }
  // the paired study in the paper's box (docs/img), the same way
  const std::vector<SettingSummary> paired = parse_ensemble_csv(
      read_text(SIMSOLS_SOURCE_DIR "/docs/img/accuracy_paired_poured_ensemble.csv"));
  EXPECT_NE(docs.find(ensemble_table_md(paired, StudySpecimen::Poured)), std::string::npos)
      << "docs/accuracy.md does not hold the table of docs/img/accuracy_paired_poured_ensemble.csv; "
         "regenerate it with: simsols study table --from docs/img/accuracy_paired_poured_ensemble.csv";
}

// The lab's line for the fast profile comes from the embedded profiles.csv
// (assets/accuracy/profiles.csv): read through the CSV reader, its layered
// row names the paired differences; the paper profile has no row.
namespace simsols {
TEST(StudyEnsemble, TheFastProfilesLineIsReadFromItsTable) {
  const std::string fast = profile_accuracy_text("fast", StudySpecimen::Layered);
  EXPECT_NE(fast.find("phi_peak"), std::string::npos) << fast;
  EXPECT_NE(fast.find("layered specimens"), std::string::npos) << fast;
  EXPECT_TRUE(profile_accuracy_text("paper", StudySpecimen::Layered).empty());
}
}  // namespace simsols
