// Adjacency, boundary/interface extraction and vertex classification on grids.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "core/adjacency.h"
#include "core/classify.h"
#include "core/surface.h"
#include "core/test_meshes.h"
#include "core/validate.h"

namespace tetlod {
namespace {

TEST(Adjacency, VertexTetsMatchBruteForce) {
  const TetMesh mesh = test::make_grid_mesh(3, 2, 2, [](int, int, int) { return 1; });
  const VertexTets vt = build_vertex_tets(mesh);
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    std::vector<uint32_t> expected;
    for (uint32_t t = 0; t < mesh.tet_count(); ++t)
      if (std::count(mesh.tets[t].begin(), mesh.tets[t].end(), v)) expected.push_back(t);
    EXPECT_EQ(std::vector<uint32_t>(vt.begin(v), vt.end(v)), expected) << "vertex " << v;
  }
}

TEST(Adjacency, FaceNeighborsAreSymmetricAndShareThreeVertices) {
  const TetMesh mesh = test::make_grid_mesh(3, 2, 2, [](int, int, int) { return 1; });
  std::vector<uint32_t> nb;
  ASSERT_EQ(build_face_neighbors(mesh, &nb).kind, FaceProblem::Kind::kNone);
  size_t boundary = 0;
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    for (int i = 0; i < 4; ++i) {
      const uint32_t o = nb[4 * t + i];
      if (o == kInvalidIndex) {
        ++boundary;
        continue;
      }
      // The neighbour has the three face vertices and not our opposite corner.
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh.tets[t][kTetFace[i][k]];
        EXPECT_TRUE(std::count(mesh.tets[o].begin(), mesh.tets[o].end(), v));
      }
      EXPECT_FALSE(std::count(mesh.tets[o].begin(), mesh.tets[o].end(), mesh.tets[t][i]));
      EXPECT_EQ(std::count(nb.begin() + 4 * o, nb.begin() + 4 * o + 4, t), 1);
    }
  }
  EXPECT_EQ(boundary, 2u * 2 * (3 * 2 + 2 * 2 + 3 * 2));  // two triangles per boundary square
}

TEST(Surface, BoundaryAndInterfaceTrianglesAreOrientedFromInnerToOuter) {
  const int n = 2;
  const TetMesh mesh =
      test::make_grid_mesh(2 * n, n, n, [&](int i, int, int) { return i < n ? 1 : 2; });
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const std::vector<SurfaceTriangle> surface = extract_surface(mesh, adjacency.tet_neighbors);
  std::map<std::pair<int, int>, int> per_pair;
  for (const SurfaceTriangle& s : surface) {
    ++per_pair[{s.inner, s.outer}];
    EXPECT_EQ(mesh.materials[s.tet], s.inner);
    // The tet's opposite corner lies behind the triangle.
    const Vec3& a = mesh.positions[s.v[0]];
    const Vec3 normal = cross(mesh.positions[s.v[1]] - a, mesh.positions[s.v[2]] - a);
    EXPECT_LT(dot(normal, mesh.positions[mesh.tets[s.tet][s.corner]] - a), 0);
    if (s.outer == 2) {
      EXPECT_GT(normal.x, 0);  // the interface x = n faces material 2
    }
  }
  EXPECT_EQ((per_pair[{1, 2}]), 2 * n * n);
  EXPECT_EQ((per_pair[{1, kOutsideMaterial}]), 2 * (n * n + 4 * n * n));
  EXPECT_EQ((per_pair[{2, kOutsideMaterial}]), 2 * (n * n + 4 * n * n));
  EXPECT_EQ(per_pair.size(), 3u);
}

size_t count_kind(const Classification& c, FeatureKind k) {
  return static_cast<size_t>(std::count(c.kind.begin(), c.kind.end(), k));
}

