// Engine options (solver/core/engine_options.h): set in code, they reach the
// kernels' configuration and the model through the device that carries
// them; read from the environment, a bad value is a UsageError naming the
// variable and what is allowed.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "solver/common/errors.h"
#include "solver/core/cl_program.h"
#include "solver/core/engine_options.h"
#include "solver/core/simulation.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

using testing::empty_scene;
using testing::glass;
using testing::sphere;
using testing::ScopedVariable;

Scene two_beads(Precision p) {
  Scene s = empty_scene(p, glass(0.9, 0.3, 0.0));
  s.particles = {sphere(1e-3, {0, 0, 0}), sphere(1e-3, {3e-3, 0, 0})};
  return s;
}

TEST(EngineOptions, LanesAndLocalSizeSetInCodeReachTheModel) {
  EngineOptions o;
  o.lanes = 2;
  o.local_size = 16;
  o.cl_options = "-cl-mad-enable";
  auto device = Device::open(o);
  EXPECT_EQ(device->options().lanes, 2);
  const KernelConfig c = make_kernel_config(two_beads(Precision::Float), *device);
  EXPECT_EQ(c.lanes, 2);
  EXPECT_EQ(c.extra_options, "-cl-mad-enable");
  EXPECT_EQ(c.prefetch_shares, !device->is_gpu());
  EXPECT_NE(c.build_options().find("-DPREFETCH_SHARES"), std::string::npos);
  Simulation sim(device, two_beads(Precision::Float));
  EXPECT_EQ(sim.model().local_size(), 16u);
  EXPECT_EQ(sim.model().config().lanes, 2);
}

TEST(EngineOptions, DefaultLanesFollowTheDeviceAndPrecision) {
  auto device = Device::open(EngineOptions{});
  const int f = make_kernel_config(two_beads(Precision::Float), *device).lanes;
  const int d = make_kernel_config(two_beads(Precision::Double), *device).lanes;
  EXPECT_EQ(f, device->is_gpu() ? 1 : 8);
  EXPECT_EQ(d, device->is_gpu() ? 1 : 4);
}

TEST(EngineOptions, PrefetchIsBuiltOnlyWithLanesAndWhenNotTurnedOff) {
  EngineOptions o;
  o.lanes = 1;  // the GPU form
  EXPECT_FALSE(make_kernel_config(two_beads(Precision::Float), *Device::open(o)).prefetch_shares);
  o.lanes = 8;
  o.prefetch = false;
  const KernelConfig c = make_kernel_config(two_beads(Precision::Float), *Device::open(o));
  EXPECT_FALSE(c.prefetch_shares);
  EXPECT_EQ(c.build_options().find("PREFETCH"), std::string::npos);
  Simulation sim(Device::open(o), two_beads(Precision::Float));  // it builds without
  sim.advance(3);
  EXPECT_EQ(sim.steps(), 3);
}

// On CPUs a buffer that fills whole 2 MiB pages to within 1/16 lives in
// host memory marked for huge pages (Device::alloc). With and without,
// what is written is read back, through views too, a new buffer reads
// zero, and the pages' rounding is counted while the buffers live.
TEST(EngineOptions, HugePageBuffersHoldWhatIsWrittenAndViewsSeeIt) {
  const size_t big = (size_t(32) << 20) - 4096, small = (size_t(4) << 20) - 65536;
  std::vector<std::uint32_t> data(big / 4);
  for (size_t k = 0; k < data.size(); ++k) data[k] = static_cast<std::uint32_t>(k * 2654435761u);
  for (const bool huge : {true, false}) {
    EngineOptions o;
    o.huge_pages = huge;
    auto device = Device::open(o);
    const size_t rounding = huge && !device->is_gpu() ? 4096 + 65536 : 0;
    for (int round = 0; round < 3; ++round) {  // released and made again
      {
        ClMem m = device->alloc(big, data.data());
        ClMem zero = device->alloc(small);
        EXPECT_EQ(device->page_rounding_bytes(), rounding) << "huge pages " << huge;
        std::vector<std::uint32_t> back(data.size());
        device->read(m.get(), big, back.data());
        EXPECT_EQ(back, data) << "huge pages " << huge;
        const size_t at = 16 * device->base_align();
        ClMem v = device->view(m.get(), at, 4096);
        std::uint32_t word = 1;
        device->read(v.get(), 4, &word);
        EXPECT_EQ(word, data[at / 4]);
        device->read(zero.get(), 4, &word, small - 4);
        EXPECT_EQ(word, 0u);
      }
      EXPECT_EQ(device->page_rounding_bytes(), 0u);
    }
  }
}

