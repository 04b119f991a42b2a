// Compares coarsened meshes of one input, whatever tool made them, on what an analyst
// asks of them: the thresholds TetLOD guarantees (stretch, size, valence), how much
// each material's volume changed, and how far the boundary and interfaces moved.
//
//   bench_compare INPUT --size S --stretch D --valence V NAME=FILE[@SECONDS] ...
//
// For each output it prints one row. The interface deviation is a two-sided estimate
// of the Hausdorff distance between the input's and the output's triangles of each
// material pair (boundary included): from the corners, edge midpoints and centroids
// of one side's triangles to the nearest triangle of the same pair on the other side.
// The largest over all pairs is printed, with the pair; a pair that exists on only
// one side is "lost". SECONDS is the time the tool reported, printed as given.
// An output that does not read as a valid mesh (TetLOD's reader rejects inverted and
// zero-volume tets) gets its read error as its row.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "core/adjacency.h"
#include "core/improve.h"
#include "core/io/mesh_io.h"
#include "core/mesh_compare.h"
#include "core/mesh_stats.h"
#include "core/metrics.h"

namespace {

using namespace tetlod;

std::string pair_name(const MaterialPair& p) {
  return std::to_string(p.first) + "|" +
         (p.second == kOutsideMaterial ? "out" : std::to_string(p.second));
}

void print_row(const std::string& name, const std::string& seconds, const TetMesh& mesh,
               const TetMesh& input, double size, double stretch, uint32_t valence) {
  const MeshStats st = compute_mesh_stats(mesh, build_vertex_tets(mesh));
  SimplifyParams thresholds;
  thresholds.sizing.uniform = size;
  thresholds.min_stretch = stretch;
  thresholds.max_valence = valence;
  const ThresholdCounts breaks = threshold_breaks(mesh, thresholds);
  const size_t thin = breaks.below_stretch, big = breaks.above_size, crowded = breaks.above_valence;
  // Volume change per material (core/mesh_compare.h), of the input's materials.
  const MeshComparison c = compare_meshes(input, mesh);
  double worst_volume = 0;
  int32_t worst_volume_material = 0;
  for (const MaterialVolumes& v : c.volumes) {
    if (v.before == 0) continue;
    const double change = 100 * (v.after - v.before) / v.before;
    if (std::abs(change) > std::abs(worst_volume))
      worst_volume = change, worst_volume_material = v.material;
  }
  // Interface deviation, both ways, per material pair.
  double worst_distance = 0;
  std::string worst_pair = "-", lost;
  for (const PairDeviation& d : c.pairs)
    if (d.distance > worst_distance) worst_distance = d.distance, worst_pair = pair_name(d.pair);
  for (const MaterialPair& p : c.lost) lost += (lost.empty() ? "" : ",") + pair_name(p);
  for (const MaterialPair& p : c.added)
    lost += std::string(lost.empty() ? "" : ",") + "new " + pair_name(p);
  char volume[64], deviation[64];
  if (std::abs(worst_volume) < 1e-6)
    std::snprintf(volume, sizeof volume, "< 1e-6 %%");
  else
    std::snprintf(volume, sizeof volume, "%+.3g %% (material %d)", worst_volume,
                  worst_volume_material);
  if (worst_distance < 1e-9)
    std::snprintf(deviation, sizeof deviation, "< 1e-9");
  else
    std::snprintf(deviation, sizeof deviation, "%.3g (%s)", worst_distance, worst_pair.c_str());
  std::printf("| %s | %zu | %.3f | %.4f | %zu | %.2f | %zu | %u | %zu | %s | %s | %s | %s |\n",
              name.c_str(), mesh.tet_count(), st.whole.average_stretch, st.whole.min_stretch, thin,
              st.whole.max_size, big, st.whole.max_valence, crowded, volume, deviation,
              lost.empty() ? "none" : lost.c_str(), seconds.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 9 || std::string(argv[2]) != "--size" || std::string(argv[4]) != "--stretch" ||
      std::string(argv[6]) != "--valence") {
    std::fprintf(stderr,
                 "usage: bench_compare INPUT --size S --stretch D --valence V "
                 "NAME=FILE[@SECONDS] ...\n");
    return 2;
  }
  const double size = std::atof(argv[3]), stretch = std::atof(argv[5]);
  const uint32_t valence = static_cast<uint32_t>(std::atoi(argv[7]));
  TetMesh input;
  Status s = read_mesh(argv[1], &input);
  if (!s) {
    std::fprintf(stderr, "bench_compare: %s\n", s.message().c_str());
    return 1;
  }

  std::printf(
      "thresholds: size %g, stretch %g, valence %d; deviation: largest distance between the "
      "input's and the output's triangles of one material pair, both ways\n\n",
      size, stretch, valence);
  std::printf(
      "| mesh | tets | ave. stretch | min. stretch | tets below %g | max. size | tets above %g | "
      "max. valence | nodes above %u | largest volume change | interface deviation (pair) | "
      "pairs lost or new | time, s |\n",
      stretch, size, valence);
  std::printf(
      "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: "
      "|\n");
  print_row("input", "", input, input, size, stretch, valence);
  for (int i = 8; i < argc; ++i) {
    const std::string arg = argv[i];
    const size_t eq = arg.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "bench_compare: expected NAME=FILE[@SECONDS], got '%s'\n", arg.c_str());
      return 2;
    }
    const std::string name = arg.substr(0, eq);
    std::string file = arg.substr(eq + 1), seconds;
    const size_t at = file.rfind('@');
    if (at != std::string::npos) seconds = file.substr(at + 1), file = file.substr(0, at);
    TetMesh mesh;
    s = read_mesh(file, &mesh);
    if (!s) {
      std::printf("| %s | not a valid mesh: %s | | | | | | | | | | | %s |\n", name.c_str(),
                  s.message().c_str(), seconds.c_str());
      continue;
    }
    print_row(name, seconds, mesh, input, size, stretch, valence);
  }
  return 0;
}
