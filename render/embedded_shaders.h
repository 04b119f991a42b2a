// GLSL sources from shaders/, embedded at build time (cmake/embed_shaders.cmake).
#pragma once

namespace tetlod::render {

// The source of shaders/<name> (e.g. "surface.vert"), or null if there is none.
const char* embedded_shader(const char* name);

}  // namespace tetlod::render