TEST(EngineOptions, LanesOutsideTheAllowedSetAreRefusedByTheConfig) {
  EngineOptions o;
  o.lanes = 3;
  auto device = Device::open(o);
  EXPECT_THROW(make_kernel_config(two_beads(Precision::Float), *device), DeviceError);
}

TEST(EngineOptions, LocalSizesThatAreNotPowersOfTwoAreRefused) {
  EngineOptions o;
  o.local_size = 48;  // the observables' reduction halves its group
  EXPECT_THROW(Simulation(Device::open(o), two_beads(Precision::Float)), DeviceError);
  for (int ok : {1, 2, 16, 64, 1024}) EXPECT_TRUE(allowed_local_size(ok)) << ok;
  for (int bad : {0, 3, 48, 100, 2048}) EXPECT_FALSE(allowed_local_size(bad)) << bad;
}

TEST(EngineOptions, TheEnvironmentIsReadIntoOptions) {
  ScopedVariable lanes("SIMSOLS_LANES", "4");
  ScopedVariable local("SIMSOLS_LOCAL_SIZE", "32");
  ScopedVariable device("SIMSOLS_CL_DEVICE", "cpu");
  ScopedVariable extra("SIMSOLS_CL_OPTIONS", "-cl-fast-relaxed-math");
  ScopedVariable prefetch("SIMSOLS_PREFETCH", "0");
  ScopedVariable huge("SIMSOLS_HUGE_PAGES", "0");
  const EngineOptions o = engine_options_from_environment();
  EXPECT_FALSE(o.prefetch);
  EXPECT_FALSE(o.huge_pages);
  EXPECT_EQ(o.lanes, 4);
  EXPECT_EQ(o.local_size, 32);
  EXPECT_EQ(o.device, "cpu");
  EXPECT_EQ(o.cl_options, "-cl-fast-relaxed-math");
}

// Reading the environment with `name` set to `value` throws a UsageError
// naming the variable, and `allowed` in its message.
void expect_refused(const char* name, const char* value, const char* allowed) {
  ScopedVariable set(name, value);
  try {
    engine_options_from_environment();
    ADD_FAILURE() << name << "=" << value << " accepted";
  } catch (const UsageError& e) {
    EXPECT_EQ(e.field, name);
    EXPECT_NE(std::string(e.what()).find(allowed), std::string::npos) << e.what();
  }
}

TEST(EngineOptions, BadVariablesAreUsageErrorsNamingThem) {
  for (const char* bad : {"3", "8x", "-4", "0"})
    expect_refused("SIMSOLS_LANES", bad, "1, 2, 4, 8 or 16");
  for (const char* bad : {"zero", "48", "0", "2048"})
    expect_refused("SIMSOLS_LOCAL_SIZE", bad, "power of two from 1 to 1024");
  ScopedVariable fine("SIMSOLS_LOCAL_SIZE", "64");
  ScopedVariable prefetch("SIMSOLS_PREFETCH", "yes");
  try {
    engine_options_from_environment();
    FAIL() << "SIMSOLS_PREFETCH=yes accepted";
  } catch (const UsageError& e) {
    EXPECT_EQ(e.field, "SIMSOLS_PREFETCH");
  }
}

}  // namespace
}  // namespace simsols
