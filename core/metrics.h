// Mesh property metrics exactly as the paper defines them (Date et al., section III):
//   size     s_t = longest edge of tet t                                  (III.B)
//   stretch  d_t = 6*sqrt(6) * V_t / (s_t * A_t), A_t total face area       (eq. 2)
//            1 for a regular tet, 0 for a flat one
//   valence  number of edge neighbours of a node
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tetlod {

struct TetShape {
  double volume = 0;   // signed volume V_t
  double size = 0;     // longest edge s_t
  double area = 0;     // total face area A_t
  double stretch = 0;  // d_t; negative for an inverted tet
};

TetShape tet_shape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// validate_mesh() (every reader) refuses a tet as flat, its shape lost in rounding,
// when six times its volume is at most this much of its longest edge cubed.
constexpr double kFlatVolume6 = 1e-12;
// Whether a tet the simplifier makes reads back: its volume twice clear of that.
inline bool reads_back(const TetShape& s) {
  return 6 * std::abs(s.volume) > 2 * kFlatVolume6 * s.size * s.size * s.size;
}

// The centroid of a tet's corners, the same to the bit in whatever order they come
// (each coordinate summed smallest first): a size limit read there (sizing.h) is then
// the same wherever the tet is checked, whichever of its corners moved. (A size map's
// value outside its mesh jumps where the tet nearest changes: summed in another order,
// a candidate checked within its limit came out above it in the final count.)
// (Inline and without branches, min and max: the simplifier reads it for each lane of
// each candidate under region rules, where a call with compare-and-swap branches,
// mispredicted half the time, made the whole run 70 % slower.)
inline double ordered_sum(double a, double b, double c, double d) {
  const double ab0 = std::min(a, b), ab1 = std::max(a, b);
  const double cd0 = std::min(c, d), cd1 = std::max(c, d);
  const double lowest = std::min(ab0, cd0), second = std::max(ab0, cd0);
  const double third = std::min(ab1, cd1), highest = std::max(ab1, cd1);
  return ((lowest + std::min(second, third)) + std::max(second, third)) + highest;
}
inline Vec3 tet_centroid(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return {ordered_sum(a.x, b.x, c.x, d.x) * 0.25, ordered_sum(a.y, b.y, c.y, d.y) * 0.25,
          ordered_sum(a.z, b.z, c.z, d.z) * 0.25};
}

// The square of the longest edge: tet_shape()'s size is its square root.
inline double tet_longest_edge2(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return std::max({squared_length(b - a), squared_length(c - a), squared_length(d - a),
                   squared_length(c - b), squared_length(d - b), squared_length(d - c)});
}

inline TetShape tet_shape(const TetMesh& mesh, const Tet& t) {
  return tet_shape(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                   mesh.positions[t[3]]);
}

}  // namespace tetlod
