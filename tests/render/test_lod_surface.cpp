// The incremental LOD surface equals a full rebuild at every step it is moved to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/simplify.h"
#include "core/test_meshes.h"
#include "render/lod_surface.h"
#include "render/snapshot.h"

namespace tetlod::render {
namespace {

// A triangle as comparable values: its corners rotated so the smallest comes
// first (keeping the orientation), its stretch and material.
using CanonicalTriangle = std::tuple<std::array<float, 9>, float, uint32_t>;

std::vector<CanonicalTriangle> canonical(const std::vector<SurfaceVertex>& vertices) {
  std::vector<CanonicalTriangle> out;
  for (size_t t = 0; t + 2 < vertices.size(); t += 3) {
    std::array<std::array<float, 3>, 3> p;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) p[k][c] = vertices[t + k].position[c];
    const int first = int(std::min_element(p.begin(), p.end()) - p.begin());
    std::array<float, 9> corners;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) corners[k * 3 + c] = p[(first + k) % 3][c];
    out.emplace_back(corners, vertices[t].stretch, vertices[t].material);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Highlighted tets as sorted sets of their 4 canonical faces.
std::vector<std::vector<CanonicalTriangle>> canonical_tets(
    const std::vector<SurfaceVertex>& vertices) {
  std::vector<std::vector<CanonicalTriangle>> out;
  for (size_t t = 0; t + 11 < vertices.size(); t += 12)
    out.push_back(
        canonical({vertices.begin() + ptrdiff_t(t), vertices.begin() + ptrdiff_t(t + 12)}));
  std::sort(out.begin(), out.end());
  return out;
}

const SimplifyResult& simplified_box2() {
  static const SimplifyResult result = [] {
    TetMesh mesh;
    ReadInfo info;
    EXPECT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh, &info).ok());
    SimplifyParams params;
    params.sizing.uniform = 0.6;
    params.tolerance = 0.01;
    SimplifyResult r;
    const Status s = simplify(mesh, params, &r);
    EXPECT_TRUE(s.ok()) << s.message();
    return r;
  }();
  return result;
}

// `by_size`: the full build coloured by the tets' sizes (render --color size).
void expect_same_as_full_build(const Lod& lod, const LodSurface& surface,
                               const SurfaceFilter& filter, const std::string& where,
                               bool by_size = false) {
  const PreparedMesh level = prepare_mesh(lod.extract());
  SurfaceBuffers full;
  SurfaceInput input = level.surface_input();
  if (by_size) input.values = level.size.data();
  build_surface(input, filter, &full);
  ASSERT_EQ(surface.triangles().size(), full.triangles.size()) << where;
  EXPECT_TRUE(canonical(surface.triangles()) == canonical(full.triangles)) << where;
  EXPECT_EQ(surface.visible_tets(), full.visible_tets) << where;
  EXPECT_EQ(surface.highlighted_tets(), full.highlighted_tets) << where;
  EXPECT_TRUE(canonical_tets(surface.highlight()) == canonical_tets(full.highlight)) << where;
}

