// Shape improvement within the thresholds: see improve.h.
#include "core/improve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/adjacency.h"
#include "core/classify.h"
#include "core/metrics.h"
#include "core/surface.h"

namespace tetlod {
namespace {

// Edge removal looks at rings of up to this many tets (42 triangulations at 7).
constexpr int kMaxRing = 7;

// Every triangulation of a convex polygon with corners 0 .. n-1, as triangles (i, j, k)
// with i < j < k.
using Triangulations = std::vector<std::vector<std::array<uint8_t, 3>>>;

void triangulate(int first, int last, Triangulations* out) {
  out->clear();
  if (last - first < 2) {
    out->push_back({});  // an edge: nothing to add
    return;
  }
  Triangulations left, right;
  for (int apex = first + 1; apex < last; ++apex) {
    triangulate(first, apex, &left);
    triangulate(apex, last, &right);
    for (const auto& l : left)
      for (const auto& rt : right) {
        std::vector<std::array<uint8_t, 3>> t = l;
        t.insert(t.end(), rt.begin(), rt.end());
        t.push_back(
            {static_cast<uint8_t>(first), static_cast<uint8_t>(apex), static_cast<uint8_t>(last)});
        out->push_back(std::move(t));
      }
  }
}

const Triangulations& polygon_triangulations(int n) {
  static const std::array<Triangulations, kMaxRing + 1> table = [] {
    std::array<Triangulations, kMaxRing + 1> t;
    for (int k = 3; k <= kMaxRing; ++k) triangulate(0, k - 1, &t[k]);
    return t;
  }();
  return table[n];
}

class Improver {
 public:
  // moves: classify the vertices for move_pass() (else none may move: edge removals only).
  Improver(TetMesh* mesh, const SimplifyParams& params, const std::atomic<bool>* cancel,
           const SurfacePatches* patches, bool moves = true)
      : mesh_(*mesh), params_(params), cancel_(cancel) {
    const size_t tet_count = mesh_.tet_count();
    alive_.assign(tet_count, 1);
    stretch_.resize(tet_count);
    big_.resize(tet_count);
    star_.resize(mesh_.vertex_count());
    mark_.assign(mesh_.vertex_count(), 0);
    for (uint32_t t = 0; t < tet_count; ++t) {
      const TetShape shape = tet_shape(mesh_, mesh_.tets[t]);
      stretch_[t] = shape.stretch;
      big_[t] = shape.size > size_limit(mesh_.tets[t], mesh_.materials[t]);
      for (uint32_t v : mesh_.tets[t]) star_[v].push_back(t);
    }
    freedom_.assign(mesh_.vertex_count(), kFixed);
    plane_normal_.assign(mesh_.vertex_count(), Vec3{0, 0, 0});
    if (moves) classify_for_moves();
    // The input groups' faces inside a material stay as they are: their vertices are
    // fixed, and their faces and edges listed (sorted corners) for the flips.
    if (patches && !patches->inside_entries().empty()) {
      for (std::array<uint32_t, 3> f : inside_faces(mesh_, *patches)) {
        for (uint32_t v : f) freedom_[v] = kFixed;
        std::sort(f.begin(), f.end());
        kept_faces_.push_back(f);
        kept_edges_.push_back({f[0], f[1]});
        kept_edges_.push_back({f[0], f[2]});
        kept_edges_.push_back({f[1], f[2]});
      }
      std::sort(kept_faces_.begin(), kept_faces_.end());
      std::sort(kept_edges_.begin(), kept_edges_.end());
    }
  }

