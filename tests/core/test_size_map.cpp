// Size maps (core/size_map.h): sizes at a mesh's vertices, linear in each tet; their
// Medit .sol files (core/io/sol.h); the simplifier keeping to them; histories that
// carry them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/io/sol.h"
#include "core/lod.h"
#include "core/metrics.h"
#include "core/simplify.h"
#include "core/size_map.h"
#include "core/sizing.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

std::shared_ptr<const SizeMap> map_of(const TetMesh& mesh, const std::vector<double>& sizes) {
  std::shared_ptr<const SizeMap> map;
  const Status s = SizeMap::build(mesh, sizes, &map);
  EXPECT_TRUE(s.ok()) << s.message();
  return map;
}

std::vector<double> sizes_of(const TetMesh& mesh, double (*f)(const Vec3&)) {
  std::vector<double> sizes;
  for (const Vec3& p : mesh.positions) sizes.push_back(f(p));
  return sizes;
}

// A point of tet t with barycentric weights from rng (inside, or on a face).
Vec3 point_in(const TetMesh& mesh, const Tet& t, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(0, 1);
  double w[4], sum = 0;
  for (double& x : w) sum += x = u(*rng);
  Vec3 p{};
  for (int c = 0; c < 4; ++c) p = p + mesh.positions[t[c]] * (w[c] / sum);
  return p;
}

// A field linear over the whole mesh is reproduced wherever the point is, to rounding.
TEST(SizeMap, ReproducesALinearField) {
  const TetMesh mesh = test::make_grid_mesh(
      5, 4, 3, [](int, int, int) { return 1; }, 0.5);
  auto linear = [](const Vec3& p) { return 1 + 2 * p.x + 3 * p.y + 0.5 * p.z; };
  const auto map = map_of(mesh, sizes_of(mesh, linear));
  ASSERT_TRUE(map);
  EXPECT_EQ(map->smallest(), 1);
  std::mt19937 rng(7);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p = point_in(mesh, mesh.tets[rng() % mesh.tets.size()], &rng);
    ASSERT_NEAR(map->at(p), linear(p), 1e-12) << k;
  }
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    ASSERT_NEAR(map->at(mesh.positions[v]), linear(mesh.positions[v]), 1e-12);
  // A thin plate (its grids' cells are bounded by its tets, not by its box's volume).
  TetMesh plate = test::make_grid_mesh(30, 30, 1, [](int, int, int) { return 1; });
  for (Vec3& p : plate.positions) p.z *= 1e-3;
  const auto plate_map = map_of(plate, sizes_of(plate, linear));
  ASSERT_TRUE(plate_map);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p = point_in(plate, plate.tets[rng() % plate.tets.size()], &rng);
    ASSERT_NEAR(plate_map->at(p), linear(p), 1e-9) << k;
  }
}

// A field that is not linear: the value at p is the interpolation in the tet that holds
// p (found here by trying every tet), the same from any order of queries.
TEST(SizeMap, InterpolatesInTheTetThatHoldsThePoint) {
  const TetMesh mesh = test::make_grid_mesh(
      4, 4, 4, [](int, int, int) { return 1; }, 0.25);
  auto curved = [](const Vec3& p) { return 0.1 + p.x * p.x + std::sin(3 * p.y) * p.z + p.z; };
  const std::vector<double> sizes = sizes_of(mesh, curved);
  const auto map = map_of(mesh, sizes);
  ASSERT_TRUE(map);
  std::mt19937 rng(3);
  std::vector<Vec3> points;
  for (int k = 0; k < 500; ++k)
    points.push_back(point_in(mesh, mesh.tets[rng() % mesh.tets.size()], &rng));
  std::vector<double> values;
  for (const Vec3& p : points) values.push_back(map->at(p));
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec3& p = points[k];
    double expected = std::numeric_limits<double>::quiet_NaN();
    for (const Tet& t : mesh.tets) {
      const double v6 = signed_volume6(mesh, t);
      double l[4];  // barycentric coordinates as volume ratios
      for (int c = 0; c < 4; ++c) {
        std::array<Vec3, 4> q{mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                              mesh.positions[t[3]]};
        q[c] = p;
        l[c] = signed_volume6(q[0], q[1], q[2], q[3]) / v6;
      }
      if (*std::min_element(l, l + 4) < -1e-12) continue;
      expected = 0;
      for (int c = 0; c < 4; ++c) expected += l[c] * sizes[t[c]];
      break;
    }
    ASSERT_NEAR(values[k], expected, 1e-12) << k;
  }
  // Backwards, the same bits: a value depends on the point alone.
  for (size_t k = points.size(); k-- > 0;) ASSERT_EQ(map->at(points[k]), values[k]) << k;
}

