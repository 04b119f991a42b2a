// Surface groups read from Abaqus / CalculiX element-face *SURFACE and from a TetGen
// .face file beside a .node/.ele pair (ReadInfo::surface_groups): hand-written files
// (by element, by element set, 4- and 10-node tets, the forms skipped with a note),
// what TetLOD's writers write reading back as the same groups, the groups through
// SurfacePatches and group_surface(), malformed files naming the line, and
// CalculiX loading the very faces the reader gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

TetMesh box2() {
  TetMesh mesh;
  const Status s = read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return mesh;
}

SurfaceGroups groups_of(const TetMesh& mesh) {
  SurfaceGroups groups;
  const Status s = group_surface(mesh, &groups);
  EXPECT_TRUE(s.ok()) << s.message();
  return groups;
}

std::vector<std::string> names_and_tags(const SurfaceGroups& groups) {
  std::vector<std::string> result;
  for (const SurfaceGroup& g : groups.groups)
    result.push_back(g.name + "=" + std::to_string(g.tag) + ":" +
                     std::to_string(g.triangles.size()));
  return result;
}

// A triangle by its corners, rotated to start at the smallest (orientation kept).
using Triangle = std::array<std::array<double, 3>, 3>;
Triangle canonical(const std::array<Vec3, 3>& t) {
  Triangle c;
  for (int k = 0; k < 3; ++k) c[k] = {t[k].x, t[k].y, t[k].z};
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}
std::vector<Triangle> canonical(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::vector<Triangle> result;
  for (const auto& t : triangles) result.push_back(canonical(t));
  std::sort(result.begin(), result.end());
  return result;
}
// The triangles of each group the writers wrote, by tag.
std::vector<std::vector<Triangle>> written_triangles(const TetMesh& mesh,
                                                     const SurfaceGroups& groups) {
  std::vector<std::vector<Triangle>> result;
  for (const SurfaceGroup& g : groups.groups) {
    std::vector<std::array<Vec3, 3>> list;
    for (uint32_t i : g.triangles) {
      const auto& v = groups.surface[i].v;
      list.push_back({mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]});
    }
    result.push_back(canonical(list));
  }
  return result;
}

std::string join(const std::vector<std::string>& notes) {
  std::string all;
  for (const std::string& n : notes) all += n + "\n";
  return all;
}

// ---- Abaqus / CalculiX ----------------------------------------------------------

// Nodes A(0,0,0) B(1,0,0) C(0,1,0) D(0,0,1) E(1,1,1) F(0,0,-1) G(0,-1,0).
const char* const kNodes =
    "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 1, 1\n6, 0, 0, -1\n"
    "7, 0, -1, 0\n";  // lines 1-8

const std::string kDeck = std::string(kNodes) +
                          "*ELEMENT, TYPE=C3D4, ELSET=UPPER\n"
                          "1, 1, 2, 3, 4\n"
                          "2, 2, 3, 4, 5\n"
                          "*ELEMENT, TYPE=C3D10, ELSET=LOWER\n"
                          "3, 1, 2, 3, 6, 1, 1, 1, 1, 1, 1\n"
                          "*ELEMENT, TYPE=C3D4, ELSET=LOWER\n"
                          "4, 1, 2, 4, 7\n"
                          "*ELEMENT, TYPE=C3D8\n"
                          "20, 1, 2, 3, 4, 5, 6, 7, 1\n"
                          "*ELEMENT, TYPE=S3, ELSET=SKIN\n"
                          "30, 1, 2, 3\n"
                          "*ELSET, ELSET=PAIR, GENERATE\n"
                          "1, 2\n"
                          "*NSET, NSET=Cap\n"
                          "2, 3, 5\n"
                          "** our writer's pair: node set Cap, surface Cap_FACES\n"
                          "*SURFACE, TYPE=ELEMENT, NAME=Cap_FACES\n"
                          "2, S2\n"
                          "*Surface, name=Lower\n"
                          "LOWER, s4\n"
                          "*SURFACE, NAME=Mixed\n"
                          "1, S1\n"
                          "1, S1\n"  // twice: once in the group
                          "SKIN, SPOS\n"
                          "20, S5\n"
                          "*SURFACE, TYPE=NODE, NAME=Points\n"
                          "Cap\n"
                          "*SURFACE, NAME=Exposed\n"
                          "PAIR\n"
                          "*SURFACE, NAME=Pair_FACES\n"  // no node set Pair: keeps its name
                          "Part-1-1.PAIR, S3\n"
                          "*SURFACE, NAME=Lower\n"  // adds to the first Lower
                          "4, S1\n";

