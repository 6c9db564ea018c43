#include "app/experiment/calibration/test_batch.h"

#include <cstdio>

#include "app/experiment/apparatus_run.h"
#include "app/experiment/campaign_loop.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

// A folder kept or resumed must hold the test asked for now: its scene as
// given, the values set, is the one written when it started.
void check_kept(const BatchTest& t) {
  const fs::path given = t.dir / "scene.toml";
  if (!fs::exists(given) || read_text(given.string()) == t.scene.source_text) return;
  throw SceneError("stale_run", given.string(), 0, "",
                   "this test was run with other values than are asked for now (the "
                   "calibration or prediction file, or the calibrated values, changed): give "
                   "a new --out folder, or remove " + t.dir.string());
}

}  // namespace

BatchOutcome run_batch(std::vector<BatchTest>& tests, double later_cost, const BatchOptions& o) {
  for (const BatchTest& t : tests) check_kept(t);
  CampaignLoop loop = campaign_loop(tests, o.what, "");
  loop.later_cost = later_cost;
  loop.keep = [](size_t) {};
  loop.run = [&](size_t k, ProgrammeRunOptions& ro) {
    ro.resume = fs::exists(tests[k].dir / "checkpoint.bin");
    const TestRun run = run_scene_test(tests[k].scene, ro, [&](const std::string& line) {
      if (!o.quiet) std::fprintf(stderr, "%s\n", line.c_str());
    });
    return run.state.interrupted;
  };
  loop.print = [](size_t) {};
  const CampaignOutcome out =
      run_campaign_loop(loop, {o.device, o.stop_requested, o.quiet, {}, false});
  BatchOutcome b;
  b.seconds = out.seconds;
  b.interrupted = out.interrupted;
  if (out.interrupted) b.interrupted_dir = tests[out.interrupted_test].dir.string();
  return b;
}

}  // namespace simsols
