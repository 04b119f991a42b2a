// Files written by hand after the conventions of other tools (tests/data): each
// describes the same three-tet solid ABCD, BCDE, ACBF with its own materials.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

struct Sample {
  const char* file;
  MeshFormat format;
  int32_t abcd, bcde, acbf;  // expected materials
  size_t reoriented;
  size_t removed_vertices;
};

const Sample kSamples[] = {
    // Physical tags 5 and 3; the third tet has physical tag 0: its elementary tag 12.
    {"gmsh22_mixed.msh", MeshFormat::kGmsh22, 5, 3, 12, 1, 1},
    // Volume 1 is the physical group named "material_0", volume 2 has physical 21,
    // volume 3 has none: its entity tag.
    {"gmsh41_entities.msh", MeshFormat::kGmsh41, 0, 21, 3, 0, 0},
    {"medit_sections.mesh", MeshFormat::kMedit, 4, 9, 4, 1, 1},
    // Second order: the 12 mid-edge nodes are dropped.
    {"medit_p2.mesh", MeshFormat::kMedit, 7, 8, 7, 0, 12},
    {"tetgen0.node", MeshFormat::kTetGen, 1, 2, 1, 0, 0},
    {"tetgen1.ele", MeshFormat::kTetGen, 3, 5, 3, 1, 0},
    {"vtk_mixed.vtk", MeshFormat::kVtkLegacy, 6, 8, 6, 0, 1},
    {"vtk51_field.vtk", MeshFormat::kVtkLegacy, 2, 3, 4, 0, 0},
    {"vtu_mixed.vtu", MeshFormat::kVtu, 11, 12, 13, 0, 0},
};

TEST(IoSamples, ReadFilesInOtherToolsConventions) {
  for (const Sample& sample : kSamples) {
    SCOPED_TRACE(sample.file);
    TetMesh mesh;
    ReadInfo info;
    const Status status = read_mesh(test::data_path(sample.file), &mesh, &info);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(info.format, sample.format);
    EXPECT_EQ(mesh.tet_count(), 3u);
    EXPECT_EQ(mesh.vertex_count(), 6u);
    EXPECT_EQ(test::canonical_tets(mesh), test::sample_tets(sample.abcd, sample.bcde, sample.acbf));
    EXPECT_EQ(info.validation.reoriented_tets, sample.reoriented);
    EXPECT_EQ(info.validation.removed_unused_vertices, sample.removed_vertices);
    test::expect_positive_orientation(mesh);
  }
}