TEST(IoInputGroups, AbaqusSurfacesByElementAndBySet) {
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(kDeck, MeshFormat::kAbaqus, "a.inp", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(mesh.tet_count(), 4u);
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1}, e{1, 1, 1}, f{0, 0, -1}, g{0, -1, 0};
  // Faces: S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1, in node order facing
  // into an element of positive volume: read facing out of it, as Abaqus takes an
  // element-based surface's normal (so reversed below); a shell keeps its node order.
  struct Expected {
    int32_t tag;
    const char* name;
    std::vector<std::array<Vec3, 3>> triangles;
    bool element_faces = true;
  };
  const std::vector<Expected> expected = {
      {1, "Cap", {{b, e, c}}},  // element 2 (B C D E), S2
      // 3 (A B C F, of negative volume: its S4 in node order, c f a, faces out) and
      // 4 (A B D G), S4; 4, S1
      {2, "Lower", {{c, a, f}, {d, g, a}, {a, b, d}}},
      {3, "Mixed", {{a, b, c}}},                  // element 1, S1 (the shell and the hex dropped)
      {4, "Pair_FACES", {{b, d, c}, {c, e, d}}},  // elements 1 and 2, S3
      {5, "SKIN", {{a, b, c}}, false},            // the shell S3's set, after the surfaces
  };
  ASSERT_EQ(info.surface_groups.size(), expected.size());
  // Tagged after the largest material number (GetDP numbers volumes and surfaces alike).
  const int32_t largest = *std::max_element(mesh.materials.begin(), mesh.materials.end());
  ASSERT_GT(largest, 0);
  for (size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(expected[i].name);
    EXPECT_EQ(info.surface_groups[i].tag, largest + expected[i].tag);
    EXPECT_EQ(info.surface_groups[i].name, expected[i].name);
    std::vector<std::array<Vec3, 3>> want = expected[i].triangles;
    if (expected[i].element_faces)
      for (auto& t : want) std::swap(t[1], t[2]);
    EXPECT_EQ(canonical(info.surface_groups[i].triangles), canonical(want));
  }
  const std::string notes = join(info.notes);
  EXPECT_NE(notes.find("2 faces of *SURFACE Mixed are on elements that are not tetrahedra"),
            std::string::npos)
      << notes;
  EXPECT_NE(notes.find("not read as surface groups: *SURFACE Points (TYPE=NODE), Exposed (line "
                       "37: an element or set without a face"),
            std::string::npos)
      << notes;
}

// A section or *ELSET may name the element set of a block of other elements (a
// mixed deck): it holds no tet, but it is defined.
TEST(IoInputGroups, AbaqusSetsOfOtherElementsAreDefined) {
  const std::string deck = std::string(kNodes) +
                           "*ELEMENT, TYPE=C3D4, ELSET=TETS\n1, 1, 2, 3, 4\n"
                           "*ELEMENT, TYPE=C3D8, ELSET=HEX\n2, 1, 2, 3, 4, 5, 6, 7, 1\n"
                           "*ELSET, ELSET=BOTH\nTETS, HEX\n"
                           "*SOLID SECTION, ELSET=HEX, MATERIAL=Steel7\n"
                           "*SOLID SECTION, ELSET=BOTH, MATERIAL=Air3\n";
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(deck, MeshFormat::kAbaqus, "a.inp", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.materials, std::vector<int32_t>{3});
}

// Triangle elements in an *ELSET, as Gmsh's .inp export writes a physical surface
// (CPS3 elements in a set named after it, besides the block's own ELSET), are a
// group named after the set; without such a set, the triangle blocks' ELSETs are.
TEST(IoInputGroups, AbaqusTriangleElementSetsAreGroups) {
  using Corners = std::vector<std::array<Vec3, 3>>;
  const std::string mesh = std::string(kNodes) +
                           "*ELEMENT, type=CPS3, ELSET=Surface1\n10, 1, 2, 3\n11, 1, 2, 4\n"
                           "12, 1, 2, 99\n"
                           "*ELEMENT, type=C3D4, ELSET=Volume1\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n";
  TetMesh read;
  ReadInfo info;
  ASSERT_TRUE(read_mesh_from_memory(mesh + "*SURFACE, NAME=Side\n1, S2\n*ELSET,ELSET=port\n10, "
                                           "10\n*ELSET,ELSET=Vol\n1, 2\n",
                                    MeshFormat::kAbaqus, "a.inp", &read, &info)
                  .ok());
  EXPECT_EQ(read.tet_count(), 2u);
  ASSERT_EQ(info.surface_groups.size(), 2u);
  EXPECT_EQ(info.surface_groups[0].name, "Side");  // the *SURFACE first
  EXPECT_EQ(info.surface_groups[1].name, "port");
  EXPECT_EQ(info.surface_groups[1].tag,
            *std::max_element(read.materials.begin(), read.materials.end()) + 2);
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  EXPECT_EQ(canonical(info.surface_groups[1].triangles), canonical(Corners{{a, b, c}}));
  // No *ELSET holds triangles: the block's set, its triangle with an unknown node left out.
  ASSERT_TRUE(read_mesh_from_memory(mesh, MeshFormat::kAbaqus, "a.inp", &read, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].name, "Surface1");
  EXPECT_EQ(canonical(info.surface_groups[0].triangles), canonical(Corners{{a, b, c}, {a, b, d}}));
  EXPECT_NE(join(info.notes).find("1 triangle elements name a node that is not defined"),
            std::string::npos)
      << join(info.notes);
}

