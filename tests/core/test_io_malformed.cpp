// Hand-made malformed variants of a small valid file of each format: each must fail
// with "name:LINE: ..." naming the right line and saying what is wrong.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// Replacements of whole lines (1-based) in a text.
using Edits = std::map<int, std::string>;

std::string edit_lines(const std::string& text, const Edits& edits) {
  std::istringstream in(text);
  std::string line, result;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto it = edits.find(number);
    result += (it != edits.end() ? it->second : line) + "\n";
  }
  return result;
}

struct Case {
  Edits edits;
  int line;          // expected line in the message
  const char* word;  // expected in the message
};

void expect_failures(MeshFormat format, const std::string& name, const std::string& valid,
                     const std::vector<Case>& cases) {
  TetMesh mesh;
  const Status ok = read_mesh_from_memory(valid, format, name, &mesh);
  ASSERT_TRUE(ok.ok()) << ok.message();
  for (const Case& c : cases) {
    const std::string text = edit_lines(valid, c.edits);
    SCOPED_TRACE(text);
    const Status status = read_mesh_from_memory(text, format, name, &mesh);
    ASSERT_FALSE(status.ok());
    const std::string where = name + ":" + std::to_string(c.line) + ": ";
    EXPECT_EQ(status.message().rfind(where, 0), 0u) << status.message();
    EXPECT_NE(status.message().find(c.word), std::string::npos) << status.message();
  }
}

const char* const kMedit =
    "MeshVersionFormatted 2\n"  // 1
    "Dimension 3\n"
    "Vertices\n"
    "5\n"
    "0 0 0 0\n"  // 5
    "1 0 0 0\n"
    "0 1 0 0\n"
    "0 0 1 0\n"
    "1 1 1 0\n"
    "Tetrahedra\n"  // 10
    "2\n"
    "1 2 3 4 1\n"
    "2 3 4 5 2\n"
    "End\n";

TEST(IoMalformed, Medit) {
  expect_failures(MeshFormat::kMedit, "m.mesh", kMedit,
                  {
                      {{{4, "6"}}, 10, "not a number"},              // too many vertices announced
                      {{{4, "4"}}, 9, "count"},                      // too few announced
                      {{{11, "3"}}, 11, "larger than"},              // too many tets announced
                      {{{12, "0 2 3 4 1"}}, 12, "start at 1"},       // index 0 in a 1-based file
                      {{{12, "1 2 3 9 1"}}, 12, "only 5 vertices"},  // index out of range
                      {{{6, "nan 0 0 0"}}, 6, "not a finite"},       // NaN
                      {{{6, "1 inf 0 0"}}, 6, "not a finite"},       // infinity
                      {{{6, "1 0 1e999 0"}}, 6, "overflow"},         // overflowing number
                      {{{6, "1 0 0x 0"}}, 6, "not a number"},        // garbage
                      {{{4, "-5"}}, 4, "negative"},                  // negative count
                      {{{4, "99999999999"}}, 4, "larger than"},      // huge count
                      {{{13, "1 2 3 4 2"}}, 13, "duplicates"},       // duplicate tet
                      {{{9, "0.5 0.5 0 0"}, {13, "1 2 3 5 2"}}, 13, "degenerate"},  // zero volume
                      {{{12, "1 2 2 4 1"}}, 12, "repeats vertex"},          // repeated vertex
                      {{{12, "1 2 3 4 -1"}}, 12, "must be >= 0"},           // negative material
                      {{{12, "1 2 3 4 99999999999"}}, 12, "out of range"},  // material beyond int32
                      {{{10, "Tetrahedrons"}}, 10, "unknown keyword"},
                      {{{2, "Dimension 2"}}, 2, "3-dimensional"},
                      {{{1, "MeshVersion 2"}}, 1, "not a Medit file"},
                      {{{3, "Triangles"}, {4, "6"}}, 10, "triangle vertex index"},
                  });
}