void walk_history(const SurfaceFilter& filter) {
  const SimplifyResult& r = simplified_box2();
  ASSERT_GT(r.history.step_count(), 50u);
  Lod lod(r.base, &r.history);
  LodSurface surface;
  const LodState state = lod_state(lod);
  surface.reset(state, filter);
  expect_same_as_full_build(lod, surface, filter, "step 0");
  std::mt19937 random(7);
  LodDelta delta;
  std::vector<size_t> targets = {lod.step_count(), 0, lod.step_count() / 2, lod.step_count()};
  for (int i = 0; i < 12; ++i) targets.push_back(random() % (lod.step_count() + 1));
  for (int i = 0; i < 10; ++i) targets.push_back(std::min(lod.step_count(), lod.step() + 1 + i));
  for (const size_t target : targets) {
    lod.seek(target, &delta);
    surface.update(state, delta);
    expect_same_as_full_build(lod, surface, filter, "step " + std::to_string(target));
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(LodSurface, MatchesAFullRebuildAtEveryStep) {
  walk_history({});
}

TEST(LodSurface, MatchesWithAHiddenMaterialCutAndHighlight) {
  SurfaceFilter filter;
  filter.hidden_materials = {2};
  filter.cut = true;
  filter.cut_plane = {{0, 0.6, 0.8}, 0.5};
  filter.highlight = true;
  filter.highlight_below = 0.35;
  walk_history(filter);
}

// reset() puts the faces into its table in batches of 2^19 (a grid of 162,000 tets
// takes two), and a mesh of no shared faces (needles touching at one point: 4 faces a
// tet, the table sized for about 2.25) grows the table between batches (filled in part
// order past the point where it grows, its first parts overflowed into long probe runs:
// 7 s here): both draw what a full build draws.
TEST(LodSurface, ResetsInBatchesAndGrowsItsTableBetweenThem) {
  const CollapseHistory none;
  const TetMesh grid = test::make_grid_mesh(
      30, 30, 30, [](int i, int j, int) { return i < 15   ? 1
                                                 : j < 10 ? 2
                                                          : 3; }, 0.1);
  ASSERT_GT(4 * grid.tet_count(), size_t(1) << 19);
  for (const TetMesh& mesh : {grid, test::make_needle_star(140000, 5)}) {
    const Lod lod(mesh, &none);
    const LodState state = lod_state(lod);
    LodSurface surface;
    SurfaceFilter filter;
    surface.reset(state, filter);
    expect_same_as_full_build(lod, surface, filter, std::to_string(mesh.tet_count()) + " tets");
    filter.hidden_materials = {2};
    filter.highlight = true;
    filter.highlight_below = 0.5;
    surface.reset(state, filter);
    expect_same_as_full_build(lod, surface, filter,
                              std::to_string(mesh.tet_count()) + " tets, filtered");
  }
}

size_t vertex_count(const std::vector<DirtyRange>& ranges) {
  size_t n = 0;
  for (const DirtyRange& r : ranges) n += r.end - r.begin;
  return n;
}

TEST(LodSurface, DirtyRangesCoverOnlyWhatChanged) {
  const SimplifyResult& r = simplified_box2();
  Lod lod(r.base, &r.history);
  LodSurface surface;
  const LodState state = lod_state(lod);
  surface.reset(state, {});
  const std::vector<DirtyRange> all = surface.take_triangle_dirty();
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].begin, 0u);
  EXPECT_EQ(all[0].end, surface.triangles().size());
  EXPECT_TRUE(surface.take_triangle_dirty().empty());
  // A collapse touches a handful of faces, not the whole buffer; applying the dirty
  // ranges to a copy of the old array reproduces the new one.
  std::vector<SurfaceVertex> mirror = surface.triangles();
  LodDelta delta;
  size_t touched = 0;
  const size_t steps = std::min<size_t>(40, lod.step_count());
  for (size_t s = 1; s <= steps; ++s) {
    lod.seek(s, &delta);
    surface.update(state, delta);
    const std::vector<DirtyRange> dirty = surface.take_triangle_dirty();
    touched += vertex_count(dirty);
    mirror.resize(surface.triangles().size());
    for (const DirtyRange& d : dirty)
      std::copy(surface.triangles().begin() + std::ptrdiff_t(d.begin),
                surface.triangles().begin() + std::ptrdiff_t(d.end),
                mirror.begin() + std::ptrdiff_t(d.begin));
    EXPECT_TRUE(canonical(mirror) == canonical(surface.triangles())) << "step " << s;
  }
  EXPECT_LT(touched / steps, 60u) << "vertices sent per step, of " << surface.triangles().size();
}

