// LOD replay benchmark: simplifies a mesh once, then times moving through the whole
// collapse history (coarsest <-> finest) and reports collapse steps per second.
//
//   bench_lod FILE --size S [--tolerance T] [--stretch D] [--valence V] [--repeat N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/simplify.h"

using tetlod::bench::Clock;
using tetlod::bench::median;
using tetlod::bench::seconds_since;

int main(int argc, char** argv) {
  using namespace tetlod;
  TetMesh mesh;
  SimplifyParams params;
  int repeat = 5;
  if (const int code = bench::load_simplify_bench("bench_lod", argc, argv, &mesh, &params, &repeat))
    return code;
  const auto start = Clock::now();
  SimplifyResult result;
  Status s = simplify(mesh, params, &result);
  if (!s) {
    std::fprintf(stderr, "bench_lod: %s\n", s.message().c_str());
    return 1;
  }
  const double simplify_seconds = seconds_since(start);
  Lod lod(result.base, &result.history);
  std::vector<double> down, up, down_delta;
  LodDelta delta;
  for (int r = 0; r < repeat; ++r) {
    auto t = Clock::now();
    lod.seek(lod.step_count());
    down.push_back(seconds_since(t));
    t = Clock::now();
    lod.seek(0);
    up.push_back(seconds_since(t));
    t = Clock::now();
    lod.seek(lod.step_count(), &delta);
    down_delta.push_back(seconds_since(t));
    lod.seek(0);
  }
  const double steps = static_cast<double>(lod.step_count());
  std::printf("file: %s  tets %zu -> base %zu -> %zu, %zu collapse steps\n", argv[1],
              mesh.tet_count(), result.base.tet_count(), result.output.tet_count(),
              lod.step_count());
  std::printf("simplify (subdivide + classify + collapse): %.3f s\n", simplify_seconds);
  std::printf("%-40s %10s %14s\n", "LOD move (median)", "seconds", "steps/s");
  std::printf("%-40s %10.4f %14.3g\n", "finest -> coarsest", median(down), steps / median(down));
  std::printf("%-40s %10.4f %14.3g\n", "coarsest -> finest", median(up), steps / median(up));
  std::printf("%-40s %10.4f %14.3g\n", "finest -> coarsest, with render delta", median(down_delta),
              steps / median(down_delta));
  return 0;
}
