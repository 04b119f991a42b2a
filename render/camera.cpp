#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace tetlod::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
// A box of no size (one point) is framed as one of this radius; any model the
// readers accept (edges from 1e-60) is larger.
constexpr double kMinRadius = 1e-100;

Vec3 normalized(const Vec3& v) {
  const double l = length(v);
  return l > 0 ? v * (1.0 / l) : v;
}

void set_clip_distances(Camera* camera, const Vec3& lo, const Vec3& hi) {
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * length(hi - lo), kMinRadius);
  const double distance = length(camera->eye - center);
  camera->near_distance = std::max(distance - 1.5 * radius, 1e-3 * radius);
  camera->far_distance = distance + 1.5 * radius;
}

}  // namespace

// The direction from the target to the eye, and the world's up, of a view.
void view_axes(ViewDirection view, Vec3* direction, Vec3* up) {
  *direction = {1, 0.75, 0.9};
  *up = {0, 0, 1};
  if (view == ViewDirection::kX) *direction = {1, 0, 0};
  if (view == ViewDirection::kY) *direction = {0, 1, 0};
  if (view == ViewDirection::kZ) {
    *direction = {0, 0, 1};
    *up = {0, 1, 0};
  }
}

Camera frame_camera(const Vec3& lo, const Vec3& hi, ViewDirection view, double aspect,
                    const LegendSpace& legend) {
  Vec3 direction, up;
  view_axes(view, &direction, &up);
  return frame_camera(lo, hi, direction, up, aspect, legend);
}

