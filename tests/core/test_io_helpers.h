// Shared pieces of the mesh file format tests (tests/core/test_io_*.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/tet_mesh.h"

namespace tetlod::test {

// Whether `program` is on PATH.
inline bool on_path(const std::string& program) {
  return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
}

// Ends a test that runs another tool (Gmsh, CalculiX, GetDP) when that tool is not on
// PATH: skipped on a developer's machine, failed in CI (CI=true), where scripts/test.sh
// installs them, so that a failed install cannot pass as skipped tests.
#define TETLOD_NEED_PROGRAM(program)                                                     \
  do {                                                                                   \
    if (!::tetlod::test::on_path(program)) {                                             \
      const char* ci = std::getenv("CI");                                                \
      if (ci && std::string(ci) == "true") FAIL() << program << " is not on PATH in CI"; \
      GTEST_SKIP() << "no " << program << " on PATH";                                    \
    }                                                                                    \
  } while (0)

inline std::string data_path(const std::string& name) {
  return std::string(TETLOD_SOURCE_DIR) + "/tests/data/" + name;
}

// A fresh directory under the test output directory.
inline std::string output_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(TETLOD_TEST_OUTPUT_DIR) / "io" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Binary file data written by hand, value by value, in this machine's byte order or
// (`swap`) the other one.
class Bytes {
 public:
  explicit Bytes(bool swap) : swap_(swap) {}
  void text(const std::string& s) { data_ += s; }
  void i32(int64_t v) { put(int32_t(v)); }
  void i64(int64_t v) { put(v); }
  void u64(uint64_t v) { put(v); }
  void f32(double v) { put(float(v)); }
  void f64(double v) { put(v); }
  const std::string& data() const { return data_; }
  std::string& data() { return data_; }

 private:
  template <typename T>
  void put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (swap_) std::reverse(bytes, bytes + sizeof(T));
    data_.append(bytes, sizeof(T));
  }
  bool swap_;
  std::string data_;
};

// A libMeshb file (.meshb, .solb) written by hand: each keyword's next position is filled in when
// the next keyword starts; the last one's stays 0.
class GmfWriter {
 public:
  GmfWriter(int version, bool swap) : version_(version), bytes_(swap) {
    i32(1);
    i32(version);
  }
  void keyword(int64_t code) {
    if (header_ != 0) patch(header_, bytes_.data().size());
    i32(code);
    header_ = bytes_.data().size();
    position(0);
  }
  void i32(int64_t v) { bytes_.i32(v); }
  void position(int64_t v) { version_ >= 3 ? bytes_.i64(v) : bytes_.i32(v); }
  void integer(int64_t v) { version_ == 4 ? bytes_.i64(v) : bytes_.i32(v); }
  void real(double v) { version_ == 1 ? bytes_.f32(v) : bytes_.f64(v); }
  void real32(double v) { bytes_.f32(v); }
  void real64(double v) { bytes_.f64(v); }
  // Gives the keyword begun last this next position instead of where the next starts.
  void override_next(int64_t v) {
    override_at_ = header_;
    next_override_ = v;
  }
  std::string finish(bool end_keyword = true) {
    if (end_keyword) keyword(54);  // End
    if (next_override_) patch(override_at_, *next_override_);
    return bytes_.data();
  }

 private:
  void patch(size_t at, int64_t value) {
    std::string& data = bytes_.data();
    const std::string saved = data.substr(at + (version_ >= 3 ? 8 : 4));
    data.resize(at);
    position(value);
    data += saved;
  }
  int version_;
  Bytes bytes_;
  size_t header_ = 0, override_at_ = 0;
  std::optional<int64_t> next_override_;
};

// A failed read whose message starts with `start` and contains `words`.
inline void expect_error(const Status& status, const std::string& start, const std::string& words) {
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind(start, 0), 0u) << status.message();
  EXPECT_NE(status.message().find(words), std::string::npos) << status.message();
}

