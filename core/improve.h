// Shape improvement of a finished mesh within the four thresholds (beyond the paper,
// whose method only collapses): edge removals (3-2 flips and their generalisation to
// rings of up to 7 tets) and 2-3 flips inside one material, and moves of
// vertices towards the centroid of their neighbours: interior vertices freely, vertices
// inside a flat patch of a boundary or interface within its plane.
//
// References:
//  - B. Joe, "Construction of three-dimensional improved-quality triangulations using
//    local transformations", SIAM J. Sci. Comput. 1995: 2-3 and 3-2 flips.
//  - L. Freitag, C. Ollivier-Gooch, "Tetrahedral mesh improvement using swapping and
//    smoothing", IJNME 1997: flips accepted when the worst tet improves; smoothing.
//  - J. Shewchuk, "Two discrete optimization algorithms for the topological improvement
//    of tetrahedral meshes", 2002: edge removal (here by trying every triangulation of
//    rings of up to 7 tets).
//
// The guarantee (each change is checked on the tets it would make before it is done):
//  - every tet a change makes has stretch >= tau_ST and size <= its tau_SZ, and a
//    change that adds edges (a 2-3 flip, an edge removal on a ring of 4 or more tets)
//    never takes a node above tau_VL;
//  - a flip raises the lowest stretch of the tets it replaces; a move raises the lowest
//    stretch of the vertex's star, or keeps it and raises the star's total; except that
//    an edge removal or a move that replaces tets above their tau_SZ (input tets the
//    simplifier could not remove) by tets within every threshold is done even if the
//    lowest stretch falls (it stays >= tau_ST), so tets above the size only ever go;
//  - the boundary and interface triangles stay the same triangles (flips only replace
//    tets of one material by tets of the same material filling the same space), and
//    they stay where they were: only interior vertices move freely; a vertex inside a
//    flat patch (a surface vertex, not on a curve or corner, whose surface triangles
//    all lie in one plane) moves within that plane (up to rounding); no other moves.
//    So every region, interface, junction curve and corner keeps its place and shape,
//    and every material its volume (up to rounding);
//  - no vertex is added or removed; tets may change in number (an edge removal on a
//    ring of n tets makes 2(n-2) of them, a 2-3 flip adds one);
//  - with the input's surface groups, their faces inside a material (inside_faces(),
//    core/surface.h) stay as they are: their vertices do not move, no edge of theirs
//    is removed and no 2-3 flip replaces one of them.
// Deterministic: the same mesh and parameters give the same result, byte for byte.
#pragma once

#include <atomic>
#include <cstddef>

#include "core/simplify.h"
#include "core/surface.h"
#include "core/tet_mesh.h"

namespace tetlod {

// Output tets and nodes that break a threshold.
struct ThresholdCounts {
  size_t below_stretch = 0;  // tets with d_t < tau_ST
  size_t above_size = 0;     // tets with s_t > tau_SZ
  size_t above_valence = 0;  // nodes with valence > tau_VL
  size_t total() const { return below_stretch + above_size + above_valence; }
};

// The tets and nodes of `mesh` that break params' stretch, size and valence thresholds.
ThresholdCounts threshold_breaks(const TetMesh& mesh, const SimplifyParams& params);

struct ImproveResult {
  size_t edge_removals = 0;  // edges inside one material removed (3-2 flips and larger)
  size_t flips_23 = 0;       // triangles replaced by an edge with three tets around it
  size_t moves = 0;          // vertex moves
  int rounds = 0;            // rounds run (a round: edge removals, 2-3 flips, moves)
  // Over the whole mesh, before and after.
  double mean_stretch_before = 0, mean_stretch_after = 0;
  double min_stretch_before = 0, min_stretch_after = 0;
  ThresholdCounts breaks_before, breaks_after;  // after <= before, by the guarantee
};

// Improves `mesh` (valid: positively oriented tets, as every reader leaves it) under
// params.min_stretch, params.max_valence and params.sizing (the other fields are not
// used), for at most `max_rounds` rounds or until a round changes nothing. `cancel`, if
// set, stops between changes; the mesh is valid whenever it returns. `patches`, if
// given: the input file's surface groups, whose faces inside a material are kept.
ImproveResult improve_mesh(TetMesh* mesh, const SimplifyParams& params, int max_rounds = 4,
                           const std::atomic<bool>* cancel = nullptr,
                           const SurfacePatches* patches = nullptr);

// Lowers the valence of each of `nodes` (vertex ids of `mesh`) above params.max_valence
// by edge removals inside one material (as improve_mesh() makes them, with the same
// guarantee, but taking a removal whose new tets are within every threshold even if
// their lowest stretch is lower), until the node is within it or none of its edges can
// go; a removal never takes another node above max_valence. Tets may be renumbered;
// vertices keep their ids. Returns the removals made.
size_t shed_valence(TetMesh* mesh, const SimplifyParams& params, const std::vector<uint32_t>& nodes,
                    const std::atomic<bool>* cancel = nullptr,
                    const SurfacePatches* patches = nullptr);

}  // namespace tetlod
