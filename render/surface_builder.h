// The triangles the renderer draws, built on the CPU in O(tets) over flat arrays:
// every face of a visible tet whose neighbour across it is missing (the boundary)
// or not visible (hidden material, cut away, retired by the LOD). Faces between
// two visible tets are never seen, so they are skipped; interfaces between a shown
// and a hidden material, and the faces the cut exposes, are drawn. Each triangle
// carries its tet's stretch and material, so one face shows one element.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/tet_mesh.h"

namespace tetlod::render {

// The plane dot(normal, x) = offset. The cut keeps whole tets whose centroid lies
// on the side dot(normal, c) <= offset and removes the others.
struct CutPlane {
  Vec3 normal{1, 0, 0};
  double offset = 0;
};

// A set of material ids looked up once per tet: a sorted list and the last answer
// (a mesh's tets come in runs of one material). Ids go up to 2^31 - 1, so there is
// no table by id.
class MaterialSet {
 public:
  MaterialSet() = default;
  explicit MaterialSet(std::vector<int32_t> ids);
  bool contains(int32_t material) const {
    if (material != last_ || !has_last_) {
      last_ = material;
      has_last_ = true;
      last_in_ = lookup(material);
    }
    return last_in_;
  }
  bool empty() const { return ids_.empty(); }

 private:
  bool lookup(int32_t material) const;

  std::vector<int32_t> ids_;
  mutable int32_t last_ = 0;
  mutable bool has_last_ = false;
  mutable bool last_in_ = false;
};

// Which tets are visible, and which are highlighted.
struct SurfaceFilter {
  std::vector<int32_t> hidden_materials;
  bool cut = false;
  CutPlane cut_plane;
  bool highlight = false;
  double highlight_below = 0;  // visible tets with stretch < this are highlighted
};

// Whether `filter`'s cut (if any) keeps the tet with corners a, b, c, d: its centroid
// on the kept side (build_surface() and build_group_overlay() agree on it).
inline bool cut_keeps(const SurfaceFilter& filter, const Vec3& a, const Vec3& b, const Vec3& c,
                      const Vec3& d) {
  // 4 * dot(n, centroid) against 4 * offset: no division per tet.
  return !filter.cut || dot(filter.cut_plane.normal, a + b + c + d) <= 4 * filter.cut_plane.offset;
}

// The arrays of one mesh state. Pointers must stay valid during build_surface().
struct SurfaceInput {
  const Vec3* positions = nullptr;
  const Tet* tets = nullptr;
  const int32_t* materials = nullptr;
  const uint8_t* alive = nullptr;       // null: every tet is alive
  const uint32_t* neighbors = nullptr;  // 4 per tet (core/adjacency.h), of this state
  const float* stretch = nullptr;       // one per tet (core/metrics.h)
  const float* values = nullptr;        // one per tet: the colour's scalar, if not stretch
  size_t vertex_count = 0;
  size_t tet_count = 0;
};

// One corner of a drawn triangle (20 bytes; the layout of the vertex buffer).
struct SurfaceVertex {
  float position[3];
  float stretch;      // of the face's tet (or SurfaceInput::values')
  uint32_t material;  // of the face's tet
};

// A range of vertices [begin, end) of a buffer that changed since it was last uploaded.
struct DirtyRange {
  size_t begin = 0;
  size_t end = 0;
  bool empty() const { return begin >= end; }
};

struct SurfaceBuffers {
  std::vector<SurfaceVertex> triangles;  // 3 per triangle, outward-facing
  std::vector<SurfaceVertex> highlight;  // all 4 faces of every highlighted tet
  size_t visible_tets = 0;
  size_t highlighted_tets = 0;
  // Bounds of the tets of shown materials, before the cut (for framing a camera, so
  // that moving the cut does not move the view). Empty if no tet is shown.
  bool has_bounds = false;
  Vec3 bounds_min, bounds_max;
  // Bounds of the tets drawn, the cut's leftovers (a picture of its own frames these).
  bool has_drawn_bounds = false;
  Vec3 drawn_bounds_min, drawn_bounds_max;
  // Materials of the visible tets, ascending (for the legend).
  std::vector<int32_t> visible_materials;
  // Scratch kept between builds so rebuilding does not allocate.
  std::vector<uint8_t> visible;
};

// The smallest and largest scalar of `triangles` (a range of some width where all are
// equal; {0, 1} if there are none): a colour map spanning the drawn faces.
std::pair<double, double> scalar_range(const std::vector<SurfaceVertex>& triangles);

// Rebuilds `out` completely: two passes over the tets, O(tets); `out`'s arrays keep
// their capacity between builds, so a rebuild does not reallocate them.
void build_surface(const SurfaceInput& input, const SurfaceFilter& filter, SurfaceBuffers* out);

}  // namespace tetlod::render
