// Simplifier benchmark: the whole pipeline (subdivide + classify + simplify) on one
// mesh, repeated; reports the median time of each phase, collapses per second and
// the peak memory per input tet. One thread.
//
//   bench_simplify FILE --size S [--tolerance T] [--stretch D] [--valence V]
//                  [--size-field SPEC] [--material-size M=S,...] [--size-map FILE.sol]
//                  [--repeat N]
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/io/mesh_io.h"
#include "core/simplify.h"

using tetlod::bench::Clock;
using tetlod::bench::median;
using tetlod::bench::seconds_since;

int main(int argc, char** argv) {
  using namespace tetlod;
  TetMesh mesh;
  SimplifyParams params;
  int repeat = 5;
  if (const int code =
          bench::load_simplify_bench("bench_simplify", argc, argv, &mesh, &params, &repeat))
    return code;
  std::vector<double> total, subdivide, classify, collapse;
  size_t collapses = 0, output_tets = 0;
  const char* kernels = "";
  tetlod::EvaluationCounts evaluations;
  for (int r = 0; r < repeat; ++r) {
    SimplifyResult result;
    const auto start = Clock::now();
    const Status s = simplify(mesh, params, &result);
    total.push_back(seconds_since(start));
    if (!s) {
      std::fprintf(stderr, "bench_simplify: %s\n", s.message().c_str());
      return 1;
    }
    subdivide.push_back(result.seconds_subdivide);
    classify.push_back(result.seconds_classify);
    collapse.push_back(result.seconds_simplify);
    collapses = result.history.step_count();
    kernels = result.kernels;
    evaluations = result.evaluations;
    output_tets = result.output.tet_count();
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;
  std::printf("input: %zu tets; size %g, stretch %g, valence %u, tolerance %g\n", mesh.tet_count(),
              params.sizing.uniform, params.min_stretch, params.max_valence, params.tolerance);
  std::printf("output: %zu tets after %zu collapses (%s kernels)\n", output_tets, collapses,
              kernels);
  std::printf(
      "evaluations: %llu at the start, %llu of new nodes' edges, %llu stale, %llu in sweeps "
      "(%llu in all; %llu repeats skipped)\n",
      static_cast<unsigned long long>(evaluations.initial),
      static_cast<unsigned long long>(evaluations.new_node),
      static_cast<unsigned long long>(evaluations.stale),
      static_cast<unsigned long long>(evaluations.sweep),
      static_cast<unsigned long long>(evaluations.total()),
      static_cast<unsigned long long>(evaluations.repeated));
  std::printf(
      "median of %d: pipeline %.3f s (subdivide %.3f, classify %.3f, simplify %.3f); "
      "%.0f collapses/s\n",
      repeat, median(total), median(subdivide), median(classify), median(collapse),
      static_cast<double>(collapses) / median(collapse));
  std::printf("fastest of %d: pipeline %.3f s, simplify %.3f s\n", repeat,
              *std::min_element(total.begin(), total.end()),
              *std::min_element(collapse.begin(), collapse.end()));
  std::printf(
      "peak memory (whole process, input mesh included): %.1f MB, %.0f bytes per input "
      "tet\n",
      peak_bytes / 1e6, peak_bytes / static_cast<double>(mesh.tet_count()));
  return 0;
}
