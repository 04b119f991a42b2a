// One exact test per rule of the edge-collapse simplifier (core/simplify.cpp:
// evaluate(), check_position(), topology_ok()), on tiny hand-built meshes: collapses
// that must happen and ones that must not. Every run uses subdivide = false and loose
// thresholds except the one under test, and reads what happened from the collapse
// history (replayed with Lod, so each step is checked against the mesh it was applied
// to), the output and the rejection counts.
//
// Vertex ids in result.base and in the history are the simplifier's own (it renumbers
// the input along a Morton curve), so vertices are matched to the input by position.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/classify.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/metrics.h"
#include "core/rule_meshes.h"
#include "core/simplify.h"
#include "core/surface.h"
#include "core/topology_checks.h"

namespace tetlod {
namespace {

using Step = CollapseHistory::Step;

// Every threshold out of the way: a collapse is refused only by topology, by an
// inverted or nearly flat tet, or by the threshold a test tightens.
SimplifyParams loose_params() {
  SimplifyParams p;
  p.tolerance = 1e3;
  p.min_stretch = 0.01;
  p.max_valence = kMaxValence;
  p.sizing.uniform = 1e3;
  p.subdivide = false;
  return p;
}

SimplifyResult run(const TetMesh& mesh, const SimplifyParams& params) {
  SimplifyResult result;
  const Status s = simplify(mesh, params, &result);
  EXPECT_TRUE(s.ok()) << s.message();
  return result;
}

TetMesh read_box2() {
  TetMesh mesh;
  const Status s = read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return mesh;
}

// The simplifier's classification of `mesh` (the same functions it calls itself).
std::vector<FeatureKind> kinds_of(const TetMesh& mesh, double crease_angle_degrees) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  ClassifyOptions options;
  options.crease_angle_degrees = crease_angle_degrees;
  return classify_vertices(mesh, extract_surface(mesh, neighbors), options).kind;
}

// Calls f(s, step, lod) for every step s with `lod` at the mesh the step was applied to.
template <class F>
void for_each_step(const SimplifyResult& r, F f) {
  Lod lod(r.base, &r.history);
  for (size_t s = 0; s < r.history.step_count(); ++s) {
    lod.seek(s);
    f(s, r.history.steps[s], lod);
  }
}

// Base vertex positions after every step; retired vertices flagged in `*removed`.
std::vector<Vec3> final_positions(const SimplifyResult& r, std::vector<uint8_t>* removed) {
  std::vector<Vec3> positions = r.base.positions;
  removed->assign(positions.size(), 0);
  for (const Step& step : r.history.steps) {
    positions[step.kept] = step.new_position;
    (*removed)[step.removed] = 1;
  }
  return positions;
}

// Tets alive in `lod` that use vertex v.
std::vector<uint32_t> alive_star(const Lod& lod, uint32_t v) {
  std::vector<uint32_t> star;
  for (uint32_t t = 0; t < lod.tets().size(); ++t) {
    if (!lod.alive()[t]) continue;
    const Tet& q = lod.tets()[t];
    if (q[0] == v || q[1] == v || q[2] == v || q[3] == v) star.push_back(t);
  }
  return star;
}

using Face = std::array<uint32_t, 3>;

// Boundary and interface faces (sorted corner ids) of the alive tets.
std::set<Face> surface_faces(const std::vector<Tet>& tets, const std::vector<int32_t>& materials,
                             const std::vector<uint8_t>& alive) {
  std::map<Face, std::vector<int32_t>> uses;
  for (uint32_t t = 0; t < tets.size(); ++t) {
    if (!alive[t]) continue;
    for (const auto& f : kTetFace) {
      Face face{tets[t][f[0]], tets[t][f[1]], tets[t][f[2]]};
      std::sort(face.begin(), face.end());
      uses[face].push_back(materials[t]);
    }
  }
  std::set<Face> surface;
  for (const auto& [face, mats] : uses)
    if (mats.size() == 1 || mats[0] != mats[1]) surface.insert(face);
  return surface;
}

bool face_has_edge(const Face& f, uint32_t a, uint32_t b) {
  const bool has_a = f[0] == a || f[1] == a || f[2] == a;
  const bool has_b = f[0] == b || f[1] == b || f[2] == b;
  return has_a && has_b;
}

struct Region {
  int32_t material = 0;
  size_t tets = 0;
  double volume = 0;
  std::set<std::array<double, 3>> points;  // positions of its vertices
};

// The regions of `mesh`, sorted by (material, volume, first point).
std::vector<Region> regions_of(const TetMesh& mesh) {
  int count = 0;
  const std::vector<int> label = test::region_labels(mesh, &count);
  std::vector<Region> regions(count);
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    Region& g = regions[label[t]];
    g.material = mesh.materials[t];
    ++g.tets;
    g.volume += signed_volume6(mesh, mesh.tets[t]) / 6;
    for (uint32_t v : mesh.tets[t]) {
      const Vec3& p = mesh.positions[v];
      g.points.insert({p.x, p.y, p.z});
    }
  }
  std::sort(regions.begin(), regions.end(), [](const Region& a, const Region& b) {
    if (a.material != b.material) return a.material < b.material;
    if (a.volume != b.volume) return a.volume < b.volume;
    return *a.points.begin() < *b.points.begin();
  });
  return regions;
}

