#include "core/surface.h"

namespace tetlod {

std::vector<SurfaceTriangle> extract_surface(const TetMesh& mesh,
                                             const std::vector<uint32_t>& tet_neighbors) {
  std::vector<SurfaceTriangle> triangles;
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    const int32_t material = mesh.materials[t];
    for (int i = 0; i < 4; ++i) {
      const uint32_t other = tet_neighbors[4 * t + i];
      int32_t outer;
      if (other == kInvalidIndex) {
        outer = kOutsideMaterial;
      } else if (mesh.materials[other] > material) {
        outer = mesh.materials[other];
      } else {
        continue;  // interior face, or an interface face taken from the other side
      }
      const Tet& tet = mesh.tets[t];
      const int* f = kTetFace[i];
      triangles.push_back(
          {{tet[f[0]], tet[f[1]], tet[f[2]]}, material, outer, t, static_cast<uint8_t>(i)});
    }
  }
  return triangles;
}

}  // namespace tetlod
