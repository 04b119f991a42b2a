#include "core/mesh_stats.h"

#include <algorithm>
#include <limits>

#include "core/metrics.h"

namespace tetlod {

// Speed notes (docs/PERFORMANCE.md, "Core: read, adjacency, metrics"): two passes, each
// in an order that keeps memory access cheap on large, badly numbered meshes. The tet
// pass streams through the tets, prefetching the corner positions a few tets ahead. The
// vertex pass walks the vertex -> tets buckets in order, prefetching the tets a few
// bucket entries ahead; it needs a tet's material only around vertices where materials
// meet, which the tet pass finds.

namespace {

// How far ahead the passes prefetch, in tets and in bucket entries.
constexpr size_t kShapePrefetchDistance = 8;
constexpr uint32_t kStarPrefetchDistance = 32;

// Dense index (0, 1, ... in increasing id order) of the material ids of a mesh: a
// table indexed by id when ids are small, as they are in practice; a binary search
// otherwise.
class MaterialIndex {
 public:
  explicit MaterialIndex(const std::vector<int32_t>& materials) {
    int32_t largest = 0;
    for (int32_t m : materials) largest = std::max(largest, m);
    const bool all_non_negative =
        std::all_of(materials.begin(), materials.end(), [](int32_t m) { return m >= 0; });
    if (all_non_negative && largest < kLargestTabledId) {
      table_.assign(static_cast<size_t>(largest) + 1, 0);
      for (int32_t m : materials) table_[m] = 1;
      for (int32_t id = 0; id <= largest; ++id) {
        if (table_[id]) {
          table_[id] = static_cast<uint32_t>(ids_.size());
          ids_.push_back(id);
        }
      }
    } else {
      ids_ = materials;
      std::sort(ids_.begin(), ids_.end());
      ids_.erase(std::unique(ids_.begin(), ids_.end()), ids_.end());
    }
  }

  // The dense index of an id that occurs in the mesh.
  uint32_t operator()(int32_t id) const {
    if (!table_.empty()) return table_[id];
    return static_cast<uint32_t>(std::lower_bound(ids_.begin(), ids_.end(), id) - ids_.begin());
  }
  const std::vector<int32_t>& ids() const { return ids_; }

