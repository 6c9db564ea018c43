// Test 6: determinism and checkpoints. Two runs of the same scene on the
// same device and precision end with identical state hashes; a run stopped
// at a checkpoint and resumed ends bit for bit where the uninterrupted run
// does.
#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "solver/io/checkpoint.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

// A frictional packing with rolling resistance settling in a box.
Scene settling_box(Precision p) {
  Scene s = empty_scene(p, glass(0.87, 0.3, 5e-5));
  s.effects.gravity = {0, 0, -9.81};
  const double R = 1e-3, spacing = 1.9998e-3;  // touching: forces from step one
  const int nx = 8, nz = 10;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < nx; ++j)
      for (int i = 0; i < nx; ++i) {
        const double jitter = 0.001 * R * (((i * 7 + j * 13 + k * 29) % 11) - 5);
        s.particles.push_back(sphere(R, {(i + 0.5) * spacing + jitter, (j + 0.5) * spacing,
                                         R + k * spacing},
                                     {0, 0, -0.2}));
      }
  s.numerics.skin = 2e-6;  // tiny skin: many list rebuilds (with atomics) to exercise
  const double L = nx * spacing;
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), plane("x0", {0, 0, 0}, {1, 0, 0}),
             plane("x1", {L, 0, 0}, {-1, 0, 0}), plane("y0", {0, 0, 0}, {0, 1, 0}),
             plane("y1", {0, L, 0}, {0, -1, 0})};
  return s;
}

class Determinism : public PrecisionTest {};

TEST_P(Determinism, SameSceneSameHash) {
  const Scene s = settling_box(GetParam());
  Simulation a(default_device(), s), b(default_device(), s);
  a.advance(400);
  b.advance(400);
  EXPECT_GT(a.observe().contacts, 100) << "the packing must be in contact";
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_GT(a.state().list_builds, 1);
}

TEST_P(Determinism, CheckpointResumesBitForBit) {
  const Scene s = settling_box(GetParam());
  Simulation straight(default_device(), s);
  straight.advance(400);

  Simulation first(default_device(), s);
  first.advance(170);
  const auto path = std::filesystem::temp_directory_path() /
                    ("simsols_ckpt_" + std::string(precision_name(GetParam())) + "_" + std::to_string(::getpid()) + ".bin");
  save_checkpoint(first, path.string());
  auto resumed = load_checkpoint(default_device(), path.string());
  EXPECT_EQ(resumed->steps(), 170);
  EXPECT_EQ(resumed->hash(), first.hash());
  resumed->advance(230);
  EXPECT_EQ(resumed->hash(), straight.hash());
  std::filesystem::remove(path);
}

TEST(Checkpoint, RejectsForeignFile) {
  const auto path = std::filesystem::temp_directory_path() / ("simsols_not_a_checkpoint_" + std::to_string(::getpid()) + ".bin");
  {
    std::ofstream out(path);
    out << "hello";
  }
  EXPECT_THROW(load_checkpoint(default_device(), path.string()), SceneError);
  std::filesystem::remove(path);
}

SIMSOLS_BOTH_PRECISIONS(Determinism);

}  // namespace
}  // namespace simsols::testing
