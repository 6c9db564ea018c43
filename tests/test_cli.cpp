// The simsols executable end to end: a bad scene writes nothing and exits
// with status 2; a run stopped at a checkpoint and resumed with --resume ends
// with the same state hash as the uninterrupted run; outputs exist.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string out;
};

Result run(const std::string& args) {
  const std::string cmd = std::string(SIMSOLS_EXE) + " " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

std::string hash_of(const std::string& out) {
  const auto at = out.find("state hash ");
  return at == std::string::npos ? "" : out.substr(at + 11, 16);
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("simsols_cli_" + name);
  fs::remove_all(d);
  return d;
}

const std::string kScene = std::string(SIMSOLS_ASSETS_DIR) + "/scenes/example_minimal.toml";

TEST(Cli, BadSceneWritesNothing) {
  const fs::path out = fresh_dir("bad");
  const Result r = run("run " + std::string(SIMSOLS_ASSETS_DIR) +
                       "/tests/bad_scenes/negative_radius.toml --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("negative_radius.toml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("radius"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written on a failed load";
}

TEST(Cli, BadFlagIsRefused) {
  const fs::path out = fresh_dir("flag");
  const Result r = run("run " + kScene + " --out " + out.string() + " --precision quad");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--precision"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, StopAndResumeIsBitForBit) {
  const fs::path a = fresh_dir("straight"), b = fresh_dir("resumed");
  const Result straight = run("run " + kScene + " --out " + a.string() + " -q --duration 0.002");
  ASSERT_EQ(straight.status, 0) << straight.out;
  const Result first = run("run " + kScene + " --out " + b.string() +
                           " -q --duration 0.002 --stop-after 777");
  ASSERT_EQ(first.status, 0) << first.out;
  EXPECT_NE(first.out.find("stopped at step 777"), std::string::npos) << first.out;
  const Result second = run("run --resume --out " + b.string() + " -q --duration 0.002");
  ASSERT_EQ(second.status, 0) << second.out;
  EXPECT_FALSE(hash_of(straight.out).empty()) << straight.out;
  EXPECT_EQ(hash_of(second.out), hash_of(straight.out)) << second.out;
  for (const char* f : {"series.csv", "scene.toml", "scene.resolved.toml", "checkpoint.bin"})
    EXPECT_TRUE(fs::exists(b / f)) << f;
  // the time series of the resumed run has no duplicate rows
  std::ifstream sa(a / "series.csv"), sb(b / "series.csv");
  const std::string ta((std::istreambuf_iterator<char>(sa)), {});
  const std::string tb((std::istreambuf_iterator<char>(sb)), {});
  EXPECT_EQ(ta, tb);
}

}  // namespace
