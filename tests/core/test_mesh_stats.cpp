// Table I metrics against an independent brute-force computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>

#include "core/adjacency.h"
#include "core/mesh_stats.h"
#include "core/metrics.h"
#include "core/simplify.h"
#include "core/test_meshes.h"
#include "core/validate.h"
#include "mesh_stats_reference.h"

namespace tetlod {
namespace {

TEST(Metrics, RegularTetHasStretchOne) {
  const TetShape s = tet_shape({1, 1, 1}, {1, -1, -1}, {-1, -1, 1}, {-1, 1, -1});
  EXPECT_NEAR(s.stretch, 1.0, 1e-12);
  EXPECT_NEAR(s.size, std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(s.volume, 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.area, 4 * std::sqrt(3.0) / 4 * 8, 1e-12);
}

// A tet's centroid is the same to the bit in any order of its corners (a size limit is
// read there both where a collapse is checked, its moving corner last, and in the final
// count, in the tet's own order); summed as given, orders differ in the last bits.
TEST(Metrics, TheCentroidIsTheSameInAnyOrderOfTheCorners) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-1e3, 1e3);
  size_t differed = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<Vec3, 4> p;
    for (Vec3& q : p) q = {coordinate(random), coordinate(random), coordinate(random)};
    const Vec3 first = tet_centroid(p[0], p[1], p[2], p[3]);
    std::array<int, 4> order{0, 1, 2, 3};
    while (std::next_permutation(order.begin(), order.end())) {
      const Vec3 c = tet_centroid(p[order[0]], p[order[1]], p[order[2]], p[order[3]]);
      ASSERT_EQ(std::memcmp(&c, &first, sizeof(Vec3)), 0) << "trial " << trial;
      const Vec3 plain = (p[order[0]] + p[order[1]] + p[order[2]] + p[order[3]]) * 0.25;
      differed += std::memcmp(&plain, &first, sizeof(Vec3)) != 0;
    }
    EXPECT_NEAR(first.x, (p[0].x + p[1].x + p[2].x + p[3].x) * 0.25, 1e-12);
  }
  EXPECT_GT(differed, 0u);  // what it is for
}

// Every tet of stretch at least kMinStretch reads back (validate_mesh() takes it as
// not flat: six times its volume above 1e-12 of its longest edge cubed), and the bound
// kMinStretch rests on holds: 6V >= d^3 s^3 / sqrt(2). Needles, slivers, caps and
// wedges, squashed in one or two directions down to that stretch.
TEST(Metrics, EveryTetAboveTheLeastStretchReadsBack) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_real_distribution<double> exponent(-9, 0);
  size_t near_the_floor = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const double fx = std::pow(10.0, exponent(random)),
                 fy = trial % 2 ? 1 : std::pow(10.0, exponent(random));
    TetMesh mesh;
    for (int k = 0; k < 4; ++k)
      mesh.positions.push_back({unit(random) * fx, unit(random) * fy, unit(random)});
    mesh.tets.push_back({0, 1, 2, 3});
    mesh.materials.push_back(1);
    const TetShape shape = tet_shape(mesh, mesh.tets[0]);
    const double d = std::abs(shape.stretch);
    if (!(d >= kMinStretch)) continue;
    near_the_floor += d < 10 * kMinStretch;
    const double volume6 = 6 * std::abs(shape.volume);
    const double s3 = shape.size * shape.size * shape.size;
    ASSERT_GE(volume6, d * d * d * s3 / std::sqrt(2.0) * (1 - 1e-9)) << trial;
    ValidationReport report;
    ASSERT_TRUE(validate_mesh(&mesh, "t", {}, &report).ok()) << trial << ": stretch " << d;
  }
  EXPECT_GT(near_the_floor, 100u);
}

TEST(Metrics, FlatAndInvertedTets) {
  EXPECT_NEAR(tet_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0}).stretch, 0.0, 1e-15);
  EXPECT_LT(tet_shape({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}).stretch, 0.0);
  // The corner tet of a unit cube: V = 1/6, s = sqrt(2), A = 3/2 + sqrt(3)/2.
  const TetShape s = tet_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_NEAR(s.stretch,
              6 * std::sqrt(6.0) * (1.0 / 6) / (std::sqrt(2.0) * (1.5 + std::sqrt(3.0) / 2)),
              1e-14);
}

TEST(MeshStats, MatchesBruteForceOnAPerturbedThreeMaterialGrid) {
  TetMesh mesh =
      test::make_grid_mesh(5, 4, 3, [](int i, int j, int) { return i < 2 ? 3 : (j < 2 ? 7 : 0); });
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (Vec3& p : mesh.positions) p = p + Vec3{jitter(rng), jitter(rng), jitter(rng)};
  ValidationReport report;
  ASSERT_TRUE(validate_mesh(&mesh, "grid", {}, &report));
  const MeshStats stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
  test::expect_stats_match_reference(mesh, stats);
  EXPECT_EQ(stats.whole.elements, 5u * 4 * 3 * 6);
  EXPECT_EQ(stats.whole.nodes, 6u * 5 * 4);
  ASSERT_EQ(stats.per_material.size(), 3u);
  EXPECT_EQ(stats.per_material[0].material, 0);
  EXPECT_EQ(stats.per_material[2].material, 7);
}

