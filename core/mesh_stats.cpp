#include "core/mesh_stats.h"

#include <algorithm>
#include <limits>

#include "core/metrics.h"

namespace tetlod {

int stretch_bin(double stretch) {
  const int bin = static_cast<int>(stretch * kStretchBins);
  return std::clamp(bin, 0, kStretchBins - 1);
}

MeshStats compute_mesh_stats(const TetMesh& mesh, const VertexTets& vertex_tets) {
  MeshStats stats;
  stats.stretch_histogram.assign(kStretchBins, 0);

  // Dense material index.
  std::vector<int32_t> material_ids(mesh.materials);
  std::sort(material_ids.begin(), material_ids.end());
  material_ids.erase(std::unique(material_ids.begin(), material_ids.end()), material_ids.end());
  const size_t material_count = material_ids.size();
  std::vector<uint32_t> dense(mesh.tet_count());
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    dense[t] = static_cast<uint32_t>(
        std::lower_bound(material_ids.begin(), material_ids.end(), mesh.materials[t]) -
        material_ids.begin());
  }
  std::vector<PropertyRow> rows(material_count);
  std::vector<double> stretch_sum(material_count, 0.0);
  for (PropertyRow& r : rows) r.min_stretch = std::numeric_limits<double>::infinity();

  // Per tet: size, stretch, volume.
  PropertyRow& whole = stats.whole;
  whole.min_stretch = std::numeric_limits<double>::infinity();
  double whole_stretch_sum = 0;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const TetShape s = tet_shape(mesh, mesh.tets[t]);
    PropertyRow& r = rows[dense[t]];
    ++r.elements;
    stretch_sum[dense[t]] += s.stretch;
    r.min_stretch = std::min(r.min_stretch, s.stretch);
    r.max_size = std::max(r.max_size, s.size);
    r.volume += s.volume;
    whole_stretch_sum += s.stretch;
    whole.min_stretch = std::min(whole.min_stretch, s.stretch);
    whole.max_size = std::max(whole.max_size, s.size);
    whole.volume += s.volume;
    ++stats.stretch_histogram[stretch_bin(s.stretch)];
  }
  whole.elements = mesh.tet_count();
  whole.average_stretch = whole.elements ? whole_stretch_sum / whole.elements : 0;
  if (whole.elements == 0) whole.min_stretch = 0;
  for (size_t m = 0; m < material_count; ++m) {
    rows[m].average_stretch = stretch_sum[m] / rows[m].elements;
  }

  // Per vertex: edge neighbours in the whole mesh and in each material's sub-mesh.
  // First gather, for every vertex, the other three corners (and the material) of each
  // tet around it, in one sequential pass over the tets: the per-vertex loop below then
  // reads memory in order instead of jumping to each tet.
  struct Corners {
    uint32_t other[3];
    uint32_t material;
  };
  std::vector<Corners> around(vertex_tets.tets.size());
  {
    std::vector<uint32_t> cursor(vertex_tets.offsets.begin(), vertex_tets.offsets.end() - 1);
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      const Tet& q = mesh.tets[t];
      for (int c = 0; c < 4; ++c) {
        Corners& e = around[cursor[q[c]]++];
        int n = 0;
        for (int k = 0; k < 4; ++k)
          if (k != c) e.other[n++] = q[k];
        e.material = dense[t];
      }
    }
  }
  std::vector<uint32_t> mark(mesh.vertex_count(), 0);
  uint32_t stamp = 0;
  auto next_stamp = [&]() {
    if (++stamp == 0) {
      std::fill(mark.begin(), mark.end(), 0);
      stamp = 1;
    }
    return stamp;
  };
  std::vector<uint32_t> vertex_materials;
  size_t whole_edge_ends = 0;
  std::vector<size_t> edge_ends(material_count, 0);
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    const Corners* first = around.data() + vertex_tets.offsets[v];
    const Corners* last = around.data() + vertex_tets.offsets[v + 1];
    if (first == last) continue;
    ++whole.nodes;
    uint32_t s = next_stamp();
    uint32_t valence = 0;
    bool one_material = true;
    for (const Corners* e = first; e != last; ++e) {
      one_material = one_material && e->material == first->material;
      for (uint32_t w : e->other) {
        if (mark[w] != s) {
          mark[w] = s;
          ++valence;
        }
      }
    }
    whole_edge_ends += valence;
    whole.max_valence = std::max(whole.max_valence, valence);
    if (one_material) {  // the common case: the sub-mesh sees the same star
      PropertyRow& r = rows[first->material];
      ++r.nodes;
      edge_ends[first->material] += valence;
      r.max_valence = std::max(r.max_valence, valence);
      continue;
    }
    vertex_materials.clear();
    for (const Corners* e = first; e != last; ++e) vertex_materials.push_back(e->material);
    std::sort(vertex_materials.begin(), vertex_materials.end());
    vertex_materials.erase(std::unique(vertex_materials.begin(), vertex_materials.end()),
                           vertex_materials.end());
    for (uint32_t m : vertex_materials) {
      s = next_stamp();
      uint32_t material_valence = 0;
      for (const Corners* e = first; e != last; ++e) {
        if (e->material != m) continue;
        for (uint32_t w : e->other) {
          if (mark[w] != s) {
            mark[w] = s;
            ++material_valence;
          }
        }
      }
      PropertyRow& r = rows[m];
      ++r.nodes;
      edge_ends[m] += material_valence;
      r.max_valence = std::max(r.max_valence, material_valence);
    }
  }
  whole.edges = whole_edge_ends / 2;
  stats.per_material.resize(material_count);
  for (size_t m = 0; m < material_count; ++m) {
    rows[m].edges = edge_ends[m] / 2;
    stats.per_material[m] = {material_ids[m], rows[m]};
  }
  return stats;
}

}  // namespace tetlod
