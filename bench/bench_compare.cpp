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
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/mesh_stats.h"
#include "core/metrics.h"
#include "core/surface.h"
#include "core/triangle_grid.h"

namespace {

using namespace tetlod;

// A triangle by its corners (core/triangle_grid.h), and the distance from p to the
// nearest one of a grid.
using Triangle = Triangle3;
double nearest_distance(const TriangleGrid& grid, const Vec3& p) {
  double d2 = INFINITY;
  grid.nearest(p, &d2);
  return std::sqrt(d2);
}

using Pair = std::pair<int32_t, int32_t>;  // (inner, outer) material; outer -1: boundary

std::map<Pair, std::vector<Triangle>> interface_triangles(const TetMesh& mesh,
                                                          const MeshAdjacency& adjacency) {
  std::map<Pair, std::vector<Triangle>> out;
  for (const SurfaceTriangle& s : extract_surface(mesh, adjacency.tet_neighbors)) {
    Triangle t;
    for (int k = 0; k < 3; ++k) t[k] = mesh.positions[s.v[k]];
    out[{s.inner, s.outer}].push_back(t);
  }
  return out;
}

// Largest distance from the sample points of `from` to the triangles in `to`.
double one_sided(const std::vector<Triangle>& from, const TriangleGrid& to) {
  double worst = 0;
  for (const Triangle& t : from) {
    const Vec3 samples[7] = {t[0],
                             t[1],
                             t[2],
                             (t[0] + t[1]) * 0.5,
                             (t[1] + t[2]) * 0.5,
                             (t[2] + t[0]) * 0.5,
                             (t[0] + t[1] + t[2]) * (1.0 / 3)};
    for (const Vec3& p : samples) worst = std::max(worst, nearest_distance(to, p));
  }
  return worst;
}

std::string pair_name(const Pair& p) {
  return std::to_string(p.first) + "|" + (p.second < 0 ? "out" : std::to_string(p.second));
}

struct Reference {
  TetMesh mesh;
  MeshStats stats;
  std::map<Pair, std::vector<Triangle>> surfaces;
  std::map<Pair, TriangleGrid> grids;
};

void print_row(const std::string& name, const std::string& seconds, const TetMesh& mesh,
               const Reference& in, double size, double stretch, uint32_t valence) {
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const VertexTets& vt = adjacency.vertex_tets;
  const MeshStats st = compute_mesh_stats(mesh, vt);
  size_t thin = 0, big = 0, crowded = 0;
  for (const Tet& t : mesh.tets) {
    const TetShape s = tet_shape(mesh, t);
    thin += s.stretch < stretch;
    big += s.size > size;
  }
  // Valence: distinct edge neighbours, from the vertex -> tets lists.
  std::vector<uint32_t> seen(mesh.vertex_count(), kInvalidIndex);
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    uint32_t n = 0;
    for (const uint32_t* t = vt.begin(v); t != vt.end(v); ++t)
      for (uint32_t w : mesh.tets[*t])
        if (w != v && seen[w] != v) seen[w] = v, ++n;
    crowded += n > valence;
  }
  // Volume change per material.
  double worst_volume = 0;
  int32_t worst_volume_material = 0;
  for (const MaterialRow& r : in.stats.per_material) {
    double after = 0;
    for (const MaterialRow& q : st.per_material)
      if (q.material == r.material) after = q.row.volume;
    const double change = 100 * (after - r.row.volume) / r.row.volume;
    if (std::abs(change) > std::abs(worst_volume))
      worst_volume = change, worst_volume_material = r.material;
  }
  // Interface deviation, both ways, per material pair.
  const auto out_surfaces = interface_triangles(mesh, adjacency);
  double worst_distance = 0;
  std::string worst_pair = "-", lost;
  for (const auto& [pair, tris] : in.surfaces) {
    auto found = out_surfaces.find(pair);
    if (found == out_surfaces.end()) {
      lost += (lost.empty() ? "" : ",") + pair_name(pair);
      continue;
    }
    const TriangleGrid out_grid(found->second);
    const double d =
        std::max(one_sided(tris, out_grid), one_sided(found->second, in.grids.at(pair)));
    if (d > worst_distance) worst_distance = d, worst_pair = pair_name(pair);
  }
  for (const auto& entry : out_surfaces)
    if (!in.surfaces.count(entry.first))
      lost += std::string(lost.empty() ? "" : ",") + "new " + pair_name(entry.first);
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
  Reference in;
  Status s = read_mesh(argv[1], &in.mesh);
  if (!s) {
    std::fprintf(stderr, "bench_compare: %s\n", s.message().c_str());
    return 1;
  }
  const MeshAdjacency adjacency = build_adjacency(in.mesh);
  in.stats = compute_mesh_stats(in.mesh, adjacency.vertex_tets);
  in.surfaces = interface_triangles(in.mesh, adjacency);
  for (const auto& [pair, tris] : in.surfaces) in.grids.emplace(pair, TriangleGrid(tris));

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
  print_row("input", "", in.mesh, in, size, stretch, valence);
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
    print_row(name, seconds, mesh, in, size, stretch, valence);
  }
  return 0;
}
