// How the engine runs, as opposed to what it simulates (the Scene says
// that): which OpenCL device, how many particles a work item handles, the
// work-group size and extra build options. None of them changes a result
// beyond round-off order (lanes) or nothing at all (device choice aside).
//
// They are filled once at the edge, by a command from the SIMSOLS_*
// environment variables or by a test, and travel with the Device they
// opened (Device::options()); nothing below the edge reads the environment.
#pragma once

#include <string>

namespace simsols {

struct EngineOptions {
  // "" : a GL context's device where one is shared, else the first GPU,
  // else the first device; "gpu", "cpu", or part of a device's name.
  std::string device;
  // Particles per work item (SIMD lanes): 1, 2, 4, 8 or 16; 0 = 8 in float
  // and 4 in double on CPUs, 1 on GPUs.
  int lanes = 0;
  // Work-group size of the particle kernels: a power of two from 1 to 1024.
  int local_size = 64;
  // CPUs (lanes > 1): finish_particles prefetches the partners' shares
  // (forces.cl, prefetch_shares); off only to measure what it buys.
  bool prefetch = true;
  // CPUs: a buffer that fills whole 2 MiB pages to within 1/16 lives in
  // memory marked for transparent huge pages (cl_device.cpp,
  // Device::create_buffer); off only to measure what it buys.
  bool huge_pages = true;
  // Extra OpenCL build options, for experiments ("-cl-fast-relaxed-math").
  std::string cl_options;
};

// Lanes a kernel can be built with: 1, 2, 4, 8 or 16 (0 = the default).
inline bool allowed_lanes(int lanes) {
  return lanes == 1 || lanes == 2 || lanes == 4 || lanes == 8 || lanes == 16;
}

// Work-group sizes a kernel can be launched with: powers of two from 1 to
// 1024 (the observables' reduction halves its group, reduce.cl).
inline bool allowed_local_size(int size) {
  return size >= 1 && size <= 1024 && (size & (size - 1)) == 0;
}

// The options the environment asks for: SIMSOLS_CL_DEVICE, SIMSOLS_LANES,
// SIMSOLS_LOCAL_SIZE, SIMSOLS_PREFETCH and SIMSOLS_HUGE_PAGES (0 or 1),
// SIMSOLS_CL_OPTIONS (docs/performance.md). For the
// edges only (app/cli, tests/support). Throws UsageError naming the
// variable and its allowed values.
EngineOptions engine_options_from_environment();

}  // namespace simsols
