// The offscreen backend: an OSMesa core-profile context (llvmpipe). libOSMesa is
// opened with dlopen(RTLD_LOCAL) so its gl* symbols never mix with libGL's.
#include <dlfcn.h>

#include <cstdlib>
#include <vector>

#include "render/gl_context.h"

namespace tetlod::render {
namespace {

// From GL/osmesa.h, which is not included: it pulls in GL/gl.h, which clashes with
// GL/glcorearb.h. These values are fixed by the OSMesa ABI.
struct osmesa_context;
using OSMesaContext = osmesa_context*;
using OSMESAproc = void (*)();
constexpr int OSMESA_FORMAT = 0x22;
constexpr int OSMESA_RGBA = GL_RGBA;
constexpr int OSMESA_DEPTH_BITS = 0x30;
constexpr int OSMESA_PROFILE = 0x33;
constexpr int OSMESA_CORE_PROFILE = 0x34;
constexpr int OSMESA_CONTEXT_MAJOR_VERSION = 0x36;
constexpr int OSMESA_CONTEXT_MINOR_VERSION = 0x37;

using CreateContextAttribsFn = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrentFn = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
using DestroyContextFn = void (*)(OSMesaContext);
using GetProcFn = OSMESAproc (*)(const char*);

// Only one OSMesa library handle per process; the get-proc-address trampoline
// needs it as a plain function pointer.
GetProcFn g_osmesa_get_proc = nullptr;

void* osmesa_get_proc(const char* name) {
  return reinterpret_cast<void*>(g_osmesa_get_proc(name));
}

// The default framebuffer is never drawn to (the renderer uses FBOs); it only has
// to exist for OSMesaMakeCurrent.
constexpr int kDefaultBufferSize = 16;

class OsMesaContext : public GlContext {
 public:
  ~OsMesaContext() override {
    if (context_) destroy_(context_);
  }
  const GlApi& gl() const override { return gl_; }
  std::string description() const override { return description_; }
  bool make_current() override {
    return make_current_(context_, buffer_.data(), GL_UNSIGNED_BYTE, kDefaultBufferSize,
                         kDefaultBufferSize);
  }

  bool init(std::string* error) {
    // TETLOD_OSMESA names the library to use instead of the system's.
    const char* override_path = std::getenv("TETLOD_OSMESA");
    void* library = nullptr;
    if (override_path && *override_path) {
      library = dlopen(override_path, RTLD_NOW | RTLD_LOCAL);
    } else {
      for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
        library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
        if (library) break;
      }
    }
    if (!library) {
      *error = "OSMesa: libOSMesa could not be loaded (" + std::string(dlerror()) +
               "; install libosmesa6)";
      return false;
    }
    // The library stays loaded for the life of the process: contexts may be made
    // again, and unloading Mesa's driver threads is not safe.
    auto create =
        reinterpret_cast<CreateContextAttribsFn>(dlsym(library, "OSMesaCreateContextAttribs"));
    make_current_ = reinterpret_cast<MakeCurrentFn>(dlsym(library, "OSMesaMakeCurrent"));
    destroy_ = reinterpret_cast<DestroyContextFn>(dlsym(library, "OSMesaDestroyContext"));
    g_osmesa_get_proc = reinterpret_cast<GetProcFn>(dlsym(library, "OSMesaGetProcAddress"));
    if (!create || !make_current_ || !destroy_ || !g_osmesa_get_proc) {
      *error = "OSMesa: libOSMesa lacks OSMesaCreateContextAttribs (Mesa >= 12)";
      return false;
    }
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context_ = create(attributes, nullptr);
    if (!context_) {
      *error = "OSMesa: OSMesa could not create a 3.3 core-profile context";
      return false;
    }
    buffer_.assign(kDefaultBufferSize * kDefaultBufferSize * 4, 0);
    if (!make_current()) {
      *error = "OSMesa: OSMesaMakeCurrent failed";
      return false;
    }
    if (!load_gl_api(&osmesa_get_proc, &gl_, error)) return false;
    description_ = std::string("OSMesa: ") +
                   reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER)) + ", " +
                   reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    return true;
  }

 private:
  OSMesaContext context_ = nullptr;
  MakeCurrentFn make_current_ = nullptr;
  DestroyContextFn destroy_ = nullptr;
  std::vector<unsigned char> buffer_;
  GlApi gl_;
  std::string description_;
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context(std::string* error) {
  auto context = std::make_unique<OsMesaContext>();
  if (!context->init(error)) return nullptr;
  return context;
}

}  // namespace tetlod::render
