#include <gtest/gtest.h>

#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/metrics.h"
#include "core/test_meshes.h"
#include "core/validate.h"

namespace tetlod {
namespace {

Status validate(TetMesh* mesh, ValidationReport* report = nullptr,
                const std::vector<uint32_t>& lines = {}) {
  ValidationReport local;
  return validate_mesh(mesh, "m.mesh", lines, report ? report : &local);
}

TEST(Validate, AcceptsGridAndKeepsIt) {
  TetMesh mesh = test::make_grid_mesh(2, 2, 2, [](int i, int, int) { return i; });
  const TetMesh before = mesh;
  ValidationReport report;
  ASSERT_TRUE(validate(&mesh, &report)) << validate(&mesh).message();
  EXPECT_EQ(report.reoriented_tets, 0u);
  EXPECT_EQ(report.removed_unused_vertices, 0u);
  EXPECT_EQ(mesh.tets, before.tets);
  EXPECT_EQ(mesh.positions.size(), before.positions.size());
}

// Two cubes meshed apart: the vertices of the face they touch at are there twice.
// The mesh is valid (each cube is), and the repeated vertices are counted.
TEST(Validate, CountsVerticesAtThePositionOfAnother) {
  TetMesh mesh = test::make_grid_mesh(2, 1, 1, [](int, int, int) { return 1; });
  ValidationReport report;
  ASSERT_TRUE(validate(&mesh, &report));
  EXPECT_EQ(report.coincident_vertices, 0u);

  TetMesh apart = test::make_grid_mesh(1, 1, 1, [](int, int, int) { return 1; });
  const size_t n = apart.positions.size();
  const size_t tets = apart.tet_count();
  // The second cube at x in [-1, 0], its face x = 0 written as -0.
  for (size_t v = 0; v < n; ++v) {
    Vec3 p = apart.positions[v] - Vec3{1, 0, 0};
    if (p.x == 0) p.x = -0.0;
    apart.positions.push_back(p);
  }
  for (size_t t = 0; t < tets; ++t) {
    Tet tet = apart.tets[t];
    for (uint32_t& v : tet) v += uint32_t(n);
    apart.tets.push_back(tet);
    apart.materials.push_back(2);
  }
  ASSERT_TRUE(validate(&apart, &report));
  EXPECT_EQ(report.coincident_vertices, 4u);  // the four corners of the face x = 0
  EXPECT_EQ(report.coincident_position.x, 0);
}

// A tet with no volume, or so little next to its longest edge that its shape is lost
// in rounding, is refused, and the message says which (a nearly flat tet was called
// "zero volume"; found by a hostile-input test).
TEST(Validate, FlatTetsAreNamedForWhatTheyAre) {
  TetMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0}};
  mesh.tets = {{0, 1, 2, 3}};
  mesh.materials = {1};
  TetMesh flat = mesh;
  EXPECT_EQ(validate(&flat).message(), "m.mesh: tetrahedron 1 is degenerate (zero volume)");
  TetMesh nearly = mesh;
  nearly.positions[3].z = 1e-13;
  EXPECT_EQ(validate(&nearly).message(),
            "m.mesh: tetrahedron 1 is degenerate (nearly flat: its volume is 5.89e-15 of its "
            "longest edge cubed, below 1.7e-13)");
  TetMesh thin = mesh;
  thin.positions[3].z = 1e-9;
  EXPECT_TRUE(validate(&thin).ok());
  // With the tet's line ("path:7: "), or without one where a binary reader gives 0
  // (a binary .vtu's said "path:0: ").
  ValidationReport report;
  flat = mesh;
  EXPECT_EQ(validate_mesh(&flat, "m.mesh", {7}, &report).message(),
            "m.mesh:7: tetrahedron 1 is degenerate (zero volume)");
  flat = mesh;
  EXPECT_EQ(validate_mesh(&flat, "m.vtu", {0}, &report).message(),
            "m.vtu: tetrahedron 1 is degenerate (zero volume)");
}

TEST(Validate, ReorientsNegativeTets) {
  TetMesh mesh = test::make_grid_mesh(1, 1, 1, [](int, int, int) { return 0; });
  std::swap(mesh.tets[0][0], mesh.tets[0][1]);
  std::swap(mesh.tets[3][2], mesh.tets[3][3]);
  ValidationReport report;
  ASSERT_TRUE(validate(&mesh, &report));
  EXPECT_EQ(report.reoriented_tets, 2u);
  for (const Tet& t : mesh.tets) EXPECT_GT(signed_volume6(mesh, t), 0);
}

TEST(Validate, DropsUnusedVertices) {
  TetMesh mesh = test::make_single_tet();
  mesh.positions.insert(mesh.positions.begin(), Vec3{5, 5, 5});
  for (uint32_t& v : mesh.tets[0]) ++v;
  ValidationReport report;
  ASSERT_TRUE(validate(&mesh, &report));
  EXPECT_EQ(report.removed_unused_vertices, 1u);
  ASSERT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.positions[0], (Vec3{0, 0, 0}));
  EXPECT_EQ(mesh.tets[0], (Tet{0, 1, 2, 3}));
}

