// Local property control: sizing fields and their parsers, and the simplifier
// honouring per-material and region sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/io/mesh_io.h"
#include "core/metrics.h"
#include "core/simplify.h"
#include "core/sizing.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

TEST(Sizing, CombinesRulesByTheirMinimum) {
  SizingField f;
  f.uniform = 8;
  ASSERT_TRUE(parse_material_sizes("2=3,5=1.5", &f));
  ASSERT_TRUE(parse_size_field("radial:0,0,0,1,0.5;box:10,10,10,11,11,11,0.25", &f));
  EXPECT_DOUBLE_EQ(f.size_at({0, 0, 0}, 1), 1.0);    // radial at the centre
  EXPECT_DOUBLE_EQ(f.size_at({4, 0, 0}, 1), 3.0);    // 1 + 0.5 * 4
  EXPECT_DOUBLE_EQ(f.size_at({4, 0, 0}, 5), 1.5);    // material 5 is finer
  EXPECT_DOUBLE_EQ(f.size_at({100, 0, 0}, 1), 8.0);  // capped by the uniform size
  EXPECT_DOUBLE_EQ(f.size_at({100, 0, 0}, 2), 3.0);
  EXPECT_DOUBLE_EQ(f.size_at({10.5, 10.5, 10.5}, 1), 0.25);
  EXPECT_DOUBLE_EQ(f.smallest_size(), 0.25);
  SizingField axis;
  ASSERT_TRUE(parse_size_field("axis:0,0,0,0,0,2,1,1", &axis));
  EXPECT_DOUBLE_EQ(axis.size_at({3, 4, 50}, 0), 6.0);  // distance 5 from the z axis
  // A ';' after the last rule, as typed in the viewer's rules box, is no rule; nothing
  // but ';' is no specification.
  SizingField trailing;
  ASSERT_TRUE(parse_size_field("box:0,0,0,1,1,1,2;", &trailing));
  EXPECT_EQ(trailing.boxes.size(), 1u);
  EXPECT_EQ(parse_size_field(";;", &trailing).message(), "--size-field: empty specification");
}

// An axis direction of any magnitude is that direction: no overflow to a zero axis
// (which would make the rule radial), no underflow to "zero".
// The simplifier evaluates sizes a block of positions at a time (material_size(),
// then apply_regions()); that must give, to the bit, what the rules say point by point:
// here written out again with Vec3 operations, as size_at() was first written.
TEST(Sizing, BlocksOfPointsGiveEachPointsSizeToTheBit) {
  SizingField f;
  f.uniform = 9;
  ASSERT_TRUE(parse_material_sizes("2=3,5=1.5", &f));
  ASSERT_TRUE(parse_size_field(
      "radial:0.3,-1,2,0.7,0.31;axis:1,2,3,0.2,-1,0.4,0.5,0.17;box:-1,-2,-3,2,1,0.5,0.05", &f));
  auto by_rules = [&f](const Vec3& p, int32_t material) {
    double size = f.uniform;
    for (const auto& m : f.material_sizes)
      if (m.first == material) size = std::min(size, m.second);
    for (const SizingField::Radial& r : f.radial) {
      Vec3 d = p - r.center;
      if (r.axis != Vec3{}) d = d - r.axis * dot(d, r.axis);
      size = std::min(size, r.size0 + r.growth * length(d));
    }
    for (const SizingField::Box& b : f.boxes)
      if (p.x >= b.low.x && p.x <= b.high.x && p.y >= b.low.y && p.y <= b.high.y &&
          p.z >= b.low.z && p.z <= b.high.z)
        size = std::min(size, b.size);
    return size;
  };
  constexpr int kPoints = 301;  // not a multiple of any block
  double x[kPoints], y[kPoints], z[kPoints], size[kPoints];
  int32_t material[kPoints];
  uint64_t state = 12345;
  auto next = [&state] {  // a fixed sequence in [-5, 5)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1p-53 * 10 - 5;
  };
  for (int i = 0; i < kPoints; ++i) {
    x[i] = next(), y[i] = next(), z[i] = next();
    material[i] = i % 6;
    size[i] = f.material_size(material[i]);
  }
  f.apply_regions(kPoints, x, y, z, size);
  int inside_box = 0, by_material = 0;
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 p{x[i], y[i], z[i]};
    const double want = by_rules(p, material[i]);
    EXPECT_EQ(std::memcmp(&size[i], &want, sizeof want), 0) << "point " << i;
    const double at = f.size_at(p, material[i]);
    EXPECT_EQ(std::memcmp(&size[i], &at, sizeof at), 0) << "point " << i;
    inside_box += size[i] == 0.05;
    by_material += size[i] == 1.5 || size[i] == 3;
  }
  EXPECT_GT(inside_box, 0);  // the box rule decided some, and the materials' sizes some
  EXPECT_GT(by_material, 0);
}