TEST(Classify, TwoMaterialBoxHasTwelveCornersAndItsJunctionCurves) {
  for (int n : {1, 2, 3}) {
    const TetMesh mesh =
        test::make_grid_mesh(2 * n, n, n, [&](int i, int, int) { return i < n ? 1 : 2; });
    const MeshAdjacency adjacency = build_adjacency(mesh);
    const Classification c =
        classify_vertices(mesh, extract_surface(mesh, adjacency.tet_neighbors));
    // 8 box corners + 4 where the interface square meets the box edges along x.
    EXPECT_EQ(count_kind(c, FeatureKind::kCorner), 12u) << "n=" << n;
    // Box edges along x (4 x (2n-2)), along y and z (8 x (n-1)), interface rim (4 x (n-1)).
    EXPECT_EQ(count_kind(c, FeatureKind::kCurve), static_cast<size_t>(20 * n - 20));
    const size_t boundary_vertices =
        (2 * n + 1) * (n + 1) * (n + 1) - (2 * n - 1) * (n - 1) * (n - 1);
    EXPECT_EQ(count_kind(c, FeatureKind::kSurface),
              boundary_vertices - 12 - (20 * n - 20) + (n - 1) * (n - 1));
    EXPECT_EQ(count_kind(c, FeatureKind::kInterior),
              static_cast<size_t>((2 * n - 1) * (n - 1) * (n - 1) - (n - 1) * (n - 1)));
    // Feature edges: 12 box edges and the 4 interface rim edges, split into grid segments.
    EXPECT_EQ(c.feature_edges.size(), static_cast<size_t>(4 * 2 * n + 8 * n + 4 * n));
  }
}

TEST(Classify, CornerOfTheBoxIsACorner) {
  const TetMesh mesh = test::make_grid_mesh(2, 2, 2, [](int, int, int) { return 1; });
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const Classification c = classify_vertices(mesh, extract_surface(mesh, adjacency.tet_neighbors));
  EXPECT_EQ(c.kind[0], FeatureKind::kCorner);
  EXPECT_EQ(c.kind[1], FeatureKind::kCurve);      // middle of an edge
  EXPECT_EQ(c.kind[4], FeatureKind::kSurface);    // middle of the z = 0 face
  EXPECT_EQ(c.kind[13], FeatureKind::kInterior);  // the centre
  EXPECT_EQ(count_kind(c, FeatureKind::kCorner), 8u);
}

TEST(Classify, TwoCubesTouchingAtOnePointPinchTheSurface) {
  // Material 1 in two diagonal cubes of a 2x2x2 grid, material 2 elsewhere: the two
  // material-1 cubes touch only at the centre vertex, whose 1|2 surface is two fans.
  // With a crease angle above 90 degrees the cube edges are no feature edges, so only
  // the two-fan test can make the centre a corner.
  const TetMesh mesh = test::make_grid_mesh(2, 2, 2, [](int i, int j, int k) {
    return (i == 0 && j == 0 && k == 0) || (i == 1 && j == 1 && k == 1) ? 1 : 2;
  });
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const std::vector<SurfaceTriangle> surface = extract_surface(mesh, adjacency.tet_neighbors);
  const Classification c = classify_vertices(mesh, surface, ClassifyOptions{100.0});
  EXPECT_EQ(c.kind[13], FeatureKind::kCorner);
  for (const auto& e : c.feature_edges) EXPECT_TRUE(e[0] != 13 && e[1] != 13);
  // Control: a single material-1 cube's corner at the centre is a smooth surface point.
  const TetMesh one = test::make_grid_mesh(
      2, 2, 2, [](int i, int j, int k) { return i == 0 && j == 0 && k == 0 ? 1 : 2; });
  const MeshAdjacency one_adjacency = build_adjacency(one);
  const Classification c1 = classify_vertices(
      one, extract_surface(one, one_adjacency.tet_neighbors), ClassifyOptions{100.0});
  EXPECT_EQ(c1.kind[13], FeatureKind::kSurface);
}

TEST(Classify, FlatFacesOfAPerturbedGridAreNotCreases) {
  // Moving interior vertices does not change the box's classification.
  TetMesh mesh = test::make_grid_mesh(3, 3, 3, [](int, int, int) { return 1; });
  mesh.positions[21].x += 0.2;  // (1,1,1)
  mesh.positions[22].y -= 0.1;  // (2,1,1)
  ValidationReport report;
  ASSERT_TRUE(validate_mesh(&mesh, "grid", {}, &report));
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const Classification c = classify_vertices(mesh, extract_surface(mesh, adjacency.tet_neighbors));
  EXPECT_EQ(count_kind(c, FeatureKind::kCorner), 8u);
  EXPECT_EQ(count_kind(c, FeatureKind::kCurve), 12u * 2);
  EXPECT_EQ(count_kind(c, FeatureKind::kInterior), 8u);
}

}  // namespace
}  // namespace tetlod
