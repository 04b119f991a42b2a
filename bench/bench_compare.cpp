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

namespace {

using namespace tetlod;

// Squared distance from p to the triangle (a, b, c): the closest point by the region
// of the triangle's plane p projects into (vertex, edge or face).
double point_triangle_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return squared_length(ap);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return squared_length(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return squared_length(ap - ab * (d1 / (d1 - d3)));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return squared_length(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return squared_length(ap - ac * (d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return squared_length(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denominator = 1 / (va + vb + vc);
  const Vec3 q = a + ab * (vb * denominator) + ac * (vc * denominator);
  return squared_length(p - q);
}

struct Triangle {
  Vec3 p[3];
};

// Triangles in a uniform grid of cells, each triangle in every cell its bounding box
// touches; nearest() searches rings of cells outwards until no closer triangle can be.
class TriangleGrid {
 public:
  explicit TriangleGrid(std::vector<Triangle> triangles) : tris_(std::move(triangles)) {
    lo_ = hi_ = tris_[0].p[0];
    double extent_sum = 0;
    for (const Triangle& t : tris_) {
      Vec3 a = t.p[0], b = t.p[0];
      for (const Vec3& q : t.p) {
        a = {std::min(a.x, q.x), std::min(a.y, q.y), std::min(a.z, q.z)};
        b = {std::max(b.x, q.x), std::max(b.y, q.y), std::max(b.z, q.z)};
      }
      lo_ = {std::min(lo_.x, a.x), std::min(lo_.y, a.y), std::min(lo_.z, a.z)};
      hi_ = {std::max(hi_.x, b.x), std::max(hi_.y, b.y), std::max(hi_.z, b.z)};
      extent_sum += std::max({b.x - a.x, b.y - a.y, b.z - a.z});
    }
    const double span = std::max({hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z, 1e-12});
    cell_ = std::max(2 * extent_sum / tris_.size(), span / 256);
    for (int k = 0; k < 3; ++k)
      n_[k] = std::max(1, static_cast<int>(std::ceil((axis(hi_, k) - axis(lo_, k)) / cell_)));
    std::vector<std::pair<size_t, uint32_t>> entries;
    for (uint32_t i = 0; i < tris_.size(); ++i) {
      int a[3], b[3];
      for (int k = 0; k < 3; ++k) {
        double mn = axis(tris_[i].p[0], k), mx = mn;
        for (const Vec3& q : tris_[i].p)
          mn = std::min(mn, axis(q, k)), mx = std::max(mx, axis(q, k));
        a[k] = cell_of(mn, k);
        b[k] = cell_of(mx, k);
      }
      for (int x = a[0]; x <= b[0]; ++x)
        for (int y = a[1]; y <= b[1]; ++y)
          for (int z = a[2]; z <= b[2]; ++z) entries.push_back({index(x, y, z), i});
    }
    std::sort(entries.begin(), entries.end());
    first_.assign(size_t(n_[0]) * n_[1] * n_[2] + 1, 0);
    for (const auto& e : entries) ++first_[e.first + 1];
    for (size_t c = 0; c + 1 < first_.size(); ++c) first_[c + 1] += first_[c];
    items_.reserve(entries.size());
    for (const auto& e : entries) items_.push_back(e.second);
  }

  double nearest(const Vec3& p) const {
    const int c[3] = {cell_of(p.x, 0), cell_of(p.y, 1), cell_of(p.z, 2)};
    double best2 = INFINITY;
    const int max_ring = std::max({n_[0], n_[1], n_[2]}) + 1;
    for (int r = 0; r <= max_ring; ++r) {
      for (int x = c[0] - r; x <= c[0] + r; ++x)
        for (int y = c[1] - r; y <= c[1] + r; ++y)
          for (int z = c[2] - r; z <= c[2] + r; ++z) {
            if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r)
              continue;  // the shell only
            if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) continue;
            const size_t cell = index(x, y, z);
            for (uint32_t k = first_[cell]; k < first_[cell + 1]; ++k) {
              const Triangle& t = tris_[items_[k]];
              best2 = std::min(best2, point_triangle_distance2(p, t.p[0], t.p[1], t.p[2]));
            }
          }
      // Cells outside ring r are at least r cells away from p's cell.
      const double reach = r * cell_;
      if (best2 <= reach * reach) break;
    }
    return std::sqrt(best2);
  }

 private:
  static double axis(const Vec3& v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }
  int cell_of(double x, int k) const {
    const int c = static_cast<int>(std::floor((x - axis(lo_, k)) / cell_));
    return std::min(std::max(c, 0), n_[k] - 1);
  }
  size_t index(int x, int y, int z) const { return (size_t(x) * n_[1] + y) * n_[2] + z; }

  std::vector<Triangle> tris_;
  Vec3 lo_, hi_;
  double cell_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<uint32_t> first_, items_;
};

using Pair = std::pair<int32_t, int32_t>;  // (inner, outer) material; outer -1: boundary

std::map<Pair, std::vector<Triangle>> interface_triangles(const TetMesh& mesh,
                                                          const MeshAdjacency& adjacency) {
  std::map<Pair, std::vector<Triangle>> out;
  for (const SurfaceTriangle& s : extract_surface(mesh, adjacency.tet_neighbors)) {
    Triangle t;
    for (int k = 0; k < 3; ++k) t.p[k] = mesh.positions[s.v[k]];
    out[{s.inner, s.outer}].push_back(t);
  }
  return out;
}

// Largest distance from the sample points of `from` to the triangles in `to`.
double one_sided(const std::vector<Triangle>& from, const TriangleGrid& to) {
  double worst = 0;
  for (const Triangle& t : from) {
    const Vec3 samples[7] = {t.p[0],
                             t.p[1],
                             t.p[2],
                             (t.p[0] + t.p[1]) * 0.5,
                             (t.p[1] + t.p[2]) * 0.5,
                             (t.p[2] + t.p[0]) * 0.5,
                             (t.p[0] + t.p[1] + t.p[2]) * (1.0 / 3)};
    for (const Vec3& p : samples) worst = std::max(worst, to.nearest(p));
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
