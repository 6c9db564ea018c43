// RenderError: everything the renderer cannot do (no GL context, a shader
// that fails to compile, a bad frame size or path), with a message that names
// the cause. The app prints it and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace simsols::render {

struct RenderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace simsols::render
