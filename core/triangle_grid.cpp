#include "core/triangle_grid.h"

#include <algorithm>

namespace tetlod {

double squared_distance(const Vec3& p, const Triangle3& t) {
  const Vec3 &a = t[0], &b = t[1], &c = t[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return squared_length(ap);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return squared_length(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return squared_length(p - (a + ab * (d1 / (d1 - d3))));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return squared_length(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return squared_length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return squared_length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double sum = va + vb + vc;
  if (!(sum > 0)) return std::min({squared_length(ap), squared_length(bp), squared_length(cp)});
  return squared_length(p - (a + ab * (vb / sum) + ac * (vc / sum)));
}

TriangleGrid::TriangleGrid(std::vector<Triangle3> triangles) : triangles_(std::move(triangles)) {
  if (triangles_.empty()) return;
  Vec3 lo = triangles_[0][0], hi = lo;
  double extent_sum = 0;
  for (const Triangle3& t : triangles_) {
    Vec3 tlo = t[0], thi = t[0];
    for (const Vec3& q : t) {
      tlo = {std::min(tlo.x, q.x), std::min(tlo.y, q.y), std::min(tlo.z, q.z)};
      thi = {std::max(thi.x, q.x), std::max(thi.y, q.y), std::max(thi.z, q.z)};
    }
    lo = {std::min(lo.x, tlo.x), std::min(lo.y, tlo.y), std::min(lo.z, tlo.z)};
    hi = {std::max(hi.x, thi.x), std::max(hi.y, thi.y), std::max(hi.z, thi.z)};
    extent_sum += length(thi - tlo);
  }
  const Vec3 span = hi - lo;
  const double count = double(triangles_.size());
  cell_ = std::max(extent_sum / count, 1e-300);
  const double limit = 2.0 * count + 8;  // cells
  // (Coordinates far apart can overflow the span: then one cell holds everything.)
  const bool finite = is_finite(span) && std::isfinite(cell_);
  for (int round = 0; finite && round < 4000; ++round) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) cells *= std::floor(span[k] / cell_) + 1;
    if (cells <= limit) break;
    cell_ *= 1.25;
  }
  origin_ = lo;
  auto set_dims = [&] {
    for (int k = 0; k < 3; ++k) {
      const double n = std::floor(span[k] / cell_) + 1;
      dims_[k] = finite && n >= 1 && n <= limit ? int(n) : 1;
    }
  };
  auto cell_range = [&](const Triangle3& t, int* from, int* to) {
    for (int k = 0; k < 3; ++k) {
      double a = t[0][k], b = a;
      for (const Vec3& q : t) a = std::min(a, q[k]), b = std::max(b, q[k]);
      from[k] = cell_index(a, k);
      to[k] = cell_index(b, k);
    }
  };
  // A few triangles far larger than the mean would each fill many cells: coarser
  // cells until the grid holds at most 16 triangles' worth.
  for (set_dims();; cell_ *= 2, set_dims()) {
    double held = 0;
    for (const Triangle3& t : triangles_) {
      int from[3], to[3];
      cell_range(t, from, to);
      held += double(to[0] - from[0] + 1) * (to[1] - from[1] + 1) * (to[2] - from[2] + 1);
    }
    if (held <= 16.0 * count + 1024 || dims_[0] * dims_[1] * dims_[2] == 1) break;
  }
  cell_start_.assign(size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<uint32_t> cursor;
    if (pass == 1) {
      for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
      cursor.assign(cell_start_.begin(), cell_start_.end() - 1);
      cell_entries_.resize(cell_start_.back());
    }
    for (uint32_t i = 0; i < triangles_.size(); ++i) {
      int from[3], to[3];
      cell_range(triangles_[i], from, to);
      for (int z = from[2]; z <= to[2]; ++z)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int x = from[0]; x <= to[0]; ++x) {
            if (pass == 0)
              ++cell_start_[cell_of(x, y, z) + 1];
            else
              cell_entries_[cursor[cell_of(x, y, z)]++] = i;
          }
    }
  }
}

uint32_t TriangleGrid::nearest(const Vec3& p, double* distance2, size_t cell_budget) const {
  double best = INFINITY;
  uint32_t found = kNone;
  if (triangles_.empty()) return kNone;
  int center[3];
  for (int k = 0; k < 3; ++k) center[k] = cell_index(p[k], k);
  auto visit = [&](int x, int y, int z) {
    const size_t cell = cell_of(x, y, z);
    for (uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      const uint32_t i = cell_entries_[k];
      const double d = squared_distance(p, triangles_[i]);
      if (d < best || (d == best && i < found)) best = d, found = i;
    }
  };
  // Shells of cells around the centre cell, outwards, each visiting only its own cells.
  size_t visited = 0;
  for (int r = 0; visited < cell_budget; ++r) {
    const int z0 = std::max(center[2] - r, 0), z1 = std::min(center[2] + r, dims_[2] - 1);
    const int y0 = std::max(center[1] - r, 0), y1 = std::min(center[1] + r, dims_[1] - 1);
    const int x0 = std::max(center[0] - r, 0), x1 = std::min(center[0] + r, dims_[0] - 1);
    for (int z = z0; z <= z1; ++z) {
      const bool z_face = std::abs(z - center[2]) == r;
      for (int y = y0; y <= y1; ++y) {
        if (z_face || std::abs(y - center[1]) == r) {
          for (int x = x0; x <= x1; ++x) visit(x, y, z), ++visited;
        } else {
          if (center[0] - r >= 0) visit(center[0] - r, y, z), ++visited;
          if (r > 0 && center[0] + r < dims_[0]) visit(center[0] + r, y, z), ++visited;
        }
      }
    }
    // Every cell not yet seen lies beyond the box of shells 0..r, on a side where the
    // grid goes on: stop once the best is nearer than those sides, or there are none.
    double margin = INFINITY;
    for (int k = 0; k < 3; ++k) {
      if (center[k] - r > 0)
        margin =
            std::min(margin, std::max(0.0, p[k] - (origin_[k] + double(center[k] - r) * cell_)));
      if (center[k] + r < dims_[k] - 1)
        margin =
            std::min(margin, std::max(0.0, origin_[k] + double(center[k] + r + 1) * cell_ - p[k]));
    }
    if (margin == INFINITY || (found != kNone && best <= margin * margin)) {
      if (distance2) *distance2 = best;
      return found;
    }
  }
  if (distance2) *distance2 = best;  // the budget ran out: the nearest seen
  return found;
}

}  // namespace tetlod
