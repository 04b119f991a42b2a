// The simplifier's guard against an outer boundary pushed through itself: on a ball
// with a thin gap inside (tests/data/gmsh/gap.geo), a tolerance above the gap's width
// lets collapses move one wall of the gap through the other. With the guard, no level
// of the history has tets that overlap (find_overlap(), which every reader runs);
// without it, the last one has.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/overlap.h"
#include "core/simplify.h"
#include "test_io_helpers.h"

namespace tetlod {
namespace {

TetMesh gap_mesh() {
  TetMesh mesh;
  const Status s = read_mesh(test::data_path("gmsh/gap.msh"), &mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return mesh;
}

SimplifyParams gap_params(double tolerance) {
  SimplifyParams params;
  params.sizing.uniform = 6;
  params.tolerance = tolerance;
  return params;
}

OverlapFinding overlap_in(const TetMesh& mesh) {
  std::vector<uint32_t> neighbors;
  const FaceProblem problem = build_face_neighbors(mesh, &neighbors);
  EXPECT_EQ(problem.kind, FaceProblem::Kind::kNone);
  return find_overlap(mesh, neighbors);
}

TEST(SimplifyOverlap, NoLevelHasTetsThatOverlap) {
  const TetMesh input = gap_mesh();
  ASSERT_EQ(overlap_in(input).kind, OverlapFinding::Kind::kNone);
  for (double tolerance : {1.0, 2.0, 4.0}) {
    SimplifyResult result;
    ASSERT_TRUE(simplify(input, gap_params(tolerance), &result).ok());
    EXPECT_GT(result.rejections.overlap, 0u) << "tolerance " << tolerance;
    EXPECT_EQ(result.violations.created, 0u);
    Lod lod(result.base, &result.history);
    const size_t steps = lod.step_count();
    for (size_t step = 0;; step = std::min(step + 7, steps)) {  // every 7th, and the last
      lod.seek(step);
      const OverlapFinding found = overlap_in(lod.extract());
      ASSERT_EQ(found.kind, OverlapFinding::Kind::kNone)
          << "tolerance " << tolerance << ", step " << step << " of " << steps << ": tets "
          << found.tet_a << " and " << found.tet_b;
      ASSERT_FALSE(found.cut_short);
      if (step == steps) break;
    }
    EXPECT_EQ(overlap_in(result.output).kind, OverlapFinding::Kind::kNone);
  }
}

TEST(SimplifyOverlap, WithoutTheGuardTheGapsWallsCross) {
  const TetMesh input = gap_mesh();
  for (double tolerance : {1.0, 2.0, 4.0}) {
    SimplifyParams params = gap_params(tolerance);
    params.keep_boundary_embedded = false;
    SimplifyResult result;
    ASSERT_TRUE(simplify(input, params, &result).ok());
    EXPECT_EQ(result.rejections.overlap, 0u);
    EXPECT_NE(overlap_in(result.output).kind, OverlapFinding::Kind::kNone)
        << "tolerance " << tolerance;
  }
}

// Where the boundary's sheets are far apart, the guard refuses nothing and the run is
// the same as without it, collapse for collapse.
TEST(SimplifyOverlap, TheGuardChangesNothingWhereNothingCrosses) {
  TetMesh input;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", &input).ok());
  SimplifyParams params;
  params.sizing.uniform = 8;
  params.tolerance = 0.05;
  SimplifyResult guarded, unguarded;
  ASSERT_TRUE(simplify(input, params, &guarded).ok());
  params.keep_boundary_embedded = false;
  ASSERT_TRUE(simplify(input, params, &unguarded).ok());
  EXPECT_EQ(guarded.rejections.overlap, 0u);
  EXPECT_EQ(guarded.output.tets, unguarded.output.tets);
  EXPECT_EQ(guarded.output.positions, unguarded.output.positions);
  EXPECT_EQ(guarded.history.step_count(), unguarded.history.step_count());
}

}  // namespace
}  // namespace tetlod
