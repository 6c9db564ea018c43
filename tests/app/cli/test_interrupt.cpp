// Nothing lost on Ctrl-C, kill or kill -9 (app/cli/interrupt.h, checkpoint.h),
// the executable end to end:
//   - a shear test interrupted with SIGINT while shearing exits with 130,
//     says how to resume, and resumed ends with the same rows as the
//     uninterrupted test;
//   - a plain run stopped with SIGTERM (143; sent twice, as a batch
//     scheduler may) and resumed ends with the same state hash and
//     series.csv;
//   - a second SIGINT exits at once;
//   - SIGINT while the specimen is prepared stops the preparation;
//   - kill -9 at random moments of a run that writes a checkpoint every
//     step always leaves a checkpoint that verifies and loads.
#include <algorithm>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "solver/io/checkpoint.h"
#include "solver/core/simulation.h"
#include "tests/support/test_support.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("simsols_interrupt_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The executable in the background, stdout and stderr into `log`.
struct Child {
  pid_t pid = -1;
  fs::path log;
  Child(const std::vector<std::string>& args, fs::path log_path) : log(std::move(log_path)) {
    pid = fork();
    if (pid == 0) {
      FILE* f = std::fopen(log.c_str(), "w");
      dup2(fileno(f), 1);
      dup2(fileno(f), 2);
      std::vector<char*> argv{const_cast<char*>(SIMSOLS_EXE)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(SIMSOLS_EXE, argv.data());
      _exit(127);
    }
  }
  // Waits until the log holds `text` (true) or the process ended (false).
  bool wait_for(const std::string& text, std::chrono::seconds limit = 300s) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      if (read(log).find(text) != std::string::npos) return true;
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        exited_ = true;
        status_ = status;
        return read(log).find(text) != std::string::npos;
      }
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }
  // Exit status (128 + signal when killed by one).
  int wait() {
    if (!exited_) waitpid(pid, &status_, 0);
    exited_ = true;
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + WTERMSIG(status_);
  }
  std::string output() const { return read(log); }

 private:
  bool exited_ = false;
  int status_ = 0;
};

int run(const std::vector<std::string>& args, const fs::path& log) {
  Child c(args, log);
  return c.wait();
}

// The suite's small shear test with a longer shear, so that a signal
// lands while it shears.
fs::path long_shear_scene(const fs::path& dir) {
  std::string text = read(std::string(SIMSOLS_ASSETS_DIR) + "/tests/shear_small.toml");
  const std::string key = "shear_displacement = 0.3e-3";
  const size_t at = text.find(key);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, key.size(), "shear_displacement = 1.5e-3");
  const fs::path p = dir / "shear_long.toml";
  std::ofstream(p) << text;
  return p;
}

std::string before_wall(const std::string& summary) {
  return summary.substr(0, summary.find("wall_seconds"));
}

TEST(Interrupt, ShearTestCtrlCThenResumeGivesTheSameRows) {
  const fs::path d = fresh_dir("shear");
  const fs::path scene = long_shear_scene(d);
  const fs::path a = d / "straight", b = d / "interrupted";
  ASSERT_EQ(run({"run", scene.string(), "--out", a.string(), "-q"}, d / "a.log"), 0)
      << read(d / "a.log");
  Child c({"run", scene.string(), "--out", b.string()}, d / "b.log");
  ASSERT_TRUE(c.wait_for("shearing at")) << c.output();
  std::this_thread::sleep_for(500ms);
  kill(c.pid, SIGINT);
  ASSERT_EQ(c.wait(), 130) << c.output();
  const std::string out = c.output();
  EXPECT_NE(out.find("interrupted"), std::string::npos) << out;
  EXPECT_NE(out.find("resume with: simsols run --resume --out " + b.string()), std::string::npos)
      << out;
  EXPECT_FALSE(fs::exists(b / "summary.txt")) << "an interrupted test is not finished";
  ASSERT_TRUE(fs::exists(b / "checkpoint.bin"));
  const std::string rows_at_stop = read(b / "shear.csv");
  EXPECT_GT(std::count(rows_at_stop.begin(), rows_at_stop.end(), '\n'), 1)
      << "the rows measured before the signal are written";

  ASSERT_EQ(run({"run", "--resume", "--out", b.string(), "-q"}, d / "c.log"), 0)
      << read(d / "c.log");
  EXPECT_NE(read(d / "c.log").find("resumed at step "), std::string::npos) << read(d / "c.log");
  EXPECT_NE(read(d / "c.log").find("shear dx = "), std::string::npos) << "says the displacement";
  EXPECT_EQ(read(a / "shear.csv"), read(b / "shear.csv"));
  EXPECT_EQ(before_wall(read(a / "summary.txt")), before_wall(read(b / "summary.txt")));
  // a finished test is not resumed again (nor turned into another run)
  ASSERT_EQ(run({"run", "--resume", "--out", b.string()}, d / "e.log"), 0);
  EXPECT_NE(read(d / "e.log").find("finished already"), std::string::npos) << read(d / "e.log");
  EXPECT_EQ(read(a / "shear.csv"), read(b / "shear.csv"));
}

