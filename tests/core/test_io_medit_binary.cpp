// Binary Medit files (.meshb, libMeshb's layout), versions 1 to 4 in both byte orders:
// written here byte by byte, they read as the mesh written; TetLOD's own .meshb reads
// back as it wrote it, and as its .mesh reads; every truncation and every broken header
// fails with "name: byte N: ...", and random damage never crashes.
// (test_io_other_tools.cpp reads the .meshb files of meshio and FreeFEM.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>

#include "core/io/mesh_formats.h"
#include "core/io/mesh_io.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

// libMeshb's keyword codes used here.
constexpr int32_t kDimension = 3, kVertices = 4, kTriangles = 6, kTetrahedra = 8, kPrisms = 9,
                  kCorners = 13, kTetrahedraP2 = 30, kFloatingPointPrecision = 155;

// What a test changes in the otherwise valid file.
struct Damage {
  int32_t one = 1;      // the byte-order word
  int32_t version = 0;  // if not 0, instead of the real one
  bool dimension_first = true;
  int32_t dimension = 3;
  int64_t vertex_count = 6;
  double first_x = 0.1;
  int64_t corner = 1;  // the first tet's first corner (1-based)
  int64_t last_material = std::numeric_limits<int32_t>::max();
  int64_t corners_next = -1;  // if >= 0, the Corners keyword's next position
  bool end_keyword = true;
};

// The mesh of test::make_io_mesh() (6 vertices, tets {0,1,2,3} of material 0,
// {1,2,3,4} of 7 and {0,2,1,5} of INT32_MAX, the last as a TetrahedraP2), with a
// keyword TetLOD skips (Corners), a triangle of reference 5, and a prism.
std::string meshb(int version, bool swap, const Damage& d = {}) {
  const TetMesh mesh = test::make_io_mesh();
  test::GmfWriter f(version, swap);
  if (!d.dimension_first) {
    f.keyword(kCorners);
    f.integer(0);
  }
  f.keyword(kDimension);
  f.i32(d.dimension);
  f.keyword(kCorners);
  if (d.corners_next >= 0) f.override_next(d.corners_next);
  f.integer(2);
  f.integer(1);
  f.integer(2);
  f.keyword(kVertices);
  f.integer(d.vertex_count);
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    const Vec3& p = mesh.positions[i];
    f.real(i == 0 ? d.first_x : p.x);
    f.real(p.y);
    f.real(p.z);
    f.integer(int64_t(i % 2));
  }
  f.keyword(kTriangles);
  f.integer(1);
  for (int64_t v : {1, 3, 2, 5}) f.integer(v);
  f.keyword(kTetrahedra);
  f.integer(2);
  for (size_t t = 0; t < 2; ++t) {
    for (size_t k = 0; k < 4; ++k)
      f.integer(t == 0 && k == 0 ? d.corner : int64_t(mesh.tets[t][k]) + 1);
    f.integer(mesh.materials[t]);
  }
  f.keyword(kTetrahedraP2);
  f.integer(1);
  for (uint32_t v : mesh.tets[2]) f.integer(int64_t(v) + 1);
  for (int64_t mid : {1, 2, 3, 4, 5, 6}) f.integer(mid);  // mid-edge nodes: not read
  f.integer(d.last_material);
  f.keyword(kPrisms);
  f.integer(1);
  for (int k = 0; k < 7; ++k) f.integer(1);
  std::string out = f.finish(d.end_keyword);
  if (d.one != 1 || d.version != 0) {
    int32_t words[2] = {d.one, d.version != 0 ? d.version : version};
    std::memcpy(&out[0], words, 8);
  }
  return out;
}

Status read(const std::string& data, TetMesh* mesh, ReadInfo* info = nullptr) {
  return read_mesh_from_memory(data, MeshFormat::kMeditBinary, "b.meshb", mesh, info);
}

// `v` rounded to a float. Through a volatile: Debian's GCC 12.2 at -O2 drops the
// rounding of some coordinates in a loop such as `for (Vec3& p : positions) p =
// {float(p.x), float(p.y), float(p.z)};` (the SLP vectorizer: right with
// -fno-tree-slp-vectorize, at -O0 and with clang; reproduced in a 10-line program).
double to_float(double v) {
  volatile float f = float(v);
  return f;
}

// make_io_mesh() as a version 1 file holds it: coordinates rounded to floats.
TetMesh expected_mesh(int version) {
  TetMesh mesh = test::make_io_mesh();
  if (version == 1)
    for (Vec3& p : mesh.positions) p = {to_float(p.x), to_float(p.y), to_float(p.z)};
  return mesh;
}

