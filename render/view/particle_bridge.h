// ParticleBridge: how the solver's particle and contact data reach the
// renderer's vertex buffers.
//
//   shared     the OpenCL context shares the GL context (cl_khr_gl_sharing):
//              the GL buffers are wrapped once as cl_mem (clCreateFromGLBuffer),
//              acquired, packed into by the ViewPacker kernels, released. No
//              copy leaves the GPU.
//   host copy  otherwise (PoCL, or a GL context on another device): the
//              kernels pack into plain OpenCL buffers, and one blocking read
//              lands them in the GL buffers mapped for writing
//              (glMapBufferRange): one host copy per frame.
//
// The choice is made once, from Device::gl_sharing() (which checks the
// extension string before any sharing call: on PoCL clCreateFromGLBuffer
// ends the process), printed once by the caller (path()), and invisible to
// the renderer, which only sees GeometryBuffers.
#pragma once

#include <string>
#include <vector>

#include "render/gl/gl_context.h"

#include "render/gl/renderer.h"
#include "render/view/view_pack.h"

namespace simsols::render {

// The OpenCL context properties that name a GL context for sharing
// (CL_GL_CONTEXT_KHR and its EGL display); empty where the platform cannot
// share (OSMesa). Pass to Device::open.
std::vector<cl_context_properties> cl_share_properties(const GlShareHandles& handles);

class ParticleBridge {
 public:
  ParticleBridge(const Gl& gl, GeometryBuffers& buffers, ViewPacker& packer, Device& device);
  ~ParticleBridge();
  ParticleBridge(const ParticleBridge&) = delete;
  ParticleBridge& operator=(const ParticleBridge&) = delete;

  bool shared() const { return shared_; }
  // "shared (cl_khr_gl_sharing; device: ...)" or "host copy (<why not shared>)"
  std::string path() const;

  // Packs the beads and their field into the GL buffers; returns the
  // field's range.
  ViewPacker::Range update_beads(ColorField field);
  // Packs every touching contact (the buffer grows to hold them all).
  ViewPacker::ContactStats update_contacts(bool walls);

 private:
  void wrap_gl_buffers();  // shared path: (re)create the cl_mem views
  template <typename Pack>
  void with_gl_objects(Pack pack);

  const Gl& gl_;
  GeometryBuffers& buffers_;
  ViewPacker& packer_;
  Device& device_;
  bool shared_ = false;
  // shared: cl_mem views of the GL buffers; host: plain device buffers
  ClMem beads_, values_, segments_;
  std::size_t wrapped_beads_ = 0, wrapped_segments_ = 0;
  std::size_t host_beads_ = 0, host_segments_ = 0;
};

}  // namespace simsols::render