// summary.csv without its last column (wall_seconds).
std::string without_wall(const std::string& csv) {
  std::string out;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

// A campaign of two tests interrupted while its second test shears, then
// rerun (which resumes it): the same table as the uninterrupted campaign.
TEST(Interrupt, CampaignCtrlCThenRerunGivesTheSameTable) {
  const fs::path d = fresh_dir("campaign");
  const std::string base = std::string(SIMSOLS_ASSETS_DIR) + "/tests/shear_small.toml";
  auto args = [&](const fs::path& out) {
    return std::vector<std::string>{"campaign", base, "--out", out.string(), "--sizes", "6.35",
                                    "--stresses", "100,300", "--displacement", "1"};
  };
  const fs::path a = d / "straight", b = d / "interrupted";
  ASSERT_EQ(run(args(a), d / "a.log"), 0) << read(d / "a.log");
  Child c(args(b), d / "b.log");
  ASSERT_TRUE(c.wait_for("[campaign 2/2 d6.35mm_300kPa] shearing at")) << c.output();
  std::this_thread::sleep_for(300ms);
  kill(c.pid, SIGINT);
  ASSERT_EQ(c.wait(), 130) << c.output();
  EXPECT_NE(c.output().find("campaign interrupted in test 2/2"), std::string::npos) << c.output();
  EXPECT_FALSE(fs::exists(b / "summary.csv"));
  ASSERT_EQ(run(args(b), d / "c.log"), 0) << read(d / "c.log");
  const std::string log = read(d / "c.log");
  EXPECT_NE(log.find("finished earlier, kept"), std::string::npos) << log;
  EXPECT_NE(log.find("resumed at step "), std::string::npos) << log;
  EXPECT_EQ(without_wall(read(b / "summary.csv")), without_wall(read(a / "summary.csv")));
}

// cases.csv without the wall-time columns (wall_s, particle_steps_per_s).
std::vector<std::string> cases_without_wall(const fs::path& csv) {
  std::vector<std::string> rows;
  std::istringstream in(read(csv));
  size_t wall = 0;  // the column of wall_s; particle_steps_per_s follows it
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cols;
    std::istringstream l(line);
    for (std::string c; std::getline(l, c, ',');) cols.push_back(c);
    if (rows.empty()) wall = static_cast<size_t>(std::find(cols.begin(), cols.end(), "wall_s") - cols.begin());
    if (cols.size() > wall + 1) cols.erase(cols.begin() + wall, cols.begin() + wall + 2);
    std::string r;
    for (const std::string& c : cols) r += c + ",";
    rows.push_back(r);
  }
  return rows;
}

