#include "core/metrics.h"

#include <algorithm>
#include <cmath>

namespace tetlod {

TetShape tet_shape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 ab = b - a, ac = c - a, ad = d - a, bc = c - b, bd = d - b, cd = d - c;
  TetShape s;
  s.volume = dot(ab, cross(ac, ad)) / 6.0;
  const double longest2 = std::max({squared_length(ab), squared_length(ac), squared_length(ad),
                                    squared_length(bc), squared_length(bd), squared_length(cd)});
  s.size = std::sqrt(longest2);
  s.area = 0.5 * (length(cross(ab, ac)) + length(cross(ab, ad)) + length(cross(ac, ad)) +
                  length(cross(bc, bd)));
  // Paper eq. (2): d_t = 6*sqrt(6) V_t / (s_t A_t).
  const double denominator = s.size * s.area;
  s.stretch = denominator > 0 ? 6.0 * std::sqrt(6.0) * s.volume / denominator : 0.0;
  return s;
}

}  // namespace tetlod