TEST(IoMeditBinary, ReadsEveryVersionInBothByteOrders) {
  for (int version = 1; version <= 4; ++version) {
    for (bool swap : {false, true}) {
      SCOPED_TRACE(std::to_string(version) + (swap ? " big-endian" : " little-endian"));
      TetMesh mesh;
      ReadInfo info;
      const Status s = read(meshb(version, swap), &mesh, &info);
      ASSERT_TRUE(s.ok()) << s.message();
      EXPECT_EQ(info.format, MeshFormat::kMeditBinary);
      test::expect_same_mesh(expected_mesh(version), mesh);
      ASSERT_EQ(info.surface_groups.size(), 1u);
      EXPECT_EQ(info.surface_groups[0].tag, 5);
      ASSERT_EQ(info.surface_groups[0].triangles.size(), 1u);
      EXPECT_EQ(info.surface_groups[0].triangles[0][1], mesh.positions[2]);
      ASSERT_EQ(info.notes.size(), 2u);
      EXPECT_EQ(info.notes[0],
                "1 TetrahedraP2 (10-node) were read as 4-node tetrahedra (by their corners; "
                "their mid-edge points are dropped)");
      EXPECT_EQ(info.notes[1].rfind("skipped 1 Prisms: TetLOD reads 4-node tetrahedra only", 0), 0u)
          << info.notes[1];
    }
  }
}

// What TetLOD writes reads back as the mesh and groups it wrote, and as the ASCII
// .mesh of the same mesh reads.
// libMeshb's FloatingPointPrecision keyword (a writer's GmfSetFloatPrecision()) sets
// the size of the reals after it, whatever the version: 32-bit coordinates in a
// version 2 or 4 file read as the floats they are; 64 changes nothing; after the
// vertices, a size other than theirs is an error, not a misread. (The ASCII reader
// skips the keyword.)
TEST(IoMeditBinary, FloatingPointPrecisionSetsTheRealSize) {
  const TetMesh mesh = test::make_single_tet();
  auto file = [&](int version, int64_t bits, bool before_vertices) {
    test::GmfWriter f(version, false);
    f.keyword(kDimension);
    f.i32(3);
    if (before_vertices) {
      f.keyword(kFloatingPointPrecision);
      f.integer(bits);
    }
    f.keyword(kVertices);
    f.integer(4);
    for (const Vec3& p : mesh.positions) {
      // Written as the keyword says where it comes first, else as the version says.
      for (double x : {p.x, p.y, p.z})
        bits == 32 && before_vertices ? f.real32(x + 0.1) : f.real(x + 0.1);
      f.integer(0);
    }
    if (!before_vertices) {
      f.keyword(kFloatingPointPrecision);
      f.integer(bits);
    }
    f.keyword(kTetrahedra);
    f.integer(1);
    for (uint32_t v : mesh.tets[0]) f.integer(int64_t(v) + 1);
    f.integer(mesh.materials[0]);
    return f.finish();
  };
  for (int version : {2, 3, 4}) {
    for (int64_t bits : {32, 64}) {
      SCOPED_TRACE(std::to_string(version) + ", " + std::to_string(bits));
      TetMesh read;
      const Status s = read_mesh_from_memory(file(version, bits, true), MeshFormat::kMeditBinary,
                                             "p.meshb", &read);
      ASSERT_TRUE(s.ok()) << s.message();
      ASSERT_EQ(read.vertex_count(), 4u);
      for (size_t v = 0; v < 4; ++v) {
        for (int k = 0; k < 3; ++k) {
          const double x = mesh.positions[v][k] + 0.1;
          EXPECT_EQ(read.positions[v][k], bits == 32 ? to_float(x) : x);
        }
      }
    }
  }
  TetMesh read;
  const Status late =
      read_mesh_from_memory(file(2, 32, false), MeshFormat::kMeditBinary, "p.meshb", &read);
  EXPECT_NE(late.message().find("FloatingPointPrecision 32 after the Vertices section, read with "
                                "64-bit reals"),
            std::string::npos)
      << late.message();
  EXPECT_TRUE(
      read_mesh_from_memory(file(2, 64, false), MeshFormat::kMeditBinary, "p.meshb", &read).ok());
  const std::string ascii =
      "MeshVersionFormatted 2\nDimension 3\nFloatingPointPrecision\n64\nVertices\n4\n"
      "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra\n1\n1 2 3 4 1\nEnd\n";
  const Status text = read_mesh_from_memory(ascii, MeshFormat::kMedit, "p.mesh", &read);
  EXPECT_TRUE(text.ok()) << text.message();
}

