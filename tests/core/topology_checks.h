// Topology checks for tests, independent of the simplifier: connected material
// regions and the Euler characteristic of each interface.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "core/adjacency.h"
#include "core/surface.h"
#include "core/tet_mesh.h"

namespace tetlod::test {

// Connected regions per material (tets joined through shared faces), labelled per tet.
inline std::vector<int> region_labels(const TetMesh& mesh, int* region_count) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  std::vector<int> label(mesh.tet_count(), -1);
  int count = 0;
  std::vector<uint32_t> stack;
  for (uint32_t seed = 0; seed < mesh.tet_count(); ++seed) {
    if (label[seed] >= 0) continue;
    label[seed] = count;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      for (int f = 0; f < 4; ++f) {
        const uint32_t o = neighbors[4 * t + f];
        if (o != kInvalidIndex && label[o] < 0 && mesh.materials[o] == mesh.materials[t]) {
          label[o] = count;
          stack.push_back(o);
        }
      }
    }
    ++count;
  }
  *region_count = count;
  return label;
}

// Euler characteristic V - E + F of the surface of each material pair.
inline std::map<std::pair<int32_t, int32_t>, long> interface_euler(const TetMesh& mesh) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  std::map<std::pair<int32_t, int32_t>, std::set<uint32_t>> vertices;
  std::map<std::pair<int32_t, int32_t>, std::set<std::pair<uint32_t, uint32_t>>> edges;
  std::map<std::pair<int32_t, int32_t>, long> faces;
  for (const SurfaceTriangle& s : extract_surface(mesh, neighbors)) {
    const auto key = std::make_pair(s.inner, s.outer);
    ++faces[key];
    for (int k = 0; k < 3; ++k) {
      vertices[key].insert(s.v[k]);
      const uint32_t a = s.v[k], b = s.v[(k + 1) % 3];
      edges[key].insert({std::min(a, b), std::max(a, b)});
    }
  }
  std::map<std::pair<int32_t, int32_t>, long> chi;
  for (const auto& [key, f] : faces) {
    chi[key] = static_cast<long>(vertices[key].size()) - static_cast<long>(edges[key].size()) + f;
  }
  return chi;
}

}  // namespace tetlod::test
