// Files written by other tools (tests/data/other_tools, made by its make.py with
// VTK 9.1 and meshio 5.0 from the bundled box2 model, and by make_freefem.edp with
// FreeFEM 4.9): every encoding and layout they use reads as the mesh they hold, and the
// compressors TetLOD does not read give a clear error.
#include <gtest/gtest.h>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

std::string tool_file(const std::string& name) {
  return test::data_path("other_tools/" + name);
}

TEST(IoOtherTools, BinaryFilesReadAsTheMeshTheyHold) {
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  TetMesh without_materials = box2;
  without_materials.materials.assign(box2.tet_count(), 0);
  const struct {
    const char* file;
    bool materials;  // meshio's .msh, .nas and .inp carry none without tool-specific data
  } files[] = {{"vtu_vtk9_binary_zlib.vtu", true},
               {"vtu_vtk9_binary_none_uint64.vtu", true},
               {"vtu_vtk9_appended_zlib.vtu", true},
               {"vtu_vtk9_appended_none_uint64.vtu", true},
               {"vtu_vtk9_appended_base64.vtu", true},
               {"vtu_meshio_zlib.vtu", true},
               {"vtu_vtk9_ascii.vtu", true},
               {"vtk_vtk9_binary51.vtk", true},
               {"vtk_vtk9_binary42.vtk", true},
               // String arrays (field data and one string per cell), as VTK writes
               // names and records.
               {"vtk_vtk9_strings_ascii.vtk", true},
               {"vtk_vtk9_strings_binary.vtk", true},
               {"vtu_vtk9_strings_ascii.vtu", true},
               {"vtu_vtk9_strings_appended.vtu", true},
               {"vtk_meshio_binary.vtk", true},
               // meshio from Gmsh and Medit files: the material is "gmsh:physical",
               // "medit:ref" (next to "gmsh:geometrical" and other integer arrays).
               {"vtu_meshio_from_gmsh.vtu", true},
               {"vtk_meshio_from_gmsh.vtk", true},
               {"vtu_meshio_from_medit.vtu", true},
               // ... from TetGen and Nastran files TetLOD wrote: "tetgen:ref",
               // "nastran:ref"; and meshio's binary 4.2 layout, whose 64-bit integers
               // are typed "long".
               {"vtu_meshio_from_tetgen.vtu", true},
               {"vtu_meshio_from_nastran.vtu", true},
               {"vtk42_meshio_binary_from_medit.vtk", true},
               // meshio's Medit writer: one Tetrahedra section per cell block.
               {"mesh_meshio_two_blocks.mesh", true},
               // meshio's Medit binary writer: version 3 (4-byte integers), or 4 (8-byte
               // integers) for 64-bit cell arrays.
               {"meshb_meshio_v3.meshb", true},
               {"meshb_meshio_v4.meshb", true},
               {"msh_meshio_binary.msh", false},
               {"msh22_meshio_binary.msh", false},
               {"nas_meshio.nas", false},
               {"inp_meshio.inp", false}};
  for (const auto& f : files) {
    SCOPED_TRACE(f.file);
    TetMesh mesh;
    const Status s = read_mesh(tool_file(f.file), &mesh);
    ASSERT_TRUE(s.ok()) << s.message();
    if (std::string(f.file).find("from_gmsh") != std::string::npos ||
        std::string(f.file).find("two_blocks") != std::string::npos) {
      // Gmsh's numbering of the nodes, or the tets grouped by block: the same tets,
      // materials and coordinates.
      EXPECT_EQ(test::canonical_tets(mesh), test::canonical_tets(box2));
    } else if (std::string(f.file) == "nas_meshio.nas") {
      // meshio writes 10 significant digits (box2's coordinates are exact in them).
      EXPECT_EQ(test::canonical_tets(mesh), test::canonical_tets(without_materials));
    } else {
      test::expect_same_mesh(f.materials ? box2 : without_materials, mesh);
    }
  }
}

