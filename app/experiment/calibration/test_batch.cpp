#include "app/experiment/calibration/test_batch.h"

#include <cstdio>
#include <optional>

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

bool all_finished(const std::vector<BatchTest>& tests) {
  for (const BatchTest& t : tests)
    if (!programme_finished(t.dir.string())) return false;
  return true;
}

// What a cluster run does with this batch: keep it whole and go on (every
// test finished), or end the command there: after writing the batch's job,
// after running the array task's test (`only`), or refusing to collect a
// job whose tests have not all finished (`collect`: the loop names them).
struct ClusterStep {
  bool end = false;
  std::optional<size_t> only;
  bool collect = false;
};

ClusterStep cluster_step(const std::vector<BatchTest>& tests, const BatchOptions& o) {
  const BatchCluster& c = *o.cluster;
  const bool finished = all_finished(tests);
  std::vector<std::string> names;
  for (const BatchTest& t : tests) names.push_back(t.scene.name);
  const bool the_job = names == c.job_tests;
  switch (c.mode) {
    case BatchCluster::Mode::here: return {};
    case BatchCluster::Mode::task:
      if (the_job || (c.job_tests.empty() && !finished)) return {true, c.task, false};
      if (!finished)
        throw UsageError("conflict", "--task",
                         "the batch with tests left (" + o.batch + ", " +
                             std::to_string(names.size()) + " tests) is not the one " +
                             c.manifest + " lists: emit the job again");
      return {};
    case BatchCluster::Mode::emit:
      if (finished) return {};
      c.write_job(tests, o.batch);
      return {true, std::nullopt, false};
    case BatchCluster::Mode::collect:
      if (finished) return {};
      if (the_job) return {true, std::nullopt, true};  // the loop names what is left
      c.write_job(tests, o.batch);                     // the next batch's job
      return {true, std::nullopt, false};
  }
  return {};
}

}  // namespace

BatchOutcome run_batch(std::vector<BatchTest>& tests, double later_cost, const BatchOptions& o) {
  for (const BatchTest& t : tests) check_kept(t);
  BatchOutcome b;
  CampaignRun run{o.device, o.stop_requested, o.quiet, std::nullopt, false};
  if (o.cluster) {
    const ClusterStep step = cluster_step(tests, o);
    b.ended = step.end;
    run.only = step.only;
    run.collect = step.collect;
    if (step.end && !step.only && !step.collect) return b;
  }
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
  const CampaignOutcome out = run_campaign_loop(loop, run);
  b.seconds = out.seconds;
  b.interrupted = out.interrupted;
  if (out.interrupted) b.interrupted_dir = tests[out.interrupted_test].dir.string();
  return b;
}

}  // namespace simsols