const char* const kGmsh22 =
    "$MeshFormat\n"  // 1
    "2.2 0 8\n"
    "$EndMeshFormat\n"
    "$Nodes\n"
    "5\n"  // 5
    "1 0 0 0\n"
    "2 1 0 0\n"
    "3 0 1 0\n"
    "4 0 0 1\n"
    "5 1 1 1\n"  // 10
    "$EndNodes\n"
    "$Elements\n"
    "2\n"
    "1 4 2 1 1 1 2 3 4\n"
    "2 4 2 2 2 2 3 4 5\n"  // 15
    "$EndElements\n";

TEST(IoMalformed, Gmsh22) {
  expect_failures(MeshFormat::kGmsh22, "m.msh", kGmsh22,
                  {
                      {{{2, "2.2 1 8"}}, 2, "byte-order check"},
                      {{{2, "2.2 2 8"}}, 2, "is not 0 (ASCII) or 1 (binary)"},
                      {{{2, "3.0 0 8"}}, 2, "unsupported .msh version"},
                      {{{5, "6"}}, 11, "not an integer"},
                      {{{5, "4"}}, 10, "wrong count"},
                      {{{13, "3"}}, 16, "not an integer"},
                      {{{14, "1 4 2 1 1 1 2 3 9"}}, 14, "not in $Nodes"},
                      // A 10-node tet's other nodes are checked as its corners are.
                      {{{14, "1 11 2 1 1 1 2 3 4 5 1 2 3 4 16"}},
                       14,
                       "element 1 uses node 16 (a higher-order node), which is not in $Nodes"},
                      {{{14, "1 4 2 1 1 0 2 3 4"}}, 14, "not in $Nodes"},
                      {{{7, "2 nan 0 0"}}, 7, "not a finite"},
                      {{{7, "2 1 -inf 0"}}, 7, "not a finite"},
                      {{{7, "2 1 0 -1e999"}}, 7, "overflow"},
                      {{{7, "2 1 0 zz"}}, 7, "not a number"},
                      {{{5, "-1"}}, 5, "negative"},
                      {{{5, "99999999999"}}, 5, "larger than"},
                      {{{15, "2 4 2 2 2 1 2 3 4"}}, 15, "duplicates"},
                      {{{14, "1 4 2 1 1 1 2 2 4"}}, 14, "repeats vertex"},
                      {{{10, "5 0.5 0.5 0"}, {15, "2 4 2 2 2 1 2 3 5"}}, 15, "degenerate"},
                      {{{7, "1 1 0 0"}}, 7, "defined twice"},
                      {{{15, "1 4 2 2 2 2 3 4 5"}}, 15, "used twice"},
                      {{{14, "1 4 2 -3 1 1 2 3 4"}}, 14, "must be >= 0"},
                      {{{4, "$Elements"}}, 4, "before $Nodes"},
                      {{{11, "$EndNode"}}, 11, "$EndNodes"},
                      {{{12, "Elements"}}, 12, "expected a section"},
                  });
}

const char* const kGmsh41 =
    "$MeshFormat\n"  // 1
    "4.1 0 8\n"
    "$EndMeshFormat\n"
    "$Entities\n"
    "0 0 0 1\n"  // 5
    "7 0 0 0 1 1 1 1 3 0\n"
    "$EndEntities\n"
    "$Nodes\n"
    "1 5 1 5\n"
    "3 7 0 5\n"  // 10
    "1\n"
    "2\n"
    "3\n"
    "4\n"
    "5\n"  // 15
    "0 0 0\n"
    "1 0 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "1 1 1\n"  // 20
    "$EndNodes\n"
    "$Elements\n"
    "1 2 1 2\n"
    "3 7 4 2\n"
    "1 1 2 3 4\n"  // 25
    "2 2 3 4 5\n"
    "$EndElements\n";

