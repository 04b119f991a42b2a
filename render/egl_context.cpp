// The second offscreen backend: EGL on Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless), the successor of OSMesa (removed in Mesa 25.1).
// libEGL is opened with dlopen, like libOSMesa, and the constants below come from
// the Khronos headers (EGL/egl.h, EGL/eglext.h), which are not included so that no
// X11 or EGL development headers are needed.
#include <dlfcn.h>

#include <cstdint>
#include <cstdlib>

#include "render/gl_context.h"

namespace tetlod::render {
namespace {

using EGLDisplay = void*;
using EGLConfig = void*;
using EGLContext = void*;
using EGLSurface = void*;
using EGLint = int32_t;
using EGLBoolean = unsigned int;
using EGLenum = unsigned int;

constexpr EGLint EGL_NONE = 0x3038;
constexpr EGLint EGL_EXTENSIONS = 0x3055;
constexpr EGLint EGL_SURFACE_TYPE = 0x3033;
constexpr EGLint EGL_RENDERABLE_TYPE = 0x3040;
constexpr EGLint EGL_OPENGL_BIT = 0x0008;
constexpr EGLenum EGL_OPENGL_API = 0x30A2;
constexpr EGLint EGL_CONTEXT_MAJOR_VERSION = 0x3098;
constexpr EGLint EGL_CONTEXT_MINOR_VERSION = 0x30FB;
constexpr EGLint EGL_CONTEXT_OPENGL_PROFILE_MASK = 0x30FD;
constexpr EGLint EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT = 0x1;
constexpr EGLenum EGL_PLATFORM_SURFACELESS_MESA = 0x31DD;

using GetProcAddressFn = void* (*)(const char*);
using GetPlatformDisplayFn = EGLDisplay (*)(EGLenum, void*, const EGLint*);
using InitializeFn = EGLBoolean (*)(EGLDisplay, EGLint*, EGLint*);
using BindApiFn = EGLBoolean (*)(EGLenum);
using ChooseConfigFn = EGLBoolean (*)(EGLDisplay, const EGLint*, EGLConfig*, EGLint, EGLint*);
using CreateContextFn = EGLContext (*)(EGLDisplay, EGLConfig, EGLContext, const EGLint*);
using MakeCurrentFn = EGLBoolean (*)(EGLDisplay, EGLSurface, EGLSurface, EGLContext);
using DestroyContextFn = EGLBoolean (*)(EGLDisplay, EGLContext);
using TerminateFn = EGLBoolean (*)(EGLDisplay);
using QueryStringFn = const char* (*)(EGLDisplay, EGLint);

GetProcAddressFn g_egl_get_proc = nullptr;

void* egl_get_proc(const char* name) {
  return g_egl_get_proc(name);
}

class EglContext : public GlContext {
 public:
  ~EglContext() override {
    if (context_) {
      make_current_(display_, nullptr, nullptr, nullptr);
      destroy_context_(display_, context_);
    }
    if (display_) terminate_(display_);
  }
  const GlApi& gl() const override { return gl_; }
  std::string description() const override { return description_; }
  bool make_current() override { return make_current_(display_, nullptr, nullptr, context_); }

  bool init(std::string* error) {
    void* library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!library) {
      *error = "EGL: libEGL.so.1 could not be loaded (install libegl1 and libegl-mesa0)";
      return false;
    }
    g_egl_get_proc = reinterpret_cast<GetProcAddressFn>(dlsym(library, "eglGetProcAddress"));
    auto query_string = reinterpret_cast<QueryStringFn>(dlsym(library, "eglQueryString"));
    auto get_display =
        reinterpret_cast<GetPlatformDisplayFn>(dlsym(library, "eglGetPlatformDisplay"));
    auto initialize = reinterpret_cast<InitializeFn>(dlsym(library, "eglInitialize"));
    auto bind_api = reinterpret_cast<BindApiFn>(dlsym(library, "eglBindAPI"));
    auto choose_config = reinterpret_cast<ChooseConfigFn>(dlsym(library, "eglChooseConfig"));
    auto create_context = reinterpret_cast<CreateContextFn>(dlsym(library, "eglCreateContext"));
    make_current_ = reinterpret_cast<MakeCurrentFn>(dlsym(library, "eglMakeCurrent"));
    destroy_context_ = reinterpret_cast<DestroyContextFn>(dlsym(library, "eglDestroyContext"));
    terminate_ = reinterpret_cast<TerminateFn>(dlsym(library, "eglTerminate"));
    if (!g_egl_get_proc || !query_string || !get_display || !initialize || !bind_api ||
        !choose_config || !create_context || !make_current_ || !destroy_context_ || !terminate_) {
      *error = "EGL: libEGL lacks EGL 1.5 entry points";
      return false;
    }
    const char* client_extensions = query_string(nullptr, EGL_EXTENSIONS);
    if (!client_extensions ||
        std::string(client_extensions).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
      *error = "EGL: no EGL_MESA_platform_surfaceless";
      return false;
    }
    display_ = get_display(EGL_PLATFORM_SURFACELESS_MESA, nullptr, nullptr);
    EGLint major = 0, minor = 0;
    if (!display_ || !initialize(display_, &major, &minor)) {
      display_ = nullptr;
      *error = "EGL: the surfaceless display could not be initialised";
      return false;
    }
    const EGLint config_attributes[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
    EGLConfig config = nullptr;
    EGLint config_count = 0;
    if (!bind_api(EGL_OPENGL_API) ||
        !choose_config(display_, config_attributes, &config, 1, &config_count) ||
        config_count < 1) {
      *error = "EGL: no desktop OpenGL config on the surfaceless display";
      return false;
    }
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    context_ = create_context(display_, config, nullptr, context_attributes);
    if (!context_ || !make_current_(display_, nullptr, nullptr, context_)) {
      *error = "EGL: no OpenGL 3.3 core context without a surface";
      return false;
    }
    if (!load_gl_api(&egl_get_proc, &gl_, error)) return false;
    description_ = std::string("EGL surfaceless: ") +
                   reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER)) + ", " +
                   reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    return true;
  }

 private:
  EGLDisplay display_ = nullptr;
  EGLContext context_ = nullptr;
  MakeCurrentFn make_current_ = nullptr;
  DestroyContextFn destroy_context_ = nullptr;
  TerminateFn terminate_ = nullptr;
  GlApi gl_;
  std::string description_;
};

}  // namespace

std::unique_ptr<GlContext> create_egl_context(std::string* error) {
  auto context = std::make_unique<EglContext>();
  if (!context->init(error)) return nullptr;
  return context;
}

}  // namespace tetlod::render