// Outside the mesh (a centroid just past a concave boundary, say): the value of a
// point of the nearest tet tried, within the sizes of its corners; never NaN.
TEST(SizeMap, PointsOutsideTakeANearbyValue) {
  // An L of cubes: the notch is outside.
  TetMesh mesh = test::make_grid_mesh(2, 2, 1, [](int, int, int) { return 1; });
  std::vector<Tet> kept;
  for (const Tet& t : mesh.tets) {
    Vec3 c{};
    for (uint32_t v : t) c = c + mesh.positions[v] * 0.25;
    if (!(c.x > 1 && c.y > 1)) kept.push_back(t);
  }
  mesh.tets = kept;
  mesh.materials.assign(kept.size(), 1);
  std::vector<double> sizes;
  for (const Vec3& p : mesh.positions) sizes.push_back(1 + p.x + 10 * p.y);
  // The notch's corner vertex (2, 2, z) is no longer used: keep the sizes of the rest.
  const auto map = map_of(mesh, sizes);
  ASSERT_TRUE(map);
  for (const Vec3& p : {Vec3{1.5, 1.5, 0.5}, Vec3{1.9, 1.9, 0.5}, Vec3{-1, -1, -1}, Vec3{5, 0.5, 9},
                        Vec3{1e300, -1e300, 0}}) {
    const double v = map->at(p);
    EXPECT_TRUE(std::isfinite(v)) << p.x;
    EXPECT_GE(v, 1) << p.x;
    EXPECT_LE(v, 1 + 2 + 20) << p.x;
  }
  // Just outside the face x = 2 (0 < y < 1): a value on that face.
  const double beside = map->at({2.25, 0.5, 0.5});
  EXPECT_GE(beside, 1 + 2);
  EXPECT_LE(beside, 1 + 2 + 10);
  // Where the sizes are equal, that size to the bit, inside and out.
  const auto flat = map_of(mesh, std::vector<double>(mesh.vertex_count(), 0.3));
  std::mt19937 rng(11);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 p = point_in(mesh, mesh.tets[rng() % mesh.tets.size()], &rng);
    ASSERT_EQ(flat->at(p), 0.3) << k;
    ASSERT_EQ(flat->at(p * 1.7 - Vec3{0.5, 0.5, 0.5}), 0.3) << k;
  }
}

// Sizes 60 orders of magnitude apart (fuzz_sol found a corner's size cancelled to 0
// by an interpolation written as differences from another's): every value stays
// within the sizes' range, however far off the point.
TEST(SizeMap, ExtremeSizesStayInTheirRange) {
  const TetMesh mesh = test::make_grid_mesh(2, 1, 1, [](int, int, int) { return 1; });
  std::vector<double> sizes;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) sizes.push_back(v % 3 == 1 ? 1e63 : 2 + v % 3);
  const auto map = map_of(mesh, sizes);
  ASSERT_TRUE(map);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int k = 0; k < 2000; ++k) {
    const double scale = std::pow(10.0, double(k % 12) * 25);
    const Vec3 p{u(rng) * scale, u(rng), u(rng)};
    const double v = map->at(p);
    ASSERT_GE(v, 2) << k;
    ASSERT_LE(v, 1e63) << k;
  }
}

