#include "render/renderer.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "render/embedded_shaders.h"
#include "render/image.h"

namespace tetlod::render {
namespace {

constexpr int kSamples = 4;

bool compile(const GlApi& gl, GLenum type, const char* name, GLuint* shader, std::string* error) {
  const char* source = embedded_shader(name);
  if (!source) {
    *error = std::string("shader ") + name + " is not embedded";
    return false;
  }
  *shader = gl.CreateShader(type);
  gl.ShaderSource(*shader, 1, &source, nullptr);
  gl.CompileShader(*shader);
  GLint ok = 0;
  gl.GetShaderiv(*shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(*shader, sizeof log, nullptr, log);
    *error = std::string("shader ") + name + ": " + log;
    return false;
  }
  return true;
}

bool link(const GlApi& gl, const char* vertex, const char* fragment, GLuint* program,
          std::string* error) {
  GLuint vs = 0, fs = 0;
  const bool compiled = compile(gl, GL_VERTEX_SHADER, vertex, &vs, error) &&
                        compile(gl, GL_FRAGMENT_SHADER, fragment, &fs, error);
  if (compiled) {
    *program = gl.CreateProgram();
    gl.AttachShader(*program, vs);
    gl.AttachShader(*program, fs);
    gl.LinkProgram(*program);
  }
  if (vs) gl.DeleteShader(vs);
  if (fs) gl.DeleteShader(fs);
  if (!compiled) return false;
  GLint ok = 0;
  gl.GetProgramiv(*program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(*program, sizeof log, nullptr, log);
    *error = std::string("linking ") + vertex + " + " + fragment + ": " + log;
    return false;
  }
  return true;
}

void setup_surface_vao(const GlApi& gl, GLuint vao, GLuint vbo) {
  gl.BindVertexArray(vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
  const auto stride = static_cast<GLsizei>(sizeof(SurfaceVertex));
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride,
                         reinterpret_cast<const void*>(offsetof(SurfaceVertex, position)));
  gl.EnableVertexAttribArray(1);
  gl.VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride,
                         reinterpret_cast<const void*>(offsetof(SurfaceVertex, stretch)));
  gl.EnableVertexAttribArray(2);
  gl.VertexAttribIPointer(2, 1, GL_UNSIGNED_INT, stride,
                          reinterpret_cast<const void*>(offsetof(SurfaceVertex, material)));
  gl.BindVertexArray(0);
}

// One overlay vertex: pixel position, colour, colour-map coordinate (or -1).
struct OverlayVertex {
  float x, y;
  float r, g, b, a;
  float ramp;
};

void add_rect(std::vector<OverlayVertex>* out, float x0, float y0, float x1, float y1, const Rgb& c,
              float ramp0 = -1, float ramp1 = -1) {
  const OverlayVertex v00{x0, y0, c[0], c[1], c[2], 1, ramp0};
  const OverlayVertex v10{x1, y0, c[0], c[1], c[2], 1, ramp1};
  const OverlayVertex v01{x0, y1, c[0], c[1], c[2], 1, ramp0};
  const OverlayVertex v11{x1, y1, c[0], c[1], c[2], 1, ramp1};
  out->insert(out->end(), {v00, v10, v11, v00, v11, v01});
}

// Text through stb_easy_font quads, `scale` pixels per font pixel.
void add_text(std::vector<OverlayVertex>* out, float x, float y, const std::string& text,
              const Rgb& c, float scale) {
  struct FontVertex {
    float x, y, z;
    unsigned char color[4];
  };
  std::vector<FontVertex> quads(text.size() * 300 / 4 + 4);
  std::string copy = text;
  const int count = stb_easy_font_print(0, 0, copy.data(), nullptr, quads.data(),
                                        static_cast<int>(quads.size() * sizeof(FontVertex)));
  for (int q = 0; q < count; ++q) {
    const FontVertex* v = &quads[size_t(q) * 4];
    add_rect(out, x + v[0].x * scale, y + v[0].y * scale, x + v[2].x * scale, y + v[2].y * scale,
             c);
  }
}

float text_pixels(const std::string& text, float scale) {
  std::string copy = text;
  return static_cast<float>(stb_easy_font_width(copy.data())) * scale;
}

// A colour bar's end: two decimals for values from 0.01 to 10^5 (stretch, sizes in
// mm), else three significant digits ("7.07e-04" for a size in metres, not "0.00").
std::string format_value(double v) {
  char buffer[32];
  const double magnitude = std::abs(v);
  std::snprintf(buffer, sizeof buffer,
                magnitude == 0 || (magnitude >= 0.01 && magnitude < 1e5) ? "%.2f" : "%.2e", v);
  return buffer;
}

}  // namespace

