// Exact simplifier cases on hand-made meshes: collapses that must happen and ones
// that must not, one per threshold and topology rule; the LOD round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <string>

#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/mesh_compare.h"
#include "core/metrics.h"
#include "core/simplify.h"
#include "core/test_meshes.h"
#include "core/validate.h"

namespace tetlod {
namespace {

TetMesh two_material_box(int n) {
  return test::make_grid_mesh(
      2 * n, n, n, [&](int i, int, int) { return i < n ? 1 : 2; }, 1.0 / n);
}

SimplifyParams loose_params(double size) {
  SimplifyParams p;
  p.tolerance = 1e-9;
  p.min_stretch = 0.05;
  p.max_valence = 40;
  p.sizing.uniform = size;
  p.subdivide = false;
  return p;
}

std::map<int32_t, double> volume_per_material(const TetMesh& m) {
  std::map<int32_t, double> v;
  for (size_t t = 0; t < m.tet_count(); ++t) v[m.materials[t]] += signed_volume6(m, m.tets[t]) / 6;
  return v;
}

TEST(Simplify, RejectsAbsurdThresholds) {
  const TetMesh mesh = two_material_box(1);
  SimplifyResult r;
  SimplifyParams p = loose_params(1);
  p.min_stretch = 1.0;
  EXPECT_NE(simplify(mesh, p, &r).message().find("stretch"), std::string::npos);
  p = loose_params(1);
  p.min_stretch = std::nan("");
  EXPECT_FALSE(simplify(mesh, p, &r).ok());
  p = loose_params(1);
  p.max_valence = 3;
  EXPECT_NE(simplify(mesh, p, &r).message().find("valence"), std::string::npos);
  p = loose_params(-1);
  EXPECT_FALSE(simplify(mesh, p, &r).ok());
  p = loose_params(1);
  p.tolerance = -1;
  EXPECT_NE(simplify(mesh, p, &r).message().find("tolerance"), std::string::npos);
  p = loose_params(1e-6);
  p.subdivide = true;
  EXPECT_NE(simplify(mesh, p, &r).message().find("subdivide"), std::string::npos);
  // Values are printed as given, and an astronomically small size does not overflow the
  // predicted count.
  p = loose_params(1e-300);
  p.subdivide = true;
  const std::string message = simplify(mesh, p, &r).message();
  EXPECT_NE(message.find("size 1e-300 "), std::string::npos) << message;
  EXPECT_NE(message.find("more than 10^15 tets"), std::string::npos) << message;
  p = loose_params(1);
  p.tolerance = -1e-9;
  EXPECT_NE(simplify(mesh, p, &r).message().find("tolerance -1e-09 "), std::string::npos);
}

TEST(Simplify, CoarsensTheTwoMaterialBoxKeepingItsShape) {
  const TetMesh mesh = two_material_box(4);
  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, loose_params(10), &r));
  EXPECT_GT(r.history.step_count(), 0u);
  EXPECT_LT(r.output.tet_count(), mesh.tet_count() / 4);
  // Planar faces and a tolerance of 1e-9: every material keeps its volume.
  const auto before = volume_per_material(mesh), after = volume_per_material(r.output);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_NEAR(after.at(1), before.at(1), 1e-9);
  EXPECT_NEAR(after.at(2), before.at(2), 1e-9);
  for (size_t t = 0; t < r.output.tet_count(); ++t) {
    EXPECT_GE(tet_shape(r.output, r.output.tets[t]).stretch, 0.05);
  }
  EXPECT_EQ(r.violations.created, 0u);
  // The 12 corners (box corners and the ends of the interface rim) survive in place.
  std::set<std::array<double, 3>> points;
  for (const Vec3& p : r.output.positions) points.insert({p.x, p.y, p.z});
  for (double x : {0.0, 1.0, 2.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, 1.0}) EXPECT_TRUE(points.count({x, y, z})) << x << " " << y << " " << z;
}

