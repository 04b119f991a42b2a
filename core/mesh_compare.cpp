#include "core/mesh_compare.h"

#include <algorithm>
#include <array>
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

struct PairSurfaces {
  std::map<MaterialPair, std::vector<Triangle3>> triangles;  // positions less the shift
  std::map<MaterialPair, long> euler;                        // V - E + F of each
  std::map<int32_t, long> pieces;                            // of each material
};

PairSurfaces pair_surfaces(const TetMesh& mesh, const Vec3& shift) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  PairSurfaces out;
  std::map<MaterialPair, std::vector<std::pair<uint32_t, uint32_t>>> edges;
  std::map<MaterialPair, std::vector<uint32_t>> vertices;
  for (const SurfaceTriangle& s : extract_surface(mesh, neighbors)) {
    const MaterialPair pair{s.inner, s.outer};
    Triangle3 t;
    for (int k = 0; k < 3; ++k) {
      t[k] = mesh.positions[s.v[k]] - shift;
      const uint32_t a = s.v[k], b = s.v[(k + 1) % 3];
      edges[pair].push_back({std::min(a, b), std::max(a, b)});
      vertices[pair].push_back(a);
    }
    out.triangles[pair].push_back(t);
  }
  const auto distinct = [](auto* items) {
    std::sort(items->begin(), items->end());
    return static_cast<long>(std::unique(items->begin(), items->end()) - items->begin());
  };
  for (auto& [pair, list] : out.triangles)
    out.euler[pair] =
        distinct(&vertices[pair]) - distinct(&edges[pair]) + static_cast<long>(list.size());
  // Pieces: tets joined through faces of the same material.
  std::vector<uint8_t> seen(mesh.tet_count(), 0);
  std::vector<uint32_t> stack;
  for (uint32_t seed = 0; seed < mesh.tet_count(); ++seed) {
    if (seen[seed]) continue;
    ++out.pieces[mesh.materials[seed]];
    seen[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      for (int f = 0; f < 4; ++f) {
        const uint32_t o = neighbors[4 * size_t(t) + size_t(f)];
        if (o != kInvalidIndex && !seen[o] && mesh.materials[o] == mesh.materials[t]) {
          seen[o] = 1;
          stack.push_back(o);
        }
      }
    }
  }
  return out;
}

// A triangle's corners in a fixed order (sorted), to find the same triangle in another
// list.
std::array<Vec3, 3> sorted_corners(const Triangle3& t) {
  std::array<Vec3, 3> c = {t[0], t[1], t[2]};
  const auto less = [](const Vec3& a, const Vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  std::sort(c.begin(), c.end(), less);
  return c;
}

bool corners_less(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c)
      if (a[k][c] != b[k][c]) return a[k][c] < b[k][c];
  return false;
}

// The sorted_corners() of each triangle of `list`, sorted by corners_less().
std::vector<std::array<Vec3, 3>> sorted_triangles(const std::vector<Triangle3>& list) {
  std::vector<std::array<Vec3, 3>> out;
  out.reserve(list.size());
  for (const Triangle3& t : list) out.push_back(sorted_corners(t));
  std::sort(out.begin(), out.end(), corners_less);
  return out;
}

// Largest distance from the sample points of `from` to the triangles of `to`. A
// triangle of `from` that is one of `to` (`to_sorted`: their sorted_corners(), sorted)
// is at 0 and not searched: on an unchanged surface, and where a search would read
// every triangle of a cell (a fan of N triangles round one edge put N in each cell
// there, and comparing it with itself took minutes).
double one_sided(const std::vector<Triangle3>& from, const TriangleGrid& to,
                 const std::vector<std::array<Vec3, 3>>& to_sorted) {
  double worst2 = 0;
  for (const Triangle3& t : from) {
    if (std::binary_search(to_sorted.begin(), to_sorted.end(), sorted_corners(t), corners_less))
      continue;
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

  const PairSurfaces s0 = pair_surfaces(before, shift);
  const PairSurfaces s1 = pair_surfaces(after, shift);
  for (const auto& [pair, triangles] : s0.triangles) {
    const auto other = s1.triangles.find(pair);
    if (other == s1.triangles.end()) {
      c.lost.push_back(pair);
      continue;
    }
    const TriangleGrid grid0(triangles), grid1(other->second);
    c.pairs.push_back(
        {pair, std::max(one_sided(triangles, grid1, sorted_triangles(other->second)),
                        one_sided(other->second, grid0, sorted_triangles(triangles)))});
    c.euler.push_back({pair, s0.euler.at(pair), s1.euler.at(pair)});
  }
  for (const auto& entry : s1.triangles)
    if (!s0.triangles.count(entry.first)) c.added.push_back(entry.first);
  std::map<int32_t, MaterialPieces> pieces;
  for (const auto& [m, n] : s0.pieces) pieces[m] = {m, n, 0};
  for (const auto& [m, n] : s1.pieces) pieces[m] = {m, pieces[m].before, n};
  for (const auto& [m, p] : pieces) c.pieces.push_back(p);
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
    if (at != before_ids.end()) {
      to = at->second;
      ++match.by_name;
    } else {
      match.names_only_after.push_back({m, *name});
    }
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
