#include "core/surface.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
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

std::vector<SurfaceEdgeUse> surface_edge_uses(const std::vector<SurfaceTriangle>& surface) {
  std::vector<SurfaceEdgeUse> uses;
  uses.reserve(3 * surface.size());
  for (uint32_t k = 0; k < surface.size(); ++k) {
    const auto& v = surface[k].v;
    for (int e = 0; e < 3; ++e) {
      const uint32_t p = v[e], q = v[(e + 1) % 3];
      uses.push_back({std::min(p, q), std::max(p, q), k});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const SurfaceEdgeUse& x, const SurfaceEdgeUse& y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.triangle < y.triangle);
  });
  return uses;
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

// The face neighbours of a valid mesh's tets (build_face_neighbors()), without the
// vertex -> tets lists build_adjacency() makes too.
std::vector<uint32_t> face_neighbors(const TetMesh& mesh) {
  std::vector<uint32_t> neighbors;
  const FaceProblem problem = build_face_neighbors(mesh, &neighbors);
  assert(problem.kind == FaceProblem::Kind::kNone);
  (void)problem;
  return neighbors;
}

// `given` (a caller's face neighbours of `mesh`), or else those built into `built`.
const std::vector<uint32_t>& given_or_built(const TetMesh& mesh, const std::vector<uint32_t>* given,
                                            std::vector<uint32_t>* built) {
  if (given) return *given;
  *built = face_neighbors(mesh);
  return *built;
}

// A hash of a key's coordinates (-0 as 0, so that equal keys hash alike).
uint64_t corner_hash(const TriangleKey& key) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (double x : key) {
    uint64_t bits;
    const double value = x + 0.0;
    std::memcpy(&bits, &value, sizeof bits);
    h = (h ^ bits) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

// A triangle given by its corners' positions, found as a face of a mesh between two
// tets of one material: its corners (the mesh's vertices, in the given order), that
// material, and the tet on its back side with the corner opposite it.
struct InnerFace {
  bool found = false;
  std::array<uint32_t, 3> v{};
  int32_t material = 0;
  uint32_t tet = kInvalidIndex;
  uint8_t corner = 0;
};

bool position_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}