// Each malformed line names the file and line and says what is wrong. A surface whose
// references TetLOD cannot follow (an element or set not defined, a face a tet does
// not have) is left out with a note naming the line: the mesh still reads.
TEST(IoInputGroups, AbaqusBrokenSurfacesNameTheLine) {
  const std::string mesh =
      std::string(kNodes) + "*ELEMENT, TYPE=C3D4, ELSET=UPPER\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n";
  // The *SURFACE line is line 12, its first data line 13.
  const struct {
    std::string surface;
    int line;
    const char* words;
  } cases[] = {
      {"*SURFACE, TYPE=ELEMENT\n1, S1\n", 12, "*SURFACE needs NAME="},
      {"*SURFACE, NAME=X\n1, S1, 2\n", 13, "expected 'element or element set, face'"},
      {"*SURFACE, NAME=X\n, S1\n", 13, "expected 'element or element set, face'"},
      {"*SURFACE, NAME=X\n1 S1\n", 13, "expected 'element or element set, face'"},
  };
  for (const auto& c : cases) {
    TetMesh read;
    const Status s = read_mesh_from_memory(mesh + c.surface, MeshFormat::kAbaqus, "a.inp", &read);
    ASSERT_FALSE(s.ok()) << c.surface;
    EXPECT_EQ(s.message().rfind("a.inp:" + std::to_string(c.line) + ": ", 0), 0u) << s.message();
    EXPECT_NE(s.message().find(c.words), std::string::npos) << s.message();
  }
  const struct {
    std::string surface;
    const char* note;
  } skipped[] = {
      {"*SURFACE, NAME=X\n1, S5\n",
       "X (line 13: element 1 is a tetrahedron, whose faces are S1 to S4, not 'S5')"},
      {"*SURFACE, NAME=X\n1, S0\n", "X (line 13: element 1 is a tetrahedron, whose faces"},
      {"*SURFACE, NAME=X\n1, 7\n",
       "X (line 13: element 1 is a tetrahedron, whose faces are S1 to S4, not '7')"},
      {"*SURFACE, NAME=X\n2, S1\nUPPER, SNEG\n", "X (line 14: element 1 is a tetrahedron"},
      {"*SURFACE, NAME=X\n1, S1\n99, S1\n", "X (line 14: element 99 is not defined)"},
      {"*SURFACE, NAME=X\nPart-1-1.99, S1\n", "X (line 13: element 99 is not defined)"},
      {"*SURFACE, NAME=X\nNOPE, S1\n",
       "X (line 13: 'NOPE' is neither an element nor an element set)"},
  };
  for (const auto& c : skipped) {
    // A good surface after the skipped one keeps every face it names.
    TetMesh read;
    ReadInfo info;
    const Status s = read_mesh_from_memory(mesh + c.surface + "*SURFACE, NAME=Y\n1, S1\n2, S1\n",
                                           MeshFormat::kAbaqus, "a.inp", &read, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(read.tet_count(), 2u);
    ASSERT_EQ(info.surface_groups.size(), 1u) << c.surface;
    EXPECT_EQ(info.surface_groups[0].name, "Y");
    EXPECT_EQ(info.surface_groups[0].tag,
              *std::max_element(read.materials.begin(), read.materials.end()) + 1);
    EXPECT_EQ(info.surface_groups[0].triangles.size(), 2u) << c.surface;
    const std::string notes = join(info.notes);
    EXPECT_NE(notes.find("not read as surface groups: *SURFACE " + std::string(c.note)),
              std::string::npos)
        << notes;
  }
  // An element qualified by its instance, as at assembly level, is that element.
  {
    TetMesh read;
    ReadInfo info;
    ASSERT_TRUE(read_mesh_from_memory(mesh + "*ELSET, ELSET=Q\nPart-1-1.2\n*SURFACE, NAME=X\n"
                                             "Part-1-1.1, S1\nQ, S2\n",
                                      MeshFormat::kAbaqus, "a.inp", &read, &info)
                    .ok());
    ASSERT_EQ(info.surface_groups.size(), 1u);
    EXPECT_EQ(info.surface_groups[0].triangles.size(), 2u);
  }
  // A set that generates more faces than an input of this size can hold.
  const std::string flood = mesh +
                            "*ELSET, ELSET=MANY, GENERATE\n1, 1000000\n"
                            "*SURFACE, NAME=X\nMANY, S1\nMANY, S2\nMANY, S3\n";
  TetMesh read;
  const Status s = read_mesh_from_memory(flood, MeshFormat::kAbaqus, "a.inp", &read);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("a.inp:15: the surfaces hold more faces", 0), 0u) << s.message();
}

TEST(IoInputGroups, AbaqusRandomDamageNeverCrashes) {
  std::mt19937 random(7);
  const char alphabet[] = "0123456789,*.-= \nSNEGLTabc";
  for (int trial = 0; trial < 4000; ++trial) {
    std::string data = kDeck;
    for (int k = 0; k <= trial % 3; ++k)
      data[random() % data.size()] = alphabet[random() % (sizeof alphabet - 1)];
    if (trial % 5 == 0) data.resize(random() % data.size());
    test::expect_error_or_valid_mesh(data, MeshFormat::kAbaqus, "a.inp");
    if (testing::Test::HasFatalFailure()) return;
  }
}

