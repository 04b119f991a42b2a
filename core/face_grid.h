// Ids in the cells of a uniform grid over a fixed box, each in every cell its bounding
// box touches, for a set of boxes that changes: entries are only added; one whose box
// moved or went away stays where it was until clear(), and the caller skips what it no
// longer holds. For the simplifier's boundary faces (core/simplify.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace tetlod {

class FaceGrid {
 public:
  // Empties the grid and lays cells of about `cell` (made larger if the box would
  // need more than `max_cells`) over the box [lo, hi].
  void reset(const Vec3& lo, const Vec3& hi, double cell, size_t max_cells) {
    lo_ = lo;
    cell_ = cell > 0 && std::isfinite(cell) ? cell : 1;
    for (;;) {
      size_t count = 1;
      for (int k = 0; k < 3; ++k) {
        const double n = std::floor((hi[k] - lo[k]) / cell_) + 1;
        dims_[k] = n < 1 ? 1 : (n < 1e6 ? int(n) : 1000000);
        count *= size_t(dims_[k]);
      }
      if (count <= std::max<size_t>(max_cells, 1)) break;
      cell_ *= 1.5;
    }
    for (auto& c : cells_) c.clear();
    cells_.resize(size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]));
    entries_ = 0;
  }

  size_t entries() const { return entries_; }
  double cell() const { return cell_; }

  // Adds `id` to every cell that the box [lo, hi] touches.
  void insert(uint32_t id, const Vec3& lo, const Vec3& hi) {
    int from[3], to[3];
    range(lo, hi, from, to);
    for (int z = from[2]; z <= to[2]; ++z)
      for (int y = from[1]; y <= to[1]; ++y)
        for (int x = from[0]; x <= to[0]; ++x) {
          cells_[index(x, y, z)].push_back(id);
          ++entries_;
        }
  }

  // Appends to `ids` every id in the cells that the box [lo, hi] touches (an id may
  // come more than once), as long as there are at most `budget` of them; returns
  // false, with `ids` incomplete, if there are more.
  bool gather(const Vec3& lo, const Vec3& hi, size_t budget, std::vector<uint32_t>* ids) const {
    int from[3], to[3];
    range(lo, hi, from, to);
    for (int z = from[2]; z <= to[2]; ++z)
      for (int y = from[1]; y <= to[1]; ++y)
        for (int x = from[0]; x <= to[0]; ++x) {
          const std::vector<uint32_t>& cell = cells_[index(x, y, z)];
          if (ids->size() + cell.size() > budget) return false;
          ids->insert(ids->end(), cell.begin(), cell.end());
        }
    return true;
  }

 private:
  int clamp(double x, int k) const {
    const double f = std::floor((x - lo_[k]) / cell_);
    return f >= 0 ? (f < double(dims_[k] - 1) ? int(f) : dims_[k] - 1) : 0;
  }
  void range(const Vec3& lo, const Vec3& hi, int* from, int* to) const {
    for (int k = 0; k < 3; ++k) {
      from[k] = clamp(lo[k], k);
      to[k] = clamp(hi[k], k);
    }
  }
  size_t index(int x, int y, int z) const {
    return (size_t(z) * size_t(dims_[1]) + size_t(y)) * size_t(dims_[0]) + size_t(x);
  }

  std::vector<std::vector<uint32_t>> cells_;
  Vec3 lo_;
  double cell_ = 1;
  int dims_[3] = {1, 1, 1};
  size_t entries_ = 0;
};

}  // namespace tetlod