std::map<int32_t, double> volume_per_material(const TetMesh& mesh) {
  std::map<int32_t, double> volume;
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    volume[mesh.materials[t]] += signed_volume6(mesh, mesh.tets[t]) / 6;
  return volume;
}

// Number of edge neighbours of every vertex.
std::vector<uint32_t> valences(const TetMesh& mesh) {
  std::vector<std::set<uint32_t>> around(mesh.vertex_count());
  for (const Tet& t : mesh.tets)
    for (uint32_t a : t)
      for (uint32_t b : t)
        if (a != b) around[a].insert(b);
  std::vector<uint32_t> n(mesh.vertex_count());
  for (size_t v = 0; v < n.size(); ++v) n[v] = static_cast<uint32_t>(around[v].size());
  return n;
}

uint32_t max_valence(const TetMesh& mesh) {
  const std::vector<uint32_t> n = valences(mesh);
  return n.empty() ? 0 : *std::max_element(n.begin(), n.end());
}

double min_stretch(const TetMesh& mesh) {
  double d = 1;
  for (const Tet& t : mesh.tets) d = std::min(d, tet_shape(mesh, t).stretch);
  return d;
}

double max_size(const TetMesh& mesh) {
  double s = 0;
  for (const Tet& t : mesh.tets) s = std::max(s, tet_shape(mesh, t).size);
  return s;
}

std::array<double, 3> key(const Vec3& p) {
  return {p.x, p.y, p.z};
}

// The link condition of Dey, Edelsbrunner et al. for collapsing edge (i, j) in the
// sub-complex of alive tets that `in` accepts, closed by coning its boundary to a
// virtual outside vertex: lk(i) and lk(j) share only simplices of lk(i, j). Written
// from the definition, independently of the simplifier's version.
template <class Filter>
bool link_condition_holds(const Lod& lod, uint32_t i, uint32_t j, Filter in) {
  constexpr uint32_t kOut = kInvalidIndex;
  struct Links {
    std::set<uint32_t> vertices;
    std::set<std::pair<uint32_t, uint32_t>> edges;
    std::set<Face> triangles;
    void add_edge(uint32_t a, uint32_t b) {
      vertices.insert(a);
      vertices.insert(b);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
    void add_triangle(uint32_t a, uint32_t b, uint32_t c) {
      add_edge(a, b), add_edge(b, c), add_edge(a, c);
      Face f{a, b, c};
      std::sort(f.begin(), f.end());
      triangles.insert(f);
    }
  };
  // Faces (v, a, b) of v's star in the sub-complex, with the number of its tets using each.
  auto star_faces = [&](uint32_t v) {
    std::map<std::pair<uint32_t, uint32_t>, int> faces;
    for (uint32_t t : alive_star(lod, v)) {
      if (!in(t)) continue;
      std::vector<uint32_t> o;
      for (uint32_t w : lod.tets()[t])
        if (w != v) o.push_back(w);
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = o[k], b = o[(k + 1) % 3];
        ++faces[{std::min(a, b), std::max(a, b)}];
      }
    }
    return faces;
  };
  auto vertex_link = [&](uint32_t v) {
    Links link;
    for (uint32_t t : alive_star(lod, v)) {
      if (!in(t)) continue;
      std::vector<uint32_t> o;
      for (uint32_t w : lod.tets()[t])
        if (w != v) o.push_back(w);
      link.add_triangle(o[0], o[1], o[2]);
    }
    for (const auto& [ab, uses] : star_faces(v))
      if (uses == 1) link.add_triangle(ab.first, ab.second, kOut);
    return link;
  };
  const Links li = vertex_link(i), lj = vertex_link(j);
  Links lij;
  for (uint32_t t : alive_star(lod, i)) {
    if (!in(t) || !tet_has(lod.tets()[t], j)) continue;
    std::vector<uint32_t> o;
    for (uint32_t w : lod.tets()[t])
      if (w != i && w != j) o.push_back(w);
    lij.add_edge(o[0], o[1]);
  }
  for (const auto& [ab, uses] : star_faces(i)) {
    if (uses != 1 || (ab.first != j && ab.second != j)) continue;
    lij.add_edge(ab.first == j ? ab.second : ab.first, kOut);
  }
  for (uint32_t v : li.vertices)
    if (lj.vertices.count(v) && !lij.vertices.count(v)) return false;
  for (const auto& e : li.edges)
    if (lj.edges.count(e) && !lij.edges.count(e)) return false;
  for (const Face& f : li.triangles)
    if (lj.triangles.count(f)) return false;
  return true;
}

