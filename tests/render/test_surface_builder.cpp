// Exact tests of the drawn faces on a hand-built two-material grid.
#include <gtest/gtest.h>

#include <limits>

#include "core/adjacency.h"
#include "core/test_meshes.h"
#include "render/snapshot.h"
#include "render/surface_builder.h"

namespace tetlod::render {
namespace {

// 4 x 2 x 2 unit cubes of 6 tets each: material 1 for x < 2, material 2 for x > 2.
PreparedMesh grid() {
  return prepare_mesh(test::make_grid_mesh(4, 2, 2, [](int i, int, int) { return i < 2 ? 1 : 2; }));
}

size_t triangles(const SurfaceBuffers& b) {
  return b.triangles.size() / 3;
}

TEST(SurfaceBuilder, BoundaryOfTheWholeMesh) {
  const PreparedMesh mesh = grid();
  SurfaceBuffers b;
  build_surface(mesh.surface_input(), {}, &b);
  // 2 * (4*2 + 4*2 + 2*2) unit squares, 2 triangles each; interfaces between two
  // visible tets are never drawn.
  EXPECT_EQ(triangles(b), 80u);
  EXPECT_EQ(b.visible_tets, 96u);
  EXPECT_EQ(b.visible_materials, (std::vector<int32_t>{1, 2}));
  ASSERT_TRUE(b.has_bounds);
  EXPECT_EQ(b.bounds_max.x, 4);
  // Every triangle faces away from the box centre.
  const Vec3 center{2, 1, 1};
  for (size_t t = 0; t < b.triangles.size(); t += 3) {
    Vec3 p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = {b.triangles[t + k].position[0], b.triangles[t + k].position[1],
              b.triangles[t + k].position[2]};
    const Vec3 normal = cross(p[1] - p[0], p[2] - p[0]);
    EXPECT_GT(dot(normal, (p[0] + p[1] + p[2]) * (1.0 / 3) - center), 0) << "triangle " << t / 3;
  }
}

TEST(SurfaceBuilder, HidingAMaterialShowsTheInterface) {
  const PreparedMesh mesh = grid();
  SurfaceFilter filter;
  filter.hidden_materials = {2};
  SurfaceBuffers b;
  build_surface(mesh.surface_input(), filter, &b);
  EXPECT_EQ(triangles(b), 48u);  // the 2x2x2 block of material 1: 6 sides of 4 squares
  EXPECT_EQ(b.visible_tets, 48u);
  EXPECT_EQ(b.visible_materials, (std::vector<int32_t>{1}));
  for (const SurfaceVertex& v : b.triangles) {
    EXPECT_EQ(v.material, 1u);
    EXPECT_LE(v.position[0], 2.0f);
  }
  EXPECT_EQ(b.bounds_max.x, 2);  // framing follows the shown materials
}

// The largest material id is as good as any: no table is sized by the ids (one
// was, and hiding 2^31 - 1 asked for 2^63 bytes).
TEST(SurfaceBuilder, AnyMaterialIdCanBeHiddenAndListed) {
  constexpr int32_t kLargest = std::numeric_limits<int32_t>::max();
  TetMesh mesh =
      test::make_grid_mesh(4, 2, 2, [](int i, int, int) { return i < 2 ? 1 : kLargest; });
  const PreparedMesh prepared = prepare_mesh(mesh);
  SurfaceBuffers b;
  build_surface(prepared.surface_input(), {}, &b);
  EXPECT_EQ(b.visible_materials, (std::vector<int32_t>{1, kLargest}));
  SurfaceFilter filter;
  filter.hidden_materials = {kLargest, 7, kLargest};
  build_surface(prepared.surface_input(), filter, &b);
  EXPECT_EQ(triangles(b), 48u);
  EXPECT_EQ(b.visible_materials, (std::vector<int32_t>{1}));
  filter.hidden_materials = {1};
  build_surface(prepared.surface_input(), filter, &b);
  EXPECT_EQ(triangles(b), 48u);
  EXPECT_EQ(b.visible_materials, (std::vector<int32_t>{kLargest}));
}

TEST(SurfaceBuilder, RetiredTetsAreNotDrawn) {
  const PreparedMesh mesh = grid();
  std::vector<uint8_t> alive(mesh.mesh.tet_count());
  for (size_t i = 0; i < alive.size(); ++i) alive[i] = mesh.mesh.materials[i] == 1;
  SurfaceInput input = mesh.surface_input();
  input.alive = alive.data();
  SurfaceBuffers b;
  build_surface(input, {}, &b);
  EXPECT_EQ(triangles(b), 48u);
}

TEST(SurfaceBuilder, CutKeepsWholeTetsAndDrawsTheExposedFaces) {
  const PreparedMesh mesh = grid();
  SurfaceFilter filter;
  filter.cut = true;
  filter.cut_plane = {{1, 0, 0}, 2.0};  // keeps centroids with x <= 2
  SurfaceBuffers b;
  build_surface(mesh.surface_input(), filter, &b);
  EXPECT_EQ(triangles(b), 48u);
  EXPECT_EQ(b.bounds_max.x, 4);  // framing ignores the cut, so moving it keeps the view
  // The plane through the middle of the first column of cubes: tets are kept whole,
  // so the exposed surface is jagged but closed: every edge is used an even number
  // of times.
  filter.cut_plane = {{1, 0, 0}, 0.5};
  build_surface(mesh.surface_input(), filter, &b);
  EXPECT_GT(b.visible_tets, 0u);
  EXPECT_LT(b.visible_tets, 24u);
  EXPECT_EQ(triangles(b) % 2, 0u);
  // A cut that keeps nothing draws nothing.
  filter.cut_plane = {{1, 0, 0}, -1};
  build_surface(mesh.surface_input(), filter, &b);
  EXPECT_EQ(triangles(b), 0u);
  EXPECT_EQ(b.visible_tets, 0u);
  EXPECT_TRUE(b.visible_materials.empty());
}

TEST(SurfaceBuilder, HighlightTakesEveryFaceOfTheLowStretchTets) {
  const PreparedMesh mesh = grid();
  SurfaceFilter filter;
  filter.highlight = true;
  filter.highlight_below = 0.01;  // the Kuhn tets all have stretch ~0.6
  SurfaceBuffers b;
  build_surface(mesh.surface_input(), filter, &b);
  EXPECT_EQ(b.highlighted_tets, 0u);
  EXPECT_TRUE(b.highlight.empty());
  filter.highlight_below = 1.0;
  filter.hidden_materials = {1};
  build_surface(mesh.surface_input(), filter, &b);
  EXPECT_EQ(b.highlighted_tets, 48u);
  EXPECT_EQ(b.highlight.size(), 48u * 4 * 3);
  for (const SurfaceVertex& v : b.highlight) EXPECT_EQ(v.material, 2u);
}

TEST(SurfaceBuilder, VerticesCarryTheirTetsStretch) {
  const PreparedMesh mesh = grid();
  SurfaceBuffers b;
  build_surface(mesh.surface_input(), {}, &b);
  for (const SurfaceVertex& v : b.triangles) {
    EXPECT_GT(v.stretch, 0.5f);
    EXPECT_LT(v.stretch, 0.8f);
  }
}

}  // namespace
}  // namespace tetlod::render