// Line, point and other elements that are neither tets nor triangles are named in a
// note by every reader (Medit's Edges, Nastran's CBAR, Abaqus' T3D2 and CPS4 were
// dropped without a word).
TEST(IoSamples, LineElementsAreNoted) {
  const struct {
    MeshFormat format;
    const char* name;
    std::string text;
    const char* note;
  } files[] = {
      {MeshFormat::kMedit, "m.mesh",
       "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
       "0 0 1 0\nTetrahedra\n1\n1 2 3 4 1\nEdges\n2\n1 2 5\n2 3 5\nEnd\n",
       "2 edges (Edges) are not kept"},
      {MeshFormat::kNastran, "m.bdf",
       "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n"
       "CTETRA,1,3,1,2,3,4\nCBAR,2,7,1,2\nCONM2,3,1\nENDDATA\n",
       "skipped the elements 1 CBAR, 1 CONM2"},
      {MeshFormat::kAbaqus, "m.inp",
       "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n"
       "*ELEMENT, TYPE=C3D4, ELSET=solid\n1, 1, 2, 3, 4\n"
       "*ELEMENT, TYPE=T3D2, ELSET=edge\n2, 1, 2\n"
       "*ELEMENT, TYPE=CPS4, ELSET=quads\n3, 1, 2, 3, 4\n",
       "skipped the elements 1 CPS4, 1 T3D2, and their element sets"},
  };
  for (const auto& f : files) {
    SCOPED_TRACE(f.name);
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_mesh_from_memory(f.text, f.format, f.name, &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(mesh.tet_count(), 1u);
    EXPECT_TRUE(std::any_of(info.notes.begin(), info.notes.end(), [&](const std::string& n) {
      return n.find(f.note) != std::string::npos;
    })) << ::testing::PrintToString(info.notes);
  }
}

// Cells the readers skip, or read by their corners, are named in a note.
TEST(IoSamples, SkippedCellsAreNoted) {
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("vtk_mixed.vtk"), &mesh, &info).ok());
  ASSERT_FALSE(info.notes.empty());
  EXPECT_NE(info.notes[0].find("skipped 1 hexahedra: TetLOD reads tetrahedra only"),
            std::string::npos)
      << info.notes[0];
  // A quadratic tet (type 24) and a wedge (13) in a legacy file.
  const std::string vtk =
      "# vtk DataFile Version 3.0\nm\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 10 double\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 0.5 0 0 0.5 0.5 0 0 0.5 0 0 0 0.5 0.5 0 0.5 0 0.5 0.5\n"
      "CELLS 2 18\n10 0 1 2 3 4 5 6 7 8 9\n6 0 1 2 3 4 5\nCELL_TYPES 2\n24\n13\n";
  ASSERT_TRUE(read_mesh_from_memory(vtk, MeshFormat::kVtkLegacy, "m.vtk", &mesh, &info).ok());
  ASSERT_EQ(info.notes.size(), 3u);  // and: no cell arrays, so material 0
  EXPECT_NE(info.notes[2].find("the file has no cell arrays"), std::string::npos) << info.notes[2];
  EXPECT_NE(info.notes[0].find("skipped 1 wedges"), std::string::npos) << info.notes[0];
  EXPECT_NE(info.notes[1].find("1 quadratic (10-node) tetrahedra were read as 4-node ones"),
            std::string::npos)
      << info.notes[1];
  EXPECT_EQ(mesh.tet_count(), 1u);
  // Lagrange (71) and Bezier (78) tets of any order are read by their corners (they were
  // skipped); one whose point count is no tet's is an error naming it; vertices and lines
  // are noted as not kept (they were dropped without a word).
  const std::string lagrange =
      "# vtk DataFile Version 3.0\nm\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 11 double\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 0.5 0 0 0.5 0.5 0 0 0.5 0 0 0 0.5 0.5 0 0.5 0 0.5 0.5 1 1 1\n"
      "CELLS 4 21\n10 0 1 2 3 4 5 6 7 8 9\n4 1 2 3 10\n1 4\n2 0 1\nCELL_TYPES 4\n71\n78\n1\n3\n";
  ASSERT_TRUE(read_mesh_from_memory(lagrange, MeshFormat::kVtkLegacy, "m.vtk", &mesh, &info).ok());
  EXPECT_EQ(mesh.tet_count(), 2u);
  const auto noted = [&info](const std::string& part) {
    return std::any_of(info.notes.begin(), info.notes.end(),
                       [&](const std::string& n) { return n.find(part) != std::string::npos; });
  };
  EXPECT_TRUE(noted("2 Lagrange or Bezier tetrahedra were read as 4-node ones"))
      << ::testing::PrintToString(info.notes);
  EXPECT_TRUE(noted("2 vertex and line cells are not kept"))
      << ::testing::PrintToString(info.notes);
  // A quadratic-linear wedge (31) is a wedge, a quadratic polygon (36) a surface cell,
  // and a type VTK has not got (99) is named by its number (all three were dropped
  // without a word).
  std::string others = lagrange;
  others.replace(others.find("CELL_TYPES 4\n71\n78\n1\n3\n"), 25, "CELL_TYPES 4\n71\n31\n36\n99\n");
  ASSERT_TRUE(read_mesh_from_memory(others, MeshFormat::kVtkLegacy, "m.vtk", &mesh, &info).ok());
  EXPECT_TRUE(noted("skipped 1 wedges")) << ::testing::PrintToString(info.notes);
  EXPECT_EQ(info.surface_elements_not_kept, 1u);
  EXPECT_TRUE(noted("cells of types TetLOD does not know are not kept (type 99: 1)"))
      << ::testing::PrintToString(info.notes);
  std::string eight = lagrange;
  eight.replace(eight.find("CELLS 4 21\n10 0 1 2 3 4 5 6 7 8 9"), 33,
                "CELLS 4 19\n8 0 1 2 3 4 5 6 7");
  const Status wrong = read_mesh_from_memory(eight, MeshFormat::kVtkLegacy, "m.vtk", &mesh, &info);
  EXPECT_NE(wrong.message().find("cell 0 of type 71 has 8 points"), std::string::npos)
      << wrong.message();
  // Medit: a Prisms section beside the tets is noted.
  const std::string medit =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
      "0 0 1 0\n";
  ASSERT_TRUE(read_mesh_from_memory(medit + "Tetrahedra\n1\n1 2 3 4 1\nPrisms\n1\n"
                                            "1 2 3 1 2 3 2\nEnd\n",
                                    MeshFormat::kMedit, "m.mesh", &mesh, &info)
                  .ok());
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_NE(info.notes[0].find("skipped 1 Prisms: TetLOD reads 4-node tetrahedra only"),
            std::string::npos)
      << info.notes[0];
  // TetrahedraP2 (Gmsh's second-order export) are read by their corners, and TrianglesP2
  // are surface groups by theirs; the mid-edge vertices are dropped as unused.
  const std::string p2 =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n10\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
      "0 0 1 0\n0.5 0 0 0\n0.5 0.5 0 0\n0 0.5 0 0\n0 0 0.5 0\n0.5 0 0.5 0\n0 0.5 0.5 0\n"
      "TrianglesP2\n1\n1 3 2 7 6 5 4\n";
  ASSERT_TRUE(read_mesh_from_memory(p2 + "TetrahedraP2\n1\n1 2 3 4 5 6 7 8 9 10 3\nEnd\n",
                                    MeshFormat::kMedit, "m.mesh", &mesh, &info)
                  .ok());
  ASSERT_EQ(mesh.tet_count(), 1u);
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.materials[0], 3);
  EXPECT_EQ(info.validation.removed_unused_vertices, 6u);
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_EQ(info.notes[0],
            "1 TetrahedraP2 (10-node) were read as 4-node tetrahedra (by their corners; their "
            "mid-edge points are dropped)");
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].tag, 4);
  ASSERT_EQ(info.surface_groups[0].triangles.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].triangles[0][1].y, 1.0);
  // A mid-edge index out of range is an error on its line.
  const Status bad = read_mesh_from_memory(p2 + "TetrahedraP2\n1\n1 2 3 4 5 6 7 8 9 0 3\nEnd\n",
                                           MeshFormat::kMedit, "m.mesh", &mesh, &info);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("m.mesh:20: vertex index 0 is out of range"), std::string::npos)
      << bad.message();
  // Nastran's CPENTA and Abaqus's C3D6 beside a tet.
  const std::string nastran =
      "BEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n"
      "GRID,5,,1.,1.,1.\nGRID,6,,1.,1.,0.\nCTETRA,1,1,1,2,3,4\nCPENTA,2,2,1,2,3,4,5,6\n"
      "ENDDATA\n";
  ASSERT_TRUE(read_mesh_from_memory(nastran, MeshFormat::kNastran, "m.bdf", &mesh, &info).ok());
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_NE(info.notes[0].find("skipped the solid elements 1 CPENTA"), std::string::npos)
      << info.notes[0];
  const std::string abaqus =
      "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n5,1,1,1\n6,1,1,0\n"
      "*ELEMENT,TYPE=C3D4,ELSET=A\n1,1,2,3,4\n*ELEMENT,TYPE=C3D6,ELSET=B\n2,1,2,3,4,5,6\n";
  ASSERT_TRUE(read_mesh_from_memory(abaqus, MeshFormat::kAbaqus, "m.inp", &mesh, &info).ok());
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_NE(info.notes[0].find("skipped the elements 1 C3D6"), std::string::npos) << info.notes[0];
}

