// Binary .vtu: inline base64 and appended raw arrays, UInt32 and UInt64 headers,
// either byte order, with and without zlib blocks, written here from the format's
// description, read as the same mesh; broken headers and damaged files give errors
// naming the file. (tests/data/vtu_vtk9_*.vtu, written by VTK itself: IoSamples.)
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <random>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

struct Options {
  bool appended = false;
  bool header64 = false;
  bool big_endian = false;
  bool zlib = false;
  bool separate_base64 = true;  // header and values encoded apart (as VTK does)
};

std::string base64(const std::string& bytes) {
  const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t group = 0;
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    for (size_t k = 0; k < 3; ++k) group = group << 8 | (k < n ? uint8_t(bytes[i + k]) : 0);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[group >> (18 - 6 * k) & 63] : '=';
  }
  return out;
}

class Writer {
 public:
  explicit Writer(const Options& o) : o_(o) {}

  template <typename T>
  std::string bytes_of(const std::vector<T>& values) const {
    std::string out;
    for (T v : values) put(&out, v);
    return out;
  }

  // One array: its XML and, for appended data, the bytes added to appended_.
  std::string array(const char* type, const char* name, int components, const std::string& data) {
    std::string header, body = data;
    if (o_.zlib) {
      // Blocks of 16 bytes, so that every array has several.
      const size_t block = 16;
      const size_t blocks = (data.size() + block - 1) / block;
      std::vector<uint64_t> sizes;
      body.clear();
      for (size_t b = 0; b < blocks; ++b) {
        const std::string piece = data.substr(b * block, block);
        uLongf length = compressBound(uLong(piece.size()));
        std::string compressed(length, '\0');
        compress(reinterpret_cast<Bytef*>(&compressed[0]), &length,
                 reinterpret_cast<const Bytef*>(piece.data()), uLong(piece.size()));
        compressed.resize(length);
        sizes.push_back(length);
        body += compressed;
      }
      put_header(&header, blocks);
      put_header(&header, block);
      put_header(&header, data.size() % block);
      for (uint64_t size : sizes) put_header(&header, size);
    } else {
      put_header(&header, data.size());
    }
    std::string xml = std::string("<DataArray type=\"") + type + "\" Name=\"" + name +
                      "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"";
    if (o_.appended) {
      xml += "appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
      appended_ += header + body;
    } else {
      xml += "binary\">\n" +
             (o_.separate_base64 ? base64(header) + base64(body) : base64(header + body)) +
             "\n</DataArray>\n";
    }
    return xml;
  }

  std::string file(const TetMesh& m) {
    std::vector<double> points;
    for (const Vec3& p : m.positions) points.insert(points.end(), {p.x, p.y, p.z});
    std::vector<int64_t> connectivity, offsets;
    std::vector<uint8_t> types;
    std::vector<int32_t> materials;
    // A triangle first, then the tets; the second tet as a 10-node tet.
    connectivity.insert(connectivity.end(), {1, 2, 3});
    offsets.push_back(3);
    types.push_back(5);
    materials.push_back(99);
    for (size_t t = 0; t < m.tet_count(); ++t) {
      for (uint32_t v : m.tets[t]) connectivity.push_back(v);
      if (t == 1) connectivity.insert(connectivity.end(), 6, 0);
      offsets.push_back(int64_t(connectivity.size()));
      types.push_back(t == 1 ? 24 : 10);
      materials.push_back(m.materials[t]);
    }
    std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"";
    xml += std::string(" byte_order=\"") + (o_.big_endian ? "BigEndian" : "LittleEndian") + "\"";
    xml += std::string(" header_type=\"") + (o_.header64 ? "UInt64" : "UInt32") + "\"";
    if (o_.zlib) xml += " compressor=\"vtkZLibDataCompressor\"";
    xml += ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(m.vertex_count()) +
           "\" NumberOfCells=\"" + std::to_string(m.tet_count() + 1) + "\">\n";
    xml += "<PointData>\n" + array("Float32", "weight", 1, bytes_of(std::vector<float>(6, 0.5f))) +
           "</PointData>\n";
    xml += "<Points>\n" + array("Float64", "Points", 3, bytes_of(points)) + "</Points>\n";
    xml += "<Cells>\n" + array("Int64", "connectivity", 1, bytes_of(connectivity)) +
           array("Int64", "offsets", 1, bytes_of(offsets)) +
           array("UInt8", "types", 1, bytes_of(types)) + "</Cells>\n";
    xml += "<CellData>\n" + array("Float64", "stretch", 1, bytes_of(std::vector<double>(4, 0.1))) +
           array("Int32", "material", 1, bytes_of(materials)) + "</CellData>\n";
    xml += "</Piece>\n</UnstructuredGrid>\n";
    if (o_.appended)
      xml += "<AppendedData encoding=\"raw\">\n_" + appended_ + "\n</AppendedData>\n";
    return xml + "</VTKFile>\n";
  }