TEST(SizeMap, BadSizesAreNamed) {
  const TetMesh mesh = test::make_single_tet();
  std::shared_ptr<const SizeMap> map;
  Status s = SizeMap::build(mesh, {1, 1, 1}, &map);
  EXPECT_NE(s.message().find("3 sizes for a mesh of 4 vertices"), std::string::npos) << s.message();
  s = SizeMap::build(mesh, {1, 1, -2, 1}, &map);
  EXPECT_NE(s.message().find("size 3 (vertex 3) is -2"), std::string::npos) << s.message();
  s = SizeMap::build(mesh, {1, std::nan(""), 1, 1}, &map);
  EXPECT_NE(s.message().find("size 2 (vertex 2) is nan"), std::string::npos) << s.message();
  EXPECT_FALSE(map);
}

TEST(SolFile, ReadsSizesAtVertices) {
  std::vector<double> sizes;
  std::string count_at;  // for an error the caller finds: a count other than the mesh's
  const Status s = parse_sol_sizes(
      "MeshVersionFormatted 2\n# sizes\nDimension\n3\nSolAtVertices\n3\n1 1\n0.5\n1e-3\n2\nEnd\n",
      "m.sol", &sizes, &count_at);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(sizes, (std::vector<double>{0.5, 1e-3, 2}));
  EXPECT_EQ(count_at, "m.sol:6");
  // MMG writes a version 1 file without End, and keywords in any case.
  ASSERT_TRUE(
      parse_sol_sizes("meshversionformatted 1 dimension 3 solatvertices 1 1 1 4\n", "m.sol", &sizes)
          .ok());
  EXPECT_EQ(sizes, std::vector<double>{4});
}

TEST(SolFile, ErrorsNameTheFileLineAndWhat) {
  auto error = [](const std::string& text) {
    std::vector<double> sizes{7};
    const Status s = parse_sol_sizes(text, "m.sol", &sizes);
    EXPECT_EQ(sizes, std::vector<double>{7}) << "changed on error: " << text;
    return s.ok() ? std::string("accepted") : s.message();
  };
  const std::string head = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n";
  EXPECT_EQ(error(head + "2\n1 3\n1 0 1 0 0 1\n1 0 1 0 0 1\n").rfind("m.sol:5: a tensor field", 0),
            0u)
      << error(head + "2\n1 3\n");
  EXPECT_NE(error(head + "2\n1 3\n").find("anisotropic metric"), std::string::npos);
  EXPECT_NE(error(head + "2\n1 2\n").find("a vector field (type 2)"), std::string::npos);
  EXPECT_NE(error(head + "2\n2 1 1\n").find("m.sol:5: 2 fields at each vertex"), std::string::npos);
  EXPECT_EQ(error(head + "3\n1 1\n1\n2\n-3\n"), "m.sol:8: size 3 is -3: sizes must be > 0");
  EXPECT_EQ(error(head + "3\n1 1\n1\n0\n3\n"), "m.sol:7: size 2 is 0: sizes must be > 0");
  EXPECT_NE(error(head + "3\n1 1\n1\nnan\n3\n").find("m.sol:7:"), std::string::npos);
  EXPECT_NE(error(head + "3\n1 1\n1\n2\n").find("m.sol"), std::string::npos);  // cut short
  EXPECT_NE(error(head + "2\n1 1\n1\n2\n3\n").find("m.sol:8: found the number '3'"),
            std::string::npos)
      << error(head + "2\n1 1\n1\n2\n3\n");
  EXPECT_NE(error("MeshVersionFormatted 2\nDimension 2\n").find("m.sol:2: only 3-dimensional"),
            std::string::npos);
  EXPECT_NE(error("MeshVersionFormatted 2\nSolAtTetrahedra 1 1 1 1\n")
                .find("m.sol:2: 'SolAtTetrahedra': sizes on other entities"),
            std::string::npos)
      << error("MeshVersionFormatted 2\nSolAtTetrahedra 1 1 1 1\n");
  EXPECT_EQ(error("MeshVersionFormatted 2\nDimension 3\nEnd\n"), "m.sol: no SolAtVertices section");
  EXPECT_NE(error(std::string("\1\0\0\0\2\0\0\0", 8)).find("m.sol: byte 8: the file ends"),
            std::string::npos)
      << error(std::string("\1\0\0\0\2\0\0\0", 8));
  EXPECT_NE(error("Vertices 3").find("not a Medit .sol file"), std::string::npos);
  EXPECT_NE(
      error(head + "1\n1 1\n1\n" + "SolAtVertices\n1\n1 1\n1\n").find("a second SolAtVertices"),
      std::string::npos);
  EXPECT_NE(error(head + "99999999999\n1 1\n1\n").find("m.sol:4:"), std::string::npos);
}

