// Hand-built meshes for the exact simplifier rule tests (test_simplify_rules.cpp).
// Every builder returns positively oriented tets; see test_meshes.h for the grid.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/test_meshes.h"
#include "core/tet_mesh.h"

namespace tetlod::test {

// Swaps the last two corners of every negatively oriented tet.
inline void orient_positively(TetMesh* mesh) {
  for (Tet& t : mesh->tets)
    if (signed_volume6(*mesh, t) < 0) std::swap(t[2], t[3]);
}

// An nx*ny*nz grid of unit cubes (one material) whose top face z = nz is bent into
// the paraboloid z = nz + bend * ((x - nx/2)^2 + (y - ny/2)^2): no two neighbouring
// top triangles are coplanar, yet they turn by far less than a 40 degree crease.
inline TetMesh make_bent_grid(int nx, int ny, int nz, double bend) {
  TetMesh mesh = make_grid_mesh(nx, ny, nz, [](int, int, int) { return 1; });
  for (Vec3& p : mesh.positions) {
    if (p.z != nz) continue;
    const double dx = p.x - 0.5 * nx, dy = p.y - 0.5 * ny;
    p.z += bend * (dx * dx + dy * dy);
  }
  return mesh;
}

// An n^3 grid of unit cubes (one material) whose interior vertices are moved by a
// fixed pseudo-random offset of up to `amplitude` per coordinate. Boundary vertices
// stay on their faces, so the boundary is the exact box [0, n]^3.
inline TetMesh make_jittered_grid(int n, double amplitude) {
  TetMesh mesh = make_grid_mesh(n, n, n, [](int, int, int) { return 1; });
  uint32_t state = 12345u;
  auto next = [&state]() {  // a small LCG: the same offsets on every platform
    state = state * 1664525u + 1013904223u;
    return (static_cast<double>(state >> 8) / 16777216.0) * 2 - 1;  // [-1, 1)
  };
  for (Vec3& p : mesh.positions) {
    const double ox = next(), oy = next(), oz = next();
    const bool interior = p.x > 0 && p.x < n && p.y > 0 && p.y < n && p.z > 0 && p.z < n;
    if (!interior) continue;
    p = p + Vec3{ox, oy, oz} * amplitude;
  }
  orient_positively(&mesh);
  return mesh;
}

// The octahedron with vertices +-e_x, +-e_y, +-e_z around a centre vertex 0 at the
// origin: 7 vertices, 8 tets (one per octant). Every outer vertex is a corner (the
// octahedron's faces meet at 109.5 degrees), so the only collapsible edges are the six
// from the centre, and by symmetry they all give the same mesh: the octahedron cut
// into 4 tets around the axis from the kept vertex to its opposite.
inline TetMesh make_centred_octahedron() {
  TetMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (uint32_t x : {1u, 2u})
    for (uint32_t y : {3u, 4u})
      for (uint32_t z : {5u, 6u}) {
        mesh.tets.push_back({0, x, y, z});
        mesh.materials.push_back(1);
      }
  orient_positively(&mesh);
  return mesh;
}

// A tube of `layers` triangular prisms stacked along z: cross-section l is the
// equilateral triangle (a_l, b_l, c_l) = vertices (3l, 3l+1, 3l+2) of circumradius
// `radius` at z = l. Each prism is cut into the three tets
// (a0 b0 c0 a1), (b0 c0 a1 b1), (c0 a1 b1 c1); every vertex lies on the boundary and
// every inner cross-section is a "neck": a triangle of three boundary edges that is
// not a boundary face.
inline TetMesh make_prism_tube(int layers, double radius) {
  TetMesh mesh;
  for (int l = 0; l <= layers; ++l)
    for (int c = 0; c < 3; ++c) {
      const double angle = 2 * M_PI * c / 3;
      mesh.positions.push_back({radius * std::cos(angle), radius * std::sin(angle), double(l)});
    }
  for (uint32_t l = 0; l < static_cast<uint32_t>(layers); ++l) {
    const uint32_t a0 = 3 * l, b0 = a0 + 1, c0 = a0 + 2, a1 = a0 + 3, b1 = a0 + 4, c1 = a0 + 5;
    for (const Tet& t : {Tet{a0, b0, c0, a1}, Tet{b0, c0, a1, b1}, Tet{c0, a1, b1, c1}}) {
      mesh.tets.push_back(t);
      mesh.materials.push_back(1);
    }
  }
  orient_positively(&mesh);
  return mesh;
}

// Three tets around the edge (x, y) = vertices (3, 4) on the z axis, with the other
// corners i, j, z = vertices (0, 1, 2) at 0, 120 and 240 degrees around it:
// (i j x y), (i x y z), (j x y z). Collapsing (i, j) would turn the last two into the
// same tet.
inline TetMesh make_three_tets_around_an_edge() {
  TetMesh mesh;
  for (int c = 0; c < 3; ++c) {
    const double angle = 2 * M_PI * c / 3;
    mesh.positions.push_back({std::cos(angle), std::sin(angle), 0});
  }
  mesh.positions.push_back({0, 0, -1});
  mesh.positions.push_back({0, 0, 1});
  mesh.tets = {{0, 1, 3, 4}, {0, 3, 4, 2}, {1, 3, 4, 2}};
  mesh.materials = {1, 1, 1};
  orient_positively(&mesh);
  return mesh;
}

// An nx*ny*nz grid of material 1 in which the unit cubes inside each box
// [lo, hi) (in cube indices) are material 2.
using CubeBox = std::pair<std::array<int, 3>, std::array<int, 3>>;
inline TetMesh make_grid_with_inclusions(int nx, int ny, int nz,
                                         const std::vector<CubeBox>& inclusions) {
  return make_grid_mesh(nx, ny, nz, [&](int i, int j, int k) {
    for (const auto& [lo, hi] : inclusions)
      if (i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2]) return 2;
    return 1;
  });
}

}  // namespace tetlod::test
