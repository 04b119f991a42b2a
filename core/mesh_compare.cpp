#include "core/mesh_compare.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/adjacency.h"
#include "core/metrics.h"
#include "core/surface.h"
#include "core/triangle_grid.h"

namespace tetlod {
namespace {

// Both measured with positions less `shift` (far_shift() of the mesh compared
// against: far from the origin, a surface compared with itself moved 3.7e-8 at 1e8).
std::map<int32_t, double> volume_per_material(const TetMesh& mesh, const Vec3& shift) {
  std::map<int32_t, double> volume;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& q = mesh.tets[t];
    volume[mesh.materials[t]] +=
        signed_volume6(mesh.positions[q[0]] - shift, mesh.positions[q[1]] - shift,
                       mesh.positions[q[2]] - shift, mesh.positions[q[3]] - shift) /
        6;
  }
  return volume;
}

std::map<MaterialPair, std::vector<Triangle3>> pair_triangles(const TetMesh& mesh,
                                                              const Vec3& shift) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  std::map<MaterialPair, std::vector<Triangle3>> out;
  for (const SurfaceTriangle& s : extract_surface(mesh, neighbors)) {
    Triangle3 t;
    for (int k = 0; k < 3; ++k) t[k] = mesh.positions[s.v[k]] - shift;
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
  const Vec3 shift = far_shift(before);
  const std::map<int32_t, double> v0 = volume_per_material(before, shift);
  const std::map<int32_t, double> v1 = volume_per_material(after, shift);
  std::map<int32_t, MaterialVolumes> volumes;
  for (const auto& [m, v] : v0) volumes[m] = {m, v, 0};
  for (const auto& [m, v] : v1) {
    volumes[m].material = m;
    volumes[m].after = v;
  }
  for (const auto& [m, v] : volumes) c.volumes.push_back(v);

  const auto s0 = pair_triangles(before, shift);
  const auto s1 = pair_triangles(after, shift);
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

namespace {
// name -> material of `names`; false (with `why`) if a name is given to two materials.
bool by_name(const std::vector<MaterialName>& names, const char* which,
             std::map<std::string, int32_t>* out, std::string* why) {
  for (const MaterialName& n : names) {
    const auto [at, inserted] = out->emplace(n.name, n.material);
    if (!inserted) {
      *why = std::string(which) + " names two materials '" + n.name + "' (" +
             std::to_string(at->second) + " and " + std::to_string(n.material) + ")";
      return false;
    }
  }
  return true;
}
}  // namespace

MaterialMatch match_materials_by_name(const std::vector<MaterialName>& before_names,
                                      const TetMesh& after,
                                      const std::vector<MaterialName>& after_names) {
  MaterialMatch match;
  if (before_names.empty() || after_names.empty()) {
    match.why_by_id = before_names.empty() && after_names.empty() ? "neither file names them"
                      : before_names.empty()                      ? "BEFORE does not name them"
                                                                  : "AFTER does not name them";
    return match;
  }
  std::map<std::string, int32_t> before_ids, after_ids;
  if (!by_name(before_names, "BEFORE", &before_ids, &match.why_by_id) ||
      !by_name(after_names, "AFTER", &after_ids, &match.why_by_id))
    return match;
  std::map<int32_t, int32_t> target;  // every material of AFTER's tets -> its id in BEFORE
  for (const int32_t m : after.materials) target.emplace(m, m);
  for (auto& [m, to] : target) {
    const std::string* name = find_material_name(&after_names, m);
    if (!name) continue;
    const auto at = before_ids.find(*name);
    if (at != before_ids.end()) to = at->second;
  }
  std::map<int32_t, int32_t> source;  // BEFORE's id -> the AFTER material that takes it
  for (const auto& [m, to] : target) {
    const auto [at, inserted] = source.emplace(to, m);
    if (!inserted) {
      match.why_by_id = "AFTER's materials " + std::to_string(at->second) + " and " +
                        std::to_string(m) + " would both be " + std::to_string(to);
      return match;
    }
  }
  for (const auto& [m, to] : target)
    if (m != to) match.renumbered.emplace_back(m, to);
  return match;
}

void renumber_materials(const MaterialMatch& match, TetMesh* mesh,
                        std::vector<MaterialName>* names) {
  if (match.renumbered.empty()) return;
  const std::map<int32_t, int32_t> to(match.renumbered.begin(), match.renumbered.end());
  for (int32_t& m : mesh->materials) {
    const auto at = to.find(m);
    if (at != to.end()) m = at->second;
  }
  // A name of an id that another material takes (one without tets: a material with tets
  // would have made match_materials_by_name() keep the ids) goes.
  std::set<int32_t> taken;
  for (const auto& entry : match.renumbered) taken.insert(entry.second);
  std::vector<MaterialName> kept;
  for (const MaterialName& n : *names) {
    const auto at = to.find(n.material);
    if (at != to.end())
      kept.push_back({at->second, n.name});
    else if (!taken.count(n.material))
      kept.push_back(n);
  }
  *names = std::move(kept);
  sort_by_material(names);
}

}  // namespace tetlod