// The reduced accuracy study (its reference, the reference's round-off twin
// and one precision case, one member each), interrupted while the third
// run shears and resumed: the same table.
TEST(Interrupt, StudyCtrlCThenResumeGivesTheSameCases) {
  const fs::path d = fresh_dir("study");
  const fs::path a = d / "straight", b = d / "interrupted";
  const std::vector<std::string> args{"study", "accuracy", "--preset",   "ci",       "--ensemble",
                                      "1",     "--knob",   "precision", "--specimen", "layered"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> v = args;
    v.insert(v.end(), extra.begin(), extra.end());
    return v;
  };
  ASSERT_EQ(run(with({"--out", a.string(), "-q"}), d / "a.log"), 0) << read(d / "a.log");
  Child c(with({"--out", b.string()}), d / "b.log");
  // Interrupt the third case while it shears. It prints nothing until it
  // ends, and a fixed wait outlasts it on a faster machine, so the wait is
  // scaled by the second case's duration: the third (double at dt 0.2
  // against the reference's twin at 0.15) takes about 0.9 of it, its contact
  // checks the first fifth (measured: 6.4 s for the twin, 5.8 s for the
  // third, of which about 1.3 s of checks).
  ASSERT_TRUE(c.wait_for("[study 2/3]")) << c.output();
  const auto second = std::chrono::steady_clock::now();
  ASSERT_TRUE(c.wait_for("[study 3/3]")) << c.output();
  std::this_thread::sleep_for(0.5 * (std::chrono::steady_clock::now() - second));
  kill(c.pid, SIGINT);
  ASSERT_EQ(c.wait(), 130) << c.output();
  EXPECT_NE(c.output().find("study interrupted in case 3/3"), std::string::npos) << c.output();
  EXPECT_NE(c.output().find("--knob 'precision' --specimen layered --resume"), std::string::npos) << c.output();
  ASSERT_TRUE(fs::exists(b / "case_checkpoint.bin")) << c.output();
  ASSERT_EQ(run(with({"--out", b.string(), "--resume", "-q"}), d / "c.log"), 0)
      << read(d / "c.log");
  EXPECT_NE(read(d / "c.log").find("resumed after 2 of 3 cases (the next one from its checkpoint)"),
            std::string::npos)
      << read(d / "c.log");
  EXPECT_NE(read(d / "c.log").find("case resumed at step "), std::string::npos) << read(d / "c.log");
  EXPECT_FALSE(fs::exists(b / "case_checkpoint.bin"));
  const auto straight = cases_without_wall(a / "cases.csv");
  EXPECT_EQ(straight.size(), 4u) << "header and three runs";
  EXPECT_EQ(cases_without_wall(b / "cases.csv"), straight);
  // two cases at once, each on its own context and queue: the same results
  const fs::path j = d / "two_jobs";
  ASSERT_EQ(run(with({"--out", j.string(), "--jobs", "2", "-q"}), d / "j.log"), 0)
      << read(d / "j.log");
  EXPECT_EQ(cases_without_wall(j / "cases.csv"), straight);
  // another study's state is refused, naming the file
  Child other(std::vector<std::string>{"study", "accuracy", "--preset", "quick", "--out",
                                       b.string(), "--resume"},
              d / "d.log");
  EXPECT_EQ(other.wait(), 2) << other.output();
  EXPECT_NE(other.output().find("study_state.txt"), std::string::npos) << other.output();
}

// `layers` x 20 x 20 beads of 1 mm settling on a floor (6 000 for 15
// layers: 1 000 to 4 000 steps/s on two cores); with `checkpoint_every_step`
// most of the run is spent writing checkpoints (4 MB for 6 000 beads).
fs::path heavy_scene(const fs::path& dir, int layers, bool checkpoint_every_step) {
  const fs::path p = dir / "heavy.toml";
  std::ofstream(p) << R"([scene]
name = "heavy"
[[materials]]
name = "glass"
young_modulus = 62.784e9
poisson_ratio = 0.2
density = 2230
restitution = 0.87
sliding_friction = 0.02
rolling_friction = 5e-5
[[generators]]
type = "lattice"
material = "glass"
radius = 0.5e-3
arrangement = "cubic"
spacing = 1.05e-3
min = [0, 0, 0.01e-3]
max = [21e-3, 21e-3, )" << 1.05e-3 * layers + 0.05e-3 << R"(]
[[walls]]
name = "floor"
type = "plane"
material = "glass"
point = [0, 0, 0]
normal = [0, 0, 1]
[numerics]
precision = "float"
duration = 0.01
[output]
series_interval = 1e-5
)" << (checkpoint_every_step ? "checkpoint_interval = 1e-12\n" : "");
  return p;
}

