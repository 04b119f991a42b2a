#include "core/metrics.h"

#include <utility>

#include <algorithm>
#include <cmath>

namespace tetlod {

namespace {

// a + b + c + d, smallest first (five compare-exchanges): the same for any order.
double ordered_sum(double a, double b, double c, double d) {
  if (b < a) std::swap(a, b);
  if (d < c) std::swap(c, d);
  if (c < a) std::swap(a, c);
  if (d < b) std::swap(b, d);
  if (c < b) std::swap(b, c);
  return ((a + b) + c) + d;
}

}  // namespace

Vec3 tet_centroid(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return {ordered_sum(a.x, b.x, c.x, d.x) * 0.25, ordered_sum(a.y, b.y, c.y, d.y) * 0.25,
          ordered_sum(a.z, b.z, c.z, d.z) * 0.25};
}

TetShape tet_shape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 ab = b - a, ac = c - a, ad = d - a, bc = c - b, bd = d - b;
  TetShape s;
  s.volume = dot(ab, cross(ac, ad)) / 6.0;
  s.size = std::sqrt(tet_longest_edge2(a, b, c, d));
  s.area = 0.5 * (length(cross(ab, ac)) + length(cross(ab, ad)) + length(cross(ac, ad)) +
                  length(cross(bc, bd)));
  // Paper eq. (2): d_t = 6*sqrt(6) V_t / (s_t A_t).
  const double denominator = s.size * s.area;
  s.stretch = denominator > 0 ? 6.0 * std::sqrt(6.0) * s.volume / denominator : 0.0;
  return s;
}

}  // namespace tetlod
