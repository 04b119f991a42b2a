// libFuzzer target for the simplifier: the first 8 bytes choose the thresholds (size
// relative to the mesh's bounding box, stretch, valence, tolerance, subdivision, a
// size field, an element target), the rest is a Medit mesh. Whatever the reader and
// the validation accept, the pipeline must not crash or hang, and must keep its
// guarantee: every output tet positively oriented, no threshold broken by anything the
// run made (violations.created == 0), and the history replaying to the output and back
// to the subdivided base exactly, with deltas that say everything a seek changed, and
// the output passing validation as a file read back would (no overlapping tets) when
// the subdivided base does, and no boundary faces of two bodies meshed apart crossing
// where none of the base's do.
// Per material the same number of regions, per material pair the same interface Euler
// characteristic (tests/core/topology_checks.h), after subdivision and at the end.
// Then `--improve` on the output must keep its own guarantee: positive tets, no more
// tets or nodes over a threshold than before, the same vertices, and the same boundary
// and interface triangles.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string_view>
#include <vector>

#include "core/adjacency.h"
#include "core/improve.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/metrics.h"
#include "core/overlap.h"
#include "core/simplify.h"
#include "core/surface.h"
#include "core/topology_checks.h"  // tests/
#include "core/triangle_cross.h"
#include "core/validate.h"

// A failed check: a crash for libFuzzer; tests/core/test_fuzz_seeds.cpp, which runs
// this harness on the seeds, defines it to throw instead.
#ifndef TETLOD_FUZZ_FAIL
#define TETLOD_FUZZ_FAIL() __builtin_trap()
#endif
// Called when every check ran (the test counts them).
#ifndef TETLOD_FUZZ_CHECKED
#define TETLOD_FUZZ_CHECKED()
#endif

