#include "core/metrics.h"

#include <algorithm>
#include <cmath>

namespace tetlod {

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