// The same surface groups, in the same order: tags, names and triangles (corner
// positions, in order).
inline void expect_same_groups(const std::vector<InputSurfaceGroup>& expected,
                               const std::vector<InputSurfaceGroup>& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  for (size_t g = 0; g < expected.size(); ++g) {
    EXPECT_EQ(expected[g].tag, actual[g].tag) << "group " << g;
    EXPECT_EQ(expected[g].name, actual[g].name) << "group " << g;
    EXPECT_EQ(expected[g].triangles, actual[g].triangles) << "group " << g;
  }
}

// Two unit-ish cells of six tets each, plus a lone tet, with coordinates that have
// no short decimal form, materials 0, 7 and INT32_MAX.
inline TetMesh make_io_mesh() {
  TetMesh mesh;
  const double third = 1.0 / 3.0;
  const Vec3 a{0.1, -2.5e-7, third}, b{1.1, 0.0, third}, c{0.1, 1.0 + 1e-9, third},
      d{0.1, 0.0, 1.0 + third}, e{1.1, 1.0, 1.0 + third}, f{0.1, 0.0, -1234.5678};
  mesh.positions = {a, b, c, d, e, f};
  // Positively oriented: see the signed volumes checked in the tests.
  mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}, {0, 2, 1, 5}};
  mesh.materials = {0, 7, 2147483647};
  return mesh;
}

inline void expect_same_mesh(const TetMesh& expected, const TetMesh& actual) {
  ASSERT_EQ(expected.positions.size(), actual.positions.size());
  for (size_t i = 0; i < expected.positions.size(); ++i) {
    EXPECT_EQ(expected.positions[i].x, actual.positions[i].x) << "vertex " << i;
    EXPECT_EQ(expected.positions[i].y, actual.positions[i].y) << "vertex " << i;
    EXPECT_EQ(expected.positions[i].z, actual.positions[i].z) << "vertex " << i;
  }
  EXPECT_EQ(expected.tets, actual.tets);
  EXPECT_EQ(expected.materials, actual.materials);
}

// A tet as its material and its four corner positions in a canonical order, so
// that meshes numbered differently can be compared.
using CanonicalTet = std::pair<int32_t, std::array<std::array<double, 3>, 4>>;

inline std::vector<CanonicalTet> canonical_tets(const TetMesh& mesh) {
  std::vector<CanonicalTet> result;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    CanonicalTet c;
    c.first = mesh.materials[t];
    for (int k = 0; k < 4; ++k) {
      const Vec3& p = mesh.positions[mesh.tets[t][k]];
      c.second[k] = {p.x, p.y, p.z};
    }
    std::sort(c.second.begin(), c.second.end());
    result.push_back(c);
  }
  std::sort(result.begin(), result.end());
  return result;
}

// Reads damaged `data` as `format`: it must give an error that starts with
// "name:" or a consistent mesh (every corner a vertex, one material per tet).
inline void expect_error_or_valid_mesh(std::string_view data, MeshFormat format,
                                       const std::string& name) {
  TetMesh mesh;
  const Status s = read_mesh_from_memory(data, format, name, &mesh);
  if (!s.ok()) {
    ASSERT_EQ(s.message().rfind(name + ":", 0), 0u) << s.message();
    return;
  }
  ASSERT_EQ(mesh.materials.size(), mesh.tets.size());
  for (const Tet& t : mesh.tets)
    for (uint32_t v : t) ASSERT_LT(v, mesh.positions.size());
}

inline void expect_positive_orientation(const TetMesh& mesh) {
  for (const Tet& t : mesh.tets) EXPECT_GT(signed_volume6(mesh, t), 0.0);
}

// The three-tet solid the hand-written samples in tests/data describe:
// A(0,0,0) B(1,0,0) C(0,1,0) D(0,0,1) E(1,1,1) F(0,0,-1); tets ABCD, BCDE, ACBF
// with the materials given.
inline std::vector<CanonicalTet> sample_tets(int32_t abcd, int32_t bcde, int32_t acbf) {
  TetMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {0, 0, -1}};
  mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}, {0, 2, 1, 5}};
  mesh.materials = {abcd, bcde, acbf};
  return canonical_tets(mesh);
}

}  // namespace tetlod::test