// The face neighbours the checks build are handed over on request, and are those of
// the mesh as validated (its unused vertices dropped, its tets reoriented); so are
// those read_mesh() keeps in ReadInfo when asked, and only then.
TEST(Validate, HandsOverTheFaceNeighboursItBuilds) {
  TetMesh mesh = test::make_grid_mesh(
      2, 2, 1, [](int i, int j, int k) { return 1 + (i + j + k) % 2; }, 1.0);
  mesh.positions.insert(mesh.positions.begin(), Vec3{50, 50, 50});
  for (Tet& t : mesh.tets)
    for (uint32_t& v : t) ++v;
  std::swap(mesh.tets[3][0], mesh.tets[3][1]);
  ValidationReport report;
  std::vector<uint32_t> handed;
  ASSERT_TRUE(validate_mesh(&mesh, "m.mesh", {}, &report, &handed).ok());
  EXPECT_EQ(report.removed_unused_vertices, 1u);
  EXPECT_EQ(report.reoriented_tets, 1u);
  std::vector<uint32_t> built;
  ASSERT_EQ(build_face_neighbors(mesh, &built).kind, FaceProblem::Kind::kNone);
  ASSERT_EQ(handed.size(), 4 * mesh.tet_count());
  EXPECT_EQ(handed, built);

  const std::string box2 = std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh";
  TetMesh read;
  ReadInfo plain, keeping;
  keeping.keep_face_neighbors = true;
  ASSERT_TRUE(read_mesh(box2, &read, &plain).ok());
  EXPECT_TRUE(plain.face_neighbors.empty());
  ASSERT_TRUE(read_mesh(box2, &read, &keeping).ok());
  ASSERT_EQ(build_face_neighbors(read, &built).kind, FaceProblem::Kind::kNone);
  EXPECT_EQ(keeping.face_neighbors, built);
}

void expect_error(TetMesh mesh, const std::string& fragment,
                  const std::vector<uint32_t>& lines = {}) {
  const Status s = validate(&mesh, nullptr, lines);
  ASSERT_FALSE(s.ok()) << "expected an error containing '" << fragment << "'";
  EXPECT_NE(s.message().find(fragment), std::string::npos) << s.message();
}

// A regular tet measures as regular at any accepted scale; beyond [1e-60, 1e60] the
// face areas would under- or overflow (stretch 0), so such meshes are refused.
TEST(Validate, ScalesWhereTheMetricsAreExact) {
  TetMesh unit = test::make_single_tet();
  unit.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (const double scale : {1e-60, 1e-30, 1.0, 1e30, 1e59}) {  // edges 2.83 * scale
    TetMesh m = unit;
    for (Vec3& p : m.positions) p = p * scale;
    ASSERT_TRUE(validate(&m)) << scale;
    EXPECT_NEAR(tet_shape(m, m.tets[0]).stretch, 1.0, 1e-12) << scale;
  }
  for (const double scale : {1e-90, 1e-62, 1e62, 1e100}) {
    TetMesh m = unit;
    for (Vec3& p : m.positions) p = p * scale;
    expect_error(m, "outside [1e-60, 1e60] where TetLOD's metrics are exact");
  }
}

TEST(Validate, RejectsBadMeshesWithLineNumbers) {
  TetMesh m = test::make_single_tet();
  m.tets[0][2] = 7;
  expect_error(m, "m.mesh:42: tetrahedron 1 uses vertex 8", {42});

  m = test::make_single_tet();
  m.tets[0][2] = m.tets[0][1];
  // By the node's position: its number here is not the file's id (a hostile-input
  // tester read "repeats vertex 3" of a file whose nodes were numbered 10 to 50).
  const Vec3 p = m.positions[m.tets[0][1]];
  char at[128];
  std::snprintf(at, sizeof at, "repeats vertex: it names the node at (%.17g, %.17g, %.17g) twice",
                p.x, p.y, p.z);
  expect_error(m, at);

  m = test::make_single_tet();
  m.positions[3] = {0.5, 0.5, 0};  // coplanar
  expect_error(m, "m.mesh:9: tetrahedron 1 is degenerate", {9});

  m = test::make_single_tet();
  m.positions[1].y = std::nan("");
  expect_error(m, "non-finite");

  m = test::make_single_tet();
  m.materials[0] = -3;
  expect_error(m, "material id -3");

  m = test::make_single_tet();
  m.materials.push_back(1);
  expect_error(m, "material ids");

  m = test::make_single_tet();
  m.tets.push_back({3, 2, 1, 0});
  m.materials.push_back(1);
  expect_error(m, "tetrahedron 2 duplicates tetrahedron 1");

  expect_error(TetMesh{}, "no tetrahedra");
}

TEST(Validate, RejectsOverlappingAndNonManifoldTets) {
  // Two tets on the same side of face (0,1,2): they overlap.
  TetMesh m = test::make_single_tet();
  m.positions.push_back({0.1, 0.1, 2});
  m.tets.push_back({0, 1, 2, 4});
  m.materials.push_back(1);
  expect_error(m, "overlaps");

  // Three tets around face (0,1,2).
  m = test::make_single_tet();
  m.positions.push_back({0.2, 0.2, -1});
  m.positions.push_back({0.1, 0.1, 2});
  m.tets.push_back({0, 2, 1, 4});
  m.tets.push_back({0, 1, 2, 5});
  m.materials.insert(m.materials.end(), {1, 1});
  expect_error(m, "not a manifold");
}

}  // namespace
}  // namespace tetlod