namespace {

void check_mesh(const tetlod::TetMesh& mesh) {
  if (mesh.materials.size() != mesh.tets.size()) TETLOD_FUZZ_FAIL();
  for (const tetlod::Tet& t : mesh.tets) {
    for (uint32_t v : t)
      if (v >= mesh.vertex_count()) TETLOD_FUZZ_FAIL();
    if (!(tetlod::signed_volume6(mesh, t) > 0)) TETLOD_FUZZ_FAIL();
  }
}

// The boundary and interface triangles as sorted vertex triples with their materials,
// sorted: equal for two meshes with the same surface, whatever their tets.
std::vector<std::array<int64_t, 5>> surface_of(const tetlod::TetMesh& mesh) {
  // Also a check of its own: no face shared by three tets, no two tets overlapping.
  std::vector<uint32_t> neighbors;
  if (tetlod::build_face_neighbors(mesh, &neighbors).kind != tetlod::FaceProblem::Kind::kNone)
    TETLOD_FUZZ_FAIL();
  std::vector<std::array<int64_t, 5>> out;
  for (const tetlod::SurfaceTriangle& t : tetlod::extract_surface(mesh, neighbors)) {
    std::array<uint32_t, 3> v = t.v;
    std::sort(v.begin(), v.end());
    out.push_back({v[0], v[1], v[2], t.inner, t.outer});
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::map<int32_t, int> regions_per_material(const tetlod::TetMesh& mesh) {
  int region_count = 0;
  const std::vector<int> label = tetlod::test::region_labels(mesh, &region_count);
  std::vector<int32_t> material_of(region_count);
  for (size_t t = 0; t < mesh.tet_count(); ++t) material_of[label[t]] = mesh.materials[t];
  std::map<int32_t, int> count;
  for (int32_t m : material_of) ++count[m];
  return count;
}

// Whether boundary faces of two different pieces (bodies meshed apart, which the
// reader lets cross) clearly cross: a sweep along x over the faces' boxes.
bool pieces_cross(const tetlod::TetMesh& mesh) {
  std::vector<uint32_t> neighbors;
  if (tetlod::build_face_neighbors(mesh, &neighbors).kind != tetlod::FaceProblem::Kind::kNone)
    TETLOD_FUZZ_FAIL();
  const std::vector<uint32_t> piece = tetlod::vertex_pieces(mesh);
  struct Face {
    tetlod::Triangle3 t;
    tetlod::Vec3 lo, hi;
    uint32_t piece;
  };
  std::vector<Face> faces;
  for (const tetlod::SurfaceTriangle& s : tetlod::extract_surface(mesh, neighbors)) {
    if (s.outer != tetlod::kOutsideMaterial) continue;
    Face f{{mesh.positions[s.v[0]], mesh.positions[s.v[1]], mesh.positions[s.v[2]]},
           {},
           {},
           piece[s.v[0]]};
    f.lo = f.hi = f.t[0];
    for (const tetlod::Vec3& x : f.t) {
      for (int a = 0; a < 3; ++a)
        f.lo[a] = std::min(f.lo[a], x[a]), f.hi[a] = std::max(f.hi[a], x[a]);
    }
    faces.push_back(f);
  }
  std::sort(faces.begin(), faces.end(),
            [](const Face& a, const Face& b) { return a.lo.x < b.lo.x; });
  for (size_t i = 0; i < faces.size(); ++i) {
    const Face& a = faces[i];
    for (size_t j = i + 1; j < faces.size() && faces[j].lo.x <= a.hi.x; ++j) {
      const Face& b = faces[j];
      if (a.piece == b.piece || b.lo.y > a.hi.y || a.lo.y > b.hi.y || b.lo.z > a.hi.z ||
          a.lo.z > b.hi.z)
        continue;
      if (tetlod::triangles_cross(a.t, tetlod::plane_of(a.t), b.t, tetlod::plane_of(b.t)))
        return true;
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  constexpr size_t kParamBytes = 8;
  if (size < kParamBytes) return 0;
  const uint8_t* p = data;
  const std::string_view text(reinterpret_cast<const char*>(data + kParamBytes),
                              size - kParamBytes);
  tetlod::TetMesh mesh;
  if (!tetlod::read_mesh_from_memory(text, tetlod::MeshFormat::kMedit, "fuzz", &mesh, nullptr).ok())
    return 0;
  if (mesh.tet_count() > 4000) return 0;  // small meshes: many runs a second
  tetlod::Vec3 low = mesh.positions[0], high = low;
  for (const tetlod::Vec3& q : mesh.positions) {
    low = {std::min(low.x, q.x), std::min(low.y, q.y), std::min(low.z, q.z)};
    high = {std::max(high.x, q.x), std::max(high.y, q.y), std::max(high.z, q.z)};
  }
  const double diagonal = tetlod::length(high - low);

  tetlod::SimplifyParams params;
  // Size from a fifth of the diagonal to twice it; with subdivision at the small end,
  // the run stays within a few thousand tets for the meshes above.
  params.sizing.uniform = diagonal * (0.2 + 1.8 * p[0] / 255.0);
  params.min_stretch = 0.01 + 0.9 * p[1] / 255.0;
  params.max_valence = 4 + p[2] % 40;
  params.tolerance = diagonal * std::pow(10.0, -(p[3] % 8));
  params.subdivide = (p[4] & 1) != 0;
  if (p[4] & 2) {  // a radial field around the box's centre
    tetlod::SizingField::Radial r;
    r.center = (low + high) * 0.5;
    r.size0 = params.sizing.uniform * (0.25 + p[5] / 255.0);
    r.growth = (p[5] & 15) / 8.0;
    params.sizing.radial.push_back(r);
  }
  if (p[4] & 4) {  // a smaller size for material 1
    params.sizing.material_sizes.push_back({1, params.sizing.uniform * 0.5});
  }
  params.target_elements = (p[4] & 8) ? p[6] : 0;
  params.crease_angle_degrees = 10 + p[7] % 170;
  if (!tetlod::check_params(params).ok()) TETLOD_FUZZ_FAIL();  // chosen valid above

  tetlod::SimplifyResult result;
  if (!tetlod::simplify(mesh, params, &result).ok()) return 0;  // e.g. too many tets
  check_mesh(result.base);
  check_mesh(result.output);
  // The output reads back: validation, which refuses overlapping tets too, accepts it
  // if it accepts the subdivided base. (The input passed it, but the crossing test
  // allows 1e-8 of the faces' size: faces that touch within that, or cross by less,
  // may clearly cross once subdivision halved them. The simplifier never pushes the
  // boundary through itself; it does not undo such a crossing.)
  tetlod::TetMesh reread = result.base;
  tetlod::ValidationReport report;
  if (tetlod::validate_mesh(&reread, "base", {}, &report).ok()) {
    reread = result.output;
    if (!tetlod::validate_mesh(&reread, "output", {}, &report).ok()) TETLOD_FUZZ_FAIL();
  }
  if (!pieces_cross(result.base) && pieces_cross(result.output)) TETLOD_FUZZ_FAIL();
  if (result.violations.created != 0) TETLOD_FUZZ_FAIL();
  if (regions_per_material(result.output) != regions_per_material(result.base) ||
      tetlod::test::interface_euler(result.output) != tetlod::test::interface_euler(result.base))
    TETLOD_FUZZ_FAIL();
  tetlod::Lod lod(result.base, &result.history);
  lod.seek(lod.step_count());
  const tetlod::TetMesh last = lod.extract();
  if (last.tets != result.output.tets || last.positions != result.output.positions ||
      last.materials != result.output.materials)
    TETLOD_FUZZ_FAIL();
  lod.seek(0);
  if (lod.tets() != result.base.tets || lod.positions() != result.base.positions)
    TETLOD_FUZZ_FAIL();
  // Seeks with a delta, as the renderer makes them: the delta must say every tet that
  // appeared, vanished, or changed its corners or their positions.
  uint64_t state = size * 0x9E3779B97F4A7C15ull;
  for (int k = 0; k < 8; ++k) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const size_t step = (state >> 33) % (lod.step_count() + 1);
    const std::vector<uint8_t> alive = lod.alive();
    const std::vector<tetlod::Tet> tets = lod.tets();
    const std::vector<tetlod::Vec3> positions = lod.positions();
    tetlod::LodDelta delta;
    lod.seek(step, &delta);
    std::vector<uint8_t> expected = alive, reported(alive.size(), 0);
    for (uint32_t t : delta.vanished) {
      if (!expected[t]) TETLOD_FUZZ_FAIL();
      expected[t] = 0;
    }
    for (uint32_t t : delta.appeared) {
      if (expected[t]) TETLOD_FUZZ_FAIL();
      expected[t] = 1, reported[t] = 1;
    }
    for (uint32_t t : delta.changed) reported[t] = 1;
    if (expected != lod.alive()) TETLOD_FUZZ_FAIL();
    for (size_t t = 0; t < tets.size(); ++t) {
      if (!lod.alive()[t] || reported[t]) continue;
      if (lod.tets()[t] != tets[t]) TETLOD_FUZZ_FAIL();
      for (uint32_t v : tets[t])
        if (!(lod.positions()[v] == positions[v])) TETLOD_FUZZ_FAIL();
    }
  }

  tetlod::TetMesh improved = result.output;
  const tetlod::ImproveResult ir = tetlod::improve_mesh(&improved, params);
  check_mesh(improved);
  if (improved.positions.size() != result.output.positions.size()) TETLOD_FUZZ_FAIL();
  if (ir.breaks_after.below_stretch > ir.breaks_before.below_stretch ||
      ir.breaks_after.above_size > ir.breaks_before.above_size ||
      ir.breaks_after.above_valence > ir.breaks_before.above_valence)
    TETLOD_FUZZ_FAIL();
  if (surface_of(improved) != surface_of(result.output)) TETLOD_FUZZ_FAIL();
  TETLOD_FUZZ_CHECKED();
  return 0;
}
