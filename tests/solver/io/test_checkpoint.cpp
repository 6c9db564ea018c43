// Checkpoint files (solver/io/checkpoint.h, solver/common/input_file.h): a damaged
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
#include <utility>
#include <vector>

#include "solver/io/checkpoint.h"
#include "solver/core/observe.h"
#include "solver/common/errors.h"
#include "solver/common/input_file.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

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


// A checkpoint file's payload taken apart: the scene and counters as they
// are, then the buffers by name, then the driver's state.
struct Payload {
  std::vector<char> head;  // the scene (a block) and the counters, verbatim
  std::vector<std::pair<std::string, std::vector<char>>> buffers;
  std::vector<char> tail;  // the driver's state (a block)
};

constexpr size_t kHeader = 12 + 4 + 8 + 4;  // magic, version, payload size, CRC

std::uint64_t block_size(const std::vector<char>& f, size_t at) {
  std::uint64_t n = 0;
  std::memcpy(&n, f.data() + at, 8);
  return n;
}

Payload take_apart(const std::vector<char>& f, size_t nbuffers) {
  Payload p;
  size_t at = kHeader;
  at += 8 + block_size(f, at) + 4 * 8 + 3 * 4;  // scene, four i64, three i32
  p.head.assign(f.begin() + kHeader, f.begin() + std::ptrdiff_t(at));
  for (size_t b = 0; b < nbuffers; ++b) {
    const size_t name = block_size(f, at);
    std::string key(f.data() + at + 8, name);
    at += 8 + name;
    const size_t size = block_size(f, at);
    p.buffers.emplace_back(key, std::vector<char>(f.begin() + std::ptrdiff_t(at + 8),
                                                  f.begin() + std::ptrdiff_t(at + 8 + size)));
    at += 8 + size;
  }
  p.tail.assign(f.begin() + std::ptrdiff_t(at), f.end());
  return p;
}

std::vector<char> put_together(const Payload& p, std::uint32_t version) {
  std::vector<char> body = p.head;
  auto block = [&body](const char* data, std::uint64_t n) {
    const char* size = reinterpret_cast<const char*>(&n);
    body.insert(body.end(), size, size + 8);
    body.insert(body.end(), data, data + n);
  };
  for (const auto& [name, bytes] : p.buffers) {
    block(name.data(), name.size());
    block(bytes.data(), bytes.size());
  }
  body.insert(body.end(), p.tail.begin(), p.tail.end());
  const std::uint64_t payload = body.size();
  const std::uint32_t crc = static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(payload)));
  std::vector<char> f(kHeader + body.size());
  std::memcpy(f.data(), "SIMSOLS-CKPT", 12);
  std::memcpy(f.data() + 12, &version, 4);
  std::memcpy(f.data() + 16, &payload, 8);
  std::memcpy(f.data() + 24, &crc, 4);
  std::memcpy(f.data() + kHeader, body.data(), body.size());
  return f;
}

// A packed block of 18 beads on a floor, sliding and spinning: loaded
// springs in every slice, bead and wall contacts.
Scene sliding_block() {
  Scene block = empty_scene(Precision::Float, glass(0.5, 0.3, 1e-5));
  for (int k = 0; k < 18; ++k)
    block.particles.push_back(sphere(1e-3,
                                     {2e-3 * (k % 3), 2e-3 * (k / 3 % 3), 1e-3 + 2e-3 * (k / 9)},
                                     {0.001 * (k % 4), -0.001 * (k % 3), 0}, {0, 0, double(k % 5)}));
  block.walls.push_back(plane("floor", {0, 0, 0}, {0, 0, 1}));
  block.effects.gravity = {3, 2, -9.81};  // the block slides and settles
  validate_scene(block, "block");
  return block;
}

// A loaded run shows the contact forces it was saved with (what the force
// chains and the contact series draw), before it takes a step.
TEST_F(CheckpointFile, LoadedRunsKeepTheirContactForces) {
  Simulation sim(default_device(), sliding_block());
  sim.advance(2000);
  const std::vector<ContactForce> saved = contact_list(sim.model(), sim.state());
  const auto pairs = std::count_if(saved.begin(), saved.end(),
                                   [](const ContactForce& c) { return c.b >= 0; });
  ASSERT_GE(pairs, 9) << "the block should rest on its contacts";
  const fs::path f = dir_ / "forces.bin";
  save_checkpoint(sim, f.string());
  auto loaded = load_checkpoint(default_device(), f.string());
  const std::vector<ContactForce> read = contact_list(loaded->model(), loaded->state());
  ASSERT_EQ(read.size(), saved.size());
  for (size_t c = 0; c < saved.size(); ++c) {
    EXPECT_EQ(read[c].a, saved[c].a);
    EXPECT_EQ(read[c].b, saved[c].b);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(read[c].force[a], saved[c].force[a]) << "contact " << c;
  }
}

// Versions 5 to 7 kept no shares; 5 and 6 kept each history record whole
// (spring: x, y, z, w of a slot together), and version 5 one more buffer,
// the lower slots' partner ids ("nbr_lo", before "mirror"). Files written
// that way load to the state a version 8 file gives, and run on the same.
TEST_F(CheckpointFile, VersionsFiveToSevenLoadToTheSameState) {
  auto sim = std::make_unique<Simulation>(default_device(), sliding_block());
  sim->advance(2000);
  const std::uint64_t at_save = sim->hash();
  const fs::path now_file = dir_ / "block.bin";
  save_checkpoint(*sim, now_file.string());
  const size_t slots = size_t(sim->state().up_slots);
  const int slice = sim->model().config().slice;
  const size_t real = sim->model().real_size();
  // the dynamic buffers and the shares
  const Payload now = take_apart(read_bytes(now_file), sim->state().dynamic_buffers().size() + 1);
  for (const auto& [name, bytes] : now.buffers) {
    if (name != "spring") continue;
    EXPECT_NE(std::count(bytes.begin(), bytes.end(), char(0)), std::ptrdiff_t(bytes.size()))
        << "no spring loaded: the test would not see a misplaced record";
  }
  sim->advance(200);
  for (std::uint32_t version : {5u, 6u, 7u}) {
    Payload old = now;
    ASSERT_EQ(old.buffers.back().first, "share");
    old.buffers.pop_back();
    for (auto& [name, bytes] : old.buffers) {
      if (version == 7 || name != "spring") continue;
      std::vector<char> whole(bytes.size(), 0);
      const size_t plane = 4 * slots * real;
      for (size_t p = 0; p + plane <= bytes.size(); p += plane)
        for (size_t s = 0; s < slots; ++s)
          for (int c = 0; c < 4; ++c)
            if (slot_real(s, slice, c) < 4 * slots)
              std::memcpy(&whole[p + (4 * s + c) * real], &bytes[p + slot_real(s, slice, c) * real],
                          real);
      bytes = whole;
    }
    if (version == 5) {
      auto at = std::find_if(old.buffers.begin(), old.buffers.end(),
                             [](const auto& b) { return b.first == "mirror"; });
      ASSERT_NE(at, old.buffers.end());
      old.buffers.insert(at, {"nbr_lo", std::vector<char>(16, char(0x5a))});
    }
    const fs::path f = dir_ / ("v" + std::to_string(version) + ".bin");
    write_bytes(f, put_together(old, version));
    EXPECT_EQ(verify_checkpoint(f.string()), version);
    auto loaded = load_checkpoint(default_device(), f.string());
    EXPECT_EQ(loaded->hash(), at_save) << "version " << version;
    loaded->advance(200);
    EXPECT_EQ(loaded->hash(), sim->hash()) << "version " << version;
  }
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
