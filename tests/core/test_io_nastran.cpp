// Nastran bulk data (.bdf/.nas): the three field formats, continuations, short
// reals, skipped entries and executive control read as the mesh they describe;
// what TetLOD writes reads back with every material; random damage never crashes.
// (test_io_gmsh_interop.cpp checks that Gmsh reads ours and we read Gmsh's.)
#include <gtest/gtest.h>
#include <algorithm>

#include <cmath>
#include <random>

#include "core/io/mesh_io.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

// A fixed-field line: the name and the fields each padded to `width` (the name to 8).
std::string fixed(const std::string& name, const std::vector<std::string>& fields,
                  size_t width = 8) {
  std::string line = name;
  line.resize(8, ' ');
  for (const std::string& f : fields) {
    std::string padded = f;
    padded.resize(width, ' ');
    line += padded;
  }
  return line + "\n";
}

// Seven GRIDs and four CTETRAs in every field format, among entries to skip.
std::string sample() {
  std::string s =
      "$ executive and case control, then the bulk data\n"
      "SOL 101\n"
      "CEND\n"
      "TITLE = GRID 99 is not bulk data\n"
      "BEGIN BULK\n";
  s += fixed("PSOLID", {"3", "1"});
  s += fixed("MAT1", {"1", "2.1+5", "", "0.3"});
  s += fixed("GRID", {"1", "", "0.", "0.", "0."});
  s += fixed("GRID", {"2", "0", "1.0", "", "0.0"});  // a blank coordinate is 0
  s += fixed("GRID*", {"3", "", "0.", "1.0D0"}, 16) + fixed("*", {"0."}, 16);
  s += "grid,4,,0.,0.,10.-1\n";             // 10.-1 = 1.0
  s += "GRID,5,0,1.,+1.,.1+1 $ comment\n";  // .1+1 = 1.0
  s += "GRID\t6\t\t0.\t0.\t-1.E0\n";        // tabs: 8-column fields
  s += fixed("CTETRA", {"1", "3", "1", "2", "3", "4"});
  s += "ctetra,2,7,2,3,4,5\n";
  s += fixed("CHEXA", {"9", "1", "1", "2", "3", "4", "5", "6"}) + fixed("+", {"7", "8"});
  s += fixed("CTETRA*", {"3", "7", "1", "2"}, 16) + fixed("*", {"3", "6"}, 16);
  // A 10-node tet (the PID left blank: material 0) over a continuation line.
  s += fixed("CTETRA", {"4", "", "1", "2", "4", "7", "1", "1"}) + fixed("+", {"1", "1", "1", "1"});
  s += fixed("GRID", {"7", "", "0.", "-1.", "0."});  // after the CTETRA that uses it
  s += "ENDDATA\n"
       "GRID,8,,text after ENDDATA is not read\n";
  return s;
}

