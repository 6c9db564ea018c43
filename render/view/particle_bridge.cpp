#include "render/view/particle_bridge.h"

#include <CL/cl_gl.h>

#include <algorithm>

namespace simsols::render {

namespace {

// Writes `bytes` from device buffer `src` into GL buffer `dst` through a
// mapped pointer: the one host copy of the host path.
void read_into_gl(const Gl& gl, Device& device, cl_mem src, GLuint dst, std::size_t bytes) {
  if (bytes == 0) return;
  GLint prev = 0;
  gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev);
  gl.BindBuffer(GL_ARRAY_BUFFER, dst);
  void* p = gl.MapBufferRange(GL_ARRAY_BUFFER, 0, GLsizeiptr(bytes),
                              GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT);
  if (!p) {
    gl.BindBuffer(GL_ARRAY_BUFFER, GLuint(prev));
    throw RenderError("glMapBufferRange failed for " + std::to_string(bytes) + " bytes");
  }
  try {
    device.read(src, bytes, p);
  } catch (...) {
    gl.UnmapBuffer(GL_ARRAY_BUFFER);
    gl.BindBuffer(GL_ARRAY_BUFFER, GLuint(prev));
    throw;
  }
  gl.UnmapBuffer(GL_ARRAY_BUFFER);
  gl.BindBuffer(GL_ARRAY_BUFFER, GLuint(prev));
}

}  // namespace

std::vector<cl_context_properties> cl_share_properties(const GlShareHandles& h) {
  if (!h.gl_context) return {};
  if (h.egl_display)
    return {CL_GL_CONTEXT_KHR, cl_context_properties(h.gl_context), CL_EGL_DISPLAY_KHR,
            cl_context_properties(h.egl_display)};
  if (h.glx_display)
    return {CL_GL_CONTEXT_KHR, cl_context_properties(h.gl_context), CL_GLX_DISPLAY_KHR,
            cl_context_properties(h.glx_display)};
  return {};
}

ParticleBridge::ParticleBridge(const Gl& gl, GeometryBuffers& buffers, ViewPacker& packer,
                               Device& device)
    : gl_(gl), buffers_(buffers), packer_(packer), device_(device), shared_(device.gl_sharing()) {
  const std::size_t n = std::size_t(std::max(packer.particles(), 1));
  buffers_.reserve(n, 4 * n + 64);
}

ParticleBridge::~ParticleBridge() = default;

std::string ParticleBridge::path() const {
  if (shared_) return "shared (" + device_.sharing_note() + ")";
  return "host copy (" + device_.sharing_note() + ")";
}

void ParticleBridge::wrap_gl_buffers() {
  if (wrapped_beads_ == buffers_.bead_capacity() && wrapped_segments_ == buffers_.segment_capacity())
    return;
  cl_int err = CL_SUCCESS;
  beads_ = ClMem(clCreateFromGLBuffer(device_.context(), CL_MEM_WRITE_ONLY, buffers_.beads(), &err));
  check(err, "clCreateFromGLBuffer (beads)");
  values_ = ClMem(clCreateFromGLBuffer(device_.context(), CL_MEM_WRITE_ONLY, buffers_.values(), &err));
  check(err, "clCreateFromGLBuffer (values)");
  segments_ =
      ClMem(clCreateFromGLBuffer(device_.context(), CL_MEM_WRITE_ONLY, buffers_.segments(), &err));
  check(err, "clCreateFromGLBuffer (segments)");
  wrapped_beads_ = buffers_.bead_capacity();
  wrapped_segments_ = buffers_.segment_capacity();
}

template <typename Pack>
void ParticleBridge::with_gl_objects(Pack pack) {
  wrap_gl_buffers();
  gl_.Finish();  // GL is done with the buffers before OpenCL writes them
  cl_mem objs[3] = {beads_.get(), values_.get(), segments_.get()};
  check(clEnqueueAcquireGLObjects(device_.queue(), 3, objs, 0, nullptr, nullptr),
        "clEnqueueAcquireGLObjects");
  try {
    pack();
  } catch (...) {
    clEnqueueReleaseGLObjects(device_.queue(), 3, objs, 0, nullptr, nullptr);
    clFinish(device_.queue());
    throw;
  }
  check(clEnqueueReleaseGLObjects(device_.queue(), 3, objs, 0, nullptr, nullptr),
        "clEnqueueReleaseGLObjects");
  device_.finish();  // OpenCL is done before GL draws
}

ViewPacker::Range ParticleBridge::update_beads(ColorField field) {
  const std::size_t n = std::size_t(packer_.particles());
  buffers_.reserve(n, 0);
  ViewPacker::Range range;
  if (n == 0) {
    buffers_.mutable_geometry().bead_count = 0;
    return range;
  }
  if (shared_) {
    with_gl_objects([&] { range = packer_.pack_beads(field, beads_.get(), values_.get()); });
  } else {
    if (host_beads_ < n) {
      beads_ = device_.alloc(n * 16);
      values_ = device_.alloc(n * 4);
      host_beads_ = n;
    }
    range = packer_.pack_beads(field, beads_.get(), values_.get());
    read_into_gl(gl_, device_, beads_.get(), buffers_.beads(), n * 16);
    read_into_gl(gl_, device_, values_.get(), buffers_.values(), n * 4);
  }
  buffers_.mutable_geometry().bead_count = n;
  return range;
}

ViewPacker::ContactStats ParticleBridge::update_contacts(bool walls) {
  ViewPacker::ContactStats stats;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const std::size_t cap = buffers_.segment_capacity();
    if (shared_) {
      with_gl_objects([&] { stats = packer_.pack_contacts(segments_.get(), cap, walls); });
    } else {
      if (host_segments_ < cap) {
        segments_ = device_.alloc(cap * 32);
        host_segments_ = cap;
      }
      stats = packer_.pack_contacts(segments_.get(), cap, walls);
    }
    if (stats.total <= cap) break;
    // more contacts than room: grow with a margin and pack again
    buffers_.reserve(0, stats.total + stats.total / 4 + 64);
  }
  if (!shared_) read_into_gl(gl_, device_, segments_.get(), buffers_.segments(), stats.count * 32);
  buffers_.mutable_geometry().segment_count = stats.count;
  buffers_.mutable_geometry().mean_force = float(stats.mean_force);
  buffers_.mutable_geometry().max_force = float(stats.max_force);
  return stats;
}

}  // namespace simsols::render
