// Binary Gmsh files (file type 1), 2.2 and 4.1, in both byte orders: written here
// byte by byte from the manual's layout, they read as the same mesh as the text
// files; every truncation and every broken count fails with "name: byte N: ...",
// and random damage never crashes. (test_io_gmsh_interop.cpp reads Gmsh's own.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// What a test changes in the otherwise valid file.
struct Damage {
  int data_size = 8;
  int file_type = 1;
  int32_t one = 1;           // the byte-order check
  int64_t node_count = -1;   // the $Nodes header's count, if >= 0
  int64_t block_count = -1;  // 4.1: the $Nodes header's block count, if >= 0
  int32_t tet_type = 4;      // of the first group or block of tets
  int32_t following = -1;    // 2.2: elements following the first tet header, if >= 0
  double first_x = 0.1;      // x of the first vertex
  int64_t first_tag = -1;    // the first node's tag, if >= 0
  int64_t corner_tag = -1;   // the first tet's first corner's node tag, if >= 0
};

using test::Bytes;

// The mesh of test::make_io_mesh(): 6 vertices, tets {0,1,2,3} (material 0),
// {1,2,3,4} (7) and {0,2,1,5} (INT32_MAX).
const TetMesh& io_mesh() {
  static const TetMesh mesh = test::make_io_mesh();
  return mesh;
}

void header(Bytes& b, const char* version, const Damage& d) {
  b.text(std::string("$MeshFormat\n") + version + " " + std::to_string(d.file_type) + " " +
         std::to_string(d.data_size) + "\n");
  b.i32(d.one);
  b.text("\n$EndMeshFormat\n");
}

// 2.2: nodes in reverse order with tags 3, 6, ..., 18; a triangle, then the tets
// (the second one as a 10-node tet) with physical tags = materials.
std::string binary_22(bool swap, const Damage& d = {}) {
  const TetMesh& m = io_mesh();
  Bytes b(swap);
  header(b, "2.2", d);
  b.text("$Nodes\n" + std::to_string(d.node_count >= 0 ? d.node_count : 6) + "\n");
  for (int v = 5; v >= 0; --v) {
    b.i32(v == 0 && d.first_tag >= 0 ? d.first_tag : 3 * (v + 1));
    b.f64(v == 0 ? d.first_x : m.positions[v].x);
    b.f64(m.positions[v].y);
    b.f64(m.positions[v].z);
  }
  b.text("\n$EndNodes\n$Elements\n4\n");
  // A triangle with three tags.
  b.i32(2), b.i32(1), b.i32(3);
  b.i32(1), b.i32(5), b.i32(5), b.i32(0), b.i32(3), b.i32(6), b.i32(9);
  auto tet = [&](int t, int nodes) {
    b.i32(10 * (t + 1));
    b.i32(m.materials[t]), b.i32(m.materials[t]);
    for (int k = 0; k < 4; ++k)
      b.i32(t == 0 && k == 0 && d.corner_tag >= 0 ? d.corner_tag : 3 * (m.tets[t][k] + 1));
    for (int k = 4; k < nodes; ++k) b.i32(3);
  };
  b.i32(d.tet_type), b.i32(d.following >= 0 ? d.following : 1), b.i32(2);
  tet(0, 4);
  b.i32(11), b.i32(1), b.i32(2);
  tet(1, 10);
  b.i32(4), b.i32(1), b.i32(2);
  tet(2, 4);
  b.text("\n$EndElements\n");
  return b.data();
}

