// Nearest-triangle queries: triangles in a uniform grid of cells, each in every cell
// its bounding box touches, searched in shells of cells outwards from the query's
// cell until no unseen cell can hold a nearer triangle. For SurfacePatches (which
// input triangle a simplified one lies on) and the benchmarks' surface distances.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace tetlod {

using Triangle3 = std::array<Vec3, 3>;

// Squared distance from p to the triangle t (Ericson, Real-Time Collision Detection,
// 5.1.5: the closest point by the Voronoi region of p).
double squared_distance(const Vec3& p, const Triangle3& t);

class TriangleGrid {
 public:
  static constexpr uint32_t kNone = 0xffffffffu;
  TriangleGrid() = default;
  // Any triangles, finite or not, of any sizes: cells about the mean triangle's size,
  // coarser where a few huge triangles would fill the grid (it holds at most ~16
  // triangles' worth of cell entries), one cell if coordinates overflow the span.
  explicit TriangleGrid(std::vector<Triangle3> triangles);
  bool empty() const { return triangles_.empty(); }
  const std::vector<Triangle3>& triangles() const { return triangles_; }
  // The index of the triangle nearest p (ties: the smaller index), its squared
  // distance in `*distance2` if given; kNone if there are none. Past `cell_budget`
  // cells the search stops with the nearest seen so far (kNone if none).
  uint32_t nearest(const Vec3& p, double* distance2 = nullptr, size_t cell_budget = SIZE_MAX) const;

 private:
  // The cell along axis k of coordinate x, clamped to the grid (any x, NaN too).
  int cell_index(double x, int k) const {
    const double f = std::floor((x - origin_[k]) / cell_);
    return f >= 0 ? (f < double(dims_[k] - 1) ? int(f) : dims_[k] - 1) : 0;
  }
  size_t cell_of(int x, int y, int z) const {
    return (size_t(z) * size_t(dims_[1]) + size_t(y)) * size_t(dims_[0]) + size_t(x);
  }
  std::vector<Triangle3> triangles_;
  std::vector<uint32_t> cell_start_, cell_entries_;  // CSR: the triangles of each cell
  Vec3 origin_;
  double cell_ = 1;
  int dims_[3] = {1, 1, 1};
};

}  // namespace tetlod
