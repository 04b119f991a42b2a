// How a mesh made from another keeps what that one has, whatever tool made it: each
// material's volume, and how far each material pair's surface (an interface, or a
// material's outer boundary) moved. For `tetlod compare` and bench_compare.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/tet_mesh.h"

namespace tetlod {

struct MaterialVolumes {
  int32_t material = 0;
  double before = 0, after = 0;  // 0 where the mesh has no tet of it
};

// (inner, outer) materials of a surface triangle; outer kOutsideMaterial: the boundary.
using MaterialPair = std::pair<int32_t, int32_t>;

struct PairDeviation {
  MaterialPair pair;
  // A two-sided estimate of the Hausdorff distance between the two meshes' triangles
  // of the pair: the largest distance from the corners, edge midpoints and centroids of
  // one side's triangles to the nearest triangle of the same pair on the other side.
  double distance = 0;
};

// The topology a remesher must keep (the paper's constraints): how many connected
// pieces a material has (its tets joined through shared faces), and the Euler
// characteristic V - E + F of each pair's surface (a sphere's 2, a torus's 0; it
// changes where a surface is pinched, punctured or merged).
struct MaterialPieces {
  int32_t material = 0;
  long before = 0, after = 0;
};
struct PairEuler {
  MaterialPair pair;
  long before = 0, after = 0;
};

struct MeshComparison {
  std::vector<MaterialVolumes> volumes;  // every material of either mesh, by id
  std::vector<PairDeviation> pairs;      // pairs both meshes have, by pair
  std::vector<MaterialPair> lost;        // pairs only `before` has
  std::vector<MaterialPair> added;       // pairs only `after` has
  std::vector<MaterialPieces> pieces;    // every material of either mesh (0: none), by id
  std::vector<PairEuler> euler;          // pairs both meshes have, by pair
};

MeshComparison compare_meshes(const TetMesh& before, const TetMesh& after);

// Which of AFTER's materials are BEFORE's, by name, when both files name them (another
// tool may number the same materials differently: Gmsh's physical tags, Abaqus sets).
// A material of AFTER whose name BEFORE has is matched to BEFORE's id for it; one
// without a name, or with a name BEFORE does not have, keeps its id. Nothing is matched
// (ids are used, and `why_by_id` says why) if either list is empty, a name is given to
// two materials of one file, or two of AFTER's materials would become one.
struct MaterialMatch {
  std::vector<std::pair<int32_t, int32_t>> renumbered;  // (AFTER's id, BEFORE's id), ids differ
  std::string why_by_id;                                // empty if names were used
  size_t by_name = 0;  // AFTER's materials (with tets) matched by their name
  // AFTER's materials (with tets) whose name BEFORE does not have: matched by id.
  std::vector<MaterialName> names_only_after;
};
MaterialMatch match_materials_by_name(const std::vector<MaterialName>& before_names,
                                      const TetMesh& after,
                                      const std::vector<MaterialName>& after_names);

// Gives AFTER's tets (and its names list, sorted again) BEFORE's ids as `match` says.
void renumber_materials(const MaterialMatch& match, TetMesh* mesh,
                        std::vector<MaterialName>* names);

}  // namespace tetlod
