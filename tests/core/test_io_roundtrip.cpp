// Every format writes and reads back the same mesh, bit for bit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "core/io/mesh_io.h"
#include "core/metrics.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

struct RoundTripCase {
  const char* file_name;
  int gmsh_version;
  MeshFormat format;
};

const RoundTripCase kRoundTripCases[] = {
    {"m.mesh", 41, MeshFormat::kMedit},        {"m22.msh", 22, MeshFormat::kGmsh22},
    {"m41.msh", 41, MeshFormat::kGmsh41},      {"m.node", 41, MeshFormat::kTetGen},
    {"m.vtk", 41, MeshFormat::kVtkLegacy},     {"m.vtu", 41, MeshFormat::kVtu},
    {"m.meshb", 41, MeshFormat::kMeditBinary},
};

void expect_round_trip(const TetMesh& mesh, const std::string& dir) {
  for (const RoundTripCase& c : kRoundTripCases) {
    SCOPED_TRACE(c.file_name);
    const std::string path = dir + "/" + c.file_name;
    WriteOptions options;
    options.gmsh_version = c.gmsh_version;
    ASSERT_TRUE(write_mesh(path, mesh, options).ok());
    TetMesh read;
    ReadInfo info;
    const Status status = read_mesh(path, &read, &info);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(info.format, c.format);
    EXPECT_EQ(info.validation.reoriented_tets, 0u);
    EXPECT_EQ(info.validation.removed_unused_vertices, 0u);
    test::expect_same_mesh(mesh, read);
    test::expect_positive_orientation(read);
  }
}

TEST(IoRoundTrip, CheckMeshPathKnowsTheExtensions) {
  for (const char* path : {"a.mesh", "dir.x/b.MSH", "c.node", "c.ele", "d.vtk", "e.vtu", "f.bdf",
                           "g.nas", "h.inp", "i.meshb"})
    EXPECT_TRUE(check_mesh_path(path).ok()) << path;
  for (const char* path : {"a.txt", "a.tlh", "a.meshc", "mesh", "dir.mesh/file", ""})
    EXPECT_FALSE(check_mesh_path(path).ok()) << path;
}

TEST(IoRoundTrip, HandBuiltMeshWithAwkwardNumbersAndMaterials) {
  const TetMesh mesh = test::make_io_mesh();
  test::expect_positive_orientation(mesh);
  expect_round_trip(mesh, test::output_dir("round_trip_hand_built"));
}

TEST(IoRoundTrip, GridWithManyMaterialsIncludingZero) {
  // Materials 0..4 spread so that Gmsh node blocks and entities are exercised.
  const TetMesh mesh = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int k) { return (i + 2 * j + k) % 5; }, 0.37);
  expect_round_trip(mesh, test::output_dir("round_trip_grid"));
}

TEST(IoRoundTrip, SingleMaterialAboveZero) {
  const TetMesh mesh = test::make_single_tet();
  expect_round_trip(mesh, test::output_dir("round_trip_single"));
}