// FreeFEM's savesol() (libMeshb; tests/data/other_tools/make_freefem.edp) wrote
// h = 0.1 + 0.2 x + 0.05 y z at the vertices of its cube, as a version 1 .solb (4-byte
// reals) and as ASCII .sol (6 digits): both read as that function at the vertices of
// the cube it wrote alongside.
TEST(SolFile, ReadsFreeFemsBinaryAndAsciiFiles) {
  TetMesh cube;
  ASSERT_TRUE(read_mesh(test::data_path("other_tools/meshb_freefem_cube.meshb"), &cube).ok());
  std::vector<double> binary, ascii;
  Status s = read_sol_sizes(test::data_path("other_tools/solb_freefem_cube.solb"), &binary);
  ASSERT_TRUE(s.ok()) << s.message();
  s = read_sol_sizes(test::data_path("other_tools/sol_freefem_cube.sol"), &ascii);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(binary.size(), cube.vertex_count());
  ASSERT_EQ(ascii.size(), cube.vertex_count());
  double largest = 0;
  for (size_t v = 0; v < cube.vertex_count(); ++v) {
    const Vec3& p = cube.positions[v];
    const double h = 0.1 + 0.2 * p.x + 0.05 * p.y * p.z;
    EXPECT_EQ(binary[v], double(float(h))) << v;
    EXPECT_NEAR(ascii[v], h, 5e-6 * h) << v;
    largest = std::max(largest, binary[v]);
  }
  EXPECT_NEAR(largest, 0.35, 1e-7);
}

// A .solb written by hand: `reals` sizes in SolAtVertices of a file of `version` in
// this machine's byte order or the other, with other keywords before it.
std::string solb(int version, bool swap, const std::vector<double>& reals, int type = 1) {
  test::GmfWriter f(version, swap);
  f.keyword(3);  // Dimension
  f.i32(3);
  f.keyword(59);  // Tangents, skipped: any keyword may be there
  f.integer(1);
  f.real(1), f.real(0), f.real(0);
  f.keyword(62);  // SolAtVertices
  f.integer(int64_t(reals.size()));
  f.i32(1);
  f.i32(type);
  for (double r : reals) f.real(r);
  return f.finish();
}

TEST(SolFile, ReadsBinaryFilesOfEveryVersionInBothByteOrders) {
  const std::vector<double> sizes{0.5, 1e-3, 2, 1.0 / 3};
  for (int version = 1; version <= 4; ++version)
    for (bool swap : {false, true}) {
      std::vector<double> read;
      std::string count_at;
      const std::string bytes = solb(version, swap, sizes);
      const Status s = parse_sol_sizes(bytes, "m.solb", &read, &count_at);
      ASSERT_TRUE(s.ok()) << version << swap << ": " << s.message();
      ASSERT_EQ(count_at.rfind("m.solb: byte ", 0), 0u) << count_at;
      const size_t at = std::stoul(count_at.substr(13));  // the count, 4 (its low byte)
      ASSERT_LT(at + 8, bytes.size());
      EXPECT_EQ(bytes[swap ? at + (version >= 4 ? 7 : 3) : at], 4) << version << swap;
      ASSERT_EQ(read.size(), sizes.size());
      for (size_t i = 0; i < sizes.size(); ++i)
        EXPECT_EQ(read[i], version == 1 ? double(float(sizes[i])) : sizes[i]) << version << swap;
    }
  // FloatingPointPrecision 64 in a version 1 file: 8-byte reals after it.
  test::GmfWriter f(1, false);
  f.keyword(3);
  f.i32(3);
  f.keyword(155);
  f.integer(64);
  f.keyword(62);
  f.integer(1);
  f.i32(1);
  f.i32(1);
  f.real64(1.0 / 3);
  std::vector<double> read;
  ASSERT_TRUE(parse_sol_sizes(f.finish(), "m.solb", &read).ok());
  EXPECT_EQ(read, std::vector<double>{1.0 / 3});
}

