// Gl: the OpenGL 3.3 core entry points the renderer uses, as a table of
// function pointers loaded through whatever the context offers
// (eglGetProcAddress, OSMesaGetProcAddress, glfwGetProcAddress).
//
// Why our own table instead of GLEW: Debian's GLEW is built for GLX. Under
// EGL its glewInit() reports NO_GLX_DISPLAY yet loads the pointers; under
// OSMesa it loads nothing. A table filled from the context's own loader works
// the same under all three, has no global state (each context owns its
// table, like Dear ImGui's backends take their context explicitly), and names
// the missing function when a driver lacks one.
//
// Call sites read `gl.DrawArrays(...)`: the list below is the whole surface
// of OpenGL the renderer touches.
#pragma once

#include <GL/glcorearb.h>

#include <functional>
#include <string>

#include "render/gl/render_error.h"

namespace simsols::render {

#define SIMSOLS_GL_FUNCTIONS(X)                                              \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                         \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLGETFLOATVPROC, GetFloatv)                                           \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLVIEWPORTPROC, Viewport)                                             \
  X(PFNGLSCISSORPROC, Scissor)                                               \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                         \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                                   \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLISENABLEDPROC, IsEnabled)                                           \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                           \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                                   \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLCOLORMASKPROC, ColorMask)                                           \
  X(PFNGLCULLFACEPROC, CullFace)                                             \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLFINISHPROC, Finish)                                                 \
  X(PFNGLFLUSHPROC, Flush)                                                   \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                       \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                                       \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                   \
  X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange)                                 \
  X(PFNGLUNMAPBUFFERPROC, UnmapBuffer)                                       \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                       \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
  X(PFNGLUNIFORM2IPROC, Uniform2i)                                           \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                           \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                           \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLBINDFRAGDATALOCATIONPROC, BindFragDataLocation)                     \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXIMAGE3DPROC, TexImage3D)                                         \
  X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                                   \
  X(PFNGLTEXSUBIMAGE3DPROC, TexSubImage3D)                                   \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                     \
  X(PFNGLFRAMEBUFFERTEXTURELAYERPROC, FramebufferTextureLayer)               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLGENQUERIESPROC, GenQueries)                                         \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                   \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                         \
  X(PFNGLENDQUERYPROC, EndQuery)                                             \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

struct Gl {
#define SIMSOLS_GL_MEMBER(type, name) type name = nullptr;
  SIMSOLS_GL_FUNCTIONS(SIMSOLS_GL_MEMBER)
#undef SIMSOLS_GL_MEMBER

  // Fills every entry with `get("gl" + name)`; throws RenderError naming the
  // first function the loader does not provide.
  void load(const std::function<void*(const char*)>& get);

  // Throws RenderError("<what>: GL error 0x...") when glGetError reports one.
  void check(const char* what) const;
};

}  // namespace simsols::render
