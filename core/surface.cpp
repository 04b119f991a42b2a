#include "core/surface.h"

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

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

int64_t first_surface_tag(const TetMesh& mesh) {
  if (mesh.materials.empty()) return 1;
  std::vector<int32_t> materials = mesh.materials;
  std::sort(materials.begin(), materials.end());
  materials.erase(std::unique(materials.begin(), materials.end()), materials.end());
  int32_t largest = materials.back();
  if (materials.front() == 0) {
    int32_t zero_tag = 1;  // as write_gmsh() numbers material 0
    for (int32_t m : materials) {
      if (m == zero_tag) ++zero_tag;
    }
    largest = std::max(largest, zero_tag);
  }
  return int64_t{std::max(largest, 0)} + 1;
}

Status group_surface(const TetMesh& mesh, SurfaceGroups* groups) {
  SurfaceGroups result;
  result.surface = extract_surface(mesh, build_adjacency(mesh).tet_neighbors);
  // Key: boundaries (0, m, -1) before interfaces (1, a, b).
  std::map<std::tuple<int, int32_t, int32_t>, std::vector<uint32_t>> by_pair;
  for (uint32_t i = 0; i < result.surface.size(); ++i) {
    const SurfaceTriangle& t = result.surface[i];
    by_pair[{t.outer == kOutsideMaterial ? 0 : 1, t.inner, t.outer}].push_back(i);
  }
  const int64_t first = first_surface_tag(mesh);
  if (first + int64_t(by_pair.size()) - 1 > std::numeric_limits<int32_t>::max()) {
    return Status::error("material ids up to " + std::to_string(first - 1) +
                         " leave no room to number the " + std::to_string(by_pair.size()) +
                         " surface groups above them (tags end at 2147483647)");
  }
  int32_t tag = static_cast<int32_t>(first);
  for (auto& [key, triangles] : by_pair) {
    SurfaceGroup group;
    group.material = std::get<1>(key);
    group.other = std::get<2>(key);
    group.tag = tag++;
    group.name = group.other == kOutsideMaterial ? "boundary_" + std::to_string(group.material)
                                                 : "interface_" + std::to_string(group.material) +
                                                       "_" + std::to_string(group.other);
    group.triangles = std::move(triangles);
    result.groups.push_back(std::move(group));
  }
  *groups = std::move(result);
  return Status();
}

}  // namespace tetlod
