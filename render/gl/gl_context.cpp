#include "render/gl/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
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

bool GlContext::software_rasterizer() const {
  const GLubyte* r = gl_.GetString(GL_RENDERER);
  const std::string name = r ? reinterpret_cast<const char*>(r) : "";
  for (const char* cpu : {"llvmpipe", "softpipe", "swrast", "SwiftShader", "lavapipe"})
    if (name.find(cpu) != std::string::npos) return true;
  return false;
}

namespace {

// ---------------------------------------------------------------- EGL
// Whole-word match in a space-separated extension list (NULL: none).
bool has_word(const char* list, std::string_view word) {
  if (!list) return false;
  const std::string_view l(list);
  for (size_t pos = l.find(word); pos != std::string_view::npos; pos = l.find(word, pos + 1)) {
    const size_t end = pos + word.size();
    if ((pos == 0 || l[pos - 1] == ' ') && (end == l.size() || l[end] == ' ')) return true;
  }
  return false;
}

std::string egl_error() {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04x", eglGetError());
  return b;
}

// The devices eglQueryDevicesEXT lists, with what the display order needs
// to know of them, and the entry point that opens a display on one.
struct EglDevices {
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
  std::vector<EGLDeviceEXT> handles;
  EglInventory inventory;
};

// "NVIDIA Corporation NVIDIA H200, /dev/dri/card1": EGL_VENDOR and
// EGL_RENDERER_EXT (EGL_EXT_device_query_name), EGL_DRM_DEVICE_FILE_EXT
// (EGL_EXT_device_drm); a device without them answers NULL.
std::string egl_device_name(EGLDeviceEXT d, PFNEGLQUERYDEVICESTRINGEXTPROC query, bool software) {
  std::string name;
  auto append = [&](EGLint what, const char* separator) {
    const char* s = query ? query(d, what) : nullptr;
    if (s && *s) name += (name.empty() ? "" : separator) + std::string(s);
  };
  append(EGL_VENDOR, " ");
  append(EGL_RENDERER_EXT, " ");
  append(EGL_DRM_DEVICE_FILE_EXT, ", ");
  if (software) name += name.empty() ? "software" : ", software";
  return name;
}

EglDevices list_egl_devices() {
  EglDevices out;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  out.get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!out.get_platform_display) return out;
  out.inventory.surfaceless = has_word(client, "EGL_MESA_platform_surfaceless");
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  EGLint n = 0;
  if (!query_devices || !has_word(client, "EGL_EXT_platform_device") ||
      !query_devices(0, nullptr, &n) || n <= 0)
    return out;
  out.handles.resize(std::size_t(n));
  if (!query_devices(n, out.handles.data(), &n)) n = 0;
  out.handles.resize(std::size_t(n));
  for (EGLDeviceEXT d : out.handles) {
    const bool software =
        query_string && has_word(query_string(d, EGL_EXTENSIONS), "EGL_MESA_device_software");
    out.inventory.devices.push_back({software, egl_device_name(d, query_string, software)});
  }
  return out;
}

class EglContext final : public GlContext {
 public:
  // Tries the displays in egl_display_order; the first that gives a 3.3
  // core context is kept, and *why lists every failure when none does.
  EglContext(EglPreference preference, std::string* why) {
    const EglDevices egl = list_egl_devices();
    std::string tried;
    for (const EglDisplayChoice& choice : egl_display_order(egl.inventory, preference)) {
      label_ = egl_display_label(choice, egl.inventory);
      std::string why_not;
      if (open_display(egl, choice, &why_not) && create_context(&why_not)) {
        ok_ = true;
        return;
      }
      release();
      tried += "\n    " + label_ + ": " + why_not;
    }
    *why = "EGL: no display gave an OpenGL 3.3 core context" + tried;
  }
  ~EglContext() override { release(); }
  bool ok() const { return ok_; }
  std::string description() const override { return label_ + ": " + gl_strings(); }
  GlShareHandles share_handles() const override {
    GlShareHandles h;
    h.gl_context = reinterpret_cast<std::intptr_t>(context_);
    h.egl_display = reinterpret_cast<std::intptr_t>(display_);
    return h;
  }
  void make_current() override { eglMakeCurrent(display_, surface_, surface_, context_); }

 private:
  // How many contexts use each EGL display, process-wide because EGL's
  // displays are (eglGetPlatformDisplay returns the same one to every
  // caller); contexts open and close on any thread (the lab builds in the
  // background), so every use holds the mutex.
  struct DisplayUsers {
    std::mutex mutex;
    std::map<EGLDisplay, int> count;
  };
  static DisplayUsers& display_users() {
    static DisplayUsers users;
    return users;
  }

