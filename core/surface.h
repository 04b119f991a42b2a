// Boundary and interface triangles of a multi-material tet mesh: the faces on the
// outer boundary and the faces between two tets of different materials.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/status.h"
#include "core/tet_mesh.h"
#include "core/triangle_grid.h"

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

// An edge of a surface triangle: its ends (a < b) and the triangle (an index).
struct SurfaceEdgeUse {
  uint32_t a, b, triangle;
};
// Every edge of every triangle of `surface`, sorted by (a, b, triangle), so that the
// triangles around an edge are consecutive.
std::vector<SurfaceEdgeUse> surface_edge_uses(const std::vector<SurfaceTriangle>& surface);

// The surface triangles grouped by material pair, as writers carry them for boundary
// conditions (Gmsh physical surfaces, Medit triangle references, TetGen face
// markers, Abaqus node sets and element-face surfaces). One group per pair that
// has triangles: first the boundary of each material ("boundary_<m>"), by material,
// then each interface ("interface_<a>_<b>", a < b), by pair. Groups are numbered
// from first_surface_tag() up, in that order, so a group's tag is above every tag a
// writer gives a material and is the same in every format.
struct SurfaceGroup {
  int32_t material;  // the smaller material of the pair (of its first triangle)
  int32_t other;     // the larger one, kOutsideMaterial on the boundary, material inside it
  int32_t tag;       // >= first_surface_tag(mesh)
  std::string name;  // "boundary_<m>" or "interface_<a>_<b>"
  std::vector<uint32_t> triangles;  // indices into the surface, increasing
};
struct SurfaceGroups {
  // extract_surface() of the mesh, then any faces inside a material that a group holds
  // (group_surface() with `inside`: inner == outer).
  std::vector<SurfaceTriangle> surface;
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

class SurfacePatches;

// The faces of `mesh` (a valid mesh) that the input groups' triangles inside a
// material (SurfacePatches::inside_entries()) are, found by their corners'
// positions: their corners, in the entries' order, leaving out any that is no face
// between two tets of one material of `mesh`. simplify() keeps these faces as they are.
std::vector<std::array<uint32_t, 3>> inside_faces(const TetMesh& mesh,
                                                  const SurfacePatches& patches);

// Precondition: the mesh passed validate_mesh(). An error, naming the largest
// material, when the tags would run past 2^31 - 1 (the largest tag Gmsh and Medit
// take); `groups` is then left as it was.
Status group_surface(const TetMesh& mesh, SurfaceGroups* groups);
// With the input's groups: each surface triangle that SurfacePatches::locate() puts
// in an input group goes to a group of that name and tag (in the order of the first
// material pair it touches, then of the input); the others are grouped by material
// pair as above, numbered around the input groups' tags (a pair whose triangles all
// went to input groups has no group). An input group whose triangles are exactly
// one pair's is so that pair's group under the input's name and tag. An unnamed
// input group is named after its pair if it is one pair's, else surface_<tag>.
// With `inside`, the groups' triangles inside one material
// (SurfacePatches::inside_entries()) that are faces of `mesh` go to their groups too,
// after the surface's triangles (material == other == that material; oriented as in
// the input, `tet` on their back side); an input group's interface triangles face the
// way the input's faced there (their `inner` is then the larger material); a group of such
// triangles only comes after the others. That is for the input's mesh itself (convert), and for the
// meshes made from it by simplify() and improve_mesh() with these patches, which keep those faces;
// a mesh made otherwise may keep only some of them.
//
// The input groups' triangles on `mesh`, as group_surface() finds them: `surface` is
// extract_surface(mesh, across), each triangle that an input group holds facing as
// the input's did there, then (with `inside`) the groups' faces inside one material
// that are faces of `mesh`; `label` gives each of the first boundary_count its group
// (an index into patches.groups()) or SurfacePatches::kNone; in_group[g] lists group
// g's triangles, increasing. `across`: the face neighbours of `mesh`'s tets.
struct LocatedGroups {
  std::vector<SurfaceTriangle> surface;
  size_t boundary_count = 0;
  std::vector<uint32_t> label;
  std::vector<std::vector<uint32_t>> in_group;
};
LocatedGroups locate_groups(const TetMesh& mesh, const SurfacePatches& patches, bool inside,
                            const std::vector<uint32_t>& across);

// `face_neighbors`, here and below: those of `mesh`'s tets (build_face_neighbors(), or
// ReadInfo::face_neighbors) if the caller has them; null to build them.
Status group_surface(const TetMesh& mesh, SurfaceGroups* groups, const SurfacePatches& patches,
                     bool inside = false, const std::vector<uint32_t>* face_neighbors = nullptr);

// A surface group of an input file (a Gmsh physical surface, a Medit triangle
// reference, a TetGen .face marker, an Abaqus *SURFACE): its triangles by the
// positions of their corners.
struct InputSurfaceGroup {
  int32_t tag = 0;
  std::string name;  // "" if the file names none
  std::vector<std::array<Vec3, 3>> triangles;
};

// The input file's surface groups laid on the surface of the mesh read with them, so
// that they can be found again on any mesh made from it (subdivided, simplified, a
// level of its history): every boundary and interface triangle of the input, with
// the smallest input group that holds it (by the positions of its corners; the first
// in the input's order among groups of one size). locate()
// gives a triangle of another mesh the group of the input triangle of the same
// material pair nearest its centroid: exact for the input's own triangles and for
// pieces of them, and right away from a group's border for a simplified surface,
// whose border curves the simplifier keeps (simplify() with these patches).
class SurfacePatches {
 public:
  static constexpr uint32_t kNone = 0xffffffffu;
  struct Group {
    int32_t tag = 0;
    std::string name;
    size_t triangles = 0;  // of the input surface
    size_t missing = 0;    // triangles of the group that are not faces of the input mesh
    size_t shared = 0;     // on it or inside, but held by a smaller group (not saved in histories)
    size_t inside = 0;     // faces of the input inside one material (not saved in histories)
  };
  // An input surface triangle and its group (kNone if in none).
  struct Entry {
    std::array<Vec3, 3> p;
    int32_t inner, outer;  // inner < outer, or outer == kOutsideMaterial
    uint32_t group;
  };
  SurfacePatches() = default;
  // `input` passed validate_mesh().
  SurfacePatches(const TetMesh& input, const std::vector<InputSurfaceGroup>& groups,
                 const std::vector<uint32_t>* face_neighbors = nullptr);
  // From the parts another one gave (a history file's): each entry's group < the
  // number of groups or kNone, its positions finite; an entry with inner == outer (and
  // a group) is one of inside_entries().
  SurfacePatches(std::vector<Group> groups, std::vector<Entry> entries);
  // Whether any input surface triangle is in a group.
  bool any() const { return any_; }
  const std::vector<Group>& groups() const { return groups_; }
  const std::vector<Entry>& entries() const { return entries_; }
  // The groups' triangles that are faces of the input between two tets of one
  // material (inner == outer == that material), each held by one group, as the input
  // gives their corners (simplify() keeps these faces; a history keeps them too).
  const std::vector<Entry>& inside_entries() const { return inside_; }
  // Forgets the triangles inside a material, for a run that need not keep them (it
  // writes no groups): simplify() then coarsens there too. Their groups count them as
  // missing.
  void drop_inside();
  // The group (index into groups()) of the triangle (a, b, c) between materials
  // `inner` and `outer` (kOutsideMaterial on the boundary), or kNone. With `reversed`:
  // whether the input's triangle there faces the other way (an entry in a group keeps
  // its group's corner order; the others face from `inner` to `outer`).
  uint32_t locate(const Vec3& a, const Vec3& b, const Vec3& c, int32_t inner, int32_t outer,
                  bool* reversed = nullptr) const;

 private:
  void build_index();
  // The entry whose corners are exactly a, b, c (in any order), or kNone.
  uint32_t find_exact(const Vec3& a, const Vec3& b, const Vec3& c) const;
  std::vector<Group> groups_;
  std::vector<Entry> entries_;
  std::vector<Entry> inside_;
  // (hash of an entry's sorted corners, entry), sorted: the input's own triangles,
  // and the pieces of a mesh made from it that kept their corners, are found here
  // without a search of the grids.
  std::vector<std::pair<uint64_t, uint32_t>> exact_;
  // Per material pair (sorted): a grid of its entries' triangles, and their entries.
  std::vector<std::pair<int32_t, int32_t>> pairs_;
  std::vector<TriangleGrid> grids_;
  std::vector<std::vector<uint32_t>> grid_entries_;
  bool any_ = false;
};

}  // namespace tetlod
