#include "app/experiment/campaign_loop.h"

#include <chrono>
#include <cstdio>

#include "app/experiment/run_cost.h"
#include "solver/common/errors.h"

namespace simsols {

namespace fs = std::filesystem;

namespace {

// --task and --collect: the index must name a test; every test collected
// must have finished.
void check_selection(const CampaignLoop& loop, const CampaignRun& run) {
  if (run.only && *run.only >= loop.count)
    throw UsageError("out_of_range", "--task",
                     std::to_string(*run.only) + " is out of range, allowed [0, " +
                         std::to_string(loop.count - 1) + "] (one of the " +
                         std::to_string(loop.count) + " " + loop.what + ")");
  if (!run.collect) return;
  std::string missing;
  size_t n = 0;
  for (size_t k = 0; k < loop.count; ++k)
    if (!programme_finished(loop.dir(k).string()))
      missing += (n++ ? ", " : "") + std::to_string(k) + " (" + loop.name(k) + ")";
  if (n > 0)
    throw UsageError("unfinished", "--collect",
                     std::to_string(n) + " of " + std::to_string(loop.count) + " " + loop.what +
                         " have not finished: " + missing +
                         "; run them first (their array tasks, or the command without --collect)");
}

}  // namespace

CampaignOutcome run_campaign_loop(const CampaignLoop& loop, const CampaignRun& run) {
  check_selection(loop, run);
  CampaignOutcome outcome;
  double total_cost = 0, done_cost = 0;
  const auto selected = [&](size_t k) { return !run.only || *run.only == k; };
  for (size_t k = 0; k < loop.count; ++k)
    if (selected(k) && !programme_finished(loop.dir(k).string())) total_cost += loop.cost(k);
  if (!run.quiet)
    std::fprintf(stderr, "[campaign] %zu %s, ~%.3g particle-steps to run, ~%s at %.0e "
                 "particle-steps/s\n", loop.count, loop.what.c_str(), total_cost,
                 human_seconds(total_cost / kAssumedRate).c_str(), kAssumedRate);
  for (size_t k = 0; k < loop.count; ++k) {
    if (!selected(k)) continue;
    const fs::path dir = loop.dir(k);
    const std::string label = "campaign " + std::to_string(k + 1) + "/" +
                              std::to_string(loop.count) + " " + loop.name(k);
    if (programme_finished(dir.string())) {
      loop.keep(k);
      if (!run.quiet) std::fprintf(stderr, "[%s] finished earlier, kept\n", label.c_str());
      continue;
    }
    if (!run.quiet && done_cost > 0)
      std::fprintf(stderr, "[campaign] %zu/%zu tests, %.0f s so far, ETA %.0f s\n", k,
                   loop.count, outcome.seconds,
                   outcome.seconds / done_cost * (total_cost - done_cost + loop.later_cost));
    ProgrammeRunOptions o;
    o.device = run.device;
    o.out_dir = dir.string();
    o.label = label;
    o.quiet = run.quiet;
    o.resume = fs::exists(dir / "checkpoint.bin") && fs::exists(dir / loop.rows_file);
    o.stop_requested = run.stop_requested;
    o.later_particle_steps = total_cost - done_cost - loop.cost(k) + loop.later_cost;
    const auto t0 = std::chrono::steady_clock::now();
    if (loop.run(k, o)) {
      outcome.interrupted = true;
      outcome.interrupted_test = k;
      return outcome;
    }
    outcome.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    done_cost += loop.cost(k);
    loop.print(k);
  }
  return outcome;
}

}  // namespace simsols
