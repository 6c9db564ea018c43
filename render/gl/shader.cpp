#include "render/gl/shader.h"

namespace simsols::render {

namespace {

std::string assemble(std::string_view file, bool fragment, const std::vector<std::string>& defines) {
  std::string text = "#version 330 core\n";
  // Conservative depth lets the sphere impostors keep early depth rejection
  // while writing gl_FragDepth; where a driver lacks it, "enable" only warns.
  if (fragment) text += "#extension GL_ARB_conservative_depth : enable\n";
  for (const std::string& d : defines) text += "#define " + d + "\n";
  text += "#line 1 1\n";  // source string 1: common.glsl or common_vertex.glsl
  text += shader_file(fragment ? "common.glsl" : "common_vertex.glsl");
  text += "\n";
  text += "#line 1 2\n";  // source string 2: the file itself
  text += shader_file(file);
  return text;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& d : v) s += (s.empty() ? "" : " ") + d;
  return s.empty() ? "none" : s;
}

}  // namespace

ShaderProgram::ShaderProgram(const Gl& gl, std::string_view vertex_file,
                             std::string_view fragment_file, const std::vector<std::string>& defines)
    : gl_(gl) {
  GLuint shaders[2] = {0, 0};
  const std::string_view files[2] = {vertex_file, fragment_file};
  for (int s = 0; s < 2; ++s) {
    const std::string text = assemble(files[s], s == 1, defines);
    shaders[s] = gl.CreateShader(s == 0 ? GL_VERTEX_SHADER : GL_FRAGMENT_SHADER);
    const char* src = text.c_str();
    gl.ShaderSource(shaders[s], 1, &src, nullptr);
    gl.CompileShader(shaders[s]);
    GLint ok = 0;
    gl.GetShaderiv(shaders[s], GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      gl.GetShaderInfoLog(shaders[s], sizeof log, nullptr, log);
      gl.DeleteShader(shaders[s]);
      if (s == 1) gl.DeleteShader(shaders[0]);
      throw RenderError("shader " + std::string(files[s]) + " (defines: " + join(defines) +
                        ") does not compile (source 1 = common.glsl or common_vertex.glsl, 2 = the file):\n" + log);
    }
  }
  id_ = gl.CreateProgram();
  gl.AttachShader(id_, shaders[0]);
  gl.AttachShader(id_, shaders[1]);
  gl.LinkProgram(id_);
  gl.DeleteShader(shaders[0]);
  gl.DeleteShader(shaders[1]);
  GLint ok = 0;
  gl.GetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(id_, sizeof log, nullptr, log);
    gl.DeleteProgram(id_);
    id_ = 0;
    throw RenderError("shaders " + std::string(vertex_file) + " + " + std::string(fragment_file) +
                      " (defines: " + join(defines) + ") do not link:\n" + log);
  }
}

ShaderProgram::~ShaderProgram() {
  if (id_) gl_.DeleteProgram(id_);
}

GLint ShaderProgram::uniform(const char* name) {
  auto it = uniforms_.find(name);
  if (it != uniforms_.end()) return it->second;
  const GLint loc = gl_.GetUniformLocation(id_, name);
  uniforms_.emplace(name, loc);
  return loc;
}

}  // namespace simsols::render