// ---------------------------------------------------------------- 1. tolerance
// tau_TL bounds the quadric error of eq. (1). On a paraboloid top face every
// neighbouring triangle has its own plane, so with tau_TL = 0 no top vertex may move
// or be removed, while collapses between interior vertices (zero quadric) go on; with
// a large tau_TL the top face coarsens.
TEST(SimplifyRules, ToleranceZeroFreezesACurvedBoundaryButNotTheInterior) {
  const TetMesh mesh = test::make_bent_grid(4, 4, 3, 0.1);
  for (const Tet& t : mesh.tets) ASSERT_GT(signed_volume6(mesh, t), 0);
  size_t top_input = 0;
  for (const Vec3& p : mesh.positions) top_input += p.z > 2.5;
  ASSERT_EQ(top_input, 25u);

  SimplifyParams p = loose_params();
  p.tolerance = 0;
  const SimplifyResult frozen = run(mesh, p);
  const std::vector<FeatureKind> kind = kinds_of(frozen.base, p.crease_angle_degrees);
  auto on_top = [&](uint32_t v) { return frozen.base.positions[v].z > 2.5; };
  size_t interior_steps = 0;
  for_each_step(frozen, [&](size_t s, const Step& step, const Lod&) {
    EXPECT_FALSE(on_top(step.removed)) << "step " << s << " removed a vertex of the curved face";
    if (on_top(step.kept)) {
      EXPECT_EQ(step.new_position, step.old_position) << "step " << s << " moved a top vertex";
    }
    interior_steps +=
        kind[step.kept] == FeatureKind::kInterior && kind[step.removed] == FeatureKind::kInterior;
  });
  EXPECT_GT(interior_steps, 0u);
  EXPECT_GT(frozen.rejections.tolerance, 0u);
  std::set<std::array<double, 3>> top_before, top_after;
  for (const Vec3& q : mesh.positions)
    if (q.z > 2.5) top_before.insert(key(q));
  for (const Vec3& q : frozen.output.positions)
    if (q.z > 2.5) top_after.insert(key(q));
  EXPECT_EQ(top_after, top_before);

  p.tolerance = 1;
  const SimplifyResult coarse = run(mesh, p);
  size_t top_removed = 0;
  for (const Step& step : coarse.history.steps)
    top_removed += coarse.base.positions[step.removed].z > 2.5;
  EXPECT_GT(top_removed, 0u);
  size_t top_output = 0;
  for (const Vec3& q : coarse.output.positions) top_output += q.z > 2.5;
  EXPECT_LT(top_output, top_input);
}

// Every candidate the feature rules allow on a mesh with planar faces and straight
// edges lies exactly in its planes, so the quadric error is exactly 0 and tau_TL must
// not matter: the translated box2 must give the same run with tau_TL = 1e-9 as with
// tau_TL = 1, and as the untranslated box2.
TEST(SimplifyRules, ToleranceDoesNotDependOnWhereAPlanarModelSits) {
  TetMesh box = read_box2();
  SimplifyParams p = loose_params();
  p.tolerance = 1;
  const SimplifyResult at_origin = run(box, p);
  for (Vec3& q : box.positions) q = q + Vec3{0.1, 0.1, 0.1};
  const SimplifyResult loose = run(box, p);
  p.tolerance = 1e-9;
  const SimplifyResult tight = run(box, p);
  EXPECT_EQ(loose.rejections.tolerance, 0u);
  EXPECT_EQ(tight.rejections.tolerance, 0u);
  EXPECT_EQ(tight.history.step_count(), loose.history.step_count());
  EXPECT_EQ(tight.output.tet_count(), loose.output.tet_count());
  EXPECT_EQ(tight.history.step_count(), at_origin.history.step_count());
}