// Per-tet values (|E| in the viewer) replace the stretch of exactly the faces of
// their tets, are dropped by the next update (they belong to one state), and
// clearing them restores the stretch-coloured buffer bit for bit.
TEST(LodSurface, TetValuesRecolourTheDrawnFacesUntilTheLevelChanges) {
  const SimplifyResult& r = simplified_box2();
  Lod lod(r.base, &r.history);
  lod.seek(lod.step_count() / 2);
  LodSurface surface;
  const LodState state = lod_state(lod);
  surface.reset(state, {});
  const std::vector<SurfaceVertex> by_stretch = surface.triangles();
  (void)surface.take_triangle_dirty();

  // Value of tet t: 1000 + t, so every face tells which tet it came from.
  std::vector<float> values(lod.tets().size());
  for (size_t t = 0; t < values.size(); ++t) values[t] = 1000.0f + float(t);
  surface.set_tet_values(values);
  EXPECT_TRUE(surface.has_tet_values());
  const std::vector<DirtyRange> dirty = surface.take_triangle_dirty();
  ASSERT_EQ(dirty.size(), 1u);
  EXPECT_EQ(dirty[0].end - dirty[0].begin, surface.triangles().size());
  ASSERT_EQ(surface.triangles().size(), by_stretch.size());
  for (size_t i = 0; i < by_stretch.size(); ++i) {
    const SurfaceVertex& v = surface.triangles()[i];
    const float tet = v.stretch - 1000.0f;
    ASSERT_GE(tet, 0.0f);
    ASSERT_LT(tet, float(values.size()));
    EXPECT_TRUE(lod.alive()[size_t(tet)]);
    EXPECT_EQ(lod.materials()[size_t(tet)], int32_t(v.material));
    EXPECT_EQ(std::memcmp(v.position, by_stretch[i].position, sizeof(v.position)), 0);
  }

  surface.clear_tet_values();
  EXPECT_FALSE(surface.has_tet_values());
  EXPECT_EQ(std::memcmp(surface.triangles().data(), by_stretch.data(),
                        by_stretch.size() * sizeof(SurfaceVertex)),
            0);

  // An update drops the values before it changes anything: the result is the same
  // as a full rebuild (stretch-coloured).
  surface.set_tet_values(values);
  LodDelta delta;
  lod.seek(lod.step() + 5, &delta);
  surface.update(state, delta);
  EXPECT_FALSE(surface.has_tet_values());
  expect_same_as_full_build(lod, surface, {}, "after an update with values set");
}

// Coloured by size, every drawn face carries its tet's longest edge through seeks and
// resets, as a full build with the sizes as its values; back to stretch, as before.
TEST(LodSurface, ColoursBySizeThroughSeeksAndResets) {
  const SimplifyResult& r = simplified_box2();
  Lod lod(r.base, &r.history);
  LodSurface surface;
  const LodState state = lod_state(lod);
  surface.reset(state, {});
  (void)surface.take_triangle_dirty();
  surface.set_color_by_size(true);
  EXPECT_TRUE(surface.color_by_size());
  const std::vector<DirtyRange> dirty = surface.take_triangle_dirty();
  ASSERT_EQ(dirty.size(), 1u);
  EXPECT_EQ(dirty[0].end - dirty[0].begin, surface.triangles().size());
  expect_same_as_full_build(lod, surface, {}, "sizes at step 0", true);
  LodDelta delta;
  for (const size_t target : {lod.step_count(), size_t{0}, lod.step_count() / 3}) {
    lod.seek(target, &delta);
    surface.update(state, delta);
    expect_same_as_full_build(lod, surface, {}, "sizes at step " + std::to_string(target), true);
  }
  SurfaceFilter filter;
  filter.hidden_materials = {1};
  surface.reset(state, filter);
  expect_same_as_full_build(lod, surface, filter, "sizes after a reset", true);
  surface.set_color_by_size(false);
  expect_same_as_full_build(lod, surface, filter, "stretch again");
}

// The ray through a pixel meets the point drawn at that pixel: pixel_ray() inverts
// projection_matrix() * view_matrix().
TEST(LodSurface, PixelRayInvertsTheProjection) {
  Camera camera = frame_camera({0, 0, 0}, {2, 1, 1}, ViewDirection::kIso);
  // Also with a lens shift (render::frame_picture()'s).
  for (const auto& [width, height, shift_x, shift_y] :
       {std::tuple{640, 480, 0.0, 0.0}, std::tuple{300, 500, 0.0, 0.0},
        std::tuple{640, 480, 0.3, -0.2}}) {
    camera.shift_x = shift_x;
    camera.shift_y = shift_y;
    const Mat4 m = multiply(projection_matrix(camera, double(width) / height), view_matrix(camera));
    for (const Vec3& p : {Vec3{0.3, 0.2, 0.9}, Vec3{1.7, 0.8, 0.1}, Vec3{1, 0.5, 0.5}}) {
      const double clip[4] = {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
                              m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13], 0,
                              m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15]};
      const double px = (clip[0] / clip[3] + 1) / 2 * width;
      const double py = (1 - clip[1] / clip[3]) / 2 * height;
      const Ray ray = pixel_ray(camera, px, py, width, height);
      EXPECT_NEAR(length(ray.direction), 1, 1e-12);
      const Vec3 to = p - ray.origin;
      const Vec3 off = to - ray.direction * dot(to, ray.direction);  // p's distance from it
      EXPECT_LT(length(off), 1e-5 * length(to)) << width << "x" << height;
    }
  }
}