// Each triangle of `triangles` as an inner face of `mesh` (a valid mesh), if it is one.
// Only the faces whose corners are all at positions of the triangles are listed, by
// the hash of their corners' positions; each distinct triangle is looked up once, so
// that the work stays near linear whatever the input (vertices at one position
// included).
std::vector<InnerFace> find_inner_faces(const TetMesh& mesh,
                                        const std::vector<std::array<Vec3, 3>>& triangles) {
  std::vector<InnerFace> found(triangles.size());
  if (triangles.empty()) return found;
  const auto& p = mesh.positions;
  std::vector<Vec3> wanted;
  wanted.reserve(3 * triangles.size());
  for (const auto& t : triangles) wanted.insert(wanted.end(), t.begin(), t.end());
  std::sort(wanted.begin(), wanted.end(), position_less);
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  std::vector<uint8_t> at_wanted(mesh.vertex_count());
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v)
    at_wanted[v] = std::binary_search(wanted.begin(), wanted.end(), p[v], position_less);
  // Those faces, each side apart: the two sides of one face are next to each other.
  struct Side {
    uint64_t hash;
    std::array<uint32_t, 3> ids;  // sorted
    uint32_t tet;
    uint8_t corner;
  };
  std::vector<Side> sides;
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    for (int i = 0; i < 4; ++i) {
      const int* f = kTetFace[i];
      std::array<uint32_t, 3> ids = {tet[f[0]], tet[f[1]], tet[f[2]]};
      if (!(at_wanted[ids[0]] && at_wanted[ids[1]] && at_wanted[ids[2]])) continue;
      std::sort(ids.begin(), ids.end());
      sides.push_back(
          {corner_hash(triangle_key(p[ids[0]], p[ids[1]], p[ids[2]])), ids, t, uint8_t(i)});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return std::tie(x.hash, x.ids, x.tet) < std::tie(y.hash, y.ids, y.tet);
  });
  // The triangles by key, so that one key is looked up once: (hash, triangle).
  std::vector<std::pair<uint64_t, uint32_t>> order(triangles.size());
  std::vector<TriangleKey> keys(triangles.size());
  for (uint32_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    keys[i] = triangle_key(t[0], t[1], t[2]);
    order[i] = {corner_hash(keys[i]), i};
  }
  std::sort(order.begin(), order.end(), [&](const auto& x, const auto& y) {
    return std::tie(x.first, keys[x.second]) < std::tie(y.first, keys[y.second]);
  });
  const size_t kNoPair = sides.size();
  size_t pair = kNoPair;  // the first side of the current key's inner face
  for (size_t n = 0; n < order.size(); ++n) {
    const uint32_t i = order[n].second;
    if (n == 0 || order[n].first != order[n - 1].first || keys[i] != keys[order[n - 1].second]) {
      pair = kNoPair;
      size_t k = size_t(std::lower_bound(sides.begin(), sides.end(), order[n].first,
                                         [](const Side& x, uint64_t h) { return x.hash < h; }) -
                        sides.begin());
      for (; k + 1 < sides.size() && sides[k].hash == order[n].first; ++k) {
        const Side &x = sides[k], &y = sides[k + 1];
        if (x.ids == y.ids && mesh.materials[x.tet] == mesh.materials[y.tet] &&
            triangle_key(p[x.ids[0]], p[x.ids[1]], p[x.ids[2]]) == keys[i]) {
          pair = k;
          break;
        }
      }
    }
    if (pair == kNoPair) continue;
    // The corners in the triangle's order, and the side behind it.
    const Side* two = &sides[pair];
    std::array<uint32_t, 3> v = two->ids;
    for (int c = 0; c < 3; ++c)
      for (uint32_t id : two->ids)
        if (p[id] == triangles[i][size_t(c)]) v[size_t(c)] = id;
    const Vec3 normal = cross(p[v[1]] - p[v[0]], p[v[2]] - p[v[0]]);
    const Side& back =
        dot(normal, p[mesh.tets[two[0].tet][two[0].corner]] - p[v[0]]) < 0 ? two[0] : two[1];
    found[i] = {true, v, mesh.materials[back.tet], back.tet, back.corner};
  }
  return found;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> inside_faces(const TetMesh& mesh,
                                                  const SurfacePatches& patches) {
  std::vector<std::array<Vec3, 3>> corners;
  for (const SurfacePatches::Entry& e : patches.inside_entries()) corners.push_back(e.p);
  std::vector<std::array<uint32_t, 3>> faces;
  for (const InnerFace& f : find_inner_faces(mesh, corners))
    if (f.found) faces.push_back(f.v);
  return faces;
}

Status group_surface(const TetMesh& mesh, SurfaceGroups* groups) {
  return group_surface(mesh, groups, SurfacePatches());
}