TEST(IoMalformed, Gmsh41) {
  expect_failures(MeshFormat::kGmsh41, "m.msh", kGmsh41,
                  {
                      {{{2, "4.1 1 8"}}, 2, "byte-order check"},
                      {{{2, "4.0 0 8"}}, 2, "unsupported .msh version"},
                      {{{9, "1 6 1 6"}}, 20, "header says 6"},
                      {{{9, "1 6 1 6"}, {10, "3 7 0 6"}}, 16, "out of range"},
                      {{{24, "3 7 4 3"}}, 24, "more elements"},
                      {{{26, "2 2 3 4 6"}}, 26, "not in $Nodes"},
                      {{{17, "1 nan 0"}}, 17, "not a finite"},
                      {{{17, "1 inf 0"}}, 17, "not a finite"},
                      {{{17, "1 1e999 0"}}, 17, "overflow"},
                      {{{17, "1 0 #"}}, 17, "not a number"},
                      {{{9, "1 -5 1 5"}}, 9, "negative"},
                      {{{23, "1 99999999999 1 2"}}, 23, "larger than"},
                      {{{26, "2 1 2 3 4"}}, 26, "duplicates"},
                      {{{25, "1 1 2 3 3"}}, 25, "repeats vertex"},
                      {{{20, "0.5 0.5 0"}, {26, "2 1 2 3 5"}}, 26, "degenerate"},
                      {{{6, "7 0 0 0 1 1 1 1 -3 0"}}, 25, "must be >= 0"},
                      {{{10, "3 7 2 5"}}, 10, "parametric flag"},
                  });
}

const char* const kTetGenNode =
    "5 3 0 0\n"  // 1
    "1 0 0 0\n"
    "2 1 0 0\n"
    "3 0 1 0\n"
    "4 0 0 1\n"  // 5
    "5 1 1 1\n";
const char* const kTetGenEle =
    "2 4 1\n"  // 1
    "1 1 2 3 4 1\n"
    "2 2 3 4 5 2\n";

struct TetGenCase {
  Edits node_edits, ele_edits;
  const char* name;  // the file named in the message
  int line;
  const char* word;
};

