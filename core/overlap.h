// Tetrahedra that overlap without sharing a face.
//
// build_face_neighbors() refuses two tets on the same side of a face they share. Tets
// can also overlap with no face between them: one whose vertex number in the file is
// wrong reaches across the mesh, or a whole body is written twice. With every tet
// positively oriented, each point is covered as many times as the boundary (the faces
// that belong to one tet, oriented outwards) winds around it: this is the degree of
// the map from the tets to space. So if tets overlap, either the boundary crosses
// itself, or a part of it lies inside another part without crossing it.
// find_overlap() looks for both:
//  - within each piece (tets joined through shared vertices), two boundary triangles
//    that clearly cross: an edge of one passes through the inside of the other, its
//    ends and the crossing point farther than a small tolerance (1e-8 of the
//    triangles' size) from the other's plane and edges. Faces that touch, or lie in
//    one plane, are not crossings;
//  - with no crossing, the number of times a piece's boundary winds around a point just
//    inside one of its faces (the generalised winding number: solid angles over 4 pi)
//    is the same all along the face's sheet (faces joined through edges that no third
//    boundary face has), and is the number of times the tets cover that point: above
//    one and a half, tets overlap. One point per sheet (a tet whose vertex number is
//    wrong usually reaches through the mesh with its faces touching the boundary only
//    at vertices, so that nothing crosses: this finds it);
//  - at each boundary edge with two boundary faces, the tets around it fill less than a
//    full turn (the sum of their dihedral angles there): tets that wrap round the edge
//    overlap, and the sheet goes through itself along the edge, where no face crosses
//    another and the winding number just inside the sheet changes;
//  - at each boundary edge with more than two boundary faces (bodies meeting along it),
//    the wedges of the tets round it do not overlap (wedges_overlap());
//  - for each piece, a point well inside it (the centroid of its first tet with no
//    vertex on the boundary, else of its first tet) around which another piece
//    winds more than one half.
// Crossings between two pieces are not looked for: two volumes meshed apart along a
// curved surface overlap by a sliver by design (the chords of their two
// triangulations cut each other), and TetLOD reads such meshes as separate bodies.
// The cost is linear in the number of tets (a pass or two) and about linear in the
// number of boundary triangles: sparse grids of cells about the size of what they
// hold find the faces that may cross and the surfaces and pieces whose boxes hold a
// point, and a mesh has few sheets, each wound round one point. A work budget bounds
// the rest (faces crowding by the thousand into one cell, many nested surfaces).
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tetlod {

struct OverlapFinding {
  enum class Kind {
    kNone,
    kCrossing,  // tet_a and tet_b have boundary faces that cross
    kInside,    // a point inside tet_a, near its face or deep in its piece, is in tet_b too
  };
  Kind kind = Kind::kNone;
  uint32_t tet_a = kInvalidIndex;
  uint32_t tet_b = kInvalidIndex;
  // The checks stopped early, after a work budget proportional to the number of
  // boundary triangles (a hostile mesh whose boundary triangles all overlap one
  // another's bounding boxes would take quadratic time): what was checked passed.
  bool cut_short = false;
};

// `neighbors` as build_face_neighbors() made it for `mesh`, whose tets must all be
// positively oriented and match faces with no problem. The first finding is returned;
// the same mesh always gives the same finding.
OverlapFinding find_overlap(const TetMesh& mesh, const std::vector<uint32_t>& neighbors);

// Whether bodies that meet along an edge (u, v) overlap there: an edge with more than
// two boundary faces, each given by its third corner `w` and the corner `x` of its tet
// off the face. Round the edge, each face starts or ends the tets of its side (whether
// x is turned from w the right way round the edge), and where nothing overlaps they
// take turns; faces within 1e-9 radians of each other count as touching, an end before
// a start. No crossing of faces shows such an overlap when the faces only touch.
struct EdgeFace {
  Vec3 w, x;
};
// If they do, `*a` and `*b` are two faces whose wedges overlap.
bool wedges_overlap(const Vec3& u, const Vec3& v, const std::vector<EdgeFace>& faces,
                    size_t* a = nullptr, size_t* b = nullptr);

// The pieces find_overlap() checks one by one (tets joined through shared vertices), per
// vertex: the smallest vertex of its piece (a vertex in no tet is a piece of its own).
std::vector<uint32_t> vertex_pieces(const TetMesh& mesh);

}  // namespace tetlod
