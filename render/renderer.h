// Draws SurfaceBuffers with OpenGL 3.3 core into a framebuffer object of any size
// (4x multisampled, resolved), which is read back for PNG export or blitted to a
// window, so the screen, reports and snapshot tests see the same pixels.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/colormap.h"
#include "render/gl_api.h"
#include "render/group_overlay.h"
#include "render/image.h"
#include "render/surface_builder.h"

namespace tetlod::render {

// kStretch, kField and kSize map the per-vertex scalar through the colour map between
// range_min and range_max; they differ in the legend's title ("stretch"; "|E|", the
// field magnitude of an electrostatic solve, core/electrostatics.h; "size", the tet's
// longest edge, in model units).
enum class ColorMode { kStretch, kMaterial, kField, kSize };

// How to draw (no rebuild of the buffers needed to change any of these).
struct DrawSettings {
  ColorMode color_mode = ColorMode::kStretch;
  ColorMap color_map = ColorMap::kViridis;
  double range_min = 0;  // scalar (stretch or |E|) at the low end of the colour map
  double range_max = 1;  // and at the high end
  // Field mode: range_max is this percentile of |E| (100: its maximum); the legend
  // says so below 100, as higher values take the top colour.
  double field_percentile = 100;
  bool wireframe = false;
  bool legend = true;
  Rgb background = {1, 1, 1};
  double highlight_below = 0;  // only for the legend label; the buffers hold the tets
  // The picture's resolution against the size it is shown at (the viewer draws at 0.5
  // while the view moves, then scales up): the legend keeps its size on screen.
  float resolution = 1;
};

class Renderer {
 public:
  // `gl` must belong to the context current on this thread and outlive the renderer.
  explicit Renderer(const GlApi& gl);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Compiles the embedded shaders and makes the colour-map textures. False with a
  // message (a shader log) on failure.
  bool init(std::string* error);

  // Replaces the GPU buffers with `buffers` (a full rebuild).
  void upload(const SurfaceBuffers& buffers);
  // Incremental updates (LodSurface): `vertices` is the whole current array, `dirty`
  // the vertex ranges that changed since the last update; only those are sent unless
  // the array outgrew the GPU buffer.
  void update_triangles(const std::vector<SurfaceVertex>& vertices,
                        const std::vector<DirtyRange>& dirty);
  void update_highlight(const std::vector<SurfaceVertex>& vertices,
                        const std::vector<DirtyRange>& dirty, size_t highlighted_tets);

  // The input's surface groups drawn over the surface, each in its colour, opaque where
  // in front and see-through where hidden (as the highlight), and listed in the key.
  // Kept until set again; an empty overlay draws none.
  void set_groups(const GroupOverlay& overlay);

  // The materials the legend lists in material mode. upload() sets them from its
  // buffers; after incremental updates (LodSurface) the caller sets them.
  void set_legend_materials(std::vector<int32_t> materials) {
    visible_materials_ = std::move(materials);
  }
  // Names for the legend's materials, sorted by id ("3 shield" instead of "material
  // 3"); materials not listed keep their number. Kept until set again.
  void set_material_names(std::vector<MaterialName> names) { material_names_ = std::move(names); }

  // Draws the uploaded surface (and highlight, and legend) at width x height. False
  // (see last_error()) if the framebuffer cannot be made or GL reports an error. The
  // surface is drawn in `scene` if given (pixels from the top left; it may reach past
  // the picture, which clips it), with its aspect; the legend in the whole picture.
  bool draw(const DrawSettings& settings, const Camera& camera, int width, int height,
            const PixelRect* scene = nullptr);
  const std::string& last_error() const { return last_error_; }
  // The last drawn frame, top row first.
  Image read_pixels();
  // Copies the last drawn frame into the default framebuffer (a window).
  void present(int framebuffer_width, int framebuffer_height);
  // Copies it, scaled, into the rectangle [x, x + width) x [y, y + height) of the
  // default framebuffer (pixels, origin bottom left): the viewer's 3D view beside
  // its panels.
  void present_into(int x, int y, int width, int height);

  size_t triangle_count() const { return triangle_vertices_ / 3; }
  // Whether the point (fx, fy) of the last drawn frame, as fractions of its width and
  // height from its top left, lies on the legend (the colour bar or the key): the
  // viewer names no tet under it.
  bool over_legend(double fx, double fy) const;

  // Where the legend draw() would draw at width x height goes, as fractions of the
  // picture (with the materials and highlight last set): frame_camera() keeps the model
  // clear of it. Parts that do not fit a small picture are left out (the colour bar
  // where its numbers would overlap; the key where 8 characters of its names would not
  // fit in half the width), here and in the picture.
  LegendSpace legend_space(const DrawSettings& settings, int width, int height) const;

 private:
  struct KeyLayout {
    struct Line {
      Rgb color;
      std::string text;
      bool striped = false;  // a surface group's swatch
    };
    std::vector<Line> lines;  // none: no key
    float text_width = 0;     // in pixels
  };
  KeyLayout key_layout(const DrawSettings& settings, int width, int height) const;
  bool bar_fits(const DrawSettings& settings, int width, int height) const;
  struct LegendBox {
    float x0, y0, x1, y1;  // fractions of the frame, from its top left
  };
  std::vector<LegendBox> legend_boxes_;  // of the last frame drawn
  bool ensure_targets(int width, int height);
  void release_targets();
  void draw_legend(const DrawSettings& settings, int width, int height);
  // Draws vertices [first, first + count) of `vao` in `color`, with their edges or (if
  // `stripe` > 0) in stripes that many pixels wide, opaque where in front of the
  // surface, then at 45 % where behind it.
  void draw_see_through(GLuint vao, size_t first, size_t count, const Rgb& color, float stripe);
  // Writes vertices[dirty] into `vbo`, growing it (and sending everything) if needed.
  void update_buffer(GLuint vbo, size_t* capacity, const std::vector<SurfaceVertex>& vertices,
                     const std::vector<DirtyRange>& dirty);

  const GlApi& gl_;
  GLuint surface_program_ = 0, overlay_program_ = 0;
  GLuint surface_vao_ = 0, surface_vbo_ = 0, highlight_vao_ = 0, highlight_vbo_ = 0;
  GLuint overlay_vao_ = 0, overlay_vbo_ = 0;
  GLuint groups_vao_ = 0, groups_vbo_ = 0;
  struct GroupRange {
    size_t first, count;
    Rgb color;
    std::string label;
  };
  std::vector<GroupRange> groups_;  // set_groups()'s, in the key's order
  GLuint colormap_textures_[2] = {0, 0};
  GLuint msaa_fbo_ = 0, msaa_color_ = 0, msaa_depth_ = 0, resolve_fbo_ = 0, resolve_color_ = 0;
  int target_width_ = 0, target_height_ = 0;
  size_t triangle_vertices_ = 0, highlight_vertices_ = 0, highlighted_tets_ = 0;
  size_t triangle_capacity_ = 0, highlight_capacity_ = 0;  // in vertices
  std::vector<int32_t> visible_materials_;
  std::vector<MaterialName> material_names_;  // sorted by id
  std::string last_error_;
};

}  // namespace tetlod::render
