#include "app/experiment/calibration/test_batch.h"

#include <cstdio>

#include "app/experiment/apparatus_run.h"
#include "app/experiment/campaign_loop.h"

namespace simsols {

namespace fs = std::filesystem;

BatchOutcome run_batch(std::vector<BatchTest>& tests, double later_cost, const BatchOptions& o) {
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