// VTK's legacy files with string arrays, cut anywhere: an error naming the file, or
// box2 (without its materials when the cut came before them). A cut inside a string
// array is an error, in text (a string a line) as in binary (each after its length).
TEST(IoOtherTools, LegacyStringArraysCutShortFail) {
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  TetMesh without_materials = box2;
  without_materials.materials.assign(box2.tet_count(), 0);
  for (const char* file : {"vtk_vtk9_strings_ascii.vtk", "vtk_vtk9_strings_binary.vtk"}) {
    SCOPED_TRACE(file);
    const std::string data = test::read_text(tool_file(file));
    const size_t records = data.find("Information%20Records 1 4 string\n");
    ASSERT_NE(records, std::string::npos);
    for (size_t length = 0; length < data.size(); ++length) {
      TetMesh mesh;
      const Status s = read_mesh_from_memory(std::string_view(data).substr(0, length),
                                             MeshFormat::kVtkLegacy, "s.vtk", &mesh);
      if (s.ok()) {
        test::expect_same_mesh(mesh.materials[0] == 0 ? without_materials : box2, mesh);
      } else {
        ASSERT_EQ(s.message().rfind("s.vtk:", 0), 0u) << s.message();
        // Before the records' last string: the four strings do not fit, or the
        // file ends before all four.
        if (length > records + 34 && length <= data.find("Kupfer")) {
          EXPECT_TRUE(s.message().find("inside a string array") != std::string::npos ||
                      s.message().find("larger than the rest of the file") != std::string::npos)
              << length << ": " << s.message();
        }
      }
      if (testing::Test::HasFailure()) return;
    }
  }
}

