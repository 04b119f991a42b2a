#include "core/surface.h"

#include <algorithm>
#include <cmath>
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

Status group_surface(const TetMesh& mesh, SurfaceGroups* groups) {
  return group_surface(mesh, groups, SurfacePatches());
}

namespace {

// Squared distance from p to the triangle t (Ericson, Real-Time Collision Detection,
// 5.1.5: the closest point by the Voronoi region of p).
double squared_distance(const Vec3& p, const std::array<Vec3, 3>& t) {
  const Vec3 &a = t[0], &b = t[1], &c = t[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return squared_length(ap);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return squared_length(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return squared_length(p - (a + ab * (d1 / (d1 - d3))));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return squared_length(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return squared_length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return squared_length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double sum = va + vb + vc;
  if (!(sum > 0)) return std::min({squared_length(ap), squared_length(bp), squared_length(cp)});
  return squared_length(p - (a + ab * (vb / sum) + ac * (vc / sum)));
}

}  // namespace

SurfacePatches::SurfacePatches(const TetMesh& input, const std::vector<InputSurfaceGroup>& groups) {
  const std::vector<SurfaceTriangle> surface =
      extract_surface(input, build_adjacency(input).tet_neighbors);
  const auto& p = input.positions;
  std::map<TriangleKey, uint32_t> index;  // surface triangle -> its entry
  entries_.reserve(surface.size());
  for (const SurfaceTriangle& t : surface) {
    index.emplace(triangle_key(p[t.v[0]], p[t.v[1]], p[t.v[2]]), uint32_t(entries_.size()));
    entries_.push_back({{p[t.v[0]], p[t.v[1]], p[t.v[2]]}, t.inner, t.outer, kNone});
  }
  for (const InputSurfaceGroup& g : groups) {
    Group group;
    group.tag = g.tag;
    group.name = g.name;
    const uint32_t id = uint32_t(groups_.size());
    for (const auto& t : g.triangles) {
      const auto it = g.tag >= 1 ? index.find(triangle_key(t[0], t[1], t[2])) : index.end();
      if (it == index.end()) {
        ++group.missing;
      } else if (entries_[it->second].group == kNone) {
        entries_[it->second].group = id;  // the first group holding it
        ++group.triangles;
        any_ = true;
      }
    }
    groups_.push_back(std::move(group));
  }
  build_index();
}

SurfacePatches::SurfacePatches(std::vector<Group> groups, std::vector<Entry> entries)
    : groups_(std::move(groups)), entries_(std::move(entries)) {
  for (const Entry& e : entries_) any_ = any_ || e.group != kNone;
  build_index();
}

void SurfacePatches::build_index() {
  if (entries_.empty()) return;
  for (const Entry& e : entries_) pairs_.push_back({e.inner, e.outer});
  std::sort(pairs_.begin(), pairs_.end());
  pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
  // The grid: cells about the mean triangle's size, at most ~2 entries' worth.
  Vec3 lo = entries_[0].p[0], hi = lo;
  double extent_sum = 0;
  for (const Entry& e : entries_) {
    Vec3 elo = e.p[0], ehi = e.p[0];
    for (const Vec3& q : e.p) {
      elo = {std::min(elo.x, q.x), std::min(elo.y, q.y), std::min(elo.z, q.z)};
      ehi = {std::max(ehi.x, q.x), std::max(ehi.y, q.y), std::max(ehi.z, q.z)};
    }
    lo = {std::min(lo.x, elo.x), std::min(lo.y, elo.y), std::min(lo.z, elo.z)};
    hi = {std::max(hi.x, ehi.x), std::max(hi.y, ehi.y), std::max(hi.z, ehi.z)};
    extent_sum += length(ehi - elo);
  }
  const Vec3 span = hi - lo;
  cell_ = std::max(extent_sum / double(entries_.size()), 1e-300);
  const double limit = 2.0 * double(entries_.size()) + 8;
  // (Coordinates far apart can overflow the span: then one cell holds everything.)
  const bool finite = is_finite(span) && std::isfinite(cell_);
  for (int round = 0; finite && round < 4000; ++round) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) cells *= std::floor(span[k] / cell_) + 1;
    if (cells <= limit) break;
    cell_ *= 1.25;
  }
  origin_ = lo;
  auto set_dims = [&] {
    for (int k = 0; k < 3; ++k) {
      const double n = std::floor(span[k] / cell_) + 1;
      dims_[k] = finite && n >= 1 && n <= limit ? int(n) : 1;
    }
  };
  auto cell_range = [&](const Entry& e, int* from, int* to) {
    for (int k = 0; k < 3; ++k) {
      double a = e.p[0][k], b = a;
      for (const Vec3& q : e.p) a = std::min(a, q[k]), b = std::max(b, q[k]);
      from[k] = cell_index(a, k);
      to[k] = cell_index(b, k);
    }
  };
  // A few triangles far larger than the mean would each fill many cells: coarser
  // cells until the grid holds at most 16 entries' worth.
  for (set_dims();; cell_ *= 2, set_dims()) {
    double held = 0;
    for (const Entry& e : entries_) {
      int from[3], to[3];
      cell_range(e, from, to);
      held += double(to[0] - from[0] + 1) * (to[1] - from[1] + 1) * (to[2] - from[2] + 1);
    }
    if (held <= 16.0 * double(entries_.size()) + 1024 || dims_[0] * dims_[1] * dims_[2] == 1) break;
  }
  cell_start_.assign(size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<uint32_t> cursor;
    if (pass == 1) {
      for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
      cursor.assign(cell_start_.begin(), cell_start_.end() - 1);
      cell_entries_.resize(cell_start_.back());
    }
    for (uint32_t i = 0; i < entries_.size(); ++i) {
      int from[3], to[3];
      cell_range(entries_[i], from, to);
      for (int z = from[2]; z <= to[2]; ++z)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int x = from[0]; x <= to[0]; ++x) {
            if (pass == 0)
              ++cell_start_[cell_of(x, y, z) + 1];
            else
              cell_entries_[cursor[cell_of(x, y, z)]++] = i;
          }
    }
  }
}