Renderer::Renderer(const GlApi& gl) : gl_(gl) {}

Renderer::~Renderer() {
  release_targets();
  const GLuint buffers[] = {surface_vbo_, highlight_vbo_, overlay_vbo_, groups_vbo_};
  gl_.DeleteBuffers(4, buffers);
  const GLuint arrays[] = {surface_vao_, highlight_vao_, overlay_vao_, groups_vao_};
  gl_.DeleteVertexArrays(4, arrays);
  gl_.DeleteTextures(2, colormap_textures_);
  if (surface_program_) gl_.DeleteProgram(surface_program_);
  if (overlay_program_) gl_.DeleteProgram(overlay_program_);
}

bool Renderer::init(std::string* error) {
  if (!link(gl_, "surface.vert", "surface.frag", &surface_program_, error)) return false;
  if (!link(gl_, "overlay.vert", "overlay.frag", &overlay_program_, error)) return false;
  gl_.GenVertexArrays(1, &surface_vao_);
  gl_.GenVertexArrays(1, &highlight_vao_);
  gl_.GenVertexArrays(1, &overlay_vao_);
  gl_.GenVertexArrays(1, &groups_vao_);
  gl_.GenBuffers(1, &surface_vbo_);
  gl_.GenBuffers(1, &highlight_vbo_);
  gl_.GenBuffers(1, &overlay_vbo_);
  gl_.GenBuffers(1, &groups_vbo_);
  setup_surface_vao(gl_, surface_vao_, surface_vbo_);
  setup_surface_vao(gl_, highlight_vao_, highlight_vbo_);
  setup_surface_vao(gl_, groups_vao_, groups_vbo_);
  gl_.BindVertexArray(overlay_vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, overlay_vbo_);
  const auto stride = static_cast<GLsizei>(sizeof(OverlayVertex));
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
  gl_.EnableVertexAttribArray(1);
  gl_.VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(OverlayVertex, r)));
  gl_.EnableVertexAttribArray(2);
  gl_.VertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offsetof(OverlayVertex, ramp)));
  gl_.BindVertexArray(0);

  gl_.GenTextures(2, colormap_textures_);
  for (int m = 0; m < 2; ++m) {
    uint8_t texels[256 * 3];
    for (int i = 0; i < 256; ++i) {
      const Rgb c = colormap_rgb(m == 0 ? ColorMap::kViridis : ColorMap::kTurbo, i / 255.0);
      for (int k = 0; k < 3; ++k) texels[i * 3 + k] = static_cast<uint8_t>(c[k] * 255 + 0.5f);
    }
    gl_.BindTexture(GL_TEXTURE_2D, colormap_textures_[m]);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, 256, 1, 0, GL_RGB, GL_UNSIGNED_BYTE, texels);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  const GLenum status = gl_.GetError();
  if (status != GL_NO_ERROR) {
    *error = "OpenGL error " + std::to_string(status) + " while setting up the renderer";
    return false;
  }
  return true;
}

void Renderer::upload(const SurfaceBuffers& buffers) {
  gl_.BindBuffer(GL_ARRAY_BUFFER, surface_vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(buffers.triangles.size() * sizeof(SurfaceVertex)),
                 buffers.triangles.data(), GL_STATIC_DRAW);
  gl_.BindBuffer(GL_ARRAY_BUFFER, highlight_vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(buffers.highlight.size() * sizeof(SurfaceVertex)),
                 buffers.highlight.data(), GL_STATIC_DRAW);
  gl_.BindBuffer(GL_ARRAY_BUFFER, 0);
  triangle_vertices_ = triangle_capacity_ = buffers.triangles.size();
  highlight_vertices_ = highlight_capacity_ = buffers.highlight.size();
  highlighted_tets_ = buffers.highlighted_tets;
  visible_materials_ = buffers.visible_materials;
}

