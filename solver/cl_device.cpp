#include "cl_device.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

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

}  // namespace

std::shared_ptr<Device> Device::open() { return open(std::vector<cl_context_properties>{}); }

std::shared_ptr<Device> Device::open(const std::vector<cl_context_properties>& gl_properties) {
  cl_uint np = 0;
  if (clGetPlatformIDs(0, nullptr, &np) != CL_SUCCESS || np == 0)
    throw DeviceError(
        "no OpenCL platform found: install an OpenCL driver (Debian: pocl-opencl-icd)");
  std::vector<cl_platform_id> platforms(np);
  check(clGetPlatformIDs(np, platforms.data(), nullptr), "clGetPlatformIDs");

  struct Candidate { cl_platform_id p; cl_device_id d; bool gpu; std::string name; };
  std::vector<Candidate> all;
  for (cl_platform_id p : platforms) {
    cl_uint nd = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS || nd == 0) continue;
    std::vector<cl_device_id> devs(nd);
    check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, devs.data(), nullptr), "clGetDeviceIDs");
    for (cl_device_id d : devs) {
      cl_device_type t = 0;
      check(clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof t, &t, nullptr), "clGetDeviceInfo");
      all.push_back({p, d, (t & CL_DEVICE_TYPE_GPU) != 0, device_string(d, CL_DEVICE_NAME)});
    }
  }
  if (all.empty()) throw DeviceError("no OpenCL device found");

  const char* want_env = std::getenv("SIMSOLS_CL_DEVICE");
  const std::string want = want_env ? lower(want_env) : "";
  auto pick = all.end();
  if (!want.empty()) {
    pick = std::find_if(all.begin(), all.end(), [&](const Candidate& c) {
      if (want == "gpu") return c.gpu;
      if (want == "cpu") return !c.gpu;
      return lower(c.name).find(want) != std::string::npos;
    });
    if (pick == all.end())
      throw DeviceError("SIMSOLS_CL_DEVICE='" + want + "' matches no OpenCL device");
  } else {
    pick = std::find_if(all.begin(), all.end(), [](const Candidate& c) { return c.gpu; });
    if (pick == all.end()) pick = all.begin();
  }

  std::shared_ptr<Device> dev(new Device());
  dev->platform_ = pick->p;
  dev->device_ = pick->d;
  dev->gpu_ = pick->gpu;
  dev->name_ = pick->name;
  dev->platform_name_ = platform_string(pick->p, CL_PLATFORM_NAME);
  dev->version_ = device_string(pick->d, CL_DEVICE_VERSION);
  dev->extensions_ = device_string(pick->d, CL_DEVICE_EXTENSIONS);
  cl_int err = CL_SUCCESS;
  if (gl_properties.empty()) {
    dev->sharing_note_ = "no OpenGL context to share with";
  } else if (!dev->has_extension("cl_khr_gl_sharing")) {
    // Checked before any sharing call: on devices without the extension
    // (PoCL) clCreateFromGLBuffer ends the process.
    dev->sharing_note_ = "the OpenCL device has no cl_khr_gl_sharing";
  } else {
    std::vector<cl_context_properties> props = gl_properties;
    props.push_back(CL_CONTEXT_PLATFORM);
    props.push_back(reinterpret_cast<cl_context_properties>(pick->p));
    props.push_back(0);
    cl_context shared = clCreateContext(props.data(), 1, &dev->device_, nullptr, nullptr, &err);
    if (err == CL_SUCCESS && shared) {
      dev->context_ = ClContext(shared);
      dev->gl_sharing_ = true;
      dev->sharing_note_ = "cl_khr_gl_sharing";
    } else {
      // e.g. the GL context runs on another GPU than the OpenCL device
      dev->sharing_note_ = "clCreateContext with the OpenGL context failed (error " +
                           std::to_string(err) + ")";
    }
  }
  if (!dev->context_) {
    dev->context_ = ClContext(clCreateContext(nullptr, 1, &dev->device_, nullptr, nullptr, &err));
    check(err, "clCreateContext");
  }
  dev->queue_ = ClQueue(clCreateCommandQueue(dev->context_.get(), dev->device_, 0, &err));
  check(err, "clCreateCommandQueue");
  return dev;
}

bool Device::has_extension(const std::string& ext) const {
  // whole-word match in the space-separated list
  size_t pos = 0;
  while ((pos = extensions_.find(ext, pos)) != std::string::npos) {
    const size_t end = pos + ext.size();
    const bool left = pos == 0 || extensions_[pos - 1] == ' ';
    const bool right = end == extensions_.size() || extensions_[end] == ' ';
    if (left && right) return true;
    pos = end;
  }
  return false;
}

bool Device::has_double() const { return has_extension("cl_khr_fp64"); }

std::string Device::description() const {
  return name_ + " (" + platform_name_ + ", " + version_ + ")";
}

ClMem Device::alloc(size_t bytes, const void* init) {
  cl_int err = CL_SUCCESS;
  const size_t size = std::max<size_t>(bytes, 16);  // no zero-sized buffers
  cl_mem m = clCreateBuffer(context_.get(), CL_MEM_READ_WRITE, size, nullptr, &err);
  check(err, "clCreateBuffer");
  ClMem mem(m);
  if (init) write(m, bytes, init);
  else fill_zero(m, size);
  return mem;
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
