// Every byte prefix of a valid file either fails with "name:line: ..." or, when
// the cut removed only text that carries no mesh data, reads as the full mesh.
// Never an ok result with other counts, positions, tets or materials.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// The line number of "name:LINE: ..." or 0 when the message has none.
size_t message_line(const std::string& message, const std::string& name) {
  if (message.rfind(name + ":", 0) != 0) return 0;
  return std::strtoul(message.c_str() + name.size() + 1, nullptr, 10);
}

size_t line_count(const std::string& text) {
  return size_t(std::count(text.begin(), text.end(), '\n')) + 1;
}

// Checks a failed read: "name:line: ..." with `name` one of `names` and the line
// within the text of that name.
void check_error(const Status& status, const std::vector<std::string>& names,
                 const std::vector<std::string>& texts) {
  for (size_t i = 0; i < names.size(); ++i) {
    if (status.message().rfind(names[i] + ":", 0) == 0) {
      EXPECT_LE(message_line(status.message(), names[i]), line_count(texts[i])) << status.message();
      return;
    }
  }
  ADD_FAILURE() << "message without the file name: " << status.message();
}

// Checks a successful read of a prefix: the full mesh. VTK legacy has no end marker
// and the material array is optional, so a cut before it is a file without materials.
void check_mesh(const TetMesh& mesh, const TetMesh& full, const std::string& prefix,
                bool materials_optional) {
  EXPECT_EQ(mesh.positions, full.positions) << "prefix of " << prefix.size() << " bytes";
  EXPECT_EQ(mesh.tets, full.tets) << "prefix of " << prefix.size() << " bytes";
  if (materials_optional && prefix.find("material") == std::string::npos) {
    EXPECT_EQ(mesh.materials, std::vector<int32_t>(full.tet_count(), 0));
  } else {
    EXPECT_EQ(mesh.materials, full.materials) << "prefix of " << prefix.size() << " bytes";
  }
}

void check_truncations(const std::string& text, MeshFormat format, const std::string& name) {
  SCOPED_TRACE(name);
  TetMesh full;
  const Status status = read_mesh_from_memory(text, format, name, &full);
  ASSERT_TRUE(status.ok()) << status.message();
  size_t ok_count = 0;
  for (size_t length = 0; length < text.size(); ++length) {
    // A copy, so that AddressSanitizer sees any read past the prefix.
    const std::string prefix = text.substr(0, length);
    TetMesh mesh;
    const Status read = read_mesh_from_memory(prefix, format, name, &mesh);
    if (read.ok()) {
      ++ok_count;
      check_mesh(mesh, full, prefix, format == MeshFormat::kVtkLegacy);
    } else {
      check_error(read, {name}, {prefix});
    }
    if (testing::Test::HasFailure()) return;
  }
  // Only cuts in the trailing text without data read: never most of them.
  EXPECT_LT(ok_count, text.size() / 4);
}

void check_tetgen_truncations(const std::string& node, const std::string& ele) {
  TetMesh full;
  ASSERT_TRUE(read_tetgen_from_memory(node, ele, "t.node", "t.ele", &full).ok());
  size_t ok_count = 0;
  for (int cut_ele = 0; cut_ele < 2; ++cut_ele) {
    const std::string& text = cut_ele ? ele : node;
    for (size_t length = 0; length < text.size(); ++length) {
      const std::string prefix = text.substr(0, length);
      const std::string& node_text = cut_ele ? node : prefix;
      const std::string& ele_text = cut_ele ? prefix : ele;
      TetMesh mesh;
      const Status read = read_tetgen_from_memory(node_text, ele_text, "t.node", "t.ele", &mesh);
      if (read.ok()) {
        ++ok_count;
        check_mesh(mesh, full, prefix, false);
      } else {
        check_error(read, {"t.node", "t.ele"}, {node_text, ele_text});
      }
      if (testing::Test::HasFailure()) return;
    }
  }
  EXPECT_LT(ok_count, (node.size() + ele.size()) / 4);
}

TEST(IoTruncation, WrittenFilesOfEveryFormat) {
  const std::string dir = test::output_dir("truncation");
  const TetMesh mesh = test::make_io_mesh();
  const struct {
    const char* file;
    int gmsh_version;
    MeshFormat format;
  } files[] = {{"t.mesh", 41, MeshFormat::kMedit},   {"t22.msh", 22, MeshFormat::kGmsh22},
               {"t41.msh", 41, MeshFormat::kGmsh41}, {"t.vtk", 41, MeshFormat::kVtkLegacy},
               {"t.vtu", 41, MeshFormat::kVtu},      {"t.bdf", 41, MeshFormat::kNastran}};
  for (const auto& file : files) {
    WriteOptions options;
    options.gmsh_version = file.gmsh_version;
    ASSERT_TRUE(write_mesh(dir + "/" + file.file, mesh, options).ok());
    check_truncations(test::read_text(dir + "/" + file.file), file.format, file.file);
  }
  ASSERT_TRUE(write_mesh(dir + "/t.node", mesh).ok());
  check_tetgen_truncations(test::read_text(dir + "/t.node"), test::read_text(dir + "/t.ele"));
}

TEST(IoTruncation, HandWrittenSamples) {
  const struct {
    const char* file;
    MeshFormat format;
  } files[] = {
      {"medit_sections.mesh", MeshFormat::kMedit},  {"gmsh22_mixed.msh", MeshFormat::kGmsh22},
      {"gmsh41_entities.msh", MeshFormat::kGmsh41}, {"vtk_mixed.vtk", MeshFormat::kVtkLegacy},
      {"vtk51_field.vtk", MeshFormat::kVtkLegacy},  {"vtu_mixed.vtu", MeshFormat::kVtu},
      {"medit_p2.mesh", MeshFormat::kMedit}};
  for (const auto& file : files) {
    check_truncations(test::read_text(test::data_path(file.file)), file.format, file.file);
  }
  check_tetgen_truncations(test::read_text(test::data_path("tetgen0.node")),
                           test::read_text(test::data_path("tetgen0.ele")));
  check_tetgen_truncations(test::read_text(test::data_path("tetgen1.node")),
                           test::read_text(test::data_path("tetgen1.ele")));
}

// The cuts that keep the mesh are exactly those past the last data token.
TEST(IoTruncation, MeditReadsWithoutEndButNotWithACutNumber) {
  const std::string text =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
      "Tetrahedra\n1\n1 2 3 4 12\nEnd\n";
  TetMesh mesh;
  const size_t end = text.find("End");
  EXPECT_TRUE(read_mesh_from_memory(text.substr(0, end), MeshFormat::kMedit, "t", &mesh).ok());
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{12}));
  const Status cut = read_mesh_from_memory(text.substr(0, end - 2), MeshFormat::kMedit, "t", &mesh);
  ASSERT_FALSE(cut.ok());
  EXPECT_EQ(cut.message(),
            "t:11: the file ends inside tetrahedron reference (material) '1' "
            "(truncated file?)");
}

}  // namespace
}  // namespace tetlod
