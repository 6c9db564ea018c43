#include "render/gl/gl_api.h"

#include <cstdio>

namespace simsols::render {

void Gl::load(const std::function<void*(const char*)>& get) {
#define SIMSOLS_GL_LOAD(type, name)                                                       \
  name = reinterpret_cast<type>(get("gl" #name));                                         \
  if (!name) throw RenderError("OpenGL function gl" #name " is not available from this context");
  SIMSOLS_GL_FUNCTIONS(SIMSOLS_GL_LOAD)
#undef SIMSOLS_GL_LOAD
}

void Gl::check(const char* what) const {
  const GLenum e = GetError();
  if (e == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", e);
  while (GetError() != GL_NO_ERROR) {
  }
  throw RenderError(std::string(what) + ": OpenGL error " + code);
}

}  // namespace simsols::render
