// Kernel arguments bound by name (solver/core/kernel_args.h): a call site that
// binds the kernel's parameters in their order runs; one that swaps two,
// leaves one out or adds one is refused before anything is set, naming the
// kernel, the position and both names. The solver's own kernels are bound
// the same way, so every simulation in the suite checks its call sites.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "solver/core/cl_program.h"
#include "solver/common/errors.h"
#include "solver/core/kernel_args.h"
#include "solver/core/simulation.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

const char* kScale = R"CL(
__kernel void scale(__global real* values, real factor, int n) {
  const int i = get_global_id(0);
  if (i < n) values[i] *= factor;
}
)CL";

class KernelArgs : public ::testing::Test {
 protected:
  KernelArgs()
      : sim_(default_device(), [] {
          Scene s = empty_scene(Precision::Float, glass());
          s.particles.push_back(sphere(1e-3, {0, 0, 0}));
          return s;
        }()) {}
  Kernel build() {
    std::vector<KernelFile> files = {kernel_file("layout.h"), kernel_file("common.cl"), {"scale.cl", kScale}};
    program_ = std::make_unique<Program>(sim_.model().device(), sim_.model().config(), files);
    return program_->kernel("scale");
  }
  std::string refusal(const auto& bind) {
    try {
      bind();
    } catch (const DeviceError& e) {
      return e.what();
    }
    return "";
  }
  Simulation sim_;
  std::unique_ptr<Program> program_;
};

TEST_F(KernelArgs, TheCompilerReportsTheParameterNames) {
  const Kernel k = build();
  EXPECT_EQ(k.count, 3u);
  EXPECT_EQ(k.params, (std::vector<std::string>{"values", "factor", "n"}));
}

TEST_F(KernelArgs, ArgumentsBoundInOrderRun) {
  const Kernel k = build();
  const Model& m = sim_.model();
  const std::vector<float> in = {1, 2, 3, 4};
  ClMem buf = m.device().alloc(in.size() * sizeof(float), in.data());
  set_args(m, k, arg("values", buf.get()), arg("factor", Real{2.5}), arg("n", 4));
  launch_exact(m, k, 4);
  std::vector<float> out(4);
  m.device().read(buf.get(), out.size() * sizeof(float), out.data());
  EXPECT_EQ(out, (std::vector<float>{2.5f, 5, 7.5f, 10}));
}

TEST_F(KernelArgs, ASwappedMissingOrExtraArgumentIsRefusedByName) {
  const Kernel k = build();
  const Model& m = sim_.model();
  ClMem buf = m.device().alloc(16);
  const std::string swapped = refusal(
      [&] { set_args(m, k, arg("values", buf.get()), arg("n", 4), arg("factor", Real{2})); });
  EXPECT_NE(swapped.find("kernel 'scale' argument 1 is 'factor'"), std::string::npos) << swapped;
  EXPECT_NE(swapped.find("binds 'n'"), std::string::npos) << swapped;
  const std::string missing =
      refusal([&] { set_args(m, k, arg("values", buf.get()), arg("factor", Real{2})); });
  EXPECT_NE(missing.find("takes 3 arguments; its call site binds 2"), std::string::npos)
      << missing;
  const std::string extra = refusal([&] {
    set_args(m, k, arg("values", buf.get()), arg("factor", Real{2}), arg("n", 4), arg("m", 1));
  });
  EXPECT_NE(extra.find("binds 4"), std::string::npos) << extra;
}

}  // namespace
}  // namespace simsols::testing