void Renderer::set_groups(const GroupOverlay& overlay) {
  gl_.BindBuffer(GL_ARRAY_BUFFER, groups_vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(overlay.vertices.size() * sizeof(SurfaceVertex)),
                 overlay.vertices.data(), GL_DYNAMIC_DRAW);
  gl_.BindBuffer(GL_ARRAY_BUFFER, 0);
  groups_.clear();
  for (const GroupOverlay::Group& g : overlay.groups)
    groups_.push_back({g.first, g.count, g.color, g.label});
}

void Renderer::update_buffer(GLuint vbo, size_t* capacity,
                             const std::vector<SurfaceVertex>& vertices,
                             const std::vector<DirtyRange>& dirty) {
  constexpr size_t kVertexBytes = sizeof(SurfaceVertex);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo);
  if (vertices.size() > *capacity) {
    // Grow with room to spare, so that a sequence of LOD steps rarely reallocates.
    *capacity = vertices.size() + vertices.size() / 2 + 3 * 1024;
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(*capacity * kVertexBytes), nullptr,
                   GL_DYNAMIC_DRAW);
    gl_.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(vertices.size() * kVertexBytes),
                      vertices.data());
  } else {
    for (const DirtyRange& range : dirty) {
      const size_t end = std::min(range.end, vertices.size());
      if (range.begin >= end) continue;
      gl_.BufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(range.begin * kVertexBytes),
                        static_cast<GLsizeiptr>((end - range.begin) * kVertexBytes),
                        vertices.data() + range.begin);
    }
  }
  gl_.BindBuffer(GL_ARRAY_BUFFER, 0);
}

void Renderer::update_triangles(const std::vector<SurfaceVertex>& vertices,
                                const std::vector<DirtyRange>& dirty) {
  update_buffer(surface_vbo_, &triangle_capacity_, vertices, dirty);
  triangle_vertices_ = vertices.size();
}

void Renderer::update_highlight(const std::vector<SurfaceVertex>& vertices,
                                const std::vector<DirtyRange>& dirty, size_t highlighted_tets) {
  update_buffer(highlight_vbo_, &highlight_capacity_, vertices, dirty);
  highlight_vertices_ = vertices.size();
  highlighted_tets_ = highlighted_tets;
}

void Renderer::release_targets() {
  const GLuint framebuffers[] = {msaa_fbo_, resolve_fbo_};
  gl_.DeleteFramebuffers(2, framebuffers);
  const GLuint renderbuffers[] = {msaa_color_, msaa_depth_, resolve_color_};
  gl_.DeleteRenderbuffers(3, renderbuffers);
  msaa_fbo_ = resolve_fbo_ = msaa_color_ = msaa_depth_ = resolve_color_ = 0;
  target_width_ = target_height_ = 0;
}

bool Renderer::ensure_targets(int width, int height) {
  if (width == target_width_ && height == target_height_ && msaa_fbo_) return true;
  release_targets();
  while (gl_.GetError() != GL_NO_ERROR) {
  }
  gl_.GenRenderbuffers(1, &msaa_color_);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, msaa_color_);
  gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, kSamples, GL_RGBA8, width, height);
  gl_.GenRenderbuffers(1, &msaa_depth_);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, msaa_depth_);
  gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, kSamples, GL_DEPTH_COMPONENT24, width,
                                     height);
  gl_.GenFramebuffers(1, &msaa_fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color_);
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_);
  gl_.GenRenderbuffers(1, &resolve_color_);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, resolve_color_);
  gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl_.GenFramebuffers(1, &resolve_fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              resolve_color_);
  const GLenum resolve_status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
  const GLenum msaa_status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLenum gl_error = gl_.GetError();
  if (resolve_status != GL_FRAMEBUFFER_COMPLETE || msaa_status != GL_FRAMEBUFFER_COMPLETE ||
      gl_error != GL_NO_ERROR) {
    release_targets();
    last_error_ = "cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                  " framebuffer (OpenGL error " + std::to_string(gl_error) + ")";
    return false;
  }
  target_width_ = width;
  target_height_ = height;
  return true;
}

