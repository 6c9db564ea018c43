#include "solver/core/cl_device.h"

#include <CL/cl_gl.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdlib>
#include <sys/mman.h>
#include <vector>

#include "solver/core/kernel_cache_lock.h"

namespace simsols {

void check(cl_int err, const char* what) {
  if (err != CL_SUCCESS)
    throw DeviceError(std::string("OpenCL error ") + std::to_string(err) + " in " + what);
}

namespace {

std::string device_string(cl_device_id d, cl_device_info what) {
  size_t n = 0;
  check(clGetDeviceInfo(d, what, 0, nullptr, &n), "clGetDeviceInfo");
  std::string s(n, '\0');
  check(clGetDeviceInfo(d, what, n, s.data(), nullptr), "clGetDeviceInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::string platform_string(cl_platform_id p, cl_platform_info what) {
  size_t n = 0;
  check(clGetPlatformInfo(p, what, 0, nullptr, &n), "clGetPlatformInfo");
  std::string s(n, '\0');
  check(clGetPlatformInfo(p, what, n, s.data(), nullptr), "clGetPlatformInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Whole-word match in a space-separated extension list.
bool has_word(const std::string& list, const std::string& word) {
  for (size_t pos = list.find(word); pos != std::string::npos; pos = list.find(word, pos + 1)) {
    const size_t end = pos + word.size();
    if ((pos == 0 || list[pos - 1] == ' ') && (end == list.size() || list[end] == ' ')) return true;
  }
  return false;
}

struct Candidate {
  cl_platform_id p;
  cl_device_id d;
  bool gpu;
  bool gl_sharing;  // the device lists cl_khr_gl_sharing
  std::string name;
};

std::vector<cl_platform_id> list_platforms() {
  cl_uint np = 0;
  if (clGetPlatformIDs(0, nullptr, &np) != CL_SUCCESS || np == 0)
    throw DeviceError(
        "no OpenCL platform found: install an OpenCL driver (Debian: pocl-opencl-icd)");
  std::vector<cl_platform_id> platforms(np);
  check(clGetPlatformIDs(np, platforms.data(), nullptr), "clGetPlatformIDs");
  return platforms;
}

std::vector<Candidate> list_devices(const std::vector<cl_platform_id>& platforms) {
  std::vector<Candidate> all;
  for (cl_platform_id p : platforms) {
    cl_uint nd = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS || nd == 0) continue;
    std::vector<cl_device_id> devs(nd);
    check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, devs.data(), nullptr), "clGetDeviceIDs");
    for (cl_device_id d : devs) {
      cl_device_type t = 0;
      check(clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof t, &t, nullptr), "clGetDeviceInfo");
      all.push_back({p, d, (t & CL_DEVICE_TYPE_GPU) != 0,
                     has_word(device_string(d, CL_DEVICE_EXTENSIONS), "cl_khr_gl_sharing"),
                     device_string(d, CL_DEVICE_NAME)});
    }
  }
  if (all.empty()) throw DeviceError("no OpenCL device found");
  return all;
}

// A platform may be asked about GL contexts only when it offers
// cl_khr_gl_sharing (itself or through one of its devices): on PoCL, which
// does not, a sharing call ends the process.
bool platform_shares(cl_platform_id p, const std::vector<Candidate>& all) {
  if (has_word(platform_string(p, CL_PLATFORM_EXTENSIONS), "cl_khr_gl_sharing")) return true;
  return std::any_of(all.begin(), all.end(),
                     [&](const Candidate& c) { return c.p == p && c.gl_sharing; });
}

// The device that runs the GL context (clGetGLContextInfoKHR,
// CL_CURRENT_DEVICE_FOR_GL_CONTEXT_KHR), asked of each platform that offers
// cl_khr_gl_sharing; all.end() when none answers, with *note saying why
// (empty when no platform offers the extension: nothing was asked).
std::vector<Candidate>::const_iterator gl_context_device(
    const std::vector<Candidate>& all, const std::vector<cl_platform_id>& platforms,
    const std::vector<cl_context_properties>& gl_properties, std::string* note) {
  for (cl_platform_id p : platforms) {
    if (!platform_shares(p, all)) continue;
    const std::string platform = "'" + platform_string(p, CL_PLATFORM_NAME) + "'";
    auto get_info = reinterpret_cast<clGetGLContextInfoKHR_fn>(
        clGetExtensionFunctionAddressForPlatform(p, "clGetGLContextInfoKHR"));
    if (!get_info) {
      *note += (note->empty() ? "" : ", ") + platform + " has no clGetGLContextInfoKHR";
      continue;
    }
    std::vector<cl_context_properties> props = gl_properties;
    props.insert(props.end(), {CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(p), 0});
    cl_device_id d = nullptr;
    const cl_int err =
        get_info(props.data(), CL_CURRENT_DEVICE_FOR_GL_CONTEXT_KHR, sizeof d, &d, nullptr);
    auto found = std::find_if(all.begin(), all.end(), [&](const Candidate& c) { return c.d == d; });
    if (err == CL_SUCCESS && d && found != all.end()) return found;
    *note += (note->empty() ? "" : ", ") + platform + ": clGetGLContextInfoKHR " +
             (err == CL_SUCCESS ? std::string("named no listed device")
                                : "failed (error " + std::to_string(err) + ")");
  }
  return all.end();
}

// The GL context's device `gl` (all.end(): unknown) unless `wanted_device`
// (EngineOptions::device, SIMSOLS_CL_DEVICE) names another; else its
// choice, else the first GPU, else the first device. *how says which rule
// chose.
std::vector<Candidate>::const_iterator choose_device(const std::vector<Candidate>& all,
                                                     std::vector<Candidate>::const_iterator gl,
                                                     const std::string& wanted_device,
                                                     std::string* how) {
  const std::string want = lower(wanted_device);
  auto wanted = [&](const Candidate& c) {
    if (want == "gpu") return c.gpu;
    if (want == "cpu") return !c.gpu;
    return lower(c.name).find(want) != std::string::npos;
  };
  if (gl != all.end() && (want.empty() || wanted(*gl))) {
    *how = "the GL context's device (clGetGLContextInfoKHR)";
    return gl;
  }
  if (!want.empty()) {
    auto pick = std::find_if(all.begin(), all.end(), wanted);
    if (pick == all.end())
      throw DeviceError("SIMSOLS_CL_DEVICE='" + want + "' matches no OpenCL device");
    *how = "SIMSOLS_CL_DEVICE='" + want + "'";
    if (gl != all.end()) *how += ", not the GL context's '" + gl->name + "'";
    return pick;
  }
  auto pick = std::find_if(all.begin(), all.end(), [](const Candidate& c) { return c.gpu; });
  *how = pick == all.end() ? "the first device" : "the first GPU";
  return pick == all.end() ? all.begin() : pick;
}

}  // namespace