TEST(SolFile, BinaryErrorsNameTheFileByteAndWhat) {
  auto error = [](const std::string& data) {
    std::vector<double> sizes{7};
    const Status s = parse_sol_sizes(data, "m.solb", &sizes);
    EXPECT_EQ(sizes, std::vector<double>{7}) << "changed on error";
    return s.ok() ? std::string("accepted") : s.message();
  };
  auto has = [](const std::string& message, const std::string& words) {
    return message.rfind("m.solb: byte ", 0) == 0 && message.find(words) != std::string::npos;
  };
  // Version 2: the header is 8 bytes, Dimension 4 + 4 + 4, Tangents 4 + 4 + 4 + 24,
  // SolAtVertices' body starts at byte 64.
  EXPECT_EQ(error(solb(2, false, {1, 2}, 3)),
            "m.solb: byte 68: a tensor field (type 3, an anisotropic metric): TetLOD reads "
            "isotropic sizes, one number a vertex (type 1)");
  EXPECT_TRUE(has(error(solb(2, true, {1, 2}, 2)), "a vector field (type 2)"));
  EXPECT_EQ(error(solb(2, false, {1, -2, 3})), "m.solb: byte 84: size 2 is -2: sizes must be > 0");
  EXPECT_EQ(error(solb(2, false, {1, std::numeric_limits<double>::infinity()})),
            "m.solb: byte 84: size 2 is inf: sizes must be finite");
  EXPECT_TRUE(has(error(solb(2, false, {1, std::nan("")})), "size 2 is nan"));
  EXPECT_EQ(error(solb(3, false, {1}).substr(0, 60)),
            "m.solb: byte 28: keyword 59: the next keyword's position 64 is past the end of "
            "the file (60 bytes; truncated file?)")
      << "(version 3: 8-byte positions)";
  auto file = [](auto&& body) {
    test::GmfWriter f(2, false);
    f.keyword(3);
    f.i32(3);
    body(f);
    return f.finish();
  };
  EXPECT_TRUE(has(error(file([](test::GmfWriter& f) {
                    f.keyword(62);
                    f.integer(1);
                    f.i32(2);
                    f.i32(1);
                    f.i32(1);
                    f.real(1), f.real(1);
                  })),
                  "2 fields at each vertex: TetLOD reads one, the size (type 1)"));
  EXPECT_TRUE(has(error(file([](test::GmfWriter& f) {
                    f.keyword(62);
                    f.integer(1);
                    f.i32(-1);  // fields
                  })),
                  "-1 fields at each vertex"));
  EXPECT_TRUE(has(error(file([](test::GmfWriter& f) {
                    f.keyword(66);  // SolAtTetrahedra
                    f.integer(0);
                    f.i32(1);
                    f.i32(1);
                  })),
                  "SolAtTetrahedra: sizes on other entities than vertices are not read"));
  EXPECT_TRUE(has(error(file([](test::GmfWriter& f) {
                    f.keyword(62);
                    f.integer(5);
                    f.i32(1);
                    f.i32(1);
                    f.real(1);
                  })),
                  "SolAtVertices: 5 sizes of 8 bytes do not fit in the 8 bytes"));
  EXPECT_TRUE(has(error(file([](test::GmfWriter& f) {
                    f.keyword(62);
                    f.integer(-1);
                    f.i32(1);
                    f.i32(1);
                    f.real(1);
                  })),
                  "SolAtVertices: a vertex count of -1"));
  EXPECT_TRUE(has(error(file([](test::GmfWriter& f) {
                    for (int k = 0; k < 2; ++k) {
                      f.keyword(62);
                      f.integer(1);
                      f.i32(1);
                      f.i32(1);
                      f.real(1);
                    }
                  })),
                  "a second SolAtVertices section"));
  EXPECT_EQ(error(file([](test::GmfWriter&) {})), "m.solb: no SolAtVertices section");
  test::GmfWriter flat(2, false);
  flat.keyword(3);
  flat.i32(2);
  EXPECT_TRUE(has(error(flat.finish()), "only 3-dimensional sizes are supported (Dimension 2)"));
  // Every truncation of a valid file fails, naming the file.
  const std::string whole = solb(4, true, {1, 2, 3});
  for (size_t n = 0; n < whole.size(); ++n) {
    const std::string message = error(whole.substr(0, n));
    EXPECT_EQ(message.rfind("m.solb", 0), 0u) << n << ": " << message;
  }
}