TEST(IoMalformed, TetGen) {
  const std::vector<TetGenCase> cases = {
      {{{1, "6 3 0 0"}}, {}, "m.node", 6, "end of file"},
      {{{1, "4 3 0 0"}}, {}, "m.node", 6, "wrong count"},
      {{}, {{1, "3 4 1"}}, "m.ele", 3, "end of file"},
      {{}, {{2, "1 0 2 3 4 1"}}, "m.ele", 2, "out of range"},
      {{},
       {{2, "1 1 2 3 9 1"}},
       "m.ele",
       2,
       "vertex index 9 is out of range (the points are numbered from 1 to 5)"},
      {{}, {{2, "1 1 2 3 6 1"}}, "m.ele", 2, "vertex index 6 is out of range"},
      // A 10-node tet's mid-side points are checked as its corners are.
      {{},
       {{1, "2 10 1"}, {2, "1 1 2 3 4 5 1 2 3 4 9 1"}, {3, "2 2 3 4 5 1 2 3 4 5 1 2"}},
       "m.ele",
       2,
       "vertex index 9 is out of range"},
      {{{3, "2 nan 0 0"}}, {}, "m.node", 3, "not a finite"},
      {{{3, "2 INF 0 0"}}, {}, "m.node", 3, "not a finite"},
      {{{3, "2 1e999 0 0"}}, {}, "m.node", 3, "overflow"},
      {{{3, "2 1 0 0q"}}, {}, "m.node", 3, "not a number"},
      {{{1, "-5 3 0 0"}}, {}, "m.node", 1, "negative"},
      {{{1, "99999999999 3 0 0"}}, {}, "m.node", 1, "larger than"},
      {{}, {{3, "2 1 2 3 4 2"}}, "m.ele", 3, "duplicates"},
      {{}, {{3, "2 1 2 2 4 2"}}, "m.ele", 3, "repeats vertex"},
      {{{6, "5 0.5 0.5 0"}}, {{3, "2 1 2 3 5 2"}}, "m.ele", 3, "degenerate"},
      {{}, {{2, "1 1 2 3 4 1.5"}}, "m.ele", 2, "not an integer"},
      {{}, {{3, "7 2 3 4 5 2"}}, "m.ele", 3, "expected tetrahedron index 2"},
      {{{2, "2 0 0 0"}}, {}, "m.node", 2, "must be 0 or 1"},
      {{{1, "5 2 0 0"}}, {}, "m.node", 1, "3-dimensional"},
      // A 2-D file's short lines: its dimension is said, not a count too large.
      {{{1, "5 2 0 0"}, {2, "1 0 0"}, {3, "2 1 0"}, {4, "3 0 1"}, {5, "4 0 0"}, {6, "5 1 1"}},
       {},
       "m.node",
       1,
       "only 3-dimensional points are supported (dimension 2)"},
      {{}, {{1, "2 6 1"}}, "m.ele", 1, "4 or 10"},
      {{{1, "5 3 0 0 z"}}, {}, "m.node", 1, "unexpected 'z' in the header"},
      {{{1, "5 3 0 x"}}, {}, "m.node", 1, "boundary marker count 'x' is not an integer"},
      {{}, {{1, "2 4 -1"}}, "m.ele", 1, "attribute count -1 is negative"},
      {{}, {{2, "1 1 2 3 4 1 x"}}, "m.ele", 2, "unexpected 'x' after the tetrahedron"},
      {{{3, "2 1 0 0 7 z"}}, {}, "m.node", 3, "unexpected 'z' after the point"},
  };
  TetMesh mesh;
  ASSERT_TRUE(read_tetgen_from_memory(kTetGenNode, kTetGenEle, "m.node", "m.ele", &mesh).ok());
  // As TetGen does, numbers after the fields a header declares are ignored: a header
  // "2" (no region attribute) over lines that have one reads material 0.
  ASSERT_TRUE(read_tetgen_from_memory(edit_lines(kTetGenNode, {{3, "2 1 0 0 1"}}),
                                      edit_lines(kTetGenEle, {{1, "2"}}), "m.node", "m.ele", &mesh)
                  .ok());
  EXPECT_EQ(mesh.tet_count(), 2u);
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{0, 0}));
  // So are numbers after the fields of a header itself, as TetGen ignores them.
  TetMesh extra;
  ASSERT_TRUE(read_tetgen_from_memory(edit_lines(kTetGenNode, {{1, "5 3 0 0 0 9"}}),
                                      edit_lines(kTetGenEle, {{1, "2 4 1 7"}}), "m.node", "m.ele",
                                      &extra)
                  .ok());
  ASSERT_TRUE(read_tetgen_from_memory(kTetGenNode, kTetGenEle, "m.node", "m.ele", &mesh).ok());
  EXPECT_EQ(extra.tets, mesh.tets);
  EXPECT_EQ(extra.materials, mesh.materials);
  for (const TetGenCase& c : cases) {
    const std::string node = edit_lines(kTetGenNode, c.node_edits);
    const std::string ele = edit_lines(kTetGenEle, c.ele_edits);
    SCOPED_TRACE(node + "----\n" + ele);
    const Status status = read_tetgen_from_memory(node, ele, "m.node", "m.ele", &mesh);
    ASSERT_FALSE(status.ok());
    const std::string where = std::string(c.name) + ":" + std::to_string(c.line) + ": ";
    EXPECT_EQ(status.message().rfind(where, 0), 0u) << status.message();
    EXPECT_NE(status.message().find(c.word), std::string::npos) << status.message();
  }
}

