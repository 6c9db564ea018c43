// Driving the contact law itself (contact_law.cl) from a small test kernel:
// tests that need kinematics no free particles can have (a pair turning
// rigidly, a contact displaced back and forth at a fixed overlap) build
// the solver's sources with their own kernel after them. This holds what
// every such kernel shares: the lanes a work item owns and the pair's
// coefficients, in OpenCL C (kLawDriverCl, placed before the test's kernel),
// and the host's packing of those coefficients.
#pragma once

#include <cmath>
#include <vector>

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

}  // namespace simsols::testing