namespace {

// A rectangle of the picture in normalised device coordinates ([-1, 1] each way).
struct NdcRect {
  double x0 = -1, x1 = 1, y0 = -1, y1 = 1;
  bool contains(const NdcRect& r) const {
    return r.x0 >= x0 - 1e-9 && r.x1 <= x1 + 1e-9 && r.y0 >= y0 - 1e-9 && r.y1 <= y1 + 1e-9;
  }
  bool overlaps(const NdcRect& r) const { return r.x0 < x1 && r.x1 > x0 && r.y0 < y1 && r.y1 > y0; }
};

// The camera's placement: `distance` from the box's centre along `back`, moved by
// `dx` along the screen's right and `dy` along its up (the picture moves the other way).
struct Placement {
  double distance = 0, dx = 0, dy = 0;
};

// The box [lo, hi]'s corners, or `points` (within the box) if there are any, in the
// camera's frame (right, up, towards the eye) from the box's centre: a placement's
// extent is then three subtractions and two divisions a point.
std::vector<Vec3> camera_frame(const Vec3& lo, const Vec3& hi, const Vec3& back, const Vec3& side,
                               const Vec3& screen_up, const std::vector<Vec3>& points = {}) {
  std::vector<Vec3> frame;
  const Vec3 center = 0.5 * (lo + hi);
  const auto add = [&](const Vec3& p) {
    const Vec3 v = p - center;
    frame.push_back({dot(v, side), dot(v, screen_up), dot(v, back)});
  };
  if (points.empty()) {
    for (int k = 0; k < 8; ++k)
      add(Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  } else {
    frame.reserve(points.size());
    for (const Vec3& p : points) add(p);
  }
  return frame;
}

// Frames the points of `frame` (camera_frame() of the box [lo, hi]; it must outlive the
// Framer).
class Framer {
 public:
  Framer(const std::vector<Vec3>& frame, const Vec3& lo, const Vec3& hi, double tan_half_x,
         double tan_half_y)
      : frame_(frame),
        tx_(tan_half_x),
        ty_(tan_half_y),
        min_distance_(1.25 * 0.5 * length(hi - lo)) {}

  // Where the corners (or points) are in the picture from `p`.
  NdcRect extent(const Placement& p) const {
    NdcRect r{1e300, -1e300, 1e300, -1e300};
    for (const Vec3& f : frame_) {
      const double depth = p.distance - f.z;
      const double x = (f.x - p.dx) / (depth * tx_), y = (f.y - p.dy) / (depth * ty_);
      r = {std::min(r.x0, x), std::max(r.x1, x), std::min(r.y0, y), std::max(r.y1, y)};
    }
    return r;
  }

  // From `p`, the corners brought into `target`: further away until they fit it (with
  // 2 % to spare), then moved the least way in. False if they do not fit after that.
  bool fit(const NdcRect& target, Placement* p) const {
    for (int round = 0; round < 8; ++round) {
      const NdcRect r = extent(*p);
      const double grow = std::max({(r.x1 - r.x0) / (0.98 * (target.x1 - target.x0)),
                                    (r.y1 - r.y0) / (0.98 * (target.y1 - target.y0)), 1.0});
      if (grow <= 1) break;
      p->distance *= grow;
    }
    for (const bool y : {false, true}) {
      const NdcRect r = extent(*p);
      const double low = y ? r.y0 : r.x0, high = y ? r.y1 : r.x1;
      const double floor = y ? target.y0 : target.x0, ceiling = y ? target.y1 : target.x1;
      if (low < floor) move(p, y, -1, floor + 0.005);
      if (high > ceiling) move(p, y, 1, ceiling - 0.005);
    }
    return target.contains(extent(*p));
  }

  // From `p`, nearer or further away until the corners fill `target` (94 % of its width
  // or of its height: a margin of 3 % each side), never so near that a corner is beside
  // or behind the eye (a needle seen end on would draw the camera onto its tip).
  void scale_to(const NdcRect& target, Placement* p) const {
    for (int round = 0; round < 12; ++round) {
      const NdcRect r = extent(*p);
      const double scale = std::max((r.x1 - r.x0) / (0.94 * (target.x1 - target.x0)),
                                    (r.y1 - r.y0) / (0.94 * (target.y1 - target.y0)));
      if (!(scale > 0) || std::abs(scale - 1) < 0.002) break;
      p->distance = std::max(p->distance * scale, min_distance_);
    }
  }

 private:
  // Moves the camera along the screen's right (or up, `y`) until the corners' lowest
  // (`edge` -1) or highest (1) normalised x (or y) is `goal`. Each corner's
  // falls steadily as the camera moves that way, at a rate its depth sets (a deep box's
  // near and far corners move at very different rates, so no one step size would do):
  // found by bisection, within moves that take every corner across the picture twice.
  void move(Placement* p, bool y, int edge, double goal) const {
    const double reach = 4 * p->distance * (y ? ty_ : tx_);
    double lo = (y ? p->dy : p->dx) - reach, hi = (y ? p->dy : p->dx) + reach;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      Placement q = *p;
      (y ? q.dy : q.dx) = mid;
      const NdcRect r = extent(q);
      const double a = y ? r.y0 : r.x0, b = y ? r.y1 : r.x1;
      const double at = edge < 0 ? a : b;
      (at > goal ? lo : hi) = mid;
    }
    (y ? p->dy : p->dx) = 0.5 * (lo + hi);
  }

  const std::vector<Vec3>& frame_;  // the corners or points: right, up, back of the centre
  double tx_, ty_;
  double min_distance_;  // every corner at least a quarter of the half diagonal ahead
};

}  // namespace