const char* const kVtk =
    "# vtk DataFile Version 3.0\n"  // 1
    "t\n"
    "ASCII\n"
    "DATASET UNSTRUCTURED_GRID\n"
    "POINTS 5 double\n"  // 5
    "0 0 0\n"
    "1 0 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "1 1 1\n"  // 10
    "CELLS 2 10\n"
    "4 0 1 2 3\n"
    "4 1 2 3 4\n"
    "CELL_TYPES 2\n"
    "10\n"  // 15
    "10\n"
    "CELL_DATA 2\n"
    "SCALARS material int 1\n"
    "LOOKUP_TABLE default\n"
    "1\n"  // 20
    "2\n";

TEST(IoMalformed, VtkLegacy) {
  expect_failures(
      MeshFormat::kVtkLegacy, "m.vtk", kVtk,
      {
          {{{3, "TEXT"}}, 3, "expected ASCII or BINARY"},
          {{{4, "DATASET POLYDATA"}}, 4, "UNSTRUCTURED_GRID"},
          {{{1, "# vtk"}}, 1, "not a VTK"},
          {{{5, "POINTS 6 double"}}, 11, "not a number"},
          {{{11, "CELLS 2 11"}}, 13, "announced 11"},
          {{{11, "CELLS 3 15"}}, 14, "not an integer"},
          {{{12, "4 0 1 2 9"}}, 12, "uses point 9, but there are only 5 points"},
          // 0-based: point 5 is one past the last (not "vertex 6").
          {{{12, "4 0 1 2 5"}}, 12, "uses point 5, but there are only 5 points (numbered from 0)"},
          {{{12, "4 0 1 2 -1"}}, 12, "out of range"},
          {{{7, "nan 0 0"}}, 7, "not a finite"},
          {{{7, "inf 0 0"}}, 7, "not a finite"},
          {{{7, "1e999 0 0"}}, 7, "overflow"},
          {{{7, "1 0 O"}}, 7, "not a number"},
          {{{5, "POINTS -5 double"}}, 5, "negative"},
          {{{5, "POINTS 99999999999 double"}}, 5, "larger than"},
          {{{13, "4 0 1 2 3"}}, 13, "duplicates"},
          {{{13, "4 1 2 2 4"}}, 13, "repeats vertex"},
          {{{10, "0.5 0.5 0"}, {13, "4 0 1 2 4"}}, 13, "degenerate"},
          {{{20, "-1"}}, 12, "must be >= 0"},
          {{{20, "1.5"}}, 20, "not an integer"},
          {{{14, "CELL_TYPES 3"}}, 14, "entries for 2 cells"},
          {{{17, "CELL_DATA 3"}}, 17, "entries for 2 cells"},
          {{{13, "3 1 2 3"}, {11, "CELLS 2 9"}}, 13, "has 3 points"},
          // Triangles (kept as surface groups) are checked as tets are.
          {{{16, "5"}}, 13, "cell 1 of type 5 has 4 points"},
          {{{13, "3 1 2 9"}, {11, "CELLS 2 9"}, {16, "5"}},
           13,
           "cell 1 uses point 9, but there are only 5 points"},
          {{{18, "SCALARS material int 7"}}, 18, "count from 1 to 4"},
          {{{18, "SCALAR material int 1"}}, 18, "unknown keyword"},
      });
}

const char* const kVtu =
    "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"  // 1
    "<UnstructuredGrid>\n"
    "<Piece NumberOfPoints=\"5\" NumberOfCells=\"2\">\n"
    "<Points>\n"
    "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"  // 5
    "0 0 0\n"
    "1 0 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "1 1 1\n"  // 10
    "</DataArray>\n"
    "</Points>\n"
    "<Cells>\n"
    "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n"
    "0 1 2 3\n"  // 15
    "1 2 3 4\n"
    "</DataArray>\n"
    "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 8</DataArray>\n"
    "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 10</DataArray>\n"
    "</Cells>\n"  // 20
    "<CellData>\n"
    "<DataArray type=\"Int32\" Name=\"material\" format=\"ascii\">1 2</DataArray>\n"
    "</CellData>\n"
    "</Piece>\n"
    "</UnstructuredGrid>\n"  // 25
    "</VTKFile>\n";

