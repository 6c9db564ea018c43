// OpenCL device: platform/device choice, context and one in-order queue.
//
// The device is chosen once per process: the environment variable
// SIMSOLS_CL_DEVICE ("gpu", "cpu", or a substring of the device name) picks
// one, otherwise the first GPU, otherwise the first device found. Given an
// OpenGL context to share with, the device that runs that context comes
// first: clGetGLContextInfoKHR (CL_CURRENT_DEVICE_FOR_GL_CONTEXT_KHR, looked
// up with clGetExtensionFunctionAddressForPlatform) names it, asked only of
// platforms that offer cl_khr_gl_sharing (on PoCL a sharing call ends the
// process); SIMSOLS_CL_DEVICE still overrides it when the two disagree, and
// sharing_note() says which rule chose. Small RAII
// handles (ClMem, ClKernel, ClProgram) release OpenCL objects; check() turns
// every OpenCL error code into a DeviceError naming the call.
#pragma once

#include <CL/cl.h>

#include <atomic>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "solver/common/errors.h"
#include "solver/core/engine_options.h"

namespace simsols {

void check(cl_int err, const char* what);

template <typename T, cl_int (*Release)(T)>
class ClHandle {
 public:
  ClHandle() = default;
  explicit ClHandle(T h) : h_(h) {}
  ClHandle(const ClHandle&) = delete;
  ClHandle& operator=(const ClHandle&) = delete;
  ClHandle(ClHandle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  ClHandle& operator=(ClHandle&& o) noexcept {
    if (this != &o) { reset(); h_ = std::exchange(o.h_, nullptr); }
    return *this;
  }
  ~ClHandle() { reset(); }
  void reset() { if (h_) Release(h_); h_ = nullptr; }
  T get() const { return h_; }
  explicit operator bool() const { return h_ != nullptr; }
  void swap(ClHandle& o) noexcept { std::swap(h_, o.h_); }

 private:
  T h_ = nullptr;
};

using ClMem = ClHandle<cl_mem, clReleaseMemObject>;
using ClKernel = ClHandle<cl_kernel, clReleaseKernel>;
using ClProgram = ClHandle<cl_program, clReleaseProgram>;
using ClQueue = ClHandle<cl_command_queue, clReleaseCommandQueue>;
using ClContext = ClHandle<cl_context, clReleaseContext>;

class Device {
 public:
  // Opens the device `options.device` selects, as described above; the
  // options travel with it (options()). Throws DeviceError.
  static std::shared_ptr<Device> open(const EngineOptions& options);
  // The GL context's device where a platform names it (else the same
  // choice as open()), its context shared with the OpenGL context when the
  // device offers cl_khr_gl_sharing: `gl_properties` are the property pairs
  // naming the GL context (CL_GL_CONTEXT_KHR, CL_EGL_DISPLAY_KHR or
  // CL_GLX_DISPLAY_KHR, without the terminating 0; the platform is added).
  // When sharing is impossible the context is a plain one: gl_sharing()
  // says which, sharing_note() why.
  static std::shared_ptr<Device> open(const EngineOptions& options,
                                      const std::vector<cl_context_properties>& gl_properties);
  const EngineOptions& options() const { return options_; }
  bool gl_sharing() const { return gl_sharing_; }
  // "cl_khr_gl_sharing; device: the GL context's device (clGetGLContextInfoKHR)",
  // "the OpenCL device has no cl_khr_gl_sharing", "clCreateContext with the
  // OpenGL context failed (error N); device: the first GPU ('NVIDIA CUDA':
  // clGetGLContextInfoKHR failed (error M))", ...
  const std::string& sharing_note() const { return sharing_note_; }

  cl_context context() const { return context_.get(); }
  cl_command_queue queue() const { return queue_.get(); }
  cl_device_id id() const { return device_; }
  const std::string& name() const { return name_; }
  const std::string& extensions() const { return extensions_; }
  bool is_gpu() const { return gpu_; }
  bool has_double() const;
  bool has_extension(const std::string& ext) const;
  std::string description() const;  // "name (platform, OpenCL version)"
  // The lock file that serialises kernel compilation between processes
  // (kernel_cache_lock.h): in PoCL's cache directory on PoCL, else "".
  const std::string& compile_lock_path() const { return compile_lock_path_; }

  ClMem alloc(size_t bytes, const void* init = nullptr);
  // A view of bytes [offset, offset + bytes) of `parent` (clCreateSubBuffer);
  // offset a multiple of base_align().
  ClMem view(cl_mem parent, size_t offset, size_t bytes);
  // The alignment, in bytes, of a view's offset (CL_DEVICE_MEM_BASE_ADDR_ALIGN).
  size_t base_align() const { return base_align_; }
  // Host memory the live buffers hold beyond their sizes: on CPUs, large
  // buffers are rounded up to whole 2 MiB pages (at most 1/16 more).
  size_t page_rounding_bytes() const { return rounding_->load(); }
  void write(cl_mem mem, size_t bytes, const void* src, size_t offset = 0);
  void read(cl_mem mem, size_t bytes, void* dst, size_t offset = 0);
  void fill_zero(cl_mem mem, size_t bytes);
  void copy(cl_mem from, cl_mem to, size_t bytes);  // device to device, in queue order
  void finish();

 private:
  Device() = default;
  // The context: shared with the GL context when the device can, else plain.
  void open_context(const std::vector<cl_context_properties>& gl_properties);
  cl_mem create_buffer(size_t size);  // see cl_device.cpp
  EngineOptions options_;
  cl_platform_id platform_ = nullptr;
  cl_device_id device_ = nullptr;
  ClContext context_;
  ClQueue queue_;
  std::string name_, platform_name_, version_, extensions_;
  std::string compile_lock_path_;
  bool gpu_ = false;
  size_t base_align_ = 16;
  // host bytes the live buffers' rounding to huge pages adds (create_buffer)
  std::shared_ptr<std::atomic<size_t>> rounding_ = std::make_shared<std::atomic<size_t>>(0);
  bool gl_sharing_ = false;
  std::string sharing_note_;
};

}  // namespace simsols
