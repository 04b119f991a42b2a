#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <utility>

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

Camera frame_camera(const Vec3& lo, const Vec3& hi, ViewDirection view, double aspect,
                    double bottom_band) {
  Vec3 direction{1, 0.75, 0.9};
  Vec3 up{0, 0, 1};
  if (view == ViewDirection::kX) direction = {1, 0, 0};
  if (view == ViewDirection::kY) direction = {0, 1, 0};
  if (view == ViewDirection::kZ) {
    direction = {0, 0, 1};
    up = {0, 1, 0};
  }
  return frame_camera(lo, hi, direction, up, aspect, bottom_band);
}

Camera frame_camera(const Vec3& lo, const Vec3& hi, const Vec3& direction, const Vec3& up,
                    double aspect, double bottom_band) {
  Camera camera;
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * length(hi - lo), kMinRadius);
  camera.up = up;
  const double half_fov = 0.5 * camera.fov_y_degrees * kPi / 180;
  double distance = 1.02 * radius / std::sin(half_fov);
  const Vec3 back = normalized(direction);  // from the target to the eye
  const Vec3 side = normalized(cross(-1 * back, camera.up));
  const Vec3 screen_up = cross(side, -1 * back);
  double shift = 0;  // the eye and the target moved down by this much
  const double band = std::clamp(bottom_band, 0.0, 0.5);
  if (band > 0) {
    // The box's corners from a camera `d` from the centre and `h` below it: the lowest
    // and highest in normalised device y (the image's height is [-1, 1]; the vertical
    // half field is the smaller side's, as in projection_matrix()).
    const double tan_half_y = std::tan(half_fov) / (aspect > 0 && aspect < 1 ? aspect : 1);
    const auto extent = [&](double d, double h) {
      const Vec3 eye = center + back * d - screen_up * h;
      double y_lo = 1e300, y_hi = -1e300;
      for (int k = 0; k < 8; ++k) {
        const Vec3 v = Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z} - eye;
        const double y = dot(v, screen_up) / (-dot(v, back) * tan_half_y);
        y_lo = std::min(y_lo, y);
        y_hi = std::max(y_hi, y);
      }
      return std::pair{y_lo, y_hi};
    };
    // The picture above the band is [floor, 1]. Where the box's corners reach below
    // it, further away until they fit its height (with 2 % to spare), then up until
    // the lowest stands on it: a few rounds, as perspective makes neither exact.
    const double floor = -1 + 2 * band;
    if (extent(distance, 0).first < floor) {
      for (int round = 0; round < 8; ++round) {
        const auto [y_lo, y_hi] = extent(distance, 0);
        const double room = 0.98 * (1 - floor);
        if (y_hi - y_lo <= room) break;
        distance *= (y_hi - y_lo) / room;
      }
      for (int round = 0; round < 8; ++round) {
        const double y_lo = extent(distance, shift).first;
        if (y_lo >= floor && y_lo <= floor + 0.01) break;
        shift += (floor + 0.005 - y_lo) * distance * tan_half_y;
      }
    }
  }
  camera.target = center - screen_up * shift;
  camera.eye = center + back * distance - screen_up * shift;
  set_clip_distances(&camera, lo, hi);
  return camera;
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
  const double x = 2 * px / width - 1, y = 1 - 2 * py / height;  // normalised device
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
