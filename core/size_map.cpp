#include "core/size_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/adjacency.h"
#include "core/morton.h"

namespace tetlod {
namespace {

// A point whose smallest barycentric coordinate is at least -kInside is in the tet
// (the coordinates of a point on a face come out within rounding of 0).
constexpr double kInside = 1e-12;
// Steps a walk may take before the point's cell is scanned instead (a walk can
// circle in a mesh that is not Delaunay; graded meshes make long walks from a cell
// of large tets into small ones).
constexpr int kMostSteps = 4096;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

inline void SizeMap::barycentric(uint32_t t, const Vec3& p, double l[4]) const {
  const TetData& a = tets_[t];
  const double dx = p.x - a.ox, dy = p.y - a.oy, dz = p.z - a.oz;
  l[1] = a.m[0] * dx + a.m[1] * dy + a.m[2] * dz;
  l[2] = a.m[3] * dx + a.m[4] * dy + a.m[5] * dz;
  l[3] = a.m[6] * dx + a.m[7] * dy + a.m[8] * dz;
  l[0] = 1 - l[1] - l[2] - l[3];
}

Status SizeMap::build(const TetMesh& mesh, std::vector<double> sizes,
                      std::shared_ptr<const SizeMap>* out) {
  if (sizes.size() != mesh.vertex_count()) {
    return Status::error(std::to_string(sizes.size()) + " sizes for a mesh of " +
                         std::to_string(mesh.vertex_count()) + " vertices");
  }
  if (mesh.tets.empty()) return Status::error("a size map needs a mesh with tets");
  auto map = std::make_shared<SizeMap>();
  map->smallest_ = std::numeric_limits<double>::infinity();
  map->largest_ = 0;
  for (size_t v = 0; v < sizes.size(); ++v) {
    if (!std::isfinite(sizes[v]) || !(sizes[v] > 0)) {
      return Status::error("size " + std::to_string(v + 1) + " (vertex " + std::to_string(v + 1) +
                           ") is " + number(sizes[v]) + ": sizes must be finite and > 0");
    }
    map->smallest_ = std::min(map->smallest_, sizes[v]);
    map->largest_ = std::max(map->largest_, sizes[v]);
  }
  map->vertex_count_ = sizes.size();
  map->source_.positions = mesh.positions;
  map->source_.tets = mesh.tets;
  map->sizes_ = sizes;

  // The tets in Morton order of their centroids (ties by their order in `mesh`).
  const size_t n = mesh.tets.size();
  Vec3 lo, hi;
  mesh_bounds(mesh, &lo, &hi);
  const Vec3 extent = hi - lo;
  const double largest_extent = std::max({extent.x, extent.y, extent.z});
  std::vector<std::pair<uint64_t, uint32_t>> order(n);
  const double scale = largest_extent > 0 ? 2097151.0 / largest_extent : 0;
  for (size_t t = 0; t < n; ++t) {
    const Tet& q = mesh.tets[t];
    const Vec3 c = (mesh.positions[q[0]] + mesh.positions[q[1]] + mesh.positions[q[2]] +
                    mesh.positions[q[3]]) *
                   0.25;
    order[t] = {morton_key((c - lo) * scale), uint32_t(t)};
  }
  std::sort(order.begin(), order.end());
  TetMesh sorted;
  sorted.positions = mesh.positions;
  sorted.tets.resize(n);
  sorted.materials.assign(n, 0);
  for (size_t t = 0; t < n; ++t) sorted.tets[t] = mesh.tets[order[t].second];
  std::vector<uint32_t> across;
  const FaceProblem problem = build_face_neighbors(sorted, &across);
  if (problem.kind != FaceProblem::Kind::kNone)
    return Status::error("tets " + std::to_string(order[problem.tet_a].second + 1) + " and " +
                         std::to_string(order[problem.tet_b].second + 1) +
                         " do not meet face to face");

  map->tets_.resize(n);
  for (size_t t = 0; t < n; ++t) {
    const Tet& q = sorted.tets[t];
    const Vec3& a = mesh.positions[q[0]];
    const Vec3 e1 = mesh.positions[q[1]] - a, e2 = mesh.positions[q[2]] - a,
               e3 = mesh.positions[q[3]] - a;
    const Vec3 r1 = cross(e2, e3), r2 = cross(e3, e1), r3 = cross(e1, e2);
    const double det = dot(e1, r1);
    if (!(det > 0) || !std::isfinite(det))
      return Status::error("tet " + std::to_string(order[t].second + 1) + " is flat or inverted");
    const double s = 1 / det;
    TetData& d = map->tets_[t];
    d = {a.x,
         a.y,
         a.z,
         {r1.x * s, r1.y * s, r1.z * s, r2.x * s, r2.y * s, r2.z * s, r3.x * s, r3.y * s, r3.z * s},
         {sizes[q[0]], sizes[q[1]], sizes[q[2]], sizes[q[3]]},
         {across[4 * t], across[4 * t + 1], across[4 * t + 2], across[4 * t + 3]}};
  }

  // The tets' grid: cells about twice the edge of a cube of the mean tet volume (a few
  // tets each), made larger while the tets' boxes would make more than 16 entries a
  // tet on average (large tets of a graded mesh span many small cells).
  const double volume = std::max(extent.x, largest_extent * 1e-6) *
                        std::max(extent.y, largest_extent * 1e-6) *
                        std::max(extent.z, largest_extent * 1e-6);
  const double mean_edge = std::cbrt(volume / double(n));
  Grid& grid = map->tets_grid_;
  std::vector<std::array<uint32_t, 6>> ranges(n);
  for (double cell = 2 * mean_edge;; cell *= 1.5) {
    grid.lay(lo, extent, cell);
    if (grid.cells() > 4 * n + 64) continue;
    size_t entries = 0;
    for (size_t t = 0; t < n && entries <= 16 * n; ++t) {
      Vec3 tlo = mesh.positions[sorted.tets[t][0]], thi = tlo;
      for (int c = 1; c < 4; ++c) {
        const Vec3& p = mesh.positions[sorted.tets[t][c]];
        tlo = {std::min(tlo.x, p.x), std::min(tlo.y, p.y), std::min(tlo.z, p.z)};
        thi = {std::max(thi.x, p.x), std::max(thi.y, p.y), std::max(thi.z, p.z)};
      }
      std::array<uint32_t, 6>& r = ranges[t];
      const size_t a = grid.index(tlo), b = grid.index(thi);
      const size_t nx = size_t(grid.dims[0]), nxy = nx * size_t(grid.dims[1]);
      r = {uint32_t(a % nx), uint32_t(a / nx % size_t(grid.dims[1])), uint32_t(a / nxy),
           uint32_t(b % nx), uint32_t(b / nx % size_t(grid.dims[1])), uint32_t(b / nxy)};
      entries += size_t(r[3] - r[0] + 1) * size_t(r[4] - r[1] + 1) * size_t(r[5] - r[2] + 1);
    }
    if (entries <= 16 * n) break;
  }
  const size_t cells = grid.cells();
  const size_t nx = size_t(grid.dims[0]), nxy = nx * size_t(grid.dims[1]);
  auto for_cells = [&](size_t t, auto&& f) {
    const std::array<uint32_t, 6>& r = ranges[t];
    for (size_t z = r[2]; z <= r[5]; ++z)
      for (size_t y = r[1]; y <= r[4]; ++y)
        for (size_t x = r[0]; x <= r[3]; ++x) f(x + y * nx + z * nxy);
  };
  map->cell_begin_.assign(cells + 1, 0);
  for (size_t t = 0; t < n; ++t) for_cells(t, [&](size_t c) { ++map->cell_begin_[c + 1]; });
  for (size_t c = 0; c < cells; ++c) map->cell_begin_[c + 1] += map->cell_begin_[c];
  map->cell_tets_.resize(map->cell_begin_[cells]);
  {
    std::vector<uint32_t> next(map->cell_begin_.begin(), map->cell_begin_.end() - 1);
    for (size_t t = 0; t < n; ++t)
      for_cells(t, [&](size_t c) { map->cell_tets_[next[c]++] = uint32_t(t); });
  }

  // The starts: each cell's centre located by a walk from the previous cell's tet (a
  // neighbour, in x-fastest order), so that a query's walk begins within half a
  // cell of its point.
  // (At most about eight cells a tet: a thin plate's box would hold far more.)
  Grid& starts = map->start_grid_;
  for (double cell = mean_edge * 0.6;; cell *= 1.5) {
    starts.lay(lo, extent, cell);
    if (starts.cells() <= 8 * n + 64) break;
  }
  map->start_.resize(starts.cells());
  uint32_t t = 0;
  double l[4];
  for (size_t c = 0; c < starts.cells(); ++c) {
    t = map->locate(starts.center(c), t, l);
    map->start_[c] = t;
  }
  *out = std::move(map);
  return Status();
}

void SizeMap::Grid::lay(const Vec3& low, const Vec3& extent, double cell) {
  lo = low;
  inverse_cell = 1 / cell;
  for (int k = 0; k < 3; ++k) {
    const double d = std::floor(extent[k] / cell) + 1;
    dims[k] = d < 1 ? 1 : (d < 1e6 ? int(d) : 1000000);
  }
}

size_t SizeMap::Grid::index(const Vec3& p) const {
  size_t result = 0, stride = 1;
  for (int k = 0; k < 3; ++k) {
    double f = (p[k] - lo[k]) * inverse_cell;
    if (!(f >= 0)) f = 0;  // NaN too
    if (f > dims[k] - 1) f = dims[k] - 1;
    result += size_t(f) * stride;
    stride *= size_t(dims[k]);
  }
  return result;
}

Vec3 SizeMap::Grid::center(size_t cell) const {
  const size_t nx = size_t(dims[0]), ny = size_t(dims[1]);
  const double x = double(cell % nx), y = double(cell / nx % ny), z = double(cell / (nx * ny));
  return {lo.x + (x + 0.5) / inverse_cell, lo.y + (y + 0.5) / inverse_cell,
          lo.z + (z + 0.5) / inverse_cell};
}

// The value at the barycentric coordinates l, the negative ones taken as 0 (a point
// outside the tet: the value at a point of the tet near it): a weighted mean of the
// corners' sizes, so within their range; their size to the bit where they are equal
// (a tet exactly at the size there is not over it by rounding).
double SizeMap::value(uint32_t t, const double l[4]) const {
  const double* h = tets_[t].h;
  if (h[0] == h[1] && h[0] == h[2] && h[0] == h[3]) return h[0];
  double weight = 0, sum = 0, low = h[0], high = h[0];
  for (int c = 0; c < 4; ++c) {
    const double w = l[c] > 0 ? l[c] : 0;
    weight += w;
    sum += w * h[c];
    low = std::min(low, h[c]);
    high = std::max(high, h[c]);
  }
  const double v = sum / weight;  // NaN only for a point so far off that l overflowed
  return v >= low ? (v <= high ? v : high) : low;
}

uint32_t SizeMap::locate(const Vec3& p, uint32_t t, double l[4]) const {
  uint32_t best = t;
  double best_l[4] = {1, 0, 0, 0}, best_min = -std::numeric_limits<double>::infinity();
  for (int step = 0; step < kMostSteps; ++step) {
    barycentric(t, p, l);
    int worst = 0;
    for (int c = 1; c < 4; ++c)
      if (l[c] < l[worst]) worst = c;
    if (l[worst] >= -kInside) return t;
    if (l[worst] > best_min) {
      best = t, best_min = l[worst];
      std::copy(l, l + 4, best_l);
    }
    const uint32_t next = tets_[t].across[worst];
    if (next == kInvalidIndex) break;  // the walk left the mesh
    t = next;
  }
  // Every tet whose box touches p's cell: the first that holds p, else the one it is
  // least outside of.
  const size_t cell = tets_grid_.index(p);
  for (uint32_t i = cell_begin_[cell]; i < cell_begin_[cell + 1]; ++i) {
    const uint32_t u = cell_tets_[i];
    barycentric(u, p, l);
    const double low = std::min({l[0], l[1], l[2], l[3]});
    if (low >= -kInside) return u;
    if (low > best_min) {
      best = u, best_min = low;
      std::copy(l, l + 4, best_l);
    }
  }
  std::copy(best_l, best_l + 4, l);
  return best;
}

double SizeMap::at(const Vec3& p) const {
  double l[4];
  const uint32_t t = locate(p, start_[start_grid_.index(p)], l);
  return value(t, l);
}

void SizeMap::apply(size_t n, const double* x, const double* y, const double* z,
                    double* size) const {
  for (size_t i = 0; i < n; ++i) size[i] = std::min(size[i], at({x[i], y[i], z[i]}));
}

}  // namespace tetlod
