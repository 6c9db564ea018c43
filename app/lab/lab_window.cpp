#include "app/lab/lab_window.h"

#define GLFW_EXPOSE_NATIVE_X11
#define GLFW_EXPOSE_NATIVE_GLX
#define GLFW_INCLUDE_NONE  // GL comes from render/gl/gl_api.h
#include <GLFW/glfw3.h>
#include <GLFW/glfw3native.h>

#include <cstdlib>

namespace simsols {

bool LabWindow::display_available() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
}

LabWindow::LabWindow(int width, int height, const std::string& title) {
  if (!glfwInit()) throw render::RenderError("GLFW could not initialise (no display?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw render::RenderError("GLFW could not open an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);  // the lab paces itself (the solver uses the spare time)
  init_gl([](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); });
}

LabWindow::~LabWindow() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::string LabWindow::description() const { return "GLFW window: " + gl_strings(); }

render::GlShareHandles LabWindow::share_handles() const {
  render::GlShareHandles h;
  h.gl_context = reinterpret_cast<std::intptr_t>(glfwGetGLXContext(window_));
  h.glx_display = reinterpret_cast<std::intptr_t>(glfwGetX11Display());
  return h;
}

void LabWindow::make_current() { glfwMakeContextCurrent(window_); }

void LabWindow::position(int* x, int* y) const { glfwGetWindowPos(window_, x, y); }

void LabWindow::toggle_fullscreen() {
  if (glfwGetWindowMonitor(window_)) {
    glfwSetWindowMonitor(window_, nullptr, saved_[0], saved_[1], saved_[2], saved_[3], 0);
    return;
  }
  glfwGetWindowPos(window_, &saved_[0], &saved_[1]);
  glfwGetWindowSize(window_, &saved_[2], &saved_[3]);
  GLFWmonitor* monitor = glfwGetPrimaryMonitor();
  if (!monitor) return;
  const GLFWvidmode* mode = glfwGetVideoMode(monitor);
  glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
}

}  // namespace simsols