// 4.1: material 0 through a physical group named "material_0"; a surface entity
// with parametric nodes; node tags 1..6 listed out of order in two blocks.
std::string binary_41(bool swap, const Damage& d = {}) {
  const TetMesh& m = io_mesh();
  Bytes b(swap);
  header(b, "4.1", d);
  b.text("$PhysicalNames\n1\n3 9 \"material_0\"\n$EndPhysicalNames\n$Entities\n");
  b.u64(1), b.u64(0), b.u64(1), b.u64(3);
  b.i32(1), b.f64(0), b.f64(0), b.f64(0), b.u64(0);  // a point
  // The surface: bounding box, no physical group, one bounding curve.
  b.i32(1);
  for (int k = 0; k < 6; ++k) b.f64(k);
  b.u64(0), b.u64(1), b.i32(-1);
  const int32_t physicals[3] = {9, 7, std::numeric_limits<int32_t>::max()};
  for (int volume = 0; volume < 3; ++volume) {
    b.i32(11 + volume);
    for (int k = 0; k < 6; ++k) b.f64(k);
    b.u64(1), b.i32(physicals[volume]), b.u64(0);
  }
  b.text("\n$EndEntities\n$Nodes\n");
  b.u64(d.block_count >= 0 ? uint64_t(d.block_count) : 2);
  b.u64(d.node_count >= 0 ? uint64_t(d.node_count) : 6), b.u64(1), b.u64(6);
  auto position = [&](int v) {
    b.f64(v == 0 ? d.first_x : m.positions[v].x), b.f64(m.positions[v].y), b.f64(m.positions[v].z);
  };
  b.i32(3), b.i32(11), b.i32(0), b.u64(3);  // vertices 5, 4, 3
  for (int v = 5; v >= 3; --v) b.u64(v + 1);
  for (int v = 5; v >= 3; --v) position(v);
  b.i32(2), b.i32(1), b.i32(1), b.u64(3);  // vertices 0, 1, 2 with (u, v)
  for (int v = 0; v < 3; ++v) b.u64(v == 0 && d.first_tag >= 0 ? d.first_tag : v + 1);
  for (int v = 0; v < 3; ++v) position(v), b.f64(0.5), b.f64(0.25);
  b.text("\n$EndNodes\n$Elements\n");
  b.u64(4), b.u64(4), b.u64(1), b.u64(40);
  b.i32(2), b.i32(1), b.i32(2), b.u64(1);  // a triangle
  b.u64(1), b.u64(1), b.u64(2), b.u64(3);
  for (int t = 0; t < 3; ++t) {
    const int32_t type = t == 0 ? d.tet_type : t == 1 ? 11 : 4;
    b.i32(3), b.i32(11 + t), b.i32(type), b.u64(1);
    b.u64(10 * (t + 1));
    for (int k = 0; k < 4; ++k)
      b.u64(t == 0 && k == 0 && d.corner_tag >= 0 ? uint64_t(d.corner_tag) : m.tets[t][k] + 1);
    for (int k = 4; k < (type == 11 ? 10 : 4); ++k) b.u64(1);
  }
  b.text("\n$EndElements\n");
  return b.data();
}

Status read(const std::string& data, TetMesh* mesh) {
  return read_mesh_from_memory(data, MeshFormat::kGmsh41, "b.msh", mesh);
}

TEST(IoGmshBinary, ReadsTheSameMeshInBothVersionsAndByteOrders) {
  for (bool swap : {false, true}) {
    for (int version : {22, 41}) {
      SCOPED_TRACE(std::to_string(version) + (swap ? " big-endian" : " little-endian"));
      TetMesh mesh;
      ReadInfo info;
      const std::string data = version == 22 ? binary_22(swap) : binary_41(swap);
      const Status s = read_mesh_from_memory(data, MeshFormat::kGmsh41, "b.msh", &mesh, &info);
      ASSERT_TRUE(s.ok()) << s.message();
      test::expect_same_mesh(io_mesh(), mesh);
      EXPECT_EQ(info.format, version == 22 ? MeshFormat::kGmsh22 : MeshFormat::kGmsh41);
    }
  }
}

// Every cut fails with "b.msh: ..." or, past the last data, reads the whole mesh.
TEST(IoGmshBinary, EveryTruncationFailsOrReadsTheWholeMesh) {
  for (int version : {22, 41}) {
    const std::string data = version == 22 ? binary_22(false) : binary_41(false);
    size_t ok_count = 0;
    for (size_t length = 0; length < data.size(); ++length) {
      const std::string prefix = data.substr(0, length);  // ASan sees reads past it
      TetMesh mesh;
      const Status s = read(prefix, &mesh);
      if (s.ok()) {
        ++ok_count;
        test::expect_same_mesh(io_mesh(), mesh);
      } else {
        EXPECT_EQ(s.message().rfind("b.msh:", 0), 0u) << s.message();
      }
      if (testing::Test::HasFailure()) return;
    }
    EXPECT_LE(ok_count, 2u) << version;  // "$EndElements" and "$EndElements\n" only
  }
}

struct Case {
  Damage damage;
  const char* words;  // expected in the message
};