TEST(IoSamples, GmshOrdersVerticesByNodeTagAndTetsByElementTag) {
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh22_mixed.msh"), &mesh).ok());
  // Node tags 3 (B), 7 (D), 10 (A), 42 (E), 100 (F), 9000000000 (C); 55 is unused.
  const std::vector<Vec3> expected = {{1, 0, 0}, {0, 0, 1},  {0, 0, 0},
                                      {1, 1, 1}, {0, 0, -1}, {0, 1, 0}};
  ASSERT_EQ(mesh.positions.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(mesh.positions[i], expected[i]) << i;
  // Element tags 4 (ABCD, material 5), 5 (ACBF, 12), 7 (BCDE, 3).
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{5, 12, 3}));
}

TEST(IoSamples, TetGenTenNodeTetsGiveTheirCorners) {
  const std::string node = "6 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n6 0 0 -1\n";
  // Mid-edge nodes are not checked by TetLOD; reuse corners for them.
  const std::string ele = "2 10 1\n1 1 2 3 4 1 1 1 1 1 1 7\n2 2 3 4 5 2 2 2 2 2 2 8\n";
  TetMesh mesh;
  ReadInfo info;
  const Status status = read_tetgen_from_memory(node, ele, "t.node", "t.ele", &mesh, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(mesh.tets, (std::vector<Tet>{{0, 1, 2, 3}, {1, 2, 3, 4}}));
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{7, 8}));
  // Said, as every other reader says it (it was not).
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_EQ(info.notes[0].rfind("2 10-node tetrahedra (TetGen -o2) were read as 4-node ones", 0),
            0u)
      << info.notes[0];
}