std::shared_ptr<Device> Device::open(const EngineOptions& options) {
  return open(options, std::vector<cl_context_properties>{});
}

std::shared_ptr<Device> Device::open(const EngineOptions& options,
                                     const std::vector<cl_context_properties>& gl_properties) {
  const std::vector<cl_platform_id> platforms = list_platforms();
  const std::vector<Candidate> all = list_devices(platforms);
  std::string asked;  // what clGetGLContextInfoKHR answered, where it failed
  auto gl = all.end();
  if (!gl_properties.empty()) gl = gl_context_device(all, platforms, gl_properties, &asked);
  std::string how;
  const auto pick = choose_device(all, gl, options.device, &how);

  std::shared_ptr<Device> dev(new Device());
  dev->options_ = options;
  dev->platform_ = pick->p;
  dev->device_ = pick->d;
  dev->gpu_ = pick->gpu;
  dev->name_ = pick->name;
  dev->platform_name_ = platform_string(pick->p, CL_PLATFORM_NAME);
  dev->version_ = device_string(pick->d, CL_DEVICE_VERSION);
  dev->extensions_ = device_string(pick->d, CL_DEVICE_EXTENSIONS);
  if (dev->platform_name_ == "Portable Computing Language")
    dev->compile_lock_path_ = pocl_compile_lock_path();
  cl_uint align_bits = 0;
  check(clGetDeviceInfo(pick->d, CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof align_bits, &align_bits,
                        nullptr),
        "clGetDeviceInfo(CL_DEVICE_MEM_BASE_ADDR_ALIGN)");
  dev->base_align_ = std::max<size_t>(align_bits / 8, 16);
  dev->open_context(gl_properties);
  // Which way the device was chosen, where a platform could have named the
  // GL context's device (on PoCL none can, and the note stays as it was).
  if (gl != all.end() || !asked.empty()) {
    dev->sharing_note_ += "; device: " + how;
    if (!asked.empty()) dev->sharing_note_ += " (" + asked + ")";
  }
  cl_int err = CL_SUCCESS;
  dev->queue_ = ClQueue(clCreateCommandQueue(dev->context_.get(), dev->device_, 0, &err));
  check(err, "clCreateCommandQueue");
  return dev;
}

void Device::open_context(const std::vector<cl_context_properties>& gl_properties) {
  cl_int err = CL_SUCCESS;
  if (gl_properties.empty()) {
    sharing_note_ = "no OpenGL context to share with";
  } else if (!has_extension("cl_khr_gl_sharing")) {
    // Checked before any sharing call: on devices without the extension
    // (PoCL) clCreateFromGLBuffer ends the process.
    sharing_note_ = "the OpenCL device has no cl_khr_gl_sharing";
  } else {
    std::vector<cl_context_properties> props = gl_properties;
    props.insert(props.end(),
                 {CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(platform_), 0});
    cl_context shared = clCreateContext(props.data(), 1, &device_, nullptr, nullptr, &err);
    if (err == CL_SUCCESS && shared) {
      context_ = ClContext(shared);
      gl_sharing_ = true;
      sharing_note_ = "cl_khr_gl_sharing";
    } else {
      // e.g. the GL context runs on another GPU than the OpenCL device, or
      // the driver does not take this kind of GL context (EGL or GLX)
      sharing_note_ = "clCreateContext with the OpenGL context failed (error " +
                      std::to_string(err) + ")";
    }
  }
  if (!context_) {
    context_ = ClContext(clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &err));
    check(err, "clCreateContext");
  }
}

