#include "render/camera.h"

#include <algorithm>
#include <cmath>

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

Camera frame_camera(const Vec3& lo, const Vec3& hi, ViewDirection view) {
  Camera camera;
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * length(hi - lo), kMinRadius);
  Vec3 direction{1, 1, 1};
  camera.up = {0, 0, 1};
  switch (view) {
    case ViewDirection::kIso:
      direction = {1, 0.75, 0.9};
      break;
    case ViewDirection::kX:
      direction = {1, 0, 0};
      break;
    case ViewDirection::kY:
      direction = {0, 1, 0};
      break;
    case ViewDirection::kZ:
      direction = {0, 0, 1};
      camera.up = {0, 1, 0};
      break;
  }
  const double half_fov = 0.5 * camera.fov_y_degrees * kPi / 180;
  const double distance = 1.02 * radius / std::sin(half_fov);
  camera.target = center;
  camera.eye = center + normalized(direction) * distance;
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
