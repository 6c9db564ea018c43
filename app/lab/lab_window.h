// LabWindow: the desktop platform of the lab, a GLFW window with an
// OpenGL 3.3 core context. Another implementation of render::GlContext (the
// headless ones are EGL and OSMesa): the renderer draws into its own
// framebuffers and the lab blits the result into this window, so nothing
// in render/ knows about windows. GLFW state is per window (user pointer);
// the only process-wide state is GLFW's own initialisation.
#pragma once

#include <memory>
#include <string>

#include "render/gl/gl_context.h"

struct GLFWwindow;

namespace simsols {

class LabWindow final : public render::GlContext {
 public:
  // Throws render::RenderError when no display or no 3.3 core context.
  LabWindow(int width, int height, const std::string& title);
  ~LabWindow() override;

  GLFWwindow* handle() const { return window_; }
  std::string description() const override;
  render::GlShareHandles share_handles() const override;  // GLX handles for CL sharing
  void make_current() override;

  void toggle_fullscreen();
  // The window's top-left pixel on the screen (Alioscopy interleaving).
  void position(int* x, int* y) const;

  // True when a display is there to open a window on.
  static bool display_available();

 private:
  GLFWwindow* window_ = nullptr;
  int saved_[4] = {100, 100, 1280, 800};  // position and size before full screen
};

}  // namespace simsols