// What write_abaqus() writes reads back as the same groups, named as written (our
// <NAME>_FACES is NAME again), tagged in order; written again, the file is the same.
TEST(IoInputGroups, AbaqusWrittenGroupsReadBack) {
  const std::string dir = test::output_dir("input_groups_abaqus");
  WriteOptions options;
  options.surface_groups = true;
  // box2: a group per material pair.
  const TetMesh mesh = box2();
  const SurfaceGroups plain = groups_of(mesh);
  ASSERT_TRUE(write_mesh(dir + "/box2.inp", mesh, options).ok());
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(dir + "/box2.inp", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), plain.groups.size());
  const auto written = written_triangles(mesh, plain);
  const int32_t largest = *std::max_element(back.materials.begin(), back.materials.end());
  for (size_t i = 0; i < plain.groups.size(); ++i) {
    EXPECT_EQ(info.surface_groups[i].tag, largest + int32_t(i + 1));
    EXPECT_EQ(info.surface_groups[i].name, plain.groups[i].name);  // in its case
    // A face's corners in the order of its Abaqus face, not of the writer's
    // triangle: compare them as sets of corners.
    auto corners = [](std::vector<Triangle> list) {
      for (Triangle& t : list) std::sort(t.begin(), t.end());
      std::sort(list.begin(), list.end());
      return list;
    };
    EXPECT_EQ(corners(canonical(info.surface_groups[i].triangles)), corners(written[i]));
  }
  // End to end: each is a whole pair's, so group_surface() keeps it under its name.
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(back, &groups, SurfacePatches(back, info.surface_groups)).ok());
  std::vector<std::string> expected;
  for (size_t i = 0; i < plain.groups.size(); ++i)
    expected.push_back(info.surface_groups[i].name + "=" + std::to_string(largest + i + 1) + ":" +
                       std::to_string(plain.groups[i].triangles.size()));
  EXPECT_EQ(names_and_tags(groups), expected);

  // A Gmsh file's own groups: .msh -> .inp -> .inp keeps the names, and the second
  // .inp is the first.
  TetMesh input;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/groups41.msh"), &input, &info).ok());
  ASSERT_TRUE(group_surface(input, &groups, SurfacePatches(input, info.surface_groups)).ok());
  options.groups = &groups;
  ASSERT_TRUE(write_mesh(dir + "/groups.inp", input, options).ok());
  ASSERT_TRUE(read_mesh(dir + "/groups.inp", &back, &info).ok());
  std::vector<std::string> names;
  for (const InputSurfaceGroup& g : info.surface_groups)
    names.push_back(g.name + ":" + std::to_string(g.triangles.size()));
  EXPECT_EQ(names, (std::vector<std::string>{"outer_left:332", "boundary_2:264", "right_end:68",
                                             "membrane:66"}));
  ASSERT_TRUE(group_surface(back, &groups, SurfacePatches(back, info.surface_groups)).ok());
  ASSERT_TRUE(write_mesh(dir + "/again.inp", back, options).ok());
  EXPECT_EQ(test::read_text(dir + "/again.inp"), test::read_text(dir + "/groups.inp"));

  // Names keep their hyphens, as Abaqus/CAE writes them ("Surf-Load"); other
  // characters a label cannot hold become '_' in the label, and TetLOD's comment line
  // gives the group its name (blanks and all) and its tag back.
  groups.groups[0].name = "Surf-Load";
  groups.groups[1].name = "port 1";
  ASSERT_TRUE(write_mesh(dir + "/hyphen.inp", back, options).ok());
  const std::string text = test::read_text(dir + "/hyphen.inp");
  for (const char* line :
       {"*NSET, NSET=Surf-Load\n", "NAME=Surf-Load_FACES\n", "*NSET, NSET=port_1\n"})
    EXPECT_NE(text.find(line), std::string::npos) << line;
  ASSERT_TRUE(read_mesh(dir + "/hyphen.inp", &back, &info).ok());
  ASSERT_GE(info.surface_groups.size(), 2u);
  EXPECT_EQ(info.surface_groups[0].name, "Surf-Load");
  EXPECT_EQ(info.surface_groups[1].name, "port 1");
  groups.groups[0].tag = 22;  // tags a .msh gave, not the reader's next ones
  groups.groups[1].tag = 24;
  ASSERT_TRUE(write_mesh(dir + "/tags.inp", back, options).ok());
  EXPECT_NE(test::read_text(dir + "/tags.inp").find("** TetLOD surface port_1_FACES 24 port 1\n"),
            std::string::npos);
  ASSERT_TRUE(read_mesh(dir + "/tags.inp", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), groups.groups.size());
  for (size_t i = 0; i < groups.groups.size(); ++i) {
    EXPECT_EQ(info.surface_groups[i].tag, groups.groups[i].tag) << i;
    EXPECT_EQ(info.surface_groups[i].name, groups.groups[i].name) << i;
  }
  // A comment's tag that a material has is kept (a Gmsh file's physical surface may
  // have one), and the groups after it keep theirs.
  const std::string tagged = test::read_text(dir + "/tags.inp");
  const size_t at = tagged.find(" 22 Surf-Load\n");
  ASSERT_NE(at, std::string::npos);
  ASSERT_FALSE(back.materials.empty());
  const int32_t material = back.materials[0];
  std::string shared = tagged;
  shared.replace(at, 3, " " + std::to_string(material));
  ASSERT_TRUE(read_mesh_from_memory(shared, MeshFormat::kAbaqus, "m.inp", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), groups.groups.size());
  EXPECT_EQ(info.surface_groups[0].tag, material);
  for (size_t i = 1; i < groups.groups.size(); ++i) {
    EXPECT_EQ(info.surface_groups[i].tag, groups.groups[i].tag) << i;
    EXPECT_EQ(info.surface_groups[i].name, groups.groups[i].name) << i;
  }
  // An earlier group's tag is not taken: the group keeps its name and gets a tag no
  // other group has nor any comment gives, with a note.
  std::string clash = tagged;
  clash.replace(tagged.find(" 24 port 1\n"), 3, " 22");
  ASSERT_TRUE(read_mesh_from_memory(clash, MeshFormat::kAbaqus, "c.inp", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), groups.groups.size());
  EXPECT_EQ(info.surface_groups[0].tag, 22);
  EXPECT_EQ(info.surface_groups[1].name, "port 1");
  std::set<int32_t> tags;
  for (const InputSurfaceGroup& g : info.surface_groups) EXPECT_TRUE(tags.insert(g.tag).second);
  for (size_t i = 2; i < groups.groups.size(); ++i)
    EXPECT_EQ(info.surface_groups[i].tag, groups.groups[i].tag) << i;
  bool noted = false;
  for (const std::string& note : info.notes)
    noted |= note.find("numbered anew") != std::string::npos &&
             note.find("port_1_FACES (22 -> ") != std::string::npos;
  EXPECT_TRUE(noted);
  // A comment that cannot be read, or that names no *SURFACE, gives nothing: the
  // note says which lines (none when every comment was used).
  const auto ignored_note = [](const std::vector<std::string>& notes) {
    for (const std::string& note : notes)
      if (note.find("TetLOD comment") != std::string::npos) return note;
    return std::string();
  };
  ASSERT_TRUE(read_mesh_from_memory(tagged, MeshFormat::kAbaqus, "t.inp", &back, &info).ok());
  EXPECT_EQ(ignored_note(info.notes), "");
  std::string edited = tagged;
  const size_t bad_tag = edited.find(" 24 port 1\n");
  edited.replace(bad_tag, 3, " 2x");
  const size_t renamed = edited.find("surface Surf-Load_FACES");
  ASSERT_NE(renamed, std::string::npos);
  edited.replace(renamed, 17, "surface Gone_FACES");
  const auto line_of = [&](size_t where) {
    return std::count(edited.begin(), edited.begin() + where, '\n') + 1;
  };
  ASSERT_TRUE(read_mesh_from_memory(edited, MeshFormat::kAbaqus, "e.inp", &back, &info).ok());
  const std::vector<long> lines = {line_of(renamed), line_of(bad_tag)};
  EXPECT_NE(
      ignored_note(info.notes)
          .find("2 TetLOD comments ignored (lines " + std::to_string(std::min(lines[0], lines[1])) +
                ", " + std::to_string(std::max(lines[0], lines[1])) + "):"),
      std::string::npos)
      << ignored_note(info.notes);
  ASSERT_EQ(info.surface_groups.size(), groups.groups.size());
  EXPECT_NE(info.surface_groups[0].tag, 22);         // the reader's next tag
  EXPECT_EQ(info.surface_groups[1].name, "port_1");  // the label's, not the comment's
  // A bare comment line, and the first of two comments for one surface, are noted too.
  std::string twice = tagged;
  const size_t port = twice.find("** TetLOD surface port_1_FACES");
  ASSERT_NE(port, std::string::npos);
  twice.insert(port, "** TetLOD surface\n** TetLOD surface port_1_FACES 30 old name\n");
  ASSERT_TRUE(read_mesh_from_memory(twice, MeshFormat::kAbaqus, "t.inp", &back, &info).ok());
  const long first = std::count(twice.begin(), twice.begin() + port, '\n') + 1;
  EXPECT_NE(ignored_note(info.notes)
                .find("2 TetLOD comments ignored (lines " + std::to_string(first) + ", " +
                      std::to_string(first + 1) + "):"),
            std::string::npos)
      << ignored_note(info.notes);
  ASSERT_EQ(info.surface_groups.size(), groups.groups.size());
  EXPECT_EQ(info.surface_groups[1].name, "port 1");  // the later comment's
}

