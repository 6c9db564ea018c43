// Checkpoint files (solver/checkpoint.h, solver/input_file.h): a damaged
// file is refused before anything is built from it, whatever byte is
// damaged; a truncated one too; files that are neither a scene nor a
// checkpoint are named as such; an intact file loads to the same state.
#include <gtest/gtest.h>
#include <unistd.h>

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "checkpoint.h"
#include "errors.h"
#include "input_file.h"
#include "scene_toml.h"
#include "test_support.h"

namespace simsols::testing {
namespace {

namespace fs = std::filesystem;

std::vector<char> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), {});
}

void write_bytes(const fs::path& p, const std::vector<char>& b) {
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
}

// Two beads colliding over a floor: every dynamic buffer holds non-zero data.
Scene two_beads() {
  Scene s = empty_scene(Precision::Float, glass(0.5, 0.3, 1e-5));
  s.particles.push_back(sphere(1e-3, {0, 0, 1.05e-3}, {0.1, 0, -0.2}));
  s.particles.push_back(sphere(1e-3, {2.1e-3, 0, 1.2e-3}, {-0.1, 0, 0}, {0, 5, 0}));
  s.walls.push_back(plane("floor", {0, 0, 0}, {0, 0, 1}));
  s.numerics.duration = 1e-3;
  validate_scene(s, "two_beads");
  return s;
}

