// A plain 3-vector of doubles for mesh geometry. Core code does not use GLM.
#pragma once

#include <algorithm>
#include <cmath>

namespace tetlod {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator*(const Vec3& a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline Vec3 operator*(double s, const Vec3& a) {
  return a * s;
}
inline bool operator==(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
inline bool operator!=(const Vec3& a, const Vec3& b) {
  return !(a == b);
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double squared_length(const Vec3& a) {
  return dot(a, a);
}
inline double length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
inline bool is_finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
// A direction given by a user, made unit length without overflow or underflow: the
// components are divided by the largest first, so (1e300, 1e300, 0) and
// (1e-200, 0, 0) are fine. (Then |a| = dot(a, unit), without overflow either.) False
// for a zero or non-finite vector.
inline bool unit_direction(const Vec3& a, Vec3* unit) {
  const double m = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
  if (!(m > 0) || !std::isfinite(m)) return false;
  const Vec3 b{a.x / m, a.y / m, a.z / m};
  *unit = b * (1 / length(b));
  return true;
}

}  // namespace tetlod
