// A current OpenGL 3.3+ core context from one of two backends: offscreen (OSMesa,
// software, needs no display and no GPU) or a window (GLFW). The renderer only
// sees the GlApi the context loads, so the backends are interchangeable; EGL
// surfaceless is the natural successor of OSMesa (Mesa 25.1 removed OSMesa).
#pragma once

#include <memory>
#include <string>

#include "render/gl_api.h"

namespace tetlod::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  // Entry points of this context; valid while the context lives and is current.
  virtual const GlApi& gl() const = 0;
  // Makes this context current on the calling thread again (after another was).
  virtual bool make_current() = 0;
  // Human-readable "backend: GL_RENDERER, GL_VERSION".
  virtual std::string description() const = 0;
};

enum class OffscreenBackend {
  kAuto,    // TETLOD_GL_BACKEND (osmesa or egl) if set, else OSMesa, then EGL
  kOsMesa,  // OSMesa core profile (Mesa <= 25.0)
  kEgl,     // EGL, Mesa's surfaceless platform
};

// An offscreen core-profile context with no display and no GPU needed (both
// libraries are loaded at run time with dlopen, so a missing one is an error
// message, not a start-up failure). The renderer draws into its own framebuffer
// objects of any size. Null with `error` set ("no offscreen OpenGL context: ...",
// with each backend's reason) if no context can be made.
std::unique_ptr<GlContext> create_offscreen_context(
    std::string* error, OffscreenBackend backend = OffscreenBackend::kAuto);
// The backends themselves; `error` gets the reason on failure.
std::unique_ptr<GlContext> create_osmesa_context(std::string* error);
std::unique_ptr<GlContext> create_egl_context(std::string* error);

// A GLFW window with a core-profile context, current on the calling thread.
class WindowContext : public GlContext {
 public:
  // Null with `error` set if GLFW cannot open a display or a 3.3 core context.
  static std::unique_ptr<WindowContext> create(int width, int height, const std::string& title,
                                               bool visible, std::string* error);
  // The GLFWwindow*, for input handling by the caller.
  virtual void* native_window() const = 0;
  virtual bool should_close() const = 0;
  virtual void swap_buffers() = 0;
  virtual void poll_events() = 0;
  // Size of the default framebuffer in pixels.
  virtual void framebuffer_size(int* width, int* height) const = 0;
};

}  // namespace tetlod::render