// CalculiX loads the faces the reader gives: four disjoint copies of one scalene
// tet, copy k with face Sk under a unit pressure and the corners of another face
// held. A linear tet passes a third of a uniform pressure to each corner of the
// face, and CalculiX's reaction is the force the element passes to the held nodes
// (not the load put on them directly): the free corner's third, so the reaction
// is a third of the loaded face's area vector, outward from the tet. Each face of
// this tet has a different one.
TEST(IoInputGroups, CalculixLoadsTheFacesTheReaderGives) {
  TETLOD_NEED_PROGRAM("ccx");
  const std::string dir = test::output_dir("input_groups_calculix");
  const Vec3 corner[4] = {{0, 0, 0}, {2, 0, 0}, {0.5, 3, 0}, {0.3, 0.2, 5}};
  std::ostringstream deck;
  deck << "*NODE\n";
  for (int copy = 0; copy < 4; ++copy)
    for (int k = 0; k < 4; ++k)
      deck << copy * 4 + k + 1 << ", " << corner[k].x + 10 * copy << ", " << corner[k].y << ", "
           << corner[k].z << "\n";
  deck << "*ELEMENT, TYPE=C3D4, ELSET=SOLID\n";
  for (int copy = 0; copy < 4; ++copy)
    deck << copy + 1 << ", " << copy * 4 + 1 << ", " << copy * 4 + 2 << ", " << copy * 4 + 3 << ", "
         << copy * 4 + 4 << "\n";
  // The corners (0-based) of S1..S4 (Abaqus and CalculiX manuals).
  const int face_corners[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  for (int copy = 0; copy < 4; ++copy) {
    const int* held = face_corners[(copy + 1) % 4];
    deck << "*NSET, NSET=N" << copy + 1 << "\n"
         << copy * 4 + held[0] + 1 << ", " << copy * 4 + held[1] + 1 << ", "
         << copy * 4 + held[2] + 1 << "\n";
    deck << "*SURFACE, NAME=F" << copy + 1 << "\n" << copy + 1 << ", S" << copy + 1 << "\n";
  }
  const std::string mesh_text = deck.str();
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh_from_memory(mesh_text, MeshFormat::kAbaqus, "four.inp", &mesh, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), 4u);
  deck << "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n"
          "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n"
          "*STEP\n*STATIC\n*BOUNDARY\n";
  for (int copy = 0; copy < 4; ++copy) deck << "N" << copy + 1 << ", 1, 3\n";
  deck << "*DLOAD\n";
  for (int copy = 0; copy < 4; ++copy) deck << "F" << copy + 1 << ", P, 1.0\n";
  for (int copy = 0; copy < 4; ++copy)
    deck << "*NODE PRINT, NSET=N" << copy + 1 << ", TOTALS=ONLY\nRF\n";
  deck << "*END STEP\n";
  test::write_text(dir + "/job.inp", deck.str());
  ASSERT_EQ(std::system(("cd '" + dir + "' && ccx job > ccx.log 2>&1").c_str()), 0)
      << test::read_text(dir + "/ccx.log");
  const std::string dat = test::read_text(dir + "/job.dat");
  for (int copy = 0; copy < 4; ++copy) {
    SCOPED_TRACE("S" + std::to_string(copy + 1));
    const size_t at = dat.find("total force (fx,fy,fz) for set N" + std::to_string(copy + 1));
    ASSERT_NE(at, std::string::npos) << dat;
    std::istringstream in(dat.substr(dat.find('\n', at)));
    Vec3 reaction;
    in >> reaction.x >> reaction.y >> reaction.z;
    // The group's one triangle, its area vector turned away from the copy's other
    // corner.
    const InputSurfaceGroup& group = info.surface_groups[size_t(copy)];
    ASSERT_EQ(group.triangles.size(), 1u);
    const auto& t = group.triangles[0];
    Vec3 area = cross(t[1] - t[0], t[2] - t[0]) * 0.5;
    Vec3 centre{0, 0, 0};
    for (int k = 0; k < 4; ++k)
      centre = centre + Vec3{corner[k].x + 10 * copy, corner[k].y, corner[k].z} * 0.25;
    if (dot(area, t[0] - centre) < 0) area = area * -1.0;
    EXPECT_NEAR(3 * reaction.x, area.x, 1e-5);
    EXPECT_NEAR(3 * reaction.y, area.y, 1e-5);
    EXPECT_NEAR(3 * reaction.z, area.z, 1e-5);
  }
}

