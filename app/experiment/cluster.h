// Campaigns and studies on a Slurm cluster (docs/cluster.md).
//
// A campaign or a study is a list of independent tests, each in its own
// folder, each resumable from its checkpoint. On a cluster each test is
// one task of a job array, running the same command with `--task K`
// (CampaignRun::only): it plans the same tests, runs test K only (resuming
// its checkpoint when the scheduler requeued it) and writes no report. A
// job that depends on the array runs the command with `--collect DIR`:
// every test must have finished, and the report (tables, plots, envelopes)
// is written from their folders exactly as a local run writes it.
//
// `--emit slurm` writes, in DIR/slurm/:
//   manifest.toml   the command (its arguments, absolute paths), the
//                   executable, and per test its index, name, folder,
//                   beads, estimated particle-steps, time and memory
//   array.sbatch    the job array: one task per test, requeueable, with the
//                   largest test's time and memory
//   collect.sbatch  the collecting job
//   submit.sh       submits both, the second after the array
//                   (--dependency=afterany); extra arguments go to both
//                   sbatch calls (a partition, an account, ...)
// Each file is written whole (write_file_atomic) and the scripts are
// executable. The manifest is what `--collect DIR` reads back.
//
// A command that runs in batches (a calibration's rounds, each drawn from
// the last's results) writes one batch's job at a time, named in the
// manifest (`batch`). Its collecting job runs `--collect`, which writes
// the next batch's job once this one's tests have finished; the collecting
// job then submits it with the same sbatch arguments (submit.sh hands them
// to it), until the last batch's collection writes the report.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace simsols {

struct ClusterTest {
  std::string name;
  std::filesystem::path dir;
  int particles = 0;
  double particle_steps = 0;
};

// A test's needs on a cluster node, estimated from its scene: time at a
// conservative rate (a 2-core CPU's, half kAssumedRate; a GPU is faster),
// doubled and at least 10 minutes; memory: the process and OpenCL
// runtime (400 MB) plus ~12 kB per bead (host and device copies, rows,
// checkpoints).
struct ClusterNeeds {
  int minutes = 10;
  int memory_mb = 512;
};
ClusterNeeds cluster_needs(const ClusterTest& t);

struct ClusterJob {
  std::string command;             // "campaign", "study sensitivity"
  std::vector<std::string> args;   // the command's words and flags, paths absolute (no --task)
  std::filesystem::path out_dir;   // absolute
  std::filesystem::path executable;
  std::vector<ClusterTest> tests;
  std::string batch;  // a command run in batches: this job's ("round0"); else ""
};

// Writes DIR/slurm/{manifest.toml, array.sbatch, collect.sbatch, submit.sh}.
// Throws UsageError naming --out when DIR holds a space or a '%' (sbatch's
// #SBATCH lines and its file patterns cannot carry them) or the job has no
// tests.
void write_slurm_job(const ClusterJob& job);

// What the manifest in `dir` recorded (throws SceneError naming the
// manifest's file and field when it is missing or malformed).
struct Manifest {
  std::string command;
  std::vector<std::string> args;
  std::vector<std::string> tests;  // the tests' names, in array order
  std::string batch;               // "" for a command run in one job
};
Manifest read_manifest(const std::filesystem::path& dir);

// A word for a POSIX shell: quoted unless it is plainly safe.
std::string shell_word(const std::string& word);

}  // namespace simsols