Camera frame_camera(const Vec3& lo, const Vec3& hi, const Vec3& direction, const Vec3& up,
                    double aspect, const LegendSpace& legend) {
  Camera camera;
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * length(hi - lo), kMinRadius);
  camera.up = up;
  const double half_fov = 0.5 * camera.fov_y_degrees * kPi / 180;
  const Vec3 back = normalized(direction);  // from the target to the eye
  const Vec3 side = normalized(cross(-1 * back, camera.up));
  const Vec3 screen_up = cross(side, -1 * back);
  Placement at{1.02 * radius / std::sin(half_fov), 0, 0};
  const double bottom = std::clamp(legend.bottom, 0.0, 0.5);
  const double key_w = std::clamp(legend.key_width, 0.0, 1.0);
  const double key_h = std::clamp(legend.key_height, 0.0, 1.0);
  if (bottom > 0 || (key_w > 0 && key_h > 0)) {
    // The half fields of projection_matrix(), which fits the smaller side.
    const double tan_half = std::tan(half_fov);
    const std::vector<Vec3> corners = camera_frame(lo, hi, back, side, screen_up);
    const Framer framer(corners, lo, hi, tan_half * std::max(aspect, 1.0),
                        tan_half / (aspect > 0 && aspect < 1 ? aspect : 1));
    // Above the colour bar.
    const NdcRect above{-1, 1, -1 + 2 * bottom, 1};
    if (!above.contains(framer.extent(at))) framer.fit(above, &at);
    // Clear of the key: below it or right of it, whichever shows the model larger.
    const NdcRect key{-1, -1 + 2 * key_w, 1 - 2 * key_h, 1};
    if (key_w > 0 && key_h > 0 && key.overlaps(framer.extent(at))) {
      Placement below = at, right = at;
      const NdcRect below_key{-1, 1, above.y0, 1 - 2 * key_h};
      const NdcRect right_of_key{-1 + 2 * key_w, 1, above.y0, 1};
      const bool below_fits = below_key.y1 - below_key.y0 > 0.2 && framer.fit(below_key, &below);
      const bool right_fits =
          right_of_key.x1 - right_of_key.x0 > 0.2 && framer.fit(right_of_key, &right);
      if (below_fits && (!right_fits || below.distance <= right.distance))
        at = below;
      else if (right_fits)
        at = right;
    }
  }
  const Vec3 shift = side * at.dx + screen_up * at.dy;
  camera.target = center + shift;
  camera.eye = center + back * at.distance + shift;
  set_clip_distances(&camera, lo, hi);
  return camera;
}

PictureFraming frame_picture(const Vec3& lo, const Vec3& hi, ViewDirection view, int width,
                             int height, const LegendSpace& legend,
                             const std::vector<Vec3>& points) {
  Vec3 direction, up;
  view_axes(view, &direction, &up);
  Camera camera;
  camera.up = up;
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * length(hi - lo), kMinRadius);
  const double tan_half = std::tan(0.5 * camera.fov_y_degrees * kPi / 180);
  const Vec3 back = normalized(direction);
  const Vec3 side = normalized(cross(-1 * back, up));
  const Vec3 screen_up = cross(side, -1 * back);
  // The camera for a scene drawn in `r`: as near as lets the corners fill it, its
  // picture shifted so that they are centred in `r` (a lens shift, not a move of the
  // camera, which would turn the view); and where they then are, in pixels.
  struct Fit {
    Placement at;
    double shift_x = 0, shift_y = 0;
    PixelRect viewport;
    double x0, y0, x1, y1;  // the corners' box in the picture, pixels from the top left
  };
  const std::vector<Vec3> frame = camera_frame(lo, hi, back, side, screen_up, points);
  const auto fit_in = [&](const PixelRect& r) {
    const double aspect = double(r.width) / r.height;
    const Framer framer(frame, lo, hi, tan_half * std::max(aspect, 1.0),
                        tan_half / std::min(aspect, 1.0));
    Fit f;
    f.at = {1.02 * radius / std::sin(std::atan(tan_half)), 0, 0};
    framer.scale_to({-1, 1, -1, 1}, &f.at);
    const NdcRect e = framer.extent(f.at);
    const double cx = 0.5 * (e.x0 + e.x1), cy = 0.5 * (e.y0 + e.y1);
    f.shift_x = cx;
    f.shift_y = cy;
    f.viewport = r;
    const double mx = r.x + 0.5 * r.width, my = r.y + 0.5 * r.height;
    f.x0 = mx + (e.x0 - cx) * r.width / 2;
    f.x1 = mx + (e.x1 - cx) * r.width / 2;
    f.y0 = my - (e.y1 - cy) * r.height / 2;
    f.y1 = my - (e.y0 - cy) * r.height / 2;
    return f;
  };
  const int bar = static_cast<int>(std::ceil(std::clamp(legend.bottom, 0.0, 0.5) * height));
  const int key_w = static_cast<int>(std::ceil(std::clamp(legend.key_width, 0.0, 1.0) * width));
  const int key_h = static_cast<int>(std::ceil(std::clamp(legend.key_height, 0.0, 1.0) * height));
  Fit chosen = fit_in({0, 0, width, std::max(1, height - bar)});
  // Clear of the key: below it or right of it, whichever shows the model larger.
  if (key_w > 0 && key_h > 0 && chosen.x0 < key_w && chosen.y0 < key_h) {
    std::vector<Fit> options;
    if (height - bar - key_h > height / 5)
      options.push_back(fit_in({0, key_h, width, height - bar - key_h}));
    if (width - key_w > width / 5)
      options.push_back(fit_in({key_w, 0, width - key_w, height - bar}));
    for (size_t i = 0; i < options.size(); ++i)
      if (i == 0 || options[i].x1 - options[i].x0 > chosen.x1 - chosen.x0) chosen = options[i];
  }
  camera.target = center;
  camera.eye = center + back * chosen.at.distance;
  camera.shift_x = chosen.shift_x;
  camera.shift_y = chosen.shift_y;
  set_clip_distances(&camera, lo, hi);
  return {camera, chosen.viewport};
}