bool Device::has_extension(const std::string& ext) const {
  return has_word(extensions_, ext);
}

bool Device::has_double() const { return has_extension("cl_khr_fp64"); }

std::string Device::description() const {
  return name_ + " (" + platform_name_ + ", " + version_ + ")";
}

namespace {

constexpr size_t kHugePage = size_t(2) << 20;  // x86-64's transparent huge page

// The host memory under one buffer, and what its rounding to whole pages
// adds to the device's count (Device::page_rounding_bytes).
struct HostBlock {
  void* memory;
  size_t extra;
  std::shared_ptr<std::atomic<size_t>> rounding;
};

void CL_CALLBACK free_host_block(cl_mem, void* data) {
  auto* block = static_cast<HostBlock*>(data);
  block->rounding->fetch_sub(block->extra);
  std::free(block->memory);
  delete block;
}

}  // namespace

// CPU devices: a buffer that fills whole 2 MiB pages to within 1/16 (the
// spare a growing buffer keeps anyway) lives in host memory the process
// allocates itself, aligned to 2 MiB and marked MADV_HUGEPAGE (Linux gives
// transparent huge pages where asked, and often only there), which the
// device uses in place (CL_MEM_USE_HOST_PTR). With 4 KiB pages the gathers
// of a million-bead step miss the TLB as well as the caches.
cl_mem Device::create_buffer(size_t size) {
  cl_int err = CL_SUCCESS;
  const size_t rounded = (size + kHugePage - 1) / kHugePage * kHugePage;
  if (gpu_ || !options_.huge_pages || size < kHugePage || rounded - size > size / 16) {
    cl_mem m = clCreateBuffer(context_.get(), CL_MEM_READ_WRITE, size, nullptr, &err);
    check(err, "clCreateBuffer");
    return m;
  }
  auto* block = new HostBlock{std::aligned_alloc(kHugePage, rounded), rounded - size, rounding_};
  if (!block->memory) {
    delete block;
    throw DeviceError("out of host memory for a buffer of " + std::to_string(rounded) + " bytes");
  }
  madvise(block->memory, rounded, MADV_HUGEPAGE);  // a hint: refused, the pages stay small
  cl_mem m = clCreateBuffer(context_.get(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, size,
                            block->memory, &err);
  if (err == CL_SUCCESS) {
    rounding_->fetch_add(block->extra);
    err = clSetMemObjectDestructorCallback(m, free_host_block, block);
    if (err == CL_SUCCESS) return m;
    clReleaseMemObject(m);  // without the callback: the block is freed here
    rounding_->fetch_sub(block->extra);
  }
  std::free(block->memory);
  delete block;
  check(err, "clCreateBuffer with host memory");
  return nullptr;
}

ClMem Device::alloc(size_t bytes, const void* init) {
  const size_t size = std::max<size_t>(bytes, 16);  // no zero-sized buffers
  cl_mem m = create_buffer(size);
  ClMem mem(m);
  if (init) write(m, bytes, init);
  else fill_zero(m, size);
  return mem;
}

ClMem Device::view(cl_mem parent, size_t offset, size_t bytes) {
  cl_int err = CL_SUCCESS;
  const cl_buffer_region region{offset, bytes};
  cl_mem m = clCreateSubBuffer(parent, CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region, &err);
  check(err, "clCreateSubBuffer");
  return ClMem(m);
}

void Device::write(cl_mem mem, size_t bytes, const void* src, size_t offset) {
  if (bytes == 0) return;
  check(clEnqueueWriteBuffer(queue_.get(), mem, CL_TRUE, offset, bytes, src, 0, nullptr, nullptr),
        "clEnqueueWriteBuffer");
}

void Device::read(cl_mem mem, size_t bytes, void* dst, size_t offset) {
  if (bytes == 0) return;
  check(clEnqueueReadBuffer(queue_.get(), mem, CL_TRUE, offset, bytes, dst, 0, nullptr, nullptr),
        "clEnqueueReadBuffer");
}

void Device::fill_zero(cl_mem mem, size_t bytes) {
  const cl_uint zero = 0;
  check(clEnqueueFillBuffer(queue_.get(), mem, &zero, sizeof zero, 0, bytes & ~size_t(3), 0,
                            nullptr, nullptr),
        "clEnqueueFillBuffer");
}

void Device::copy(cl_mem from, cl_mem to, size_t bytes) {
  if (bytes == 0) return;
  check(clEnqueueCopyBuffer(queue_.get(), from, to, 0, 0, bytes, 0, nullptr, nullptr),
        "clEnqueueCopyBuffer");
}

void Device::finish() { check(clFinish(queue_.get()), "clFinish"); }

}  // namespace simsols
