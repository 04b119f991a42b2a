// One picture of a mesh: what to show, how, from where, at what size. Used by the
// CLI (`tetlod render`, `tetlod report`) and the golden-image tests, so both go
// through exactly the same path.
#pragma once

#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "render/surface_builder.h"

namespace tetlod::render {

// A mesh with what drawing needs derived once: face neighbours, stretches and sizes.
struct PreparedMesh {
  TetMesh mesh;
  std::vector<uint32_t> neighbors;  // 4 per tet
  std::vector<float> stretch;       // per tet
  std::vector<float> size;          // per tet: its longest edge

  SurfaceInput surface_input() const;
};

// Precondition: `mesh` passed validate_mesh() (every reader runs it).
PreparedMesh prepare_mesh(TetMesh mesh);

struct ViewSpec {
  bool custom = false;  // use eye/target instead of `direction`
  ViewDirection direction = ViewDirection::kIso;
  Vec3 eye, target;
};

struct SnapshotSettings {
  int width = 800;
  int height = 800;
  SurfaceFilter filter;
  DrawSettings draw;
  ViewSpec view;
  // With ColorMode::kSize, the colour map spans the drawn faces' sizes (smallest to
  // largest) instead of draw.range_min..range_max.
  bool size_range_from_faces = true;
};

// The camera `view` gives for `buffers` in a width x height picture, and the part of it
// the scene is drawn in (render::frame_picture(), clear of the `legend`; the whole
// picture for a custom camera): framed on the drawn faces (what a cut leaves), else
// the shown materials' bounds, else the whole mesh's.
PictureFraming snapshot_framing(const PreparedMesh& mesh, const SurfaceBuffers& buffers,
                                const ViewSpec& view, int width, int height,
                                const LegendSpace& legend = {});

// Whether the GPU's float positions can hold `mesh`: every coordinate within
// +-1e30, and a bounding box at least 1e-30 across and at least 1e-5 of the largest
// coordinate (the readers accept edges from 1e-60 to 1e60, anywhere; beyond this a
// picture comes out empty or in pieces). The error names the mesh's extent and
// what to do.
Status check_drawable(const TetMesh& mesh);

// Builds the surface, uploads it, draws it and reads it back. `renderer` must be
// initialised on the current context. An empty image (width 0) if drawing failed:
// see renderer->last_error().
Image render_snapshot(Renderer* renderer, const PreparedMesh& mesh,
                      const SnapshotSettings& settings);

}  // namespace tetlod::render