// The run keeps every tet it makes within the map's size at its centroid, and the
// mesh comes out graded as the map asks: fine where the sizes are small.
TEST(SizeMap, SimplifierKeepsToTheMap) {
  TetMesh input;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", &input).ok());
  SimplifyParams p;
  p.tolerance = 0.05;
  p.subdivide_past_valence = false;  // faster
  // Small (12) on the side x < 0, large (30) on the other.
  std::vector<double> sizes;
  for (const Vec3& v : input.positions) sizes.push_back(v.x < 0 ? 12 : 30);
  p.sizing.map = map_of(input, sizes);
  ASSERT_TRUE(check_params(p).ok());
  SimplifyResult r;
  ASSERT_TRUE(simplify(input, p, &r).ok());
  EXPECT_GT(r.history.step_count(), 0u);
  EXPECT_EQ(r.violations.created, 0u);
  size_t above = 0, left = 0, right = 0;
  for (size_t t = 0; t < r.output.tet_count(); ++t) {
    const Tet& q = r.output.tets[t];
    const Vec3 c = (r.output.positions[q[0]] + r.output.positions[q[1]] + r.output.positions[q[2]] +
                    r.output.positions[q[3]]) *
                   0.25;
    const double size = tet_shape(r.output, q).size;
    above += size > p.sizing.size_at(c, r.output.materials[t]);
    if (c.x < -15) ++left;
    if (c.x > 15) ++right;
  }
  // Those above it are the ones the run counts (pieces of input tets it could not
  // split without breaking another threshold; `created` says none is of its making).
  EXPECT_EQ(above, r.violations.above_size);
  EXPECT_GT(left, 2 * right) << left << " tets on the fine side, " << right << " on the other";
}

