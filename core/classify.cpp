#include "core/classify.h"

#include <algorithm>
#include <cmath>

namespace tetlod {

const char* feature_kind_name(FeatureKind kind) {
  switch (kind) {
    case FeatureKind::kCorner:
      return "corner";
    case FeatureKind::kCurve:
      return "curve";
    case FeatureKind::kSurface:
      return "surface";
    case FeatureKind::kInterior:
      return "interior";
  }
  return "?";
}

namespace {

uint64_t material_pair_key(const SurfaceTriangle& t) {
  return (uint64_t{static_cast<uint32_t>(t.inner)} << 32) | static_cast<uint32_t>(t.outer);
}

Vec3 triangle_normal(const TetMesh& mesh, const SurfaceTriangle& t) {
  const Vec3& p = mesh.positions[t.v[0]];
  return cross(mesh.positions[t.v[1]] - p, mesh.positions[t.v[2]] - p);
}

double angle_between(const Vec3& x, const Vec3& y) {
  const double denominator = length(x) * length(y);
  if (!(denominator > 0)) return M_PI;  // degenerate: treat as sharp
  return std::acos(std::clamp(dot(x, y) / denominator, -1.0, 1.0));
}

// Per vertex: how many feature edges, and the first two (other end, junction signature).
struct VertexFeatures {
  uint32_t count = 0;
  uint32_t other[2] = {kInvalidIndex, kInvalidIndex};
  uint64_t signature[2] = {0, 0};
};

void add_feature(VertexFeatures& f, uint32_t other, uint64_t signature) {
  if (f.count < 2) {
    f.other[f.count] = other;
    f.signature[f.count] = signature;
  }
  ++f.count;
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

Classification classify_vertices(const TetMesh& mesh, const std::vector<SurfaceTriangle>& surface,
                                 const ClassifyOptions& options,
                                 const std::vector<uint32_t>* patch) {
  const size_t vertex_count = mesh.vertex_count();
  const double crease = options.crease_angle_degrees * M_PI / 180.0;
  Classification result;
  result.kind.assign(vertex_count, FeatureKind::kInterior);
  for (const SurfaceTriangle& t : surface)
    for (uint32_t v : t.v) result.kind[v] = FeatureKind::kSurface;

  const std::vector<SurfaceEdgeUse> uses = surface_edge_uses(surface);

  std::vector<VertexFeatures> features(vertex_count);
  std::vector<std::pair<uint64_t, uint32_t>> pairs;  // (material pair, patch)
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    pairs.clear();
    for (size_t k = i; k < j; ++k) {
      const uint32_t t = uses[k].triangle;
      pairs.push_back({material_pair_key(surface[t]), patch ? (*patch)[t] : 0});
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    bool feature = (j - i) != 2 || pairs.size() != 1;
    if (!feature) {
      const Vec3 n0 = triangle_normal(mesh, surface[uses[i].triangle]);
      const Vec3 n1 = triangle_normal(mesh, surface[uses[i + 1].triangle]);
      feature = angle_between(n0, n1) > crease;
    }
    if (feature) {
      uint64_t signature = 1469598103934665603ull;  // FNV-1a over the sorted pairs
      for (const auto& [p, id] : pairs) {
        signature = (signature ^ p) * 1099511628211ull;
        if (id != 0) signature = (signature ^ id) * 1099511628211ull;  // 0: as without patches
      }
      result.feature_edges.push_back({uses[i].a, uses[i].b});
      add_feature(features[uses[i].a], uses[i].b, signature);
      add_feature(features[uses[i].b], uses[i].a, signature);
    }
    i = j;
  }

  // Vertex -> surface triangles (CSR), for the one-fan test.
  std::vector<uint32_t> offsets(vertex_count + 1, 0);
  for (const SurfaceTriangle& t : surface)
    for (uint32_t v : t.v) ++offsets[v + 1];
  for (size_t v = 0; v < vertex_count; ++v) offsets[v + 1] += offsets[v];
  std::vector<uint32_t> incident(offsets[vertex_count]);
  {
    std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
    for (uint32_t k = 0; k < surface.size(); ++k)
      for (uint32_t v : surface[k].v) incident[cursor[v]++] = k;
  }

  std::vector<uint32_t> parent;
  std::vector<std::pair<uint32_t, uint32_t>> rim;  // (other vertex, local triangle)
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (result.kind[v] == FeatureKind::kInterior) continue;
    const VertexFeatures& f = features[v];
    if (f.count == 0) {
      // One fan: the triangles around v, joined through shared edges, form one component.
      const uint32_t n = offsets[v + 1] - offsets[v];
      parent.resize(n);
      rim.clear();
      for (uint32_t k = 0; k < n; ++k) {
        parent[k] = k;
        for (uint32_t w : surface[incident[offsets[v] + k]].v)
          if (w != v) rim.push_back({w, k});
      }
      std::sort(rim.begin(), rim.end());
      for (size_t k = 1; k < rim.size(); ++k) {
        if (rim[k].first == rim[k - 1].first) {
          parent[find_root(parent, rim[k].second)] = find_root(parent, rim[k - 1].second);
        }
      }
      uint32_t components = 0;
      for (uint32_t k = 0; k < n; ++k) components += find_root(parent, k) == k;
      result.kind[v] = components == 1 ? FeatureKind::kSurface : FeatureKind::kCorner;
    } else if (f.count == 2 && f.signature[0] == f.signature[1]) {
      const Vec3 e0 = mesh.positions[f.other[0]] - mesh.positions[v];
      const Vec3 e1 = mesh.positions[f.other[1]] - mesh.positions[v];
      const double turn = M_PI - angle_between(e0, e1);
      result.kind[v] = turn > crease ? FeatureKind::kCorner : FeatureKind::kCurve;
    } else {
      result.kind[v] = FeatureKind::kCorner;
    }
  }
  return result;
}

}  // namespace tetlod
