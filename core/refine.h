// Uniform 1:8 ("red") refinement of a tet mesh (Bey, "Tetrahedral grid refinement",
// Computing 55, 1995): every edge is split at its midpoint; each tet becomes its four
// corner tets and four tets of the inner octahedron, cut along its shortest diagonal.
// Materials are inherited, so every material region, interface and boundary keeps its
// exact shape (flat facets stay flat), and the P1 space of the refined mesh contains
// the one of the input (nested spaces: a finite-element energy can only go down).
#pragma once

#include "core/tet_mesh.h"

namespace tetlod {

// Precondition: a valid mesh (tet_mesh.h). The result is valid too: 8x the tets,
// positively oriented; the input vertices keep their ids, edge midpoints follow.
TetMesh refine_uniform(const TetMesh& mesh);

}  // namespace tetlod
