// Binary VTK legacy files: keyword lines in text, each array's values after its line
// as big-endian numbers. Written here byte by byte in both cell layouts (4.2 and
// 5.1), with the material as SCALARS or as a FIELD array among arrays to skip, they
// read as the same mesh as the ASCII file; every truncation fails with the file's
// name, and random damage never crashes. (Gmsh's own -bin output: interop test.)
// What TetLOD writes in binary (WriteOptions::vtk_binary), .vtk and .vtu, reads as
// what it writes in text, with the bytes in the order each format has.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

class BigEndian {
 public:
  void text(const std::string& s) { data_ += s; }
  template <typename T>
  void put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (size_t i = sizeof(T); i-- > 0;) data_.push_back(bytes[i]);  // little-endian host
  }
  const std::string& data() const { return data_; }

 private:
  std::string data_;
};

// test::make_io_mesh() (6 points; tets {0,1,2,3}, {1,2,3,4}, {0,2,1,5}; materials
// 0, 7, INT32_MAX) plus a triangle cell, the second tet as a 10-node tet.
std::string binary_vtk(bool layout_51, bool material_as_field, bool float_points = false) {
  const TetMesh& m = test::make_io_mesh();
  BigEndian b;
  b.text(std::string("# vtk DataFile Version ") + (layout_51 ? "5.1" : "4.2") +
         "\ntitle\nBINARY\nDATASET UNSTRUCTURED_GRID\n");
  b.text(std::string("POINTS 6 ") + (float_points ? "float" : "double") + "\n");
  for (const Vec3& p : m.positions) {
    for (int k = 0; k < 3; ++k) {
      if (float_points) {
        b.put(float(p[k]));
      } else {
        b.put(p[k]);
      }
    }
  }
  // Cells: the triangle (1 2 3), the three tets; the second tet with six more points.
  const std::vector<std::vector<int64_t>> cells = {
      {1, 2, 3}, {0, 1, 2, 3}, {1, 2, 3, 4, 0, 0, 0, 0, 0, 0}, {0, 2, 1, 5}};
  size_t total = 0;
  for (const auto& c : cells) total += c.size();
  if (layout_51) {
    b.text("\nCELLS 5 " + std::to_string(total) + "\nOFFSETS vtktypeint64\n");
    int64_t offset = 0;
    b.put(offset);
    for (const auto& c : cells) b.put(offset += int64_t(c.size()));
    b.text("\nCONNECTIVITY vtktypeint64\n");
    for (const auto& c : cells)
      for (int64_t v : c) b.put(v);
  } else {
    b.text("\nCELLS 4 " + std::to_string(total + 4) + "\n");
    for (const auto& c : cells) {
      b.put(int32_t(c.size()));
      for (int64_t v : c) b.put(int32_t(v));
    }
  }
  b.text("\nCELL_TYPES 4\n");
  for (int32_t type : {5, 10, 24, 10}) b.put(type);
  b.text("\nCELL_DATA 4\n");
  b.text("VECTORS flow float\n");
  for (int i = 0; i < 12; ++i) b.put(float(i));
  const int32_t materials[4] = {99, m.materials[0], m.materials[1], m.materials[2]};
  if (material_as_field) {
    b.text("\nFIELD FieldData 2\nquality 1 4 double\n");
    for (int i = 0; i < 4; ++i) b.put(0.5 * i);
    b.text("\nmaterial 1 4 int\n");
    for (int32_t material : materials) b.put(material);
  } else {
    b.text("\nSCALARS material int 1\nLOOKUP_TABLE default\n");
    for (int32_t material : materials) b.put(material);
    b.text("\nCOLOR_SCALARS colours 3\n");
    for (int i = 0; i < 12; ++i) b.put(uint8_t(i));
  }
  b.text("\nPOINT_DATA 6\nLOOKUP_TABLE table 2\n");
  for (int i = 0; i < 8; ++i) b.put(uint8_t(200 + i));
  b.text("\nTEXTURE_COORDINATES uv 2 short\n");
  for (int i = 0; i < 12; ++i) b.put(int16_t(-i));
  b.text("\n");
  return b.data();
}

