// Derived connectivity of a TetMesh: vertex -> tets in CSR form, and the face
// neighbours of each tet. Both are rebuilt from the flat arrays whenever needed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tetlod {

// tets_of(v) lists, in increasing order, the tets that use vertex v.
struct VertexTets {
  std::vector<uint32_t> offsets;  // vertex_count + 1 entries
  std::vector<uint32_t> tets;

  const uint32_t* begin(uint32_t v) const { return tets.data() + offsets[v]; }
  const uint32_t* end(uint32_t v) const { return tets.data() + offsets[v + 1]; }
  uint32_t count(uint32_t v) const { return offsets[v + 1] - offsets[v]; }
};

VertexTets build_vertex_tets(const TetMesh& mesh);

// Whether the tets round an edge (a, b), whose ends' stars hold star_a and star_b tets,
// are better found in b's star than in a's: only where a's is far larger (a node every
// tet of a fan has; walking its star for each of its edges takes time quadratic in its
// valence). Stars of tens of tets, as meshes have, always give a's (and its order).
inline bool ring_from_other_end(size_t star_a, size_t star_b) {
  return star_a > 512 && star_a > 4 * star_b;
}

// What went wrong while matching tet faces, if anything.
struct FaceProblem {
  enum class Kind { kNone, kNonManifold, kOverlap };
  Kind kind = Kind::kNone;
  uint32_t tet_a = kInvalidIndex;  // two of the tets involved
  uint32_t tet_b = kInvalidIndex;
};

// neighbors[4*t + i] is the tet across the face of t opposite corner i, or
// kInvalidIndex where that face is on the boundary. Detects faces shared by three
// or more tets (kNonManifold) and pairs of tets on the same side of a shared face
// (kOverlap, i.e. inverted or overlapping tets); the first one found is returned
// and `neighbors` is then incomplete. Tets must be positively oriented.
FaceProblem build_face_neighbors(const TetMesh& mesh, std::vector<uint32_t>* neighbors);

struct MeshAdjacency {
  VertexTets vertex_tets;
  std::vector<uint32_t> tet_neighbors;  // 4 per tet, see build_face_neighbors
};

// Precondition: the mesh passed validate_mesh() (which rejects face problems).
MeshAdjacency build_adjacency(const TetMesh& mesh);

}  // namespace tetlod
