// The cluster flags every multi-test command shares (campaign, study
// sensitivity; app/experiment/cluster.h):
//   --emit slurm   write DIR/slurm/ (the job array and its collector), run nothing
//   --task K       run test K of the plan only (an array task), no report
//   --collect DIR  write the report of DIR's finished tests, with the
//                  arguments its manifest recorded
// Read at the edge, passed down as CampaignRun::only / ::collect.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/experiment/calibration/test_batch.h"
#include "app/experiment/campaign_loop.h"
#include "app/experiment/cluster.h"

namespace simsols {

struct ClusterFlags {
  std::string emit;        // "" or "slurm"
  long long task = -1;     // -1: every test
  std::string collect;     // --collect DIR
  bool collecting = false;  // set when the manifest's command is parsed again
  bool emitting() const { return !emit.empty(); }
};

void add_cluster_flags(CLI::App* cmd, ClusterFlags& flags);

// The run of a multi-test command: stopped by `stop` (Ctrl-C), `quiet`,
// and the tests the flags select (`only` / `collect`), no device yet.
// Checks the flags' values and combinations (UsageError naming the flag).
CampaignRun campaign_run(const ClusterFlags& flags, const std::string& out_dir,
                         std::function<bool()> stop, bool quiet);

// --collect DIR: the `command` of DIR's manifest parsed again (registered
// by `add`, its --out replaced by DIR wherever the folder now is) with
// `collecting` set, and run; its exit status. Refuses --task and --emit
// beside it, and another command's folder.
int collect_from_manifest(const ClusterFlags& flags, const std::string& command,
                          CommandRunner (*add)(CLI::App&));

// After planning: with --emit slurm, writes the job of `tests` with the
// command's `args` (the words after `simsols`, paths absolute, no cluster
// flags) into `out_dir`/slurm, prints how to submit it and returns true
// (the command ends there). With --task, checks that the plan is the one
// the manifest in `out_dir` lists (the same tests in the same order), so an
// array task never runs another test than its index names.
bool emit_or_check_plan(const ClusterFlags& flags, const std::string& command,
                        const std::vector<std::string>& args, const std::string& out_dir,
                        const std::vector<ClusterTest>& tests);

// A command run in batches (calibrate, predict; test_batch.h): what the
// flags make of its batches. --task and --collect read the tests of the
// job in `out_dir`'s manifest; a batch's job is written with the
// command's `args` (given_args) and its name.
BatchCluster batch_cluster(const ClusterFlags& flags, const std::string& command,
                           const std::vector<std::string>& args, const std::string& out_dir);

// The tests of a plan as the cluster files list them.
template <class Test>
std::vector<ClusterTest> cluster_tests(const std::vector<Test>& tests) {
  std::vector<ClusterTest> out;
  for (const Test& t : tests)
    out.push_back({t.scene.name, std::filesystem::absolute(t.dir),
                   static_cast<int>(t.scene.particles.size()), t.cost});
  return out;
}

// The words after `simsols` that give `cmd` what it was given again: its
// name (and its parents'), the positionals' values, then each option given
// with each of its values as parsed (flags by their name when set); the
// options named in `paths` (e.g. "base", "--out") made absolute, the
// cluster flags (their --help group) and hidden options left out. One
// source for the command line an array task reruns: a new option travels
// without being listed here.
std::vector<std::string> given_args(const CLI::App* cmd, const std::vector<std::string>& paths);

}  // namespace simsols
