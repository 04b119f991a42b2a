// A piecewise linear complex (PLC) — points, polygonal facets, region seeds — and
// its constrained quality tetrahedralization with TetGen.
//
// This header does not include tetgen.h: TetGen (AGPLv3) stays inside
// core/generate/tetgen_mesher.cpp.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

#include "core/status.h"
#include "core/tet_mesh.h"

namespace tetlod {

// A region seed: every tet of the closed region containing `seed` gets `material`.
struct PlcRegion {
  Vec3 seed;
  int32_t material = 0;
  double max_volume = -1;  // > 0: a volume bound for this region's tets (below the global one)
};

// The PLC in flat arrays. A facet is a planar set of polygons: the first one is
// normally the facet's outer loop, the others are loops or segments (two
// vertices) inside it that the mesh must respect. Facet f owns polygons
// [facet_first_polygon[f], facet_first_polygon[f + 1]); polygon p owns vertex ids
// polygon_vertices[polygon_first_vertex[p] .. polygon_first_vertex[p + 1]).
struct Plc {
  std::vector<Vec3> points;
  std::vector<uint32_t> polygon_vertices;
  std::vector<uint32_t> polygon_first_vertex{0};
  std::vector<uint32_t> facet_first_polygon{0};
  std::vector<int32_t> facet_markers;
  std::vector<PlcRegion> regions;

  size_t facet_count() const { return facet_markers.size(); }
  size_t polygon_count() const { return polygon_first_vertex.size() - 1; }

  uint32_t add_point(const Vec3& p) {
    points.push_back(p);
    return static_cast<uint32_t>(points.size() - 1);
  }
  // Appends a polygon to the facet under construction.
  void add_polygon(const uint32_t* vertices, size_t count);
  void add_polygon(std::initializer_list<uint32_t> vertices) {
    add_polygon(vertices.begin(), vertices.size());
  }
  void add_polygon(const std::vector<uint32_t>& vertices) {
    add_polygon(vertices.data(), vertices.size());
  }
  // Closes the facet under construction, which must hold at least one polygon.
  void close_facet(int32_t marker);
  // A facet made of one polygon.
  void add_facet(std::initializer_list<uint32_t> vertices, int32_t marker) {
    add_polygon(vertices);
    close_facet(marker);
  }
  void add_region(const Vec3& seed, int32_t material) { regions.push_back({seed, material}); }
};

struct TetgenParams {
  double max_volume = 0;  // TetGen `a`: no tet larger than this (> 0)
  double quality = 2.0;   // TetGen `q`: bound on circumradius / shortest edge (>= 1.2)
};

// Meshes `plc` with TetGen switches "pzq<quality>a<max_volume>AQ" (plus a bare "a" for
// the regional bounds when a region has max_volume > 0) and returns the tets
// with their region attribute as material, positively oriented, validated by
// validate_mesh() without repairs. The PLC's own points come first in mesh->positions,
// in order (when every point is a facet vertex and no two coincide), followed by the
// Steiner points TetGen added. Every closed region of the PLC must have a seed.
// TetGen runs in a forked child process (see tetgen_mesher.cpp), so its failures —
// intersecting facets, an assertion, a crash, out of memory — and an unseeded region
// come back as an error Status, with whatever TetGen printed; nothing is printed.
// POSIX (fork, pipes); may be called from any thread.
Status tetrahedralize_plc(const Plc& plc, const TetgenParams& params, TetMesh* mesh);

}  // namespace tetlod
