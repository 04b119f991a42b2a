// Material names: Gmsh physical volume names and Abaqus section materials or element
// sets are read as ReadInfo::material_names, and written again (WriteOptions::
// material_names) to .msh physical names and .inp element sets, without changing any
// tet's material; Gmsh itself sees the names we write.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

using Names = std::vector<std::pair<int32_t, std::string>>;

Names as_pairs(const std::vector<MaterialName>& names) {
  Names pairs;
  for (const MaterialName& n : names) pairs.push_back({n.material, n.name});
  return pairs;
}

const Names kCoaxNames = {
    {1, "inner_conductor"}, {2, "dielectric_inner"}, {3, "dielectric_outer"}, {4, "shield"}};

// Gmsh files as Gmsh wrote them: text and binary, partitioned or not.
TEST(MaterialNames, GmshPhysicalVolumeNamesAreRead) {
  for (const char* file : {"coax_order2.msh", "coax_part3.msh", "coax_part3_bin.msh"}) {
    SCOPED_TRACE(file);
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_mesh(test::data_path(std::string("gmsh/") + file), &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(as_pairs(info.material_names), kCoaxNames);
  }
  // Volume groups without names: none.
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/groups41.msh"), &mesh, &info).ok());
  EXPECT_TRUE(info.material_names.empty());
}

// A group named twice in $PhysicalNames takes the last name, and a note says so.
TEST(MaterialNames, GmshGroupNamedTwiceTakesTheLastName) {
  std::string text = test::read_text(test::data_path("gmsh/coax_part3.msh"));
  const std::string names = "$PhysicalNames\n6\n";
  ASSERT_EQ(text.find(names), text.find("$PhysicalNames"));
  text.replace(text.find(names), names.size(),
               "$PhysicalNames\n8\n3 4 \"screen\"\n2 21 \"outer\"\n");
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(text, MeshFormat::kGmsh41, "c.msh", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(as_pairs(info.material_names), kCoaxNames);  // "shield" came last
  const auto has = [&](const std::string& note) {
    return std::find(info.notes.begin(), info.notes.end(), note) != info.notes.end();
  };
  EXPECT_TRUE(
      has("the volume group 4 is named 'screen', then 'shield' in $PhysicalNames: the "
          "last name is kept"));
  EXPECT_TRUE(
      has("the surface group 21 is named 'outer', then 'jacket' in $PhysicalNames: the "
          "last name is kept"));
}

TEST(MaterialNames, GmshWritesThemAndReadsThemBack) {
  const std::string dir = test::output_dir("material_names_gmsh");
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/coax_order2.msh"), &mesh, &info).ok());
  for (int version : {22, 41}) {
    SCOPED_TRACE(version);
    const std::string path = dir + "/coax" + std::to_string(version) + ".msh";
    WriteOptions options;
    options.gmsh_version = version;
    options.material_names = &info.material_names;
    ASSERT_TRUE(write_mesh(path, mesh, options).ok());
    EXPECT_NE(test::read_text(path).find("$PhysicalNames\n4\n3 1 \"inner_conductor\"\n3 2 "
                                         "\"dielectric_inner\"\n3 3 \"dielectric_outer\"\n3 4 "
                                         "\"shield\"\n$EndPhysicalNames\n"),
              std::string::npos);
    TetMesh back;
    ReadInfo back_info;
    ASSERT_TRUE(read_mesh(path, &back, &back_info).ok());
    test::expect_same_mesh(mesh, back);
    EXPECT_EQ(as_pairs(back_info.material_names), kCoaxNames);
  }
  // Without names: material_<m>, as before.
  ASSERT_TRUE(write_mesh(dir + "/plain.msh", mesh).ok());
  EXPECT_NE(test::read_text(dir + "/plain.msh").find("3 1 \"material_1\"\n"), std::string::npos);
}

// Names that cannot be written as they are: material 0 (its Gmsh tag is not its id)
// keeps material_0; an empty name, or "material_0" on another material, gives
// material_<m>; quotes and line breaks become '_'; names of absent materials are
// ignored. "material_9" on material 2 is a name like any other (its tag is the
// material). Every tet keeps its material.
TEST(MaterialNames, GmshNamesThatCannotStandAreReplaced) {
  const std::string dir = test::output_dir("material_names_odd");
  const TetMesh mesh = test::make_grid_mesh(
      5, 1, 1, [](int i, int, int) { return i; }, 0.5);  // materials 0..4
  const std::vector<MaterialName> names = {{0, "zero"}, {1, "a\"b\nc"},    {2, "material_9"},
                                           {3, ""},     {4, "material_0"}, {7, "absent"}};
  WriteOptions options;
  options.material_names = &names;
  const std::string path = dir + "/odd.msh";
  ASSERT_TRUE(write_mesh(path, mesh, options).ok());
  const std::string text = test::read_text(path);
  EXPECT_NE(text.find("3 5 \"material_0\"\n3 1 \"a_b_c\"\n3 2 \"material_9\"\n3 3 "
                      "\"material_3\"\n3 4 \"material_4\"\n$EndPhysicalNames"),
            std::string::npos)
      << text.substr(0, 240);
  EXPECT_EQ(text.find("absent"), std::string::npos);
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(path, &back, &info).ok());
  test::expect_same_mesh(mesh, back);
  EXPECT_EQ(as_pairs(info.material_names), (Names{{1, "a_b_c"}, {2, "material_9"}}));
}

// A Gmsh volume group's tag is its material, whatever its name: groups named
// "material_2" (tag 1) and "material_1" (tag 2) were read as materials 2 and 1,
// swapped, and "material_1" on tag 12 merged into material 1. "material_0" on any tag
// is material 0 (TetLOD writes it so), "material_<tag>" no name.
TEST(MaterialNames, GmshTagsAreMaterialsWhateverTheirNames) {
  const std::string dir = test::output_dir("material_names_tags");
  const TetMesh mesh = test::make_grid_mesh(
      4, 1, 1, [](int i, int, int) { return i + 1; }, 0.5);  // materials 1..4
  const std::string path = dir + "/tags.msh";
  ASSERT_TRUE(write_mesh(path, mesh).ok());
  std::string text = test::read_text(path);
  const std::string names =
      "3 1 \"material_1\"\n3 2 \"material_2\"\n3 3 \"material_3\"\n"
      "3 4 \"material_4\"\n";
  const size_t at = text.find(names);
  ASSERT_NE(at, std::string::npos) << text.substr(0, 240);
  text.replace(at, names.size(),
               "3 1 \"material_2\"\n3 2 \"material_1\"\n3 3 \"material_0\"\n"
               "3 4 \"material_4\"\n");
  std::ofstream(path) << text;
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(path, &back, &info).ok());
  TetMesh expected = mesh;
  for (int32_t& m : expected.materials)
    if (m == 3) m = 0;
  test::expect_same_mesh(expected, back);
  EXPECT_EQ(as_pairs(info.material_names), (Names{{1, "material_2"}, {2, "material_1"}}));
  // "material_00" is a name, and a second "material_0" keeps its tag: they merged into
  // material 0.
  for (const char* fourth : {"material_00", "material_0"}) {
    std::string again = text;
    const std::string old_name = "3 4 \"material_4\"";
    again.replace(again.find(old_name), old_name.size(), "3 4 \"" + std::string(fourth) + "\"");
    std::ofstream(path) << again;
    ASSERT_TRUE(read_mesh(path, &back, &info).ok());
    test::expect_same_mesh(expected, back);
    EXPECT_EQ(as_pairs(info.material_names),
              (Names{{1, "material_2"}, {2, "material_1"}, {4, fourth}}));
  }
}

