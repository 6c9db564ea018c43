// The one path from a scene to its result (apparatus_run.h) and what a run
// shows of each kind (apparatus_report.h): every kind of the registry has a
// report; a shear test stopped early through run_scene_test leaves a
// checkpoint that resume_test continues, with the same steps as one run
// straight through; a malformed checkpoint state is the user's bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

#include "app/experiment/apparatus_report.h"
#include "app/experiment/apparatus_run.h"
#include "solver/io/checkpoint.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

TEST(ApparatusReport, EveryKindHasOne) {
  for (const ApparatusKind& k : apparatus_kinds()) EXPECT_TRUE(has_test_report(k.name)) << k.name;
  EXPECT_FALSE(has_test_report("ring_shear"));
}

ProgrammeRunOptions options(const fs::path& dir, long long stop_after) {
  ProgrammeRunOptions o;
  o.device = default_device();
  o.out_dir = dir.string();
  o.quiet = true;
  o.stop_after = stop_after;
  return o;
}

TEST(ApparatusRun, StoppedThenResumedIsTheStraightRun) {
  const Scene scene =
      load_scene(std::string(SIMSOLS_SOURCE_DIR) + "/assets/scenes/oedometer.toml");
  const fs::path base = fs::temp_directory_path() / ("simsols_apparatus_run_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const TestRun straight = run_scene_test(scene, options(base / "straight", 600), {});
  EXPECT_FALSE(straight.state.finished);
  EXPECT_EQ(straight.state.steps, 600);
  EXPECT_STREQ(straight.kind->name, "oedometer");
  const TestRun first = run_scene_test(scene, options(base / "split", 250), {});
  EXPECT_EQ(first.state.steps, 250);
  EXPECT_TRUE(fs::exists(base / "split" / "checkpoint.bin"));
  EXPECT_TRUE(fs::exists(base / "split" / "oedometer.csv"));
  EXPECT_FALSE(fs::exists(base / "split" / "summary.txt"));
  const std::string text = test_result_text(first, (base / "split").string());
  EXPECT_NE(text.find("oedometer test stopped"), std::string::npos) << text;
  EXPECT_NE(text.find("--resume"), std::string::npos) << text;
  // A checkpoint whose programme state is malformed (the checksum right):
  // bad input naming the checkpoint (exit 2), not an internal error.
  fs::copy(base / "split", base / "broken", fs::copy_options::recursive);
  const std::string ck = (base / "broken" / "checkpoint.bin").string();
  save_checkpoint(*load_checkpoint(default_device(), ck, nullptr), ck, "oedometer 1 2 x");
  ProgrammeRunOptions broken = options(base / "broken", 10);
  broken.resume = true;
  try {
    run_test(scene, broken);
    ADD_FAILURE() << "a malformed programme state was resumed";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "bad_checkpoint");
    EXPECT_EQ(e.file, ck);
  }
  ProgrammeRunOptions more = options(base / "split", 350);
  more.resume = true;
  const TestRun second = run_test(scene, more);
  EXPECT_EQ(second.state.steps, 600);
  EXPECT_EQ(second.sim->hash(), straight.sim->hash());
  fs::remove_all(base);
}

}  // namespace
}  // namespace simsols