// A part placed far from the coordinates' origin (a plant's or a vehicle's frame) is
// held to the tolerance as it is at the origin: the quadrics' rounding grows with the
// square of the distance from the point they are taken about.
TEST(Simplify, KeepsTheToleranceFarFromTheOrigin) {
  // Two materials meeting on a wavy sheet, for collapses the tolerance refuses.
  const int n = 8;
  TetMesh at_origin = two_material_box(n);
  for (Vec3& v : at_origin.positions) v.x += 0.1 * std::sin(3.0 * v.y) * std::sin(3.0 * v.z);
  SimplifyParams p = loose_params(1);
  p.tolerance = 0.02;
  auto largest_move = [](const TetMesh& before, const TetMesh& after) {
    double largest = 0;
    for (const PairDeviation& d : compare_meshes(before, after).pairs)
      largest = std::max(largest, d.distance);
    return largest;
  };
  SimplifyResult near;
  ASSERT_TRUE(simplify(at_origin, p, &near));
  const double near_move = largest_move(at_origin, near.output);
  ASSERT_GT(near.rejections.tolerance, 0u);
  ASSERT_LE(near_move, 2 * p.tolerance);
  for (double offset : {1e7, -3e9}) {
    TetMesh far = at_origin;
    for (Vec3& v : far.positions) v = v + Vec3{offset, offset / 2, 0};
    SimplifyResult r;
    ASSERT_TRUE(simplify(far, p, &r));
    EXPECT_LE(largest_move(far, r.output), 2 * p.tolerance) << offset;
    EXPECT_GT(r.rejections.tolerance, near.rejections.tolerance / 2) << offset;
    // (The moved input carries the rounding of the move, 5e-7 at 3e9, and the grid's
    // many equal priorities then fall otherwise: a count within 15 %.)
    EXPECT_NEAR(double(r.output.tet_count()), double(near.output.tet_count()),
                0.15 * double(near.output.tet_count()))
        << offset;
  }
}

// Far from the origin a mesh is simplified round it and moved back: the bundled spheres
// 1e6 away (the helper-found case: a run past the valence that brings every node back
// at the origin gave up there, and 108 tets stayed above the size) keep the size as at
// the origin, with a region rule moved with them; the input's vertices come back bit
// for bit, and the history's last level is the output.
TEST(Simplify, AMeshFarFromTheOriginIsSimplifiedAsAtIt) {
  TetMesh at_origin;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh", &at_origin).ok());
  SimplifyParams p;  // the command line's defaults
  p.sizing.uniform = 1.5;
  p.tolerance = 0.02;
  p.past_valence_alongside = false;
  SimplifyParams radial = p;
  radial.sizing.uniform = 3;
  radial.sizing.radial.push_back({{1, 0, 0}, {}, 0.4, 0.3});
  SimplifyResult near, near_radial;
  ASSERT_TRUE(simplify(at_origin, p, &near));
  ASSERT_TRUE(simplify(at_origin, radial, &near_radial));
  ASSERT_EQ(near.violations.above_size, 0u);
  const Vec3 offset{1e6, 1e6, 1e6};
  TetMesh far = at_origin;
  for (Vec3& v : far.positions) v = v + offset;
  SimplifyResult r;
  ASSERT_TRUE(simplify(far, p, &r));
  EXPECT_EQ(r.violations.above_size, 0u);
  EXPECT_EQ(r.violations.created, 0u);
  EXPECT_NEAR(double(r.output.tet_count()), double(near.output.tet_count()),
              0.05 * double(near.output.tet_count()));
  for (const Vec3& v : r.output.positions) EXPECT_GT(v.x, 1e6 - 5);
  std::set<std::array<double, 3>> base;
  for (const Vec3& v : r.base.positions) base.insert({v.x, v.y, v.z});
  for (const Vec3& v : far.positions) EXPECT_EQ(base.count({v.x, v.y, v.z}), 1u);
  Lod lod(r.base, &r.history);
  lod.seek(r.history.step_count());
  const TetMesh last = lod.extract();
  ASSERT_EQ(last.positions.size(), r.output.positions.size());
  EXPECT_EQ(std::memcmp(last.positions.data(), r.output.positions.data(),
                        last.positions.size() * sizeof(Vec3)),
            0);
  // The rule's centre moves with the mesh.
  radial.sizing.radial[0].center = radial.sizing.radial[0].center + offset;
  SimplifyResult far_radial;
  ASSERT_TRUE(simplify(far, radial, &far_radial));
  EXPECT_EQ(far_radial.violations.above_size, near_radial.violations.above_size);
  EXPECT_NEAR(double(far_radial.output.tet_count()), double(near_radial.output.tet_count()),
              0.05 * double(near_radial.output.tet_count()));
}

TEST(Simplify, NothingCollapsesWhenEveryThresholdForbidsIt) {
  const TetMesh mesh = two_material_box(2);
  SimplifyResult r;
  // Size: the grid's longest edge is the cube diagonal sqrt(3)/2; any collapse makes a
  // longer edge.
  ASSERT_TRUE(simplify(mesh, loose_params(std::sqrt(3.0) / 2 + 1e-9), &r));
  EXPECT_EQ(r.history.step_count(), 0u);
  EXPECT_GT(r.rejections.size, 0u);
  // Stretch: Kuhn tets have stretch ~0.71 at best; asking for 0.9 forbids everything.
  SimplifyParams p = loose_params(10);
  p.min_stretch = 0.9;
  ASSERT_TRUE(simplify(mesh, p, &r));
  EXPECT_EQ(r.history.step_count(), 0u);
  EXPECT_GT(r.rejections.stretch, 0u);
  // Valence: every merged node would have more than 4 neighbours.
  p = loose_params(10);
  p.max_valence = 4;
  ASSERT_TRUE(simplify(mesh, p, &r));
  EXPECT_EQ(r.history.step_count(), 0u);
  EXPECT_GT(r.rejections.valence, 0u);
}

