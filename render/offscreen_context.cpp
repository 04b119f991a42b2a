// Choosing the offscreen backend.
#include <cstdlib>
#include <string>

#include "render/gl_context.h"

namespace tetlod::render {

std::unique_ptr<GlContext> create_offscreen_context(std::string* error, OffscreenBackend backend) {
  if (backend == OffscreenBackend::kAuto) {
    const char* name = std::getenv("TETLOD_GL_BACKEND");
    const std::string chosen = name ? name : "";
    if (chosen == "osmesa") {
      backend = OffscreenBackend::kOsMesa;
    } else if (chosen == "egl") {
      backend = OffscreenBackend::kEgl;
    } else if (!chosen.empty()) {
      *error =
          "no offscreen OpenGL context: TETLOD_GL_BACKEND='" + chosen + "' is not osmesa or egl";
      return nullptr;
    }
  }
  std::string osmesa_error, egl_error;
  if (backend != OffscreenBackend::kEgl) {
    if (auto context = create_osmesa_context(&osmesa_error)) return context;
  }
  if (backend != OffscreenBackend::kOsMesa) {
    if (auto context = create_egl_context(&egl_error)) return context;
  }
  *error = "no offscreen OpenGL context: " + osmesa_error +
           (!osmesa_error.empty() && !egl_error.empty() ? "; " : "") + egl_error;
  return nullptr;
}

}  // namespace tetlod::render
