// Local property control (paper, section IV.C): the target element size tau_SZ as a
// field over the mesh, combining uniform, region-based and material-based sizing.
//
// The size allowed for a tet of material m whose centroid is p is the minimum of
//   - the uniform size,
//   - the size given for material m, if any (so an interface, whose triangles belong
//     to tets of both materials, gets the smaller of the two: Fig. 4(e)),
//   - every region rule that applies at p: a radial rule around a point or an axis
//     (size = size0 + growth * distance, Fig. 4(d)), or a box (size inside it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/size_map.h"
#include "core/status.h"
#include "core/tet_mesh.h"
#include "core/vec3.h"

namespace tetlod {

struct SizingField {
  struct Radial {
    Vec3 center;
    Vec3 axis;  // zero: distance from the point; else distance from the line through
                // `center` along `axis` (normalised on parse)
    double size0 = 0;
    double growth = 0;  // size per unit distance, >= 0
    bool operator==(const Radial& o) const {
      return center == o.center && axis == o.axis && size0 == o.size0 && growth == o.growth;
    }
  };
  struct Box {
    Vec3 low, high;
    double size = 0;
    bool operator==(const Box& o) const { return low == o.low && high == o.high && size == o.size; }
  };

  double uniform = std::numeric_limits<double>::infinity();
  std::vector<std::pair<int32_t, double>> material_sizes;  // sorted by material, unique
  std::vector<Radial> radial;
  std::vector<Box> boxes;
  std::shared_ptr<const SizeMap> map;  // may be null; shared by copies, never changed

  // tau_SZ for a tet of `material` with centroid `p`; +inf if nothing limits it.
  double size_at(const Vec3& p, int32_t material) const;
  // size_at() in two parts, for a caller that evaluates many positions: the part that
  // does not depend on the position (the smaller of the uniform size and the size of
  // `material`), then the region rules at n points (x[i], y[i], z[i]), each size[i]
  // made the smaller of itself and every rule that applies there. size_at(p, m) is
  // apply_regions() on material_size(m), so the two give the same value to the bit.
  double material_size(int32_t material) const;
  void apply_regions(size_t n, const double* x, const double* y, const double* z,
                     double* size) const;
  // True if any radial or box rule or a size map is set (sizes that depend on the
  // position).
  bool has_region_rules() const { return !radial.empty() || !boxes.empty() || map; }
  // The smallest size any rule can give (a lower bound of size_at), for diagnostics.
  double smallest_size() const;
  // True if any material, radial or box rule or a size map is set (besides the
  // uniform size).
  bool has_local_rules() const;
  // True if no rule is set.
  bool unlimited() const;
};

// A default uniform size for `mesh`, the viewer's starting tau_SZ: three times the
// median of its tets' sizes s_t (longest edges, metrics.h), rounded to two significant
// digits; 0 for a mesh without tets. Subdivision splits every edge longer than half the
// target size (paper, section II), so a size near the mesh's own edges would split most
// of them and the "simplified" mesh would come out larger than the input; at three
// times the median s_t, half the size is above about 90% of the edges of the bundled
// meshes and a first simplification coarsens each of them (motor 26512 -> 11649 tets at
// size 23, spheres 16088 -> 14222 at 2.3, box2 136 -> 12 at 2.3, at the tolerance
// 0.001 x the bounding-box diagonal). On a graded mesh, whose median is its fine parts'
// (a Gmsh antenna in an air sphere: 97,735 tets, median 0.76, air tets up to 29 long),
// subdivision at that size would multiply the air's tets (2.2 M tets at 2.3): there the
// size is raised, rounded up, until subdivision's estimated growth (each tet of longest
// edge L > s/2 making (2L/s)^3) is at most kSuggestedGrowth times the input (18 there),
// and so that at most kSuggestedAbove of the tets are above it (their long edges, where
// subdivision cannot split them within the valence, stay above the size).
// `raised` (may be null) says whether it was.
inline constexpr double kSuggestedGrowth = 2;
inline constexpr double kSuggestedAbove = 0.01;
double suggested_size(const TetMesh& mesh, bool* raised = nullptr);

// Parses "M=S,M=S,..." (material id, size) into field->material_sizes. Sizes must be
// finite and > 0; ids >= 0 and not repeated. Errors name the offending item.
Status parse_material_sizes(const std::string& spec, SizingField* field);

// Parses region rules separated by ';':
//   radial:cx,cy,cz,size0,growth            distance from a point
//   axis:cx,cy,cz,dx,dy,dz,size0,growth     distance from a line
//   box:x0,y0,z0,x1,y1,z1,size              inside an axis-aligned box
// and appends them to `field`. Errors name the offending rule and value.
Status parse_size_field(const std::string& spec, SizingField* field);

}  // namespace tetlod