 private:
  template <typename T>
  void put(std::string* out, T value) const {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (o_.big_endian) std::reverse(b, b + sizeof(T));  // little-endian host
    out->append(b, sizeof(T));
  }
  void put_header(std::string* out, uint64_t value) const {
    if (o_.header64) {
      put(out, value);
    } else {
      put(out, uint32_t(value));
    }
  }

  Options o_;
  std::string appended_;
};

std::vector<Options> every_option() {
  std::vector<Options> all;
  for (int bits = 0; bits < 32; ++bits) {
    Options o;
    o.appended = bits & 1;
    o.header64 = bits & 2;
    o.big_endian = bits & 4;
    o.zlib = bits & 8;
    o.separate_base64 = bits & 16;
    if (o.appended && !o.separate_base64) continue;  // no base64 in raw appended data
    all.push_back(o);
  }
  return all;
}

std::string describe(const Options& o) {
  return std::string(o.appended ? "appended" : "inline") + (o.header64 ? " UInt64" : " UInt32") +
         (o.big_endian ? " big-endian" : " little-endian") + (o.zlib ? " zlib" : "") +
         (o.separate_base64 ? "" : " joint base64");
}

Status read(const std::string& data, TetMesh* mesh) {
  return read_mesh_from_memory(data, MeshFormat::kVtu, "b.vtu", mesh);
}

TEST(IoVtuBinary, ReadsEveryEncoding) {
  for (const Options& o : every_option()) {
    SCOPED_TRACE(describe(o));
    TetMesh mesh;
    const Status s = read(Writer(o).file(test::make_io_mesh()), &mesh);
    ASSERT_TRUE(s.ok()) << s.message();
    test::expect_same_mesh(test::make_io_mesh(), mesh);
  }
}

TEST(IoVtuBinary, EveryTruncationFails) {
  for (const Options& o : every_option()) {
    const std::string data = Writer(o).file(test::make_io_mesh());
    for (size_t length = 0; length + 1 < data.size(); ++length) {
      TetMesh mesh;
      const Status s = read(data.substr(0, length), &mesh);
      ASSERT_FALSE(s.ok()) << describe(o) << ", cut at " << length;
      ASSERT_EQ(s.message().rfind("b.vtu:", 0), 0u) << s.message();
    }
  }
}

TEST(IoVtuBinary, BrokenEncodingsNameTheProblem) {
  Options o;
  o.zlib = true;
  const std::string valid = Writer(o).file(test::make_io_mesh());
  TetMesh mesh;
  auto message = [&](const std::string& from, const std::string& to) {
    std::string data = valid;
    const size_t at = data.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) data.replace(at, from.size(), to);
    return read(data, &mesh).message();
  };
  EXPECT_NE(message("vtkZLibDataCompressor", "vtkLZ4DataCompressor").find("only vtkZLib"),
            std::string::npos);
  EXPECT_NE(message("header_type=\"UInt32\"", "header_type=\"UInt16\"").find("not UInt32 or"),
            std::string::npos);
  EXPECT_NE(message("byte_order=\"LittleEndian\"", "byte_order=\"Middle\"").find("byte_order"),
            std::string::npos);
  EXPECT_NE(message("type=\"Float64\" Name=\"Points\"", "type=\"Float16\" Name=\"Points\"")
                .find("not a VTK numeric type"),
            std::string::npos);
  // The header read in the other byte order: sizes that do not fit.
  EXPECT_NE(message("LittleEndian", "BigEndian").find("DataArray"), std::string::npos);
  // Base64 with a character outside the alphabet.
  const size_t points = valid.find("Name=\"Points\"");
  const size_t content = valid.find('\n', points) + 1;
  std::string data = valid;
  data[content + 2] = '!';
  EXPECT_NE(read(data, &mesh).message().find("is not valid base64"), std::string::npos);
  // An appended array past the data.
  o.appended = true;
  const std::string appended = Writer(o).file(test::make_io_mesh());
  data = appended;
  const size_t offset = data.find("offset=\"", data.find("Name=\"material\"")) + 8;
  data.replace(offset, data.find('"', offset) - offset, "99999");
  EXPECT_NE(read(data, &mesh).message().find("past the"), std::string::npos)
      << read(data, &mesh).message();
}

TEST(IoVtuBinary, RandomDamageNeverCrashes) {
  std::mt19937 random(99);
  for (const Options& o : every_option()) {
    const std::string valid = Writer(o).file(test::make_io_mesh());
    for (int trial = 0; trial < 300; ++trial) {
      std::string data = valid;
      for (int k = 0; k <= trial % 4; ++k) data[random() % data.size()] = char(random() & 0xff);
      test::expect_error_or_valid_mesh(data, MeshFormat::kVtu, "b.vtu");
      if (testing::Test::HasFatalFailure()) return;
    }
  }
}

}  // namespace
}  // namespace tetlod
