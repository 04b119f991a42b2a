// A size map: target sizes given at the vertices of a tet mesh (as MMG3D takes them,
// in a Medit .sol file; io/sol.h), interpolated linearly inside each tet (P1). The
// size allowed for a tet is then the map's value at its centroid (sizing.h), as for
// the region rules: an adaptive loop (solve, estimate the error, remesh) gives the
// sizes its estimator wants where it wants them.
//
// A point is located by a walk from a tet listed in its cell of a uniform grid, with
// a scan of that cell's tets where the walk leaves the mesh; a point outside every tet
// takes the value of the nearest one it was compared with, its barycentric
// coordinates clamped. The value is a function of the point alone (not of the order
// of queries), and queries are const: threads may share a map.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/status.h"
#include "core/tet_mesh.h"
#include "core/vec3.h"

namespace tetlod {

class SizeMap {
 public:
  // A map over `mesh` (valid: positively oriented tets, see validate.h) with
  // sizes[v] at vertex v. Errors name the first size that is not a finite number > 0
  // ("size 12 (vertex 13) is -1: ...") or a count that does not match.
  static Status build(const TetMesh& mesh, std::vector<double> sizes,
                      std::shared_ptr<const SizeMap>* out);

  // The map's value at p.
  double at(const Vec3& p) const;
  // size[i] = min(size[i], at(x[i], y[i], z[i])) for i < n.
  void apply(size_t n, const double* x, const double* y, const double* z, double* size) const;

  double smallest() const { return smallest_; }
  double largest() const { return largest_; }
  size_t vertex_count() const { return vertex_count_; }
  size_t tet_count() const { return tets_.size(); }
  // What it was built from: build(source(), sizes()) makes the same map, value for
  // value (a history saves these; lod.h).
  const TetMesh& source() const { return source_; }
  const std::vector<double>& sizes() const { return sizes_; }

 private:
  // What a walk reads of a tet, in one place: barycentric coordinates of p are
  // l[1..3] = m * (p - origin), l[0] = 1 - l[1] - l[2] - l[3]; the sizes at its
  // corners; the tets across its faces (opposite each corner; kInvalidIndex: none).
  struct TetData {
    double ox, oy, oz;
    double m[9];
    double h[4];
    uint32_t across[4];
  };
  void barycentric(uint32_t t, const Vec3& p, double l[4]) const;
  double value(uint32_t t, const double l[4]) const;
  // The tet that holds p, or the one p is least outside of, walking from `t` (then
  // scanning p's cell of `tets_grid_`); l receives p's coordinates in it.
  uint32_t locate(const Vec3& p, uint32_t t, double l[4]) const;

  // A uniform grid over the mesh's box; a point outside it is in the nearest cell.
  struct Grid {
    Vec3 lo;
    double inverse_cell = 1;
    int dims[3] = {1, 1, 1};
    void lay(const Vec3& low, const Vec3& extent, double cell);
    size_t cells() const { return size_t(dims[0]) * size_t(dims[1]) * size_t(dims[2]); }
    size_t index(const Vec3& p) const;
    Vec3 center(size_t cell) const;
  };

  size_t vertex_count_ = 0;
  // In the order of their centroids along a Morton curve, so that a walk, and the
  // walks for points near each other, read tets near each other in memory.
  std::vector<TetData> tets_;
  // The tets whose bounding box touches each cell (CSR, in tet order), for the points
  // a walk does not reach.
  Grid tets_grid_;
  std::vector<uint32_t> cell_begin_, cell_tets_;
  // A finer grid, about four cells a tet, for the walks' starts: start_[c] holds the
  // centre of cell c, or is the tet that centre is least outside of.
  Grid start_grid_;
  std::vector<uint32_t> start_;
  double smallest_ = 0, largest_ = 0;
  TetMesh source_;  // positions and tets (no materials)
  std::vector<double> sizes_;
};

}  // namespace tetlod