  // Which vertices may move, and within what: a vertex on no boundary or interface
  // triangle anywhere; a vertex inside a flat patch of one boundary or interface (a
  // surface vertex, not on a curve or corner, all of whose surface triangles lie in
  // one plane) within that plane; no other. Flips keep every surface triangle, and
  // moves keep each patch's plane, so these stay right.
  void classify_for_moves() {
    std::vector<uint32_t> neighbors;
    build_face_neighbors(mesh_, &neighbors);
    const std::vector<SurfaceTriangle> surface = extract_surface(mesh_, neighbors);
    ClassifyOptions options;
    options.crease_angle_degrees = params_.crease_angle_degrees;
    const Classification c = classify_vertices(mesh_, surface, options);
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
      const size_t removals = edge_removal_pass();
      const size_t flips_23 = flip_23_pass();
      const size_t moves = move_pass();
      r.edge_removals += removals;
      r.flips_23 += flips_23;
      r.moves += moves;
      if (removals + flips_23 + moves == 0) break;
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

  // The edge neighbours of v, in id order.
  void sorted_neighbors(uint32_t v, std::vector<uint32_t>* out) {
    out->clear();
    const uint32_t s = next_stamp();
    mark_[v] = s;
    for (uint32_t t : star_[v])
      for (uint32_t w : mesh_.tets[t])
        if (mark_[w] != s) mark_[w] = s, out->push_back(w);
    std::sort(out->begin(), out->end());
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
    return params_.sizing.size_at(tet_centroid(p[t[0]], p[t[1]], p[t[2]], p[t[3]]), material);
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
    big_.push_back(0);  // made within every threshold
    for (uint32_t v : tet) star_[v].push_back(t);
  }

  // Edge removal (the 3-2 flip is its smallest case): an edge (a, b) with n tets around
  // it (3 <= n <= kMaxRing), all of one material, in a closed ring (so the edge is inside
  // that material). The ring vertices r_0 .. r_{n-1}, in order around the edge, bound a
  // polygon; each triangulation of it gives the 2(n-2) tets of its triangles with a and
  // with b, filling the same space without the edge. The best triangulation is taken.
  size_t edge_removal_pass() {
    size_t removals = 0;
    std::vector<uint32_t> others;
    for (uint32_t a = 0; a < mesh_.vertex_count(); ++a) {
      if (cancelled()) break;
      sorted_neighbors(a, &others);
      for (uint32_t b : others)
        if (b > a && try_edge_removal(a, b)) ++removals;
    }
    return removals;
  }

 public:
  // Lowers the valence of each of `nodes` above tau_VL by removing its edges (to its
  // neighbours in id order, the first removal that can be made each time) until it is
  // within tau_VL or none of its edges can go; again over the nodes until a pass
  // removes nothing (a removal elsewhere may have made room). Returns the removals.
  // A node whose tries all failed is tried again only once a removal has changed its
  // star or a neighbour's (which is all its tries read), so with the same outcome.
  size_t shed_valence(const std::vector<uint32_t>& nodes) {
    size_t removals = 0, before = 0;
    changed_at_.assign(mesh_.vertex_count(), 0);
    std::vector<uint32_t> failed_at(mesh_.vertex_count(), 0);
    clock_ = 1;
    do {
      before = removals;
      for (uint32_t h : nodes) {
        if (failed_at[h] != 0 && !changed_since(h, failed_at[h])) continue;
        if (valence(h) <= params_.max_valence || cancelled()) continue;
        const size_t made = remove_edges_of(h);
        removals += made;
        if (made == 0) failed_at[h] = ++clock_;
      }
    } while (removals != before);
    compact();
    return removals;
  }

 private:
  // Whether h or a neighbour of h was in a removal after `clock`.
  bool changed_since(uint32_t h, uint32_t clock) {
    if (changed_at_[h] > clock) return true;
    for (uint32_t t : star_[h])
      for (uint32_t w : mesh_.tets[t])
        if (changed_at_[w] > clock) return true;
    return false;
  }

  // Tries to remove h's edges, to its neighbours in id order, while h is past the
  // valence; returns how many it removed.
  size_t remove_edges_of(uint32_t h) {
    std::vector<uint32_t>& others = others_;
    sorted_neighbors(h, &others);
    size_t made = 0;
    for (uint32_t x : others) {
      if (valence(h) <= params_.max_valence) break;
      made += try_edge_removal(h, x, /*any_valid=*/true);
    }
    return made;
  }

  // any_valid: take the triangulation of highest lowest stretch among those within
  // every threshold, even if it is lower than the ring's (to shed a neighbour).
  bool try_edge_removal(uint32_t a, uint32_t b, bool any_valid = false) {
    if (!kept_edges_.empty() && std::binary_search(kept_edges_.begin(), kept_edges_.end(),
                                                   std::make_pair(std::min(a, b), std::max(a, b))))
      return false;
    uint32_t ring[kMaxRing];
    int n = 0;
    const bool from_b = ring_from_other_end(star_[a].size(), star_[b].size());
    for (uint32_t t : star_[from_b ? b : a])
      if (tet_has(mesh_.tets[t], from_b ? a : b)) {
        if (n == kMaxRing) return false;
        ring[n++] = t;
      }
    if (n < 3) return false;
    const int32_t material = mesh_.materials[ring[0]];
    for (int k = 1; k < n; ++k)
      if (mesh_.materials[ring[k]] != material) return false;
    // Each ring tet (a, b, x, y) links x to y, in the direction that makes the tet
    // positive: following the links goes once around a closed ring.
    const auto& p = mesh_.positions;
    uint32_t from[kMaxRing], to[kMaxRing];
    for (int k = 0; k < n; ++k) {
      uint32_t xy[2], m = 0;
      for (uint32_t w : mesh_.tets[ring[k]])
        if (w != a && w != b) xy[m++] = w;
      const bool forward = signed_volume6(p[a], p[b], p[xy[0]], p[xy[1]]) > 0;
      from[k] = forward ? xy[0] : xy[1];
      to[k] = forward ? xy[1] : xy[0];
    }
    uint32_t r[kMaxRing];
    r[0] = from[0];
    for (int k = 1; k <= n; ++k) {
      const uint32_t* link = std::find(from, from + n, r[k - 1]);
      if (link == from + n) return false;  // an open fan: a boundary edge
      const uint32_t next = to[link - from];
      if (k == n) {
        if (next != r[0]) return false;
        break;
      }
      if (std::find(r, r + k, next) != r + k) return false;  // closes early
      r[k] = next;
    }
    double old_min = 1;
    bool fixes_size = false;
    for (int k = 0; k < n; ++k) {
      old_min = std::min(old_min, stretch_[ring[k]]);
      fixes_size |= big_[ring[k]] != 0;
    }
    // New edges between ring vertices (the diagonals of a triangulation): they must not
    // be edges already (elsewhere), and each raises the valence of its two ends, which
    // must stay within tau_VL. Known per pair before the triangulations are tried.
    // The one triangle of a 3-2 flip has no diagonal, and must not be a face already: in
    // a mesh whose tets overlap without sharing faces (which validation cannot see), a
    // tet elsewhere may have it, and would then share it with both new tets.
    if (n == 3) {
      for (uint32_t t : star_[r[0]])
        if (tet_has(mesh_.tets[t], r[1]) && tet_has(mesh_.tets[t], r[2])) return false;
    }
    bool joined[kMaxRing][kMaxRing] = {};
    uint32_t room[kMaxRing] = {};  // how many more neighbours each may take
    bool known = false;            // joined and room, found when first needed
    auto find_joined_and_room = [&] {
      for (int i = 0; i < n; ++i) {
        const uint32_t v = valence(r[i]);
        room[i] = v < params_.max_valence ? params_.max_valence - v : 0;
        for (int j = i + 2; j < n; ++j) {
          if (i == 0 && j == n - 1) continue;  // a side of the polygon
          for (uint32_t t : star_[r[i]])
            if (tet_has(mesh_.tets[t], r[j])) {
              joined[i][j] = true;
              break;
            }
        }
      }
      known = true;
    };
    const Triangulations& all = polygon_triangulations(n);
    Tet best[2 * (kMaxRing - 2)];
    double best_d[2 * (kMaxRing - 2)];
    double best_min = fixes_size || any_valid ? -1 : old_min;
    int best_index = -1;
    for (size_t i = 0; i < all.size(); ++i) {
      const std::vector<std::array<uint8_t, 3>>& triangles = all[i];
      Tet made[2 * (kMaxRing - 2)];
      double d[2 * (kMaxRing - 2)];
      double low = 1;
      bool ok = true;
      for (size_t k = 0; k < triangles.size() && ok; ++k) {
        const uint32_t x = r[triangles[k][0]], y = r[triangles[k][1]], z = r[triangles[k][2]];
        // Positive for a below the triangle and b above: the ring's direction.
        if (!(signed_volume6(p[x], p[y], p[z], p[a]) < 0 &&
              signed_volume6(p[x], p[y], p[z], p[b]) > 0)) {
          ok = false;
          break;
        }
        made[2 * k] = {x, z, y, a};
        made[2 * k + 1] = {x, y, z, b};
        for (int h = 0; h < 2 && ok; ++h) {
          ok = meets_thresholds(made[2 * k + h], material, &d[2 * k + h]);
          low = std::min(low, d[2 * k + h]);
        }
      }
      if (!ok || !(low > best_min)) continue;
      if (n > 3 && !known) find_joined_and_room();
      uint32_t gain[kMaxRing] = {};
      for (size_t k = 0; k < triangles.size() && ok; ++k)
        for (int e = 0; e < 3; ++e) {
          const int lo = std::min(triangles[k][e], triangles[k][(e + 1) % 3]);
          const int hi = std::max(triangles[k][e], triangles[k][(e + 1) % 3]);
          if (hi == lo + 1 || (lo == 0 && hi == n - 1)) continue;     // a side of the polygon
          if (triangles[k][e] > triangles[k][(e + 1) % 3]) continue;  // each diagonal once
          if (joined[lo][hi] || ++gain[lo] > room[lo] || ++gain[hi] > room[hi]) ok = false;
        }
      if (!ok) continue;
      best_min = low;
      best_index = static_cast<int>(i);
      std::copy(made, made + 2 * triangles.size(), best);
      std::copy(d, d + 2 * triangles.size(), best_d);
    }
    if (best_index < 0) return false;
    const auto& triangles = all[best_index];
    for (int k = 0; k < n; ++k) remove_tet(ring[k]);
    for (size_t k = 0; k < 2 * triangles.size(); ++k) add_tet(best[k], material, best_d[k]);
    if (!changed_at_.empty()) {  // shed_valence()
      ++clock_;
      changed_at_[a] = changed_at_[b] = clock_;
      for (int k = 0; k < n; ++k) changed_at_[r[k]] = clock_;
    }
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
    // The tet on the face's other side (at most one), from the smallest of its corners'
    // stars (a node every tet of a fan has: walking its star for each of its faces took
    // time quadratic in its valence).
    int c0 = 0;
    for (int k = 1; k < 3; ++k)
      if (star_[u[k]].size() < star_[u[c0]].size()) c0 = k;
    const uint32_t c1 = u[(c0 + 1) % 3], c2 = u[(c0 + 2) % 3];
    uint32_t other = kInvalidIndex;
    for (uint32_t s : star_[u[c0]])
      if (s != t && tet_has(mesh_.tets[s], c1) && tet_has(mesh_.tets[s], c2)) other = s;
    // Each pair is tried once, from its smaller tet (new tets come last).
    if (other == kInvalidIndex || other < t) return false;
    const int32_t material = mesh_.materials[t];
    if (mesh_.materials[other] != material) return false;
    if (!kept_faces_.empty()) {
      std::array<uint32_t, 3> face = {u[0], u[1], u[2]};
      std::sort(face.begin(), face.end());
      if (std::binary_search(kept_faces_.begin(), kept_faces_.end(), face)) return false;
    }
    uint32_t q = kInvalidIndex;
    for (uint32_t w : mesh_.tets[other])
      if (w != u[0] && w != u[1] && w != u[2]) q = w;
    const bool from_q = star_[q].size() < star_[p].size();
    for (uint32_t s : star_[from_q ? q : p])
      if (tet_has(mesh_.tets[s], from_q ? p : q)) return false;  // already an edge
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
      bool fixes_size = false;
      for (uint32_t t : star_[v]) {
        fixes_size |= big_[t] != 0;
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
        if (ok && (fixes_size || new_min > old_min || (new_min == old_min && new_sum > old_sum))) {
          for (size_t k = 0; k < trial.size(); ++k) {
            stretch_[star_[v][k]] = trial[k];
            big_[star_[v][k]] = 0;  // every tet of the star now meets the thresholds
          }
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
      big_[kept] = big_[t];
      ++kept;
    }
    mesh_.tets.resize(kept);
    mesh_.materials.resize(kept);
    stretch_.resize(kept);
    big_.resize(kept);
    alive_.assign(kept, 1);
    for (auto& s : star_) s.clear();
    for (uint32_t t = 0; t < kept; ++t)
      for (uint32_t v : mesh_.tets[t]) star_[v].push_back(t);
  }

  // Over the live tets, from the cached stretch and size flags.
  void summarize(double* mean, double* min, ThresholdCounts* breaks) {
    double sum = 0, low = 1;
    *breaks = {};
    size_t n = 0;
    for (size_t t = 0; t < mesh_.tets.size(); ++t) {
      if (!alive_[t]) continue;
      sum += stretch_[t];
      low = std::min(low, stretch_[t]);
      ++n;
      breaks->below_stretch += stretch_[t] < params_.min_stretch;
      breaks->above_size += big_[t];
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
  std::vector<double> stretch_;  // of each tet, kept up to date
  // Per tet: above its tau_SZ (an input tet the simplifier could not remove). A change
  // that replaces such tets by tets within every threshold is taken even if the worst
  // stretch does not rise. Only input tets can be; a tet a change makes or reshapes
  // meets the thresholds, so the flag only ever clears.
  std::vector<uint8_t> big_;
  std::vector<std::vector<uint32_t>> star_;
  enum Freedom : uint8_t { kFixed, kInPlane, kFree };
  std::vector<uint8_t> freedom_;
  std::vector<Vec3> plane_normal_;  // of the flat patch a kInPlane vertex lies in
  // The faces (sorted corners) and edges (a < b) kept as they are, sorted.
  std::vector<std::array<uint32_t, 3>> kept_faces_;
  std::vector<std::pair<uint32_t, uint32_t>> kept_edges_;
  std::vector<uint32_t> mark_;
  uint32_t stamp_ = 0;
  std::vector<uint32_t> others_;  // remove_an_edge_of()
  // shed_valence(): per vertex, the clock at the last removal that changed its star.
  std::vector<uint32_t> changed_at_;
  uint32_t clock_ = 0;
};

}  // namespace

ThresholdCounts threshold_breaks(const TetMesh& mesh, const SimplifyParams& params) {
  // As Improver::summarize() counts them, without an Improver's set-up (a copy of the
  // mesh and a star per node).
  ThresholdCounts counts;
  const std::vector<Vec3>& p = mesh.positions;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& q = mesh.tets[t];
    const TetShape shape = tet_shape(mesh, q);
    const Vec3 centroid = tet_centroid(p[q[0]], p[q[1]], p[q[2]], p[q[3]]);
    counts.below_stretch += shape.stretch < params.min_stretch;
    counts.above_size += shape.size > params.sizing.size_at(centroid, mesh.materials[t]);
  }
  const VertexTets stars = build_vertex_tets(mesh);
  std::vector<uint32_t> mark(mesh.vertex_count(), kInvalidIndex);
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    mark[v] = v;
    uint32_t valence = 0;
    for (const uint32_t* t = stars.begin(v); t != stars.end(v); ++t)
      for (uint32_t w : mesh.tets[*t])
        if (mark[w] != v) mark[w] = v, ++valence;
    counts.above_valence += valence > params.max_valence;
  }
  return counts;
}

size_t shed_valence(TetMesh* mesh, const SimplifyParams& params, const std::vector<uint32_t>& nodes,
                    const std::atomic<bool>* cancel, const SurfacePatches* patches) {
  Improver improver(mesh, params, cancel, patches, /*moves=*/false);
  return improver.shed_valence(nodes);
}

ImproveResult improve_mesh(TetMesh* mesh, const SimplifyParams& params, int max_rounds,
                           const std::atomic<bool>* cancel, const SurfacePatches* patches) {
  Improver improver(mesh, params, cancel, patches);
  return improver.run(max_rounds);
}

}  // namespace tetlod