// A history made with a map carries what the map was built from, so that lod
// --improve keeps to the same map, value for value: over the input, and over another
// mesh (--size-map-mesh; the values at the base's vertices that histories saved
// before, TLSZMAP1, still read, gave there another function). Damaged blocks are
// refused, naming them.
TEST(SizeMap, HistoriesCarryTheMap) {
  const TetMesh mesh = test::make_grid_mesh(
      6, 3, 3, [](int i, int, int) { return i < 3 ? 1 : 2; }, 1.0 / 3);
  // The same domain in 12 tets: a background mesh.
  const TetMesh coarse = test::make_grid_mesh(2, 1, 1, [](int, int, int) { return 1; });
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/size_map";
  std::filesystem::create_directories(dir);
  std::string bytes;  // the first history's, its base and map
  TetMesh first_base;
  std::shared_ptr<const SizeMap> first_map;
  for (const TetMesh* over : {&mesh, &coarse}) {
    SCOPED_TRACE(over == &mesh ? "over the input" : "over a background mesh");
    SimplifyParams p;
    p.tolerance = 1e-9;
    p.min_stretch = 0.05;
    p.max_valence = 40;
    std::vector<double> sizes;
    for (const Vec3& v : over->positions) sizes.push_back(0.3 + v.x * v.x);
    p.sizing.map = map_of(*over, sizes);
    SimplifyResult r;
    ASSERT_TRUE(simplify(mesh, p, &r).ok());
    const std::string path = dir + "/with_map.tlh";
    ASSERT_TRUE(write_history(path, r.base, r.history, &p).ok());
    TetMesh base;
    CollapseHistory history;
    std::optional<SimplifyParams> read;
    const Status s = read_history(path, &base, &history, &read);
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_TRUE(read && read->sizing.map);
    EXPECT_EQ(read->sizing.map->vertex_count(), over->vertex_count());
    std::mt19937 rng(5);
    for (int k = 0; k < 600; ++k) {
      Vec3 q = point_in(base, base.tets[rng() % base.tets.size()], &rng);
      if (k % 3 == 0) q = q * 1.5 - Vec3{0.5, 0.25, 0.25};  // outside too
      ASSERT_EQ(read->sizing.map->at(q), p.sizing.map->at(q)) << k;
    }
    if (over == &mesh) {
      std::ifstream in(path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), {});
      first_base = r.base;
      first_map = p.sizing.map;
    }
  }

  // The block, after the thresholds: "TLSZMAP2", the vertex count, the vertices, the
  // tet count, the tets, the sizes; the end block holds the file's length last.
  const size_t at = bytes.find("TLSZMAP2");
  ASSERT_NE(at, std::string::npos);
  const size_t nv = mesh.vertex_count(), nt = mesh.tet_count();
  const size_t tets_at = at + 16 + 24 * nv + 8, sizes_at = tets_at + 16 * nt;
  auto sealed = [](std::string file) {  // sealed again: the end block's checksum
    const uint64_t sum = history_checksum(std::string_view(file).substr(0, file.size() - 8));
    std::memcpy(&file[file.size() - 8], &sum, 8);
    return file;
  };
  TetMesh base;
  CollapseHistory history;
  std::optional<SimplifyParams> read;
  auto error_with = [&](const std::string& damaged) {
    const std::string other = dir + "/damaged.tlh";
    std::ofstream(other, std::ios::binary) << damaged;
    const Status e = read_history(other, &base, &history, &read);
    return e.ok() ? std::string("accepted") : e.message();
  };
  std::string bytes_bad = bytes;
  const double negative = -1;
  std::memcpy(&bytes_bad[sizes_at + 8 * 4], &negative, 8);
  EXPECT_NE(error_with(bytes_bad).find("corrupt history: size map: size 5 (vertex 5) is -1"),
            std::string::npos)
      << error_with(bytes_bad);
  bytes_bad = bytes;
  const uint32_t beyond = uint32_t(nv);
  std::memcpy(&bytes_bad[tets_at + 4], &beyond, 4);
  EXPECT_NE(error_with(bytes_bad).find("size map: a tet's vertex out of range"), std::string::npos)
      << error_with(bytes_bad);
  bytes_bad = bytes;
  const uint64_t fewer = nv - 1;
  std::memcpy(&bytes_bad[at + 8], &fewer, 8);
  EXPECT_NE(error_with(bytes_bad).find("corrupt history"), std::string::npos);
  // Without the thresholds before it.
  const size_t params_at = bytes.find("TLPARAM1");
  ASSERT_NE(params_at, std::string::npos);
  bytes_bad = sealed(bytes.substr(0, params_at) + bytes.substr(at));
  EXPECT_NE(error_with(bytes_bad).find("a size map without thresholds"), std::string::npos)
      << error_with(bytes_bad);

  // A TLSZMAP1 block (the map's values at the base's vertices) in its place: a map
  // over the base, the same function over the input's tets to rounding.
  const size_t block_end = sizes_at + 8 * nv;
  std::string v1 = "TLSZMAP1";
  const uint64_t count = first_base.vertex_count();
  v1.append(reinterpret_cast<const char*>(&count), 8);
  for (const Vec3& q : first_base.positions) {
    const double value = first_map->at(q);
    v1.append(reinterpret_cast<const char*>(&value), 8);
  }
  const Status old = (std::ofstream(dir + "/v1.tlh", std::ios::binary)
                          << sealed(bytes.substr(0, at) + v1 + bytes.substr(block_end)),
                      read_history(dir + "/v1.tlh", &base, &history, &read));
  ASSERT_TRUE(old.ok()) << old.message();
  ASSERT_TRUE(read && read->sizing.map);
  EXPECT_EQ(read->sizing.map->vertex_count(), first_base.vertex_count());
  std::mt19937 rng(6);
  for (int k = 0; k < 300; ++k) {
    const Vec3 q = point_in(base, base.tets[rng() % base.tets.size()], &rng);
    ASSERT_NEAR(read->sizing.map->at(q), first_map->at(q), 1e-12) << k;
  }
}

}  // namespace
}  // namespace tetlod