TEST(IoMalformed, Vtu) {
  const std::string points = "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=";
  expect_failures(
      MeshFormat::kVtu, "m.vtu", kVtu,
      {
          {{{5, points + "\"binary\">"}}, 5, "not valid base64"},
          {{{5, points + "\"appended\" offset=\"0\"/>"}, {11, ""}, {6, ""}},
           5,
           "no <AppendedData>"},
          {{{3, "<Piece NumberOfPoints=\"6\" NumberOfCells=\"2\">"}}, 10, "end of file"},
          {{{3, "<Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">"}}, 10, "more values"},
          {{{15, "0 1 2 9"}}, 15, "uses point 9, but there are only 5 points"},
          {{{15, "0 1 2 5"}}, 15, "uses point 5, but there are only 5 points (numbered from 0)"},
          {{{15, "0 1 2 -3"}}, 15, "out of range"},
          {{{7, "nan 0 0"}}, 7, "not a finite"},
          {{{7, "inf 0 0"}}, 7, "not a finite"},
          {{{7, "1e999 0 0"}}, 7, "overflow"},
          {{{7, "1 0 0,"}}, 7, "not a number"},
          {{{3, "<Piece NumberOfPoints=\"-5\" NumberOfCells=\"2\">"}}, 3, "needs a count"},
          {{{3, "<Piece NumberOfPoints=\"99999999999\" NumberOfCells=\"2\">"}}, 3, "larger than"},
          {{{16, "0 1 2 3"}}, 16, "duplicates"},
          {{{16, "1 2 2 4"}}, 16, "repeats vertex"},
          {{{10, "0.5 0.5 0"}, {16, "0 1 2 4"}}, 16, "degenerate"},
          {{{22, "<DataArray type=\"Int32\" Name=\"material\" format=\"ascii\">1 -2</DataArray>"}},
           16,
           "must be >= 0"},
          {{{19, "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 5</DataArray>"}},
           16,
           "cell 1 of type 5 has 4 points"},
          {{{16, "1 2 9"},
            {18, "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 7</DataArray>"},
            {19, "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 5</DataArray>"}},
           16,
           "cell 1 uses point 9, but there are only 5 points"},
          {{{24, "</Pieces>"}}, 24, "does not match"},
          {{{1, "<VTKFile type=\"PolyData\" version=\"0.1\">"}}, 1, "UnstructuredGrid"},
          {{{18, "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 9</DataArray>"}},
           18,
           "past the connectivity"},
          {{{21, "<AppendedData encoding=\"raw\">"}, {23, "</AppendedData>"}}, 21, "needs '_'"},
      });
}

const char* const kNastran =
    "$ two tets\n"  // 1
    "GRID,1,,0.,0.,0.\n"
    "GRID,2,,1.,0.,0.\n"
    "GRID,3,,0.,1.,0.\n"
    "GRID,4,,0.,0.,1.\n"  // 5
    "GRID,5,,1.,1.,1.\n"
    "CTETRA,1,3,1,2,3,4\n"
    "CTETRA,2,7,2,3,4,5\n"
    "ENDDATA\n";

TEST(IoMalformed, Nastran) {
  expect_failures(
      MeshFormat::kNastran, "m.bdf", kNastran,
      {
          {{{3, "GRID,2,5,1.,0.,0."}}, 3, "coordinate system '5' is not supported"},
          {{{3, "GRID,2,,1.2.3,0.,0."}}, 3, "x coordinate '1.2.3' is not a finite number"},
          {{{4, "GRID,3,,0.,1.e999,0."}}, 4, "y coordinate"},
          {{{4, "GRID,2,,0.,1.,0."}}, 4, "GRID 2 is defined twice"},
          {{{4, "GRID,0,,0.,1.,0."}}, 4, "id '0' is not an integer >= 1"},
          {{{7, "CTETRA,1,3,1,2,3,99"}}, 7, "uses GRID 99, which is not defined"},
          {{{8, "CTETRA,2,7,2,3,,5"}}, 8, "grid '' is not an integer >= 1"},
          {{{8, "CTETRA,2,3000000000,2,3,4,5"}}, 8, "too large for a material id"},
          {{{8, "CTETRA,2,-1,2,3,4,5"}}, 8, "property id (PID) '-1'"},
          {{{2, "+,1"}}, 2, "a continuation line without an entry"},
          {{{9, ""}}, 8, "no ENDDATA"},
          {{{1, "$ TetLOD material 0 = PID x"}}, 1, "not a positive integer"},
          {{{8, "CTETRA,2,7,2,3,4,1"}}, 8, "duplicates"},
          {{{8, "CTETRA,2,7,2,3,4,4"}}, 8, "repeats vertex"},
          {{{6, "INCLUDE 'grids.bdf'"}}, 6, "INCLUDE is not followed"},
          // Surface elements (kept as surface groups) are checked as tets are.
          {{{1, "CTRIA3,9,20,1,2,99"}}, 1, "CTRIA3 9 uses GRID 99, which is not defined"},
          {{{1, "CTRIA6,9,20,1,x,3,4,5,6"}}, 1, "CTRIA6 9: grid 'x' is not an integer >= 1"},
          {{{1, "CTRIA3,9,-2,1,2,3"}}, 1, "property id (PID) '-2'"},
          // An element id given twice, as a GRID's; a 10-node CTETRA's mid-side grids
          // are checked as its corners are (they were not read at all).
          {{{8, "CTETRA,1,7,2,3,4,5"}}, 8, "CTETRA 1 is defined twice"},
          {{{8, "CTETRA,2,7,2,3,4,5,1,2\n+,3,4,5,77"}},
           8,
           "CTETRA 2 uses GRID 77 (a mid-side node), which is not defined"},
          {{{8, "CTETRA,2,7,2,3,4,5,x"}}, 8, "grid 'x' is not an integer >= 1"},
      });
}

// A CTETRA with a blank or zero PID (meshio leaves it blank for a mesh without
// properties) is read as material 0, with a note: Nastran would take its element id.
TEST(IoMalformed, NastranBlankPidIsNoted) {
  TetMesh mesh;
  ReadInfo info;
  const std::string text =
      edit_lines(kNastran, {{7, "CTETRA,1,,1,2,3,4"}, {8, "CTETRA,2,0,2,3,4,5"}});
  const Status s = read_mesh_from_memory(text, MeshFormat::kNastran, "m.bdf", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.materials, (std::vector<int32_t>{0, 0}));
  bool noted = false;
  for (const std::string& note : info.notes)
    noted |= note.find("2 CTETRAs have a blank or zero PID") != std::string::npos;
  EXPECT_TRUE(noted);
}

// Inputs the fuzzers found.
TEST(IoMalformed, FuzzerFindings) {
  TetMesh mesh;
  // A self-closing root element (was a read of back() on an empty stack).
  const Status root = read_mesh_from_memory("<VTKFile type=\"UnstructuredGrid\"/>\n",
                                            MeshFormat::kVtu, "f.vtu", &mesh);
  EXPECT_EQ(root.message(), "f.vtu:1: no <Piece>");
  // A Nastran real of 40 signs: an 'E' goes before each (was a write past a buffer).
  const Status signs = read_mesh_from_memory("GRID,1,,0.," + std::string(40, '-') + ",0.\n",
                                             MeshFormat::kNastran, "f.bdf", &mesh);
  EXPECT_EQ(signs.message(),
            "f.bdf:1: GRID 1: y coordinate '" + std::string(40, '-') + "' is not a finite number");
}

}  // namespace
}  // namespace tetlod
