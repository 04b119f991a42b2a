// Whether two triangles clearly cross: the test find_overlap() (core/overlap.h) runs on
// a mesh's boundary, and the simplifier on the boundary triangles a collapse would make,
// so that what one writes the other reads.
#pragma once

#include "core/triangle_grid.h"
#include "core/vec3.h"

namespace tetlod {

// A triangle's plane (unit normal, through its first corner) and the tolerance of a
// clear crossing: 1e-8 of its longest edge, plus what rounding far from the origin can
// reach. A degenerate triangle has a zero normal, and crosses nothing.
struct TrianglePlane {
  Vec3 normal;
  double offset = 0;  // dot(normal, corner)
  double delta = 0;
};

TrianglePlane plane_of(const Triangle3& t);

// Whether triangles s and t (with their planes) clearly cross: an edge of one passes
// through the inside of the other, its ends and the crossing point farther than the
// larger tolerance from the other's plane and edges. Triangles that only touch (at a
// shared corner or edge too), or lie in one plane, do not cross.
bool triangles_cross(const Triangle3& s, const TrianglePlane& ps, const Triangle3& t,
                     const TrianglePlane& pt);

}  // namespace tetlod