// Gmsh reads our names: it saves the physical groups again under them.
TEST(MaterialNames, GmshKeepsTheNamesWeWrite) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("material_names_by_gmsh");
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/coax_order2.msh"), &mesh, &info).ok());
  WriteOptions options;
  options.material_names = &info.material_names;
  ASSERT_TRUE(write_mesh(dir + "/ours.msh", mesh, options).ok());
  const std::string theirs = dir + "/gmsh_saved.msh";
  ASSERT_EQ(std::system(("gmsh '" + dir + "/ours.msh' -0 -format msh22 -o '" + theirs + "' > '" +
                         dir + "/gmsh.log' 2>&1")
                            .c_str()),
            0)
      << test::read_text(dir + "/gmsh.log");
  TetMesh back;
  ReadInfo back_info;
  ASSERT_TRUE(read_mesh(theirs, &back, &back_info).ok());
  EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));
  EXPECT_EQ(as_pairs(back_info.material_names), kCoaxNames);
}

// Names are valid UTF-8 whatever the file holds: a byte that is not part of a
// well-formed sequence becomes '?', the rest (here "ü" and a 4-byte emoji) stays.
TEST(MaterialNames, NamesAreValidUtf8) {
  std::string text = test::read_text(test::data_path("gmsh/coax_order2.msh"));
  const size_t at = text.find("\"inner_conductor\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "\"co\xff\xc3il \xc3\xbc \xf0\x9f\x94\x8c \xed\xa0\x80\"");
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(text, MeshFormat::kGmsh41, "n.msh", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_FALSE(info.material_names.empty());
  EXPECT_EQ(info.material_names[0].name, "co??il \xc3\xbc \xf0\x9f\x94\x8c ???");
}

// Abaqus: a section's material name, or the element set's, is the name; our own
// MATERIAL_<id> is none.
TEST(MaterialNames, AbaqusNamesAreRead) {
  const std::string deck =
      "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 1, 1\n6, 0, 0, -1\n"
      "7, 0, -1, 0\n"
      "*ELEMENT, type=C3D4, ELSET=EIRON\n1, 1, 2, 3, 4\n"
      "*ELEMENT, type=C3D4, ELSET=Coil2\n2, 2, 3, 4, 5\n"
      "*ELEMENT, type=C3D4, ELSET=MATERIAL_5\n3, 1, 2, 3, 6\n4, 1, 2, 4, 7\n"
      "*SOLID SECTION, ELSET=EIRON, MATERIAL=Iron\n"
      "*SOLID SECTION, ELSET=Coil2, MATERIAL=Copper_7\n"
      "*SOLID SECTION, ELSET=MATERIAL_5, MATERIAL=MATERIAL_5\n";
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(deck, MeshFormat::kAbaqus, "a.inp", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{8, 7, 5, 5}));
  // As first written (Abaqus compares names case-insensitively).
  EXPECT_EQ(as_pairs(info.material_names), (Names{{7, "Copper_7"}, {8, "Iron"}}));
}

