#include "core/refine.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace tetlod {

TetMesh refine_uniform(const TetMesh& mesh) {
  // Edge list: (low, high, tet * 6 + local edge), sorted, gives one midpoint per edge.
  struct EdgeRef {
    uint32_t low, high;
    size_t slot;
  };
  std::vector<EdgeRef> edges;
  edges.reserve(mesh.tet_count() * 6);
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    for (int e = 0; e < 6; ++e) {
      uint32_t a = mesh.tets[t][kTetEdge[e][0]], b = mesh.tets[t][kTetEdge[e][1]];
      if (a > b) std::swap(a, b);
      edges.push_back({a, b, t * 6 + e});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const EdgeRef& x, const EdgeRef& y) {
    return x.low != y.low ? x.low < y.low : (x.high != y.high ? x.high < y.high : x.slot < y.slot);
  });
  TetMesh out;
  out.positions = mesh.positions;
  std::vector<uint32_t> midpoint(mesh.tet_count() * 6);
  for (size_t i = 0; i < edges.size(); ++i) {
    if (i == 0 || edges[i].low != edges[i - 1].low || edges[i].high != edges[i - 1].high) {
      const Vec3& a = mesh.positions[edges[i].low];
      const Vec3& b = mesh.positions[edges[i].high];
      out.positions.push_back((a + b) * 0.5);
    }
    midpoint[edges[i].slot] = static_cast<uint32_t>(out.positions.size() - 1);
  }
  out.tets.reserve(mesh.tet_count() * 8);
  out.materials.reserve(mesh.tet_count() * 8);
  auto add = [&](Tet tet, int32_t material) {
    if (signed_volume6(out, tet) < 0) std::swap(tet[2], tet[3]);
    out.tets.push_back(tet);
    out.materials.push_back(material);
  };
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& v = mesh.tets[t];
    const int32_t material = mesh.materials[t];
    // m[i][j]: midpoint of edge (i, j).
    uint32_t m[4][4] = {};
    for (int e = 0; e < 6; ++e) {
      const int i = kTetEdge[e][0], j = kTetEdge[e][1];
      m[i][j] = m[j][i] = midpoint[t * 6 + e];
    }
    for (int corner = 0; corner < 4; ++corner) {
      Tet tet;
      for (int k = 0; k < 4; ++k) tet[k] = k == corner ? v[corner] : m[corner][k];
      add(tet, material);
    }
    // The octahedron's three diagonals join midpoints of opposite edges.
    const int diagonals[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};
    int best = 0;
    double best_length = 0;
    for (int d = 0; d < 3; ++d) {
      const auto& g = diagonals[d];
      const double l = squared_length(out.positions[m[g[0]][g[1]]] - out.positions[m[g[2]][g[3]]]);
      if (d == 0 || l < best_length) {
        best = d;
        best_length = l;
      }
    }
    // The diagonal (p, q) and the four other midpoints, in cyclic order around it.
    const auto& g = diagonals[best];
    const uint32_t p = m[g[0]][g[1]], q = m[g[2]][g[3]];
    const uint32_t ring[4] = {m[g[0]][g[2]], m[g[2]][g[1]], m[g[1]][g[3]], m[g[3]][g[0]]};
    for (int k = 0; k < 4; ++k) add({p, q, ring[k], ring[(k + 1) % 4]}, material);
  }
  assert(out.tets.size() == mesh.tet_count() * 8);
  return out;
}

}  // namespace tetlod