TEST(IoNastran, ReadsEveryFieldFormat) {
  const char* medit =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n7\n"
      "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 0\n0 0 -1 0\n0 -1 0 0\n"
      "Tetrahedra\n4\n1 2 3 4 3\n2 3 4 5 7\n1 2 3 6 7\n1 2 4 7 0\nEnd\n";
  TetMesh expected, mesh;
  ASSERT_TRUE(read_mesh_from_memory(medit, MeshFormat::kMedit, "e.mesh", &expected).ok());
  ReadInfo info;
  const Status s = read_mesh_from_memory(sample(), MeshFormat::kNastran, "s.bdf", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message() << "\n" << sample();
  test::expect_same_mesh(expected, mesh);
  EXPECT_EQ(info.format, MeshFormat::kNastran);
}

TEST(IoNastran, WrittenFilesReadBackWithEveryMaterial) {
  const std::string dir = test::output_dir("nastran");
  // Materials 0 (not a valid PID), 7 and INT32_MAX (too wide for small field).
  const TetMesh mesh = test::make_io_mesh();
  ASSERT_TRUE(write_mesh(dir + "/io.nas", mesh).ok());
  TetMesh back;
  const Status s = read_mesh(dir + "/io.nas", &back);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(back.tets, mesh.tets);
  EXPECT_EQ(back.materials, mesh.materials);
  ASSERT_EQ(back.positions.size(), mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.positions[v][k];
      EXPECT_NEAR(back.positions[v][k], x, 1e-13 * std::max(1.0, std::abs(x))) << v;
    }
  }
  // Every line fits in 80 columns; coordinates that fit in 16 characters are exact.
  const std::string text = test::read_text(dir + "/io.nas");
  size_t start = 0;
  for (size_t end = text.find('\n'); end != std::string::npos; end = text.find('\n', start)) {
    if (text[start] != '$') {
      EXPECT_LE(end - start, 80u) << text.substr(start, end - start);
    }
    start = end + 1;
  }
  const TetMesh grid = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int) { return 1 + i + j; }, 0.25);
  ASSERT_TRUE(write_mesh(dir + "/grid.bdf", grid).ok());
  ASSERT_TRUE(read_mesh(dir + "/grid.bdf", &back).ok());
  test::expect_same_mesh(grid, back);
}

// With surface groups: a CTRIA3 per triangle, the group's tag as its PID; in large
// field when a tag does not fit in 8 characters.
TEST(IoNastran, SurfaceGroupsReadBackInSmallAndLargeField) {
  const std::string dir = test::output_dir("nastran_groups");
  for (int32_t second : {2, 99999999}) {
    SCOPED_TRACE(second);
    const TetMesh grid = test::make_grid_mesh(
        2, 2, 1, [&](int i, int, int) { return i == 0 ? 1 : second; }, 0.5);
    SurfaceGroups groups;
    ASSERT_TRUE(group_surface(grid, &groups).ok());
    WriteOptions options;
    options.surface_groups = true;
    const std::string path = dir + "/groups.bdf";
    ASSERT_TRUE(write_mesh(path, grid, options).ok());
    const std::string text = test::read_text(path);
    EXPECT_EQ(text.find("\nCTRIA3* ") != std::string::npos, second > 2);
    size_t start = 0;
    for (size_t end = text.find('\n'); end != std::string::npos; end = text.find('\n', start)) {
      if (text[start] != '$') {
        EXPECT_LE(end - start, 80u) << text.substr(start, end - start);
      }
      start = end + 1;
    }
    TetMesh back;
    ReadInfo info;
    ASSERT_TRUE(read_mesh(path, &back, &info).ok());
    test::expect_same_mesh(grid, back);
    ASSERT_EQ(info.surface_groups.size(), groups.groups.size());
    for (size_t g = 0; g < groups.groups.size(); ++g) {
      EXPECT_EQ(info.surface_groups[g].tag, groups.groups[g].tag);
      EXPECT_EQ(info.surface_groups[g].name, groups.groups[g].name);
      EXPECT_EQ(info.surface_groups[g].triangles.size(), groups.groups[g].triangles.size());
    }
  }
}

