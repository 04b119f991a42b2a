// Shape improvement within the thresholds: see improve.h.
#include "core/improve.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/adjacency.h"
#include "core/classify.h"
#include "core/metrics.h"
#include "core/surface.h"

namespace tetlod {
namespace {

inline bool tet_has(const Tet& t, uint32_t v) {
  return t[0] == v || t[1] == v || t[2] == v || t[3] == v;
}

class Improver {
 public:
  Improver(TetMesh* mesh, const SimplifyParams& params, const std::atomic<bool>* cancel)
      : mesh_(*mesh), params_(params), cancel_(cancel) {
    const size_t tet_count = mesh_.tet_count();
    alive_.assign(tet_count, 1);
    stretch_.resize(tet_count);
    star_.resize(mesh_.vertex_count());
    mark_.assign(mesh_.vertex_count(), 0);
    for (uint32_t t = 0; t < tet_count; ++t) {
      stretch_[t] = tet_shape(mesh_, mesh_.tets[t]).stretch;
      for (uint32_t v : mesh_.tets[t]) star_[v].push_back(t);
    }
    // Which vertices may move, and within what: a vertex on no boundary or interface
    // triangle anywhere; a vertex inside a flat patch of one boundary or interface (a
    // surface vertex, not on a curve or corner, all of whose surface triangles lie in
    // one plane) within that plane; no other. Flips keep every surface triangle, and
    // moves keep each patch's plane, so these stay right.
    std::vector<uint32_t> neighbors;
    build_face_neighbors(mesh_, &neighbors);
    const std::vector<SurfaceTriangle> surface = extract_surface(mesh_, neighbors);
    ClassifyOptions options;
    options.crease_angle_degrees = params.crease_angle_degrees;
    const Classification c = classify_vertices(mesh_, surface, options);
    freedom_.assign(mesh_.vertex_count(), kFixed);
    plane_normal_.assign(mesh_.vertex_count(), Vec3{0, 0, 0});
    for (uint32_t v = 0; v < mesh_.vertex_count(); ++v)
      if (c.kind[v] == FeatureKind::kInterior)
        freedom_[v] = kFree;
      else if (c.kind[v] == FeatureKind::kSurface)
        freedom_[v] = kInPlane;
    const auto& p = mesh_.positions;
    for (const SurfaceTriangle& tri : surface) {
      const Vec3 n = cross(p[tri.v[1]] - p[tri.v[0]], p[tri.v[2]] - p[tri.v[0]]);
      const double length_n = length(n);
      for (uint32_t v : tri.v) {
        if (freedom_[v] != kInPlane) continue;
        if (!(length_n > 0)) {
          freedom_[v] = kFixed;
          continue;
        }
        const Vec3 unit = n * (1 / length_n);
        Vec3& seen = plane_normal_[v];
        if (seen == Vec3{0, 0, 0}) {
          seen = unit;
        } else if (!(dot(seen, unit) >= 1 - 1e-12)) {
          freedom_[v] = kFixed;  // its surface triangles are not all in one plane
        }
      }
    }
  }

  ImproveResult run(int max_rounds) {
    ImproveResult r;
    summarize(&r.mean_stretch_before, &r.min_stretch_before, &r.breaks_before);
    while (r.rounds < max_rounds && !cancelled()) {
      ++r.rounds;
      const size_t flips_32 = flip_32_pass();
      const size_t flips_23 = flip_23_pass();
      const size_t moves = move_pass();
      r.flips_32 += flips_32;
      r.flips_23 += flips_23;
      r.moves += moves;
      if (flips_32 + flips_23 + moves == 0) break;
    }
    compact();
    summarize(&r.mean_stretch_after, &r.min_stretch_after, &r.breaks_after);
    return r;
  }

 private:
  bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }

  uint32_t next_stamp() {
    if (++stamp_ == 0) {
      std::fill(mark_.begin(), mark_.end(), 0);
      stamp_ = 1;
    }
    return stamp_;
  }

