// Boundary and interface triangles of a multi-material tet mesh: the faces on the
// outer boundary and the faces between two tets of different materials.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/status.h"
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

// The surface triangles grouped by material pair, as writers carry them for boundary
// conditions (Gmsh physical surfaces, Medit triangle references, TetGen face
// markers, Abaqus node sets and element-face surfaces). One group per pair that
// has triangles: first the boundary of each material ("boundary_<m>"), by material,
// then each interface ("interface_<a>_<b>", a < b), by pair. Groups are numbered
// from first_surface_tag() up, in that order, so a group's tag is above every tag a
// writer gives a material and is the same in every format.
struct SurfaceGroup {
  int32_t material;                 // the smaller material of the pair
  int32_t other;                    // the larger one, kOutsideMaterial on the boundary
  int32_t tag;                      // >= first_surface_tag(mesh)
  std::string name;                 // "boundary_<m>" or "interface_<a>_<b>"
  std::vector<uint32_t> triangles;  // indices into the surface, increasing
};
struct SurfaceGroups {
  std::vector<SurfaceTriangle> surface;  // extract_surface() of the mesh
  std::vector<SurfaceGroup> groups;
};

// The Gmsh physical tag of material 0 (tags must be > 0): the smallest positive tag
// none of `materials` (distinct, increasing) uses. write_gmsh() numbers it so, and
// first_surface_tag() counts it.
int32_t gmsh_material_zero_tag(const std::vector<int32_t>& materials);

// 1 + the largest tag a writer gives a material: the largest material, or, when
// material 0 is present, the Gmsh tag it gets (the smallest positive tag no
// material uses) if that is larger. At least 1; may exceed the int32 range.
int64_t first_surface_tag(const TetMesh& mesh);

// A material pair's group under a name and tag of the user's own (an input file's
// surface group that is exactly that pair's boundary or interface).
struct SurfaceGroupName {
  int32_t material;  // the pair, as in SurfaceGroup
  int32_t other;
  int32_t tag;       // >= 1
  std::string name;  // "" keeps the generated name
};

// Precondition: the mesh passed validate_mesh(). The pairs in `names` take those
// tags and names; the others are numbered as above, skipping the tags `names` uses.
// An error, naming the largest material, when the tags would run past 2^31 - 1 (the
// largest tag Gmsh and Medit take); `groups` is then left as it was.
Status group_surface(const TetMesh& mesh, SurfaceGroups* groups,
                     const std::vector<SurfaceGroupName>* names = nullptr);

// A surface group of an input file (a Gmsh physical surface): its triangles by the
// positions of their corners.
struct InputSurfaceGroup {
  int32_t tag = 0;
  std::string name;  // "" if the file names none
  std::vector<std::array<Vec3, 3>> triangles;
};

// The input groups that are exactly one material pair's whole boundary or interface
// of `mesh` (every triangle of the pair, in any order and orientation, and no other),
// as names for group_surface(); the first such group of a pair wins. The others are
// listed in `unmatched` (e.g. a group covering part of a boundary, or several pairs).
std::vector<SurfaceGroupName> match_surface_groups(
    const TetMesh& mesh, const std::vector<InputSurfaceGroup>& input,
    std::vector<const InputSurfaceGroup*>* unmatched);

}  // namespace tetlod