  bool open_display(const EglDevices& egl, const EglDisplayChoice& choice, std::string* why) {
    EGLDisplay d = EGL_NO_DISPLAY;
    switch (choice.kind) {
      case EglDisplayChoice::Kind::Device:
        d = egl.get_platform_display(EGL_PLATFORM_DEVICE_EXT,
                                     egl.handles[std::size_t(choice.device)], nullptr);
        break;
      case EglDisplayChoice::Kind::Surfaceless:
        d = egl.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        break;
      case EglDisplayChoice::Kind::Default: d = eglGetDisplay(EGL_DEFAULT_DISPLAY); break;
    }
    if (d == EGL_NO_DISPLAY) {
      *why = "no display (error " + egl_error() + ")";
      return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) {
      *why = "eglInitialize failed (error " + egl_error() + ")";
      return false;
    }
    {
      DisplayUsers& users = display_users();
      const std::lock_guard lock(users.mutex);
      ++users.count[d];
    }
    display_ = d;
    return true;
  }

  bool create_context(std::string* why) {
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,  // surfaceless needs it
                                     EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0) {
      *why = "no config with EGL_PBUFFER_BIT and EGL_OPENGL_BIT";
      return false;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      *why = "eglBindAPI(EGL_OPENGL_API) failed";
      return false;
    }
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, ctx_attribs);
    if (context_ == EGL_NO_CONTEXT) {
      *why = "no OpenGL 3.3 core context (error " + egl_error() + ")";
      return false;
    }
    if (!has_word(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
      const EGLint pb[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display_, config, pb);
    }
    if (!eglMakeCurrent(display_, surface_, surface_, context_)) {
      *why = "eglMakeCurrent failed (error " + egl_error() + ")";
      return false;
    }
    try {
      init_gl([](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); });
    } catch (const RenderError& e) {
      *why = e.what();
      return false;
    }
    return true;
  }

  // Undoes open_display and create_context (a failed display, or the end).
  void release() {
    if (display_ == EGL_NO_DISPLAY) return;
    if (context_ != EGL_NO_CONTEXT && eglGetCurrentContext() == context_)
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    // eglGetPlatformDisplay returns the same display to every context of the
    // process and eglTerminate ends it for all: the last one out terminates.
    DisplayUsers& users = display_users();
    const std::lock_guard lock(users.mutex);
    if (--users.count[display_] == 0) eglTerminate(display_);
    display_ = EGL_NO_DISPLAY;
    context_ = EGL_NO_CONTEXT;
    surface_ = EGL_NO_SURFACE;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
  std::string label_;  // "EGL device 0 (...)", "EGL surfaceless", ...
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

EglInventory egl_inventory() { return list_egl_devices().inventory; }

std::vector<EglDisplayChoice> egl_display_order(const EglInventory& inventory,
                                                EglPreference preference) {
  using Kind = EglDisplayChoice::Kind;
  std::vector<EglDisplayChoice> order;
  auto add_devices = [&](auto keep) {
    for (std::size_t i = 0; i < inventory.devices.size(); ++i)
      if (keep(inventory.devices[i])) order.push_back({Kind::Device, int(i)});
  };
  if (preference == EglPreference::Hardware) {
    add_devices([](const EglDeviceInfo& d) { return !d.software; });
    if (inventory.surfaceless) order.push_back({Kind::Surfaceless});
    add_devices([](const EglDeviceInfo& d) { return d.software; });
  } else {
    if (inventory.surfaceless) order.push_back({Kind::Surfaceless});
    add_devices([](const EglDeviceInfo&) { return true; });
  }
  order.push_back({Kind::Default});
  return order;
}

std::string egl_display_label(const EglDisplayChoice& choice, const EglInventory& inventory) {
  switch (choice.kind) {
    case EglDisplayChoice::Kind::Surfaceless: return "EGL surfaceless";
    case EglDisplayChoice::Kind::Default: return "EGL default display";
    case EglDisplayChoice::Kind::Device: break;
  }
  const bool listed = choice.device >= 0 && std::size_t(choice.device) < inventory.devices.size();
  const std::string name = listed ? inventory.devices[std::size_t(choice.device)].name : "";
  return "EGL device " + std::to_string(choice.device) + " (" + (name.empty() ? "unnamed" : name) +
         ")";
}

std::unique_ptr<GlContext> create_headless_context(GlBackend backend) {
  HeadlessOptions options;
  options.backend = backend;
  return create_headless_context(options);
}

std::unique_ptr<GlContext> create_headless_context(const HeadlessOptions& options) {
  GlBackend backend = options.backend;
  std::string errors;
  if (backend == GlBackend::Auto || backend == GlBackend::Egl) {
    std::string why;
    auto c = std::make_unique<EglContext>(options.egl, &why);
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
                    "\n  install Mesa's EGL (libegl1-mesa) or OSMesa (libosmesa6), or choose one "
                    "with --gl egl|osmesa (SIMSOLS_GL)");
}

}  // namespace simsols::render