Status read(const std::string& data, TetMesh* mesh) {
  return read_mesh_from_memory(data, MeshFormat::kVtkLegacy, "b.vtk", mesh);
}

TEST(IoVtkBinary, ReadsBothLayoutsAndBothMaterialForms) {
  for (bool layout_51 : {false, true}) {
    for (bool field : {false, true}) {
      SCOPED_TRACE(std::to_string(layout_51) + std::to_string(field));
      TetMesh mesh;
      const Status s = read(binary_vtk(layout_51, field), &mesh);
      ASSERT_TRUE(s.ok()) << s.message();
      test::expect_same_mesh(test::make_io_mesh(), mesh);
    }
  }
  // Float points: the coordinates rounded to float.
  TetMesh mesh;
  ASSERT_TRUE(read(binary_vtk(false, false, true), &mesh).ok());
  const TetMesh expected = test::make_io_mesh();
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(mesh.positions[v][k], double(float(expected.positions[v][k])));
}

TEST(IoVtkBinary, EveryTruncationFailsWithTheFileName) {
  for (bool layout_51 : {false, true}) {
    const std::string data = binary_vtk(layout_51, layout_51);
    for (size_t length = 0; length < data.size(); ++length) {
      TetMesh mesh;
      const std::string prefix = data.substr(0, length);
      const Status s = read(prefix, &mesh);
      if (s.ok()) {
        // A legacy file has no end marker and the material array is optional: a cut
        // between whole arrays before the materials reads as a mesh without them (as
        // for ASCII files), a cut after them as the whole mesh.
        TetMesh expected = test::make_io_mesh();
        if (prefix.find("material") == std::string::npos) {
          expected.materials.assign(expected.tet_count(), 0);
        }
        test::expect_same_mesh(expected, mesh);
      } else {
        EXPECT_EQ(s.message().rfind("b.vtk:", 0), 0u) << s.message();
      }
      if (testing::Test::HasFailure()) return;
    }
  }
}

TEST(IoVtkBinary, BrokenArraysNameTheProblem) {
  const std::string valid = binary_vtk(true, false);
  TetMesh mesh;
  auto message = [&](std::string data) { return read(data, &mesh).message(); };
  std::string data = valid;
  data.replace(data.find("OFFSETS vtktypeint64"), 20, "OFFSETS vtktypestrng");
  EXPECT_NE(message(data).find("OFFSETS of type 'vtktypestrng' cannot be read"), std::string::npos)
      << message(data);
  data = valid;
  data.replace(data.find("CELLS 5"), 7, "CELLS 9");
  EXPECT_EQ(message(data).rfind("b.vtk: byte ", 0), 0u) << message(data);
  data = valid;
  data.replace(data.find("POINTS 6"), 8, "POINTS 7");
  EXPECT_NE(message(data).find("b.vtk: byte "), std::string::npos) << message(data);
  data = valid;
  data.replace(data.find("POINTS 6 double"), 15, "POINTS 6 int   ");
  EXPECT_NE(message(data).find("binary POINTS of type 'int' are not supported"), std::string::npos)
      << message(data);
  // A connectivity index past the points.
  data = valid;
  const size_t at = data.find("CONNECTIVITY vtktypeint64\n") + 26 + 8 * 3 + 7;
  data[at] = 100;
  EXPECT_NE(message(data).find("only 6"), std::string::npos) << message(data);
  // A negative index is named by its value and place (the place was given as the
  // value; found by a hostile-input test).
  data = valid;
  const size_t first = data.find("CONNECTIVITY vtktypeint64\n") + 26 + 8 * 4;
  for (int k = 0; k < 8; ++k) data[first + k] = char(0xff);  // -1, big-endian
  EXPECT_NE(message(data).find("CONNECTIVITY: value 5 of 21, -1, is not an integer from 0"),
            std::string::npos)
      << message(data);
}

