// GlContext: an OpenGL 3.3 core context and its function table.
//
// The platform layer, kept apart from the renderer as Dear ImGui keeps its
// platform backends apart from its renderer backends: the renderer draws
// into framebuffer objects it owns and never asks where the context came
// from. Two headless platforms live here; the desktop window (GLFW) is
// another implementation of the same interface.
//
//   EGL     Mesa's surfaceless platform (EGL_MESA_platform_surfaceless),
//           else an EGL device (EGL_EXT_platform_device, headless NVIDIA),
//           else the default display; a config with EGL_PBUFFER_BIT, made
//           current without a surface (or on a 16x16 pbuffer).
//   OSMesa  Mesa's off-screen library, loaded with dlopen when chosen, so a
//           machine without it still runs the EGL path.
//
// Auto tries EGL, then OSMesa; SIMSOLS_GL=egl|osmesa (or the --gl flag)
// forces one. When none works the error lists why each attempt failed.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "gl_api.h"

namespace simsols::render {

enum class GlBackend { Auto, Egl, OSMesa };
const char* to_string(GlBackend b);  // "auto", "egl", "osmesa"
std::optional<GlBackend> parse_gl_backend(std::string_view s);

// What an OpenCL context needs to share buffers with this GL context
// (cl_khr_gl_sharing): CL_GL_CONTEXT_KHR plus CL_EGL_DISPLAY_KHR or
// CL_GLX_DISPLAY_KHR. Zero where the platform cannot share (OSMesa).
struct GlShareHandles {
  std::intptr_t gl_context = 0;
  std::intptr_t egl_display = 0;
  std::intptr_t glx_display = 0;
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  const Gl& gl() const { return gl_; }
  // "EGL surfaceless: llvmpipe (...), OpenGL 4.5 (Core Profile) Mesa 22.3.6"
  virtual std::string description() const = 0;
  virtual GlShareHandles share_handles() const = 0;
  virtual void make_current() = 0;

 protected:
  // Loads the table and reads the version strings (the context is current).
  void init_gl(const std::function<void*(const char*)>& get);
  std::string gl_strings() const;  // renderer and version
  Gl gl_;
};

// A headless context (no window, no display). Throws RenderError.
std::unique_ptr<GlContext> create_headless_context(GlBackend backend = GlBackend::Auto);

// The backend `Auto` resolves to from the environment (SIMSOLS_GL), or Auto.
// Throws RenderError for an unknown value, naming the variable.
GlBackend backend_from_environment();

}  // namespace simsols::render
