// Setting kernel arguments without repeating clSetKernelArg by hand.
//
// set_args(model, kernel, a, b, ...) sets the arguments in order. Buffers
// pass as Buffer or cl_mem, integers as int / uint32_t, and floating-point
// values as Real{x}, converted to the precision the program was built with.
// Real4 likewise. Local memory is Local{bytes}. Errors name the kernel
// argument index.
#pragma once

#include <cstdint>

#include "cl_device.h"
#include "model.h"
#include "state.h"

namespace simsols {

struct Real { double v; };
struct Real4 { double x, y, z, w; };
struct Local { size_t bytes; };

namespace detail {
inline void set_one(const Model&, cl_kernel k, cl_uint i, const Buffer& b) {
  cl_mem m = b.get();
  check(clSetKernelArg(k, i, sizeof m, &m), "clSetKernelArg(buffer)");
}
inline void set_one(const Model&, cl_kernel k, cl_uint i, cl_mem m) {
  check(clSetKernelArg(k, i, sizeof m, &m), "clSetKernelArg(buffer)");
}
inline void set_one(const Model&, cl_kernel k, cl_uint i, int v) {
  check(clSetKernelArg(k, i, sizeof v, &v), "clSetKernelArg(int)");
}
inline void set_one(const Model&, cl_kernel k, cl_uint i, std::uint32_t v) {
  check(clSetKernelArg(k, i, sizeof v, &v), "clSetKernelArg(uint)");
}
inline void set_one(const Model&, cl_kernel k, cl_uint i, Local l) {
  check(clSetKernelArg(k, i, l.bytes, nullptr), "clSetKernelArg(local)");
}
inline void set_one(const Model& m, cl_kernel k, cl_uint i, Real r) {
  if (m.config().double_precision) {
    check(clSetKernelArg(k, i, sizeof(double), &r.v), "clSetKernelArg(real)");
  } else {
    const float f = static_cast<float>(r.v);
    check(clSetKernelArg(k, i, sizeof f, &f), "clSetKernelArg(real)");
  }
}
inline void set_one(const Model& m, cl_kernel k, cl_uint i, Real4 r) {
  if (m.config().double_precision) {
    const cl_double4 v = {{r.x, r.y, r.z, r.w}};
    check(clSetKernelArg(k, i, sizeof v, &v), "clSetKernelArg(real4)");
  } else {
    const cl_float4 v = {{float(r.x), float(r.y), float(r.z), float(r.w)}};
    check(clSetKernelArg(k, i, sizeof v, &v), "clSetKernelArg(real4)");
  }
}
}  // namespace detail

template <typename... Args>
void set_args(const Model& m, const ClKernel& k, const Args&... args) {
  cl_uint i = 0;
  (detail::set_one(m, k.get(), i++, args), ...);
}

// Gravity as a real4 kernel argument.
inline Real4 gravity_arg(const Model& m) {
  const Vec3& g = m.scene().effects.gravity;
  return {g[0], g[1], g[2], 0};
}

// The fluid of the drag slot as a real4: (velocity, density).
inline Real4 fluid_arg(const Model& m) {
  const Fluid& f = m.scene().effects.fluid_params;
  return {f.velocity[0], f.velocity[1], f.velocity[2], f.density};
}

// Enqueues a 1-D range over `n` items, padded to the model's local size.
inline void launch(const Model& m, const ClKernel& k, size_t n) {
  if (n == 0) return;
  const size_t local = m.local_size();
  const size_t global = m.global_size(n);
  check(clEnqueueNDRangeKernel(m.device().queue(), k.get(), 1, nullptr, &global, &local, 0,
                               nullptr, nullptr),
        "clEnqueueNDRangeKernel");
}

// Enqueues exactly `n` items with no local size (serial helpers, small ranges).
inline void launch_exact(const Model& m, const ClKernel& k, size_t n) {
  if (n == 0) return;
  check(clEnqueueNDRangeKernel(m.device().queue(), k.get(), 1, nullptr, &n, nullptr, 0, nullptr,
                               nullptr),
        "clEnqueueNDRangeKernel");
}

}  // namespace simsols
