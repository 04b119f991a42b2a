#include "core/surface.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
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

int32_t gmsh_material_zero_tag(const std::vector<int32_t>& materials) {
  int32_t tag = 1;
  for (int32_t m : materials) {
    if (m == tag) ++tag;
  }
  return tag;
}

int64_t first_surface_tag(const TetMesh& mesh) {
  if (mesh.materials.empty()) return 1;
  std::vector<int32_t> materials = mesh.materials;
  std::sort(materials.begin(), materials.end());
  materials.erase(std::unique(materials.begin(), materials.end()), materials.end());
  int32_t largest = materials.back();
  if (materials.front() == 0) largest = std::max(largest, gmsh_material_zero_tag(materials));
  return int64_t{std::max(largest, 0)} + 1;
}

namespace {

using PairKey = std::tuple<int, int32_t, int32_t>;  // boundaries (0, m, -1), interfaces (1, a, b)

PairKey pair_key(const SurfaceTriangle& t) {
  return {t.outer == kOutsideMaterial ? 0 : 1, t.inner, t.outer};
}

std::string pair_name(int32_t material, int32_t other) {
  return other == kOutsideMaterial
             ? "boundary_" + std::to_string(material)
             : "interface_" + std::to_string(material) + "_" + std::to_string(other);
}

// A triangle by its corners' coordinates, the corners sorted: the same key for any
// order or orientation.
using TriangleKey = std::array<double, 9>;
TriangleKey triangle_key(const Vec3& a, const Vec3& b, const Vec3& c) {
  std::array<std::array<double, 3>, 3> corners = {
      {{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}}};
  std::sort(corners.begin(), corners.end());
  TriangleKey key;
  for (int k = 0; k < 9; ++k) key[size_t(k)] = corners[size_t(k / 3)][size_t(k % 3)];
  return key;
}

}  // namespace

Status group_surface(const TetMesh& mesh, SurfaceGroups* groups,
                     const std::vector<SurfaceGroupName>* names) {
  SurfaceGroups result;
  result.surface = extract_surface(mesh, build_adjacency(mesh).tet_neighbors);
  std::map<PairKey, std::vector<uint32_t>> by_pair;
  for (uint32_t i = 0; i < result.surface.size(); ++i)
    by_pair[pair_key(result.surface[i])].push_back(i);
  std::map<std::pair<int32_t, int32_t>, const SurfaceGroupName*> named;
  std::set<int32_t> used_tags;
  if (names) {
    for (const SurfaceGroupName& n : *names) {
      named[{n.material, n.other}] = &n;
      used_tags.insert(n.tag);
    }
  }
  const int64_t first = first_surface_tag(mesh);
  int64_t tag = first;
  for (auto& [key, triangles] : by_pair) {
    SurfaceGroup group;
    group.material = std::get<1>(key);
    group.other = std::get<2>(key);
    group.name = pair_name(group.material, group.other);
    const auto it = named.find({group.material, group.other});
    if (it != named.end()) {
      group.tag = it->second->tag;
      if (!it->second->name.empty()) group.name = it->second->name;
    } else {
      while (tag <= std::numeric_limits<int32_t>::max() && used_tags.count(int32_t(tag))) ++tag;
      if (tag > std::numeric_limits<int32_t>::max()) {
        return Status::error("material ids up to " + std::to_string(first - 1) +
                             " leave no room to number the " + std::to_string(by_pair.size()) +
                             " surface groups above them (tags end at 2147483647)");
      }
      group.tag = static_cast<int32_t>(tag++);
    }
    group.triangles = std::move(triangles);
    result.groups.push_back(std::move(group));
  }
  *groups = std::move(result);
  return Status();
}

std::vector<SurfaceGroupName> match_surface_groups(
    const TetMesh& mesh, const std::vector<InputSurfaceGroup>& input,
    std::vector<const InputSurfaceGroup*>* unmatched) {
  // The pairs as group_surface() groups them (its tags are not used); if it cannot
  // number them, no write can, and no group is matched.
  SurfaceGroups groups;
  if (!group_surface(mesh, &groups).ok()) {
    if (unmatched)
      for (const InputSurfaceGroup& group : input) unmatched->push_back(&group);
    return {};
  }
  std::map<TriangleKey, size_t> pair_of;  // surface triangle -> its group
  for (size_t g = 0; g < groups.groups.size(); ++g) {
    for (uint32_t i : groups.groups[g].triangles) {
      const auto& v = groups.surface[i].v;
      const auto& p = mesh.positions;
      pair_of[triangle_key(p[v[0]], p[v[1]], p[v[2]])] = g;
    }
  }
  std::vector<SurfaceGroupName> names;
  std::vector<bool> taken(groups.groups.size(), false);
  for (const InputSurfaceGroup& group : input) {
    std::set<TriangleKey> seen;
    size_t pair = SIZE_MAX;
    bool one_pair = !group.triangles.empty();
    for (const auto& t : group.triangles) {
      const TriangleKey key = triangle_key(t[0], t[1], t[2]);
      const auto it = pair_of.find(key);
      if (it == pair_of.end() || (pair != SIZE_MAX && it->second != pair)) {
        one_pair = false;
        break;
      }
      pair = it->second;
      seen.insert(key);
    }
    if (one_pair && seen.size() == groups.groups[pair].triangles.size() && !taken[pair] &&
        group.tag >= 1) {
      taken[pair] = true;
      names.push_back(
          {groups.groups[pair].material, groups.groups[pair].other, group.tag, group.name});
    } else if (unmatched) {
      unmatched->push_back(&group);
    }
  }
  return names;
}

}  // namespace tetlod