Camera look_at_camera(const Vec3& eye, const Vec3& target, const Vec3& lo, const Vec3& hi) {
  Camera camera;
  camera.eye = eye;
  camera.target = target;
  const Vec3 forward = normalized(target - eye);
  camera.up = std::abs(forward.z) > 0.99 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  set_clip_distances(&camera, lo, hi);
  return camera;
}

Mat4 view_matrix(const Camera& camera, double scale) {
  const Vec3 f = normalized(camera.target - camera.eye) * scale;
  const Vec3 s = normalized(cross(f, camera.up)) * scale;
  const Vec3 u = normalized(cross(s, f)) * scale;
  Mat4 m{};
  m[0] = float(s.x), m[4] = float(s.y), m[8] = float(s.z);
  m[1] = float(u.x), m[5] = float(u.y), m[9] = float(u.z);
  m[2] = float(-f.x), m[6] = float(-f.y), m[10] = float(-f.z);
  m[12] = float(-dot(s, camera.eye));
  m[13] = float(-dot(u, camera.eye));
  m[14] = float(dot(f, camera.eye));
  m[15] = 1;
  return m;
}

Mat4 projection_matrix(const Camera& camera, double aspect, double scale) {
  const double f = 1.0 / std::tan(0.5 * camera.fov_y_degrees * kPi / 180);
  // Fit the smaller image side: on a tall image, narrow the vertical field.
  const double fx = aspect >= 1 ? f / aspect : f;
  const double fy = aspect >= 1 ? f : f * aspect;
  const double n = camera.near_distance * scale, d = camera.far_distance * scale;
  Mat4 m{};
  m[0] = float(fx);
  m[5] = float(fy);
  // Lens shift: x_ndc - shift_x (the clip w is -z).
  m[8] = float(camera.shift_x);
  m[9] = float(camera.shift_y);
  m[10] = float((d + n) / (n - d));
  m[11] = -1;
  m[14] = float(2 * d * n / (n - d));
  return m;
}

Ray pixel_ray(const Camera& camera, double px, double py, int width, int height) {
  const double aspect = double(width) / double(height);
  const double f = 1.0 / std::tan(0.5 * camera.fov_y_degrees * kPi / 180);
  const double fx = aspect >= 1 ? f / aspect : f;  // as projection_matrix()
  const double fy = aspect >= 1 ? f : f * aspect;
  // Normalised device coordinates, before the lens shift.
  const double x = 2 * px / width - 1 + camera.shift_x, y = 1 - 2 * py / height + camera.shift_y;
  const Vec3 forward = normalized(camera.target - camera.eye);
  const Vec3 side = normalized(cross(forward, camera.up));  // as view_matrix()
  const Vec3 up = normalized(cross(side, forward));
  return {camera.eye, normalized(forward + side * (x / fx) + up * (y / fy))};
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      float v = 0;
      for (int k = 0; k < 4; ++k) v += a[k * 4 + r] * b[c * 4 + k];
      m[c * 4 + r] = v;
    }
  return m;
}

}  // namespace tetlod::render
