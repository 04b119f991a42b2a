// An independent, brute-force computation of the Table I row with std::set, used
// to check compute_mesh_stats() on hand-made meshes and on the bundled models.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "core/mesh_stats.h"
#include "core/tet_mesh.h"

namespace tetlod::test {

struct ReferenceRow {
  std::set<uint32_t> nodes;
  std::set<std::pair<uint32_t, uint32_t>> edges;
  size_t elements = 0;
  double stretch_sum = 0, min_stretch = 1e300, max_size = 0;
};

inline double reference_stretch(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 p[4] = {a, b, c, d};
  double longest = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) longest = std::max(longest, length(p[i] - p[j]));
  const double volume = dot(b - a, cross(c - a, d - a)) / 6;
  double area = 0;
  for (int skip = 0; skip < 4; ++skip) {
    Vec3 f[3];
    int k = 0;
    for (int i = 0; i < 4; ++i)
      if (i != skip) f[k++] = p[i];
    area += 0.5 * length(cross(f[1] - f[0], f[2] - f[0]));
  }
  return 6 * std::sqrt(6.0) * volume / (longest * area);
}

inline void expect_row_matches(const ReferenceRow& ref, const PropertyRow& row, const char* what) {
  EXPECT_EQ(row.nodes, ref.nodes.size()) << what;
  EXPECT_EQ(row.edges, ref.edges.size()) << what;
  EXPECT_EQ(row.elements, ref.elements) << what;
  EXPECT_NEAR(row.average_stretch, ref.stretch_sum / ref.elements, 1e-12) << what;
  EXPECT_NEAR(row.min_stretch, ref.min_stretch, 1e-12) << what;
  EXPECT_NEAR(row.max_size, ref.max_size, 1e-12 * std::max(1.0, ref.max_size)) << what;
  std::map<uint32_t, size_t> valence;
  for (const auto& e : ref.edges) {
    ++valence[e.first];
    ++valence[e.second];
  }
  size_t max_valence = 0;
  for (const auto& [v, count] : valence) max_valence = std::max(max_valence, count);
  EXPECT_EQ(row.max_valence, max_valence) << what;
}

inline void expect_stats_match_reference(const TetMesh& mesh, const MeshStats& stats) {
  ReferenceRow whole;
  std::map<int32_t, ReferenceRow> per;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    const double d = reference_stretch(mesh.positions[tet[0]], mesh.positions[tet[1]],
                                       mesh.positions[tet[2]], mesh.positions[tet[3]]);
    double longest = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        longest = std::max(longest, length(mesh.positions[tet[i]] - mesh.positions[tet[j]]));
    for (ReferenceRow* r : {&whole, &per[mesh.materials[t]]}) {
      ++r->elements;
      r->stretch_sum += d;
      r->min_stretch = std::min(r->min_stretch, d);
      r->max_size = std::max(r->max_size, longest);
      for (int i = 0; i < 4; ++i) {
        r->nodes.insert(tet[i]);
        for (int j = i + 1; j < 4; ++j)
          r->edges.insert({std::min(tet[i], tet[j]), std::max(tet[i], tet[j])});
      }
    }
  }
  expect_row_matches(whole, stats.whole, "whole mesh");
  ASSERT_EQ(stats.per_material.size(), per.size());
  size_t i = 0;
  for (const auto& [material, ref] : per) {
    EXPECT_EQ(stats.per_material[i].material, material);
    expect_row_matches(ref, stats.per_material[i].row,
                       ("material " + std::to_string(material)).c_str());
    ++i;
  }
}

}  // namespace tetlod::test
