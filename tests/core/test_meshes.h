// Hand-built meshes for exact tests.
#pragma once

#include <array>
#include <functional>
#include <utility>

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

}  // namespace tetlod::test
