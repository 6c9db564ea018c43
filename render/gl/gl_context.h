// GlContext: an OpenGL 3.3 core context and its function table.
//
// The platform layer, kept apart from the renderer as Dear ImGui keeps its
// platform backends apart from its renderer backends: the renderer draws
// into framebuffer objects it owns and never asks where the context came
// from. Two headless platforms live here; the desktop window (GLFW) is
// another implementation of the same interface.
//
//   EGL     the displays below, in this order (EglPreference::Hardware,
//           the default); the first that gives a 3.3 core context wins.
//           A config with EGL_PBUFFER_BIT, made current without a surface
//           (or on a 16x16 pbuffer).
//             1. a hardware EGL device (eglQueryDevicesEXT,
//                EGL_EXT_platform_device: headless NVIDIA)
//             2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless,
//                llvmpipe on a machine without a GPU)
//             3. a software EGL device (EGL_MESA_device_software)
//             4. the default display
//           Hardware comes first because cl_khr_gl_sharing needs the GL
//           context on the OpenCL device: llvmpipe beside a GPU means a host
//           copy per frame. EglPreference::Surfaceless keeps the older order
//           (surfaceless, every device, default).
//   OSMesa  Mesa's off-screen library, loaded with dlopen when chosen, so a
//           machine without it still runs the EGL path.
//
// Auto tries EGL, then OSMesa; Egl or OSMesa (the --gl flag, or SIMSOLS_GL
// read by the commands) forces one. When none works the error lists why each attempt failed, and
// description() names the display that was used ("EGL device 0 (...)",
// "EGL surfaceless", "EGL default display").
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/gl_api.h"

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
  // Whether the renderer rasterises on the CPU (llvmpipe, softpipe,
  // SwiftShader...): its drawing then takes the same cores as a CPU
  // OpenCL device's kernels.
  bool software_rasterizer() const;

 protected:
  // Loads the table and reads the version strings (the context is current).
  void init_gl(const std::function<void*(const char*)>& get);
  std::string gl_strings() const;  // renderer and version
  Gl gl_;
};

// Which EGL display is tried first (see the order above).
enum class EglPreference { Hardware, Surfaceless };

struct HeadlessOptions {
  GlBackend backend = GlBackend::Auto;  // Auto: EGL, then OSMesa
  EglPreference egl = EglPreference::Hardware;
};

// A headless context (no window, no display). Throws RenderError.
std::unique_ptr<GlContext> create_headless_context(const HeadlessOptions& options = {});
std::unique_ptr<GlContext> create_headless_context(GlBackend backend);

// ------------------------------------------------ the EGL display order
// What EGL offers on this machine, as the order below needs it.
struct EglDeviceInfo {
  bool software = false;  // EGL_MESA_device_software (llvmpipe, swrast)
  std::string name;       // vendor and renderer, or the DRM node; may be empty
};
struct EglInventory {
  bool surfaceless = false;  // EGL_MESA_platform_surfaceless
  std::vector<EglDeviceInfo> devices;  // eglQueryDevicesEXT order
};
// Lists the EGL devices and platforms (no display is initialised).
EglInventory egl_inventory();

// One display to try.
struct EglDisplayChoice {
  enum class Kind { Device, Surfaceless, Default };
  Kind kind = Kind::Default;
  int device = -1;  // index into EglInventory::devices, for Kind::Device
  bool operator==(const EglDisplayChoice&) const = default;
};

// The displays to try, first to last: a pure function of the inventory,
// ending with the default display.
std::vector<EglDisplayChoice> egl_display_order(const EglInventory& inventory,
                                                EglPreference preference);
// "EGL device 0 (NVIDIA Corporation, /dev/dri/card1)", "EGL surfaceless",
// "EGL default display": the start of GlContext::description().
std::string egl_display_label(const EglDisplayChoice& choice, const EglInventory& inventory);


}  // namespace simsols::render