TEST(IoRoundTrip, ReadingEitherTetGenNameReadsThePair) {
  const std::string dir = test::output_dir("tetgen_pair");
  const TetMesh mesh = test::make_io_mesh();
  ASSERT_TRUE(write_mesh(dir + "/pair.ele", mesh).ok());
  EXPECT_TRUE(std::filesystem::exists(dir + "/pair.node"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/pair.ele"));
  for (const char* name : {"/pair.node", "/pair.ele"}) {
    TetMesh read;
    ASSERT_TRUE(read_mesh(dir + name, &read).ok());
    test::expect_same_mesh(mesh, read);
  }
}

TEST(IoRoundTrip, MeditTextIsTheDocumentedLayout) {
  const std::string dir = test::output_dir("medit_layout");
  ASSERT_TRUE(write_mesh(dir + "/one.mesh", test::make_single_tet()).ok());
  EXPECT_EQ(test::read_text(dir + "/one.mesh"),
            "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
            "0 0 1 0\n\nTetrahedra\n1\n1 2 3 4 1\n\nEnd\n");
}

TEST(IoRoundTrip, VtkFilesCarryStretch) {
  const std::string dir = test::output_dir("vtk_stretch");
  const TetMesh mesh = test::make_io_mesh();
  ASSERT_TRUE(write_mesh(dir + "/m.vtk", mesh).ok());
  ASSERT_TRUE(write_mesh(dir + "/m.vtu", mesh).ok());
  const struct {
    const char* name;
    const char* header;
  } files[] = {{"/m.vtk", "FIELD FieldData 1\nstretch 1 3 double\n"},
               {"/m.vtu", "Name=\"stretch\" format=\"ascii\">"}};
  for (const auto& file : files) {
    const std::string text = test::read_text(dir + file.name);
    const size_t at = text.find(file.header);
    ASSERT_NE(at, std::string::npos) << file.name;
    const char* cursor = text.c_str() + at + std::strlen(file.header);
    for (const Tet& tet : mesh.tets) {
      char* end = nullptr;
      EXPECT_EQ(std::strtod(cursor, &end), tet_shape(mesh, tet).stretch) << file.name;
      cursor = end;
    }
  }
}

TEST(IoRoundTrip, GmshMaterialTagMapping) {
  const std::string dir = test::output_dir("gmsh_tags");
  const TetMesh mesh = test::make_io_mesh();  // materials 0, 7, INT32_MAX
  ASSERT_TRUE(write_mesh(dir + "/m.msh", mesh).ok());
  const std::string text = test::read_text(dir + "/m.msh");
  // Material 0 takes the smallest free positive tag (1); others keep their id.
  EXPECT_NE(text.find("3 1 \"material_0\""), std::string::npos) << text;
  EXPECT_NE(text.find("3 7 \"material_7\""), std::string::npos) << text;
  EXPECT_NE(text.find("3 2147483647 \"material_2147483647\""), std::string::npos) << text;

  // With material 1 taken, material 0 moves to tag 2.
  TetMesh other = mesh;
  other.materials = {0, 1, 3};
  ASSERT_TRUE(write_mesh(dir + "/other.msh", other).ok());
  EXPECT_NE(test::read_text(dir + "/other.msh").find("3 2 \"material_0\""), std::string::npos);
  TetMesh read;
  ASSERT_TRUE(read_mesh(dir + "/other.msh", &read).ok());
  EXPECT_EQ(read.materials, other.materials);
}

TEST(IoRoundTrip, FormatNames) {
  EXPECT_STREQ(format_name(MeshFormat::kMedit), "Medit .mesh");
  EXPECT_STREQ(format_name(MeshFormat::kGmsh22), "Gmsh 2.2 .msh");
  EXPECT_STREQ(format_name(MeshFormat::kGmsh41), "Gmsh 4.1 .msh");
  EXPECT_STREQ(format_name(MeshFormat::kTetGen), "TetGen .node/.ele");
  EXPECT_STREQ(format_name(MeshFormat::kVtkLegacy), "VTK legacy .vtk");
  EXPECT_STREQ(format_name(MeshFormat::kVtu), "VTK XML .vtu");
}

TEST(IoRoundTrip, ExtensionsAreCaseInsensitive) {
  const std::string dir = test::output_dir("upper_case");
  const TetMesh mesh = test::make_single_tet();
  ASSERT_TRUE(write_mesh(dir + "/ONE.MESH", mesh).ok());
  TetMesh read;
  ASSERT_TRUE(read_mesh(dir + "/ONE.MESH", &read).ok());
  test::expect_same_mesh(mesh, read);
}

TEST(IoRoundTrip, RejectsUnknownExtensionsListingSupportedOnes) {
  TetMesh mesh = test::make_single_tet();
  for (const char* path : {"out/mesh.obj", "out/mesh", "out.d/mesh"}) {
    const Status status = write_mesh(path, mesh);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.message().rfind(std::string(path) + ": unknown mesh file extension", 0), 0u)
        << status.message();
    EXPECT_NE(status.message().find(".mesh, .meshb, .msh, .node/.ele, .vtk, .vtu, .bdf/.nas, .inp"),
              std::string::npos);
    EXPECT_FALSE(read_mesh(path, &mesh).ok());
  }
}

TEST(IoRoundTrip, RefusesToWriteInvalidMeshes) {
  const std::string dir = test::output_dir("invalid_write");
  TetMesh mesh = test::make_single_tet();
  mesh.materials.clear();
  EXPECT_FALSE(write_mesh(dir + "/a.mesh", mesh).ok());
  mesh = test::make_single_tet();
  mesh.tets[0][2] = 17;
  EXPECT_FALSE(write_mesh(dir + "/a.mesh", mesh).ok());
  mesh = test::make_single_tet();
  mesh.materials[0] = -1;
  EXPECT_FALSE(write_mesh(dir + "/a.msh", mesh).ok());
  EXPECT_FALSE(write_mesh(dir + "/a.mesh", TetMesh()).ok());
  WriteOptions options;
  options.gmsh_version = 40;
  EXPECT_FALSE(write_mesh(dir + "/a.msh", test::make_single_tet(), options).ok());
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace tetlod