SurfacePatches::SurfacePatches(const TetMesh& input, const std::vector<InputSurfaceGroup>& groups,
                               const std::vector<uint32_t>* neighbors) {
  std::vector<uint32_t> built;
  const std::vector<SurfaceTriangle> surface =
      extract_surface(input, given_or_built(input, neighbors, &built));
  const auto& p = input.positions;
  entries_.reserve(surface.size());
  for (const SurfaceTriangle& t : surface)
    entries_.push_back({{p[t.v[0]], p[t.v[1]], p[t.v[2]]}, t.inner, t.outer, kNone});
  build_index();
  // A triangle in several groups goes to the smallest ("x0" rather than "all outer"),
  // so that both are written; the first in the input's order among equals.
  groups_.resize(groups.size());
  std::vector<uint32_t> order(groups.size());
  for (uint32_t g = 0; g < order.size(); ++g) order[g] = g;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return groups[a].triangles.size() < groups[b].triangles.size();
  });
  // The triangles not on the surface, in that order, with their group.
  std::vector<std::array<Vec3, 3>> off_surface;
  std::vector<uint32_t> off_group;
  for (const uint32_t id : order) {
    const InputSurfaceGroup& g = groups[id];
    Group& group = groups_[id];
    group.tag = g.tag;
    group.name = g.name;
    for (const auto& t : g.triangles) {
      const uint32_t e = g.tag >= 1 ? find_exact(t[0], t[1], t[2]) : kNone;
      if (e == kNone) {
        if (g.tag >= 1) off_surface.push_back(t), off_group.push_back(id);
        if (g.tag < 1) ++group.missing;
      } else if (entries_[e].group == kNone) {
        entries_[e].group = id;
        entries_[e].p = t;  // the group's corner order: its facing
        ++group.triangles;
        any_ = true;
      } else if (entries_[e].group != id) {
        ++group.shared;
      }
    }
  }
  // Those that are faces inside one material, each held by the first group to hold it
  // (the smallest), as on the surface.
  const std::vector<InnerFace> inner = find_inner_faces(input, off_surface);
  std::vector<std::pair<std::array<uint32_t, 3>, uint32_t>> held;  // sorted corners, group
  for (size_t i = 0; i < off_surface.size(); ++i) {
    Group& group = groups_[off_group[i]];
    if (!inner[i].found) {
      ++group.missing;
      continue;
    }
    std::array<uint32_t, 3> key = inner[i].v;
    std::sort(key.begin(), key.end());
    held.push_back({key, uint32_t(i)});
  }
  std::stable_sort(held.begin(), held.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  // In a run of one triangle, the first is the holder (stable: the smallest group).
  std::vector<uint8_t> holds(off_surface.size(), 0);
  for (size_t k = 0, first = 0; k < held.size(); ++k) {
    if (k == 0 || held[k].first != held[k - 1].first) {
      first = k;
      holds[held[k].second] = 1;
    } else if (off_group[held[k].second] != off_group[held[first].second]) {
      ++groups_[off_group[held[k].second]].shared;
    }
  }
  for (size_t i = 0; i < off_surface.size(); ++i) {
    if (!holds[i]) continue;
    ++groups_[off_group[i]].inside;
    const int32_t m = inner[i].material;
    inside_.push_back({off_surface[i], m, m, off_group[i]});
  }
}

SurfacePatches::SurfacePatches(std::vector<Group> groups, std::vector<Entry> entries)
    : groups_(std::move(groups)) {
  // Entries inside a material (inner == outer) are the groups' triangles there.
  for (Entry& e : entries) {
    if (e.inner == e.outer && e.group != kNone) {
      ++groups_[e.group].inside;
      inside_.push_back(e);
    } else {
      any_ = any_ || e.group != kNone;
      entries_.push_back(e);
    }
  }
  build_index();
}

void SurfacePatches::build_index() {
  exact_.resize(entries_.size());
  for (uint32_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    exact_[i] = {corner_hash(triangle_key(e.p[0], e.p[1], e.p[2])), i};
  }
  std::sort(exact_.begin(), exact_.end());
  std::vector<std::pair<std::pair<int32_t, int32_t>, uint32_t>> by_pair(entries_.size());
  for (uint32_t i = 0; i < entries_.size(); ++i)
    by_pair[i] = {{entries_[i].inner, entries_[i].outer}, i};
  std::sort(by_pair.begin(), by_pair.end());
  for (size_t i = 0; i < by_pair.size();) {
    size_t j = i;
    std::vector<Triangle3> triangles;
    std::vector<uint32_t> ids;
    for (; j < by_pair.size() && by_pair[j].first == by_pair[i].first; ++j) {
      triangles.push_back(entries_[by_pair[j].second].p);
      ids.push_back(by_pair[j].second);
    }
    pairs_.push_back(by_pair[i].first);
    grids_.emplace_back(std::move(triangles));
    grid_entries_.push_back(std::move(ids));
    i = j;
  }
}

void SurfacePatches::drop_inside() {
  for (Group& g : groups_) g.missing += g.inside, g.inside = 0;
  inside_.clear();
}

uint32_t SurfacePatches::find_exact(const Vec3& a, const Vec3& b, const Vec3& c) const {
  const TriangleKey key = triangle_key(a, b, c);
  const uint64_t hash = corner_hash(key);
  auto it = std::lower_bound(exact_.begin(), exact_.end(), std::make_pair(hash, uint32_t(0)));
  for (; it != exact_.end() && it->first == hash; ++it) {
    const Entry& e = entries_[it->second];
    if (triangle_key(e.p[0], e.p[1], e.p[2]) == key) return it->second;
  }
  return kNone;
}