TEST(IoMeditBinary, WrittenFilesReadBack) {
  const std::string dir = test::output_dir("meshb");
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  const TetMesh grid = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int k) { return (i + 2 * j + k) % 3; }, 0.25);
  for (const TetMesh& mesh : {grid, box2}) {
    WriteOptions options;
    options.surface_groups = true;
    ASSERT_TRUE(write_mesh(dir + "/m.meshb", mesh, options).ok());
    ASSERT_TRUE(write_mesh(dir + "/m.mesh", mesh, options).ok());
    const std::string data = test::read_text(dir + "/m.meshb");
    // Version 2, little-endian.
    ASSERT_GE(data.size(), 8u);
    EXPECT_EQ(data.substr(0, 8), std::string("\1\0\0\0\2\0\0\0", 8));
    TetMesh binary, ascii;
    ReadInfo binary_info, ascii_info;
    ASSERT_TRUE(read_mesh(dir + "/m.meshb", &binary, &binary_info).ok());
    ASSERT_TRUE(read_mesh(dir + "/m.mesh", &ascii, &ascii_info).ok());
    test::expect_same_mesh(mesh, binary);
    EXPECT_TRUE(binary_info.notes.empty());
    ASSERT_FALSE(binary_info.surface_groups.empty());
    test::expect_same_groups(ascii_info.surface_groups, binary_info.surface_groups);
  }
}

// Versions 3 (8-byte keyword positions) and 4 (8-byte integers too) are written only
// for files past 2 GiB or vertex numbers past 2^31 - 1; written so for small meshes,
// they read back as the same mesh and groups as version 2 (the reader itself is checked
// on meshio's files of those versions in test_io_other_tools.cpp).
TEST(IoMeditBinary, Versions3And4ReadBackAsVersion2) {
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(box2, &groups).ok());
  std::string v2;
  io::write_medit_binary(box2, &groups, &v2);
  TetMesh expected;
  ReadInfo expected_info;
  ASSERT_TRUE(
      read_mesh_from_memory(v2, MeshFormat::kMeditBinary, "v2.meshb", &expected, &expected_info)
          .ok());
  ASSERT_FALSE(expected_info.surface_groups.empty());
  for (int version : {3, 4}) {
    SCOPED_TRACE(version);
    std::string data;
    io::write_medit_binary(box2, &groups, &data, version);
    ASSERT_GE(data.size(), 8u);
    EXPECT_EQ(data.substr(0, 8), std::string("\1\0\0\0", 4) + char(version) + std::string(3, '\0'));
    // The positions take 4 more bytes per keyword (5: Dimension, Vertices, Triangles,
    // Tetrahedra, End); version 4 also writes every integer in 8 bytes.
    const size_t integers =
        1 + box2.vertex_count() + 1 + 4 * groups.surface.size() + 1 + 5 * box2.tet_count();
    EXPECT_EQ(data.size(), v2.size() + 5 * 4 + (version == 4 ? 4 * integers : 0));
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_mesh_from_memory(data, MeshFormat::kMeditBinary, "v.meshb", &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    test::expect_same_mesh(expected, mesh);
    EXPECT_TRUE(info.notes.empty());
    test::expect_same_groups(expected_info.surface_groups, info.surface_groups);
  }
}