// Written to .inp, each named material's element set is its name ending in its id, so
// that reading gives every tet its material again, and a comment line gives the name as
// it was (a label has no spaces), which TetLOD reads back; written again from what was
// read, the deck is the same. Hyphens stay (Abaqus labels allow them).
TEST(MaterialNames, AbaqusElementSetsCarryThem) {
  const std::string dir = test::output_dir("material_names_abaqus");
  const TetMesh mesh = test::make_grid_mesh(
      6, 1, 1, [](int i, int, int) { return i + 1; }, 0.5);  // materials 1..6
  // "Material_6" is MATERIAL_6 but for case: its comment gives it back (it was lost).
  const std::vector<MaterialName> names = {{1, "inner conductor"}, {2, "Rotor2"},
                                           {3, "3phase"},          {4, "coil_2"},
                                           {5, "Iron-Core"},       {6, "Material_6"}};
  WriteOptions options;
  options.material_names = &names;
  const std::string path = dir + "/named.inp";
  ASSERT_TRUE(write_mesh(path, mesh, options).ok());
  const std::string text = test::read_text(path);
  for (const char* set : {"ELSET=inner_conductor_1\n", "ELSET=Rotor2\n", "ELSET=M_3phase_3\n",
                          "ELSET=coil_2_4\n", "ELSET=Iron-Core_5\n", "ELSET=Material_6\n"})
    EXPECT_NE(text.find(set), std::string::npos) << set;
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(path, &back, &info).ok());
  test::expect_same_mesh(mesh, back);
  EXPECT_EQ(as_pairs(info.material_names), as_pairs(names));
  options.material_names = &info.material_names;
  ASSERT_TRUE(write_mesh(dir + "/again.inp", back, options).ok());
  EXPECT_EQ(test::read_text(dir + "/again.inp"), text);
  // Without the comments (a deck edited by hand, or another tool's), the set names;
  // a comment whose number is not the set's is not taken.
  std::string edited;
  for (size_t at = 0; at < text.size();) {
    const size_t end = text.find('\n', at) + 1;
    const std::string line = text.substr(at, end - at);
    if (line.rfind("** TetLOD material Rotor2 ", 0) == 0)
      edited += "** TetLOD material Rotor2 7 Stator\n";
    else if (line.rfind("** ", 0) != 0)
      edited += line;
    at = end;
  }
  ASSERT_TRUE(read_mesh_from_memory(edited, MeshFormat::kAbaqus, "e.inp", &back, &info).ok());
  EXPECT_EQ(as_pairs(info.material_names), (Names{{1, "inner_conductor_1"},
                                                  {2, "Rotor2"},
                                                  {3, "M_3phase_3"},
                                                  {4, "coil_2_4"},
                                                  {5, "Iron-Core_5"}}));
}

}  // namespace
}  // namespace tetlod
