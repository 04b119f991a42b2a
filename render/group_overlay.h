// The input file's surface groups (Gmsh physical surfaces, Medit triangle references,
// Abaqus *SURFACEs, ...) drawn over the surface of a mesh made from it: the viewer's
// "Surface groups drawn" and `tetlod render --groups`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/surface.h"
#include "core/tet_mesh.h"
#include "render/colormap.h"
#include "render/surface_builder.h"

namespace tetlod::render {

struct GroupOverlay {
  struct Group {
    uint32_t index = 0;           // in SurfacePatches::groups()
    size_t first = 0, count = 0;  // its vertices in `vertices`
    size_t triangles = 0;         // on the mesh, drawn or not
    Rgb color{};                  // surface_group_rgb(index)
    std::string label;            // its name, or "surface <tag>" if it has none
  };
  std::vector<SurfaceVertex> vertices;  // 3 per triangle
  std::vector<Group> groups;            // the groups asked for, in the input's order
};

// The colour of the input's surface group `index`: a palette of 8, then generated_rgb()
// colours, cycled every kColorCycle (groups are drawn in stripes, which no material
// has).
Rgb surface_group_rgb(uint32_t index);

// A group's name for a key or a list: its name, or "surface <tag>".
std::string surface_group_label(const SurfacePatches::Group& group);

// The triangles of `mesh` that the input groups `shown` (indices into
// patches.groups(), increasing) hold, as group_surface() finds them (faces inside a
// material too), leaving out those with no tet on either side that `filter` shows
// (of a shown material, on the kept side of the cut). `neighbors`: the face
// neighbours of `mesh`'s tets.
GroupOverlay build_group_overlay(const TetMesh& mesh, const std::vector<uint32_t>& neighbors,
                                 const SurfacePatches& patches, const std::vector<uint32_t>& shown,
                                 const SurfaceFilter& filter);

}  // namespace tetlod::render