// A binary file named .mesh, or an ASCII one named .meshb: the error says which it is.
TEST(IoMeditBinary, FilesNamedForTheOtherKindAreNamedSo) {
  TetMesh mesh;
  for (bool swap : {false, true}) {
    const Status s =
        read_mesh_from_memory(meshb(2, swap), MeshFormat::kMedit, "b.mesh", &mesh, nullptr);
    EXPECT_EQ(s.message(),
              "b.mesh:1: not an ASCII Medit file: it starts as a binary one does (name it .meshb)");
  }
  const std::string ascii = test::read_text(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh");
  EXPECT_EQ(read(ascii, &mesh).message(),
            "b.meshb: byte 0: not a binary Medit file: it is an ASCII one (name it .mesh)");
}

// Every cut of the file fails, naming the byte: the End keyword (or a last keyword whose
// next position is 0) is the only way a .meshb ends.
TEST(IoMeditBinary, EveryTruncationFails) {
  for (int version : {2, 4}) {
    const std::string data = meshb(version, version == 4);
    for (size_t length = 0; length < data.size(); ++length) {
      const std::string prefix = data.substr(0, length);  // ASan sees reads past it
      TetMesh mesh;
      test::expect_error(read(prefix, &mesh), "b.meshb: byte ", "");
      if (testing::Test::HasFailure()) return;
    }
  }
}

TEST(IoMeditBinary, BrokenHeadersAndCountsNameTheProblem) {
  auto damage = [](auto change) {
    Damage d;
    change(d);
    return d;
  };
  const struct {
    Damage damage;
    const char* words;  // expected in the message
  } cases[] = {
      {damage([](Damage& d) { d.one = 7; }), "byte 0: not a binary Medit (.meshb) file"},
      {damage([](Damage& d) { d.version = 5; }), "byte 4: version 5 (libMeshb knows 1 to 4)"},
      {damage([](Damage& d) { d.dimension_first = false; }),
       "byte 8: the first keyword is code 13, not Dimension (3)"},
      {damage([](Damage& d) { d.dimension = 2; }), "only 3-dimensional meshes are supported"},
      {damage([](Damage& d) { d.vertex_count = 1000000; }),
       "Vertices: 1000000 entries of 28 bytes do not fit"},
      {damage([](Damage& d) { d.vertex_count = -1; }), "Vertices: -1 entries"},
      {damage([](Damage& d) { d.first_x = std::nan(""); }), "vertex 1: a coordinate is not finite"},
      {damage([](Damage& d) { d.corner = 0; }), "vertex index 0 is out of range"},
      {damage([](Damage& d) { d.corners_next = 4; }), "the next keyword's position 4 is not after"},
      {damage([](Damage& d) { d.corners_next = 1 << 20; }),
       "the next keyword's position 1048576 is past the end of the file"},
  };
  for (int version : {2, 3}) {
    for (const auto& c : cases) {
      SCOPED_TRACE(std::to_string(version) + ": " + c.words);
      TetMesh mesh;
      test::expect_error(read(meshb(version, false, c.damage), &mesh), "b.meshb: byte ", c.words);
    }
  }
  // A next position inside the keyword's own header (the Corners keyword starts at byte
  // 20 of a version 2 file, its entries at 28): refused before its count is read.
  Damage inside;
  inside.corners_next = 22;
  TetMesh read_back;
  EXPECT_NE(read(meshb(2, false, inside), &read_back)
                .message()
                .find("byte 24: keyword 13: the next keyword's position 22 is not after this one"),
            std::string::npos)
      << read(meshb(2, false, inside), &read_back).message();
  // Version 4's 8-byte references: one past the int32 range is named.
  Damage d;
  d.last_material = int64_t(1) << 40;
  TetMesh mesh;
  EXPECT_NE(read(meshb(4, false, d), &mesh).message().find("(material) 1099511627776 is out of"),
            std::string::npos);
  // A vertex index past the vertices: the validation's error, naming the file.
  d = Damage();
  d.corner = 99;
  const Status s = read(meshb(2, false, d), &mesh);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("b.meshb: ", 0), 0u) << s.message();
  EXPECT_NE(s.message().find("99"), std::string::npos) << s.message();
  // Without the End keyword, a last keyword whose next position is 0 ends the file, as
  // libMeshb reads it; one whose next position is the end of the file (the End keyword
  // cut off) does not.
  d = Damage();
  d.end_keyword = false;
  const std::string without_end = meshb(2, false, d);
  ASSERT_TRUE(read(without_end, &mesh).ok());
  test::expect_same_mesh(expected_mesh(2), mesh);
  const std::string cut = meshb(2, false).substr(0, meshb(2, false).size() - 8);
  EXPECT_NE(
      read(cut, &mesh)
          .message()
          .find("byte " + std::to_string(cut.size()) + ": the file ends before the End keyword"),
      std::string::npos)
      << read(cut, &mesh).message();
}

// Random damage to the binary data: an error naming the file, or a valid mesh.
TEST(IoMeditBinary, RandomDamageNeverCrashes) {
  std::mt19937 random(2026);
  for (int version = 1; version <= 4; ++version) {
    const std::string valid = meshb(version, version % 2 == 0);
    for (int trial = 0; trial < 2000; ++trial) {
      std::string data = valid;
      const int changes = 1 + trial % 4;
      for (int k = 0; k < changes; ++k) {
        const size_t at = random() % data.size();
        data[at] = char(trial % 3 == 0 ? 0xff : random() & 0xff);
      }
      test::expect_error_or_valid_mesh(data, MeshFormat::kMeditBinary, "b.meshb");
      if (testing::Test::HasFatalFailure()) return;
    }
  }
}

}  // namespace
}  // namespace tetlod