// The names of materials (material 0 too, under its PID) and groups come back from the
// comments they are written in; a name's control characters become '_'; other comments,
// and ours damaged, are only comments.
TEST(IoNastran, NamesReadBackFromTheirComments) {
  const std::string dir = test::output_dir("nastran_names");
  const TetMesh grid = test::make_grid_mesh(
      3, 1, 1, [](int i, int, int) { return i; }, 0.5);
  const std::vector<MaterialName> names = {{0, "air gap"}, {2, "Wicklung \xc3\xbc, prim\xc3\xa4r"}};
  WriteOptions options;
  options.surface_groups = true;
  options.material_names = &names;
  const std::string path = dir + "/named.bdf";
  ASSERT_TRUE(write_mesh(path, grid, options).ok());
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(path, &back, &info).ok());
  test::expect_same_mesh(grid, back);
  ASSERT_EQ(info.material_names.size(), 2u);
  EXPECT_EQ(info.material_names[0].material, 0);
  EXPECT_EQ(info.material_names[0].name, "air gap");
  EXPECT_EQ(info.material_names[1].material, 2);
  EXPECT_EQ(info.material_names[1].name, names[1].name);
  ASSERT_FALSE(info.surface_groups.empty());
  for (const InputSurfaceGroup& group : info.surface_groups)
    EXPECT_EQ(group.name.rfind("interface_", 0) == 0 || group.name.rfind("boundary_", 0) == 0, true)
        << group.name;

  std::string text = test::read_text(path);
  const std::string two = "$ material: the CTETRA with PID 2 are ";
  ASSERT_NE(text.find(two), std::string::npos);
  text.insert(text.find(two), "$ material: the CTETRA with PID x are junk\n$ material: the\n");
  const std::vector<MaterialName> odd = {{1, "two\nlines"}};
  options.material_names = &odd;
  ASSERT_TRUE(write_mesh(dir + "/odd.bdf", grid, options).ok());
  EXPECT_NE(test::read_text(dir + "/odd.bdf").find("PID 1 are two_lines\n"), std::string::npos);
  ASSERT_TRUE(read_mesh_from_memory(text, MeshFormat::kNastran, "n.bdf", &back, &info).ok());
  ASSERT_EQ(info.material_names.size(), 2u);
  EXPECT_EQ(info.material_names[1].name, names[1].name);

  // Names as a file may spell them: a byte that is no UTF-8 becomes '?', and a name
  // longer than kMaxNameBytes is cut, at a character's start (not inside the é that
  // straddles byte 240), with a note.
  const auto read_named = [&](const std::string& name, ReadInfo* named_info) {
    std::string named_text = text;
    named_text.insert(named_text.find('\n', named_text.find(two)) + 1, two + name + "\n");
    ASSERT_TRUE(
        read_mesh_from_memory(named_text, MeshFormat::kNastran, "n.bdf", &back, named_info).ok());
    ASSERT_EQ(named_info->material_names.size(), 2u);
  };
  ReadInfo spelled;
  read_named(std::string("bad\xff") + "byte", &spelled);
  EXPECT_EQ(spelled.material_names[1].name, "bad?byte");
  read_named(std::string(239, 'L') + "\xc3\xa9tail", &spelled);
  EXPECT_EQ(spelled.material_names[1].name, std::string(239, 'L'));
  EXPECT_NE(std::find(spelled.notes.begin(), spelled.notes.end(),
                      "1 name was cut to 240 bytes (what Gmsh reads of a physical name)"),
            spelled.notes.end());

  // A second name for a PID: the last is taken, and a note says so with the line.
  const size_t line = std::count(text.begin(), text.begin() + text.find(two), '\n') + 2;
  text.insert(text.find('\n', text.find(two)) + 1, two + "other\n");
  ASSERT_TRUE(read_mesh_from_memory(text, MeshFormat::kNastran, "n.bdf", &back, &info).ok());
  ASSERT_EQ(info.material_names.size(), 2u);
  EXPECT_EQ(info.material_names[1].name, "other");
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_EQ(info.notes[0], "a comment gives a PID a second name, the last is taken (line " +
                               std::to_string(line) + " names material PID 2 'other', named '" +
                               names[1].name + "' before)");
}

TEST(IoNastran, RandomDamageNeverCrashes) {
  std::mt19937 random(777);
  const std::string valid = sample();
  const char alphabet[] = "0123456789+-.,*$ \t\nEDGRIDCTETRA";
  for (int trial = 0; trial < 4000; ++trial) {
    std::string data = valid;
    for (int k = 0; k <= trial % 3; ++k) {
      data[random() % data.size()] = alphabet[random() % (sizeof alphabet - 1)];
    }
    if (trial % 5 == 0) data.resize(random() % data.size());
    test::expect_error_or_valid_mesh(data, MeshFormat::kNastran, "d.bdf");
    if (testing::Test::HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace tetlod