// ------------------------------------------------------------------ 2. stretch
// Every collapse of the centred octahedron gives 4 tets congruent to
// (e_x, e_y, e_z, -e_x), of stretch d* ~ 0.656 < 0.732 (the input tets): tau_ST just
// above d* forbids all six, just below allows exactly one. On a jittered grid, every
// tet alive at any step keeps d_t >= tau_ST.
TEST(SimplifyRules, StretchThresholdIsNeverCrossed) {
  const TetMesh octahedron = test::make_centred_octahedron();
  const double best = tet_shape({1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {-1, 0, 0}).stretch;
  // eq. (2): 6 sqrt(6) V / (s A) with V = 1/3, s = 2, A = 2 + sqrt(3).
  ASSERT_NEAR(best, 2 * std::sqrt(6.0) / (2 * (2 + std::sqrt(3.0))), 1e-12);
  ASSERT_GT(min_stretch(octahedron), best + 0.05);

  SimplifyParams p = loose_params();
  p.min_stretch = best + 1e-9;
  SimplifyResult r = run(octahedron, p);
  EXPECT_EQ(r.history.step_count(), 0u);
  EXPECT_EQ(r.rejections.stretch, 6u);    // the six centre edges
  EXPECT_EQ(r.rejections.topology, 12u);  // the twelve corner-corner edges
  EXPECT_EQ(r.output.tet_count(), 8u);

  p.min_stretch = best - 1e-9;
  r = run(octahedron, p);
  ASSERT_EQ(r.history.step_count(), 1u);
  ASSERT_EQ(r.output.tet_count(), 4u);
  for (const Tet& t : r.output.tets) EXPECT_NEAR(tet_shape(r.output, t).stretch, best, 1e-12);

  const TetMesh grid = test::make_jittered_grid(4, 0.15);
  const double tau = 0.3;
  ASSERT_GE(min_stretch(grid), tau);
  p = loose_params();
  p.min_stretch = tau;
  r = run(grid, p);
  EXPECT_GT(r.history.step_count(), 10u);
  EXPECT_GT(r.rejections.stretch, 0u);
  Lod lod(r.base, &r.history);
  for (size_t s = 1; s <= r.history.step_count(); ++s) {
    lod.seek(s);
    const TetMesh m = lod.extract();
    EXPECT_GE(min_stretch(m), tau) << "after step " << s;
  }
  EXPECT_GE(min_stretch(r.output), tau);
  EXPECT_EQ(r.violations.below_stretch, 0u);
}

// --------------------------------------------------------------------- 3. size
// Each collapse of the centred octahedron makes the edge from the kept vertex to its
// opposite, of length 2: tau_SZ just below 2 forbids all six, just above allows one.
TEST(SimplifyRules, SizeJustBelowEveryCollapseForbidsThemAll) {
  const TetMesh octahedron = test::make_centred_octahedron();
  ASSERT_NEAR(max_size(octahedron), std::sqrt(2.0), 1e-15);
  SimplifyParams p = loose_params();
  p.sizing.uniform = 2 - 1e-9;
  SimplifyResult r = run(octahedron, p);
  EXPECT_EQ(r.history.step_count(), 0u);
  EXPECT_EQ(r.rejections.size, 6u);
  EXPECT_EQ(r.rejections.topology, 12u);
  EXPECT_EQ(r.output.tet_count(), 8u);

  p.sizing.uniform = 2 + 1e-9;
  r = run(octahedron, p);
  ASSERT_EQ(r.history.step_count(), 1u);
  ASSERT_EQ(r.output.tet_count(), 4u);
  EXPECT_EQ(max_size(r.output), 2.0);

  // On a jittered grid no tet alive at any step is longer than tau_SZ.
  const TetMesh grid = test::make_jittered_grid(4, 0.15);
  const double tau = 2.0;
  ASSERT_LE(max_size(grid), tau);
  p = loose_params();
  p.sizing.uniform = tau;
  r = run(grid, p);
  EXPECT_GT(r.history.step_count(), 10u);
  EXPECT_GT(r.rejections.size, 0u);
  Lod lod(r.base, &r.history);
  for (size_t s = 1; s <= r.history.step_count(); ++s) {
    lod.seek(s);
    EXPECT_LE(max_size(lod.extract()), tau) << "after step " << s;
  }
}

// ------------------------------------------------------------------ 4. valence
// Every collapse of the centred octahedron leaves a node joined to the other five:
// tau_VL = 4 forbids all six (counted as valence), 5 allows one. On a jittered grid
// whose nodes are all within tau_VL, every node at every step stays within it.
TEST(SimplifyRules, ValenceLimitIsNeverExceeded) {
  const TetMesh octahedron = test::make_centred_octahedron();
  SimplifyParams p = loose_params();
  p.max_valence = 4;
  SimplifyResult r = run(octahedron, p);
  EXPECT_EQ(r.history.step_count(), 0u);
  EXPECT_EQ(r.rejections.valence, 6u);
  EXPECT_EQ(r.rejections.topology, 12u);

  p.max_valence = 5;
  r = run(octahedron, p);
  ASSERT_EQ(r.history.step_count(), 1u);
  EXPECT_EQ(max_valence(r.output), 5u);

  const TetMesh grid = test::make_jittered_grid(4, 0.15);
  const uint32_t tau = 14;
  ASSERT_EQ(max_valence(grid), tau);  // the Kuhn grid's interior nodes
  p = loose_params();
  p.max_valence = tau;
  r = run(grid, p);
  EXPECT_GT(r.history.step_count(), 10u);
  EXPECT_GT(r.rejections.valence, 0u);
  Lod lod(r.base, &r.history);
  for (size_t s = 1; s <= r.history.step_count(); ++s) {
    lod.seek(s);
    EXPECT_LE(max_valence(lod.extract()), tau) << "after step " << s;
  }
  EXPECT_EQ(r.violations.above_valence, 0u);
}

// ------------------------------------------------------- 5. topology (a): interior edges
// A slab one cube thick: every vertex is on the boundary, on the face z = 0 or z = 1.
// An edge between the two faces runs through the interior (or along a side face
// without being a feature edge) and must never be collapsed: that would pinch the
// slab. Collapses along the top and bottom faces must happen.
TEST(SimplifyRules, InteriorEdgeBetweenTwoBoundaryNodesIsNeverCollapsed) {
  const TetMesh slab = test::make_grid_mesh(4, 4, 1, [](int, int, int) { return 1; });
  const SimplifyResult r = run(slab, loose_params());
  const std::vector<FeatureKind> kind = kinds_of(r.base, 40);
  for (FeatureKind k : kind) ASSERT_NE(k, FeatureKind::kInterior);
  EXPECT_GT(r.history.step_count(), 5u);
  EXPECT_GT(r.rejections.topology, 0u);
  for_each_step(r, [&](size_t s, const Step& step, const Lod& lod) {
    EXPECT_EQ(r.base.positions[step.kept].z, r.base.positions[step.removed].z)
        << "step " << s << " collapsed an edge between the two faces of the slab";
    const std::set<Face> surface = surface_faces(lod.tets(), lod.materials(), lod.alive());
    bool on_surface = false;
    for (const Face& f : surface)
      on_surface = on_surface || face_has_edge(f, step.kept, step.removed);
    EXPECT_TRUE(on_surface) << "step " << s << " collapsed an interior edge (" << step.kept << ", "
                            << step.removed << ") whose ends are both on the boundary";
  });
  for (const Vec3& q : r.output.positions) EXPECT_TRUE(q.z == 0 || q.z == 1);
  EXPECT_NEAR(volume_per_material(r.output).at(1), 16.0, 1e-12);
}

// ---------------------------------------------------------------- 6. topology (b): corners
// box2: the 8 box corners and the 4 ends of the interface rim are corners; they are
// never removed, never moved, and two of them never merge.
TEST(SimplifyRules, CornersNeverMoveNeverVanishNeverMerge) {
  const TetMesh box = read_box2();
  ASSERT_EQ(box.tet_count(), 136u);
  std::set<std::array<double, 3>> corners;
  for (double x : {0.0, 1.0, 2.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, 1.0}) corners.insert({x, y, z});

  const SimplifyResult r = run(box, loose_params());
  ASSERT_GT(r.history.step_count(), 20u);
  const std::vector<FeatureKind> kind = kinds_of(r.base, 40);
  std::set<std::array<double, 3>> classified;
  for (uint32_t v = 0; v < kind.size(); ++v)
    if (kind[v] == FeatureKind::kCorner) classified.insert(key(r.base.positions[v]));
  EXPECT_EQ(classified, corners);

  for (const Step& step : r.history.steps) {
    const bool kept_corner = corners.count(key(r.base.positions[step.kept])) > 0;
    const bool removed_corner = corners.count(key(r.base.positions[step.removed])) > 0;
    EXPECT_FALSE(removed_corner) << "corner " << step.removed << " removed";
    EXPECT_FALSE(kept_corner && removed_corner);
    if (kept_corner) {
      EXPECT_EQ(step.new_position, step.old_position) << "corner " << step.kept << " moved";
    }
  }
  std::set<std::array<double, 3>> output_corners;
  for (const Vec3& q : r.output.positions)
    if (corners.count(key(q))) output_corners.insert(key(q));
  EXPECT_EQ(output_corners, corners);
  // Each corner is still one vertex (none was merged into another vertex's place).
  size_t corner_vertices = 0;
  for (const Vec3& q : r.output.positions) corner_vertices += corners.count(key(q));
  EXPECT_EQ(corner_vertices, 12u);
}

// ---------------------------------------------------- 7. topology (c): move within the feature
// box2 with a loose tolerance: only the feature rule keeps vertices in place. A vertex
// on the interface x = 1 stays on it, one on a box face stays on the face, one on a
// box edge or rim curve stays on that line (every coordinate that put it on a plane
// keeps its exact value), and each material keeps its exact volume.
TEST(SimplifyRules, VerticesMoveOnlyWithinTheirFeature) {
  const TetMesh box = read_box2();
  const SimplifyResult r = run(box, loose_params());
  ASSERT_GT(r.history.step_count(), 20u);
  // The planes of box2: x in {0, 1, 2} (1 is the interface), y and z in {0, 1}.
  auto pinned = [](int axis, double value) {
    return axis == 0 ? (value == 0 || value == 1 || value == 2) : (value == 0 || value == 1);
  };
  // At every step, the kept vertex stays on every plane its base position lies on.
  size_t interface_moves = 0;
  for (const Step& step : r.history.steps) {
    const Vec3& base = r.base.positions[step.kept];
    for (int axis = 0; axis < 3; ++axis) {
      if (!pinned(axis, base[axis])) continue;
      EXPECT_EQ(step.new_position[axis], base[axis]) << "vertex " << step.kept << " left the plane "
                                                     << "xyz"[axis] << " = " << base[axis];
    }
    interface_moves += base.x == 1 && step.new_position != step.old_position;
  }
  EXPECT_GT(interface_moves, 0u);  // interface vertices did slide within x = 1
  std::vector<uint8_t> removed;
  const std::vector<Vec3> positions = final_positions(r, &removed);
  std::vector<Vec3> alive_positions;
  for (uint32_t v = 0; v < positions.size(); ++v) {
    if (removed[v]) continue;
    alive_positions.push_back(positions[v]);
    for (int axis = 0; axis < 3; ++axis) {
      const double b = r.base.positions[v][axis];
      if (pinned(axis, b)) {
        EXPECT_EQ(positions[v][axis], b) << "vertex " << v;
      }
    }
  }
  // The replayed positions are the output's (the output keeps base id order).
  ASSERT_EQ(alive_positions.size(), r.output.vertex_count());
  for (size_t v = 0; v < alive_positions.size(); ++v)
    EXPECT_EQ(alive_positions[v], r.output.positions[v]);
  const auto before = volume_per_material(box), after = volume_per_material(r.output);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_NEAR(after.at(1), 1.0, 1e-12);
  EXPECT_NEAR(after.at(2), 1.0, 1e-12);
  EXPECT_NEAR(before.at(1), 1.0, 1e-12);
}

// ------------------------------------------------------ 8. topology (d): material regions
// Inclusions of material 2 in material 1: after every step, each region still exists
// (same material, > 0 tets), none is split or merged, every interface keeps its Euler
// characteristic, and inclusions that touch at a vertex or along an edge touch exactly
// there, without sharing a face. With the default crease angle the feature rules keep
// every planar face in place, so volumes are exact too; with 179 degrees nearly every
// vertex is a surface vertex and only the link conditions guard the topology.
void expect_regions_kept(const TetMesh& mesh, const std::string& name,
                         double crease_angle_degrees) {
  SCOPED_TRACE(name + ", crease " + std::to_string(crease_angle_degrees));
  const bool exact_volumes = crease_angle_degrees < 90;
  const std::vector<Region> before = regions_of(mesh);
  const auto euler_before = test::interface_euler(mesh);
  SimplifyParams p = loose_params();
  p.crease_angle_degrees = crease_angle_degrees;
  const SimplifyResult r = run(mesh, p);
  EXPECT_GT(r.history.step_count(), 20u);
  Lod lod(r.base, &r.history), previous(r.base, &r.history);
  for (size_t s = 1; s <= r.history.step_count(); ++s) {
    lod.seek(s);
    const TetMesh now = lod.extract();
    EXPECT_EQ(test::interface_euler(now), euler_before) << "after step " << s;
    // The step that led here satisfied the link condition in every material's region,
    // including a region that touches both ends but not the edge.
    previous.seek(s - 1);
    const Step& step = r.history.steps[s - 1];
    for (int32_t m : {1, 2}) {
      EXPECT_TRUE(link_condition_holds(previous, step.kept, step.removed,
                                       [&](uint32_t t) { return previous.materials()[t] == m; }))
          << "step " << s - 1 << ", material " << m;
    }
    const std::vector<Region> after = regions_of(now);
    ASSERT_EQ(after.size(), before.size()) << "after step " << s;
    for (size_t g = 0; g < after.size(); ++g) {
      EXPECT_EQ(after[g].material, before[g].material) << "after step " << s;
      EXPECT_GT(after[g].tets, 0u);
      if (exact_volumes) {
        EXPECT_NEAR(after[g].volume, before[g].volume, 1e-9) << "after step " << s;
      }
    }
    // Regions of material 2 share exactly the points they shared at the start.
    for (size_t g = 0; g < after.size(); ++g)
      for (size_t h = g + 1; h < after.size(); ++h) {
        if (after[g].material != 2 || after[h].material != 2) continue;
        std::vector<std::array<double, 3>> shared_before, shared_after;
        std::set_intersection(before[g].points.begin(), before[g].points.end(),
                              before[h].points.begin(), before[h].points.end(),
                              std::back_inserter(shared_before));
        std::set_intersection(after[g].points.begin(), after[g].points.end(),
                              after[h].points.begin(), after[h].points.end(),
                              std::back_inserter(shared_after));
        if (shared_before.size() <= 1) {
          EXPECT_EQ(shared_after, shared_before) << "after step " << s;
        } else {
          // Touching along a segment: its two ends stay shared, and every shared point
          // stays on it (middle vertices may slide along it or go).
          const auto& lo = shared_before.front();
          const auto& hi = shared_before.back();
          EXPECT_TRUE(std::binary_search(shared_after.begin(), shared_after.end(), lo));
          EXPECT_TRUE(std::binary_search(shared_after.begin(), shared_after.end(), hi));
          const Vec3 a{lo[0], lo[1], lo[2]}, d = Vec3{hi[0], hi[1], hi[2]} - a;
          for (const auto& q : shared_after) {
            EXPECT_EQ(squared_length(cross(Vec3{q[0], q[1], q[2]} - a, d)), 0)
                << "after step " << s;
          }
        }
      }
  }
}

TEST(SimplifyRules, MaterialRegionsNeverVanishSplitOrMerge) {
  using test::CubeBox;
  const std::vector<std::pair<std::string, TetMesh>> cases = {
      // One 2x2x2 inclusion with an interior vertex, edge vertices and face vertices.
      {"one inclusion", test::make_grid_with_inclusions(4, 4, 4, {CubeBox{{1, 1, 1}, {3, 3, 3}}})},
      // Two inclusions of material 2 separated by a wall of material 1 one cube thick.
      {"two separate inclusions",
       test::make_grid_with_inclusions(
           7, 4, 4, {CubeBox{{1, 1, 1}, {3, 3, 3}}, CubeBox{{4, 1, 1}, {6, 3, 3}}})},
      // Touching along the edge x = y = 3, 1 <= z <= 3 (which has a middle vertex).
      {"touching along an edge",
       test::make_grid_with_inclusions(
           6, 6, 4, {CubeBox{{1, 1, 1}, {3, 3, 3}}, CubeBox{{3, 3, 1}, {5, 5, 3}}})},
      // Touching at the vertex (3, 3, 3), along the grid's Kuhn diagonal ...
      {"touching at a vertex along the diagonal",
       test::make_grid_with_inclusions(
           6, 6, 6, {CubeBox{{1, 1, 1}, {3, 3, 3}}, CubeBox{{3, 3, 3}, {5, 5, 5}}})},
      // ... and across it.
      {"touching at a vertex across the diagonal",
       test::make_grid_with_inclusions(
           6, 6, 6, {CubeBox{{1, 3, 1}, {3, 5, 3}}, CubeBox{{3, 1, 3}, {5, 3, 5}}})},
      // An inclusion that reaches the outer boundary: its rim is a junction curve.
      {"touching the boundary",
       test::make_grid_with_inclusions(4, 4, 4, {CubeBox{{0, 1, 1}, {2, 3, 3}}})},
      // A bar through the box: material 1 is a solid torus (its interfaces are a
      // cylinder and an annulus-bounded box surface), which must keep its hole.
      {"a bar through the box",
       test::make_grid_with_inclusions(4, 4, 4, {CubeBox{{0, 1, 1}, {4, 3, 3}}})},
  };
  for (const auto& [name, mesh] : cases) {
    expect_regions_kept(mesh, name, 40);
    expect_regions_kept(mesh, name, 179);
  }
}

// --------------------------------------------------------------- 9. link condition
// A tube of three triangular prisms (crease angle 179 degrees, so every vertex is a
// surface vertex and only the link conditions guard topology). Collapsing an edge of
// an inner cross-section to its midpoint gives only positive tets of stretch above
// tau_ST, yet it would pinch the tube at a point: the link condition (with the virtual
// outside vertex) must reject it. After every step the region stays one piece whose
// boundary is a closed 2-manifold sphere.
void expect_closed_sphere(const TetMesh& m, size_t s) {
  std::vector<uint8_t> alive(m.tet_count(), 1);
  const std::set<Face> surface = surface_faces(m.tets, m.materials, alive);
  std::map<std::pair<uint32_t, uint32_t>, int> edge_uses;
  std::set<uint32_t> vertices;
  for (const Face& f : surface)
    for (int k = 0; k < 3; ++k) {
      vertices.insert(f[k]);
      ++edge_uses[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
    }
  for (const auto& [edge, uses] : edge_uses) EXPECT_EQ(uses, 2) << "after step " << s;
  const long euler = static_cast<long>(vertices.size()) - static_cast<long>(edge_uses.size()) +
                     static_cast<long>(surface.size());
  EXPECT_EQ(euler, 2) << "after step " << s;
  // Every vertex's boundary triangles form one fan (no pinch point).
  for (uint32_t v : vertices) {
    std::vector<Face> fan;
    for (const Face& f : surface)
      if (f[0] == v || f[1] == v || f[2] == v) fan.push_back(f);
    std::vector<uint8_t> reached(fan.size(), 0);
    std::vector<size_t> stack{0};
    reached[0] = 1;
    size_t count = 1;
    while (!stack.empty()) {
      const size_t a = stack.back();
      stack.pop_back();
      for (size_t b = 0; b < fan.size(); ++b) {
        if (reached[b]) continue;
        int common = 0;
        for (uint32_t x : fan[a])
          common += x != v && (fan[b][0] == x || fan[b][1] == x || fan[b][2] == x);
        if (common > 0) reached[b] = 1, ++count, stack.push_back(b);
      }
    }
    EXPECT_EQ(count, fan.size()) << "vertex " << v << " pinched after step " << s;
  }
  int regions = 0;
  test::region_labels(m, &regions);
  EXPECT_EQ(regions, 1) << "after step " << s;
}

TEST(SimplifyRules, LinkConditionRejectsPinchingATube) {
  const TetMesh tube = test::make_prism_tube(3, 1.0);
  SimplifyParams p = loose_params();
  p.crease_angle_degrees = 179;
  const std::vector<FeatureKind> input_kind = kinds_of(tube, p.crease_angle_degrees);
  for (FeatureKind k : input_kind) ASSERT_EQ(k, FeatureKind::kSurface);
  // Geometry alone would allow the pinch: collapse (a1, b1) = (3, 4) to its midpoint.
  {
    const Vec3 m = (tube.positions[3] + tube.positions[4]) * 0.5;
    size_t survivors = 0;
    for (const Tet& t : tube.tets) {
      const bool has3 = tet_has(t, 3), has4 = tet_has(t, 4);
      if (has3 == has4) continue;  // removed with the edge, or untouched
      Vec3 q[4];
      for (int c = 0; c < 4; ++c) q[c] = t[c] == 3 || t[c] == 4 ? m : tube.positions[t[c]];
      EXPECT_GT(tet_shape(q[0], q[1], q[2], q[3]).stretch, p.min_stretch);
      EXPECT_LT(tet_shape(q[0], q[1], q[2], q[3]).size, p.sizing.uniform);
      ++survivors;
    }
    ASSERT_EQ(survivors, 2u);
  }
  const SimplifyResult r = run(tube, p);
  EXPECT_GT(r.history.step_count(), 3u);
  EXPECT_GT(r.rejections.topology, 0u);
  // Every step satisfies the link condition, checked from its definition.
  for_each_step(r, [&](size_t s, const Step& step, const Lod& lod) {
    EXPECT_TRUE(link_condition_holds(lod, step.kept, step.removed, [](uint32_t) { return true; }))
        << "step " << s << " (" << step.kept << ", " << step.removed << ")";
  });
  Lod lod(r.base, &r.history);
  for (size_t s = 0; s <= r.history.step_count(); ++s) {
    lod.seek(s);
    expect_closed_sphere(lod.extract(), s);
  }
}

// Three tets around an edge: collapsing (i, j) would make (i x y z) and (j x y z) the
// same tet. It is never done, and no two output tets share their vertex set.
TEST(SimplifyRules, CollapseThatWouldDuplicateATetIsRejected) {
  const TetMesh mesh = test::make_three_tets_around_an_edge();
  SimplifyParams p = loose_params();
  p.crease_angle_degrees = 179;
  const SimplifyResult r = run(mesh, p);
  EXPECT_GT(r.rejections.stretch + r.rejections.topology, 0u);
  const std::array<double, 3> i = key(mesh.positions[0]), j = key(mesh.positions[1]);
  for (const Step& step : r.history.steps) {
    const auto a = key(r.base.positions[step.kept]), b = key(r.base.positions[step.removed]);
    EXPECT_FALSE((a == i && b == j) || (a == j && b == i));
  }
  std::set<std::array<uint32_t, 4>> seen;
  for (const Tet& t : r.output.tets) {
    std::array<uint32_t, 4> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_TRUE(seen.insert(sorted).second);
    EXPECT_GT(signed_volume6(r.output, t), 0);
  }
  EXPECT_GE(r.output.tet_count(), 1u);
}

// ------------------------------------------------------------- 10. candidate order
// Ends of different dimension: the more constrained end is kept, in place. Ends both
// interior: the midpoint whenever it is valid (every tet around it keeps d_t >= tau_ST
// and s_t <= tau_SZ; interior quadrics are zero), kept under the smaller id; else an
// end, in place.
TEST(SimplifyRules, CandidatePositionsFollowThePaperOrder) {
  const TetMesh grid = test::make_jittered_grid(4, 0.15);
  SimplifyParams p = loose_params();
  p.min_stretch = 0.2;
  const SimplifyResult r = run(grid, p);
  const std::vector<FeatureKind> kind = kinds_of(r.base, p.crease_angle_degrees);
  size_t mixed = 0, interior_to_surface = 0, midpoints = 0;
  for_each_step(r, [&](size_t s, const Step& step, const Lod& lod) {
    const FeatureKind kk = kind[step.kept], kr = kind[step.removed];
    const Vec3& kept_at = lod.positions()[step.kept];
    const Vec3& removed_at = lod.positions()[step.removed];
    ASSERT_EQ(step.old_position, kept_at);
    if (kk != kr) {
      ++mixed;
      interior_to_surface += kr == FeatureKind::kInterior && kk == FeatureKind::kSurface;
      EXPECT_LT(kk, kr) << "step " << s << " kept the less constrained end";
      EXPECT_EQ(step.new_position, kept_at) << "step " << s << " moved the constrained end";
      return;
    }
    if (kk != FeatureKind::kInterior) return;
    const Vec3 mid = (kept_at + removed_at) * 0.5;
    bool mid_valid = true;
    for (uint32_t v : {step.kept, step.removed}) {
      const uint32_t other = v == step.kept ? step.removed : step.kept;
      for (uint32_t t : alive_star(lod, v)) {
        const Tet& q = lod.tets()[t];
        if (tet_has(q, other)) continue;
        Vec3 c[4];
        for (int k = 0; k < 4; ++k) c[k] = q[k] == v ? mid : lod.positions()[q[k]];
        const TetShape shape = tet_shape(c[0], c[1], c[2], c[3]);
        if (!(shape.stretch >= p.min_stretch) || shape.size > p.sizing.uniform) mid_valid = false;
      }
    }
    if (mid_valid) {
      ++midpoints;
      EXPECT_EQ(step.new_position, mid) << "step " << s << ": valid midpoint not taken";
      EXPECT_LT(step.kept, step.removed) << "step " << s;
    } else {
      EXPECT_EQ(step.new_position, kept_at) << "step " << s << ": neither midpoint nor end";
    }
  });
  EXPECT_GT(interior_to_surface, 0u);
  EXPECT_GT(mixed, interior_to_surface);  // surface into curve, curve into corner, ...
  EXPECT_GT(midpoints, 0u);
}

// ------------------------------------------------------------ 11. target_elements
// target_elements = T stops right after the first step that leaves at most T tets; the
// steps done are those of the unlimited run, in the same order.
TEST(SimplifyRules, TargetElementsStopsAtTheFirstStepWithinIt) {
  const TetMesh box = read_box2();
  SimplifyParams p = loose_params();
  const SimplifyResult full = run(box, p);
  const size_t n = full.history.step_count();
  ASSERT_GT(n, 20u);
  const Lod lod(full.base, &full.history);
  for (size_t s = 1; s <= n; ++s) ASSERT_LT(lod.tet_count_at(s), lod.tet_count_at(s - 1));
  const size_t final_count = lod.tet_count_at(n);

  for (const size_t stop : {size_t{1}, n / 3, n / 2, n - 1}) {
    // A target equal to the count after `stop` steps, and one just above it.
    for (const size_t target : {lod.tet_count_at(stop), lod.tet_count_at(stop) + 1}) {
      if (target >= lod.tet_count_at(stop - 1)) continue;
      p.target_elements = target;
      const SimplifyResult r = run(box, p);
      ASSERT_EQ(r.history.step_count(), stop) << "target " << target;
      EXPECT_EQ(r.output.tet_count(), lod.tet_count_at(stop));
      EXPECT_LE(r.output.tet_count(), target);
      for (size_t s = 0; s < stop; ++s) {
        EXPECT_EQ(r.history.steps[s].kept, full.history.steps[s].kept);
        EXPECT_EQ(r.history.steps[s].removed, full.history.steps[s].removed);
        EXPECT_EQ(r.history.steps[s].new_position, full.history.steps[s].new_position);
      }
    }
  }
  p.target_elements = box.tet_count();  // already within: nothing to do
  EXPECT_EQ(run(box, p).history.step_count(), 0u);
  p.target_elements = final_count > 1 ? final_count - 1 : 1;  // out of reach: run to the end
  EXPECT_EQ(run(box, p).history.step_count(), n);
}

}  // namespace
}  // namespace tetlod