TEST(IoGmshBinary, BrokenHeadersAndCountsNameTheProblem) {
  auto damage = [](auto change) {
    Damage d;
    change(d);
    return d;
  };
  const std::vector<Case> cases = {
      {damage([](Damage& d) { d.data_size = 4; }), "data size 4 is not supported"},
      {damage([](Damage& d) { d.file_type = 2; }), "is not 0 (ASCII) or 1 (binary)"},
      {damage([](Damage& d) { d.one = 7; }), "byte-order check reads 7"},
      {damage([](Damage& d) { d.node_count = 1000000000; }), "node count"},
      {damage([](Damage& d) { d.node_count = 5; }), ""},
      {damage([](Damage& d) { d.tet_type = 141; }), "element type 141 is unknown: a binary file"},
      {damage([](Damage& d) { d.first_x = std::nan(""); }), "not a finite number"},
      {damage([](Damage& d) { d.first_tag = 0; }), "node tag 0"},
      {damage([](Damage& d) { d.first_tag = 6; }), "node tag 6 is defined twice"},
      {damage([](Damage& d) { d.corner_tag = 999; }), "uses node 999, which is not in $Nodes"},
  };
  for (int version : {22, 41}) {
    for (const Case& c : cases) {
      const std::string data =
          version == 22 ? binary_22(false, c.damage) : binary_41(false, c.damage);
      SCOPED_TRACE(std::to_string(version) + ": " + c.words);
      TetMesh mesh;
      test::expect_error(read(data, &mesh), "b.msh:", c.words);
    }
  }
  // Past the header, messages give the byte offset instead of a line.
  Damage d;
  d.corner_tag = 999;
  TetMesh mesh;
  EXPECT_EQ(read(binary_41(false, d), &mesh).message().rfind("b.msh: byte ", 0), 0u);
  // Counts larger than the file: an error, without reserving for them.
  d = Damage();
  d.block_count = int64_t(1) << 60;
  EXPECT_NE(read(binary_41(false, d), &mesh).message().find("more than the rest of the file"),
            std::string::npos);
  d = Damage();
  d.following = 1 << 30;
  EXPECT_NE(read(binary_22(false, d), &mesh).message().find("elements being left"),
            std::string::npos);
  d.following = 0;
  EXPECT_NE(read(binary_22(false, d), &mesh).message().find("gives 0 elements"), std::string::npos);
}

// What TetLOD writes with WriteOptions::gmsh_binary reads as what it writes in text:
// the same mesh, materials' names and surface groups, in both versions.
TEST(IoGmshBinary, OurBinaryFilesReadAsOurTextFiles) {
  const std::string dir = test::output_dir("gmsh_binary_written");
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  const std::vector<MaterialName> names = {{1, "Rotor"}, {2, "air gap"}};
  for (int version : {22, 41}) {
    for (bool groups : {false, true}) {
      SCOPED_TRACE(std::to_string(version) + (groups ? " with groups" : ""));
      // make_io_mesh()'s material INT32_MAX leaves no tag for groups.
      const TetMesh mesh = groups ? box2 : io_mesh();
      TetMesh read[2];
      ReadInfo info[2];
      for (bool binary : {false, true}) {
        WriteOptions options;
        options.gmsh_version = version;
        options.gmsh_binary = binary;
        options.surface_groups = groups;
        options.material_names = &names;
        const std::string path = dir + (binary ? "/b.msh" : "/t.msh");
        ASSERT_TRUE(write_mesh(path, mesh, options).ok());
        const Status s = read_mesh(path, &read[binary], &info[binary]);
        ASSERT_TRUE(s.ok()) << s.message();
      }
      test::expect_same_mesh(read[0], read[1]);
      test::expect_same_mesh(mesh, read[1]);
      EXPECT_EQ(info[1].format, version == 22 ? MeshFormat::kGmsh22 : MeshFormat::kGmsh41);
      ASSERT_EQ(info[1].material_names.size(), info[0].material_names.size());
      for (size_t i = 0; i < info[0].material_names.size(); ++i)
        EXPECT_EQ(info[1].material_names[i].name, info[0].material_names[i].name);
      EXPECT_EQ(info[1].surface_groups.empty(), !groups);
      test::expect_same_groups(info[0].surface_groups, info[1].surface_groups);
    }
  }
}

// Random damage to the binary data: an error naming the file, or a valid mesh.
TEST(IoGmshBinary, RandomDamageNeverCrashes) {
  std::mt19937 random(12345);
  for (int version : {22, 41}) {
    const std::string valid = version == 22 ? binary_22(true) : binary_41(true);
    for (int trial = 0; trial < 3000; ++trial) {
      std::string data = valid;
      const int changes = 1 + trial % 4;
      for (int k = 0; k < changes; ++k) {
        const size_t at = 30 + random() % (data.size() - 30);
        data[at] = char(trial % 3 == 0 ? 0xff : random() & 0xff);
      }
      test::expect_error_or_valid_mesh(data, MeshFormat::kGmsh41, "b.msh");
      if (testing::Test::HasFatalFailure()) return;
    }
  }
}

}  // namespace
}  // namespace tetlod