TEST(MeshStats, GridCountsAreExact) {
  // An n^3 Kuhn grid: (n+1)^3 nodes, 6 n^3 tets; edges: 3n(n+1)^2 axis edges,
  // 3 n^2 (n+1) face diagonals and n^3 cube diagonals.
  const int n = 3;
  const TetMesh mesh = test::make_grid_mesh(n, n, n, [](int, int, int) { return 1; });
  const MeshStats stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
  EXPECT_EQ(stats.whole.nodes, 64u);
  EXPECT_EQ(stats.whole.edges,
            static_cast<size_t>(3 * n * (n + 1) * (n + 1) + 3 * n * n * (n + 1) + n * n * n));
  EXPECT_EQ(stats.whole.max_valence, 14u);  // interior Kuhn vertices
  EXPECT_NEAR(stats.whole.max_size, std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(stats.whole.volume, 27.0, 1e-12);
  uint64_t total = 0;
  for (uint64_t c : stats.stretch_histogram) total += c;
  EXPECT_EQ(total, stats.whole.elements);
}

}  // namespace
}  // namespace tetlod

namespace tetlod {
namespace {

// Many materials and large ids take other paths (lookup table limits, bit masks).
TEST(MeshStats, ManyAndLargeMaterialIdsMatchBruteForce) {
  for (int variant = 0; variant < 3; ++variant) {
    TetMesh mesh = test::make_grid_mesh(8, 6, 5, [&](int i, int j, int k) {
      const int cell = (k * 6 + j) * 8 + i;
      if (variant == 0) return cell % 40;                // > 32 materials
      if (variant == 1) return cell;                     // 240 materials, one per cube
      return cell % 3 == 0 ? 2000000000 : 7 + cell % 5;  // huge id mixed with small ones
    });
    std::mt19937 rng(11 + variant);
    std::uniform_real_distribution<double> jitter(-0.1, 0.1);
    for (Vec3& p : mesh.positions) p = p + Vec3{jitter(rng), jitter(rng), jitter(rng)};
    ValidationReport report;
    ASSERT_TRUE(validate_mesh(&mesh, "grid", {}, &report));
    const MeshStats stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
    test::expect_stats_match_reference(mesh, stats);
  }
  // More than 256 materials.
  TetMesh mesh =
      test::make_grid_mesh(10, 10, 3, [](int i, int j, int k) { return (k * 10 + j) * 10 + i; });
  const MeshStats stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
  EXPECT_EQ(stats.per_material.size(), 300u);
  test::expect_stats_match_reference(mesh, stats);
}

// A 6 x 6 x 1 slab of material 2 between two 6 x 6 x 2 blocks of material 1 (a thin
// layer), and a 6 x 6 x 5 block of material 3 beside them: each material's volume and
// the area of its faces on the boundary or an interface, exactly; the layer's
// thickness, twice the one over the other, is near its own (1; its rim adds 24 to the
// 72 of its two faces), the blocks' larger.
TEST(MeshStats, MaterialSurfacesGiveALayersThickness) {
  const TetMesh mesh = test::make_grid_mesh(6, 12, 5, [](int, int j, int k) -> int32_t {
    if (j >= 6) return 3;
    return k == 2 ? 2 : 1;
  });
  const std::vector<MaterialSurface> surfaces = material_surfaces(mesh);
  ASSERT_EQ(surfaces.size(), 3u);
  EXPECT_EQ(surfaces[0].material, 1);
  EXPECT_NEAR(surfaces[0].volume, 144, 1e-9);
  // Two 6 x 6 x 2 blocks: each 2 * 36 + 4 * 12 = 120.
  EXPECT_NEAR(surfaces[0].area, 240, 1e-9);
  EXPECT_NEAR(surfaces[1].volume, 36, 1e-9);
  EXPECT_NEAR(surfaces[1].area, 96, 1e-9);
  EXPECT_NEAR(surfaces[1].thickness(), 0.75, 1e-12);
  // 6 x 6 x 5: 2 * 36 + 4 * 30.
  EXPECT_NEAR(surfaces[2].volume, 180, 1e-9);
  EXPECT_NEAR(surfaces[2].area, 192, 1e-9);
  EXPECT_NEAR(surfaces[0].thickness(), 1.2, 1e-12);  // each block 2 thick
  EXPECT_NEAR(surfaces[2].thickness(), 1.875, 1e-12);
}

}  // namespace
}  // namespace tetlod
