// Driving the contact law itself (contact_law.cl) from a small test kernel:
// tests that need kinematics no free particles can have (a pair turning
// rigidly, a contact displaced back and forth at a fixed overlap) build
// the solver's sources with their own kernel after them. This holds what
// every such kernel shares: the lanes a work item owns and the pair's
// coefficients, in OpenCL C (kLawDriverCl, placed before the test's kernel),
// the host's packing of those coefficients, and LawDriver, which passes a
// kernel its arguments, runs it and reads its results back.
#pragma once

#include <CL/cl.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/core/cl_device.h"
#include "solver/core/cl_program.h"
#include "solver/kernels/kernel_source.h"
#include "solver/scene/contact_model.h"
#include "solver/scene/scene.h"

namespace simsols::testing {

// driver_lanes(m, idx, keep): the work item's cases (clamped to the last,
// keep false beyond m); false when it owns none. driver_pair(coeff): the
// coefficients packed by driver_coefficients below.
inline constexpr const char* kLawDriverCl = R"CL(
INLINE bool driver_lanes(int m, int* idx, int* keep) {
  const int base = get_global_id(0) * LANES;
  for (int l = 0; l < LANES; ++l) {
    keep[l] = base + l < m;
    idx[l] = keep[l] ? base + l : m - 1;
  }
  return base < m;
}

INLINE PairLanes driver_pair(__global const real* coeff) {
  PairLanes c;
  c.estar = (lane)coeff[0];
  c.gstar = (lane)coeff[1];
  c.gamma = (lane)coeff[2];
  c.mu_s = (lane)coeff[3];
  c.mu_r = (lane)coeff[4];
  c.kt_ratio = (lane)coeff[5];
  return c;
}
)CL";

// The solver's sources the law needs, the shared driver code, then the
// test's kernel.
inline std::vector<KernelFile> law_driver_files(const KernelFile& test_kernel) {
  return {kernel_file("layout.h"), kernel_file("common.cl"), kernel_file("contact_law.cl"),
          {"law_driver.cl", kLawDriverCl}, test_kernel};
}

// Material 0's pair coefficients as driver_pair() reads them (8 reals).
inline std::vector<double> driver_coefficients(const Scene& scene) {
  const PairTable table = make_pair_table(scene);
  const PairCoefficients& pc = table.at(0, 0);
  return {pc.e_star, pc.g_star, pc.gamma_n, pc.sliding_friction, pc.rolling_friction,
          std::sqrt(6 * pc.g_star / pc.e_star), 0, 0};
}

// A driver kernel's arguments in their order (buffers, reals in the
// program's precision, ints), its run over m cases (LANES per work item),
// and a buffer of reals read back as doubles.
class LawDriver {
 public:
  LawDriver(Device& device, const KernelConfig& config, const Kernel& kernel)
      : device_(device), config_(config), kernel_(kernel) {}
  LawDriver& mem(const ClMem& b) {
    const cl_mem h = b.get();
    return set(sizeof h, &h);
  }
  LawDriver& real(double v) {
    const float f = static_cast<float>(v);
    return config_.double_precision ? set(sizeof v, &v) : set(sizeof f, &f);
  }
  LawDriver& integer(int v) { return set(sizeof v, &v); }
  void run(int m) {
    enqueue_kernel(device_, kernel_, (m + config_.lanes - 1) / config_.lanes, 0);
    device_.finish();
  }
  std::vector<double> read(const ClMem& b, size_t count) const {
    std::vector<double> v(count);
    if (config_.double_precision) {
      device_.read(b.get(), count * sizeof(double), v.data());
    } else {
      std::vector<float> f(count);
      device_.read(b.get(), count * sizeof(float), f.data());
      std::copy(f.begin(), f.end(), v.begin());
    }
    return v;
  }

 private:
  LawDriver& set(size_t size, const void* value) {
    check(clSetKernelArg(kernel_.get(), arg_++, size, value), "law driver kernel argument");
    return *this;
  }
  Device& device_;
  const KernelConfig& config_;
  const Kernel& kernel_;
  cl_uint arg_ = 0;
};

}  // namespace simsols::testing
