// Morton (Z-order) keys: 21 bits of each coordinate interleaved, for sorting points
// (vertices, centroids) so that those near each other in space are near each other in
// memory.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/vec3.h"

namespace tetlod {

// The low 21 bits of v spread to every third bit of 63.
inline uint64_t morton_spread(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// The key of q, a finite point scaled to [0, 2^21 - 1] in each coordinate (a coordinate
// outside is clamped; the integer part counts).
inline uint64_t morton_key(const Vec3& q) {
  auto cell = [](double x) { return static_cast<uint64_t>(std::clamp(x, 0.0, 2097151.0)); };
  return morton_spread(cell(q.x)) | morton_spread(cell(q.y)) << 1 | morton_spread(cell(q.z)) << 2;
}

}  // namespace tetlod
