// The paper's Table I row (Date et al., "Properties of resulting meshes") for a
// whole mesh and per material, plus a stretch histogram.
#pragma once

#include <cstdint>
#include <vector>

#include "core/adjacency.h"
#include "core/tet_mesh.h"

namespace tetlod {

struct PropertyRow {
  size_t nodes = 0;
  size_t edges = 0;
  size_t elements = 0;
  double average_stretch = 0;
  double min_stretch = 0;
  uint32_t max_valence = 0;  // most edge neighbours of one node
  double max_size = 0;       // longest edge
  double volume = 0;
};

struct MaterialRow {
  int32_t material = 0;
  PropertyRow row;  // of the sub-mesh made of this material's tets alone
};

inline constexpr int kStretchBins = 10;  // bins of width 0.1 over [0, 1]

struct MeshStats {
  PropertyRow whole;
  std::vector<MaterialRow> per_material;    // sorted by material id
  std::vector<uint64_t> stretch_histogram;  // kStretchBins counts, whole mesh
};

// Histogram bin of a stretch value: [0, 0.1) -> 0 ... [0.9, 1] -> 9; below 0 -> 0.
int stretch_bin(double stretch);

MeshStats compute_mesh_stats(const TetMesh& mesh, const VertexTets& vertex_tets);

// Each material's volume (the sum of its tets' signed volumes), by material id.
struct MaterialVolume {
  int32_t material = 0;
  double volume = 0;
};
std::vector<MaterialVolume> material_volumes(const TetMesh& mesh);

// Each material's volume and the area of its surface (its tets' faces on the boundary
// or on an interface with another material), by material id. Twice the one over the
// other is how thick the material is where it is a layer: a slab t thick gives t
// (its edges aside), a wire of radius r gives r, a ball 2r/3. Precondition: the mesh
// passed validate_mesh().
struct MaterialSurface {
  int32_t material = 0;
  double volume = 0;
  double area = 0;
  double thickness() const { return area > 0 ? 2 * volume / area : 0; }
};
std::vector<MaterialSurface> material_surfaces(const TetMesh& mesh);

}  // namespace tetlod