TEST(Sizing, AxisDirectionsOfAnyMagnitude) {
  for (const char* rule : {"axis:0,0,0,0,0,1e200,1,1", "axis:0,0,0,0,0,1e-200,1,1",
                           "axis:0,0,0,0,0,-1e308,1,1", "axis:0,0,0,0,0,5e-324,1,1"}) {
    SizingField f;
    ASSERT_TRUE(parse_size_field(rule, &f)) << rule;
    EXPECT_DOUBLE_EQ(f.size_at({3, 4, 50}, 0), 6.0) << rule;
  }
}

TEST(Sizing, ParsersNameTheOffendingValue) {
  SizingField f;
  EXPECT_NE(parse_material_sizes("1=2,x=3", &f).message().find("'x'"), std::string::npos);
  EXPECT_NE(parse_material_sizes("1=-2", &f).message().find("-2"), std::string::npos);
  EXPECT_NE(parse_material_sizes("1=2,1=3", &f).message().find("twice"), std::string::npos);
  EXPECT_NE(parse_material_sizes("1", &f).message().find("MATERIAL=SIZE"), std::string::npos);
  EXPECT_NE(parse_size_field("sphere:1,2,3", &f).message().find("unknown rule"), std::string::npos);
  EXPECT_NE(parse_size_field("radial:0,0,0,1", &f).message().find("needs 5"), std::string::npos);
  EXPECT_NE(parse_size_field("radial:0,0,0,nan,1", &f).message().find("nan"), std::string::npos);
  EXPECT_NE(parse_size_field("radial:0,0,0,1,-1", &f).message().find("growth"), std::string::npos);
  EXPECT_NE(parse_size_field("axis:0,0,0,0,0,0,1,1", &f).message().find("zero"), std::string::npos);
  EXPECT_NE(parse_size_field("box:1,0,0,0,1,1,1", &f).message().find("low corner"),
            std::string::npos);
}

TEST(Sizing, SimplifierKeepsEachMaterialWithinItsOwnSize) {
  const int n = 6;
  const TetMesh mesh = test::make_grid_mesh(
      2 * n, n, n, [&](int i, int, int) { return i < n ? 1 : 2; }, 1.0 / n);
  SimplifyParams p;
  p.tolerance = 1e-9;
  p.min_stretch = 0.05;
  p.max_valence = 40;
  p.subdivide = false;
  p.sizing.uniform = 0.9;
  ASSERT_TRUE(parse_material_sizes("1=0.4", &p.sizing));
  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, p, &r));
  double max1 = 0, max2 = 0;
  size_t count1 = 0, count2 = 0;
  for (size_t t = 0; t < r.output.tet_count(); ++t) {
    const double s = tet_shape(r.output, r.output.tets[t]).size;
    if (r.output.materials[t] == 1) {
      max1 = std::max(max1, s);
      ++count1;
    } else {
      max2 = std::max(max2, s);
      ++count2;
    }
  }
  EXPECT_LE(max1, 0.4);
  EXPECT_LE(max2, 0.9);
  EXPECT_GT(max2, 0.4);       // material 2 did coarsen beyond material 1's size
  EXPECT_GT(count1, count2);  // so the finer material keeps more elements
  EXPECT_EQ(r.violations.created, 0u);
}

// The viewer's starting size: three times the median tet size, two significant digits.
TEST(Sizing, SuggestedSizeIsThreeTimesTheMedianTetSize) {
  EXPECT_DOUBLE_EQ(suggested_size(TetMesh{}), 0.0);
  EXPECT_DOUBLE_EQ(suggested_size(test::make_single_tet()), 4.2);  // 3 * sqrt(2) = 4.24
  // Kuhn tets of unit cubes: every longest edge is a cube diagonal, 3 * sqrt(3) = 5.196.
  EXPECT_DOUBLE_EQ(suggested_size(test::make_grid_mesh(2, 2, 2, [](int, int, int) { return 1; })),
                   5.2);
  EXPECT_NEAR(suggested_size(test::make_grid_mesh(
                  2, 1, 1, [](int, int, int) { return 1; }, 10)),
              52, 1e-9);
}

// A graded mesh: its median is the fine part's, at which the coarse part would be
// subdivided thousands of times over; the size is raised until subdivision's estimated
// growth is at most kSuggestedGrowth. Here 6,000 Kuhn tets of unit cubes (longest edge
// sqrt 3) and 3,000 of cubes of side 20 beside them: 2/3 + 1/3 (2 * 20 sqrt 3 / s)^3 <= 2
// from s = 43.6, rounded up to 44 (three times the median would be 5.2).
// `fine` with `coarse` beside it (far off along x), as one mesh.
TetMesh side_by_side(TetMesh fine, const TetMesh& coarse) {
  const uint32_t offset = static_cast<uint32_t>(fine.positions.size());
  for (const Vec3& p : coarse.positions) fine.positions.push_back(p + Vec3{1000, 0, 0});
  for (size_t t = 0; t < coarse.tets.size(); ++t) {
    Tet tet = coarse.tets[t];
    for (uint32_t& v : tet) v += offset;
    fine.tets.push_back(tet);
    fine.materials.push_back(coarse.materials[t]);
  }
  return fine;
}