// FreeFEM's savemesh() (libMeshb inside): its .meshb and its .mesh of one cube mesh
// read as the same tets and the same surface groups (the six faces' labels); the
// coordinates differ only by the ASCII file's 15 significant digits.
TEST(IoOtherTools, FreeFemMeshbReadsAsItsAsciiMesh) {
  TetMesh binary, ascii;
  ReadInfo binary_info, ascii_info;
  const Status b = read_mesh(tool_file("meshb_freefem_cube.meshb"), &binary, &binary_info);
  ASSERT_TRUE(b.ok()) << b.message();
  ASSERT_TRUE(read_mesh(tool_file("mesh_freefem_cube.mesh"), &ascii, &ascii_info).ok());
  EXPECT_EQ(binary_info.format, MeshFormat::kMeditBinary);
  EXPECT_EQ(binary.tet_count(), 162u);
  EXPECT_EQ(binary.tets, ascii.tets);
  EXPECT_EQ(binary.materials, ascii.materials);
  ASSERT_EQ(binary.vertex_count(), ascii.vertex_count());
  for (size_t i = 0; i < ascii.vertex_count(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(binary.positions[i][k], ascii.positions[i][k], 1e-14) << "vertex " << i;
  ASSERT_EQ(binary_info.surface_groups.size(), 6u);
  ASSERT_EQ(ascii_info.surface_groups.size(), 6u);
  for (size_t g = 0; g < 6; ++g) {
    EXPECT_EQ(binary_info.surface_groups[g].tag, int32_t(g + 1));
    EXPECT_EQ(ascii_info.surface_groups[g].tag, int32_t(g + 1));
    EXPECT_EQ(binary_info.surface_groups[g].triangles.size(), 18u);
    EXPECT_EQ(ascii_info.surface_groups[g].triangles.size(), 18u);
  }
}

// Reads a one-tet file: its material, and the reader's one note (containing `note`)
// or none (`note` null).
void expect_material_and_note(const std::string& text, MeshFormat format, int material,
                              const char* note) {
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(text, format, "m", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.materials[0], material);
  if (note) {
    ASSERT_EQ(info.notes.size(), 1u);
    EXPECT_NE(info.notes[0].find(note), std::string::npos) << info.notes[0];
  } else {
    EXPECT_TRUE(info.notes.empty()) << info.notes[0];
  }
}

// Several candidate arrays: "material" wins whatever the order; a known name of a
// floating-point type is not a material. When no array is taken the reader says so,
// naming the file's cell arrays.
TEST(IoOtherTools, TheBestMaterialArrayIsTaken) {
  auto vtu = [](const std::string& cell_data) {
    return "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\"><UnstructuredGrid>\n"
           "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\"><Points>\n"
           "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
           "0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points><Cells>\n"
           "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>\n"
           "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4</DataArray>\n"
           "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray>\n"
           "</Cells><CellData>\n" +
           cell_data + "</CellData></Piece></UnstructuredGrid></VTKFile>\n";
  };
  auto array = [](const char* type, const char* name, int value) {
    return std::string("<DataArray type=\"") + type + "\" Name=\"" + name + "\" format=\"ascii\">" +
           std::to_string(value) + "</DataArray>\n";
  };
  const struct {
    std::string cell_data;
    int material;
    const char* note;  // what the reader notes, or nullptr for nothing
  } cases[] = {
      {array("Int32", "gmsh:physical", 4) + array("Int32", "material", 7), 7, nullptr},
      {array("Int32", "material", 7) + array("Int32", "gmsh:physical", 4), 7, nullptr},
      {array("Int32", "cell_scalars", 3) + array("Int64", "medit:ref", 5), 5, nullptr},
      {array("Int32", "medit:ref", 5) + array("Int32", "gmsh:physical", 4), 4, nullptr},
      {array("Int32", "gmsh:geometrical", 9) + array("Int32", "gmsh:physical", 4), 4, nullptr},
      {array("Int32", "gmsh:geometrical", 9), 9, nullptr},
      {array("Int64", "tetgen:ref", 6), 6, nullptr},
      {array("Int64", "nastran:ref", 8) + array("Int32", "cell_scalars", 3), 8, nullptr},
      {array("Float64", "gmsh:physical", 4), 0,
       "no cell array is read as the material, so every tet is material 0 (the file's cell "
       "arrays: 'gmsh:physical'; the material is read from 'material', 'gmsh:physical'"},
      {array("Int32", "region", 2) + array("Float64", "quality", 1), 0,
       "(the file's cell arrays: 'region', 'quality';"},
      {"", 0, "the file has no cell arrays, so every tet is material 0 (the material is read"},
  };
  // Many arrays: the note names the first ten and counts the rest.
  {
    std::string many;
    for (int k = 0; k < 25; ++k) many += array("Int32", ("a" + std::to_string(k)).c_str(), 1);
    TetMesh mesh;
    ReadInfo info;
    ASSERT_TRUE(read_mesh_from_memory(vtu(many), MeshFormat::kVtu, "m.vtu", &mesh, &info).ok());
    ASSERT_EQ(info.notes.size(), 1u);
    EXPECT_NE(info.notes[0].find("'a8', 'a9' and 15 more;"), std::string::npos) << info.notes[0];
    EXPECT_EQ(info.notes[0].find("'a10'"), std::string::npos) << info.notes[0];
  }
  for (const auto& c : cases) {
    SCOPED_TRACE(c.cell_data);
    expect_material_and_note(vtu(c.cell_data), MeshFormat::kVtu, c.material, c.note);
  }
}

// The same in a legacy .vtk: SCALARS and FIELD arrays of CELL_DATA are named in the
// note; POINT_DATA arrays are not cell arrays.
TEST(IoOtherTools, LegacyVtkSaysWhenNoArrayIsTheMaterial) {
  const std::string head =
      "# vtk DataFile Version 3.0\nm\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
  const std::string points =
      "POINT_DATA 4\nSCALARS temperature float 1\nLOOKUP_TABLE "
      "default\n1 2 3 4\n";
  const struct {
    std::string data;
    int material;
    const char* note;
  } cases[] = {
      {points + "CELL_DATA 1\nSCALARS zone int 1\nLOOKUP_TABLE colours\n3\n"
                "LOOKUP_TABLE colours 1\n0 0 1 1\nFIELD f 1\nquality 1 1 double\n0.5\n",
       0, "(the file's cell arrays: 'zone', 'quality';"},
      {"CELL_DATA 1\nFIELD f 1\ntetgen:ref 1 1 int\n6\n", 6, nullptr},
      {points, 0, "the file has no cell arrays, so every tet is material 0"},
      {"", 0, "the file has no cell arrays, so every tet is material 0"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.data);
    expect_material_and_note(head + c.data, MeshFormat::kVtkLegacy, c.material, c.note);
  }
}

TEST(IoOtherTools, UnreadCompressorsAreNamed) {
  for (const char* file : {"vtu_vtk9_appended_lz4.vtu", "vtu_meshio_lzma.vtu"}) {
    TetMesh mesh;
    const Status s = read_mesh(tool_file(file), &mesh);
    ASSERT_FALSE(s.ok()) << file;
    EXPECT_NE(s.message().find(file), std::string::npos) << s.message();
    EXPECT_NE(s.message().find("is not supported (only vtkZLibDataCompressor)"), std::string::npos)
        << s.message();
  }
}

}  // namespace
}  // namespace tetlod
