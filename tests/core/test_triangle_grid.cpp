// TriangleGrid (core/triangle_grid.h): the nearest triangle is the one a scan of all
// finds, for triangles of mixed sizes and points inside and far outside the grid;
// degenerate inputs (one triangle, huge ones, coordinates whose span overflows) work.
#include <gtest/gtest.h>

#include <random>

#include "core/triangle_grid.h"

namespace tetlod {
namespace {

// The nearest by scanning every triangle (ties: the smaller index).
uint32_t brute_nearest(const std::vector<Triangle3>& triangles, const Vec3& p, double* d2) {
  uint32_t best = TriangleGrid::kNone;
  *d2 = INFINITY;
  for (uint32_t i = 0; i < triangles.size(); ++i) {
    const double d = squared_distance(p, triangles[i]);
    if (d < *d2) *d2 = d, best = i;
  }
  return best;
}

TEST(TriangleGrid, NearestIsWhatAScanFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Triangle3> triangles;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 c{u(rng) * 10, u(rng) * 5, u(rng) * 2};
    const double r = i % 100 == 0 ? 4.0 : 0.1 * u(rng);  // a few large ones
    triangles.push_back({c, c + Vec3{r * u(rng), r * u(rng), 0}, c + Vec3{0, r * u(rng), r}});
  }
  const TriangleGrid grid(triangles);
  for (int i = 0; i < 3000; ++i) {
    const double far = i % 10 == 0 ? 40 : 1;  // some points far outside
    const Vec3 p{(u(rng) - 0.5) * 12 * far, (u(rng) - 0.5) * 7 * far, (u(rng) - 0.5) * 4 * far};
    double want2 = 0, got2 = 0;
    const uint32_t want = brute_nearest(triangles, p, &want2);
    const uint32_t got = grid.nearest(p, &got2);
    ASSERT_NE(got, TriangleGrid::kNone);
    EXPECT_EQ(got2, want2) << i;
    EXPECT_EQ(squared_distance(p, triangles[got]), want2) << i << " " << got << " " << want;
  }
}

TEST(TriangleGrid, DegenerateInputs) {
  EXPECT_EQ(TriangleGrid().nearest({0, 0, 0}), TriangleGrid::kNone);
  const TriangleGrid one({{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}});
  double d2 = 0;
  EXPECT_EQ(one.nearest({0.2, 0.2, 3}, &d2), 0u);
  EXPECT_DOUBLE_EQ(d2, 9);
  // Corners whose span overflows a double: one cell, still the right answer.
  const TriangleGrid wide({{Vec3{-1.7e308, 0, 0}, Vec3{-1.7e308, 1, 0}, Vec3{-1.7e308, 0, 1}},
                           {Vec3{1.7e308, 0, 0}, Vec3{1.7e308, 1, 0}, Vec3{1.7e308, 0, 1}}});
  EXPECT_EQ(wide.nearest({1.7e308, 0.2, 0.2}), 1u);
  EXPECT_EQ(wide.nearest({-1.7e308, 0.2, 0.2}), 0u);
  // A budget of one cell: the nearest seen in it.
  const TriangleGrid two({{Vec3{0, 0, 0}, Vec3{0.1, 0, 0}, Vec3{0, 0.1, 0}},
                          {Vec3{5, 5, 5}, Vec3{5.1, 5, 5}, Vec3{5, 5.1, 5}}});
  EXPECT_EQ(two.nearest({0, 0, 0}, nullptr, 1), 0u);
}

}  // namespace
}  // namespace tetlod
