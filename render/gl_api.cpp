#include "render/gl_api.h"

namespace tetlod::render {

bool load_gl_api(GetProcAddress get_proc, GlApi* api, std::string* error) {
#define TETLOD_GL_LOAD(name, type)                                       \
  api->name = reinterpret_cast<PFNGL##type##PROC>(get_proc("gl" #name)); \
  if (!api->name) {                                                      \
    *error = "the OpenGL context has no entry point gl" #name;           \
    return false;                                                        \
  }
  TETLOD_GL_FUNCTIONS(TETLOD_GL_LOAD)
#undef TETLOD_GL_LOAD
  return true;
}

}  // namespace tetlod::render
