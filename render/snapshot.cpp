#include "render/snapshot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "core/adjacency.h"
#include "core/metrics.h"

namespace tetlod::render {

SurfaceInput PreparedMesh::surface_input() const {
  SurfaceInput input;
  input.positions = mesh.positions.data();
  input.tets = mesh.tets.data();
  input.materials = mesh.materials.data();
  input.neighbors = neighbors.data();
  input.stretch = stretch.data();
  input.vertex_count = mesh.vertex_count();
  input.tet_count = mesh.tet_count();
  return input;
}

PreparedMesh prepare_mesh(TetMesh mesh) {
  PreparedMesh prepared;
  prepared.mesh = std::move(mesh);
  build_face_neighbors(prepared.mesh, &prepared.neighbors);
  const TetMesh& m = prepared.mesh;
  prepared.stretch.resize(m.tet_count());
  prepared.size.resize(m.tet_count());
  for (size_t t = 0; t < m.tet_count(); ++t) {
    const TetShape shape = tet_shape(m, m.tets[t]);
    prepared.stretch[t] = static_cast<float>(shape.stretch);
    prepared.size[t] = static_cast<float>(shape.size);
  }
  return prepared;
}

PictureFraming snapshot_framing(const PreparedMesh& mesh, const SurfaceBuffers& buffers,
                                const ViewSpec& view, int width, int height,
                                const LegendSpace& legend) {
  // What is drawn (a cut's leftovers); else the shown materials'; else the whole mesh.
  Vec3 lo = buffers.has_drawn_bounds ? buffers.drawn_bounds_min : buffers.bounds_min;
  Vec3 hi = buffers.has_drawn_bounds ? buffers.drawn_bounds_max : buffers.bounds_max;
  if (!buffers.has_bounds) {
    lo = hi = mesh.mesh.positions.empty() ? Vec3{} : mesh.mesh.positions[0];
    for (const Vec3& p : mesh.mesh.positions) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
  }
  if (view.custom) return {look_at_camera(view.eye, view.target, lo, hi), {0, 0, width, height}};
  // The drawn faces' corners, so that a round model fills the picture, not its box.
  std::vector<Vec3> points;
  if (buffers.has_drawn_bounds) {
    points.reserve(buffers.triangles.size());
    for (const SurfaceVertex& v : buffers.triangles)
      points.push_back({v.position[0], v.position[1], v.position[2]});
  }
  return frame_picture(lo, hi, view.direction, width, height, legend, points);
}

Status check_drawable(const TetMesh& mesh) {
  double largest = 0;
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  if (!mesh.positions.empty()) lo = hi = mesh.positions[0];
  for (const Vec3& p : mesh.positions) {
    largest = std::max({largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double extent = length(hi - lo);
  if (mesh.positions.empty() || (largest <= 1e30 && extent >= 1e-30 && extent >= 1e-5 * largest))
    return Status();
  char text[320];
  std::snprintf(text, sizeof text,
                "cannot draw a mesh %.3g across with coordinates up to %.3g: pictures hold "
                "coordinates within 1e30, meshes at least 1e-30 across, and at least 1e-5 of "
                "their distance from the origin (GPU positions have 7 digits; rescale or "
                "move it)",
                extent, largest);
  return Status::error(text);
}

Image render_snapshot(Renderer* renderer, const PreparedMesh& mesh,
                      const SnapshotSettings& settings) {
  SurfaceBuffers buffers;
  SurfaceInput input = mesh.surface_input();
  const bool by_size = settings.draw.color_mode == ColorMode::kSize;
  if (by_size) input.values = mesh.size.data();
  build_surface(input, settings.filter, &buffers);
  renderer->upload(buffers);
  DrawSettings draw = settings.draw;
  if (by_size && settings.size_range_from_faces && !buffers.triangles.empty())
    std::tie(draw.range_min, draw.range_max) = scalar_range(buffers.triangles);
  if (settings.filter.highlight) draw.highlight_below = settings.filter.highlight_below;
  const PictureFraming framing =
      snapshot_framing(mesh, buffers, settings.view, settings.width, settings.height,
                       renderer->legend_space(draw, settings.width, settings.height));
  if (!renderer->draw(draw, framing.camera, settings.width, settings.height, &framing.scene))
    return {};
  return renderer->read_pixels();
}

}  // namespace tetlod::render