  uint32_t valence(uint32_t v) {
    const uint32_t s = next_stamp();
    mark_[v] = s;
    uint32_t n = 0;
    for (uint32_t t : star_[v])
      for (uint32_t w : mesh_.tets[t])
        if (mark_[w] != s) mark_[w] = s, ++n;
    return n;
  }

  double size_limit(const Tet& t, int32_t material) const {
    const auto& p = mesh_.positions;
    return params_.sizing.size_at((p[t[0]] + p[t[1]] + p[t[2]] + p[t[3]]) * 0.25, material);
  }

  // True if tet t (positively oriented) meets tau_ST and its tau_SZ; its stretch in *d.
  bool meets_thresholds(const Tet& t, int32_t material, double* d) const {
    const TetShape s = tet_shape(mesh_, t);
    *d = s.stretch;
    return s.volume > 0 && s.stretch >= params_.min_stretch && s.size <= size_limit(t, material);
  }

  void remove_tet(uint32_t t) {
    alive_[t] = 0;
    for (uint32_t v : mesh_.tets[t]) {
      auto& s = star_[v];
      *std::find(s.begin(), s.end(), t) = s.back();
      s.pop_back();
    }
  }

  void add_tet(const Tet& tet, int32_t material, double stretch) {
    const uint32_t t = static_cast<uint32_t>(mesh_.tets.size());
    mesh_.tets.push_back(tet);
    mesh_.materials.push_back(material);
    alive_.push_back(1);
    stretch_.push_back(stretch);
    for (uint32_t v : tet) star_[v].push_back(t);
  }

  // Edges (a, b) with exactly three tets around them, all of one material, in a closed
  // ring (so the edge is inside that material): the bipyramid over the ring triangle
  // r0 r1 r2 is cut into the two tets (r0 r1 r2 a) and (r0 r1 r2 b) instead.
  size_t flip_32_pass() {
    size_t flips = 0;
    std::vector<uint32_t> others;
    for (uint32_t a = 0; a < mesh_.vertex_count(); ++a) {
      if (cancelled()) break;
      others.clear();
      const uint32_t s = next_stamp();
      mark_[a] = s;
      for (uint32_t t : star_[a])
        for (uint32_t w : mesh_.tets[t])
          if (mark_[w] != s) mark_[w] = s, others.push_back(w);
      std::sort(others.begin(), others.end());
      for (uint32_t b : others)
        if (b > a && try_flip_32(a, b)) ++flips;
    }
    return flips;
  }

  bool try_flip_32(uint32_t a, uint32_t b) {
    uint32_t ring[3];
    int n = 0;
    for (uint32_t t : star_[a])
      if (tet_has(mesh_.tets[t], b)) {
        if (n == 3) return false;
        ring[n++] = t;
      }
    if (n != 3) return false;
    const int32_t material = mesh_.materials[ring[0]];
    if (mesh_.materials[ring[1]] != material || mesh_.materials[ring[2]] != material) return false;
    uint32_t r[3];
    int rn = 0;
    for (uint32_t t : ring)
      for (uint32_t w : mesh_.tets[t]) {
        if (w == a || w == b || std::find(r, r + rn, w) != r + rn) continue;
        if (rn == 3) return false;  // four ring vertices: an open fan, a boundary edge
        r[rn++] = w;
      }
    if (rn != 3) return false;
    // The ring winds once around the line ab, so the line crosses the triangle r;
    // the segment does if a and b lie on opposite sides of it.
    const auto& p = mesh_.positions;
    const double side_a = signed_volume6(p[r[0]], p[r[1]], p[r[2]], p[a]);
    const double side_b = signed_volume6(p[r[0]], p[r[1]], p[r[2]], p[b]);
    if (!((side_a > 0 && side_b < 0) || (side_a < 0 && side_b > 0))) return false;
    if (side_a < 0) std::swap(r[1], r[2]);
    const Tet new_a = {r[0], r[1], r[2], a}, new_b = {r[0], r[2], r[1], b};
    double old_min = 1;
    for (uint32_t t : ring) old_min = std::min(old_min, stretch_[t]);
    double da = 0, db = 0;
    if (!meets_thresholds(new_a, material, &da) || !meets_thresholds(new_b, material, &db))
      return false;
    if (std::min(da, db) <= old_min) return false;
    for (uint32_t t : ring) remove_tet(t);
    add_tet(new_a, material, da);
    add_tet(new_b, material, db);
    return true;
  }