class CheckpointFile : public ::testing::Test {
 protected:
  void SetUp() override {
    // one folder per process: suites running side by side do not collide
    dir_ = fs::path(::testing::TempDir()) /
           ("simsols_checkpoint_file_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = dir_ / "checkpoint.bin";
    Simulation sim(default_device(), two_beads());
    sim.advance(300);
    hash_ = sim.hash();
    save_checkpoint(sim, path_.string(), "driver state");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_, path_;
  std::uint64_t hash_ = 0;
};

TEST_F(CheckpointFile, IntactFileLoadsToTheSameState) {
  EXPECT_EQ(verify_checkpoint(path_.string()), kCheckpointVersion);
  std::string extra;
  auto sim = load_checkpoint(default_device(), path_.string(), &extra);
  EXPECT_EQ(sim->steps(), 300);
  EXPECT_EQ(sim->hash(), hash_);
  EXPECT_EQ(extra, "driver state");
  EXPECT_FALSE(fs::exists(path_.string() + ".tmp")) << "the temporary file is renamed";
}

// Every byte of the file, flipped one at a time, is noticed (magic,
// version, size or CRC-32: a CRC detects every error within one byte).
TEST_F(CheckpointFile, AFlippedByteAnywhereIsRefused) {
  const std::vector<char> good = read_bytes(path_);
  ASSERT_GT(good.size(), 1000u);
  const fs::path bad = dir_ / "flipped.bin";
  size_t refused = 0;
  std::string sample;
  for (size_t i = 0; i < good.size(); ++i) {
    std::vector<char> b = good;
    b[i] = static_cast<char>(b[i] ^ 0x10);
    write_bytes(bad, b);
    try {
      verify_checkpoint(bad.string());
      ADD_FAILURE() << "byte " << i << " of " << good.size() << " flipped, and accepted";
    } catch (const SceneError& e) {
      ++refused;
      if (i == good.size() / 2) sample = e.what();
    }
  }
  EXPECT_EQ(refused, good.size());
  EXPECT_NE(sample.find("flipped.bin"), std::string::npos) << sample;
  EXPECT_NE(sample.find("checksum"), std::string::npos) << sample;
  // and load_checkpoint refuses it too, before building a simulation
  std::vector<char> b = good;
  b[good.size() / 2] ^= 0x01;
  write_bytes(bad, b);
  EXPECT_THROW(load_checkpoint(default_device(), bad.string()), SceneError);
}

TEST_F(CheckpointFile, TruncatedFileIsRefused) {
  const std::vector<char> good = read_bytes(path_);
  const fs::path bad = dir_ / "truncated.bin";
  for (size_t n : {size_t(0), size_t(10), size_t(12), size_t(20), size_t(40), good.size() / 2,
                   good.size() - 1}) {
    write_bytes(bad, std::vector<char>(good.begin(), good.begin() + std::ptrdiff_t(n)));
    EXPECT_THROW(verify_checkpoint(bad.string()), SceneError) << n << " bytes";
  }
  std::vector<char> longer = good;
  longer.push_back('x');
  write_bytes(bad, longer);
  EXPECT_THROW(verify_checkpoint(bad.string()), SceneError) << "a byte appended";
}

TEST_F(CheckpointFile, OlderFormatsAreRefusedWithTheReason) {
  // versions 3 and 4 held fixed-capacity neighbour lists: refused, not misread
  std::vector<char> old = read_bytes(path_);
  const fs::path f = dir_ / "old.bin";
  for (std::uint32_t version : {3u, 4u}) {
    std::memcpy(old.data() + 12, &version, 4);  // after the 12-byte magic
    write_bytes(f, old);
    try {
      verify_checkpoint(f.string());
      ADD_FAILURE() << "version " << version << " accepted";
    } catch (const SceneError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("format version " + std::to_string(version)), std::string::npos) << m;
      EXPECT_NE(m.find("sliced neighbour lists"), std::string::npos) << m;
      EXPECT_NE(m.find("old.bin"), std::string::npos) << m;
    }
  }
}


// Version 5 files held one more buffer, the lower slots' partner ids
// ("nbr_lo", before "mirror"): they load, that buffer skipped, to the state
// a version 6 file gives.
TEST_F(CheckpointFile, VersionFiveLoadsWithoutItsLowerIds) {
  std::vector<char> v5 = read_bytes(path_);
  const size_t header = 12 + 4 + 8 + 4;  // magic, version, payload size, CRC
  const std::string name = "mirror";
  std::vector<char> key(8 + name.size());
  const std::uint64_t len = name.size();
  std::memcpy(key.data(), &len, 8);
  std::memcpy(key.data() + 8, name.data(), name.size());
  const auto at = std::search(v5.begin() + header, v5.end(), key.begin(), key.end());
  ASSERT_NE(at, v5.end()) << "no mirror buffer in the file";
  std::vector<char> extra(8 + 6 + 8 + 16, char(0x5a));  // "nbr_lo", 16 bytes of junk
  const std::uint64_t six = 6, sixteen = 16;
  std::memcpy(extra.data(), &six, 8);
  std::memcpy(extra.data() + 8, "nbr_lo", 6);
  std::memcpy(extra.data() + 14, &sixteen, 8);
  v5.insert(at, extra.begin(), extra.end());
  const std::uint32_t version = 5;
  const std::uint64_t payload = v5.size() - header;
  const std::uint32_t crc = static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(v5.data() + header), uInt(payload)));
  std::memcpy(v5.data() + 12, &version, 4);
  std::memcpy(v5.data() + 16, &payload, 8);
  std::memcpy(v5.data() + 24, &crc, 4);
  const fs::path f = dir_ / "v5.bin";
  write_bytes(f, v5);
  EXPECT_EQ(verify_checkpoint(f.string()), 5u);
  auto sim = load_checkpoint(default_device(), f.string());
  EXPECT_EQ(sim->hash(), hash_);
  auto straight = load_checkpoint(default_device(), path_.string());
  sim->advance(200);
  straight->advance(200);
  EXPECT_EQ(sim->hash(), straight->hash());
}
TEST_F(CheckpointFile, InputKindsAreTold) {
  const std::vector<char> good = read_bytes(path_);
  EXPECT_EQ(classify_input(path_.string()), InputKind::Checkpoint);
  const fs::path f = dir_ / "f";
  write_bytes(f, {});
  EXPECT_EQ(classify_input(f.string()), InputKind::Empty);
  write_bytes(f, {' ', '\n', '\t'});
  EXPECT_EQ(classify_input(f.string()), InputKind::Empty);
  write_bytes(f, std::vector<char>(good.begin(), good.begin() + 10));
  EXPECT_EQ(classify_input(f.string()), InputKind::TruncatedCheckpoint);
  write_bytes(f, {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n', '\0'});
  EXPECT_EQ(classify_input(f.string()), InputKind::Binary);
  write_bytes(f, {'[', 's', 'c', 'e', 'n', 'e', ']', '\n'});
  EXPECT_EQ(classify_input(f.string()), InputKind::SceneText);
  // load_scene names what the file is instead of a missing field
  for (const std::vector<char>& bytes :
       {std::vector<char>{}, std::vector<char>(good.begin(), good.begin() + 10), good}) {
    write_bytes(f, bytes);
    try {
      load_scene(f.string());
      ADD_FAILURE() << bytes.size() << " bytes loaded as a scene";
    } catch (const SceneError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.find("numerics"), std::string::npos) << m;
      EXPECT_TRUE(m.find("empty") != std::string::npos || m.find("checkpoint") != std::string::npos)
          << m;
    }
  }
}

}  // namespace
}  // namespace simsols::testing