std::string hash_of(const std::string& out) {
  const auto at = out.find("state hash ");
  return at == std::string::npos ? "" : out.substr(at + 11, 16);
}

TEST(Interrupt, PlainRunKillThenResumeGivesTheSameState) {
  const fs::path d = fresh_dir("plain");
  const std::string scene = heavy_scene(d, 15, false).string();
  const fs::path a = d / "straight", b = d / "interrupted";
  const std::vector<std::string> common{"--duration", "0.002", "-q"};  // 26 000 steps, > 6 s
  std::vector<std::string> args{"run", scene, "--out", a.string()};
  args.insert(args.end(), common.begin(), common.end());
  ASSERT_EQ(run(args, d / "a.log"), 0) << read(d / "a.log");
  args[3] = b.string();
  Child c(args, d / "b.log");
  ASSERT_TRUE(c.wait_for("cost:")) << c.output();
  std::this_thread::sleep_for(1s);
  kill(c.pid, SIGTERM);
  ASSERT_TRUE(c.wait_for("interrupted: finishing")) << c.output();
  kill(c.pid, SIGTERM);  // again, as Slurm and the job script both send it: still checkpointed
  ASSERT_EQ(c.wait(), 143) << c.output();
  EXPECT_NE(c.output().find("interrupted at step "), std::string::npos) << c.output();
  EXPECT_NE(c.output().find("resume with"), std::string::npos) << c.output();
  std::vector<std::string> resume{"run", "--resume", "--out", b.string()};
  resume.insert(resume.end(), common.begin(), common.end());
  ASSERT_EQ(run(resume, d / "c.log"), 0) << read(d / "c.log");
  EXPECT_NE(read(d / "c.log").find("resumed at step "), std::string::npos) << read(d / "c.log");
  EXPECT_FALSE(hash_of(read(d / "a.log")).empty()) << read(d / "a.log");
  EXPECT_EQ(hash_of(read(d / "c.log")), hash_of(read(d / "a.log")));
  EXPECT_EQ(read(a / "series.csv"), read(b / "series.csv"));
}

// Ctrl-C while the specimen is being prepared (tamped in three layers)
// stops the preparation between chunks of steps: status 130, the reason
// said, no checkpoint and no test files yet. The same command then goes on
// from the last layer it finished (tamping_state.txt).
TEST(Interrupt, CtrlCWhilePreparingStopsThePreparation) {
  const fs::path d = fresh_dir("prepare");
  std::string text = read(std::string(SIMSOLS_ASSETS_DIR) + "/tests/triaxial_small.toml");
  const std::string table = "[numerics]";
  ASSERT_NE(text.find(table), std::string::npos);
  text.insert(text.find(table),
              "[triaxial.specimen.preparation]\ntamping_layers = 3\nvoid_ratio = 0.6\n\n");
  std::ofstream(d / "tamped.toml") << text;
  Child c({"run", (d / "tamped.toml").string(), "--out", (d / "out").string()}, d / "log.txt");
  ASSERT_TRUE(c.wait_for("[prepare] layer 1 of 3")) << c.output();
  const auto sent = std::chrono::steady_clock::now();
  kill(c.pid, SIGINT);
  EXPECT_EQ(c.wait(), 130) << c.output();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  std::printf("[measure] a preparation stopped %.2f s after Ctrl-C\n", seconds);
  EXPECT_LT(seconds, 30) << c.output();  // a chunk of steps, not the rest of the tamping
  EXPECT_NE(c.output().find("stopped while preparing the specimen"), std::string::npos) << c.output();
  EXPECT_EQ(c.output().find("[prepare] layer 3 of 3"), std::string::npos) << c.output();
  EXPECT_FALSE(fs::exists(d / "out" / "checkpoint.bin"));
  EXPECT_FALSE(fs::exists(d / "out" / "triaxial.csv"));
  // the same command goes on from the last layer done (here the first;
  // that it ends as a straight run does: Preparation.LayeredTampingReaches...)
  EXPECT_TRUE(fs::exists(d / "out" / "tamping_state.txt"));
  Child again({"run", (d / "tamped.toml").string(), "--out", (d / "out").string()}, d / "log2.txt");
  ASSERT_TRUE(again.wait_for("[prepare] going on after layer 1 of 3")) << again.output();
  kill(again.pid, SIGINT);
  EXPECT_EQ(again.wait(), 130) << again.output();
  EXPECT_EQ(again.output().find("[prepare] layer 1 of 3"), std::string::npos) << again.output();
  EXPECT_TRUE(fs::exists(d / "out" / "tamping_state.txt"));
  EXPECT_FALSE(fs::exists(d / "out" / "tamping.csv"));
}