  // Faces shared by two tets of one material, apexes p and q not yet joined: the two
  // tets are replaced by the three around the new edge pq.
  size_t flip_23_pass() {
    size_t flips = 0;
    const uint32_t tet_count = static_cast<uint32_t>(mesh_.tets.size());
    for (uint32_t t = 0; t < tet_count; ++t) {
      if ((t & 1023) == 0 && cancelled()) break;
      for (int f = 0; f < 4 && alive_[t]; ++f)
        if (try_flip_23(t, f)) ++flips;
    }
    return flips;
  }

  bool try_flip_23(uint32_t t, int f) {
    const Tet tet = mesh_.tets[t];
    const uint32_t p = tet[f];
    const uint32_t u[3] = {tet[kTetFace[f][0]], tet[kTetFace[f][1]], tet[kTetFace[f][2]]};
    uint32_t other = kInvalidIndex;
    for (uint32_t s : star_[u[0]])
      if (s != t && tet_has(mesh_.tets[s], u[1]) && tet_has(mesh_.tets[s], u[2])) other = s;
    // Each pair is tried once, from its smaller tet (new tets come last).
    if (other == kInvalidIndex || other < t) return false;
    const int32_t material = mesh_.materials[t];
    if (mesh_.materials[other] != material) return false;
    uint32_t q = kInvalidIndex;
    for (uint32_t w : mesh_.tets[other])
      if (w != u[0] && w != u[1] && w != u[2]) q = w;
    for (uint32_t s : star_[p])
      if (tet_has(mesh_.tets[s], q)) return false;  // already an edge
    // pq crosses the triangle u inside iff the three tets around it turn the same way.
    const auto& pos = mesh_.positions;
    double side[3];
    for (int k = 0; k < 3; ++k)
      side[k] = signed_volume6(pos[u[k]], pos[u[(k + 1) % 3]], pos[p], pos[q]);
    const bool forward = side[0] > 0 && side[1] > 0 && side[2] > 0;
    if (!forward && !(side[0] < 0 && side[1] < 0 && side[2] < 0)) return false;
    Tet made[3];
    double d[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t x = u[k], y = u[(k + 1) % 3];
      made[k] = forward ? Tet{x, y, p, q} : Tet{y, x, p, q};
      if (!meets_thresholds(made[k], material, &d[k])) return false;
    }
    if (std::min({d[0], d[1], d[2]}) <= std::min(stretch_[t], stretch_[other])) return false;
    if (valence(p) + 1 > params_.max_valence || valence(q) + 1 > params_.max_valence) return false;
    remove_tet(t);
    remove_tet(other);
    for (int k = 0; k < 3; ++k) add_tet(made[k], material, d[k]);
    return true;
  }

