// build_group_overlay(): the input's surface groups on a mesh, as group_surface() finds
// them (faces inside a material too), left out where no tet beside them is shown.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/surface.h"
#include "render/group_overlay.h"

namespace tetlod {
namespace {

struct Sheet {
  TetMesh mesh;
  std::vector<uint32_t> neighbors;
  SurfacePatches patches;
};

// tests/data/gmsh/sheet.msh: a block of material 1 with "sheet" (100) inside it,
// "bottom" (200) and "top_and_sheet" (300: the top and a second sheet inside).
Sheet read_sheet() {
  Sheet s;
  ReadInfo info;
  const Status read =
      read_mesh(std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/sheet.msh", &s.mesh, &info);
  EXPECT_TRUE(read.ok()) << read.message();
  build_face_neighbors(s.mesh, &s.neighbors);
  s.patches = SurfacePatches(s.mesh, info.surface_groups);
  return s;
}

uint32_t group_index(const SurfacePatches& patches, const std::string& name) {
  for (uint32_t g = 0; g < patches.groups().size(); ++g)
    if (patches.groups()[g].name == name) return g;
  ADD_FAILURE() << "no group " << name;
  return 0;
}

TEST(GroupOverlay, HoldsTheGroupsTrianglesAsGroupSurfaceFindsThem) {
  const Sheet s = read_sheet();
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(s.mesh, &groups, s.patches, true, &s.neighbors).ok());
  std::vector<uint32_t> all;
  for (uint32_t g = 0; g < s.patches.groups().size(); ++g) all.push_back(g);
  const render::GroupOverlay overlay =
      render::build_group_overlay(s.mesh, s.neighbors, s.patches, all, {});
  ASSERT_EQ(overlay.groups.size(), 3u);
  size_t vertices = 0;
  for (const render::GroupOverlay::Group& g : overlay.groups) {
    const SurfacePatches::Group& input = s.patches.groups()[g.index];
    EXPECT_EQ(g.label, input.name);
    EXPECT_EQ(g.first, vertices);
    // Every triangle drawn (nothing hidden), as many as group_surface() puts in it.
    size_t expected = 0;
    for (const SurfaceGroup& written : groups.groups)
      if (written.tag == input.tag) expected = written.triangles.size();
    EXPECT_GT(expected, 0u) << g.label;
    EXPECT_EQ(g.triangles, expected) << g.label;
    EXPECT_EQ(g.count, 3 * expected) << g.label;
    for (size_t v = g.first; v < g.first + g.count; ++v)
      EXPECT_EQ(overlay.vertices[v].material, g.index);
    vertices += g.count;
  }
  EXPECT_EQ(overlay.vertices.size(), vertices);
  // Only the groups asked for, each in its own colour.
  const uint32_t sheet = group_index(s.patches, "sheet");
  const render::GroupOverlay one =
      render::build_group_overlay(s.mesh, s.neighbors, s.patches, {sheet}, {});
  ASSERT_EQ(one.groups.size(), 1u);
  EXPECT_EQ(one.groups[0].color, render::surface_group_rgb(sheet));
  EXPECT_NE(render::surface_group_rgb(0), render::surface_group_rgb(1));
}

// A group's triangles with no shown tet on either side are left out (counted still).
TEST(GroupOverlay, LeavesOutWhatIsHiddenOrCutAway) {
  const Sheet s = read_sheet();
  const uint32_t sheet = group_index(s.patches, "sheet");
  render::SurfaceFilter filter;
  const render::GroupOverlay whole =
      render::build_group_overlay(s.mesh, s.neighbors, s.patches, {sheet}, filter);
  ASSERT_GT(whole.groups[0].count, 0u);
  filter.hidden_materials = {1};
  const render::GroupOverlay hidden =
      render::build_group_overlay(s.mesh, s.neighbors, s.patches, {sheet}, filter);
  EXPECT_EQ(hidden.groups[0].count, 0u);
  EXPECT_EQ(hidden.groups[0].triangles, whole.groups[0].triangles);
  // The sheet spans 0.5 <= x <= 1.5: a cut at x = 1 keeps some of it, one at x = 0.2 none.
  filter.hidden_materials.clear();
  filter.cut = true;
  filter.cut_plane = {{1, 0, 0}, 1.0};
  const size_t half =
      render::build_group_overlay(s.mesh, s.neighbors, s.patches, {sheet}, filter).groups[0].count;
  EXPECT_GT(half, 0u);
  EXPECT_LT(half, whole.groups[0].count);
  filter.cut_plane = {{1, 0, 0}, 0.2};
  EXPECT_EQ(
      render::build_group_overlay(s.mesh, s.neighbors, s.patches, {sheet}, filter).groups[0].count,
      0u);
}

}  // namespace
}  // namespace tetlod