TEST(Sizing, SuggestedSizeOfAGradedMeshKeepsSubdivisionSmall) {
  const TetMesh coarse = test::make_grid_mesh(
      5, 10, 10, [](int, int, int) { return 2; }, 20);
  const TetMesh mesh =
      side_by_side(test::make_grid_mesh(10, 10, 10, [](int, int, int) { return 1; }), coarse);
  ASSERT_EQ(mesh.tet_count(), 9000u);
  bool raised = false;
  EXPECT_DOUBLE_EQ(suggested_size(mesh, &raised), 44);
  EXPECT_TRUE(raised);
  EXPECT_DOUBLE_EQ(suggested_size(coarse, &raised), 100);  // 3 * 20 sqrt 3 = 103.9
  EXPECT_FALSE(raised);
}

// A few coarse tets, 3 % of the mesh: subdivision's estimated growth at three times the
// median (5.2) is 0.97 + 0.03 (2 x 4 sqrt 3 / 5.2)^3 = 1.54, but they would all stay
// above that size where their splits are refused: the size is raised to what all but
// 1 % of the tets meet, the coarse ones' longest edge 4 sqrt 3 = 6.93, rounded up to 7.
TEST(Sizing, SuggestedSizeLeavesFewTetsAboveIt) {
  const TetMesh mesh =
      side_by_side(test::make_grid_mesh(10, 10, 10, [](int, int, int) { return 1; }),
                   test::make_grid_mesh(
                       31, 1, 1, [](int, int, int) { return 2; }, 4));
  ASSERT_EQ(mesh.tet_count(), 6186u);
  bool raised = false;
  EXPECT_DOUBLE_EQ(suggested_size(mesh, &raised), 7);
  EXPECT_TRUE(raised);
  // With half as many coarse tets (1.5 %): the same; with 0.5 %, three times the median.
  EXPECT_DOUBLE_EQ(
      suggested_size(side_by_side(test::make_grid_mesh(10, 10, 10, [](int, int, int) { return 1; }),
                                  test::make_grid_mesh(
                                      15, 1, 1, [](int, int, int) { return 2; }, 4))),
      7);
  EXPECT_DOUBLE_EQ(
      suggested_size(side_by_side(test::make_grid_mesh(10, 10, 10, [](int, int, int) { return 1; }),
                                  test::make_grid_mesh(
                                      5, 1, 1, [](int, int, int) { return 2; }, 4)),
                     &raised),
      5.2);
  EXPECT_FALSE(raised);
}

// A first simplification at the suggested size and the CLI's default tolerance (0.001 x
// the diagonal) coarsens every bundled mesh: subdivision does not outgrow the collapses.
TEST(Sizing, SuggestedSizeCoarsensTheBundledMeshes) {
  for (const char* name : {"motor", "spheres", "box2"}) {
    SCOPED_TRACE(name);
    TetMesh input;
    ReadInfo info;
    ASSERT_TRUE(
        read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/" + name + ".mesh", &input, &info));
    Vec3 lo = input.positions[0], hi = lo;
    for (const Vec3& q : input.positions) {
      lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
    }
    SimplifyParams p;
    p.sizing.uniform = suggested_size(input);
    p.tolerance = 1e-3 * length(hi - lo);
    SimplifyResult r;
    ASSERT_TRUE(simplify(input, p, &r));
    EXPECT_LT(r.output.tet_count(), input.tet_count()) << "size " << p.sizing.uniform;
    if (std::string(name) == "motor") {
      EXPECT_DOUBLE_EQ(p.sizing.uniform, 23.0);
      EXPECT_LT(r.output.tet_count(), input.tet_count() / 2);
    }
  }
}

}  // namespace
}  // namespace tetlod

namespace tetlod {
namespace {

// With a size field, a subdivision piece has its own size limit (at its own centroid):
// subdivision must not cut a tet that was within its limit into pieces that are not.
TEST(Sizing, RegionSizingCreatesNoViolations) {
  TetMesh input;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", &input, &info));
  SimplifyParams p;
  p.tolerance = 0.05;
  p.sizing.uniform = 20;
  ASSERT_TRUE(parse_size_field("axis:0,0,0,0,0,1,2.5,0.25", &p.sizing));
  SimplifyResult r;
  ASSERT_TRUE(simplify(input, p, &r));
  EXPECT_GT(r.splits, 0u);
  EXPECT_GT(r.history.step_count(), 0u);
  EXPECT_EQ(r.violations.created, 0u);
}

}  // namespace
}  // namespace tetlod
