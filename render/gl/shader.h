// Shader programs from the embedded shaders/ files.
//
// A program is a vertex and a fragment file plus variant #defines (e.g. OIT),
// assembled as "#version 330 core", the defines, then for fragment shaders
// shaders/common.glsl, then the file. Compile and link errors throw
// RenderError with the file names, the defines and the driver's log: no
// shader fails silently. Uniform locations are looked up once and cached.
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "render/gl/gl_api.h"

namespace simsols::render {

// Text of an embedded shader file (throws RenderError if absent).
std::string_view shader_file(std::string_view name);

class ShaderProgram {
 public:
  ShaderProgram(const Gl& gl, std::string_view vertex_file, std::string_view fragment_file,
                const std::vector<std::string>& defines = {});
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const { gl_.UseProgram(id_); }
  GLuint id() const { return id_; }
  // -1 when the uniform is absent or optimised out (setting it is a no-op).
  GLint uniform(const char* name);
  void set(const char* name, int v) { gl_.Uniform1i(uniform(name), v); }
  void set(const char* name, float v) { gl_.Uniform1f(uniform(name), v); }
  void set(const char* name, float x, float y) { gl_.Uniform2f(uniform(name), x, y); }
  void set(const char* name, float x, float y, float z) { gl_.Uniform3f(uniform(name), x, y, z); }
  void set(const char* name, float x, float y, float z, float w) {
    gl_.Uniform4f(uniform(name), x, y, z, w);
  }
  void set_mat4(const char* name, const float* m) { gl_.UniformMatrix4fv(uniform(name), 1, GL_FALSE, m); }

 private:
  const Gl& gl_;
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> uniforms_;
};

}  // namespace simsols::render