// Each edge is evaluated once at the start; without collapses nothing else is; with
// them the new nodes' edges are, and their neighbourhoods are swept; every collapse
// and every rejection but the link conditions checked at the top of the queue comes
// from an evaluation.
TEST(Simplify, CountsEvaluationsByWhereTheyHappen) {
  const TetMesh mesh = two_material_box(2);
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (const Tet& t : mesh.tets)
    for (int c = 0; c < 4; ++c)
      for (int d = c + 1; d < 4; ++d) edges.insert(std::minmax(t[c], t[d]));

  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, loose_params(std::sqrt(3.0) / 2 + 1e-9), &r));
  ASSERT_EQ(r.history.step_count(), 0u);
  EXPECT_EQ(r.evaluations.initial, edges.size());
  EXPECT_EQ(r.evaluations.new_node + r.evaluations.stale + r.evaluations.sweep, 0u);
  EXPECT_EQ(r.evaluations.sweeps, 0u);

  ASSERT_TRUE(simplify(mesh, loose_params(10), &r));
  ASSERT_GT(r.history.step_count(), 0u);
  EXPECT_EQ(r.evaluations.initial, edges.size());
  EXPECT_GT(r.evaluations.new_node, 0u);
  const RejectionCounts& x = r.rejections;
  EXPECT_GE(r.evaluations.total(),
            r.history.step_count() + x.tolerance + x.stretch + x.size + x.valence);
  // The last collapse leaves its nodes to sweep once the queue runs dry.
  EXPECT_GE(r.evaluations.sweeps, 1u);
  EXPECT_GT(r.evaluations.sweep, 0u);
}

// A node every tet has (a fan of 1152 tets round vertex 0, of valence 578): its edges
// are rejected for the valence without a walk of its star, and counted so, and its long
// edges are split from their other end's star (each walk of the big star for one edge
// made both time quadratic in its valence: 82k tets took 15 s). The result is a valid
// mesh that keeps the guarantee.
TEST(Simplify, AFanRoundANodeOfThousandsOfTets) {
  const TetMesh fan = test::make_fan(12);
  ASSERT_EQ(fan.tet_count(), 1152u);
  SimplifyParams p;
  p.sizing.uniform = 0.9;  // the spokes (1 long) are split, the sphere's edges are short
  p.min_stretch = 0.01;
  p.max_valence = 25;
  p.tolerance = 0.01;
  SimplifyResult r;
  ASSERT_TRUE(simplify(fan, p, &r));
  EXPECT_GT(r.splits, 0u);
  EXPECT_EQ(r.violations.created, 0u);
  for (TetMesh m : {r.base, r.output}) {
    ValidationReport report;
    EXPECT_TRUE(validate_mesh(&m, "fan", {}, &report).ok());
  }
  // Every edge of vertex 0 (interior, far past the valence) was rejected for it, at the
  // start at least.
  // (The base is renumbered: the centre is found by its position.)
  const auto centre = std::find(r.base.positions.begin(), r.base.positions.end(), Vec3{0, 0, 0});
  ASSERT_NE(centre, r.base.positions.end());
  const uint32_t centre_edges = test::valences(r.base)[size_t(centre - r.base.positions.begin())];
  EXPECT_EQ(centre_edges, 578u);  // a split spoke's midpoint takes its outer end's place
  EXPECT_GE(r.rejections.valence, centre_edges);
}

