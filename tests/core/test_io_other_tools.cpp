// Files written by other tools (tests/data/other_tools, made by its make.py with
// VTK 9.1 and meshio 5.0 from the bundled box2 model): every binary encoding they
// use reads as box2, and the compressors TetLOD does not read give a clear error.
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
               {"vtk_meshio_binary.vtk", true},
               {"msh_meshio_binary.msh", false},
               {"msh22_meshio_binary.msh", false},
               {"nas_meshio.nas", false},
               {"inp_meshio.inp", false}};
  for (const auto& f : files) {
    SCOPED_TRACE(f.file);
    TetMesh mesh;
    const Status s = read_mesh(tool_file(f.file), &mesh);
    ASSERT_TRUE(s.ok()) << s.message();
    if (std::string(f.file).find("nas") != std::string::npos) {
      // meshio writes 10 significant digits (box2's coordinates are exact in them).
      EXPECT_EQ(test::canonical_tets(mesh), test::canonical_tets(without_materials));
    } else {
      test::expect_same_mesh(f.materials ? box2 : without_materials, mesh);
    }
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
