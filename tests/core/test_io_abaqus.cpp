// Abaqus / CalculiX input (.inp): an Abaqus/CAE-like deck with a part, sets,
// GENERATE, sections and 10-node elements over continuation lines; Gmsh's way of
// writing physical groups as *ELSET after elementary *ELEMENT sets; what TetLOD
// writes reads back; broken decks name the line; random damage never crashes.
// (Gmsh's own .inp: test_io_gmsh_interop.cpp; meshio's: IoOtherTools.)
#include <gtest/gtest.h>

#include <random>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

// The two-tet mesh of test_io_malformed.cpp plus two tets below and beside it.
const char* const kMedit =
    "MeshVersionFormatted 2\nDimension 3\nVertices\n7\n"
    "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 0\n0 0 -1 0\n0 -1 0 0\n"
    "Tetrahedra\n4\n1 2 3 4 %d\n2 3 4 5 %d\n1 2 3 6 %d\n1 2 4 7 %d\nEnd\n";

TetMesh expected(int m1, int m2, int m3, int m4) {
  char text[512];
  std::snprintf(text, sizeof text, kMedit, m1, m2, m3, m4);
  TetMesh mesh;
  EXPECT_TRUE(read_mesh_from_memory(text, MeshFormat::kMedit, "e.mesh", &mesh).ok());
  return mesh;
}

// kMedit's points as an Abaqus *NODE block.
const char* const kNodes =
    "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 1, 1\n6, 0, 0, -1\n"
    "7, 0, -1, 0\n";

Status read(const std::string& text, TetMesh* mesh) {
  return read_mesh_from_memory(text, MeshFormat::kAbaqus, "a.inp", mesh);
}

const char* const kCaeDeck =
    "*Heading\n"
    "** a comment\n"
    "*Part, name=Motor\n"
    "*node\n"
    "1, 0., 0., 0.\n"
    "2, 1., 0., 0.\n"
    "3, 0., 1., 0.\n"
    "4, 0., 0., 1.\n"
    "5, 1., 1., 1.\n"
    "6, 0., 0., -1.\n"
    "7, 0., -1.\n"  // a blank z is 0
    "*Element, type=C3D4\n"
    "11, 1, 2, 3, 4\n"
    "12, 2, 3, 4, 5\n"
    "*Element, type=C3D10M, elset=QUADRATIC\n"
    "13, 1, 2, 3, 6, 1, 1,\n"  // a record over two lines
    "     1, 1, 1, 1\n"
    "*Element, type=S3\n"
    "20, 1, 2, 3\n"
    "*ELEMENT, TYPE=DC3D4, ELSET=LAST\n"
    "14, 1, 2, 4, 7\n"
    "*Elset, elset=STEEL, generate\n"
    "11, 12, 1\n"
    "*Elset, elset=AIR_3\n"
    "QUADRATIC, 14\n"
    "*Solid Section, elset=STEEL, material=Steel\n"
    ",\n"
    "*Solid Section, elset=AIR_3, material=AIR_3\n"
    "*End Part\n"
    "*Assembly, name=Assembly\n"
    "*Instance, name=Motor-1, part=Motor\n"
    "*End Instance\n"
    "*End Assembly\n"
    "*Material, name=Steel\n"
    "*Elastic\n"
    "210000., 0.3\n"
    "*Step\n"
    "*Static\n"
    "*End Step\n";

