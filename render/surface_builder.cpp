#include "render/surface_builder.h"

#include <algorithm>

#include "core/metrics.h"

namespace tetlod::render {
namespace {

// Per-tet flags of the first pass.
constexpr uint8_t kShownMaterial = 1;  // alive and of a shown material (ignores the cut)
constexpr uint8_t kVisible = 2;        // also on the kept side of the cut
constexpr uint8_t kHighlighted = 4;

void emit_face(const SurfaceInput& input, uint32_t tet, int corner,
               std::vector<SurfaceVertex>* out) {
  const Tet& t = input.tets[tet];
  const float stretch = input.values ? input.values[tet] : input.stretch[tet];
  const auto material = static_cast<uint32_t>(input.materials[tet]);
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = input.positions[t[kTetFace[corner][k]]];
    out->push_back({{float(p.x), float(p.y), float(p.z)}, stretch, material});
  }
}

}  // namespace

MaterialSet::MaterialSet(std::vector<int32_t> ids) : ids_(std::move(ids)) {
  std::sort(ids_.begin(), ids_.end());
  ids_.erase(std::unique(ids_.begin(), ids_.end()), ids_.end());
}

bool MaterialSet::lookup(int32_t material) const {
  return std::binary_search(ids_.begin(), ids_.end(), material);
}

std::pair<double, double> scalar_range(const std::vector<SurfaceVertex>& triangles) {
  if (triangles.empty()) return {0, 1};
  float lo = triangles[0].stretch, hi = lo;
  for (const SurfaceVertex& v : triangles) {
    lo = std::min(lo, v.stretch);
    hi = std::max(hi, v.stretch);
  }
  return {lo, hi > lo ? double(hi) : double(lo) * 1.001 + 1e-30};
}

void build_surface(const SurfaceInput& input, const SurfaceFilter& filter, SurfaceBuffers* out) {
  out->triangles.clear();
  out->highlight.clear();
  out->visible_tets = 0;
  out->highlighted_tets = 0;
  out->has_bounds = false;
  out->has_drawn_bounds = false;
  out->visible_materials.clear();
  out->visible.assign(input.tet_count, 0);

  const MaterialSet hidden(filter.hidden_materials);
  // The materials of the visible tets, one entry per run of a material.
  std::vector<int32_t>& seen = out->visible_materials;

  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  Vec3 drawn_lo = lo, drawn_hi = hi;  // of the tets the cut keeps
  uint8_t* visible = out->visible.data();
  for (size_t i = 0; i < input.tet_count; ++i) {
    if (input.alive && !input.alive[i]) continue;
    const int32_t material = input.materials[i];
    if (hidden.contains(material)) continue;
    const Tet& t = input.tets[i];
    const Vec3& a = input.positions[t[0]];
    const Vec3& b = input.positions[t[1]];
    const Vec3& c = input.positions[t[2]];
    const Vec3& d = input.positions[t[3]];
    for (const Vec3* p : {&a, &b, &c, &d}) {
      lo = {std::min(lo.x, p->x), std::min(lo.y, p->y), std::min(lo.z, p->z)};
      hi = {std::max(hi.x, p->x), std::max(hi.y, p->y), std::max(hi.z, p->z)};
    }
    uint8_t flags = kShownMaterial;
    if (cut_keeps(filter, a, b, c, d)) {
      flags |= kVisible;
      ++out->visible_tets;
      for (const Vec3* p : {&a, &b, &c, &d}) {
        drawn_lo = {std::min(drawn_lo.x, p->x), std::min(drawn_lo.y, p->y),
                    std::min(drawn_lo.z, p->z)};
        drawn_hi = {std::max(drawn_hi.x, p->x), std::max(drawn_hi.y, p->y),
                    std::max(drawn_hi.z, p->z)};
      }
      if (filter.highlight && input.stretch[i] < filter.highlight_below) {
        flags |= kHighlighted;
        ++out->highlighted_tets;
      }
      const int32_t m = std::max(material, 0);
      if (seen.empty() || seen.back() != m) seen.push_back(m);
    }
    visible[i] = flags;
  }
  if (lo.x <= hi.x) {
    out->has_bounds = true;
    out->bounds_min = lo;
    out->bounds_max = hi;
  }
  out->has_drawn_bounds = drawn_lo.x <= drawn_hi.x;
  if (out->has_drawn_bounds) {
    out->drawn_bounds_min = drawn_lo;
    out->drawn_bounds_max = drawn_hi;
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());

  for (size_t i = 0; i < input.tet_count; ++i) {
    const uint8_t flags = visible[i];
    if (!(flags & kVisible)) continue;
    const uint32_t* neighbors = input.neighbors + 4 * i;
    for (int corner = 0; corner < 4; ++corner) {
      const uint32_t other = neighbors[corner];
      if (other != kInvalidIndex && (visible[other] & kVisible)) continue;
      emit_face(input, static_cast<uint32_t>(i), corner, &out->triangles);
    }
    if (flags & kHighlighted)
      for (int corner = 0; corner < 4; ++corner)
        emit_face(input, static_cast<uint32_t>(i), corner, &out->highlight);
  }
}

}  // namespace tetlod::render