uint32_t SurfacePatches::locate(const Vec3& a, const Vec3& b, const Vec3& c, int32_t inner,
                                int32_t outer) const {
  if (!any_) return kNone;
  if (outer != kOutsideMaterial && outer < inner) std::swap(inner, outer);
  // A pair the input does not have would search the whole grid for nothing.
  if (!std::binary_search(pairs_.begin(), pairs_.end(), std::make_pair(inner, outer))) return kNone;
  const Vec3 q = (a + b + c) * (1.0 / 3.0);
  int center[3];
  for (int k = 0; k < 3; ++k) center[k] = cell_index(q[k], k);
  double best = INFINITY;
  uint32_t found = kNone;
  auto visit = [&](int x, int y, int z) {
    const size_t cell = cell_of(x, y, z);
    for (uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      const uint32_t i = cell_entries_[k];
      const Entry& e = entries_[i];
      if (e.inner != inner || e.outer != outer) continue;
      const double d = squared_distance(q, e.p);
      if (d < best || (d == best && i < found)) best = d, found = i;
    }
  };
  // Shells of cells around the centre cell, outwards (only each shell's own cells),
  // within a budget of cells: a triangle farther than that from every input triangle
  // of its pair (none is, on a mesh made from the input) is in no group.
  size_t visited = 0;
  constexpr size_t kCellBudget = 1 << 14;
  for (int r = 0; visited < kCellBudget; ++r) {
    const int z0 = std::max(center[2] - r, 0), z1 = std::min(center[2] + r, dims_[2] - 1);
    const int y0 = std::max(center[1] - r, 0), y1 = std::min(center[1] + r, dims_[1] - 1);
    const int x0 = std::max(center[0] - r, 0), x1 = std::min(center[0] + r, dims_[0] - 1);
    for (int z = z0; z <= z1; ++z) {
      const bool z_face = std::abs(z - center[2]) == r;
      for (int y = y0; y <= y1; ++y) {
        if (z_face || std::abs(y - center[1]) == r) {
          for (int x = x0; x <= x1; ++x) visit(x, y, z), ++visited;
        } else {
          if (center[0] - r >= 0) visit(center[0] - r, y, z), ++visited;
          if (r > 0 && center[0] + r < dims_[0]) visit(center[0] + r, y, z), ++visited;
        }
      }
    }
    // Every cell not yet seen lies beyond the box of shells 0..r around the centre
    // cell, on a side where the grid goes on: stop once the best is nearer than
    // those sides, or when there are none.
    double margin = INFINITY;
    for (int k = 0; k < 3; ++k) {
      if (center[k] - r > 0)
        margin =
            std::min(margin, std::max(0.0, q[k] - (origin_[k] + double(center[k] - r) * cell_)));
      if (center[k] + r < dims_[k] - 1)
        margin =
            std::min(margin, std::max(0.0, origin_[k] + double(center[k] + r + 1) * cell_ - q[k]));
    }
    if (margin == INFINITY || (found != kNone && best <= margin * margin)) break;
  }
  return found == kNone ? kNone : entries_[found].group;
}

Status group_surface(const TetMesh& mesh, SurfaceGroups* groups, const SurfacePatches& patches) {
  SurfaceGroups result;
  result.surface = extract_surface(mesh, build_adjacency(mesh).tet_neighbors);
  const auto& p = mesh.positions;
  std::map<PairKey, std::vector<uint32_t>> by_pair, unlabelled;
  std::vector<std::vector<uint32_t>> in_group(patches.groups().size());
  std::vector<uint32_t> label(result.surface.size());
  for (uint32_t i = 0; i < result.surface.size(); ++i) {
    const SurfaceTriangle& t = result.surface[i];
    const uint32_t g = label[i] = patches.locate(p[t.v[0]], p[t.v[1]], p[t.v[2]], t.inner, t.outer);
    by_pair[pair_key(t)].push_back(i);
    if (g == SurfacePatches::kNone)
      unlabelled[pair_key(t)].push_back(i);
    else
      in_group[g].push_back(i);
  }
  std::set<int32_t> used_tags;
  for (size_t g = 0; g < in_group.size(); ++g)
    if (!in_group[g].empty()) used_tags.insert(patches.groups()[g].tag);
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
      group.tag = input.tag;
      group.name = input.name.empty() ? "surface_" + std::to_string(input.tag) : input.name;
      group.triangles = std::move(in_group[g]);
      result.groups.push_back(std::move(group));
    }
  }
  *groups = std::move(result);
  return Status();
}

}  // namespace tetlod
