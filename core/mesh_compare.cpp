#include "core/mesh_compare.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/adjacency.h"
#include "core/metrics.h"
#include "core/surface.h"
#include "core/triangle_grid.h"

namespace tetlod {
namespace {

std::map<int32_t, double> volume_per_material(const TetMesh& mesh) {
  std::map<int32_t, double> volume;
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    volume[mesh.materials[t]] += signed_volume6(mesh, mesh.tets[t]) / 6;
  return volume;
}

std::map<MaterialPair, std::vector<Triangle3>> pair_triangles(const TetMesh& mesh) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  std::map<MaterialPair, std::vector<Triangle3>> out;
  for (const SurfaceTriangle& s : extract_surface(mesh, neighbors)) {
    Triangle3 t;
    for (int k = 0; k < 3; ++k) t[k] = mesh.positions[s.v[k]];
    out[{s.inner, s.outer}].push_back(t);
  }
  return out;
}

// Largest distance from the sample points of `from` to the triangles of `to`.
double one_sided(const std::vector<Triangle3>& from, const TriangleGrid& to) {
  double worst2 = 0;
  for (const Triangle3& t : from) {
    const Vec3 samples[7] = {t[0],
                             t[1],
                             t[2],
                             (t[0] + t[1]) * 0.5,
                             (t[1] + t[2]) * 0.5,
                             (t[2] + t[0]) * 0.5,
                             (t[0] + t[1] + t[2]) * (1.0 / 3)};
    for (const Vec3& p : samples) {
      double d2 = INFINITY;
      to.nearest(p, &d2);
      worst2 = std::max(worst2, d2);
    }
  }
  return std::sqrt(worst2);
}

}  // namespace

MeshComparison compare_meshes(const TetMesh& before, const TetMesh& after) {
  MeshComparison c;
  const std::map<int32_t, double> v0 = volume_per_material(before);
  const std::map<int32_t, double> v1 = volume_per_material(after);
  std::map<int32_t, MaterialVolumes> volumes;
  for (const auto& [m, v] : v0) volumes[m] = {m, v, 0};
  for (const auto& [m, v] : v1) {
    volumes[m].material = m;
    volumes[m].after = v;
  }
  for (const auto& [m, v] : volumes) c.volumes.push_back(v);

  const auto s0 = pair_triangles(before);
  const auto s1 = pair_triangles(after);
  for (const auto& [pair, triangles] : s0) {
    const auto other = s1.find(pair);
    if (other == s1.end()) {
      c.lost.push_back(pair);
      continue;
    }
    const TriangleGrid grid0(triangles), grid1(other->second);
    c.pairs.push_back(
        {pair, std::max(one_sided(triangles, grid1), one_sided(other->second, grid0))});
  }
  for (const auto& entry : s1)
    if (!s0.count(entry.first)) c.added.push_back(entry.first);
  return c;
}

}  // namespace tetlod
