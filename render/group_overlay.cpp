#include "render/group_overlay.h"

#include "core/adjacency.h"

namespace tetlod::render {

Rgb surface_group_rgb(uint32_t index) {
  static constexpr Rgb kColors[8] = {
      {0.90f, 0.10f, 0.10f}, {1.00f, 0.55f, 0.00f}, {0.10f, 0.35f, 1.00f}, {0.00f, 0.80f, 0.80f},
      {0.60f, 1.00f, 0.10f}, {0.55f, 0.30f, 0.10f}, {0.50f, 0.10f, 0.70f}, {0.50f, 0.50f, 0.50f}};
  // Then generated colours (from further along than the materials' take them), cycled
  // as the materials' are: groups 1 and 9 were one red.
  const uint32_t cycled = index % kColorCycle;
  return cycled < 8 ? kColors[cycled] : generated_rgb(kColorCycle + cycled);
}

std::string surface_group_label(const SurfacePatches::Group& group) {
  return group.name.empty() ? "surface " + std::to_string(group.tag) : group.name;
}

GroupOverlay build_group_overlay(const TetMesh& mesh, const std::vector<uint32_t>& neighbors,
                                 const SurfacePatches& patches, const std::vector<uint32_t>& shown,
                                 const SurfaceFilter& filter) {
  GroupOverlay overlay;
  if (shown.empty()) return overlay;
  const LocatedGroups located = locate_groups(mesh, patches, true, neighbors);
  const MaterialSet hidden(filter.hidden_materials);
  const auto drawn = [&](uint32_t t) {
    return t != kInvalidIndex && !hidden.contains(mesh.materials[t]) &&
           cut_keeps(filter, mesh.positions[mesh.tets[t][0]], mesh.positions[mesh.tets[t][1]],
                     mesh.positions[mesh.tets[t][2]], mesh.positions[mesh.tets[t][3]]);
  };
  for (uint32_t g : shown) {
    if (g >= located.in_group.size()) continue;
    GroupOverlay::Group group;
    group.index = g;
    group.first = overlay.vertices.size();
    group.triangles = located.in_group[g].size();
    group.color = surface_group_rgb(g);
    group.label = surface_group_label(patches.groups()[g]);
    for (uint32_t i : located.in_group[g]) {
      const SurfaceTriangle& t = located.surface[i];
      if (!drawn(t.tet) && !drawn(neighbors[4 * size_t(t.tet) + t.corner])) continue;
      for (uint32_t v : t.v) {
        const Vec3& p = mesh.positions[v];
        overlay.vertices.push_back(
            {{float(p.x), float(p.y), float(p.z)}, 0.0f, static_cast<uint32_t>(g)});
      }
    }
    group.count = overlay.vertices.size() - group.first;
    overlay.groups.push_back(std::move(group));
  }
  return overlay;
}

}  // namespace tetlod::render