uint32_t SurfacePatches::locate(const Vec3& a, const Vec3& b, const Vec3& c, int32_t inner,
                                int32_t outer, bool* reversed) const {
  if (reversed) *reversed = false;
  if (!any_) return kNone;
  if (outer != kOutsideMaterial && outer < inner) std::swap(inner, outer);
  // An input triangle itself: the nearest to its centroid, found at once (on a valid
  // surface no other triangle of the pair holds that point).
  uint32_t e = find_exact(a, b, c);
  if (e == kNone || entries_[e].inner != inner || entries_[e].outer != outer) {
    const auto it = std::lower_bound(pairs_.begin(), pairs_.end(), std::make_pair(inner, outer));
    if (it == pairs_.end() || *it != std::make_pair(inner, outer)) return kNone;
    const size_t pair = size_t(it - pairs_.begin());
    // Within a budget of cells, far more than a mesh made from the input needs (its
    // triangles lie within the tolerance of the input's).
    const uint32_t i = grids_[pair].nearest((a + b + c) * (1.0 / 3.0), nullptr, 1 << 14);
    if (i == TriangleGrid::kNone) return kNone;
    e = grid_entries_[pair][i];
  }
  const Entry& entry = entries_[e];
  if (reversed && entry.group != kNone) {
    const Vec3 mine = cross(b - a, c - a);
    const Vec3 its = cross(entry.p[1] - entry.p[0], entry.p[2] - entry.p[0]);
    *reversed = dot(mine, its) < 0;
  }
  return entry.group;
}

LocatedGroups locate_groups(const TetMesh& mesh, const SurfacePatches& patches, bool inside,
                            const std::vector<uint32_t>& across) {
  LocatedGroups result;
  result.surface = extract_surface(mesh, across);
  result.boundary_count = result.surface.size();
  result.in_group.resize(patches.groups().size());
  result.label.resize(result.surface.size());
  const auto& p = mesh.positions;
  for (uint32_t i = 0; i < result.surface.size(); ++i) {
    SurfaceTriangle& t = result.surface[i];
    bool reversed = false;
    const uint32_t g = result.label[i] =
        patches.locate(p[t.v[0]], p[t.v[1]], p[t.v[2]], t.inner, t.outer, &reversed);
    if (g == SurfacePatches::kNone) continue;
    result.in_group[g].push_back(i);
    // An interface triangle of an input group faces as the input's did there: seen
    // from the tet across (a boundary triangle keeps facing out: no tet is across).
    const uint32_t other =
        t.outer == kOutsideMaterial ? kInvalidIndex : across[4 * t.tet + t.corner];
    if (reversed && other != kInvalidIndex) {
      uint8_t c = 0;
      const Tet& o = mesh.tets[other];
      while (c < 3 && (o[c] == t.v[0] || o[c] == t.v[1] || o[c] == t.v[2])) ++c;
      std::swap(t.v[1], t.v[2]);
      std::swap(t.inner, t.outer);
      t.tet = other;
      t.corner = c;
    }
  }
  if (inside) {
    // After the surface's, so that each group's indices still increase.
    const std::vector<SurfacePatches::Entry>& entries = patches.inside_entries();
    std::vector<std::array<Vec3, 3>> corners(entries.size());
    for (size_t i = 0; i < entries.size(); ++i) corners[i] = entries[i].p;
    const std::vector<InnerFace> faces = find_inner_faces(mesh, corners);
    for (size_t i = 0; i < entries.size(); ++i) {
      const InnerFace& f = faces[i];
      if (!f.found) continue;
      result.in_group[entries[i].group].push_back(uint32_t(result.surface.size()));
      result.surface.push_back({f.v, f.material, f.material, f.tet, f.corner});
    }
  }
  return result;
}

