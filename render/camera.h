// A perspective camera looking at a target, and framing helpers.
#pragma once

#include <array>
#include <vector>

#include "core/vec3.h"

namespace tetlod::render {

struct Camera {
  Vec3 eye{0, 0, 1};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov_y_degrees = 30;
  // Near and far clip distances; set by frame_camera() from the model's size.
  double near_distance = 0.01;
  double far_distance = 100;
  // The picture moved by this much, in normalised device units (a lens shift: what is
  // at (sx, sy) is drawn at the centre), without turning the view.
  double shift_x = 0, shift_y = 0;
};

enum class ViewDirection { kIso, kX, kY, kZ };

// A rectangle of a picture in pixels, from its top left.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// Where a picture's legend goes, as fractions of its width and height
// (Renderer::legend_space()): a band at the bottom (the colour bar), a box at the top
// left (the material key).
struct LegendSpace {
  double bottom = 0;
  double key_width = 0, key_height = 0;
};

// A camera looking at the box [lo, hi] from `view` (iso: from +x,+y,+z with z up;
// x: from +x; y: from +y; z: from +z with y up), far enough that the box's bounding
// sphere fills the smaller image side. The three axis views look from the + side, the
// side an unflipped cut (surface_builder.h CutPlane with a + axis normal) removes, so
// each shows the face the cut exposes. With a `legend` in a picture `aspect` = width /
// height wide, where the box's corners would reach into its bottom band, the camera
// moves away until they fit the height above it, then down until they stand on it;
// where they would reach into its key, it does the same to keep them below the key or
// right of it, whichever shows the model larger (a view to orbit, as the viewer's).
Camera frame_camera(const Vec3& lo, const Vec3& hi, ViewDirection view, double aspect = 1,
                    const LegendSpace& legend = {});
// The same from any `direction` (from the target to the eye, not along `up`), with
// `up` the world's up.
Camera frame_camera(const Vec3& lo, const Vec3& hi, const Vec3& direction, const Vec3& up,
                    double aspect = 1, const LegendSpace& legend = {});

// A picture of its own (render, report): the camera looks at the box's centre from
// `view`, as near as lets the box's corners fill the part of a width x height picture
// clear of the `legend` (above the colour bar; below the key or right of it, whichever
// shows the model larger, where the key would cover it), its picture shifted so that the
// corners are centred there (Camera::shift_x, a lens shift: moving the camera would turn
// the view), and the scene is drawn in `scene`, that part. A flat board fills it.
// Given the `points` drawn (within the box), it frames them instead of the box's
// corners: a round model fills the picture, not its box.
struct PictureFraming {
  Camera camera;
  PixelRect scene;
};
PictureFraming frame_picture(const Vec3& lo, const Vec3& hi, ViewDirection view, int width,
                             int height, const LegendSpace& legend = {},
                             const std::vector<Vec3>& points = {});

// A camera at `eye` looking at `target` (z up, or y up when looking along z); near
// and far from the box [lo, hi]. Precondition: eye != target.
Camera look_at_camera(const Vec3& eye, const Vec3& target, const Vec3& lo, const Vec3& hi);

// The ray through pixel (px, py) of a width x height image drawn with `camera` (pixels
// from the top left; a pixel's centre is at +0.5): from the eye, `direction` of unit
// length. The inverse of projection_matrix() * view_matrix().
struct Ray {
  Vec3 origin;
  Vec3 direction;
};
Ray pixel_ray(const Camera& camera, double px, double py, int width, int height);

// Column-major 4x4 matrices for OpenGL.
using Mat4 = std::array<float, 16>;
// The view transform, its result multiplied by `scale`. The renderer passes 1 over
// the camera's distance to its target, so that view-space positions are of order 1
// at any model size (the shader's lighting squares them: in float, a model of
// 1e-9 or 1e20 units drew black faces).
Mat4 view_matrix(const Camera& camera, double scale = 1);
// The projection of a view space scaled by `scale`, as view_matrix() scales it.
Mat4 projection_matrix(const Camera& camera, double aspect, double scale = 1);
Mat4 multiply(const Mat4& a, const Mat4& b);

}  // namespace tetlod::render