void Renderer::draw_see_through(GLuint vao, size_t first, size_t count, const Rgb& color,
                                float stripe) {
  const GLuint p = surface_program_;
  gl_.Uniform1i(gl_.GetUniformLocation(p, "u_color_mode"), stripe > 0 ? 3 : 2);
  gl_.Uniform1f(gl_.GetUniformLocation(p, "u_stripe"), stripe);
  gl_.Uniform3f(gl_.GetUniformLocation(p, "u_solid_color"), color[0], color[1], color[2]);
  gl_.Uniform1i(gl_.GetUniformLocation(p, "u_wireframe"), stripe > 0 ? 0 : 1);
  gl_.Uniform1f(gl_.GetUniformLocation(p, "u_alpha"), 1);
  gl_.BindVertexArray(vao);
  gl_.DepthFunc(GL_LEQUAL);
  gl_.DrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(count));
  gl_.Enable(GL_BLEND);
  // Blend colour only: the frame stays opaque (alpha 1) for PNG export.
  gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  gl_.DepthMask(GL_FALSE);
  gl_.DepthFunc(GL_GREATER);
  gl_.Uniform1f(gl_.GetUniformLocation(p, "u_alpha"), 0.45f);
  gl_.DrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(count));
  gl_.DepthMask(GL_TRUE);
  gl_.DepthFunc(GL_LESS);
  gl_.Disable(GL_BLEND);
}

bool Renderer::draw(const DrawSettings& settings, const Camera& camera, int width, int height,
                    const PixelRect* scene) {
  if (!ensure_targets(width, height)) return false;
  gl_.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
  gl_.Viewport(0, 0, width, height);
  gl_.ClearColor(settings.background[0], settings.background[1], settings.background[2], 1);
  gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.DepthMask(GL_TRUE);
  gl_.Disable(GL_BLEND);
  gl_.Disable(GL_CULL_FACE);

  // View space in units of the camera's distance to its target (camera.h).
  const double distance = length(camera.target - camera.eye);
  const double scale = distance > 0 && std::isfinite(1 / distance) ? 1 / distance : 1;
  const Mat4 view = view_matrix(camera, scale);
  const PixelRect rect = scene ? *scene : PixelRect{0, 0, width, height};
  gl_.Viewport(rect.x, height - rect.y - rect.height, std::max(rect.width, 1),
               std::max(rect.height, 1));
  const Mat4 view_projection = multiply(
      projection_matrix(camera, double(std::max(rect.width, 1)) / std::max(rect.height, 1), scale),
      view);
  const GLuint p = surface_program_;
  gl_.UseProgram(p);
  gl_.UniformMatrix4fv(gl_.GetUniformLocation(p, "u_view"), 1, GL_FALSE, view.data());
  gl_.UniformMatrix4fv(gl_.GetUniformLocation(p, "u_view_projection"), 1, GL_FALSE,
                       view_projection.data());
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, colormap_textures_[settings.color_map == ColorMap::kTurbo]);
  gl_.Uniform1i(gl_.GetUniformLocation(p, "u_colormap"), 0);
  const double span =
      settings.range_max > settings.range_min ? settings.range_max - settings.range_min : 1e-9;
  gl_.Uniform2f(gl_.GetUniformLocation(p, "u_range"), float(settings.range_min),
                float(settings.range_min + span));
  float palette[kColorCycle * 3];
  for (int i = 0; i < kColorCycle; ++i) {
    const Rgb c = material_rgb(i);
    for (int k = 0; k < 3; ++k) palette[i * 3 + k] = c[k];
  }
  gl_.Uniform3fv(gl_.GetUniformLocation(p, "u_palette"), kColorCycle, palette);
  gl_.Uniform3f(gl_.GetUniformLocation(p, "u_wire_color"), 0.1f, 0.1f, 0.12f);

  // The surface.
  gl_.Uniform1i(gl_.GetUniformLocation(p, "u_color_mode"),
                settings.color_mode == ColorMode::kMaterial ? 1 : 0);
  gl_.Uniform1f(gl_.GetUniformLocation(p, "u_alpha"), 1);
  gl_.Uniform1i(gl_.GetUniformLocation(p, "u_wireframe"), settings.wireframe ? 1 : 0);
  gl_.BindVertexArray(surface_vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangle_vertices_));

  // Highlighted tets, then the surface groups: opaque where in front, see-through where
  // hidden behind the surface, so that they can be found from outside.
  if (highlight_vertices_ > 0)
    draw_see_through(highlight_vao_, 0, highlight_vertices_, kHighlightRgb, 0);
  // Stripes 4 pixels wide on the screen, whatever the resolution drawn at.
  const float stripe = std::max(1.0f, 4 * settings.resolution);
  for (const GroupRange& g : groups_)
    if (g.count > 0) draw_see_through(groups_vao_, g.first, g.count, g.color, stripe);
  gl_.BindVertexArray(0);

  gl_.Viewport(0, 0, width, height);
  legend_boxes_.clear();
  if (settings.legend) draw_legend(settings, width, height);

  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  gl_.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLenum error = gl_.GetError();
  if (error != GL_NO_ERROR) {
    last_error_ = "OpenGL error " + std::to_string(error) + " while drawing";
    return false;
  }
  return true;
}

