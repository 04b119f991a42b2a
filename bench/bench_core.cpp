// Core speed benchmark: read a mesh, build adjacency, compute the Table I metrics,
// extract the surface and classify vertices. Prints the median of N runs of each, and
// of the validation's overlap check run again on its own.
//
//   bench_core FILE [--repeat N]
//
// bench/run_core_bench.sh makes a ~1M-tet motor and runs this on it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/adjacency.h"
#include "core/classify.h"
#include "core/io/mesh_io.h"
#include "core/mesh_stats.h"
#include "core/overlap.h"
#include "core/surface.h"

using tetlod::bench::Clock;
using tetlod::bench::median;
using tetlod::bench::seconds_since;

int main(int argc, char** argv) {
  using namespace tetlod;
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_core FILE [--repeat N]\n");
    return 2;
  }
  const std::string path = argv[1];
  int repeat = 5;
  if (argc >= 4 && std::string(argv[2]) == "--repeat") repeat = std::max(1, std::atoi(argv[3]));

  std::vector<double> read_s, adjacency_s, metrics_s, surface_s, overlap_s;
  TetMesh mesh;
  size_t checksum = 0;
  for (int r = 0; r < repeat; ++r) {
    auto start = Clock::now();
    ReadInfo info;
    const Status status = read_mesh(path, &mesh, &info);
    if (!status) {
      std::fprintf(stderr, "bench_core: %s\n", status.message().c_str());
      return 1;
    }
    read_s.push_back(seconds_since(start));

    start = Clock::now();
    const MeshAdjacency adjacency = build_adjacency(mesh);
    adjacency_s.push_back(seconds_since(start));

    // The part of the read's validation that looks for tets overlapping with no face
    // between them (core/overlap.h), timed again on its own.
    start = Clock::now();
    const OverlapFinding overlap = find_overlap(mesh, adjacency.tet_neighbors);
    overlap_s.push_back(seconds_since(start));
    checksum += overlap.kind == OverlapFinding::Kind::kNone;

    start = Clock::now();
    const MeshStats stats = compute_mesh_stats(mesh, adjacency.vertex_tets);
    metrics_s.push_back(seconds_since(start));

    start = Clock::now();
    const Classification c =
        classify_vertices(mesh, extract_surface(mesh, adjacency.tet_neighbors));
    surface_s.push_back(seconds_since(start));
    checksum += stats.whole.edges + c.feature_edges.size();
  }
  const double tets = static_cast<double>(mesh.tet_count());
  std::printf("file: %s\nvertices: %zu  tets: %zu  runs: %d  (checksum %zu)\n", path.c_str(),
              mesh.vertex_count(), mesh.tet_count(), repeat, checksum);
  std::printf("%-34s %10s %14s\n", "stage (median)", "seconds", "tets/s");
  auto row = [&](const char* name, const std::vector<double>& s) {
    const double m = median(s);
    std::printf("%-34s %10.4f %14.3g\n", name, m, tets / m);
  };
  row("read + validate", read_s);
  row("  of which overlap check", overlap_s);
  row("adjacency (vertex->tets, faces)", adjacency_s);
  row("metrics (Table I row, histogram)", metrics_s);
  const double both = median(adjacency_s) + median(metrics_s);
  std::printf("%-34s %10.4f %14.3g\n", "adjacency + metrics", both, tets / both);
  row("surface + classification", surface_s);
  return 0;
}
