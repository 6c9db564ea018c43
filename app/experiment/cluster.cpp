// The Slurm job of a campaign or study (cluster.h).
#include "app/experiment/cluster.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "app/experiment/run_cost.h"
#include "solver/common/atomic_file.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;

std::string command_line(const ClusterJob& job, const std::string& tail) {
  std::string line = shell_word(job.executable.string());
  for (const std::string& a : job.args) line += " " + shell_word(a);
  return line + tail;
}

std::string toml_string(const std::string& s) {
  std::ostringstream o;
  o << toml::value<std::string>(s);
  return o.str();
}

std::string manifest_text(const ClusterJob& job) {
  std::ostringstream o;
  o << "# simsols " << job.command << " --emit slurm: the tests of this job array\n"
    << "# (docs/cluster.md). `simsols " << job.command
    << " --collect DIR` reads `args` back.\n"
    << "command = " << toml_string(job.command) << "\nexecutable = "
    << toml_string(job.executable.string()) << "\nout = " << toml_string(job.out_dir.string())
    << "\nargs = [";
  for (size_t k = 0; k < job.args.size(); ++k) o << (k ? ", " : "") << toml_string(job.args[k]);
  o << "]\ntests = " << job.tests.size() << "\n";
  if (!job.batch.empty()) o << "batch = " << toml_string(job.batch) << "\n";
  for (size_t k = 0; k < job.tests.size(); ++k) {
    const ClusterTest& t = job.tests[k];
    const ClusterNeeds n = cluster_needs(t);
    o << "\n[[test]]\nindex = " << k << "\nname = " << toml_string(t.name)
      << "\ndir = " << toml_string(t.dir.string()) << "\nparticles = " << t.particles
      << "\nparticle_steps = " << t.particle_steps << "\ntime_limit_min = " << n.minutes
      << "\nmemory_mb = " << n.memory_mb << "\n";
  }
  return o.str();
}

std::string array_script(const ClusterJob& job, const fs::path& slurm) {
  ClusterNeeds most;
  for (const ClusterTest& t : job.tests) {
    const ClusterNeeds n = cluster_needs(t);
    most.minutes = std::max(most.minutes, n.minutes);
    most.memory_mb = std::max(most.memory_mb, n.memory_mb);
  }
  std::ostringstream o;
  o << "#!/bin/bash\n"
    << "# One array task per test of `simsols " << job.command << "` (manifest.toml).\n"
    << "# A requeued task resumes its test from its checkpoint; a finished one is kept.\n"
    << "# Time and memory: the largest test's estimate (docs/cluster.md).\n"
    << "#SBATCH --job-name=simsols-" << job.out_dir.filename().string() << "\n"
    << "#SBATCH --array=0-" << job.tests.size() - 1 << "\n"
    << "#SBATCH --requeue\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=2\n"
    << "#SBATCH --time=" << most.minutes << "\n#SBATCH --mem=" << most.memory_mb << "M\n"
    << "#SBATCH --output=" << (slurm / "logs" / "task_%a.out").string() << "\n"
    << "#SBATCH --open-mode=append\n"
    << "# SIGTERM two minutes before the limit: the test writes its checkpoint.\n"
    << "#SBATCH --signal=B:TERM@120\n"
    << "set -uo pipefail\n"
    << "# the batch shell gets the signal: pass it on, wait for the checkpoint\n"
    << "pid=\ntrap '[ -n \"$pid\" ] && kill -TERM \"$pid\"' TERM\n"
    << command_line(job, " --task \"$SLURM_ARRAY_TASK_ID\" &\n")
    << "pid=$!\nstatus=0\n"
    << "while kill -0 \"$pid\" 2>/dev/null; do wait \"$pid\"; status=$?; done\nexit \"$status\"\n";
  return o.str();
}

std::string collect_script(const ClusterJob& job, const fs::path& slurm) {
  std::ostringstream o;
  o << "#!/bin/bash\n"
    << "# Collects the array's tests into the report, as a local run writes it.\n"
    << "#SBATCH --job-name=simsols-" << job.out_dir.filename().string() << "-collect\n"
    << "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n#SBATCH --time=30\n#SBATCH --mem=2048M\n"
    << "#SBATCH --output=" << (slurm / "logs" / "collect.out").string() << "\n"
    << (job.batch.empty() ? "" : "#SBATCH --open-mode=append\n") << "set -euo pipefail\n";
  const std::string collect = shell_word(job.executable.string()) + " " + job.command +
                              " --collect " + shell_word(job.out_dir.string()) + "\n";
  if (job.batch.empty()) {
    o << "exec " << collect;
    return o.str();
  }
  // run in batches: the collection writes the next batch's job (its
  // manifest names another batch) until the last writes the report; the
  // log keeps every batch's collection
  const std::string manifest = shell_word((slurm / "manifest.toml").string());
  o << collect << "if ! grep -qxF " << shell_word("batch = " + toml_string(job.batch)) << " "
    << manifest << "; then\n  exec " << shell_word((slurm / "submit.sh").string())
    << " \"$@\"  # the next batch, with this job's sbatch arguments\nfi\n";
  return o.str();
}

