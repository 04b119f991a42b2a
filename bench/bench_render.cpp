// Renderer benchmark: full rebuild of the GPU buffers (surface extraction on the CPU
// + upload) for common views of a mesh, plus one draw, on the offscreen context.
//
//   bench_render FILE [--repeat N] [--hide M] [--lod SIZE]
//
// With --lod, the mesh is simplified to SIZE (tolerance 0.05) and LodSurface's
// incremental updates are timed against full rebuilds while moving through the
// collapse history.
//
// "prepare" (face neighbours + stretch per tet) runs once per mesh or topology
// change; a rebuild (new cut, hidden materials, highlight threshold) is
// build_surface + upload.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/simplify.h"
#include "render/gl_context.h"
#include "render/lod_surface.h"
#include "render/renderer.h"
#include "render/snapshot.h"

using tetlod::bench::Clock;
using tetlod::bench::median;
using tetlod::bench::seconds_since;

int main(int argc, char** argv) {
  using namespace tetlod;
  using namespace tetlod::render;
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_render FILE [--repeat N] [--hide M]\n");
    return 2;
  }
  int repeat = 5;
  int32_t hide = 1;
  double lod_size = 0;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--repeat") repeat = std::max(1, std::atoi(argv[i + 1]));
    if (flag == "--hide") hide = std::atoi(argv[i + 1]);
    if (flag == "--lod") lod_size = std::atof(argv[i + 1]);
  }
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh(argv[1], &mesh, &info);
  if (!s) {
    std::fprintf(stderr, "bench_render: %s\n", s.message().c_str());
    return 1;
  }
  std::string error;
  auto context = create_offscreen_context(&error);
  if (!context) {
    std::fprintf(stderr, "bench_render: %s\n", error.c_str());
    return 1;
  }
  Renderer renderer(context->gl());
  if (!renderer.init(&error)) {
    std::fprintf(stderr, "bench_render: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s: %zu vertices, %zu tets; %s\n", argv[1], mesh.vertex_count(), mesh.tet_count(),
              context->description().c_str());

  std::vector<double> prepare_times;
  PreparedMesh prepared;
  for (int r = 0; r < repeat; ++r) {
    TetMesh copy = mesh;
    const auto t = Clock::now();
    prepared = prepare_mesh(std::move(copy));
    prepare_times.push_back(seconds_since(t));
  }
  std::printf("prepare (face neighbours + stretch, once per mesh): %.1f ms\n",
              1e3 * median(prepare_times));

  Vec3 lo = prepared.mesh.positions[0], hi = lo;
  for (const Vec3& p : prepared.mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  struct Case {
    const char* name;
    SurfaceFilter filter;
  };
  std::vector<Case> cases(4);
  cases[0].name = "everything shown";
  cases[1].name = "material hidden";
  cases[1].filter.hidden_materials = {hide};
  cases[2].name = "material hidden + cut at the centre";
  cases[2].filter = cases[1].filter;
  cases[2].filter.cut = true;
  cases[2].filter.cut_plane = {{0, 1, 0}, 0.5 * (lo.y + hi.y)};
  cases[3].name = "... + highlight stretch < 0.2";
  cases[3].filter = cases[2].filter;
  cases[3].filter.highlight = true;
  cases[3].filter.highlight_below = 0.2;

  std::printf("\n%-38s %10s %10s %10s %10s %10s\n", "full rebuild (median)", "triangles",
              "build ms", "upload ms", "total ms", "Mtets/s");
  SurfaceBuffers buffers;
  for (const Case& c : cases) {
    std::vector<double> build, upload, total;
    for (int r = 0; r < repeat; ++r) {
      const auto t0 = Clock::now();
      build_surface(prepared.surface_input(), c.filter, &buffers);
      const double b = seconds_since(t0);
      const auto t1 = Clock::now();
      renderer.upload(buffers);
      context->gl().Finish();
      const double u = seconds_since(t1);
      build.push_back(b);
      upload.push_back(u);
      total.push_back(b + u);
    }
    std::printf("%-38s %10zu %10.1f %10.1f %10.1f %10.1f\n", c.name, buffers.triangles.size() / 3,
                1e3 * median(build), 1e3 * median(upload), 1e3 * median(total),
                1e-6 * double(prepared.mesh.tet_count()) / median(total));
  }

  // One frame of the last case at 800 x 800 (llvmpipe, software), for reference.
  std::vector<double> draw_times;
  const Camera camera = snapshot_framing(prepared, buffers, {}, 800, 800).camera;
  DrawSettings draw;
  for (int r = 0; r < repeat; ++r) {
    const auto t = Clock::now();
    if (!renderer.draw(draw, camera, 800, 800)) {
      std::fprintf(stderr, "bench_render: %s\n", renderer.last_error().c_str());
      return 1;
    }
    context->gl().Finish();
    draw_times.push_back(seconds_since(t));
  }
  std::printf("\ndraw 800x800 + resolve (software rasteriser): %.1f ms\n",
              1e3 * median(draw_times));

  // The viewer's tet under the pointer: LodSurface::pick() over the drawn faces, for
  // rays through a 10 x 10 grid of the 800 x 800 picture of the last case.
  {
    const CollapseHistory no_history;
    Lod input_lod(mesh, &no_history);
    LodSurface input_surface;
    // The viewer's rebuild of the input's surface (on load, and after a change of the
    // cut, hidden materials or highlight), for each case; the last case is kept.
    for (const Case& c : cases) {
      std::vector<double> reset_times;
      for (int r = 0; r < repeat; ++r) {
        const auto u = Clock::now();
        input_surface.reset(lod_state(input_lod), c.filter);
        reset_times.push_back(seconds_since(u));
      }
      std::printf("LodSurface reset of the input, %-38s %8.1f ms, %.2f us a tet\n", c.name,
                  1e3 * median(reset_times), 1e6 * median(reset_times) / double(mesh.tet_count()));
    }
    std::vector<double> pick_times;
    size_t hits = 0;
    for (int r = 0; r < repeat; ++r) {
      for (int k = 0; k < 100; ++k) {
        const Ray ray = pixel_ray(camera, 40 + 80 * (k % 10), 40 + 80 * (k / 10), 800, 800);
        const auto u = Clock::now();
        hits += input_surface.pick(ray).tet != kInvalidIndex;
        pick_times.push_back(seconds_since(u));
      }
    }
    std::printf(
        "tet under the pointer (LodSurface::pick, %zu drawn faces): median %.2f ms "
        "(%zu of %d rays hit)\n",
        input_surface.triangles().size() / 3, 1e3 * median(pick_times), hits / repeat, 100);
  }
  if (lod_size <= 0) return 0;

  // Incremental LOD updates.
  SimplifyParams params;
  params.sizing.uniform = lod_size;
  params.tolerance = 0.05;
  SimplifyResult result;
  auto t = Clock::now();
  const Status simplified = simplify(mesh, params, &result);
  if (!simplified) {
    std::fprintf(stderr, "bench_render: %s\n", simplified.message().c_str());
    return 1;
  }
  std::printf("\nLOD: simplified to size %g in %.1f s: %zu steps, %zu -> %zu tets\n", lod_size,
              seconds_since(t), result.history.step_count(), result.base.tet_count(),
              result.output.tet_count());
  Lod lod(result.base, &result.history);
  const LodState state = lod_state(lod);
  SurfaceFilter filter;
  filter.hidden_materials = {hide};
  LodSurface surface;
  t = Clock::now();
  surface.reset(state, filter);
  renderer.update_triangles(surface.triangles(), surface.take_triangle_dirty());
  context->gl().Finish();
  std::printf("LodSurface reset at step 0 (%zu tets, %zu triangles): %.1f ms\n",
              lod.alive_tet_count(), surface.triangles().size() / 3, 1e3 * seconds_since(t));

  // Single steps and jumps of 1% of the history, coarsening then refining.
  LodDelta delta;
  const size_t steps = lod.step_count();
  for (const size_t stride : {size_t(1), std::max<size_t>(1, steps / 100)}) {
    std::vector<double> times;
    size_t touched = 0;
    const size_t count = std::min<size_t>(2000, steps / stride);
    for (size_t k = 0; k < count; ++k) {
      const size_t target = (k + 1) * stride;
      const auto u = Clock::now();
      lod.seek(target, &delta);
      surface.update(state, delta);
      const std::vector<DirtyRange> dirty = surface.take_triangle_dirty();
      renderer.update_triangles(surface.triangles(), dirty);
      context->gl().Finish();
      times.push_back(seconds_since(u));
      touched += delta.appeared.size() + delta.vanished.size() + delta.changed.size();
    }
    std::printf(
        "seek + incremental update + upload, %zu step(s) at a time: median %.3f ms (%zu "
        "seeks, %.0f tets in each delta)\n",
        stride, 1e3 * median(times), count, double(touched) / double(count));
  }
  // The same move done as a full rebuild (extract + prepare + build + upload).
  t = Clock::now();
  PreparedMesh level = prepare_mesh(lod.extract());
  SurfaceBuffers level_buffers;
  build_surface(level.surface_input(), filter, &level_buffers);
  renderer.upload(level_buffers);
  context->gl().Finish();
  std::printf("full rebuild of one level instead (extract + prepare + build + upload): %.1f ms\n",
              1e3 * seconds_since(t));
  return 0;
}
