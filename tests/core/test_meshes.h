// Hand-built meshes for exact tests.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/tet_mesh.h"

namespace tetlod::test {

// A grid of nx*ny*nz unit cubes (scaled by `spacing`), each split into the six
// Kuhn tets around its main diagonal (conforming across cubes), positively
// oriented. `material(i, j, k)` gives the material of cube (i, j, k).
inline TetMesh make_grid_mesh(int nx, int ny, int nz,
                              const std::function<int32_t(int, int, int)>& material,
                              double spacing = 1.0) {
  TetMesh mesh;
  auto id = [&](int i, int j, int k) {
    return static_cast<uint32_t>((k * (ny + 1) + j) * (nx + 1) + i);
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.positions.push_back({i * spacing, j * spacing, k * spacing});
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          Tet t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (signed_volume6(mesh, t) < 0) std::swap(t[2], t[3]);
          mesh.tets.push_back(t);
          mesh.materials.push_back(material(i, j, k));
        }
  return mesh;
}

inline TetMesh make_single_tet() {
  TetMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.tets = {{0, 1, 2, 3}};
  mesh.materials = {1};
  return mesh;
}

// `needles` thin tets that all have their tip at the origin and point every way (at
// random, from `seed`), ten units long: they touch only there. A valid mesh whose
// boundary triangles all share the cell of the origin.
inline TetMesh make_needle_star(int needles, uint32_t seed) {
  TetMesh star;
  star.positions.push_back({0, 0, 0});
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  for (int n = 0; n < needles; ++n) {
    Vec3 axis{normal(rng), normal(rng), normal(rng)};
    axis = axis * (1 / length(axis));
    Vec3 side = std::fabs(axis.x) < 0.9 ? cross(axis, {1, 0, 0}) : cross(axis, {0, 1, 0});
    side = side * (1 / length(side));
    const Vec3 other = cross(axis, side);
    const uint32_t base = static_cast<uint32_t>(star.positions.size());
    for (int k = 0; k < 3; ++k) {
      const double angle = 2.0943951023931953 * k;  // 120 degrees
      star.positions.push_back(axis * 10 +
                               (side * std::cos(angle) + other * std::sin(angle)) * 0.01);
    }
    Tet t{0, base, base + 1, base + 2};
    if (signed_volume6(star, t) < 0) std::swap(t[2], t[3]);
    star.tets.push_back(t);
    star.materials.push_back(1);
  }
  return star;
}

// A fan: vertex 0 at the origin, joined to every triangle of a sphere of radius 1 (an
// octahedron's faces each cut into k x k triangles, pushed out to the sphere): 8 k^2
// tets, all of material 1, all sharing vertex 0, whose valence is 4 k^2 + 2.
inline TetMesh make_fan(int k) {
  TetMesh fan;
  fan.positions.push_back({0, 0, 0});
  std::map<std::array<long, 3>, uint32_t> ids;  // by the point's rounded coordinates
  const auto vertex = [&](const Vec3& p) {
    const Vec3 q = p * (1 / length(p));
    const std::array<long, 3> key{std::lround(q.x * 1e9), std::lround(q.y * 1e9),
                                  std::lround(q.z * 1e9)};
    const auto [it, added] = ids.emplace(key, static_cast<uint32_t>(fan.positions.size()));
    if (added) fan.positions.push_back(q);
    return it->second;
  };
  for (int octant = 0; octant < 8; ++octant) {
    const Vec3 x{octant & 1 ? -1.0 : 1.0, 0, 0}, y{0, octant & 2 ? -1.0 : 1.0, 0},
        z{0, 0, octant & 4 ? -1.0 : 1.0};
    // Point (i, j) of the face: i steps from x towards y, j from x towards z.
    const auto at = [&](int i, int j) {
      return vertex(x + (y - x) * (double(i) / k) + (z - x) * (double(j) / k));
    };
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        std::vector<std::array<uint32_t, 3>> triangles{{at(i, j), at(i + 1, j), at(i, j + 1)}};
        if (i + j + 1 < k) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        for (const auto& tri : triangles) {
          Tet t{0, tri[0], tri[1], tri[2]};
          if (signed_volume6(fan, t) < 0) std::swap(t[2], t[3]);
          fan.tets.push_back(t);
          fan.materials.push_back(1);
        }
      }
  }
  return fan;
}

// make_fan(k) wrapped in a second layer: each sphere vertex v gets an outer twin at 2v,
// and the prism between a sphere triangle and its twin is split into three tets by the
// vertex ids (the diagonal of each side joins the larger-id inner corner to the
// smaller-id outer one, so neighbouring prisms agree). The centre's edges (8k^2 tets
// in its star, against about 20 at a sphere vertex) are then interior, with closed
// rings: edge removals can take them.
inline TetMesh make_layered_fan(int k) {
  TetMesh ball = make_fan(k);
  const uint32_t inner = static_cast<uint32_t>(ball.positions.size());  // 0 and the sphere
  for (uint32_t v = 1; v < inner; ++v) ball.positions.push_back(ball.positions[v] * 2.0);
  const auto outer = [&](uint32_t v) { return v + inner - 1; };
  const size_t cones = ball.tets.size();
  for (size_t t = 0; t < cones; ++t) {
    std::array<uint32_t, 3> c{ball.tets[t][1], ball.tets[t][2], ball.tets[t][3]};
    std::sort(c.begin(), c.end());
    for (Tet tet : {Tet{c[0], c[1], c[2], outer(c[0])}, Tet{c[1], c[2], outer(c[0]), outer(c[1])},
                    Tet{c[2], outer(c[0]), outer(c[1]), outer(c[2])}}) {
      if (signed_volume6(ball, tet) < 0) std::swap(tet[2], tet[3]);
      ball.tets.push_back(tet);
      ball.materials.push_back(1);
    }
  }
  return ball;
}

// The number of edge neighbours of each vertex.
inline std::vector<uint32_t> valences(const TetMesh& mesh) {
  std::vector<std::set<uint32_t>> neighbors(mesh.vertex_count());
  for (const Tet& t : mesh.tets)
    for (uint32_t a : t)
      for (uint32_t b : t)
        if (a != b) neighbors[a].insert(b);
  std::vector<uint32_t> out;
  for (const auto& s : neighbors) out.push_back(static_cast<uint32_t>(s.size()));
  return out;
}

}  // namespace tetlod::test