TEST(IoAbaqus, ReadsACaeDeckWithPartsSetsAndSections) {
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(kCaeDeck, MeshFormat::kAbaqus, "a.inp", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  // AIR_3 is material 3; Steel, without a number, the next one: 4.
  test::expect_same_mesh(expected(4, 4, 3, 3), mesh);
  EXPECT_EQ(info.format, MeshFormat::kAbaqus);
}

// A *SYSTEM at the global origin (or with no data line) moves nothing: read.
TEST(IoAbaqus, AGlobalSystemIsRead) {
  for (const std::string system : {"*SYSTEM\n0., 0., 0.\n", "*SYSTEM\n"}) {
    TetMesh mesh;
    const Status s = read(system + kNodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n", &mesh);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(mesh.tet_count(), 1u);
  }
}

// Gmsh: elementary sets on *ELEMENT, physical groups as *ELSET: the latter win.
TEST(IoAbaqus, ElsetsWinOverTheElementSet) {
  const std::string deck = std::string(kNodes) +
                           "*ELEMENT, type=C3D4, ELSET=Volume1\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n"
                           "*ELEMENT, type=C3D4, ELSET=Volume2\n3, 1, 2, 3, 6\n4, 1, 2, 4, 7\n"
                           "*ELSET,ELSET=material_5\n1, 3, \n"
                           "*ELSET,ELSET=material_9\n2, \n";
  TetMesh mesh;
  const Status s = read(deck, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_mesh(expected(5, 9, 5, 2), mesh);
}

// Abaqus/CAE's INTERNAL element sets (made for surfaces and loads) are not materials,
// even in a deck without sections, where the first *ELSET holding a tet gives its
// material; a *SURFACE still finds them.
TEST(IoAbaqus, InternalSetsAreNotMaterials) {
  const std::string deck =
      std::string(kNodes) +
      "*ELEMENT, type=C3D4\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n3, 1, 2, 3, 6\n4, 1, 2, 4, 7\n"
      "*Elset, elset=_Surf-1_S1, internal\n1, 3\n"
      "*ELSET, ELSET=Core2\n1, 2\n"
      "*ELSET, ELSET=Air7\n3, 4\n"
      "*Surface, type=ELEMENT, name=Surf-1\n_Surf-1_S1, S1\n";
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(deck, MeshFormat::kAbaqus, "a.inp", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_mesh(expected(2, 2, 7, 7), mesh);
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].name, "Surf-1");
  EXPECT_EQ(info.surface_groups[0].triangles.size(), 2u);
}

// Without sections, a tet in two *ELSETs takes the first; a note names the sets passed
// over. A set holding every tet ("Eall") counts last when other sets tell the tets
// apart (it made one material of everything); a note says so.
TEST(IoAbaqus, OverlappingSetsWithoutSectionsAreNamedInANote) {
  const std::string mesh =
      std::string(kNodes) +
      "*ELEMENT, type=C3D4\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n3, 1, 2, 3, 6\n4, 1, 2, 4, 7\n";
  auto read_deck = [&](const std::string& sets, TetMesh* out, std::string* notes) {
    ReadInfo info;
    const Status s = read_mesh_from_memory(mesh + sets, MeshFormat::kAbaqus, "a.inp", out, &info);
    EXPECT_TRUE(s.ok()) << s.message();
    notes->clear();
    for (const std::string& note : info.notes) *notes += note + "\n";
    return info;
  };
  TetMesh read;
  std::string notes;
  // Core2 and Air7 share tet 2: it takes Core2, listed first.
  read_deck(
      "*ELSET, ELSET=Core2\n1, 2, 1\n"  // 1 twice: one set, no overlap with itself
      "*ELSET, ELSET=Air7\n2, 3, 4\n",
      &read, &notes);
  EXPECT_EQ(read.materials, (std::vector<int32_t>{2, 2, 7, 7}));
  EXPECT_NE(notes.find("1 tetrahedra are in more than one *ELSET, and no *SOLID SECTION says "
                       "which is their material: each takes the first set in the file that holds "
                       "it, not Air7"),
            std::string::npos)
      << notes;
  // Eall first: the others give every tet its material, said once; no overlap note.
  read_deck(
      "*ELSET, ELSET=Eall, GENERATE\n1, 4\n*ELSET, ELSET=Core2\n1, 2\n"
      "*ELSET, ELSET=Air7\n3, 4\n",
      &read, &notes);
  EXPECT_EQ(read.materials, (std::vector<int32_t>{2, 2, 7, 7}));
  EXPECT_NE(notes.find("*ELSET Eall holds every tetrahedron, and no *SOLID SECTION says which "
                       "sets are materials: the materials are the other sets, and it only that of "
                       "the tetrahedra no other set holds"),
            std::string::npos)
      << notes;
  EXPECT_EQ(notes.find("more than one *ELSET"), std::string::npos) << notes;
  // Tets no other set holds keep Eall's material (the next free number, 3).
  read_deck("*ELSET, ELSET=Eall, GENERATE\n1, 4\n*ELSET, ELSET=Core2\n1, 2\n", &read, &notes);
  EXPECT_EQ(read.materials, (std::vector<int32_t>{2, 2, 3, 3}));
  // The same against the *ELEMENT blocks' sets.
  const std::string blocks = std::string(kNodes) +
                             "*ELEMENT, type=C3D4, ELSET=Lower1\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n"
                             "*ELEMENT, type=C3D4, ELSET=Upper2\n3, 1, 2, 3, 6\n4, 1, 2, 4, 7\n"
                             "*ELSET, ELSET=EALL\nLower1, Upper2\n";
  ASSERT_TRUE(read_mesh_from_memory(blocks, MeshFormat::kAbaqus, "a.inp", &read).ok());
  EXPECT_EQ(read.materials, (std::vector<int32_t>{1, 1, 2, 2}));
  // A set holding every tet with nothing else to tell them apart is the material.
  const ReadInfo one = read_deck("*ELSET, ELSET=Steel\n1, 2, 3, 4\n", &read, &notes);
  EXPECT_EQ(read.materials, (std::vector<int32_t>{1, 1, 1, 1}));
  ASSERT_EQ(one.material_names.size(), 1u);
  EXPECT_EQ(one.material_names[0].name, "Steel");  // as written
  EXPECT_EQ(notes.find("*ELSET"), std::string::npos) << notes;
}

// A node line ending in a comma is one node (CalculiX reads it so), not continued on
// the next line.
// A name's character of several UTF-8 bytes becomes one '_' in a set name, as any
// other character a label cannot hold (it was one a byte: "Kupfer_______2"; found by
// a user test), and the name reads back to its material.
TEST(IoAbaqus, NamesAreMadeLabelsACharacterAtATime) {
  const TetMesh mesh = test::make_grid_mesh(2, 1, 1, [](int i, int, int) { return i + 1; });
  const std::vector<MaterialName> names = {{2, "Kupfer \xc3\xbc \xc2\xb5"}};
  WriteOptions options;
  options.material_names = &names;
  const std::string dir = test::output_dir("abaqus_labels");
  ASSERT_TRUE(write_mesh(dir + "/k.inp", mesh, options).ok());
  const std::string text = test::read_text(dir + "/k.inp");
  EXPECT_NE(text.find("ELSET=Kupfer_____2\n"), std::string::npos) << text.substr(0, 600);
  TetMesh back;
  ASSERT_TRUE(read_mesh(dir + "/k.inp", &back).ok());
  EXPECT_EQ(back.materials, mesh.materials);
}

TEST(IoAbaqus, NodeLinesWithATrailingCommaAreOneNodeEach) {
  const std::string deck =
      "*NODE\n1, 0, 0, 0,\n2, 1, 0, 0,\n3, 0, 1, 0,\n4, 0, 0, 1,\n5, 1, 1, 1,\n6, 0, 0, -1,\n"
      "7, 0, -1, 0,\n"
      "*ELEMENT, type=C3D4, ELSET=M1\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n3, 1, 2, 3, 6\n"
      "4, 1, 2, 4, 7\n";
  TetMesh mesh;
  const Status s = read(deck, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_mesh(expected(1, 1, 1, 1), mesh);
}

// Two names with the same number are two materials: the first keeps it, the later
// one takes the next free number (as a name without digits does), after every
// number a name gives ("Coil7").
TEST(IoAbaqus, NamesWithTheSameNumberAreDifferentMaterials) {
  const std::string deck = std::string(kNodes) +
                           "*ELEMENT, type=C3D4, ELSET=Rotor1\n1, 1, 2, 3, 4\n"
                           "*ELEMENT, type=C3D4, ELSET=Stator1\n2, 2, 3, 4, 5\n"
                           "*ELEMENT, type=C3D4, ELSET=Vol01\n3, 1, 2, 3, 6\n"
                           "*ELEMENT, type=C3D4, ELSET=Coil7\n4, 1, 2, 4, 7\n";
  TetMesh mesh;
  const Status s = read(deck, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_mesh(expected(1, 8, 9, 7), mesh);
}

TEST(IoAbaqus, WrittenFilesReadBack) {
  const std::string dir = test::output_dir("abaqus");
  const TetMesh mesh = test::make_io_mesh();  // materials 0, 7 and INT32_MAX
  ASSERT_TRUE(write_mesh(dir + "/io.inp", mesh).ok());
  TetMesh back;
  const Status s = read_mesh(dir + "/io.inp", &back);
  ASSERT_TRUE(s.ok()) << s.message();
  test::expect_same_mesh(mesh, back);
}

TEST(IoAbaqus, BrokenDecksNameTheLine) {
  const std::string nodes = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";  // lines 1-5
  const struct {
    std::string deck;
    int line;
    const char* words;
  } cases[] = {
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3\n", 7, "has 3 nodes, its type 4"},
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 9\n", 7, "uses node 9, which is not defined"},
      // A C3D10's mid-side nodes are checked as its corners are.
      {nodes + "*ELEMENT, TYPE=C3D10\n1, 1, 2, 3, 4, 1, 2, 3, 4, 1, 16\n", 7,
       "element 1 uses node 16 (a mid-side node), which is not defined"},
      {nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n1, 1, 2, 3, 4\n", 8, "defined twice"},
      {nodes + "2, 5, 5, 5\n", 6, "node 2 is defined twice"},
      {nodes + "5, 1, 1, x\n", 6, "coordinate 'x' is not a finite number"},
      {nodes + "*ELEMENT\n", 6, "needs TYPE="},
      {nodes + "*INCLUDE, INPUT=mesh.inp\n", 6, "*INCLUDE is not followed"},
      {"*PART, NAME=A\n*END PART\n*PART, NAME=B\n", 3, "several parts"},
      {nodes + "*INSTANCE, NAME=I, PART=P\n1., 0., 0.\n", 7, "translation or rotation"},
      // A moved system or cylindrical coordinates, and nodes or elements from another
      // file: refused (they were read as plain coordinates, or not at all).
      {"*SYSTEM\n10., 0., 0.\n" + nodes, 2, "*SYSTEM (line 1) with a translation"},
      {"*NODE, SYSTEM=C\n1, 1, 0, 0\n", 1, "SYSTEM=C (cylindrical or spherical"},
      {"*NODE, INPUT=nodes.txt\n", 1, "*NODE, INPUT=nodes.txt is not followed"},
      {nodes + "*ELEMENT, TYPE=C3D4, INPUT=e.txt\n", 6, "*ELEMENT, INPUT=e.txt is not"},
      {nodes + "*ELSET, ELSET=S, GENERATE\n5, 1\n", 7, "first <= last"},
      {nodes + "*ELSET, ELSET=S, GENERATE\n1, 9000000000000000000\n", 7, "more members"},
      {nodes + "*ELSET, ELSET=S, GENERATE\n-9000000000000000000, 9000000000000000000\n", 7,
       "1 <= first"},
      {nodes + "*ELSET, ELSET=A, GENERATE\n1, 100000\n*ELSET, ELSET=B\nA, A, A, A, A, A, A, A\n"
               "*ELSET, ELSET=C\nB, B, B, B, B, B, B, B\n",
       11, "more members"},
      {nodes + "*ELSET, ELSET=S\nNOPE\n", 7, "neither an element id nor a set"},
      {nodes + "*SOLID SECTION, ELSET=NONE, MATERIAL=M\n", 6, "element set NONE is not defined"},
      {"1, 0, 0, 0\n", 1, "not an Abaqus input"},
  };
  for (const auto& c : cases) {
    TetMesh mesh;
    const Status s = read(c.deck, &mesh);
    ASSERT_FALSE(s.ok()) << c.deck;
    EXPECT_EQ(s.message().rfind("a.inp:" + std::to_string(c.line) + ": ", 0), 0u) << s.message();
    EXPECT_NE(s.message().find(c.words), std::string::npos) << s.message();
  }
}

TEST(IoAbaqus, RandomDamageNeverCrashes) {
  std::mt19937 random(2024);
  const std::string valid = kCaeDeck;
  const char alphabet[] = "0123456789,*.-= \nEGNSLTabc";
  for (int trial = 0; trial < 4000; ++trial) {
    std::string data = valid;
    for (int k = 0; k <= trial % 3; ++k) {
      data[random() % data.size()] = alphabet[random() % (sizeof alphabet - 1)];
    }
    if (trial % 5 == 0) data.resize(random() % data.size());
    test::expect_error_or_valid_mesh(data, MeshFormat::kAbaqus, "a.inp");
    if (testing::Test::HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace tetlod