TEST(IoVtkBinary, RandomDamageNeverCrashes) {
  std::mt19937 random(4242);
  for (bool layout_51 : {false, true}) {
    const std::string valid = binary_vtk(layout_51, !layout_51);
    for (int trial = 0; trial < 3000; ++trial) {
      std::string data = valid;
      for (int k = 0; k <= trial % 4; ++k) {
        data[60 + random() % (data.size() - 60)] = char(random() & 0xff);
      }
      test::expect_error_or_valid_mesh(data, MeshFormat::kVtkLegacy, "b.vtk");
      if (testing::Test::HasFatalFailure()) return;
    }
  }
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The 8 bytes of `x` in the given order.
std::string double_bytes(double x, bool big_endian) {
  char bytes[8];
  std::memcpy(bytes, &x, 8);
  std::string s(bytes, 8);  // little-endian host, as BigEndian above assumes
  if (big_endian) std::reverse(s.begin(), s.end());
  return s;
}

TEST(IoVtkBinary, OurBinaryFilesReadAsOurTextFiles) {
  const std::string dir = test::output_dir("vtk_binary_written_pairs");
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  // Names with a space, UTF-8 letters, and a name for a material the mesh lacks.
  const std::vector<MaterialName> names = {
      {1, "Rotor"}, {2, "air gap \u00e4\u00f6"}, {7, "copper coil"}, {9, "absent"}};
  for (const char* extension : {".vtk", ".vtu"}) {
    for (bool groups : {false, true}) {
      SCOPED_TRACE(std::string(extension) + (groups ? " with groups" : ""));
      // make_io_mesh()'s material INT32_MAX leaves no tag for groups.
      const TetMesh mesh = groups ? box2 : test::make_io_mesh();
      TetMesh read[2];
      ReadInfo info[2];
      std::string bytes;
      for (bool binary : {false, true}) {
        WriteOptions options;
        options.vtk_binary = binary;
        options.surface_groups = groups;
        options.material_names = &names;
        const std::string path = dir + (binary ? "/b" : "/t") + extension;
        ASSERT_TRUE(write_mesh(path, mesh, options).ok());
        const Status s = read_mesh(path, &read[binary], &info[binary]);
        ASSERT_TRUE(s.ok()) << s.message();
        if (binary) bytes = file_bytes(path);
      }
      test::expect_same_mesh(read[0], read[1]);
      test::expect_same_mesh(mesh, read[1]);
      // The names in the field data: box2's materials 1 and 2, make_io_mesh()'s 7.
      for (const ReadInfo& i : info) {
        ASSERT_EQ(i.material_names.size(), groups ? 2u : 1u);
        EXPECT_EQ(i.material_names[0].name, groups ? "Rotor" : "copper coil");
      }
      EXPECT_EQ(info[1].surface_groups.empty(), !groups);
      test::expect_same_groups(info[0].surface_groups, info[1].surface_groups);
      // The first point's x where the format puts it: after the POINTS line,
      // big-endian; first in the appended data, after a little-endian UInt64 count.
      const double x = mesh.positions[0].x;
      if (std::string(extension) == ".vtk") {
        EXPECT_EQ(bytes.rfind("# vtk DataFile Version 3.0\nTetLOD tetrahedral mesh\nBINARY\n", 0),
                  0u);
        const std::string points = "POINTS " + std::to_string(mesh.vertex_count()) + " double\n";
        const size_t at = bytes.find(points);
        ASSERT_NE(at, std::string::npos);
        EXPECT_EQ(bytes.substr(at + points.size(), 8), double_bytes(x, true));
      } else {
        EXPECT_EQ(bytes.find("format=\"ascii\""), std::string::npos);
        const size_t at = bytes.find("<AppendedData encoding=\"raw\">\n   _");
        ASSERT_NE(at, std::string::npos);
        const std::string points =
            "Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\"";
        const size_t offset = bytes.find(points);
        ASSERT_NE(offset, std::string::npos);
        const size_t data = at + 34 + std::stoull(bytes.substr(offset + points.size()));
        const uint64_t count = 24 * mesh.vertex_count();
        std::string count_bytes(8, '\0');
        std::memcpy(&count_bytes[0], &count, 8);
        EXPECT_EQ(bytes.substr(data, 16), count_bytes + double_bytes(x, false));
        const std::string end = "\n  </AppendedData>\n</VTKFile>\n";
        EXPECT_EQ(bytes.substr(bytes.size() - end.size()), end);
      }
    }
  }
}

// Names of every length class of a binary legacy string (1-, 2- and 4-byte length
// headers), and with bytes VTK's text form encodes (space, '%', a line break), read
// back from all four forms (the line break as '_', as every reader gives a control
// character of a name).
TEST(IoVtkBinary, NamesOfEveryLengthReadBack) {
  const std::string dir = test::output_dir("vtk_binary_names");
  const TetMesh mesh = test::make_io_mesh();  // materials 0, 7 and INT32_MAX
  const std::vector<MaterialName> names = {
      {7, "a 100% line\nbreak"}, {0, std::string(70, 'x')}, {2147483647, std::string(20000, 'y')}};
  for (const char* extension : {".vtk", ".vtu"}) {
    for (bool binary : {false, true}) {
      SCOPED_TRACE(std::string(extension) + (binary ? " binary" : " text"));
      WriteOptions options;
      options.vtk_binary = binary;
      options.material_names = &names;
      const std::string path = dir + "/names" + extension;
      ASSERT_TRUE(write_mesh(path, mesh, options).ok());
      ReadInfo info;
      TetMesh read;
      ASSERT_TRUE(read_mesh(path, &read, &info).ok());
      ASSERT_EQ(info.material_names.size(), 3u);
      EXPECT_EQ(info.material_names[0].name, names[1].name);
      EXPECT_EQ(info.material_names[1].name, "a 100% line_break");
      // A name longer than Gmsh reads is cut to kMaxNameBytes (with a note).
      EXPECT_EQ(info.material_names[2].name, names[2].name.substr(0, kMaxNameBytes));
      EXPECT_NE(std::find(info.notes.begin(), info.notes.end(),
                          "1 name was cut to 240 bytes (what Gmsh reads of a physical name)"),
                info.notes.end());
    }
  }
}

// Every cut of what TetLOD writes in binary fails with the file's name, but where
// only the legacy file's optional arrays are lost (as in the truncation test above).
TEST(IoVtkBinary, OurBinaryFilesCutShortFail) {
  const std::string dir = test::output_dir("vtk_binary_written_cut");
  const TetMesh mesh = test::make_io_mesh();
  for (MeshFormat format : {MeshFormat::kVtkLegacy, MeshFormat::kVtu}) {
    const bool legacy = format == MeshFormat::kVtkLegacy;
    const std::string path = dir + (legacy ? "/cut.vtk" : "/cut.vtu");
    WriteOptions options;
    options.vtk_binary = true;
    ASSERT_TRUE(write_mesh(path, mesh, options).ok());
    const std::string data = file_bytes(path);
    const std::string name = legacy ? "b.vtk" : "b.vtu";
    for (size_t length = 0; length + 1 < data.size(); ++length) {
      TetMesh read;
      const std::string prefix = data.substr(0, length);
      const Status s = read_mesh_from_memory(prefix, format, name, &read);
      if (s.ok() && legacy) {
        const size_t materials = data.find("SCALARS material");
        if (length < materials) {
          TetMesh expected = mesh;
          expected.materials.assign(expected.tet_count(), 0);
          test::expect_same_mesh(expected, read);
        } else {
          test::expect_same_mesh(mesh, read);  // only stretch values lost
        }
      } else {
        ASSERT_FALSE(s.ok()) << name << " cut at " << length;
        EXPECT_EQ(s.message().rfind(name + ":", 0), 0u) << s.message();
      }
      if (testing::Test::HasFailure()) return;
    }
  }
}

}  // namespace
}  // namespace tetlod
