// Binding kernel arguments by name, from one list at the call site.
//
// set_args(model, kernel, arg("pos", s.pos), arg("n", s.n), ...) names each
// argument as the kernel's signature names its parameter, in the
// signature's order. Before anything is set, the list is checked against
// the names the compiler reports (Kernel::params, cl_program.h): a missing,
// extra or misplaced argument throws DeviceError naming the kernel, the
// position and both names, at the first call, so a signature changed in a
// .cl file without its call site (or the reverse) fails at start-up
// instead of binding the wrong buffer. A parameter that precision compiles
// away keeps its place under the name `<name>_unused` (common.cl's
// POS_LO_* macros), which matches `<name>`.
//
// Values: buffers as Buffer or cl_mem, integers as int / uint32_t,
// floating-point values as Real{x}, converted to the precision the program
// was built with, Real4 likewise, local memory as Local{bytes}.
#pragma once

#include <cstdint>
#include <string>

#include "solver/core/cl_device.h"
#include "solver/common/errors.h"
#include "solver/core/model.h"
#include "solver/core/state.h"

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

// One argument and the name of the parameter it binds.
template <typename T>
struct Arg {
  const char* name;
  const T& value;
};
template <typename T>
Arg<T> arg(const char* name, const T& value) {
  return {name, value};
}

namespace detail {
// Throws unless `name` is the kernel's parameter `i` (or it is absent: a
// driver without argument names).
void check_arg(const Kernel& k, cl_uint i, const char* name);
void check_count(const Kernel& k, cl_uint given);
}  // namespace detail

template <typename... Ts>
void set_args(const Model& m, const Kernel& k, const Arg<Ts>&... args) {
  detail::check_count(k, sizeof...(Ts));
  cl_uint i = 0;
  (detail::check_arg(k, i++, args.name), ...);
  i = 0;
  (detail::set_one(m, k.get(), i++, args.value), ...);
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
inline void launch(const Model& m, const Kernel& k, size_t n) {
  if (n == 0) return;
  enqueue_kernel(m.device(), k, m.global_size(n), m.local_size());
}

// Enqueues exactly `n` items with no local size (serial helpers, small ranges).
inline void launch_exact(const Model& m, const Kernel& k, size_t n) {
  if (n == 0) return;
  enqueue_kernel(m.device(), k, n, 0);
}

}  // namespace simsols
