#include "core/triangle_cross.h"

#include <algorithm>
#include <cmath>

namespace tetlod {
namespace {

// Whether triangle t has corners clearly on both sides of plane `p`: more than
// `delta` away on each. A triangle that does not cannot cross p's triangle.
bool straddles(const Triangle3& t, const TrianglePlane& p, double delta, double* distance) {
  bool above = false, below = false;
  for (int k = 0; k < 3; ++k) {
    distance[k] = dot(p.normal, t[k]) - p.offset;
    above |= distance[k] > delta;
    below |= distance[k] < -delta;
  }
  return above && below;
}

// Whether edge k of triangle `t` (its corners' distances from the plane of `s` in
// `distance`) clearly passes through the inside of s: its ends more than `delta` from
// the plane on either side, and the point where it crosses the plane more than
// `delta` inside each edge of s.
bool edge_pierces(const Triangle3& t, const double* distance, int k, const Triangle3& s,
                  const TrianglePlane& plane, double delta) {
  const double dp = distance[k], dq = distance[(k + 1) % 3];
  if (!((dp > delta && dq < -delta) || (dp < -delta && dq > delta))) return false;
  const Vec3 x = t[k] + (t[(k + 1) % 3] - t[k]) * (dp / (dp - dq));
  for (int e = 0; e < 3; ++e) {
    const Vec3 edge = s[(e + 1) % 3] - s[e];
    // The distance from x to the edge's line, in the plane, positive inside.
    if (!(dot(cross(edge, x - s[e]), plane.normal) > delta * length(edge))) return false;
  }
  return true;
}

}  // namespace

TrianglePlane plane_of(const Triangle3& t) {
  TrianglePlane p;
  const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double length2 = length(n);
  p.normal = length2 > 0 ? n * (1 / length2) : Vec3{};
  p.offset = dot(p.normal, t[0]);
  double longest2 = 0, far = 0;
  for (int k = 0; k < 3; ++k) {
    longest2 = std::max(longest2, squared_length(t[(k + 1) % 3] - t[k]));
    far = std::max({far, std::fabs(t[k].x), std::fabs(t[k].y), std::fabs(t[k].z)});
  }
  p.delta = 1e-8 * std::sqrt(longest2) + 1e-13 * far;
  return p;
}

bool triangles_cross(const Triangle3& s, const TrianglePlane& ps, const Triangle3& t,
                     const TrianglePlane& pt) {
  const double delta = std::max(ps.delta, pt.delta);
  double from_s[3], from_t[3];  // t's corners from the plane of s, and s's from t's
  if (!straddles(t, ps, delta, from_s) || !straddles(s, pt, delta, from_t)) return false;
  for (int k = 0; k < 3; ++k) {
    if (edge_pierces(t, from_s, k, s, ps, delta)) return true;
    if (edge_pierces(s, from_t, k, t, pt, delta)) return true;
  }
  return false;
}

}  // namespace tetlod
