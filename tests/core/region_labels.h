// Connected material regions of a mesh, for tests (independent of the simplifier).
#pragma once

#include <cstdint>
#include <vector>

#include "core/adjacency.h"
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

}  // namespace tetlod::test
