// Subdivision and property-controlled edge-collapse simplification.
//
// References:
//  - H. Date et al., "Flexible Control of Multimaterial Tetrahedral Mesh Properties
//    by Using Multiresolution Techniques", IEEE Trans. Magn.: thresholds (section
//    IV.A.3), candidate positions (IV.A.2), priority index (eq. 3), LOD (IV.B).
//  - M. Garland, P. Heckbert, "Surface simplification using quadric error metrics",
//    SIGGRAPH 1997: the quadrics of eq. (1).
//  - T. Dey, H. Edelsbrunner et al., "Topology preserving edge contraction", 1999:
//    the link condition, here with a virtual vertex for the outside of each region,
//    evaluated on the few vertices of the link of the edge.
//  - M.-C. Rivara, longest-edge bisection: subdivision splits the longest edge first.
#include "core/simplify.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/adjacency.h"
#include "core/classify.h"
#include "core/metrics.h"
#include "core/surface.h"

namespace tetlod {

namespace {

// A threshold as the user would write it (std::to_string prints 1e-300 as 0.000000).
std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

}  // namespace

Status check_params(const SimplifyParams& p) {
  if (!(std::isfinite(p.tolerance) && p.tolerance >= 0)) {
    return Status::error("tolerance " + number(p.tolerance) + " must be a finite length >= 0");
  }
  if (!(std::isfinite(p.min_stretch) && p.min_stretch > 0 && p.min_stretch < 1)) {
    return Status::error("stretch " + number(p.min_stretch) +
                         " must lie strictly between 0 and 1 (1 is a regular tet)");
  }
  if (p.max_valence < 4) {
    return Status::error("valence " + std::to_string(p.max_valence) +
                         " must be at least 4 (a tet's corner already has 3 neighbours)");
  }
  if (p.sizing.unlimited()) return Status::error("no size limit given (set --size)");
  const double smallest = p.sizing.smallest_size();
  if (!(smallest > 0) || std::isnan(p.sizing.uniform) || p.sizing.uniform <= 0) {
    return Status::error("size must be > 0");
  }
  if (!(std::isfinite(p.crease_angle_degrees) && p.crease_angle_degrees > 0 &&
        p.crease_angle_degrees < 180)) {
    return Status::error("crease angle must lie between 0 and 180 degrees");
  }
  return Status();
}

namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kMaxTets = 40'000'000;  // subdivision refuses to grow beyond this
constexpr uint8_t kMayBeThin = 1;        // below tau_ST
constexpr uint8_t kMayBeBig = 2;         // above tau_SZ

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Garland-Heckbert quadric of eq. (1): e(p) = p^T A p + 2 B p + C.
struct Quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double b0 = 0, b1 = 0, b2 = 0, c = 0;

  static Quadric plane(const Vec3& n, double d) {  // n.p + d = 0, |n| = 1
    Quadric q;
    q.a00 = n.x * n.x, q.a01 = n.x * n.y, q.a02 = n.x * n.z;
    q.a11 = n.y * n.y, q.a12 = n.y * n.z, q.a22 = n.z * n.z;
    q.b0 = d * n.x, q.b1 = d * n.y, q.b2 = d * n.z;
    q.c = d * d;
    return q;
  }
  void add(const Quadric& o) {
    a00 += o.a00, a01 += o.a01, a02 += o.a02, a11 += o.a11, a12 += o.a12, a22 += o.a22;
    b0 += o.b0, b1 += o.b1, b2 += o.b2, c += o.c;
  }
  double error(const Vec3& p) const {
    const double ax = a00 * p.x + a01 * p.y + a02 * p.z;
    const double ay = a01 * p.x + a11 * p.y + a12 * p.z;
    const double az = a02 * p.x + a12 * p.y + a22 * p.z;
    return p.x * ax + p.y * ay + p.z * az + 2 * (b0 * p.x + b1 * p.y + b2 * p.z) + c;
  }
  // The expanded form cancels: an error that is exactly 0 evaluates to about
  // 1e-16 |p|^2. This bounds the rounding of error(p), so that a position on every
  // plane is never rejected by a tolerance below that noise (or by a zero tolerance).
  double rounding(const Vec3& p) const {
    const Vec3 a{std::abs(p.x), std::abs(p.y), std::abs(p.z)};
    const double quadratic =
        a.x * (std::abs(a00) * a.x + std::abs(a01) * a.y + std::abs(a02) * a.z) +
        a.y * (std::abs(a01) * a.x + std::abs(a11) * a.y + std::abs(a12) * a.z) +
        a.z * (std::abs(a02) * a.x + std::abs(a12) * a.y + std::abs(a22) * a.z);
    const double linear = 2 * (std::abs(b0) * a.x + std::abs(b1) * a.y + std::abs(b2) * a.z);
    return 1e-14 * (quadratic + linear + std::abs(c));
  }
};

enum class Reject : uint8_t { kNone, kTolerance, kStretch, kSize, kValence, kTopology };

struct Collapse {
  double priority = 0;
  uint32_t kept = 0, removed = 0;
  uint32_t version_kept = 0, version_removed = 0;
  Vec3 position;
  bool surface_edge = false;
};

// Max-heap order: larger priority first, then the smaller vertex pair.
struct CollapseLess {
  bool operator()(const Collapse& x, const Collapse& y) const {
    if (x.priority != y.priority) return x.priority < y.priority;
    const uint64_t kx = (uint64_t{std::min(x.kept, x.removed)} << 32) | std::max(x.kept, x.removed);
    const uint64_t ky = (uint64_t{std::min(y.kept, y.removed)} << 32) | std::max(y.kept, y.removed);
    return kx > ky;
  }
};

struct Split {
  double length2;
  uint32_t a, b;
};
struct SplitLess {
  bool operator()(const Split& x, const Split& y) const {
    if (x.length2 != y.length2) return x.length2 < y.length2;
    return x.a != y.a ? x.a > y.a : x.b > y.b;
  }
};

// kOtherCorners[s][c]: the two corners of a tet other than s and c (s != c).
constexpr int kOtherCorners[4][4][2] = {
    {{0, 0}, {2, 3}, {1, 3}, {1, 2}},
    {{2, 3}, {0, 0}, {0, 3}, {0, 2}},
    {{1, 3}, {0, 3}, {0, 0}, {0, 1}},
    {{1, 2}, {0, 2}, {0, 1}, {0, 0}},
};

inline bool tet_has(const Tet& t, uint32_t v) {
  return t[0] == v || t[1] == v || t[2] == v || t[3] == v;
}

template <class T>
void sort_unique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// Everything the evaluation of a collapse reads of a tet, in one 32-byte record, so
// that walking a star costs one cache line per tet instead of one per array.
struct TetRecord {
  Tet v{};
  double stretch = 0;  // d_t, kept up to date from classification on
  int32_t material = 0;
  uint8_t alive = 1;
  // Which thresholds the tet may break because the input tet it comes from
  // (unchanged, or cut into pieces by subdivision) already broke them: kMayBeThin,
  // kMayBeBig.
  uint8_t allowance = 0;
};
static_assert(sizeof(TetRecord) == 32, "one tet, one half cache line");

