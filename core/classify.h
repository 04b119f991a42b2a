// Vertex classification by the dimension of the feature a vertex lies on, as in
// CGAL's Tetrahedral_remeshing: corner (0), junction curve (1), boundary or
// interface surface (2), interior (3). A collapse may only move a vertex within
// its own feature; corners never move.
//
// Feature edges are the surface edges (edges of boundary/interface triangles) where
//  - a number of surface triangles other than two meet (three or more regions meet,
//    the outside counting as a region), or
//  - the two triangles separate different material pairs (or lie in different
//    patches: `patch` below), or
//  - the two triangles make a sharp crease: their normals differ by more than the
//    crease angle.
// A surface vertex is
//  - a corner if it has one or more than two feature edges, if its two feature edges
//    belong to different junctions (different sets of material pairs) or turn by more
//    than the crease angle, or if its surface neighbourhood is not one fan (two
//    sheets touching at a point);
//  - on a curve if it has exactly two feature edges otherwise;
//  - on a surface if it has none.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/surface.h"
#include "core/tet_mesh.h"

namespace tetlod {

enum class FeatureKind : uint8_t { kCorner = 0, kCurve = 1, kSurface = 2, kInterior = 3 };

const char* feature_kind_name(FeatureKind kind);

struct ClassifyOptions {
  double crease_angle_degrees = 40.0;
};

struct Classification {
  std::vector<FeatureKind> kind;                       // one per vertex
  std::vector<std::array<uint32_t, 2>> feature_edges;  // (a, b) with a < b, sorted
};

// `patch`, if given: one id per surface triangle (an input file's surface group,
// SurfacePatches); triangles of one material pair but different patches are then
// separate surfaces, as two pairs are, so the borders between patches are curves.
Classification classify_vertices(const TetMesh& mesh, const std::vector<SurfaceTriangle>& surface,
                                 const ClassifyOptions& options = {},
                                 const std::vector<uint32_t>* patch = nullptr);

}  // namespace tetlod