// The nearest hit of a ray with a face of one tet, or infinity.
double ray_tet(const Ray& ray, const Vec3 (&p)[4]) {
  double best = std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < 4; ++corner) {
    const Vec3& a = p[kTetFace[corner][0]];
    const Vec3 e1 = p[kTetFace[corner][1]] - a, e2 = p[kTetFace[corner][2]] - a;
    const Vec3 n = cross(e1, e2);
    const double den = dot(n, ray.direction);
    if (den == 0) continue;
    const double t = dot(n, a - ray.origin) / den;
    const Vec3 x = ray.origin + ray.direction * t - a;
    // Barycentric coordinates of x in the face.
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const double b1 = dot(x, e1), b2 = dot(x, e2), det = d11 * d22 - d12 * d12;
    const double u = (d22 * b1 - d12 * b2) / det, w = (d11 * b2 - d12 * b1) / det;
    if (t > 0 && u >= 0 && w >= 0 && u + w <= 1) best = std::min(best, t);
  }
  return best;
}

// The tet under a pixel: pick() is the visible tet a brute-force ray cast through
// every tet meets first, under a hidden material and a cut, at several levels.
TEST(LodSurface, PickFindsTheFirstVisibleTetOnTheRay) {
  const SimplifyResult& r = simplified_box2();
  Lod lod(r.base, &r.history);
  const LodState state = lod_state(lod);
  SurfaceFilter filter;
  filter.hidden_materials = {2};
  filter.cut = true;
  filter.cut_plane = {{0, 0.6, 0.8}, 0.6};
  std::mt19937 random(11);
  int hits = 0, misses = 0;
  LodDelta delta;
  for (const size_t target : {size_t{0}, lod.step_count() / 2, lod.step_count()}) {
    lod.seek(target, &delta);
    for (const bool filtered : {false, true}) {
      LodSurface surface;
      surface.reset(state, filtered ? filter : SurfaceFilter{});
      const Camera camera = frame_camera({0, 0, 0}, {2, 1, 1}, ViewDirection::kIso);
      for (int i = 0; i < 300; ++i) {
        const Ray ray = pixel_ray(camera, random() % 400 + 0.5, random() % 300 + 0.5, 400, 300);
        double best = std::numeric_limits<double>::infinity(), second = best;
        uint32_t best_tet = kInvalidIndex;
        for (uint32_t t = 0; t < lod.tets().size(); ++t) {
          if (!lod.alive()[t]) continue;
          const Tet& c = lod.tets()[t];
          const Vec3 p[4] = {lod.positions()[c[0]], lod.positions()[c[1]], lod.positions()[c[2]],
                             lod.positions()[c[3]]};
          if (filtered) {
            const Vec3 centroid = 0.25 * (p[0] + p[1] + p[2] + p[3]);
            if (lod.materials()[t] == 2 ||
                dot(filter.cut_plane.normal, centroid) > filter.cut_plane.offset)
              continue;
          }
          const double hit = ray_tet(ray, p);
          if (hit < best) {
            second = best;
            best = hit;
            best_tet = t;
          } else {
            second = std::min(second, hit);
          }
        }
        const LodSurface::Pick pick = surface.pick(ray);
        if (best_tet == kInvalidIndex) {
          EXPECT_EQ(pick.tet, kInvalidIndex);
          ++misses;
          continue;
        }
        ++hits;
        EXPECT_NEAR(pick.distance, best, 1e-5 * best);
        // Through a shared edge or corner two tets are first: either will do.
        if (second - best > 1e-4 * best) {
          EXPECT_EQ(pick.tet, best_tet) << "step " << target;
        }
      }
    }
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 100);
}

}  // namespace
}  // namespace tetlod::render
