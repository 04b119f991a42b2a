// Boundary and interface triangles of a multi-material tet mesh: the faces on the
// outer boundary and the faces between two tets of different materials.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/adjacency.h"
#include "core/tet_mesh.h"

namespace tetlod {

struct SurfaceTriangle {
  std::array<uint32_t, 3> v;  // oriented so its normal points from `inner` to `outer`
  int32_t inner;              // material on the back side
  int32_t outer;              // material on the front side, kOutsideMaterial on the boundary
  uint32_t tet;               // the tet of material `inner` the face belongs to
  uint8_t corner;             // that tet's corner opposite the face
};

// One triangle per boundary face and per interface face (the latter seen from the
// tet of the smaller material id, so inner < outer), in order of (tet, corner).
std::vector<SurfaceTriangle> extract_surface(const TetMesh& mesh,
                                             const std::vector<uint32_t>& tet_neighbors);

}  // namespace tetlod