// 24 000 beads writing a 16 MB checkpoint every step: the second signal,
// sent as soon as the first is acknowledged, lands while the first is
// still being honoured.
TEST(Interrupt, SecondCtrlCExitsAtOnce) {
  const fs::path d = fresh_dir("twice");
  Child c({"run", heavy_scene(d, 60, true).string(), "--out", (d / "out").string(), "-q"},
          d / "b.log");
  ASSERT_TRUE(c.wait_for("cost:")) << c.output();
  std::this_thread::sleep_for(1s);
  kill(c.pid, SIGINT);
  ASSERT_TRUE(c.wait_for("interrupted: finishing")) << c.output();
  kill(c.pid, SIGINT);
  EXPECT_EQ(c.wait(), 130) << c.output();
  EXPECT_NE(c.output().find("second interrupt: exiting at once"), std::string::npos) << c.output();
  EXPECT_EQ(c.output().find("resume with"), std::string::npos) << c.output();
}

TEST(Interrupt, KillNineNeverLeavesAHalfCheckpoint) {
  const fs::path d = fresh_dir("kill9");
  const fs::path scene = heavy_scene(d, 15, true), out = d / "out";
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> ms(200, 1500);
  int mid_write = 0;
  for (int round = 0; round < 4; ++round) {
    std::vector<std::string> args{"run", scene.string(), "--out", out.string(), "-q"};
    if (round > 0) args = {"run", "--resume", "--out", out.string(), "-q"};
    Child c(args, d / ("round" + std::to_string(round) + ".log"));
    ASSERT_TRUE(c.wait_for("cost:")) << c.output();
    // wait for the first checkpoint of this run, then a random moment
    const auto first = fs::exists(out / "checkpoint.bin")
                           ? fs::last_write_time(out / "checkpoint.bin")
                           : fs::file_time_type::min();
    for (int i = 0; i < 3000 && (!fs::exists(out / "checkpoint.bin") ||
                                 fs::last_write_time(out / "checkpoint.bin") == first);
         ++i)
      std::this_thread::sleep_for(10ms);
    std::this_thread::sleep_for(std::chrono::milliseconds(ms(rng)));
    kill(c.pid, SIGKILL);
    EXPECT_EQ(c.wait(), 128 + SIGKILL);
    mid_write += fs::exists(out / "checkpoint.bin.tmp") ? 1 : 0;
    ASSERT_TRUE(fs::exists(out / "checkpoint.bin")) << c.output();
    EXPECT_NO_THROW(simsols::verify_checkpoint((out / "checkpoint.bin").string()))
        << "round " << round;
    const std::string series = read(out / "series.csv");
    ASSERT_FALSE(series.empty());
    EXPECT_EQ(series.back(), '\n') << "no half-written row in series.csv";
  }
  auto sim = simsols::load_checkpoint(simsols::default_device(), (out / "checkpoint.bin").string());
  EXPECT_GT(sim->steps(), 0);
  std::printf("[measure] kill -9 landed while a checkpoint was being written in %d of 4 rounds\n",
              mid_write);
}

}  // namespace
