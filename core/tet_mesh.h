// The flat multi-material tetrahedral mesh every part of TetLOD works on.
//
// Invariants of a mesh that passed validate_mesh() (every reader runs it):
//  - every tet index is < vertex_count(), the four ids of a tet are distinct;
//  - every tet is positively oriented: dot(b-a, cross(c-a, d-a)) > 0, which is
//    the convention of Gmsh, VTK and Medit/MMG;
//  - positions are finite; materials are >= 0; every vertex is used by a tet;
//  - no two tets have the same vertex set.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace tetlod {

using Tet = std::array<uint32_t, 4>;

inline constexpr uint32_t kInvalidIndex = 0xffffffffu;
// The region outside the mesh, used as the "other" material of boundary faces.
inline constexpr int32_t kOutsideMaterial = -1;

// Local vertex ids of the face opposite corner i, ordered so that the face
// normal (right-hand rule) points out of a positively oriented tet.
inline constexpr int kTetFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
// The six edges of a tet as pairs of local vertex ids.
inline constexpr int kTetEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

struct TetMesh {
  std::vector<Vec3> positions;
  std::vector<Tet> tets;
  std::vector<int32_t> materials;  // one per tet

  size_t vertex_count() const { return positions.size(); }
  size_t tet_count() const { return tets.size(); }
};

// A material's name in the file it was read from (a Gmsh physical volume's name;
// the MATERIAL of an Abaqus *SOLID SECTION, or its element set's name), so that a
// file written from the mesh can carry it again (io/mesh_io.h, WriteOptions::
// material_names; lod.h, histories). Lists of them are sorted by material.
struct MaterialName {
  int32_t material = 0;
  std::string name;
};

// The name of material m in `names` (sorted by material; may be null), or null.
inline const std::string* find_material_name(const std::vector<MaterialName>* names, int32_t m) {
  if (!names) return nullptr;
  size_t lo = 0, hi = names->size();
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if ((*names)[mid].material < m)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < names->size() && (*names)[lo].material == m ? &(*names)[lo].name : nullptr;
}

// Sorts a list of names by material, as find_material_name() needs.
inline void sort_by_material(std::vector<MaterialName>* names) {
  std::sort(names->begin(), names->end(),
            [](const MaterialName& a, const MaterialName& b) { return a.material < b.material; });
}

// Whether vertex v is a corner of tet t (branch-free: the simplifier's hot loops use it).
inline bool tet_has(const Tet& t, uint32_t v) {
  return static_cast<bool>(int{t[0] == v} | int{t[1] == v} | int{t[2] == v} | int{t[3] == v});
}

// The axis-aligned bounding box of the mesh's vertices (both the origin if it has none).
inline void mesh_bounds(const TetMesh& mesh, Vec3* lo, Vec3* hi) {
  *lo = *hi = mesh.positions.empty() ? Vec3{} : mesh.positions[0];
  for (const Vec3& p : mesh.positions) {
    *lo = {std::min(lo->x, p.x), std::min(lo->y, p.y), std::min(lo->z, p.z)};
    *hi = {std::max(hi->x, p.x), std::max(hi->y, p.y), std::max(hi->z, p.z)};
  }
}

// Where to move a mesh to compute on it: the centre of its box in each coordinate
// where that lies more than 8 half-diagonals from 0, else 0. Far from the origin the
// coordinates' rounding is far above the mesh's own scale (a part placed 1e7 away in
// a plant's coordinates keeps 1e-9 of its own size); there, a coordinate lies within
// 1/8 of the shift, so p - shift is exact (Sterbenz) and (p - shift) + shift gives p
// back, bit for bit.
inline Vec3 far_shift(const TetMesh& mesh) {
  if (mesh.positions.empty()) return {};
  Vec3 lo, hi;
  mesh_bounds(mesh, &lo, &hi);
  const Vec3 centre = (lo + hi) * 0.5;
  const double near = 8 * 0.5 * length(hi - lo);
  return {std::abs(centre.x) > near ? centre.x : 0.0, std::abs(centre.y) > near ? centre.y : 0.0,
          std::abs(centre.z) > near ? centre.z : 0.0};
}

// Six times the signed volume of the tet (a, b, c, d).
inline double signed_volume6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(b - a, cross(c - a, d - a));
}

inline double signed_volume6(const TetMesh& mesh, const Tet& t) {
  return signed_volume6(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                        mesh.positions[t[3]]);
}

}  // namespace tetlod