  // Each vertex that may move tries the centroid of its neighbours (projected onto
  // its plane if it lies on a flat patch), then half and a quarter of the way there.
  size_t move_pass() {
    size_t moves = 0;
    std::vector<double> trial;
    for (uint32_t v = 0; v < mesh_.vertex_count(); ++v) {
      if (freedom_[v] == kFixed || star_[v].empty()) continue;
      if ((v & 1023) == 0 && cancelled()) break;
      const uint32_t s = next_stamp();
      mark_[v] = s;
      Vec3 centroid{0, 0, 0};
      int count = 0;
      double old_min = 1, old_sum = 0;
      for (uint32_t t : star_[v]) {
        old_min = std::min(old_min, stretch_[t]);
        old_sum += stretch_[t];
        for (uint32_t w : mesh_.tets[t])
          if (mark_[w] != s) mark_[w] = s, centroid = centroid + mesh_.positions[w], ++count;
      }
      centroid = centroid * (1.0 / count);
      const Vec3 old = mesh_.positions[v];
      if (freedom_[v] == kInPlane) {
        const Vec3& n = plane_normal_[v];
        centroid = centroid - n * dot(centroid - old, n);
      }
      for (double step : {1.0, 0.5, 0.25}) {
        mesh_.positions[v] = old + (centroid - old) * step;
        trial.clear();
        double new_min = 1, new_sum = 0;
        bool ok = true;
        for (uint32_t t : star_[v]) {
          double d = 0;
          if (!meets_thresholds(mesh_.tets[t], mesh_.materials[t], &d)) {
            ok = false;
            break;
          }
          trial.push_back(d);
          new_min = std::min(new_min, d);
          new_sum += d;
        }
        if (ok && (new_min > old_min || (new_min == old_min && new_sum > old_sum))) {
          for (size_t k = 0; k < trial.size(); ++k) stretch_[star_[v][k]] = trial[k];
          ++moves;
          break;
        }
        mesh_.positions[v] = old;
      }
    }
    return moves;
  }

  void compact() {
    size_t kept = 0;
    for (size_t t = 0; t < mesh_.tets.size(); ++t) {
      if (!alive_[t]) continue;
      mesh_.tets[kept] = mesh_.tets[t];
      mesh_.materials[kept] = mesh_.materials[t];
      stretch_[kept] = stretch_[t];
      ++kept;
    }
    mesh_.tets.resize(kept);
    mesh_.materials.resize(kept);
    stretch_.resize(kept);
    alive_.assign(kept, 1);
    for (auto& s : star_) s.clear();
    for (uint32_t t = 0; t < kept; ++t)
      for (uint32_t v : mesh_.tets[t]) star_[v].push_back(t);
  }

  // Over the live tets (call after compact()).
  void summarize(double* mean, double* min, ThresholdCounts* breaks) {
    double sum = 0, low = 1;
    *breaks = {};
    size_t n = 0;
    for (size_t t = 0; t < mesh_.tets.size(); ++t) {
      if (!alive_[t]) continue;
      const TetShape s = tet_shape(mesh_, mesh_.tets[t]);
      sum += s.stretch;
      low = std::min(low, s.stretch);
      ++n;
      breaks->below_stretch += s.stretch < params_.min_stretch;
      breaks->above_size += s.size > size_limit(mesh_.tets[t], mesh_.materials[t]);
    }
    for (uint32_t v = 0; v < mesh_.vertex_count(); ++v)
      breaks->above_valence += valence(v) > params_.max_valence;
    *mean = n ? sum / n : 0;
    *min = n ? low : 0;
  }

  TetMesh& mesh_;
  const SimplifyParams& params_;
  const std::atomic<bool>* cancel_;
  std::vector<uint8_t> alive_;
  std::vector<double> stretch_;
  std::vector<std::vector<uint32_t>> star_;
  enum Freedom : uint8_t { kFixed, kInPlane, kFree };
  std::vector<uint8_t> freedom_;
  std::vector<Vec3> plane_normal_;  // of the flat patch a kInPlane vertex lies in
  std::vector<uint32_t> mark_;
  uint32_t stamp_ = 0;
};

}  // namespace

ImproveResult improve_mesh(TetMesh* mesh, const SimplifyParams& params, int max_rounds,
                           const std::atomic<bool>* cancel) {
  Improver improver(mesh, params, cancel);
  return improver.run(max_rounds);
}

}  // namespace tetlod