class Engine {
 public:
  Engine(const TetMesh& input, const SimplifyParams& params, const ProgressCallback& progress,
         const std::atomic<bool>* cancel)
      : params_(params), progress_(progress), cancel_(cancel), pos_(input.positions) {
    tolerance2_ = params.tolerance * params.tolerance;
    uniform_sizing_ = params.sizing.material_sizes.empty() && params.sizing.radial.empty() &&
                      params.sizing.boxes.empty();
    tet_.resize(input.tets.size());
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      tet_[t].v = input.tets[t];
      tet_[t].material = input.materials[t];
      tet_[t].allowance = own_violations(t);
    }
    vertex_alive_.assign(pos_.size(), 1);
    star_.resize(pos_.size());
    for (uint32_t t = 0; t < tet_.size(); ++t)
      for (uint32_t v : tet_[t].v) star_[v].push_back(t);
    mark_.assign(pos_.size(), 0);
    input_valence_.resize(pos_.size());
    for (uint32_t v = 0; v < pos_.size(); ++v) input_valence_[v] = valence(v);
    reorder_for_locality();
  }

  Status run(SimplifyResult* result) {
    auto start = Clock::now();
    if (params_.subdivide) {
      Status s = subdivide(result);
      if (!s) return s;
    }
    if (result->splits > 0) reorder_for_locality();  // new vertices were appended
    result->seconds_subdivide = seconds_since(start);
    result->base = mesh_now();
    if (cancelled()) {
      result->cancelled = true;
      result->output = result->base;
      return Status();
    }

    start = Clock::now();
    report("classify", 0);
    classify();
    report("classify", 1);
    result->seconds_classify = seconds_since(start);

    start = Clock::now();
    simplify(result);
    result->seconds_simplify = seconds_since(start);
    result->rejections = rejections_;
    result->output = compact();
    count_violations(&result->violations);
    return Status();
  }

 private:
  // ---------------------------------------------------------------- helpers
  bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }

  void report(const char* phase, double fraction) {
    if (progress_) progress_({phase, fraction, collapses_});
  }

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
      for (uint32_t w : tet_[t].v)
        if (mark_[w] != s) mark_[w] = s, ++n;
    return n;
  }

  void neighbors(uint32_t v, std::vector<uint32_t>* out) {
    out->clear();
    const uint32_t s = next_stamp();
    mark_[v] = s;
    for (uint32_t t : star_[v])
      for (uint32_t w : tet_[t].v)
        if (mark_[w] != s) mark_[w] = s, out->push_back(w);
  }

  double size_limit(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                    int32_t material) const {
    return params_.sizing.size_at((a + b + c + d) * 0.25, material);
  }
  double size_limit(uint32_t t) const {
    const Tet& q = tet_[t].v;
    return size_limit(pos_[q[0]], pos_[q[1]], pos_[q[2]], pos_[q[3]], tet_[t].material);
  }
  uint8_t own_violations(uint32_t t) const {
    const TetShape s = shape(t);
    return static_cast<uint8_t>((s.stretch < params_.min_stretch ? kMayBeThin : 0) |
                                (s.size > size_limit(t) ? kMayBeBig : 0));
  }
  TetShape shape(uint32_t t) const {
    const Tet& q = tet_[t].v;
    return tet_shape(pos_[q[0]], pos_[q[1]], pos_[q[2]], pos_[q[3]]);
  }

  // Renumbers vertices along a Morton (Z-order) curve and tets by their smallest
  // vertex, so that the stars the simplifier walks lie close together in memory.
  // Only internal ids change; the result is a function of the input alone.
  void reorder_for_locality() {
    const size_t vertex_count = pos_.size(), tet_count = tet_.size();
    Vec3 lo = pos_[0], hi = pos_[0];
    for (const Vec3& p : pos_) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-300});
    auto spread = [](uint64_t x) {  // 21 bits -> every third bit of 63
      x &= 0x1fffff;
      x = (x | x << 32) & 0x1f00000000ffffull;
      x = (x | x << 16) & 0x1f0000ff0000ffull;
      x = (x | x << 8) & 0x100f00f00f00f00full;
      x = (x | x << 4) & 0x10c30c30c30c30c3ull;
      x = (x | x << 2) & 0x1249249249249249ull;
      return x;
    };
    std::vector<std::pair<uint64_t, uint32_t>> order(vertex_count);
    for (uint32_t v = 0; v < vertex_count; ++v) {
      const Vec3 q = (pos_[v] - lo) * (2097151.0 / extent);
      order[v] = {spread(static_cast<uint64_t>(q.x)) | spread(static_cast<uint64_t>(q.y)) << 1 |
                      spread(static_cast<uint64_t>(q.z)) << 2,
                  v};
    }
    std::sort(order.begin(), order.end());
    std::vector<uint32_t> new_id(vertex_count);
    for (uint32_t k = 0; k < vertex_count; ++k) new_id[order[k].second] = k;
    std::vector<Vec3> positions(vertex_count);
    std::vector<uint32_t> valences(vertex_count);
    for (uint32_t v = 0; v < vertex_count; ++v) {
      positions[new_id[v]] = pos_[v];
      valences[new_id[v]] = input_valence_[v];
    }
    pos_.swap(positions);
    input_valence_.swap(valences);
    for (TetRecord& t : tet_)
      for (uint32_t& v : t.v) v = new_id[v];

    std::vector<std::pair<uint64_t, uint32_t>> tet_order(tet_count);
    for (uint32_t t = 0; t < tet_count; ++t) {
      const Tet& q = tet_[t].v;
      tet_order[t] = {(uint64_t{std::min({q[0], q[1], q[2], q[3]})} << 32) | t, t};
    }
    std::sort(tet_order.begin(), tet_order.end());
    std::vector<TetRecord> tets(tet_count);
    for (uint32_t k = 0; k < tet_count; ++k) tets[k] = tet_[tet_order[k].second];
    tet_.swap(tets);
    for (auto& star : star_) star.clear();
    for (uint32_t t = 0; t < tet_count; ++t)
      for (uint32_t v : tet_[t].v) star_[v].push_back(t);
  }

  // ------------------------------------------------------------ subdivision
  // Longest edge first (a max-heap on length): a popped edge is the longest edge of
  // every tet around it, so this is conforming longest-edge bisection. A split is
  // skipped, and counted, if a child would fall below min(tau_ST, its parent's
  // stretch) or a node would exceed tau_VL.
  double edge_size_limit(uint32_t a, uint32_t b) const {
    double limit = std::numeric_limits<double>::infinity();
    for (uint32_t t : star_[a])
      if (tet_has(tet_[t].v, b)) limit = std::min(limit, size_limit(t));
    return limit;
  }

  void push_if_long(std::vector<Split>& heap, uint32_t a, uint32_t b) {
    const double length2 = squared_length(pos_[a] - pos_[b]);
    const double half = 0.5 * edge_size_limit(a, b);
    if (length2 > half * half) {
      heap.push_back({length2, std::min(a, b), std::max(a, b)});
      std::push_heap(heap.begin(), heap.end(), SplitLess());
    }
  }

  Status subdivide(SimplifyResult* result) {
    // Refuse sizes that would explode the mesh before doing any work.
    double predicted = 0;
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      const double ratio = 2 * shape(t).size / size_limit(t);
      if (ratio > 1) predicted += ratio * ratio * ratio;
    }
    if (predicted + tet_.size() > static_cast<double>(kMaxTets)) {
      const std::string count = predicted < 1e15
                                    ? "about " + std::to_string(static_cast<long long>(predicted))
                                    : "more than 10^15";
      return Status::error("size " + number(params_.sizing.smallest_size()) +
                           " would subdivide the mesh into " + count + " tets (limit " +
                           std::to_string(kMaxTets) + "); choose a larger size or --no-subdivide");
    }
    std::vector<uint32_t> valence_now(pos_.size());
    for (uint32_t v = 0; v < pos_.size(); ++v) valence_now[v] = input_valence_[v];

    std::vector<Split> heap;
    std::vector<uint32_t> nb;
    for (uint32_t v = 0; v < pos_.size(); ++v) {
      neighbors(v, &nb);
      for (uint32_t w : nb)
        if (w > v) push_if_long(heap, v, w);
    }
    const size_t initial = std::max<size_t>(1, heap.size());
    std::vector<uint32_t> ring, opposite;
    size_t iterations = 0;
    while (!heap.empty()) {
      if ((++iterations & 4095) == 0) {
        if (cancelled()) break;
        report("subdivide", std::min(1.0, double(result->splits) / double(initial)));
      }
      std::pop_heap(heap.begin(), heap.end(), SplitLess());
      const Split e = heap.back();
      heap.pop_back();
      ring.clear();
      for (uint32_t t : star_[e.a])
        if (tet_has(tet_[t].v, e.b)) ring.push_back(t);
      if (ring.empty()) continue;  // already split

      const Vec3 m = (pos_[e.a] + pos_[e.b]) * 0.5;
      bool ok = true;
      opposite.clear();
      for (uint32_t t : ring) {
        const double parent = shape(t).stretch;
        const double floor = std::min(params_.min_stretch, parent);
        for (uint32_t replaced : {e.a, e.b}) {
          Vec3 p[4];
          for (int c = 0; c < 4; ++c) p[c] = tet_[t].v[c] == replaced ? m : pos_[tet_[t].v[c]];
          const TetShape child = tet_shape(p[0], p[1], p[2], p[3]);
          if (child.stretch < floor) ok = false;
          // A piece may only be above its own size limit if its parent already was
          // above its own (with a size field the limits of parent and piece differ).
          if (!(tet_[t].allowance & kMayBeBig) &&
              child.size > size_limit(p[0], p[1], p[2], p[3], tet_[t].material))
            ok = false;
        }
        for (uint32_t w : tet_[t].v)
          if (w != e.a && w != e.b) opposite.push_back(w);
      }
      sort_unique(opposite);
      if (opposite.size() + 2 > params_.max_valence) ok = false;
      for (uint32_t w : opposite)
        if (valence_now[w] + 1 > params_.max_valence) ok = false;
      if (!ok) {
        ++result->splits_skipped;
        continue;
      }
      if (tet_.size() + ring.size() > kMaxTets) {
        return Status::error("subdivision exceeded " + std::to_string(kMaxTets) +
                             " tets; choose a larger size or --no-subdivide");
      }

      const uint32_t mid = static_cast<uint32_t>(pos_.size());
      pos_.push_back(m);
      vertex_alive_.push_back(1);
      star_.emplace_back();
      mark_.push_back(0);
      input_valence_.push_back(0);
      valence_now.push_back(static_cast<uint32_t>(opposite.size() + 2));
      for (uint32_t w : opposite) ++valence_now[w];
      for (uint32_t t : ring) {
        const uint32_t child = static_cast<uint32_t>(tet_.size());
        // The upper piece copies t's material and allowance: a piece of t may break
        // what t broke.
        TetRecord upper = tet_[t];
        for (uint32_t& v : upper.v)
          if (v == e.a) v = mid;
        for (uint32_t& v : tet_[t].v)
          if (v == e.b) v = mid;
        tet_.push_back(upper);
        // Stars: t keeps a and loses b; the child has b instead of a.
        auto& sb = star_[e.b];
        *std::find(sb.begin(), sb.end(), t) = child;
        for (uint32_t w : upper.v)
          if (w != e.b && w != mid) star_[w].push_back(child);
        star_[mid].push_back(t);
        star_[mid].push_back(child);
      }
      ++result->splits;
      push_if_long(heap, e.a, mid);
      push_if_long(heap, mid, e.b);
      for (uint32_t w : opposite) push_if_long(heap, mid, w);
    }
    for (auto& s : star_) std::sort(s.begin(), s.end());
    report("subdivide", 1);
    return Status();
  }

  // --------------------------------------------------------- classification
  void classify() {
    const TetMesh mesh = mesh_now();
    std::vector<uint32_t> neighbors_of_tets;
    const FaceProblem problem = build_face_neighbors(mesh, &neighbors_of_tets);
    assert(problem.kind == FaceProblem::Kind::kNone);  // the input was validated
    (void)problem;
    const std::vector<SurfaceTriangle> surface = extract_surface(mesh, neighbors_of_tets);
    ClassifyOptions options;
    options.crease_angle_degrees = params_.crease_angle_degrees;
    Classification c = classify_vertices(mesh, surface, options);
    kind_ = std::move(c.kind);
    feature_neighbors_.assign(pos_.size(), {});
    for (const auto& e : c.feature_edges) {
      feature_neighbors_[e[0]].push_back(e[1]);
      feature_neighbors_[e[1]].push_back(e[0]);
    }
    outer_.assign(pos_.size(), 0);
    ring_mark_.assign(pos_.size(), 0);
    ring_slot_.assign(pos_.size(), 0);
    quadric_.assign(pos_.size(), Quadric());
    for (const SurfaceTriangle& s : surface) {
      if (s.outer == kOutsideMaterial)
        for (uint32_t v : s.v) outer_[v] = 1;
      const Vec3& p = pos_[s.v[0]];
      Vec3 n = cross(pos_[s.v[1]] - p, pos_[s.v[2]] - p);
      const double len = length(n);
      if (!(len > 0)) continue;
      n = n * (1.0 / len);
      const Quadric q = Quadric::plane(n, -dot(n, p));
      for (uint32_t v : s.v) quadric_[v].add(q);
    }
    material_ids_ = mesh.materials;
    sort_unique(material_ids_);
    material_tets_.assign(material_ids_.size(), 0);
    for (int32_t m : mesh.materials) ++material_tets_[material_index(m)];
    for (uint32_t t = 0; t < tet_.size(); ++t) tet_[t].stretch = shape(t).stretch;
    across_ = std::move(neighbors_of_tets);
  }

  // ------------------------------------------------------------ evaluation
  // Calls face(x, y, across) for each face (v, x, y) of tet t, which holds v, with
  // the tet across that face or kInvalidIndex on the boundary.
  template <class Face>
  void for_faces_at(uint32_t t, uint32_t v, Face face) const {
    const Tet& q = tet_[t].v;
    int s = 0;
    while (q[s] != v) ++s;
    for (int c = 0; c < 4; ++c) {
      if (c == s) continue;
      face(q[kOtherCorners[s][c][0]], q[kOtherCorners[s][c][1]], across_[4 * t + c]);
    }
  }

  // A surface face separates a tet from the outside or from another material.
  bool is_surface_face(uint32_t tet, uint32_t across) const {
    return across == kInvalidIndex || tet_[across].material != tet_[tet].material;
  }

  // The link condition Lk(i) n Lk(j) = Lk(ij) (Dey et al.) in the sub-complex of the
  // tets accepted by `in`, the outside of that complex coned to a virtual vertex
  // (omega). A simplex common to Lk(i) and Lk(j) has its real vertices among the
  // common neighbours of i and j, which the vertex condition confines to the few
  // vertices R of Lk(ij) (the ring of tets around the edge); so the edge and triangle
  // conditions only look at the faces of the two stars whose vertices all lie in R.
  // boundary_i / boundary_j: whether i / j lies on the boundary of the sub-complex
  // (omega is in its link).
  // R's vertices get slots 0..r-1 (ring_slot_, valid where ring_mark_ holds this
  // call's stamp); what Lk(i) holds on R is flagged per slot and per pair of slots,
  // then each simplex of Lk(j) on R is looked up there: no list is sorted.
  template <class Filter>
  bool link_condition(uint32_t i, uint32_t j, Filter in, bool boundary_i, bool boundary_j) {
    // R from the ring tets (i, j, x, y), with the ring edges (x, y) of Lk(ij). A ring
    // vertex x seen once closes a face (i, j, x) on the boundary, so (x, omega) is in
    // Lk(ij): its slot stays kOpen.
    const uint32_t in_ring = next_ring_stamp();
    slot_flags_.clear();
    ring_pairs_.clear();
    auto slot_of = [&](uint32_t x) {
      if (ring_mark_[x] != in_ring) {
        ring_mark_[x] = in_ring;
        ring_slot_[x] = static_cast<uint32_t>(slot_flags_.size());
        slot_flags_.push_back(kOpen);
      } else {
        slot_flags_[ring_slot_[x]] &= static_cast<uint8_t>(~kOpen);
      }
      return ring_slot_[x];
    };
    for (uint32_t t : star_[i]) {
      const Tet& q = tet_[t].v;
      if (!in(t) || !tet_has(q, j)) continue;
      uint32_t o[2], n = 0;
      for (uint32_t w : q)
        if (w != i && w != j) o[n++] = w;
      ring_pairs_.push_back({slot_of(o[0]), slot_of(o[1])});
    }
    const size_t r = slot_flags_.size();
    bool open = false;
    for (uint8_t f : slot_flags_) open = open || (f & kOpen);
    // Vertices: omega is common unless the edge lies on the boundary (then a face
    // (i, j, x) is); every real common neighbour must be in R (checked on j's side).
    if (boundary_i && boundary_j && !open) return false;
    // Slot r is a dummy for every vertex outside R: the flags written there are never
    // read back, as each lookup is masked by membership of R. This keeps the loops
    // below free of branches that depend on the ring.
    const uint32_t dummy = static_cast<uint32_t>(r), stride = dummy + 1;
    slot_flags_.push_back(0);
    pair_flags_.assign(size_t{stride} * stride, 0);
    auto pair = [&](uint32_t a, uint32_t b) -> uint8_t& { return pair_flags_[a * stride + b]; };
    for (const auto& [a, b] : ring_pairs_) pair(a, b) = pair(b, a) = kRingEdge;
    auto slot = [&](uint32_t x) { return ring_mark_[x] == in_ring ? ring_slot_[x] : dummy; };
    // The three vertices of tet t other than v.
    auto others = [&](const Tet& q, uint32_t v, uint32_t* o) {
      int c = 0;
      while (q[c] != v) ++c;
      o[0] = q[(c + 1) & 3], o[1] = q[(c + 2) & 3], o[2] = q[(c + 3) & 3];
    };
    // Cone simplices (only when both ends lie on the boundary): (x, omega) for x on a
    // boundary face (v, x, y) of each star, which must be in Lk(ij), and (x, y, omega),
    // never common. A face of an accepted tet is on the boundary if the tet across is
    // missing or not accepted.
    const bool cone = boundary_i && boundary_j;
    // Lk(i) on R: the vertices of i's star (for the vertex condition); the edges
    // (x, y) and triangles (x, y, z) of the tets (i, x, y, z) outside the ring; the
    // cone simplices.
    const uint32_t near_i = next_stamp();
    ring_triples_.clear();
    for (uint32_t t : star_[i]) {
      if (!in(t)) continue;
      const Tet& q = tet_[t].v;
      for (uint32_t w : q) mark_[w] = near_i;
      if (cone) {
        for_faces_at(t, i, [&](uint32_t x, uint32_t y, uint32_t across) {
          if (across != kInvalidIndex && in(across)) return;
          const uint32_t sx = slot(x), sy = slot(y);
          slot_flags_[sx] |= kConeOfI;
          slot_flags_[sy] |= kConeOfI;
          pair(sx, sy) |= kConeOfI;
          pair(sy, sx) |= kConeOfI;
        });
      }
      if (tet_has(q, j)) continue;
      uint32_t o[3];
      others(q, i, o);
      const uint32_t s0 = slot(o[0]), s1 = slot(o[1]), s2 = slot(o[2]);
      pair(s0, s1) |= kEdgeOfI, pair(s1, s0) |= kEdgeOfI;
      pair(s0, s2) |= kEdgeOfI, pair(s2, s0) |= kEdgeOfI;
      pair(s1, s2) |= kEdgeOfI, pair(s2, s1) |= kEdgeOfI;
      if ((s0 != dummy) & (s1 != dummy) & (s2 != dummy))
        ring_triples_.push_back(triple_key(s0, s1, s2));
    }
    // Lk(j) on R, each simplex checked against Lk(i): a common real neighbour must be
    // in R, a common edge must be a ring edge, no triangle may be common, and of the
    // cone simplices only (x, omega) with x open.
    for (uint32_t t : star_[j]) {
      if (!in(t)) continue;
      const Tet& q = tet_[t].v;
      bool common = false;
      for (uint32_t w : q)
        common |= (w != i) & (w != j) & (mark_[w] == near_i) & (ring_mark_[w] != in_ring);
      if (cone) {
        for_faces_at(t, j, [&](uint32_t x, uint32_t y, uint32_t across) {
          if (across != kInvalidIndex && in(across)) return;
          const uint32_t sx = slot(x), sy = slot(y);
          const bool rx = sx != dummy, ry = sy != dummy;
          common |= rx & ((slot_flags_[sx] & (kConeOfI | kOpen)) == kConeOfI);
          common |= ry & ((slot_flags_[sy] & (kConeOfI | kOpen)) == kConeOfI);
          common |= rx & ry & ((pair(sx, sy) & kConeOfI) != 0);
        });
      }
      if (!tet_has(q, i)) {
        uint32_t o[3];
        others(q, j, o);
        const uint32_t s0 = slot(o[0]), s1 = slot(o[1]), s2 = slot(o[2]);
        const bool r0 = s0 != dummy, r1 = s1 != dummy, r2 = s2 != dummy;
        auto edge = [&](uint32_t a, uint32_t b) {
          return (pair(a, b) & (kEdgeOfI | kRingEdge)) == kEdgeOfI;
        };
        common |= r0 & r1 & edge(s0, s1);
        common |= r0 & r2 & edge(s0, s2);
        common |= r1 & r2 & edge(s1, s2);
        if (r0 & r1 & r2) {
          const uint64_t key = triple_key(s0, s1, s2);
          for (uint64_t k : ring_triples_) common |= k == key;
        }
      }
      if (common) return false;
    }
    return true;
  }

  // A triangle of three slots of R, in any order, as one number.
  static uint64_t triple_key(uint64_t a, uint64_t b, uint64_t c) {
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return a << 42 | b << 21 | c;
  }

  uint32_t next_ring_stamp() {
    if (++ring_stamp_ == 0) {
      std::fill(ring_mark_.begin(), ring_mark_.end(), 0);
      ring_stamp_ = 1;
    }
    return ring_stamp_;
  }

  // Topology: the link condition for the whole complex and for every material's
  // region around the edge, and for the surface complex when the edge lies on it.
  bool topology_ok(uint32_t i, uint32_t j, bool surface_edge) {
    // The stars were last read when the collapse was queued: load them in parallel.
    for (uint32_t v : {i, j}) {
      for (uint32_t t : star_[v]) {
        __builtin_prefetch(&tet_[t]);
        __builtin_prefetch(&across_[4 * size_t{t}]);
      }
    }
    if (!link_condition(
            i, j, [](uint32_t) { return true; }, outer_[i], outer_[j]))
      return false;
    // The materials of the ring, one entry per ring tet; and whether each end has
    // tets of a single material (then which).
    edge_materials_.clear();
    int32_t material_of[2] = {0, 0};
    bool single[2] = {true, true};
    for (int side = 0; side < 2; ++side) {
      const uint32_t v = side == 0 ? i : j;
      material_of[side] = tet_[star_[v][0]].material;
      for (uint32_t t : star_[v]) {
        const TetRecord& r = tet_[t];
        single[side] = single[side] && r.material == material_of[side];
        if (side == 0 && tet_has(r.v, j)) edge_materials_.push_back(r.material);
      }
    }
    std::sort(edge_materials_.begin(), edge_materials_.end());
    // Whether v has a tet of another material than m (then it lies on m's boundary).
    auto touches_other = [&](int side, int32_t m) {
      return !single[side] || material_of[side] != m;
    };
    // If every tet around i and j has one material, that material's complex is the
    // whole complex there, already checked.
    const bool one_material =
        !touches_other(0, edge_materials_[0]) && !touches_other(1, edge_materials_[0]);
    for (size_t k = 0; k < edge_materials_.size();) {
      const int32_t m = edge_materials_[k];
      size_t removed = 0;  // ring tets of m
      while (k < edge_materials_.size() && edge_materials_[k] == m) ++k, ++removed;
      if (!one_material) {
        auto in_m = [&](uint32_t t) { return tet_[t].material == m; };
        if (!link_condition(i, j, in_m, outer_[i] || touches_other(0, m),
                            outer_[j] || touches_other(1, m)))
          return false;
      }
      // No region may vanish: keep at least one tet of every material.
      if (removed >= material_tets_[material_index(m)]) return false;
    }
    if (surface_edge) {
      // Surface complex: common surface neighbours must span a surface triangle with
      // ij. The surface neighbours x of i are marked in mark_, those with a surface
      // triangle (i, j, x) in ring_mark_.
      const uint32_t near_i = next_stamp(), with_j = next_ring_stamp();
      for (uint32_t t : star_[i]) {
        for_faces_at(t, i, [&](uint32_t x, uint32_t y, uint32_t across) {
          if (!is_surface_face(t, across)) return;
          mark_[x] = mark_[y] = near_i;
          if (x == j) ring_mark_[y] = with_j;
          if (y == j) ring_mark_[x] = with_j;
        });
      }
      bool common = false;
      for (uint32_t t : star_[j]) {
        for_faces_at(t, j, [&](uint32_t x, uint32_t y, uint32_t across) {
          if (!is_surface_face(t, across)) return;
          for (uint32_t w : {x, y})
            if (mark_[w] == near_i && ring_mark_[w] != with_j) common = true;
        });
      }
      if (common) return false;
    }
    // Curves: two curve vertices joined by a feature edge share no other feature neighbour.
    for (uint32_t x : feature_neighbors_[i]) {
      if (x == j) continue;
      const auto& fj = feature_neighbors_[j];
      if (std::find(fj.begin(), fj.end(), x) != fj.end()) return false;
    }
    return true;
  }

  size_t material_index(int32_t m) const {
    return static_cast<size_t>(std::lower_bound(material_ids_.begin(), material_ids_.end(), m) -
                               material_ids_.begin());
  }

  bool is_feature_edge(uint32_t i, uint32_t j) const {
    const auto& f = feature_neighbors_[i];
    return std::find(f.begin(), f.end(), j) != f.end();
  }

  // Whether edge (i, j) lies on a boundary or interface triangle. The tets around an
  // edge inside one material form a closed ring, in which every face (i, j, x) is
  // shared by two of them; the edge lies on a surface if the ring is open (a face on
  // the boundary) or holds two materials (a face between them).
  bool is_surface_edge(uint32_t i, uint32_t j) {
    ring_others_.clear();
    int32_t material = 0;
    bool first = true;
    for (uint32_t t : star_[i]) {
      const TetRecord& r = tet_[t];
      if (!tet_has(r.v, j)) continue;
      if (first) {
        material = r.material;
        first = false;
      } else if (r.material != material) {
        return true;
      }
      for (uint32_t x : r.v)
        if (x != i && x != j) ring_others_.push_back(x);
    }
    std::sort(ring_others_.begin(), ring_others_.end());
    for (size_t k = 0; k < ring_others_.size(); k += 2)
      if (k + 1 == ring_others_.size() || ring_others_[k] != ring_others_[k + 1]) return true;
    return false;
  }

  // A tet of t*(i) U t*(j) that survives the collapse, reduced to what its shape
  // with the moving corner at k needs: the fixed face and its fixed lengths.
  struct MovingTet {
    Vec3 f0, f1, f2;    // the three corners that stay
    Vec3 inward;        // (f1 - f0) x (f2 - f0) oriented towards the moving corner
    double fixed_area;  // area of the fixed face
    double fixed_max2;  // longest squared edge among the fixed corners
    double stretch;     // its stretch now
    uint32_t owner;     // the end of the edge the tet holds
    int32_t material;
    uint8_t allowance;  // TetRecord::allowance
  };

  // |f*(a,b)|: the distinct vertices x of the triangles (a, b, x) around edge (a, b).
  uint32_t edge_triangle_count(uint32_t a, uint32_t b) {
    const uint32_t s = next_stamp();
    uint32_t n = 0;
    for (uint32_t t : star_[a]) {
      const Tet& q = tet_[t].v;
      if (!tet_has(q, b)) continue;
      for (uint32_t w : q)
        if (w != a && w != b && mark_[w] != s) mark_[w] = s, ++n;
    }
    return n;
  }

  // Lists the tets of t*(a) U t*(b) without edge (a, b) in moving_source_, and sets
  // *old_mean to the mean stretch of t*(a) U t*(b). Their MovingTet records are made
  // on demand by moving_tet(), as most candidates are rejected after a few tets.
  void gather_moving(uint32_t a, uint32_t b, double* old_mean) {
    moving_.clear();
    moving_source_.clear();
    double sum = 0;
    size_t count = 0;
    for (uint32_t v : {a, b}) {
      const uint32_t other = v == a ? b : a;
      for (uint32_t t : star_[v]) {
        const TetRecord& r = tet_[t];
        if (tet_has(r.v, other)) {
          if (v == a) sum += r.stretch, ++count;  // a ring tet, counted once
          continue;
        }
        sum += r.stretch;
        ++count;
        moving_source_.push_back({t, v});
      }
    }
    *old_mean = sum / static_cast<double>(count);
    candidate_.resize(moving_source_.size());
  }

  // The record of moving_source_[n]; made when first asked for (in order).
  const MovingTet& moving_tet(size_t n) {
    if (n < moving_.size()) return moving_[n];
    const auto [t, v] = moving_source_[n];
    const TetRecord& r = tet_[t];
    int slot = 0;
    while (r.v[slot] != v) ++slot;
    const int* f = kTetFace[slot];  // outward: its normal points away from slot
    MovingTet& m = moving_.emplace_back();
    m.f0 = pos_[r.v[f[0]]];
    m.f1 = pos_[r.v[f[1]]];
    m.f2 = pos_[r.v[f[2]]];
    const Vec3 outward = cross(m.f1 - m.f0, m.f2 - m.f0);
    m.inward = outward * -1.0;
    m.fixed_area = 0.5 * length(outward);
    m.fixed_max2 = std::max(
        {squared_length(m.f1 - m.f0), squared_length(m.f2 - m.f0), squared_length(m.f2 - m.f1)});
    m.stretch = r.stretch;
    m.owner = v;
    m.material = r.material;
    m.allowance = r.allowance;
    return m;
  }

  // Geometry of candidate position k for collapse (i, j): tolerance, stretch and
  // size of every tet around k (moving_ must hold them). On success sets *priority
  // (eq. 3). Cheapest first: a pass without square roots rejects inverted, oversized
  // and clearly flat tets (a bound on the stretch), then a pass computes the exact
  // stretch of eq. (2) only when every tet passed the first. If k is the position of
  // end `unmoved` (else kInvalidIndex), the tets of that end keep their shape: one
  // that meets every threshold (allowance 0) needs only its size, for eq. (3).
  Reject check_position(uint32_t i, uint32_t j, const Vec3& k, uint32_t unmoved,
                        double old_stretch_mean, double* priority) {
    Quadric q = quadric_[i];
    q.add(quadric_[j]);
    if (q.error(k) > tolerance2_ + q.rounding(k)) return Reject::kTolerance;
    if (moving_source_.empty()) return Reject::kTopology;
    const double uniform = params_.sizing.uniform;
    // The bound: with a_1..a_4 the face areas, (sum a)^2 >= sum a^2, so
    // d_t^2 = 6 (6V)^2 / (s^2 A^2) <= 6 (6V)^2 / (s^2 sum a^2); a tet whose bound is
    // below tau_ST^2 (with a margin far above the rounding) fails the exact test too.
    const double floor2 = params_.min_stretch * params_.min_stretch * (1 - 1e-9);
    for (size_t n = 0; n < moving_source_.size(); ++n) {
      const MovingTet& m = moving_tet(n);
      const Vec3 d0 = m.f0 - k, d1 = m.f1 - k, d2 = m.f2 - k;
      const double size2 =
          std::max({m.fixed_max2, squared_length(d0), squared_length(d1), squared_length(d2)});
      const double limit = uniform_sizing_ ? uniform : size_limit(m.f0, m.f1, m.f2, k, m.material);
      if (m.owner == unmoved && m.allowance == 0) {
        candidate_[n] = {-1, size2, 0, 0, 0, limit};  // volume6 < 0: unchanged
        continue;
      }
      const double volume6 = -dot(m.inward, d0);  // = 6 V of the tet with k in place
      if (!(volume6 > 0)) return Reject::kStretch;
      if (size2 > limit * limit) return Reject::kSize;
      const double face0 = squared_length(cross(d0, d1)), face1 = squared_length(cross(d1, d2)),
                   face2 = squared_length(cross(d2, d0));
      const double area_squares = m.fixed_area * m.fixed_area + 0.25 * (face0 + face1 + face2);
      if (6 * volume6 * volume6 < floor2 * size2 * area_squares) return Reject::kStretch;
      candidate_[n] = {volume6, size2, face0, face1, face2, limit};
    }
    double stretch_sum = 0, size_sum = 0, limit_sum = 0;
    for (size_t n = 0; n < moving_.size(); ++n) {
      const CandidateTet& c = candidate_[n];
      const double size = std::sqrt(c.size2);
      if (c.volume6 < 0) {
        stretch_sum += moving_[n].stretch;
        size_sum += size;
        limit_sum += c.limit;
        continue;
      }
      const double area = moving_[n].fixed_area +
                          0.5 * (std::sqrt(c.face0) + std::sqrt(c.face1) + std::sqrt(c.face2));
      // Paper eq. (2): d_t = 6 sqrt(6) V_t / (s_t A_t), with 6 V_t = volume6.
      const double stretch = std::sqrt(6.0) * c.volume6 / (size * area);
      if (!(stretch >= params_.min_stretch)) return Reject::kStretch;
      stretch_sum += stretch;
      size_sum += size;
      limit_sum += c.limit;
    }
    // Delta s = tau_SZ / mean size of t*(k); Delta d = mean stretch of t*(k) over the mean
    // stretch of t*(i) U t*(j). With a size field, tau_SZ is averaged over t*(k).
    const double delta_s = limit_sum / size_sum;
    const double delta_d = (stretch_sum / static_cast<double>(moving_.size())) / old_stretch_mean;
    *priority = delta_s * delta_d;
    return Reject::kNone;
  }

  // Full evaluation of collapsing edge (a, b). Returns kNone and fills `out` if valid.
  Reject evaluate(uint32_t a, uint32_t b, Collapse* out) {
    const FeatureKind ka = kind_[a], kb = kind_[b];
    const bool a_on = ka != FeatureKind::kInterior, b_on = kb != FeatureKind::kInterior;
    bool surface_edge = false;
    if (a_on && b_on) {
      if (ka == FeatureKind::kCorner && kb == FeatureKind::kCorner) return Reject::kTopology;
      // The paper's rule: an interior edge joining two surface nodes is never collapsed.
      surface_edge = is_surface_edge(a, b);
      if (!surface_edge) return Reject::kTopology;
      // Two curve/corner nodes may only merge along their curve.
      if (ka <= FeatureKind::kCurve && kb <= FeatureKind::kCurve && !is_feature_edge(a, b))
        return Reject::kTopology;
    }

    // The paper's valence of the new node, |v*(i)| + |v*(j)| - (|f*(i,j)| + 2), with
    // f*(i,j) the triangles (i, j, x) around the edge. It is the exact valence when
    // the link condition holds and an overestimate otherwise, so never too low.
    if (valence_[a] + valence_[b] - edge_triangle_count(a, b) - 2 > params_.max_valence)
      return Reject::kValence;
    double old_mean = 0;
    gather_moving(a, b, &old_mean);

    // Candidates: the more constrained end if the dimensions differ, else the midpoint
    // and then each end.
    uint32_t kept_options[3], unmoved[3];
    Vec3 positions[3];
    int options = 0;
    if (ka != kb) {
      const uint32_t keep = ka < kb ? a : b;
      kept_options[0] = unmoved[0] = keep;
      positions[0] = pos_[keep];
      options = 1;
    } else {
      kept_options[0] = std::min(a, b);
      unmoved[0] = kInvalidIndex;
      positions[0] = (pos_[a] + pos_[b]) * 0.5;
      kept_options[1] = unmoved[1] = a;
      positions[1] = pos_[a];
      kept_options[2] = unmoved[2] = b;
      positions[2] = pos_[b];
      options = 3;
    }
    Reject first = Reject::kNone;
    for (int c = 0; c < options; ++c) {
      double priority = 0;
      const Reject r = check_position(a, b, positions[c], unmoved[c], old_mean, &priority);
      if (r == Reject::kNone) {
        // The link conditions do not depend on the position or the priority: they are
        // checked when the collapse reaches the top of the queue (see simplify()).
        out->surface_edge = surface_edge;
        out->priority = priority;
        out->kept = kept_options[c];
        out->removed = out->kept == a ? b : a;
        out->position = positions[c];
        out->version_kept = version_[out->kept];
        out->version_removed = version_[out->removed];
        return Reject::kNone;
      }
      if (first == Reject::kNone) first = r;
    }
    return first;
  }

  void count(Reject r) {
    switch (r) {
      case Reject::kTolerance:
        ++rejections_.tolerance;
        break;
      case Reject::kStretch:
        ++rejections_.stretch;
        break;
      case Reject::kSize:
        ++rejections_.size;
        break;
      case Reject::kValence:
        ++rejections_.valence;
        break;
      case Reject::kTopology:
        ++rejections_.topology;
        break;
      case Reject::kNone:
        break;
    }
  }

  void evaluate_and_push(uint32_t a, uint32_t b) {
    Collapse c;
    const Reject r = evaluate(a, b, &c);
    if (r != Reject::kNone) {
      count(r);
      return;
    }
    heap_.push_back(c);
    std::push_heap(heap_.begin(), heap_.end(), CollapseLess());
  }

  // --------------------------------------------------------------- collapse
  // In tet `tet` (if any), the neighbour `from` becomes `to`.
  void replace_across(uint32_t tet, uint32_t from, uint32_t to) {
    if (tet == kInvalidIndex) return;
    uint32_t* across = &across_[4 * size_t{tet}];
    int c = 0;
    while (across[c] != from) ++c;
    across[c] = to;
  }

  void apply(const Collapse& c, CollapseHistory* history) {
    const uint32_t i = c.kept, j = c.removed;
    history->begin_step(i, j, pos_[i], c.position);
    // The tets around the edge, in star order. The stars and valences of their other
    // vertices change below: start loading them now.
    retired_tets_.clear();
    for (uint32_t t : star_[i]) {
      const Tet& q = tet_[t].v;
      if (!tet_has(q, j)) continue;
      retired_tets_.push_back(t);
      for (uint32_t x : q) {
        if (x == i || x == j) continue;  // loaded by topology_ok()
        __builtin_prefetch(&star_[x]);
        __builtin_prefetch(&valence_[x]);
      }
    }
    // Valences: i gets the neighbours of both ends (the paper's formula, exact under the
    // link condition); each vertex x of a triangle (i, j, x) loses one (j).
    const uint32_t triangles = edge_triangle_count(i, j);
    valence_[i] = valence_[i] + valence_[j] - triangles - 2;
    const uint32_t around_edge = stamp_;  // edge_triangle_count() marked the x's
    // Then what those point to: the ring vertices' stars, and the neighbours of the
    // ring's faces (i, x, y) and (j, x, y), glued below.
    for (uint32_t t : retired_tets_) {
      const Tet& q = tet_[t].v;
      for (int corner = 0; corner < 4; ++corner) {
        const uint32_t x = q[corner], across = across_[4 * t + corner];
        if (x != i && x != j) {
          __builtin_prefetch(star_[x].data());
        } else if (across != kInvalidIndex) {
          __builtin_prefetch(&across_[4 * size_t{across}]);
        }
      }
    }
    // Rewire j's other tets to i (in star order, as star_[j] is sorted).
    rewired_tets_.clear();
    for (uint32_t t : star_[j]) {
      Tet& q = tet_[t].v;
      if (tet_has(q, i)) continue;
      for (int corner = 0; corner < 4; ++corner) {
        if (q[corner] == j) {
          q[corner] = i;
          history->rewired.push_back(4 * t + corner);
        }
      }
      tet_[t].allowance = 0;
      rewired_tets_.push_back(t);
    }
    // Retire the tets around the edge.
    for (uint32_t t : retired_tets_) {
      const Tet& q = tet_[t].v;
      for (uint32_t x : q)
        if (mark_[x] == around_edge) mark_[x] = 0, --valence_[x];
      history->removed_tets.push_back(t);
      tet_[t].alive = 0;
      --material_tets_[material_index(tet_[t].material)];
      for (uint32_t w : q) {
        if (w == i || w == j) continue;
        auto& s = star_[w];
        s.erase(std::find(s.begin(), s.end(), t));
      }
      // Its faces (i, x, y) and (j, x, y) become one: glue the tets across them.
      int corner_i = 0, corner_j = 0;
      while (q[corner_i] != i) ++corner_i;
      while (q[corner_j] != j) ++corner_j;
      const uint32_t across_ixy = across_[4 * t + corner_j], across_jxy = across_[4 * t + corner_i];
      replace_across(across_ixy, t, across_jxy);
      replace_across(across_jxy, t, across_ixy);
    }
    // i's star: its own tets but the ring, then j's rewired ones, merged in order.
    // Where i stays in place, its own tets keep their shape (and stretch).
    const bool i_moves = std::memcmp(&pos_[i], &c.position, sizeof(Vec3)) != 0;
    pos_[i] = c.position;
    auto& si = star_[i];
    merged_star_.clear();
    auto rewired = rewired_tets_.begin();
    for (uint32_t t : si) {
      if (!tet_[t].alive) continue;
      history->moved.push_back(t);
      tet_[t].allowance = 0;
      if (i_moves) tet_[t].stretch = shape(t).stretch;
      for (; rewired != rewired_tets_.end() && *rewired < t; ++rewired)
        merged_star_.push_back(*rewired);
      merged_star_.push_back(t);
    }
    merged_star_.insert(merged_star_.end(), rewired, rewired_tets_.end());
    si.swap(merged_star_);
    for (uint32_t t : rewired_tets_) tet_[t].stretch = shape(t).stretch;
    star_[j].clear();
    star_[j].shrink_to_fit();
    vertex_alive_[j] = 0;
    quadric_[i].add(quadric_[j]);
    outer_[i] |= outer_[j];
    // Curves: j's feature neighbours become i's.
    for (uint32_t x : feature_neighbors_[j]) {
      if (x == i) continue;
      for (uint32_t& y : feature_neighbors_[x])
        if (y == j) y = i;
      feature_neighbors_[i].push_back(x);
    }
    auto& fi = feature_neighbors_[i];
    fi.erase(std::remove(fi.begin(), fi.end(), j), fi.end());
    feature_neighbors_[j].clear();
    alive_tets_ -=
        history->removed_end(history->step_count() - 1) - history->steps.back().removed_begin;
    ++collapses_;
  }

  // After a collapse onto k: the stars of k and of its neighbours changed. The edges
  // of k are re-evaluated now; the neighbours are marked dirty, so that their queued
  // edges are re-evaluated when popped (their version no longer matches) and all
  // their edges, valid or not before, are re-evaluated by the next sweep.
  void refresh_around(uint32_t k) {
    neighbors(k, &ring_);
    ring_.push_back(k);
    for (uint32_t v : ring_) {
      ++version_[v];
      if (!dirty_[v]) {
        dirty_[v] = 1;
        dirty_list_.push_back(v);
      }
    }
    ring_.pop_back();
    for (uint32_t w : ring_) evaluate_and_push(k, w);
  }

  // Re-evaluates every edge with a dirty end, once.
  void sweep() {
    std::vector<uint32_t> list;
    list.swap(dirty_list_);
    std::sort(list.begin(), list.end());
    for (uint32_t v : list) {
      if (!vertex_alive_[v]) continue;
      neighbors(v, &around_);
      std::sort(around_.begin(), around_.end());
      for (uint32_t w : around_) {
        if (w < v && dirty_[w]) continue;  // done from w's side
        evaluate_and_push(v, w);
      }
    }
    for (uint32_t v : list) dirty_[v] = 0;
  }

  void simplify(SimplifyResult* result) {
    version_.assign(pos_.size(), 0);
    dirty_.assign(pos_.size(), 0);
    dirty_list_.clear();
    alive_tets_ = tet_.size();
    const size_t initial_tets = alive_tets_;
    valence_.resize(pos_.size());
    for (uint32_t v = 0; v < pos_.size(); ++v) valence_[v] = valence(v);
    std::vector<uint32_t> nb;
    for (uint32_t v = 0; v < pos_.size(); ++v) {
      neighbors(v, &nb);
      for (uint32_t w : nb)
        if (w > v) evaluate_and_push(v, w);
    }
    size_t pops = 0;
    while (true) {
      if (params_.target_elements > 0 && alive_tets_ <= params_.target_elements) break;
      if (heap_.empty()) {
        if (dirty_list_.empty()) break;
        sweep();
        continue;
      }
      if ((++pops & 1023) == 0) {
        if (cancelled()) {
          result->cancelled = true;
          break;
        }
        report("simplify", 1.0 - double(alive_tets_) / double(initial_tets));
      }
      std::pop_heap(heap_.begin(), heap_.end(), CollapseLess());
      const Collapse c = heap_.back();
      heap_.pop_back();
      if (!vertex_alive_[c.kept] || !vertex_alive_[c.removed]) continue;
      if (c.version_kept != version_[c.kept] || c.version_removed != version_[c.removed]) {
        // Stale: evaluate again now unless a sweep already did.
        if (dirty_[c.kept] || dirty_[c.removed]) evaluate_and_push(c.kept, c.removed);
        continue;
      }
      if (!topology_ok(c.kept, c.removed, c.surface_edge)) {
        count(Reject::kTopology);
        continue;
      }
      apply(c, &result->history);
      refresh_around(c.kept);
    }
    report("simplify", 1);
  }

  // ----------------------------------------------------------------- output
  // The current arrays, every tet (alive or not).
  TetMesh mesh_now() const {
    TetMesh mesh;
    mesh.positions = pos_;
    mesh.tets.resize(tet_.size());
    mesh.materials.resize(tet_.size());
    for (size_t t = 0; t < tet_.size(); ++t) {
      mesh.tets[t] = tet_[t].v;
      mesh.materials[t] = tet_[t].material;
    }
    return mesh;
  }

  TetMesh compact() const {
    const TetMesh mesh = mesh_now();
    std::vector<uint8_t> alive(tet_.size());
    for (size_t t = 0; t < tet_.size(); ++t) alive[t] = tet_[t].alive;
    return extract_alive(mesh.positions, mesh.tets, mesh.materials, alive);
  }

  void count_violations(ThresholdViolations* v) {
    *v = ThresholdViolations{};
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      if (!tet_[t].alive) continue;
      const TetShape s = shape(t);
      const bool low = s.stretch < params_.min_stretch;
      const bool big = s.size > size_limit(t);
      v->below_stretch += low;
      v->above_size += big;
      if ((low && !(tet_[t].allowance & kMayBeThin)) || (big && !(tet_[t].allowance & kMayBeBig)))
        ++v->created;
    }
    for (uint32_t x = 0; x < pos_.size(); ++x) {
      if (!vertex_alive_[x] || star_[x].empty()) continue;
      const uint32_t n = valence(x);
      if (n > params_.max_valence) {
        ++v->above_valence;
        if (n > input_valence_[x]) ++v->created;
      }
    }
  }

  const SimplifyParams& params_;
  const ProgressCallback& progress_;
  const std::atomic<bool>* cancel_;
  double tolerance2_ = 0;

  std::vector<Vec3> pos_;
  std::vector<TetRecord> tet_;
  std::vector<std::vector<uint32_t>> star_;  // sorted tet ids per vertex
  std::vector<uint8_t> vertex_alive_;
  std::vector<uint32_t> input_valence_;
  std::vector<int32_t> material_ids_;  // sorted
  std::vector<size_t> material_tets_;  // alive tets per material, by index in material_ids_

  std::vector<FeatureKind> kind_;
  std::vector<std::vector<uint32_t>> feature_neighbors_;
  std::vector<Quadric> quadric_;

  std::vector<Collapse> heap_;
  std::vector<uint32_t> version_;
  std::vector<uint8_t> dirty_;
  std::vector<uint32_t> dirty_list_;
  RejectionCounts rejections_;
  size_t collapses_ = 0;
  size_t alive_tets_ = 0;

  // Scratch, reused to keep the hot loop free of allocation.
  std::vector<uint32_t> mark_;
  uint32_t stamp_ = 0;
  std::vector<uint32_t> ring_mark_;
  uint32_t ring_stamp_ = 0;
  std::vector<uint8_t> outer_;  // on the boundary of the whole mesh
  std::vector<int32_t> edge_materials_;
  std::vector<uint32_t> ring_, around_, ring_others_;
  std::vector<MovingTet> moving_;
  std::vector<std::pair<uint32_t, uint32_t>> moving_source_;  // (tet, its end of the edge)
  std::vector<uint32_t> valence_;  // per vertex, kept up to date by apply()
  // What the first pass of check_position() found of each moving tet, for the second.
  struct CandidateTet {
    double volume6, size2, face0, face1, face2;  // squared doubled areas of k's faces
    double limit;                                // tau_SZ of the tet
  };
  std::vector<CandidateTet> candidate_;
  bool uniform_sizing_ = false;  // only the uniform size is set: no per-tet field lookups
  // The tet across each face: across_[4 * t + c] is across the face of t opposite
  // corner c, or kInvalidIndex on the boundary (build_face_neighbors); kept up to date
  // by apply() for the alive tets.
  std::vector<uint32_t> across_;
  // link_condition(): the slot of each vertex of R, and flags per slot and per pair of
  // slots (r x r).
  static constexpr uint8_t kOpen = 1, kConeOfI = 2, kEdgeOfI = 4, kRingEdge = 8;
  std::vector<uint32_t> ring_slot_;
  std::vector<uint8_t> slot_flags_, pair_flags_;
  std::vector<std::pair<uint32_t, uint32_t>> ring_pairs_;            // the ring edges, as slots
  std::vector<uint64_t> ring_triples_;                               // triple_key()s of Lk(i) on R
  std::vector<uint32_t> retired_tets_, rewired_tets_, merged_star_;  // apply()
};

}  // namespace

Status simplify(const TetMesh& input, const SimplifyParams& params, SimplifyResult* result,
                const ProgressCallback& progress, const std::atomic<bool>* cancel) {
  Status s = check_params(params);
  if (!s) return s;
  *result = SimplifyResult{};
  Engine engine(input, params, progress, cancel);
  return engine.run(result);
}

}  // namespace tetlod