namespace {

// The legend's pixels per font pixel: it grows with pictures above 320 pixels.
float legend_scale(const DrawSettings& settings, int width, int height) {
  const float resolution = settings.resolution > 0 ? settings.resolution : 1.0f;
  return resolution * std::max(1.0f, float(std::min(width, height)) / resolution / 320.0f);
}

// The legend's measures, in font pixels.
constexpr float kLegendMargin = 6, kLegendLine = 11, kLegendPad = 3, kLegendBar = 8;

// The height the colour bar's panel takes at the bottom, with one more margin above it
// (which keeps the model clear of it), in pixels.
float bar_band_pixels(float scale) {
  return (2 * kLegendMargin + kLegendLine + kLegendBar + kLegendPad) * scale + 2;
}

}  // namespace

bool Renderer::bar_fits(const DrawSettings& settings, int width, int height) const {
  if (!settings.legend || settings.color_mode == ColorMode::kMaterial || height <= 0) return false;
  // Its two numbers side by side under a bar half the picture wide, in at most a
  // third of its height (a 64-pixel picture's numbers ran into each other).
  const float scale = legend_scale(settings, width, height);
  const float numbers = text_pixels(format_value(settings.range_min), scale) +
                        text_pixels(format_value(settings.range_max), scale) + 6 * scale;
  return numbers <= 0.5f * float(width) && bar_band_pixels(scale) <= float(height) / 3;
}

Renderer::KeyLayout Renderer::key_layout(const DrawSettings& settings, int width,
                                         int height) const {
  KeyLayout key;
  if (!settings.legend) return key;
  const float scale = legend_scale(settings, width, height);
  const float margin = kLegendMargin * scale, line = kLegendLine * scale;
  const bool highlight = highlight_vertices_ > 0 || settings.highlight_below > 0;
  const size_t materials =
      settings.color_mode == ColorMode::kMaterial ? visible_materials_.size() : 0;
  // As many lines as fit in 60 % of the height (a mesh can have thousands of materials);
  // the last says how many more there are.
  const float room = 0.6f * float(height) - 2 * margin - 8 * scale;
  const size_t fit = room < 0 ? 0 : std::min<size_t>(40, size_t(room / line) + 1);
  // Materials, then the surface groups drawn, then the highlight's line. Where they do
  // not all fit, the longer list gives way a line at a time, each cut list ending in
  // "and N more ..." (the groups' key had vanished past 16, taking the materials' with
  // it); the highlight's line always stays.
  const size_t groups = groups_.size(), high = highlight ? 1 : 0;
  size_t shown = materials, shown_groups = groups;
  const auto lines = [&] {
    return shown + (shown < materials) + shown_groups + (shown_groups < groups) + high;
  };
  while (lines() > fit && (shown > 0 || shown_groups > 0)) {
    if (shown >= shown_groups && shown > 0)
      --shown;
    else
      --shown_groups;
  }
  // (A list cut to nothing but its "and N more" line leaves the key out.)
  if (fit == 0 || lines() > fit || (materials > 0 && shown == 0) ||
      (groups > 0 && shown_groups == 0))
    return key;
  // The fixed lines (the "and N more" lines, the highlight's count) in 90 % of the
  // width, else no key; the names cut to fit half the width (at most 40 characters; at
  // least 8, else no key).
  const KeyLayout::Line more_materials{
      Rgb{1, 1, 1}, "and " + std::to_string(materials - shown) + " more materials"};
  const KeyLayout::Line more_groups{
      Rgb{1, 1, 1}, "and " + std::to_string(groups - shown_groups) + " more surface groups"};
  const KeyLayout::Line high_line{kHighlightRgb, "stretch < " +
                                                     format_value(settings.highlight_below) + ": " +
                                                     std::to_string(highlighted_tets_) + " tets"};
  float fixed_w = 0;
  if (shown < materials) fixed_w = std::max(fixed_w, text_pixels(more_materials.text, scale));
  if (shown_groups < groups) fixed_w = std::max(fixed_w, text_pixels(more_groups.text, scale));
  if (highlight) fixed_w = std::max(fixed_w, text_pixels(high_line.text, scale));
  if (fixed_w > 0.9f * float(width) - 11 * scale - 2 * margin) return key;
  const float text_room = 0.5f * float(width) - 11 * scale - margin;
  for (size_t chars = 40; chars >= 8; chars -= 4) {
    key.lines.clear();
    float names_w = 0;
    for (size_t i = 0; i < shown; ++i) {
      const int32_t m = visible_materials_[i];
      const std::string* name = find_material_name(&material_names_, m);
      std::string text = name ? std::to_string(m) + " " + ascii_label(*name, chars)  // the font's
                              : "material " + std::to_string(m);                     // glyphs
      names_w = std::max(names_w, text_pixels(text, scale));
      key.lines.push_back({material_rgb(m), std::move(text)});
    }
    if (shown < materials) key.lines.push_back(more_materials);
    for (size_t g = 0; g < shown_groups; ++g) {
      std::string text = ascii_label(groups_[g].label, chars);
      names_w = std::max(names_w, text_pixels(text, scale));
      key.lines.push_back({groups_[g].color, std::move(text), true});
    }
    if (shown_groups < groups) key.lines.push_back(more_groups);
    if (names_w <= text_room) {
      if (highlight) key.lines.push_back(high_line);
      key.text_width = std::max(names_w, fixed_w);
      return key;
    }
  }
  key.lines.clear();
  return key;
}