TEST(IoSamples, GmshTenNodeTetsGiveTheirCorners) {
  const std::string text =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
      "$EndNodes\n$Elements\n1\n1 11 2 6 6 1 2 3 4 1 1 1 1 1 1\n$EndElements\n";
  TetMesh mesh;
  const Status status = read_mesh_from_memory(text, MeshFormat::kGmsh22, "t.msh", &mesh);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(mesh.tets, (std::vector<Tet>{{0, 1, 2, 3}}));
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{6}));
}

TEST(IoSamples, VtkWithoutMaterialGivesMaterialZero) {
  const std::string text =
      "# vtk DataFile Version 2.0\nno data\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
  TetMesh mesh;
  const Status status = read_mesh_from_memory(text, MeshFormat::kVtkLegacy, "t.vtk", &mesh);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{0}));
}

TEST(IoSamples, MeditAcceptsWindowsLineEndingsAndMissingEnd) {
  const std::string text =
      "MeshVersionFormatted 2\r\nDimension 3\r\nVertices\r\n4\r\n0 0 0 0\r\n1 0 0 0\r\n"
      "0 1 0 0\r\n0 0 1 0\r\nTetrahedra\r\n1\r\n1 2 3 4 3\r\n";
  TetMesh mesh;
  const Status status = read_mesh_from_memory(text, MeshFormat::kMedit, "t.mesh", &mesh);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{3}));
}

TEST(IoSamples, FailedReadLeavesTheMeshUntouched) {
  TetMesh mesh;
  mesh.positions = {{1, 2, 3}};
  EXPECT_FALSE(read_mesh_from_memory("MeshVersionFormatted 2\nVertices\n1\n0 0 0 0\n",
                                     MeshFormat::kMedit, "t.mesh", &mesh)
                   .ok());
  ASSERT_EQ(mesh.positions.size(), 1u);
  EXPECT_EQ(mesh.positions[0], (Vec3{1, 2, 3}));
}

TEST(IoSamples, MissingFileNamesThePath) {
  TetMesh mesh;
  const Status status = read_mesh("/nonexistent/dir/m.mesh", &mesh);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind("/nonexistent/dir/m.mesh: cannot open", 0), 0u)
      << status.message();
  const Status pair = read_mesh("/nonexistent/dir/m.ele", &mesh);
  EXPECT_EQ(pair.message().rfind("/nonexistent/dir/m.node: cannot open", 0), 0u) << pair.message();
}

}  // namespace
}  // namespace tetlod