std::string submit_script(const ClusterJob& job) {
  std::ostringstream o;
  o << "#!/bin/sh\n"
    << "# Submits the array (" << job.tests.size()
    << " tests), then the collecting job after it.\n"
    << "# Arguments go to both sbatch calls: ./submit.sh --partition=cpu --account=A\n"
    << "set -eu\ncd \"$(dirname \"$0\")\"\n"
    << "array=$(sbatch --parsable \"$@\" array.sbatch)\n"
    << "array=${array%%;*}\n"
    << "collect=$(sbatch --parsable \"$@\" --dependency=afterany:\"$array\" collect.sbatch"
    << (job.batch.empty() ? "" : " \"$@\"") << ")\n"
    << "echo \"array job $array, collect job ${collect%%;*}\"\n";
  return o.str();
}

}  // namespace

ClusterNeeds cluster_needs(const ClusterTest& t) {
  ClusterNeeds n;
  const double seconds = 2 * t.particle_steps / (0.5 * kAssumedRate);
  n.minutes = std::max(10, static_cast<int>(std::ceil(seconds / 60)));
  n.memory_mb = 400 + static_cast<int>(std::ceil(t.particles * 12e3 / 1048576.0));
  n.memory_mb = (n.memory_mb + 127) / 128 * 128;
  return n;
}

std::string shell_word(const std::string& w) {
  const bool safe = !w.empty() && std::all_of(w.begin(), w.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("/._-,=+:").find(c) != std::string_view::npos;
  });
  if (safe) return w;
  std::string q = "'";
  for (char c : w) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void write_slurm_job(const ClusterJob& job) {
  const std::string out = job.out_dir.string();
  if (out.find_first_of(" %\t\n'\"") != std::string::npos)
    throw UsageError("bad_path", "--out",
                     "'" + out + "' holds a space, a quote or a '%': sbatch's #SBATCH lines "
                     "cannot carry it; choose another folder");
  if (job.tests.empty()) throw UsageError("missing_field", "--out", "no tests to run");
  const fs::path slurm = job.out_dir / "slurm";
  fs::create_directories(slurm / "logs");
  write_file_atomic((slurm / "manifest.toml").string(), manifest_text(job));
  const std::pair<const char*, std::string> scripts[] = {
      {"array.sbatch", array_script(job, slurm)},
      {"collect.sbatch", collect_script(job, slurm)},
      {"submit.sh", submit_script(job)}};
  for (const auto& [name, text] : scripts) {
    write_file_atomic((slurm / name).string(), text);
    fs::permissions(slurm / name, fs::perms::owner_exec | fs::perms::group_exec |
                                      fs::perms::others_exec, fs::perm_options::add);
  }
}

Manifest read_manifest(const fs::path& dir) {
  const fs::path file = dir / "slurm" / "manifest.toml";
  if (!fs::exists(file))
    throw SceneError("io", file.string(), 0, "--collect",
                     "no manifest here: --collect takes the --out folder of a command run "
                     "with --emit slurm");
  toml::table t;
  try {
    t = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw SceneError("syntax", file.string(), int(e.source().begin.line), "",
                     std::string(e.description()));
  }
  Manifest m;
  m.command = t["command"].value_or(std::string());
  const toml::array* args = t["args"].as_array();
  if (args)
    for (const toml::node& a : *args)
      if (const auto s = a.value<std::string>()) m.args.push_back(*s);
  if (!args || m.args.size() != args->size() || m.args.empty() || m.command.empty())
    throw SceneError("missing_field", file.string(), 0, "args",
                     "must be the command's arguments, an array of strings, with its command");
  if (const toml::array* tests = t["test"].as_array())
    for (const toml::node& n : *tests)
      if (const toml::table* test = n.as_table()) m.tests.push_back((*test)["name"].value_or(std::string()));
  m.batch = t["batch"].value_or(std::string());
  return m;
}

}  // namespace simsols