 private:
  static constexpr int32_t kLargestTabledId = 1 << 16;
  std::vector<uint32_t> table_;  // id -> dense index, or empty
  std::vector<int32_t> ids_;     // dense index -> id
};

// What the tet pass learns about the materials around each vertex, besides the dense
// index of the one material around it. kNoMaterial also marks a tet already counted.
constexpr uint32_t kNoMaterial = 0xffffffffu;     // no tet seen yet
constexpr uint32_t kMixedMaterial = 0xfffffffeu;  // tets of two or more materials

}  // namespace

int stretch_bin(double stretch) {
  const int bin = static_cast<int>(stretch * kStretchBins);
  return std::clamp(bin, 0, kStretchBins - 1);
}

MeshStats compute_mesh_stats(const TetMesh& mesh, const VertexTets& vertex_tets) {
  MeshStats stats;
  stats.stretch_histogram.assign(kStretchBins, 0);
  const size_t tet_count = mesh.tet_count();
  const size_t vertex_count = mesh.vertex_count();
  const Tet* tets = mesh.tets.data();
  const Vec3* positions = mesh.positions.data();

  const MaterialIndex material_index(mesh.materials);
  const size_t material_count = material_index.ids().size();
  std::vector<PropertyRow> rows(material_count);
  std::vector<double> stretch_sum(material_count, 0.0);
  for (PropertyRow& r : rows) r.min_stretch = std::numeric_limits<double>::infinity();

  // Tet pass: size, stretch, volume; and which vertices lie where materials meet. The
  // dense material of each tet is kept in bytes when it fits, a small array for the
  // vertex pass to read in random order.
  std::vector<uint32_t> vertex_material(vertex_count, kNoMaterial);
  std::vector<uint8_t> tet_material(material_count <= 256 ? tet_count : 0);
  auto material_of = [&](uint32_t t) {
    return tet_material.empty() ? material_index(mesh.materials[t]) : tet_material[t];
  };
  PropertyRow& whole = stats.whole;
  whole.min_stretch = std::numeric_limits<double>::infinity();
  double whole_stretch_sum = 0;
  for (size_t t = 0; t < tet_count; ++t) {
    if (t + kShapePrefetchDistance < tet_count) {
      for (uint32_t v : tets[t + kShapePrefetchDistance]) __builtin_prefetch(&positions[v]);
    }
    const Tet& tet = tets[t];
    const uint32_t m = material_index(mesh.materials[t]);
    if (!tet_material.empty()) tet_material[t] = static_cast<uint8_t>(m);
    for (uint32_t v : tet) {
      uint32_t& seen = vertex_material[v];  // written so as to compile without branches
      const uint32_t before = seen == kNoMaterial ? m : seen;
      seen = before == m ? m : kMixedMaterial;
    }
    const TetShape s =
        tet_shape(positions[tet[0]], positions[tet[1]], positions[tet[2]], positions[tet[3]]);
    PropertyRow& r = rows[m];
    ++r.elements;
    stretch_sum[m] += s.stretch;
    r.min_stretch = std::min(r.min_stretch, s.stretch);
    r.max_size = std::max(r.max_size, s.size);
    r.volume += s.volume;
    whole_stretch_sum += s.stretch;
    whole.min_stretch = std::min(whole.min_stretch, s.stretch);
    whole.max_size = std::max(whole.max_size, s.size);
    whole.volume += s.volume;
    ++stats.stretch_histogram[stretch_bin(s.stretch)];
  }
  whole.elements = tet_count;
  whole.average_stretch = whole.elements ? whole_stretch_sum / whole.elements : 0;
  if (whole.elements == 0) whole.min_stretch = 0;
  for (size_t m = 0; m < material_count; ++m) {
    rows[m].average_stretch = stretch_sum[m] / rows[m].elements;
  }

  // Vertex pass: edge neighbours of each vertex, counted by marking the corners of the
  // tets around it with a stamp (the vertex itself first, so that it is not counted).
  // The marking is written without branches: whether a corner is new is unpredictable.
  std::vector<uint32_t> mark(vertex_count, 0);
  uint32_t stamp = 0;
  auto next_stamp = [&]() {
    if (++stamp == 0) {
      std::fill(mark.begin(), mark.end(), 0);
      stamp = 1;
    }
    return stamp;
  };
  // Where materials meet, each marked corner also records the materials (of one group of
  // 32 dense indices) of the tets it was seen in, valid while its mark is current.
  std::vector<uint32_t> seen_in(vertex_count, 0);
  std::vector<uint32_t> star_materials;  // of the tets around a vertex where materials meet
  const uint32_t* entries_end = vertex_tets.tets.data() + vertex_tets.tets.size();
  size_t whole_edge_ends = 0;
  std::vector<size_t> edge_ends(material_count, 0);
  auto add_node = [&](uint32_t m, uint32_t valence) {
    PropertyRow& r = rows[m];
    ++r.nodes;
    edge_ends[m] += valence;
    r.max_valence = std::max(r.max_valence, valence);
  };
  for (uint32_t v = 0; v < vertex_count; ++v) {
    const uint32_t* first = vertex_tets.begin(v);
    const uint32_t* last = vertex_tets.end(v);
    if (first == last) continue;
    const uint32_t material = vertex_material[v];
    ++whole.nodes;
    uint32_t s = next_stamp();
    mark[v] = s;
    uint32_t valence = 0;
    if (material == kMixedMaterial && !tet_material.empty()) {  // read after the walk below
      for (const uint32_t* e = first; e != last; ++e) __builtin_prefetch(&tet_material[*e]);
    }
    for (const uint32_t* e = first; e != last; ++e) {
      if (e + kStarPrefetchDistance < entries_end) {
        __builtin_prefetch(&tets[e[kStarPrefetchDistance]]);
      }
      for (uint32_t w : tets[*e]) {
        valence += mark[w] != s;
        mark[w] = s;
      }
    }
    whole_edge_ends += valence;
    whole.max_valence = std::max(whole.max_valence, valence);
    if (material != kMixedMaterial) {  // the common case: the sub-mesh sees the same star
      add_node(material, valence);
      continue;
    }
    star_materials.clear();
    for (const uint32_t* e = first; e != last; ++e) star_materials.push_back(material_of(*e));
    // One more walk over the (cached) star per group of 32 materials in it, consuming
    // the group's tets; there is one group unless the mesh has over 32 materials.
    const size_t star_size = star_materials.size();
    for (size_t i = 0; i < star_size; ++i) {
      if (star_materials[i] == kNoMaterial) continue;
      const uint32_t group = star_materials[i] / 32;
      s = next_stamp();
      mark[v] = s;
      seen_in[v] = ~0u;
      uint32_t group_valence[32] = {};
      uint32_t group_materials = 0;
      for (size_t j = i; j < star_size; ++j) {
        const uint32_t m = star_materials[j];
        if (m == kNoMaterial || m / 32 != group) continue;
        star_materials[j] = kNoMaterial;
        const uint32_t bit = 1u << (m % 32);
        group_materials |= bit;
        for (uint32_t w : tets[first[j]]) {
          const uint32_t before = mark[w] == s ? seen_in[w] : 0;
          mark[w] = s;
          seen_in[w] = before | bit;
          group_valence[m % 32] += (before & bit) == 0;
        }
      }
      for (; group_materials != 0; group_materials &= group_materials - 1) {
        const int b = __builtin_ctz(group_materials);
        add_node(group * 32 + b, group_valence[b]);
      }
    }
  }
  whole.edges = whole_edge_ends / 2;
  stats.per_material.resize(material_count);
  for (size_t m = 0; m < material_count; ++m) {
    rows[m].edges = edge_ends[m] / 2;
    stats.per_material[m] = {material_index.ids()[m], rows[m]};
  }
  return stats;
}

std::vector<MaterialVolume> material_volumes(const TetMesh& mesh) {
  std::vector<MaterialVolume> volumes;
  std::vector<int32_t> ids = mesh.materials;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (const int32_t m : ids) volumes.push_back({m, 0});
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto it =
        std::lower_bound(volumes.begin(), volumes.end(), mesh.materials[t],
                         [](const MaterialVolume& v, int32_t m) { return v.material < m; });
    it->volume += signed_volume6(mesh, mesh.tets[t]) / 6;
  }
  return volumes;
}

std::vector<MaterialSurface> material_surfaces(const TetMesh& mesh) {
  std::vector<MaterialSurface> surfaces;
  for (const MaterialVolume& m : material_volumes(mesh))
    surfaces.push_back({m.material, m.volume, 0});
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const int32_t m = mesh.materials[t];
    MaterialSurface* surface = nullptr;
    for (int f = 0; f < 4; ++f) {
      const uint32_t other = neighbors[4 * t + size_t(f)];
      if (other != kInvalidIndex && mesh.materials[other] == m) continue;
      if (!surface)
        surface = &*std::lower_bound(
            surfaces.begin(), surfaces.end(), m,
            [](const MaterialSurface& s, int32_t material) { return s.material < material; });
      const Tet& tet = mesh.tets[t];
      const Vec3& a = mesh.positions[tet[kTetFace[f][0]]];
      surface->area += 0.5 * length(cross(mesh.positions[tet[kTetFace[f][1]]] - a,
                                          mesh.positions[tet[kTetFace[f][2]]] - a));
    }
  }
  return surfaces;
}

}  // namespace tetlod
