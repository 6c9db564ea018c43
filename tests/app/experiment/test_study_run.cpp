// The accuracy study's pool of workers (study_run.h), on the ci preset's
// contact checks (no shear, seconds a case): two workers stopped after the
// first finished case, then resumed by one, give the cases one worker gives
// straight through, value for value; a study with nothing to resume from is
// refused naming its state file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "app/experiment/shear_box/study_run.h"
#include "solver/common/errors.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("simsols_study_run_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

StudyRunOptions options(const fs::path& out, int jobs) {
  StudyRunOptions o;
  o.out = out.string();
  o.quiet = true;
  o.jobs = jobs;
  o.open_device = [] { return default_device(); };
  return o;
}

TEST(StudyRun, TwoWorkersStoppedThenResumedGiveTheStraightCases) {
  std::optional<StudyPreset> preset = study_preset("ci", 1);
  ASSERT_TRUE(preset);
  preset->shear = false;
  std::vector<StudySettings> chosen(preset->cases.begin(), preset->cases.begin() + 4);
  const std::vector<StudySettings> cases = study_runs(*preset, chosen);
  ASSERT_GE(cases.size(), 4u);

  const fs::path straight = fresh("straight"), split = fresh("split");
  const StudyRunOutcome all = run_study(*preset, cases, {}, options(straight, 1));
  EXPECT_TRUE(all.complete());
  EXPECT_EQ(all.total, cases.size());

  StudyRunOptions stopping = options(split, 2);
  stopping.stop_requested = [&] { return fs::exists(split / "study_state.txt"); };
  const StudyRunOutcome first = run_study(*preset, cases, {}, stopping);
  EXPECT_FALSE(first.complete());
  EXPECT_GE(first.finished, 1u);
  EXPECT_LT(first.finished, cases.size());
  EXPECT_FALSE(first.interrupted) << "contact-only cases end between looks";

  std::vector<StudyCase> done = resumed_study_cases(split.string(), *preset, cases);
  EXPECT_EQ(done.size(), first.finished);
  const StudyRunOutcome rest = run_study(*preset, cases, std::move(done), options(split, 1));
  EXPECT_TRUE(rest.complete());

  const std::vector<StudyCase> a = resumed_study_cases(straight.string(), *preset, cases);
  const std::vector<StudyCase> b = resumed_study_cases(split.string(), *preset, cases);
  ASSERT_EQ(a.size(), cases.size());
  ASSERT_EQ(b.size(), cases.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].settings.label, b[i].settings.label);
    EXPECT_EQ(a[i].contact.ok, b[i].contact.ok) << a[i].settings.label;
    EXPECT_EQ(a[i].contact.overlap, b[i].contact.overlap) << a[i].settings.label;
    EXPECT_EQ(a[i].contact.restitution, b[i].contact.restitution) << a[i].settings.label;
    EXPECT_EQ(a[i].contact.duration, b[i].contact.duration) << a[i].settings.label;
  }
  EXPECT_TRUE(fs::exists(split / "cases.csv"));

  const fs::path empty = fresh("empty");
  try {
    resumed_study_cases(empty.string(), *preset, cases);
    FAIL() << "nothing to resume";
  } catch (const SceneError& e) {
    EXPECT_NE(e.file.find("study_state.txt"), std::string::npos) << e.what();
  }
  fs::remove_all(straight);
  fs::remove_all(split);
  fs::remove_all(empty);
}

}  // namespace
}  // namespace simsols