// Subdivision counts the long edges it leaves unsplit by what stopped it, and the
// final mesh's tets above the size are explained by them.
TEST(Simplify, CountsUnsplitEdgesByReasonAndExplainsTetsAboveTheSize) {
  const TetMesh mesh = two_material_box(2);  // edges 0.5, 0.71 and 0.87 long
  SimplifyParams p = loose_params(0.6);      // every edge is longer than half the size
  p.subdivide = true;
  // Valence 4: every new node would have more neighbours; the pieces are fine.
  p.max_valence = 4;
  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, p, &r));
  EXPECT_EQ(r.splits, 0u);
  EXPECT_GT(r.splits_skipped, 0u);
  EXPECT_EQ(r.splits_skipped_valence, r.splits_skipped);
  ASSERT_GT(r.violations.above_size, 0u);
  EXPECT_EQ(r.violations.created, 0u);
  std::string why = above_size_reason(p, r);
  EXPECT_NE(why.find("(" + std::to_string(r.splits_skipped) + " such edges in the mesh)"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("valence"), std::string::npos) << why;
  EXPECT_EQ(why.find("flatter"), std::string::npos) << why;

  // A stretch threshold above what bisecting these tets gives: no split for the shape.
  p.max_valence = 100;
  p.min_stretch = 0.7;
  ASSERT_TRUE(simplify(mesh, p, &r));
  EXPECT_EQ(r.splits, 0u);
  EXPECT_GT(r.splits_skipped, 0u);
  EXPECT_EQ(r.splits_skipped_valence, 0u);
  ASSERT_GT(r.violations.above_size, 0u);
  why = above_size_reason(p, r);
  EXPECT_NE(why.find("flatter"), std::string::npos) << why;
  EXPECT_EQ(why.find("valence threshold ("), std::string::npos) << why;
  EXPECT_NE(why.find("lower stretch threshold"), std::string::npos) << why;
  EXPECT_EQ(why.find("higher valence"), std::string::npos) << why;

  // Loose thresholds: every long edge is split and nothing is above the size.
  p.min_stretch = 0.05;
  ASSERT_TRUE(simplify(mesh, p, &r));
  EXPECT_GT(r.splits, 0u);
  EXPECT_EQ(r.splits_skipped, 0u);
  EXPECT_EQ(r.violations.above_size, 0u);

  // Without subdivision the input's own tets are the reason.
  p.subdivide = false;
  ASSERT_TRUE(simplify(mesh, p, &r));
  ASSERT_GT(r.violations.above_size, 0u);
  EXPECT_NE(above_size_reason(p, r).find("subdivision was off"), std::string::npos);
}

// An input tet so flat (below the least stretch threshold) that it is only just read
// as not flat: six times its volume 1.05e-12 of its longest edge cubed, where readers
// refuse 1e-12. Subdivision cuts no piece of it that is not twice clear of that
// (bisecting its longest edge gives two of 1.5e-12, within the stretch: refused), so
// that what it writes reads back whatever the rounding.
TEST(Simplify, SubdivisionCutsNoPieceOfAnAlmostFlatTetThatMightReadAsFlat) {
  TetMesh mesh;
  const double height = 1.05e-12 * std::pow(std::sqrt(2.0), 3);  // longest edge sqrt(2)
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, height}};
  mesh.tets = {{0, 1, 2, 3}};
  mesh.materials = {1};
  const TetShape input = tet_shape(mesh, mesh.tets[0]);
  ASSERT_LT(input.stretch, kMinStretch);
  ASSERT_FALSE(reads_back(input));
  ValidationReport report;
  TetMesh copy = mesh;
  ASSERT_TRUE(validate_mesh(&copy, "flat", {}, &report).ok());
  SimplifyParams p = loose_params(0.3);  // every edge longer than half of it
  p.subdivide = true;
  p.min_stretch = 0.15;
  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, p, &r));
  EXPECT_GT(r.splits_skipped, 0u);
  for (size_t t = 0; t < r.output.tet_count(); ++t) {
    const TetShape shape = tet_shape(r.output, r.output.tets[t]);
    if (reads_back(shape)) continue;
    for (uint32_t v : r.output.tets[t])  // only the input tet itself may be this flat
      EXPECT_TRUE(std::find(mesh.positions.begin(), mesh.positions.end(), r.output.positions[v]) !=
                  mesh.positions.end())
          << "tet " << t << ": 6V / s^3 = " << 6 * shape.volume / std::pow(shape.size, 3);
  }
}

TEST(Lod, ApplyThenUndoIsBitIdentical) {
  const TetMesh mesh = two_material_box(3);
  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, loose_params(10), &r));
  ASSERT_GT(r.history.step_count(), 3u);
  Lod lod(r.base, &r.history);
  const std::vector<Vec3> positions = lod.positions();
  const std::vector<Tet> tets = lod.tets();
  lod.seek(lod.step_count());
  const TetMesh last = lod.extract();
  EXPECT_EQ(last.tets, r.output.tets);
  EXPECT_EQ(last.positions.size(), r.output.positions.size());
  for (size_t v = 0; v < last.positions.size(); ++v)
    EXPECT_EQ(last.positions[v], r.output.positions[v]);
  lod.seek(0);
  EXPECT_EQ(lod.tets(), tets);
  ASSERT_EQ(lod.positions().size(), positions.size());
  EXPECT_EQ(std::memcmp(lod.positions().data(), positions.data(), positions.size() * sizeof(Vec3)),
            0);
  EXPECT_EQ(lod.alive_tet_count(), r.base.tet_count());
}

}  // namespace
}  // namespace tetlod