// ---- TetGen .face ---------------------------------------------------------------

// The three-tet solid of tests/data/tetgen1.*, 1-based.
const char* const kNode = "6 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n6 0 0 -1\n";
const char* const kEle = "3 4 1\n1 1 2 3 4 1\n2 2 3 4 5 1\n3 1 3 2 6 2\n";
const char* const kFace =
    "# faces of the solid\n"  // 1
    "5 1\n"
    "1 1 2 3 0   # the interface: no group\n"
    "2 2 5 3 7\n"
    "3 1 3 6 2\n"  // 5
    "\n"
    "4 1 6 2 2\n"
    "5 3 5 4 7  12 -1\n"  // TetGen -nn: the tets beside it
    "# generated by hand\n";

Status read_tetgen(const std::string& face, TetMesh* mesh, ReadInfo* info = nullptr,
                   const std::string& node = kNode, const std::string& ele = kEle) {
  return read_tetgen_from_memory(node, ele, face, "m.node", "m.ele", "m.face", mesh, info);
}

TEST(IoInputGroups, TetGenFaceMarkersAreGroups) {
  TetMesh mesh;
  ReadInfo info;
  Status s = read_tetgen(kFace, &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1}, e{1, 1, 1}, f{0, 0, -1};
  ASSERT_EQ(info.surface_groups.size(), 2u);
  EXPECT_EQ(info.surface_groups[0].tag, 2);
  EXPECT_EQ(info.surface_groups[0].name, "");
  EXPECT_EQ(canonical(info.surface_groups[0].triangles),
            canonical(std::vector<std::array<Vec3, 3>>{{a, c, f}, {a, f, b}}));
  EXPECT_EQ(info.surface_groups[1].tag, 7);
  EXPECT_EQ(canonical(info.surface_groups[1].triangles),
            canonical(std::vector<std::array<Vec3, 3>>{{b, e, c}, {c, e, d}}));

  // 0-based numbering, as the .node file's.
  const std::string node0 = "6 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n5 0 0 -1\n";
  const std::string ele0 = "3 4 1\n0 0 1 2 3 1\n1 1 2 3 4 1\n2 0 2 1 5 2\n";
  s = read_tetgen("2 1\n0 1 4 2 7\n1 0 2 5 2\n", &mesh, &info, node0, ele0);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(info.surface_groups.size(), 2u);
  EXPECT_EQ(canonical(info.surface_groups[1].triangles),
            canonical(std::vector<std::array<Vec3, 3>>{{b, e, c}}));

  // No markers, or only marker 0 (TetGen's faces inside a region): no groups.
  for (const char* face : {"2 0\n1 1 2 3\n2 2 5 3\n", "1 1\n1 1 2 3 0\n", "0 1\n"}) {
    s = read_tetgen(face, &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_TRUE(info.surface_groups.empty()) << face;
  }

  // As TetGen reads them, a header's missing trailing fields take their defaults:
  // here no markers, and no .node attributes, markers or .ele region attribute.
  for (const char* face : {"2\n1 1 2 3\n2 2 5 3\n", "0\n", "0 # no faces\n"}) {
    s = read_tetgen(face, &mesh, &info,
                    "6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n6 0 0 -1\n",
                    "3\n1 1 2 3 4\n2 2 3 4 5\n3 1 3 2 6\n");
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_TRUE(info.surface_groups.empty()) << face;
    EXPECT_EQ(mesh.tet_count(), 3u);
    EXPECT_EQ(mesh.materials, std::vector<int32_t>(3, 0));
  }

  // A marker column the header does not declare ("2" or "2 0"): ignored, as TetGen
  // ignores it, with a note that says how to read it.
  for (const char* face : {"2\n1 1 2 3 4\n2 2 5 3 7\n", "2 0\n1 1 2 3 4\n2 2 5 3 7\n"}) {
    s = read_tetgen(face, &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_TRUE(info.surface_groups.empty());
    ASSERT_EQ(info.notes.size(), 1u);
    EXPECT_EQ(info.notes[0],
              "2 faces of m.face (the first at line 2) have a number after the corners, but the "
              "header declares no boundary markers ('count 0' or 'count'): ignored, as TetGen "
              "ignores it (make the header 'count 1' to read the markers as surface groups)");
  }

  // Markers no group tag can hold are in no group, and a note says so.
  s = read_tetgen("4 1\n1 1 2 3 -1\n2 2 5 3 7\n3 1 3 6 2147483648\n4 1 6 2 -3\n", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].tag, 7);
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_EQ(info.notes[0],
            "3 faces of m.face have markers outside 1 to 2147483647 (the first at line 2, "
            "marker -1); no surface group holds them");
  s = read_tetgen("1 1\n1 1 2 3 2147483648\n", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(info.surface_groups.empty());
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_NE(info.notes[0].find("1 face of m.face has a marker outside 1 to 2147483647 (the first "
                               "at line 2, marker 2147483648); no surface group holds it"),
            std::string::npos)
      << info.notes[0];

  // After a 10-node .ele, TetGen -o2 faces have 6 nodes (the corners first).
  const std::string node10 = std::string("7 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n") +
                             "5 1 1 1\n6 0 0 -1\n7 0.5 0 0\n";
  const std::string ele10 = "1 10 0\n1 1 2 3 4 7 7 7 7 7 7\n";
  s = read_tetgen("1 1\n1 1 2 3 7 7 7 4\n", &mesh, &info, node10, ele10);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(canonical(info.surface_groups[0].triangles),
            canonical(std::vector<std::array<Vec3, 3>>{{a, b, c}}));

  // read_mesh(): the .face beside the pair, if there is one.
  const std::string dir = test::output_dir("input_groups_tetgen");
  test::write_text(dir + "/s.node", kNode);
  test::write_text(dir + "/s.ele", kEle);
  ASSERT_TRUE(read_mesh(dir + "/s.ele", &mesh, &info).ok());
  EXPECT_TRUE(info.surface_groups.empty());
  test::write_text(dir + "/s.face", kFace);
  ASSERT_TRUE(read_mesh(dir + "/s.node", &mesh, &info).ok());
  EXPECT_EQ(info.surface_groups.size(), 2u);
  test::write_text(dir + "/s.face", "1 1\n1 1 2 3\n");
  s = read_mesh(dir + "/s.node", &mesh, &info);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind(dir + "/s.face:2: ", 0), 0u) << s.message();
}

TEST(IoInputGroups, TetGenBrokenFacesNameTheLine) {
  const struct {
    const char* face;
    int line;
    const char* words;
  } cases[] = {
      {"1 2\n1 1 2 3 1\n", 1, "boundary marker count must be 0 or 1"},
      {"2 1\n1 1 2 3 1\n", 1, "face count 2 is larger than the rest of the file can hold"},
      {"2 1\n1 1 2 3 1\n        \n", 2, "unexpected end of file, expected face index"},
      {"1 1\n1 1 2 3 1\n2 2 5 3 7\n", 3, "after the last face"},
      {"2 1\n1 1 2 3 1\n3 2 5 3 7\n", 3, "expected face index 2, found 3"},
      {"1 1\n0 1 2 3 1\n", 2, "expected face index 1, found 0"},
      {"1 1\n1 1 2 9 1\n", 2,
       "vertex index 9 is out of range (the points are numbered from 1 to 6"},
      {"1 1\n1 0 2 3 1\n", 2, "vertex index 0 is out of range"},
      {"1 1\n1 1 2 1 1\n", 2, "face 1 repeats a vertex"},
      {"1 1\n1 1 2 3\n", 2, "face 1 ends before its boundary marker"},
      {"1 1\n1 1 2\n3 1\n", 2, "face 1 ends before its vertex index"},
      {"1 0\n1 1 2 3 4 5 6\n", 2, "unexpected '6' after face 1"},
      {"1 1\n1 1 2 3 1 5 6 7\n", 2, "unexpected '7' after face 1"},
      {"1 1\n1 1 2 3 x\n", 2, "boundary marker 'x' is not an integer"},
      {"1 1\n1 1 2 3.5 1\n", 2, "vertex index '3.5' is not an integer"},
      {"1 1\n1 1 2 3 1", 2, "truncated"},
      {"1 1\n1 1 2 3 1 4 5", 2, "truncated"},
      {"-1 1\n", 1, "negative"},
      {"1 -1\n1 1 2 3\n", 1, "boundary marker count -1 is negative"},
      {"1 1 q\n1 1 2 3 1\n", 1, "unexpected 'q' in the header ('faces markers')"},
      {"0", 1, "truncated"},
  };
  TetMesh mesh;
  for (const auto& c : cases) {
    const Status s = read_tetgen(c.face, &mesh);
    ASSERT_FALSE(s.ok()) << c.face;
    SCOPED_TRACE(c.face);
    EXPECT_EQ(s.message().rfind("m.face:" + std::to_string(c.line) + ": ", 0), 0u) << s.message();
    EXPECT_NE(s.message().find(c.words), std::string::npos) << s.message();
  }
}

// Every cut of a .face fails naming it or reads all of its groups (the cut removed
// only comments, or the -nn columns of the last face).
TEST(IoInputGroups, TetGenEveryTruncationOfAFace) {
  TetMesh mesh;
  ReadInfo full;
  ASSERT_TRUE(read_tetgen(kFace, &mesh, &full).ok());
  const std::string text = kFace;
  for (size_t size = 0; size < text.size(); ++size) {
    ReadInfo info;
    const Status s = read_tetgen(text.substr(0, size), &mesh, &info);
    if (!s.ok()) {
      EXPECT_EQ(s.message().rfind("m.face:", 0), 0u) << s.message();
      continue;
    }
    ASSERT_EQ(info.surface_groups.size(), full.surface_groups.size()) << size;
    for (size_t g = 0; g < full.surface_groups.size(); ++g)
      EXPECT_EQ(canonical(info.surface_groups[g].triangles),
                canonical(full.surface_groups[g].triangles));
  }
}

// What write_mesh() writes to a TetGen pair with surface groups reads back as the
// same groups (tag = marker), which group_surface() names after their pairs again.
TEST(IoInputGroups, TetGenWrittenGroupsReadBack) {
  const std::string dir = test::output_dir("input_groups_tetgen_round");
  const TetMesh mesh = box2();
  const SurfaceGroups plain = groups_of(mesh);
  WriteOptions options;
  options.surface_groups = true;
  ASSERT_TRUE(write_mesh(dir + "/box2.node", mesh, options).ok());
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(dir + "/box2.ele", &back, &info).ok());
  test::expect_same_mesh(mesh, back);
  const auto written = written_triangles(mesh, plain);
  ASSERT_EQ(info.surface_groups.size(), plain.groups.size());
  for (size_t i = 0; i < plain.groups.size(); ++i) {
    EXPECT_EQ(info.surface_groups[i].tag, plain.groups[i].tag);
    EXPECT_EQ(info.surface_groups[i].name, "");
    EXPECT_EQ(canonical(info.surface_groups[i].triangles), written[i]);
  }
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(back, &groups, SurfacePatches(back, info.surface_groups)).ok());
  EXPECT_EQ(names_and_tags(groups), names_and_tags(plain));

  // A Gmsh file's own groups, through a TetGen pair: the same triangles under the
  // same tags (TetGen has no names).
  TetMesh input;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/groups41.msh"), &input, &info).ok());
  SurfaceGroups with_input;
  ASSERT_TRUE(group_surface(input, &with_input, SurfacePatches(input, info.surface_groups)).ok());
  options.groups = &with_input;
  ASSERT_TRUE(write_mesh(dir + "/groups.node", input, options).ok());
  ASSERT_TRUE(read_mesh(dir + "/groups.node", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), with_input.groups.size());
  std::vector<std::pair<int32_t, size_t>> read, wrote;
  for (const InputSurfaceGroup& g : info.surface_groups)
    read.push_back({g.tag, g.triangles.size()});
  for (const SurfaceGroup& g : with_input.groups) wrote.push_back({g.tag, g.triangles.size()});
  std::sort(wrote.begin(), wrote.end());
  EXPECT_EQ(read, wrote);
}

TEST(IoInputGroups, TetGenRandomDamageNeverCrashes) {
  std::mt19937 random(11);
  const char alphabet[] = "0123456789 -.#\nx";
  for (int trial = 0; trial < 4000; ++trial) {
    std::string face = kFace;
    for (int k = 0; k <= trial % 3; ++k)
      face[random() % face.size()] = alphabet[random() % (sizeof alphabet - 1)];
    if (trial % 5 == 0) face.resize(random() % face.size());
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_tetgen(face, &mesh, &info);
    if (!s.ok()) {
      ASSERT_EQ(s.message().rfind("m.face:", 0), 0u) << s.message();
      continue;
    }
    for (const InputSurfaceGroup& g : info.surface_groups) ASSERT_GE(g.tag, 1);
    SurfaceGroups groups;
    EXPECT_TRUE(group_surface(mesh, &groups, SurfacePatches(mesh, info.surface_groups)).ok());
  }
}

}  // namespace
}  // namespace tetlod
