#include "app/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace tetlod::app {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxPitch = 89.0 * kPi / 180.0;  // keeps z-up well defined

Vec3 unit(const Vec3& v) {
  const double l = length(v);
  return l > 0 ? v * (1.0 / l) : Vec3{1, 0, 0};
}

}  // namespace

void OrbitCamera::fit(const Vec3& lo, const Vec3& hi, render::ViewDirection view, double aspect,
                      const render::LegendSpace& legend) {
  take_framing(lo, hi, render::frame_camera(lo, hi, view, aspect, legend));
}

void OrbitCamera::refit(const Vec3& lo, const Vec3& hi, double aspect,
                        const render::LegendSpace& legend) {
  const double yaw = yaw_, pitch = pitch_;
  const Vec3 direction{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                       std::sin(pitch)};
  take_framing(lo, hi, render::frame_camera(lo, hi, direction, {0, 0, 1}, aspect, legend));
  yaw_ = yaw;  // as it was, exactly
  pitch_ = pitch;
}

void OrbitCamera::take_framing(const Vec3& lo, const Vec3& hi, const render::Camera& framed) {
  lo_ = lo;
  hi_ = hi;
  target_ = framed.target;
  fov_y_degrees_ = framed.fov_y_degrees;
  const Vec3 d = framed.eye - framed.target;
  distance_ = std::max(length(d), 1e-9);
  pitch_ = std::clamp(std::asin(std::clamp(d.z / distance_, -1.0, 1.0)), -kMaxPitch, kMaxPitch);
  // Looking down z the framed camera has y up: keep the eye slightly on -y.
  yaw_ = (std::abs(d.x) + std::abs(d.y) > 1e-9 * distance_) ? std::atan2(d.y, d.x) : -kPi / 2;
  moved_ = false;
}

void OrbitCamera::include_in_depth(const Vec3& lo, const Vec3& hi) {
  lo_ = {std::min(lo_.x, lo.x), std::min(lo_.y, lo.y), std::min(lo_.z, lo.z)};
  hi_ = {std::max(hi_.x, hi.x), std::max(hi_.y, hi.y), std::max(hi_.z, hi.z)};
}

void OrbitCamera::orbit(double dx, double dy) {
  moved_ = moved_ || dx != 0 || dy != 0;
  yaw_ -= dx * 0.008;
  pitch_ = std::clamp(pitch_ + dy * 0.008, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(double dx, double dy, int viewport_height) {
  moved_ = moved_ || dx != 0 || dy != 0;
  const render::Camera c = camera();
  const Vec3 forward = unit(c.target - c.eye);
  const Vec3 right = unit(cross(forward, c.up));
  const Vec3 up = cross(right, forward);
  const double units_per_pixel =
      2 * distance_ * std::tan(fov_y_degrees_ * kPi / 360.0) / std::max(1, viewport_height);
  target_ = target_ - right * (dx * units_per_pixel) + up * (dy * units_per_pixel);
}

void OrbitCamera::zoom(double clicks) {
  moved_ = moved_ || clicks != 0;
  distance_ = std::max(distance_ * std::pow(0.88, clicks), 1e-6);
}

render::Camera OrbitCamera::camera() const {
  const Vec3 direction{std::cos(pitch_) * std::cos(yaw_), std::cos(pitch_) * std::sin(yaw_),
                       std::sin(pitch_)};
  const Vec3 eye = target_ + direction * distance_;
  // look_at_camera sets near and far from the box, enlarged so that a camera inside
  // it (zoomed in) still sees the model.
  render::Camera c = render::look_at_camera(eye, target_, lo_, hi_);
  c.fov_y_degrees = fov_y_degrees_;
  c.up = {0, 0, 1};  // pitch stays below 90 degrees
  c.near_distance = std::max(c.near_distance, 1e-3 * distance_);
  return c;
}

}  // namespace tetlod::app