Status group_surface(const TetMesh& mesh, SurfaceGroups* groups, const SurfacePatches& patches,
                     bool inside, const std::vector<uint32_t>* neighbors) {
  std::vector<uint32_t> built;
  LocatedGroups located =
      locate_groups(mesh, patches, inside, given_or_built(mesh, neighbors, &built));
  SurfaceGroups result;
  result.surface = std::move(located.surface);
  std::vector<std::vector<uint32_t>>& in_group = located.in_group;
  const std::vector<uint32_t>& label = located.label;
  std::map<PairKey, std::vector<uint32_t>> by_pair, unlabelled;
  for (uint32_t i = 0; i < located.boundary_count; ++i) {
    // By the pair as extract_surface() gave it (inner < outer), before any turn above.
    SurfaceTriangle t = result.surface[i];
    if (t.outer != kOutsideMaterial && t.outer < t.inner) std::swap(t.inner, t.outer);
    const PairKey key = pair_key(t);
    by_pair[key].push_back(i);
    if (label[i] == SurfacePatches::kNone) unlabelled[key].push_back(i);
  }
  std::set<int32_t> used_tags;
  std::set<std::string> used_names;  // the input groups', which a generated one must not take
  for (size_t g = 0; g < in_group.size(); ++g) {
    if (in_group[g].empty()) continue;
    used_tags.insert(patches.groups()[g].tag);
    used_names.insert(patches.groups()[g].name);
  }
  const int64_t first = first_surface_tag(mesh);
  int64_t tag = first;
  std::vector<bool> placed(in_group.size(), false);
  for (const auto& [key, triangles] : by_pair) {
    const auto rest = unlabelled.find(key);
    if (rest != unlabelled.end()) {
      SurfaceGroup group;
      group.material = std::get<1>(key);
      group.other = std::get<2>(key);
      group.name = pair_name(group.material, group.other);
      while (tag <= std::numeric_limits<int32_t>::max() && used_tags.count(int32_t(tag))) ++tag;
      if (used_names.count(group.name)) group.name += "_" + std::to_string(tag);  // an input's
      if (tag > std::numeric_limits<int32_t>::max()) {
        return Status::error("material ids up to " + std::to_string(first - 1) +
                             " leave no room to number the surface groups above them (tags "
                             "end at 2147483647)");
      }
      group.tag = static_cast<int32_t>(tag++);
      group.triangles = rest->second;
      result.groups.push_back(std::move(group));
    }
    // The input groups that first appear on this pair, in the input's order.
    std::vector<uint32_t> here;
    for (uint32_t i : triangles) {
      const uint32_t g = label[i];
      if (g != SurfacePatches::kNone && !placed[g]) placed[g] = true, here.push_back(g);
    }
    std::sort(here.begin(), here.end());
    for (uint32_t g : here) {
      const SurfacePatches::Group& input = patches.groups()[g];
      SurfaceGroup group;
      const SurfaceTriangle& t = result.surface[in_group[g].front()];
      group.material = t.inner;
      group.other = t.outer;
      if (t.outer != kOutsideMaterial && t.outer < t.inner) std::swap(group.material, group.other);
      group.tag = input.tag;
      group.name = input.name;
      if (group.name.empty()) {
        // Unnamed (a Medit reference): a whole pair's keeps the pair's name, whichever
        // way its triangles face (a reversed one has its materials swapped above).
        bool whole_pair = by_pair.at(key).size() == in_group[g].size();
        for (uint32_t i : in_group[g]) {
          PairKey k = pair_key(result.surface[i]);
          if (std::get<2>(k) != std::get<2>(key)) std::swap(std::get<1>(k), std::get<2>(k));
          whole_pair = whole_pair && k == key;
        }
        group.name = whole_pair ? pair_name(std::get<1>(key), std::get<2>(key))
                                : "surface_" + std::to_string(input.tag);
      }
      group.triangles = std::move(in_group[g]);
      result.groups.push_back(std::move(group));
    }
  }
  // The groups only inside materials, in the input's order.
  for (size_t g = 0; g < in_group.size(); ++g) {
    if (placed[g] || in_group[g].empty()) continue;
    const SurfacePatches::Group& input = patches.groups()[g];
    SurfaceGroup group;
    group.material = group.other = result.surface[in_group[g].front()].inner;
    group.tag = input.tag;
    group.name = input.name.empty() ? "surface_" + std::to_string(input.tag) : input.name;
    group.triangles = std::move(in_group[g]);
    result.groups.push_back(std::move(group));
  }
  *groups = std::move(result);
  return Status();
}

}  // namespace tetlod