LegendSpace Renderer::legend_space(const DrawSettings& settings, int width, int height) const {
  LegendSpace space;
  if (width <= 0 || height <= 0) return space;
  const float scale = legend_scale(settings, width, height);
  const float margin = kLegendMargin * scale;
  // Each with one more margin, which keeps the model clear of it.
  if (bar_fits(settings, width, height)) space.bottom = bar_band_pixels(scale) / float(height);
  const KeyLayout key = key_layout(settings, width, height);
  if (!key.lines.empty()) {
    space.key_width =
        (2 * margin + 11 * scale + key.text_width + kLegendPad * scale + 1) / float(width);
    space.key_height = (2 * margin + float(key.lines.size() - 1) * kLegendLine * scale + 8 * scale +
                        kLegendPad * scale + 1) /
                       float(height);
  }
  return space;
}

void Renderer::draw_legend(const DrawSettings& settings, int width, int height) {
  std::vector<OverlayVertex> v;
  const float scale = legend_scale(settings, width, height);
  const float margin = kLegendMargin * scale;
  const float line = kLegendLine * scale;
  const float pad = kLegendPad * scale;
  const float text_height = 8 * scale;  // stb_easy_font's glyphs, descenders included
  const Rgb ink = {0.12f, 0.12f, 0.14f};
  // Each part of the legend sits on a white panel with a grey border, so that it reads
  // where it overlaps the model.
  const auto add_panel = [&](float x0, float y0, float x1, float y1) {
    legend_boxes_.push_back({(x0 - pad - 1) / float(width), (y0 - pad - 1) / float(height),
                             (x1 + pad + 1) / float(width), (y1 + pad + 1) / float(height)});
    add_rect(&v, x0 - pad - 1, y0 - pad - 1, x1 + pad + 1, y1 + pad + 1, {0.7f, 0.7f, 0.72f});
    add_rect(&v, x0 - pad, y0 - pad, x1 + pad, y1 + pad, {1, 1, 1});
  };
  if (bar_fits(settings, width, height)) {
    // A horizontal colour bar at the bottom with the range at its ends.
    const float bar_w = 0.5f * float(width), bar_h = kLegendBar * scale;
    const float x0 = 0.25f * float(width);
    const float y1 = float(height) - margin - line;
    const float y0 = y1 - bar_h;
    add_panel(x0 - 1, y0 - 1, x0 + bar_w + 1, y1 + 3 * scale + text_height);
    add_rect(&v, x0 - 1, y0 - 1, x0 + bar_w + 1, y1 + 1, ink);
    add_rect(&v, x0, y0, x0 + bar_w, y1, ink, 0, 1);
    const std::string lo = format_value(settings.range_min);
    const std::string hi = format_value(settings.range_max);
    add_text(&v, x0, y1 + 3 * scale, lo, ink, scale);
    add_text(&v, x0 + bar_w - text_pixels(hi, scale), y1 + 3 * scale, hi, ink, scale);
    // The longest title that fits between the two numbers, if any.
    const float room =
        bar_w - 2 * (std::max(text_pixels(lo, scale), text_pixels(hi, scale)) + 3 * scale);
    std::vector<std::string> titles;
    if (settings.color_mode == ColorMode::kField && settings.field_percentile < 100) {
      for (const char* format : {"|E| (to its %gth percentile)", "|E| (%gth pctl.)", "|E| p%g"}) {
        char text[64];
        std::snprintf(text, sizeof text, format, settings.field_percentile);
        titles.push_back(text);
      }
    } else {
      titles.push_back(settings.color_mode == ColorMode::kField  ? "|E|"
                       : settings.color_mode == ColorMode::kSize ? "size"
                                                                 : "stretch");
    }
    for (const std::string& title : titles) {
      if (text_pixels(title, scale) > room) continue;
      add_text(&v, x0 + 0.5f * (bar_w - text_pixels(title, scale)), y1 + 3 * scale, title, ink,
               scale);
      break;
    }
  }
  // The key at the top left: a swatch and a name per line.
  const KeyLayout key = key_layout(settings, width, height);
  if (!key.lines.empty()) {
    add_panel(margin, margin, margin + 11 * scale + key.text_width,
              margin + float(key.lines.size() - 1) * line + 8 * scale);
    float y = margin;
    for (const KeyLayout::Line& l : key.lines) {
      add_rect(&v, margin, y, margin + 8 * scale, y + 8 * scale, l.color);
      if (l.striped)  // white bands, as the group's faces have
        for (float x = 2; x < 8; x += 4)
          add_rect(&v, margin + x * scale, y, margin + (x + 2) * scale, y + 8 * scale, {1, 1, 1});
      add_text(&v, margin + 11 * scale, y + 1 * scale, l.text, ink, scale);
      y += line;
    }
  }
  if (v.empty()) return;
  gl_.Disable(GL_DEPTH_TEST);
  gl_.UseProgram(overlay_program_);
  gl_.Uniform2f(gl_.GetUniformLocation(overlay_program_, "u_viewport"), float(width),
                float(height));
  gl_.Uniform1i(gl_.GetUniformLocation(overlay_program_, "u_colormap"), 0);
  gl_.BindVertexArray(overlay_vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, overlay_vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(OverlayVertex)),
                 v.data(), GL_STREAM_DRAW);
  gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
  gl_.BindVertexArray(0);
  gl_.Enable(GL_DEPTH_TEST);
}

bool Renderer::over_legend(double fx, double fy) const {
  return std::any_of(legend_boxes_.begin(), legend_boxes_.end(), [&](const LegendBox& b) {
    return fx >= b.x0 && fx <= b.x1 && fy >= b.y0 && fy <= b.y1;
  });
}

Image Renderer::read_pixels() {
  if (!resolve_fbo_) return {};
  Image image(target_width_, target_height_);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<uint8_t> bottom_up(image.rgba.size());
  gl_.ReadPixels(0, 0, target_width_, target_height_, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  const size_t row = size_t(target_width_) * 4;
  for (int y = 0; y < target_height_; ++y)
    std::copy_n(bottom_up.data() + size_t(target_height_ - 1 - y) * row, row,
                image.rgba.data() + size_t(y) * row);
  return image;
}

void Renderer::present(int framebuffer_width, int framebuffer_height) {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl_.BlitFramebuffer(0, 0, target_width_, target_height_, 0, 0, framebuffer_width,
                      framebuffer_height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::present_into(int x, int y, int width, int height) {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl_.BlitFramebuffer(0, 0, target_width_, target_height_, x, y, x + width, y + height,
                      GL_COLOR_BUFFER_BIT, GL_LINEAR);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tetlod::render
