#include "gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <vector>

namespace simsols::render {

const char* to_string(GlBackend b) {
  switch (b) {
    case GlBackend::Auto: return "auto";
    case GlBackend::Egl: return "egl";
    case GlBackend::OSMesa: return "osmesa";
  }
  return "?";
}

std::optional<GlBackend> parse_gl_backend(std::string_view s) {
  if (s == "auto") return GlBackend::Auto;
  if (s == "egl") return GlBackend::Egl;
  if (s == "osmesa") return GlBackend::OSMesa;
  return std::nullopt;
}

GlBackend backend_from_environment() {
  const char* v = std::getenv("SIMSOLS_GL");
  if (!v || !*v) return GlBackend::Auto;
  if (auto b = parse_gl_backend(v)) return *b;
  throw RenderError(std::string("SIMSOLS_GL='") + v + "': allowed values are auto, egl, osmesa");
}

void GlContext::init_gl(const std::function<void*(const char*)>& get) {
  gl_.load(get);
  GLint major = 0, minor = 0;
  gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 33)
    throw RenderError("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                      " context; the renderer needs 3.3 core");
}

std::string GlContext::gl_strings() const {
  auto str = [&](GLenum e) {
    const GLubyte* s = gl_.GetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

namespace {

// ---------------------------------------------------------------- EGL
class EglContext final : public GlContext {
 public:
  explicit EglContext(std::string* why) {
    if (!open_display(why)) return;
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,  // surfaceless needs it
                                     EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0) {
      *why = "EGL (" + platform_ + "): no config with EGL_PBUFFER_BIT and EGL_OPENGL_BIT";
      return;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      *why = "EGL (" + platform_ + "): eglBindAPI(EGL_OPENGL_API) failed";
      return;
    }
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, ctx_attribs);
    if (context_ == EGL_NO_CONTEXT) {
      *why = "EGL (" + platform_ + "): no OpenGL 3.3 core context (error " + egl_error() + ")";
      return;
    }
    const char* ext = eglQueryString(display_, EGL_EXTENSIONS);
    if (!ext || !std::strstr(ext, "EGL_KHR_surfaceless_context")) {
      const EGLint pb[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display_, config, pb);
    }
    if (!eglMakeCurrent(display_, surface_, surface_, context_)) {
      *why = "EGL (" + platform_ + "): eglMakeCurrent failed (error " + egl_error() + ")";
      return;
    }
    try {
      init_gl([](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); });
    } catch (const RenderError& e) {
      *why = "EGL (" + platform_ + "): " + e.what();
      return;
    }
    ok_ = true;
  }
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      // eglGetPlatformDisplay returns the same display to every context of
      // the process and eglTerminate ends it for all: the last one out
      // terminates.
      if (--display_users()[display_] == 0) eglTerminate(display_);
    }
  }
  bool ok() const { return ok_; }
  std::string description() const override { return "EGL " + platform_ + ": " + gl_strings(); }
  GlShareHandles share_handles() const override {
    GlShareHandles h;
    h.gl_context = reinterpret_cast<std::intptr_t>(context_);
    h.egl_display = reinterpret_cast<std::intptr_t>(display_);
    return h;
  }
  void make_current() override { eglMakeCurrent(display_, surface_, surface_, context_); }

 private:
  static std::string egl_error() {
    char b[16];
    std::snprintf(b, sizeof b, "0x%04x", eglGetError());
    return b;
  }

  static std::map<EGLDisplay, int>& display_users() {
    static std::map<EGLDisplay, int> users;
    return users;
  }

  bool try_init(EGLDisplay d, const char* platform) {
    if (d == EGL_NO_DISPLAY) return false;
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) return false;
    ++display_users()[d];
    display_ = d;
    platform_ = platform;
    return true;
  }

  bool open_display(std::string* why) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const std::string ext = client ? client : "";
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display && ext.find("EGL_MESA_platform_surfaceless") != std::string::npos &&
        try_init(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                 "surfaceless"))
      return true;
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (get_platform_display && query_devices &&
        ext.find("EGL_EXT_platform_device") != std::string::npos) {
      EGLDeviceEXT devices[8];
      EGLint n = 0;
      if (query_devices(8, devices, &n))
        for (EGLint i = 0; i < n; ++i)
          if (try_init(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device"))
            return true;
    }
    if (try_init(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default display")) return true;
    *why = "EGL: no display could be initialised (surfaceless, device, default)";
    return false;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
  std::string platform_;
  bool ok_ = false;
};

// ------------------------------------------------------------- OSMesa
// The few entry points of GL/osmesa.h, resolved with dlsym.
constexpr int kOsmesaFormat = 0x22;        // OSMESA_FORMAT
constexpr int kOsmesaDepthBits = 0x30;     // OSMESA_DEPTH_BITS
constexpr int kOsmesaProfile = 0x33;       // OSMESA_PROFILE
constexpr int kOsmesaCoreProfile = 0x34;   // OSMESA_CORE_PROFILE
constexpr int kOsmesaMajor = 0x36;         // OSMESA_CONTEXT_MAJOR_VERSION
constexpr int kOsmesaMinor = 0x37;         // OSMESA_CONTEXT_MINOR_VERSION
constexpr int kOsmesaRgba = 0x1908;        // GL_RGBA

class OsmesaContext final : public GlContext {
  using Ctx = void*;
  using CreateAttribs = Ctx (*)(const int*, Ctx);
  using MakeCurrent = unsigned char (*)(Ctx, void*, unsigned, int, int);
  using Destroy = void (*)(Ctx);
  using GetProc = void* (*)(const char*);

 public:
  explicit OsmesaContext(std::string* why) {
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"})
      if ((lib_ = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
    if (!lib_) {
      *why = "OSMesa: libOSMesa not found (Debian package libosmesa6)";
      return;
    }
    create_ = reinterpret_cast<CreateAttribs>(dlsym(lib_, "OSMesaCreateContextAttribs"));
    make_current_ = reinterpret_cast<MakeCurrent>(dlsym(lib_, "OSMesaMakeCurrent"));
    destroy_ = reinterpret_cast<Destroy>(dlsym(lib_, "OSMesaDestroyContext"));
    get_proc_ = reinterpret_cast<GetProc>(dlsym(lib_, "OSMesaGetProcAddress"));
    if (!create_ || !make_current_ || !destroy_ || !get_proc_) {
      *why = "OSMesa: libOSMesa lacks OSMesaCreateContextAttribs";
      return;
    }
    const int attribs[] = {kOsmesaFormat, kOsmesaRgba, kOsmesaDepthBits, 24,
                           kOsmesaProfile, kOsmesaCoreProfile, kOsmesaMajor, 3,
                           kOsmesaMinor, 3, 0};
    ctx_ = create_(attribs, nullptr);
    if (!ctx_) {
      *why = "OSMesa: no OpenGL 3.3 core context";
      return;
    }
    // The renderer draws into its own framebuffers; the context's default
    // buffer is a 16x16 placeholder.
    buffer_.assign(16 * 16 * 4, 0);
    if (!make_current_(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 16, 16)) {
      *why = "OSMesa: OSMesaMakeCurrent failed";
      return;
    }
    try {
      GetProc get = get_proc_;
      init_gl([get](const char* name) { return get(name); });
    } catch (const RenderError& e) {
      *why = std::string("OSMesa: ") + e.what();
      return;
    }
    ok_ = true;
  }
  ~OsmesaContext() override {
    if (ctx_) destroy_(ctx_);
    // libOSMesa stays loaded: unloading a GL driver at exit is not safe.
  }
  bool ok() const { return ok_; }
  std::string description() const override { return "OSMesa: " + gl_strings(); }
  GlShareHandles share_handles() const override { return {}; }
  void make_current() override { make_current_(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 16, 16); }

 private:
  void* lib_ = nullptr;
  CreateAttribs create_ = nullptr;
  MakeCurrent make_current_ = nullptr;
  Destroy destroy_ = nullptr;
  GetProc get_proc_ = nullptr;
  Ctx ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
  bool ok_ = false;
};

}  // namespace

std::unique_ptr<GlContext> create_headless_context(GlBackend backend) {
  if (backend == GlBackend::Auto) backend = backend_from_environment();
  std::string errors;
  if (backend == GlBackend::Auto || backend == GlBackend::Egl) {
    std::string why;
    auto c = std::make_unique<EglContext>(&why);
    if (c->ok()) return c;
    errors += "\n  " + why;
  }
  if (backend == GlBackend::Auto || backend == GlBackend::OSMesa) {
    std::string why;
    auto c = std::make_unique<OsmesaContext>(&why);
    if (c->ok()) return c;
    errors += "\n  " + why;
  }
  throw RenderError(std::string("no headless OpenGL 3.3 context (backend ") + to_string(backend) +
                    "):" + errors +
                    "\n  install Mesa's EGL (libegl1-mesa) or OSMesa (libosmesa6), or set "
                    "SIMSOLS_GL=egl|osmesa");
}

}  // namespace simsols::render
