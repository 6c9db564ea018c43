// The cluster flags (cluster_flags.h).
#include "app/cli/cluster_flags.h"

#include <algorithm>
#include <cstdio>

#include "solver/common/errors.h"

namespace simsols {

namespace fs = std::filesystem;

constexpr const char* kOneKindOfRun =
    "--emit, --task and --collect each make a different run: give one";

// The group the cluster flags are listed under in --help; given_args
// leaves them out by it (and the hidden --collect-mode, group "").
constexpr const char* kClusterGroup = "Cluster";

void add_cluster_flags(CLI::App* cmd, ClusterFlags& f) {
  cmd->add_option("--emit", f.emit,
                  "slurm: write OUT/slurm/ (a job array, one task per test, and a job that "
                  "collects them; docs/cluster.md) and run nothing")
      ->group(kClusterGroup);
  cmd->add_option("--task", f.task,
                  "Run only test K (0-based, the array task's index) and no report")
      ->group(kClusterGroup);
  cmd->add_option("--collect", f.collect,
                  "Write the report of the finished tests in DIR (a folder written with --emit "
                  "slurm)")
      ->group(kClusterGroup);
  cmd->add_flag("--collect-mode", f.collecting)->group("");  // set by --collect's re-parse
}

CampaignRun campaign_run(const ClusterFlags& f, const std::string& out_dir,
                         std::function<bool()> stop, bool quiet) {
  CampaignRun run;
  run.stop_requested = std::move(stop);
  run.quiet = quiet;
  if (f.emitting() && f.emit != "slurm")
    throw UsageError("bad_enum", "--emit", "'" + f.emit + "' is not one of: slurm");
  if (f.task < -1)
    throw UsageError("out_of_range", "--task", std::to_string(f.task) + " is below 0");
  const int given = int(f.emitting()) + int(f.task >= 0) + int(f.collecting);
  if (given > 1)
    throw UsageError("conflict", "--task", kOneKindOfRun);
  if ((f.emitting() || f.task >= 0) && out_dir.empty())
    throw UsageError("missing_field", "--out", "give the folder the tests run in");
  if (f.task >= 0) run.only = static_cast<size_t>(f.task);
  run.collect = f.collecting;
  return run;
}

int collect_from_manifest(const ClusterFlags& f, const std::string& command,
                          CommandRunner (*add)(CLI::App&)) {
  if (f.task >= 0 || f.emitting())
    throw UsageError("conflict", "--collect", kOneKindOfRun);
  const fs::path dir = fs::absolute(f.collect).lexically_normal();
  const fs::path file = dir / "slurm" / "manifest.toml";
  Manifest m = read_manifest(dir);
  if (m.command != command)
    throw SceneError("not_applicable", file.string(), 0, "command",
                     "this folder holds a `" + m.command + "` job: collect it with simsols " +
                         m.command + " --collect " + dir.string());
  for (size_t k = 0; k + 1 < m.args.size(); ++k)
    if (m.args[k] == "--out") m.args[k + 1] = dir.string();  // the folder may have moved
  m.args.push_back("--collect-mode");
  CLI::App app;
  const CommandRunner runner = add(app);
  std::reverse(m.args.begin(), m.args.end());  // CLI11 takes them last first
  try {
    app.parse(m.args);
  } catch (const CLI::ParseError& e) {
    throw SceneError("bad_args", file.string(), 0, "args",
                     std::string("does not parse as the command's arguments: ") + e.what());
  }
  return runner();
}

namespace {

void emit_job(const std::string& command, const std::vector<std::string>& args,
              const std::string& out_dir, const std::vector<ClusterTest>& tests,
              const std::string& batch) {
  ClusterJob job;
  job.command = command;
  job.args = args;
  job.out_dir = fs::absolute(out_dir).lexically_normal();
  job.executable = fs::read_symlink("/proc/self/exe");
  job.tests = tests;
  job.batch = batch;
  write_slurm_job(job);
  const fs::path slurm = job.out_dir / "slurm";
  std::printf("wrote %s: manifest.toml (%zu tests%s%s), array.sbatch, collect.sbatch, submit.sh\n"
              "submit with: %s [sbatch options, e.g. --partition=P]\n"
              "collect by hand: simsols %s --collect %s\n",
              slurm.string().c_str(), tests.size(), batch.empty() ? "" : " of batch ",
              batch.c_str(), (slurm / "submit.sh").string().c_str(), command.c_str(),
              job.out_dir.string().c_str());
}

}  // namespace

BatchCluster batch_cluster(const ClusterFlags& f, const std::string& command,
                           const std::vector<std::string>& args, const std::string& out_dir) {
  const CampaignRun checked = campaign_run(f, out_dir, {}, true);  // the flags' own checks
  BatchCluster c;
  if (f.emitting())
    c.mode = BatchCluster::Mode::emit;
  else if (checked.only)
    c.mode = BatchCluster::Mode::task, c.task = *checked.only;
  else if (f.collecting)
    c.mode = BatchCluster::Mode::collect;
  c.manifest = (fs::path(out_dir) / "slurm" / "manifest.toml").string();
  if (c.mode != BatchCluster::Mode::emit && c.mode != BatchCluster::Mode::here &&
      fs::exists(c.manifest))
    c.job_tests = read_manifest(out_dir).tests;
  c.write_job = [command, args, out_dir](const std::vector<BatchTest>& tests,
                                         const std::string& batch) {
    emit_job(command, args, out_dir, cluster_tests(tests), batch);
  };
  return c;
}

bool emit_or_check_plan(const ClusterFlags& f, const std::string& command,
                        const std::vector<std::string>& args, const std::string& out_dir,
                        const std::vector<ClusterTest>& tests) {
  if (f.task >= 0 && fs::exists(fs::path(out_dir) / "slurm" / "manifest.toml")) {
    const Manifest m = read_manifest(out_dir);
    std::vector<std::string> names;
    for (const ClusterTest& t : tests) names.push_back(t.name);
    if (names != m.tests)
      throw UsageError("conflict", "--task",
                       "these arguments plan other tests than " + out_dir +
                           "/slurm/manifest.toml lists (" + std::to_string(names.size()) +
                           " against " + std::to_string(m.tests.size()) +
                           "): run the array's own command, or emit the job again");
  }
  if (!f.emitting()) return false;
  emit_job(command, args, out_dir, tests, "");
  return true;
}

namespace {

// An absolute path for a stored command line ("" stays "").
std::string absolute_arg(const std::string& path) {
  return path.empty() ? path : fs::absolute(path).lexically_normal().string();
}

// One option's words: a positional's values, a set flag's name, or the
// name before each value.
void add_option_words(const CLI::Option& o, bool path, std::vector<std::string>& out) {
  if (o.get_expected_max() == 0) {  // a flag
    if (o.as<bool>()) out.push_back(o.get_name());
    return;
  }
  for (const std::string& value : o.results()) {
    if (!o.get_positional()) out.push_back(o.get_name());
    out.push_back(path ? absolute_arg(value) : value);
  }
}

}  // namespace

std::vector<std::string> given_args(const CLI::App* cmd, const std::vector<std::string>& paths) {
  std::vector<std::string> words;
  for (const CLI::App* a = cmd; a && a->get_parent(); a = a->get_parent())
    words.insert(words.begin(), a->get_name());
  const auto options = cmd->get_options();
  for (bool positional : {true, false})
    for (const CLI::Option* o : options) {
      const bool cluster = o->get_group() == kClusterGroup || o->get_group().empty();
      if (o->get_positional() != positional || o->count() == 0 || cluster) continue;
      const bool path = std::find(paths.begin(), paths.end(), o->get_name()) != paths.end();
      add_option_words(*o, path, words);
    }
  return words;
}

}  // namespace simsols
