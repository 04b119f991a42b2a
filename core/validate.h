// Validation of a freshly read mesh. Every reader calls validate_mesh() before
// handing a mesh out, so the rest of TetLOD can rely on the invariants listed in
// tet_mesh.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "core/tet_mesh.h"

namespace tetlod {

struct ValidationReport {
  size_t reoriented_tets = 0;          // negatively oriented tets that were flipped
  size_t removed_unused_vertices = 0;  // vertices no tet used, dropped
  // Where some were: the index each kept vertex had before (for data given by vertex
  // of the file, as a size map is); empty where none was dropped.
  std::vector<uint32_t> kept_vertices;
  // Vertices at exactly the position of an other vertex (not repaired: the mesh is
  // not conforming there, e.g. two volumes meshed apart), and the first position.
  size_t coincident_vertices = 0;
  Vec3 coincident_position;
  // The search for tets that overlap with no face between them stopped early (see
  // core/overlap.h): the part it saw passed.
  bool overlap_check_cut_short = false;
};

// Checks and repairs `mesh` in place:
//  - errors: materials.size() != tets.size(), an index out of range, a tet with a
//    repeated vertex, a non-finite coordinate, a negative material id, a tet whose
//    longest edge is outside [1e-60, 1e60] (the metrics would under- or overflow), a
//    tet of zero volume (|6V| <= 1e-12 * longest_edge^3), two tets with the same vertex set, a
//    face shared by three or more tets, two tets overlapping across a shared face,
//    tets overlapping with no face between them (find_overlap(), core/overlap.h);
//  - repairs (counted in `report`): negatively oriented tets are reoriented by
//    swapping their last two vertices; unused vertices are removed and tets renumbered;
//  - counted only: vertices at the position of another.
// `source` names the input in messages ("path"); `tet_lines`, when not empty, holds
// the 1-based line of each tet in the file so that messages read "path:line: ...".
// On error the mesh is left in an unspecified but destructible state.
// `face_neighbors`, if not null, receives the face neighbours of the valid mesh's tets
// (build_face_neighbors(), core/adjacency.h), which the checks build anyway.
Status validate_mesh(TetMesh* mesh, const std::string& source,
                     const std::vector<uint32_t>& tet_lines, ValidationReport* report,
                     std::vector<uint32_t>* face_neighbors = nullptr);

}  // namespace tetlod
