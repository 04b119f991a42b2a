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
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <mutex>
#include <new>
#include <optional>
#include <queue>
#include <system_error>
#include <thread>

#include "core/adjacency.h"
#include "core/classify.h"
#include "core/face_grid.h"
#include "core/improve.h"
#include "core/metrics.h"
#include "core/morton.h"
#include "core/overlap.h"
#include "core/surface.h"
#include "core/triangle_cross.h"

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
    return Status::bad_value("tolerance " + number(p.tolerance) + " must be a finite length >= 0");
  }
  if (!(std::isfinite(p.min_stretch) && p.min_stretch > 0 && p.min_stretch < 1)) {
    return Status::bad_value("stretch " + number(p.min_stretch) +
                             " must lie strictly between 0 and 1 (1 is a regular tet)");
  }
  if (p.min_stretch < kMinStretch) {
    return Status::bad_value(
        "stretch " + number(p.min_stretch) + " must be at least " + number(kMinStretch) +
        " (below it, tets too flat to read back, lost in rounding, would pass)");
  }
  if (p.max_valence < 4) {
    return Status::bad_value("valence " + std::to_string(p.max_valence) +
                             " must be at least 4 (a tet's corner already has 3 neighbours)");
  }
  if (p.max_valence > kMaxValence) {
    return Status::bad_value("valence " + std::to_string(p.max_valence) + " must be at most " +
                             std::to_string(kMaxValence) +
                             " (analysis meshes have nodes of 20 to 60 neighbours; the work of a "
                             "collapse grows with its nodes')");
  }
  if (p.sizing.unlimited()) return Status::bad_value("no size limit given (set --size)");
  const double smallest = p.sizing.smallest_size();
  if (!(smallest > 0) || std::isnan(p.sizing.uniform) || p.sizing.uniform <= 0) {
    return Status::bad_value("size must be > 0");
  }
  if (!(std::isfinite(p.crease_angle_degrees) && p.crease_angle_degrees > 0 &&
        p.crease_angle_degrees < 180)) {
    return Status::bad_value("crease angle must lie between 0 and 180 degrees");
  }
  if (p.past_valence_tets_factor < 1) {
    return Status::bad_value("past_valence_tets_factor " +
                             std::to_string(p.past_valence_tets_factor) + " must be >= 1");
  }
  return Status();
}

namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kMaxTets = 40'000'000;  // subdivision refuses to grow beyond this
constexpr int kMostRedLevels = 12;       // red levels of a run past the valence (2^12 x)
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

enum class Reject : uint8_t { kNone, kTolerance, kStretch, kSize, kValence, kTopology, kOverlap };

// What the queue keeps of a valid collapse, in 32 bytes (the queue holds a few hundred
// thousand and is walked at random): the position is restored when it is popped.
struct QueuedCollapse {
  double priority = 0;
  uint32_t kept = 0, removed = 0;
  uint32_t version_kept = 0, version_removed = 0;
  bool surface_edge = false;
  bool midpoint = false;  // the new position is the midpoint (else the kept end's)
};
static_assert(sizeof(QueuedCollapse) == 32, "two per cache line");

struct Collapse : QueuedCollapse {
  Vec3 position;
};

// Storage that starts on a cache line (64 bytes).
template <class T>
struct LineAligned {
  using value_type = T;
  LineAligned() = default;
  template <class U>
  LineAligned(const LineAligned<U>&) {}  // NOLINT: rebinding, as std::allocator
  T* allocate(size_t n) {
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64}));
  }
  void deallocate(T* p, size_t) { ::operator delete (p, std::align_val_t{64}); }
  bool operator==(const LineAligned&) const { return true; }
  bool operator!=(const LineAligned&) const { return false; }
};

// Max-heap order: larger priority first, then the smaller vertex pair.
struct CollapseLess {
  bool operator()(const QueuedCollapse& x, const QueuedCollapse& y) const {
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

template <class T>
void sort_unique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// A node by its position, bit for bit: the same in every run on one input, where the
// ids of the nodes subdivision makes are not.
using PositionKey = std::array<uint64_t, 3>;
PositionKey position_key(const Vec3& p) {
  PositionKey key;
  std::memcpy(&key[0], &p.x, sizeof(double));
  std::memcpy(&key[1], &p.y, sizeof(double));
  std::memcpy(&key[2], &p.z, sizeof(double));
  return key;
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

// The tets around a collapse that survive it, reduced to what their shape with the
// moving corner at a candidate position k needs (the fixed face, its normal and
// lengths), in blocks of kLanes tets stored by field, so that the candidate test
// runs over a block several tets per instruction.
constexpr int kLanes = 8;
struct alignas(64) TetBlock {
  double f0x[kLanes], f0y[kLanes], f0z[kLanes];  // the fixed corners
  double f1x[kLanes], f1y[kLanes], f1z[kLanes];
  double f2x[kLanes], f2y[kLanes], f2z[kLanes];
  double nx[kLanes], ny[kLanes], nz[kLanes];  // (f1 - f0) x (f2 - f0), away from k
  double fixed_max2[kLanes];                  // longest squared edge of the fixed face
  double fixed_normal2[kLanes];               // |n|^2 = (2 x fixed area)^2
  double side[kLanes];                        // 0: a tet of the first end, 1: the second
  double steady[kLanes];                      // 1: meets every threshold now (allowance 0)
  double skip[kLanes];                        // 1: not a tet of t*(k) (ring, padding)
  double stretch_now[kLanes];                 // its stretch now
  double limit[kLanes];                       // tau_SZ of the tet with k in place
  double material_limit[kLanes];              // its part that does not depend on k
  // Of the candidate: 6 V, s^2, (2 x area of k's three faces)^2, the first pass's
  // verdict (0 passed, 1 stretch, 2 size), then the exact size and stretch.
  double volume6[kLanes], size2[kLanes], face0[kLanes], face1[kLanes], face2[kLanes];
  double code[kLanes];
  double size[kLanes], stretch[kLanes];
  int32_t material[kLanes];
};

// The kernels below are compiled twice, for AVX2 and for the baseline instruction
// set, and picked at run time (vector_kernels()); both do the same IEEE operations in
// the same order (no fused multiply-add, no reassociation), so the result does not
// depend on the machine. A test runs both and compares.
#if defined(__x86_64__) && defined(__GNUC__)
#define TETLOD_X86_DISPATCH 1
#else
#define TETLOD_X86_DISPATCH 0
#endif
#define TETLOD_KERNEL inline __attribute__((always_inline))

// The normal and squared lengths of the fixed faces of a block.
TETLOD_KERNEL void fixed_faces(TetBlock& b) {
  for (int n = 0; n < kLanes; ++n) {
    const double ax = b.f1x[n] - b.f0x[n], ay = b.f1y[n] - b.f0y[n], az = b.f1z[n] - b.f0z[n];
    const double bx = b.f2x[n] - b.f0x[n], by = b.f2y[n] - b.f0y[n], bz = b.f2z[n] - b.f0z[n];
    const double cx = b.f2x[n] - b.f1x[n], cy = b.f2y[n] - b.f1y[n], cz = b.f2z[n] - b.f1z[n];
    const double px = ay * bz - az * by, py = az * bx - ax * bz, pz = ax * by - ay * bx;
    b.nx[n] = px;
    b.ny[n] = py;
    b.nz[n] = pz;
    b.fixed_normal2[n] = px * px + py * py + pz * pz;
    const double a2 = ax * ax + ay * ay + az * az, b2 = bx * bx + by * by + bz * bz,
                 c2 = cx * cx + cy * cy + cz * cz;
    const double ab = a2 < b2 ? b2 : a2;  // as std::max({a2, b2, c2})
    b.fixed_max2[n] = ab < c2 ? c2 : ab;
  }
}

// First pass for candidate k over a block: volume, size and the stretch bound,
// without square roots. Tets of end `unmoved` (0, 1; -1: neither) that meet every
// threshold keep their shape and pass.
TETLOD_KERNEL void first_pass(TetBlock& b, double kx, double ky, double kz, double unmoved,
                              double floor2) {
  for (int n = 0; n < kLanes; ++n) {
    const double d0x = b.f0x[n] - kx, d0y = b.f0y[n] - ky, d0z = b.f0z[n] - kz;
    const double d1x = b.f1x[n] - kx, d1y = b.f1y[n] - ky, d1z = b.f1z[n] - kz;
    const double d2x = b.f2x[n] - kx, d2y = b.f2y[n] - ky, d2z = b.f2z[n] - kz;
    const double l0 = d0x * d0x + d0y * d0y + d0z * d0z;
    const double l1 = d1x * d1x + d1y * d1y + d1z * d1z;
    const double l2 = d2x * d2x + d2y * d2y + d2z * d2z;
    double s2 = b.fixed_max2[n];  // as std::max({fixed, l0, l1, l2})
    s2 = s2 < l0 ? l0 : s2;
    s2 = s2 < l1 ? l1 : s2;
    s2 = s2 < l2 ? l2 : s2;
    const double v6 = b.nx[n] * d0x + b.ny[n] * d0y + b.nz[n] * d0z;  // 6 V with k in place
    const double c01x = d0y * d1z - d0z * d1y, c01y = d0z * d1x - d0x * d1z,
                 c01z = d0x * d1y - d0y * d1x;
    const double c12x = d1y * d2z - d1z * d2y, c12y = d1z * d2x - d1x * d2z,
                 c12z = d1x * d2y - d1y * d2x;
    const double c20x = d2y * d0z - d2z * d0y, c20y = d2z * d0x - d2x * d0z,
                 c20z = d2x * d0y - d2y * d0x;
    const double f0 = c01x * c01x + c01y * c01y + c01z * c01z;
    const double f1 = c12x * c12x + c12y * c12y + c12z * c12z;
    const double f2 = c20x * c20x + c20y * c20y + c20z * c20z;
    const double area_squares = 0.25 * b.fixed_normal2[n] + 0.25 * (f0 + f1 + f2);
    b.volume6[n] = v6;
    b.size2[n] = s2;
    b.face0[n] = f0;
    b.face1[n] = f1;
    b.face2[n] = f2;
    const double thin = 6 * v6 * v6 < floor2 * s2 * area_squares ? 1.0 : 0.0;
    const double verdict = v6 > 0 ? (s2 > b.limit[n] * b.limit[n] ? 2.0 : thin) : 1.0;
    const bool keeps = (b.side[n] == unmoved) & (b.steady[n] != 0);
    b.code[n] = (keeps | (b.skip[n] != 0)) ? 0.0 : verdict;
  }
}

// Exact size and stretch of eq. (2) over a block, from the first pass:
// d_t = 6 sqrt(6) V_t / (s_t A_t), with 6 V_t = volume6.
TETLOD_KERNEL void exact_pass(TetBlock& b) {
  const double root6 = std::sqrt(6.0);
  for (int n = 0; n < kLanes; ++n) {
    const double s = std::sqrt(b.size2[n]);
    const double area =
        0.5 * std::sqrt(b.fixed_normal2[n]) +
        0.5 * (std::sqrt(b.face0[n]) + std::sqrt(b.face1[n]) + std::sqrt(b.face2[n]));
    b.size[n] = s;
    b.stretch[n] = root6 * b.volume6[n] / (s * area);
  }
}

struct VectorKernels {
  const char* name;
  void (*fixed_faces)(TetBlock&);
  void (*first_pass)(TetBlock&, double, double, double, double, double);
  void (*exact_pass)(TetBlock&);
};

void fixed_faces_baseline(TetBlock& b) {
  fixed_faces(b);
}
void first_pass_baseline(TetBlock& b, double x, double y, double z, double unmoved, double f) {
  first_pass(b, x, y, z, unmoved, f);
}
void exact_pass_baseline(TetBlock& b) {
  exact_pass(b);
}

#if TETLOD_X86_DISPATCH
__attribute__((target("avx2"))) void fixed_faces_avx2(TetBlock& b) {
  fixed_faces(b);
}
__attribute__((target("avx2"))) void first_pass_avx2(TetBlock& b, double x, double y, double z,
                                                     double unmoved, double f) {
  first_pass(b, x, y, z, unmoved, f);
}
__attribute__((target("avx2"))) void exact_pass_avx2(TetBlock& b) {
  exact_pass(b);
}
#endif

// AVX2 where the processor has it, unless the environment sets TETLOD_NO_AVX2 (to a
// value other than 0): then the baseline kernels, as on a machine without AVX2.
const VectorKernels& vector_kernels() {
  static const VectorKernels chosen = [] {
#if TETLOD_X86_DISPATCH
    const char* off = std::getenv("TETLOD_NO_AVX2");
    const bool disabled = off != nullptr && *off != '\0' && std::string(off) != "0";
    if (!disabled && __builtin_cpu_supports("avx2"))
      return VectorKernels{"avx2", fixed_faces_avx2, first_pass_avx2, exact_pass_avx2};
#endif
    return VectorKernels{"baseline", fixed_faces_baseline, first_pass_baseline,
                         exact_pass_baseline};
  }();
  return chosen;
}

class Engine {
 public:
  // past_valence: subdivision may take nodes past tau_VL (see ::simplify()), but not
  // those at the positions in `pinned` (sorted), if given.
  Engine(const TetMesh& input, const SimplifyParams& params, const ProgressCallback& progress,
         const std::atomic<bool>* cancel, bool past_valence,
         const std::vector<PositionKey>* pinned = nullptr)
      : params_(params),
        progress_(progress),
        cancel_(cancel),
        past_valence_(past_valence),
        pinned_(pinned),
        pos_(input.positions) {
    tolerance2_ = params.tolerance * params.tolerance;
    uniform_sizing_ = !params.sizing.has_local_rules();
    region_sizing_ = params.sizing.has_region_rules();
    late_limits_ = params.sizing.map != nullptr;
    // For a test: TETLOD_REPEAT_EVALUATIONS (other than 0) makes every repeat again,
    // which must not change the result (evaluated_as_is()).
    const char* repeat = std::getenv("TETLOD_REPEAT_EVALUATIONS");
    skip_repeats_ = repeat == nullptr || *repeat == '\0' || std::string(repeat) == "0";
    tet_.resize(input.tets.size());
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      tet_[t].v = input.tets[t];
      tet_[t].material = input.materials[t];
    }
    star_.resize(pos_.size());
    mark_.assign(pos_.size(), 0);
    reorder_for_locality();  // builds the stars
    // Each tet's shape once: its stretch is kept up to date from here on.
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      const TetShape s = shape(t);
      const double limit = size_limit(t);
      tet_[t].stretch = s.stretch;
      tet_[t].allowance = static_cast<uint8_t>((s.stretch < params_.min_stretch ? kMayBeThin : 0) |
                                               (s.size > limit ? kMayBeBig : 0));
      const double ratio = 2 * s.size / limit;  // for the size check of subdivide()
      if (ratio > 1) predicted_splits_ += ratio * ratio * ratio;
    }
    input_valence_.resize(pos_.size());
    for (uint32_t v = 0; v < pos_.size(); ++v) input_valence_[v] = valence(v);
  }

  Status run(SimplifyResult* result) {
    auto start = Clock::now();
    // The input groups' faces inside a material: their edges, which are not split.
    if (patches_ && !patches_->inside_entries().empty()) {
      for (const auto& f : inside_faces(mesh_now(), *patches_))
        for (int k = 0; k < 3; ++k)
          kept_edges_.push_back({std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])});
      sort_unique(kept_edges_);
    }
    if (params_.subdivide) {
      Status s = subdivide(result);
      if (!s) {
        result->seconds_subdivide = seconds_since(start);
        result->over_tets_factor = over_factor_;
        return s;
      }
    }
    if (result->splits_past_valence > 0 && !cancelled()) shed_valence_by_flips(result);
    if (result->splits > 0) reorder_for_locality();  // new vertices were appended
    // (Counted in the subdivision's time: 3 ms on the 331,512 tets of the 220k motor at
    // size 9.8.)
    if (after_subdivide_ && !cancelled() && result->splits_skipped_valence > 0) {
      size_t tets = 0;
      const size_t above = tets_above_size(&tets);
      after_subdivide_(tets, above);
    }
    result->seconds_subdivide = seconds_since(start);
    result->base = mesh_now();
    if (cancelled()) {
      result->cancelled = true;
      result->output = result->base;
      return Status();
    }

    start = Clock::now();
    report("classify", 0);
    classify(result->base);
    report("classify", 1);
    result->seconds_classify = seconds_since(start);

    start = Clock::now();
    simplify(result);
    result->seconds_simplify = seconds_since(start);
    result->rejections = rejections_;
    result->evaluations = evaluations_;
    result->kernels = kernels_.name;
    result->output = compact();
    count_violations(&result->violations);
    return Status();
  }

 private:
  // ---------------------------------------------------------------- helpers
  bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }

  void report(const char* phase, double fraction) {
    if (progress_) progress_({phase, fraction, collapses_, past_valence_});
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

  // Without branches on the marks (whether a corner was seen is not predictable):
  // every corner is written, and kept if it is new.
  void neighbors(uint32_t v, std::vector<uint32_t>* out) {
    const auto& star = star_[v];
    out->resize(4 * star.size());
    const uint32_t s = next_stamp();
    mark_[v] = s;
    size_t n = 0;
    for (uint32_t t : star) {
      for (uint32_t w : tet_[t].v) {
        (*out)[n] = w;
        n += mark_[w] != s;
        mark_[w] = s;
      }
    }
    out->resize(n);
  }

  double size_limit(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                    int32_t material) const {
    return params_.sizing.size_at(tet_centroid(a, b, c, d), material);
  }
  double size_limit(uint32_t t) const {
    const Tet& q = tet_[t].v;
    return size_limit(pos_[q[0]], pos_[q[1]], pos_[q[2]], pos_[q[3]], tet_[t].material);
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
    std::vector<std::pair<uint64_t, uint32_t>> order(vertex_count);
    for (uint32_t v = 0; v < vertex_count; ++v)
      order[v] = {morton_key((pos_[v] - lo) * (2097151.0 / extent)), v};
    std::sort(order.begin(), order.end());
    std::vector<uint32_t> new_id(vertex_count);
    for (uint32_t k = 0; k < vertex_count; ++k) new_id[order[k].second] = k;
    std::vector<Vec3> positions(vertex_count);
    std::vector<uint32_t> valences(vertex_count);
    const bool has_valences = input_valence_.size() == vertex_count;
    for (uint32_t v = 0; v < vertex_count; ++v) {
      positions[new_id[v]] = pos_[v];
      if (has_valences) valences[new_id[v]] = input_valence_[v];
    }
    pos_.swap(positions);
    input_valence_.swap(valences);
    for (TetRecord& t : tet_)
      for (uint32_t& v : t.v) v = new_id[v];

    // Tets by smallest vertex, ties in their old order: a counting sort.
    std::vector<uint32_t> first(vertex_count + 1, 0);
    for (const TetRecord& t : tet_) ++first[std::min({t.v[0], t.v[1], t.v[2], t.v[3]}) + 1];
    for (size_t v = 0; v < vertex_count; ++v) first[v + 1] += first[v];
    std::vector<TetRecord> tets(tet_count);
    for (const TetRecord& t : tet_) tets[first[std::min({t.v[0], t.v[1], t.v[2], t.v[3]})]++] = t;
    tet_.swap(tets);
    std::vector<uint32_t> star_size(vertex_count, 0);
    for (const TetRecord& t : tet_)
      for (uint32_t v : t.v) ++star_size[v];
    for (uint32_t v = 0; v < vertex_count; ++v) {
      star_[v].clear();
      star_[v].reserve(star_size[v]);
    }
    for (uint32_t t = 0; t < tet_count; ++t)
      for (uint32_t v : tet_[t].v) star_[v].push_back(t);
  }

  // ------------------------------------------------------------ subdivision
  // Longest edge first (a max-heap on length): a popped edge is the longest edge of
  // every tet around it, so this is conforming longest-edge bisection. A split is
  // skipped, and counted, if a child would fall below min(tau_ST, its parent's
  // stretch) or a node would exceed tau_VL (twice tau_VL in a run past the valence,
  // whose nodes past tau_VL are brought back before the collapses start, or the run is
  // given up: see ::simplify()).
  double edge_size_limit(uint32_t a, uint32_t b) const {
    if (uniform_sizing_) return params_.sizing.uniform;
    double limit = std::numeric_limits<double>::infinity();
    for (uint32_t t : star_[a])
      if (tet_has(tet_[t].v, b)) limit = std::min(limit, size_limit(t));
    return limit;
  }

  // Whether a red level's split of edge (a, b) would give its midpoint more neighbours
  // than tau_VL: at least the two ends and the midpoints of the edges from each end to
  // each of the r nodes round the edge, 2 + 2 r (34 for the 16 tets round the bundled
  // motor's axis), however the octahedra are cut. A run past the valence bisects such
  // edges longer than their limit (those a red level would mark) before its red levels:
  // the midpoint then starts with 2 + r neighbours, and each node round the edge gains
  // one. The halves have the same nodes round them, and are bisected again while they
  // are longer than their limit. (The halves of an edge a red level splits have as
  // many nodes round them as the edge, so the red levels rarely make another; they are
  // not looked for again.) On the bundled motor at sizes 6 and 7, two such bisections
  // are what lets the run past the valence bring every node back (docs/RESULTS.md).
  bool hot_edge(uint32_t a, uint32_t b) {
    const uint32_t s = next_stamp();
    mark_[a] = mark_[b] = s;
    size_t round = 0;
    for (uint32_t t : star_[a]) {
      if (!tet_has(tet_[t].v, b)) continue;
      for (uint32_t w : tet_[t].v) {
        round += mark_[w] != s;
        mark_[w] = s;
      }
    }
    return 2 + 2 * round > params_.max_valence;
  }

  // The most neighbours subdivision may give a node at p.
  size_t valence_cap(const Vec3& p) const {
    if (!past_valence_) return params_.max_valence;
    if (pinned_ && std::binary_search(pinned_->begin(), pinned_->end(), position_key(p)))
      return params_.max_valence;
    return 2 * size_t{params_.max_valence};
  }

  // What a bisection splits: the edges longer than half their size limit, or (before
  // a run past the valence's red levels) the hot edges (hot_edge()).
  enum class Bisect { kHalfSize, kHotEdges };

  // Queues edge (a, b) for bisection if it is one `mode` splits.
  void push_if_long(std::vector<Split>& heap, uint32_t a, uint32_t b, Bisect mode) {
    const double length2 = squared_length(pos_[a] - pos_[b]);
    const double limit = edge_size_limit(a, b);
    if (mode == Bisect::kHotEdges ? length2 > limit * limit && hot_edge(a, b)
                                  : length2 > 0.25 * limit * limit) {
      heap.push_back({length2, std::min(a, b), std::max(a, b)});
      std::push_heap(heap.begin(), heap.end(), SplitLess());
    }
  }

  // ------------------------------------------------- red levels (Bey's 1:8 split)
  // Longest-edge bisection joins the two corners opposite a split edge to its
  // midpoint, so splitting the edges of a region raises the valence of its nodes by
  // about their number of neighbours: on a coarse input, subdivision within tau_VL
  // leaves long edges unsplit. Red refinement (Bey, Computing 55, 1995) does not: a
  // tet whose six edges are split becomes its four corner tets (its shape, half its
  // size) and four tets of the inner octahedron, and each corner trades its
  // neighbours for the midpoints of its edges. A run past the valence starts with red
  // levels. A level marks every edge longer than its size limit (the bisection that
  // follows splits the ones between half the size and the size), then closes the
  // marking: a face with two marked edges gets its third, unless that one is frozen.
  // Each tet then has one of five patterns with one conforming split each: none, one
  // edge (bisected), two opposite edges (bisected twice), the three edges of a face
  // (its four triangles, each joined to the opposite corner), all six (red); or, next
  // to a frozen edge, any other, whose faces are cut by face_triangles() and joined to
  // the tet's centroid. A tet whose pieces would be flatter than min(tau_ST, itself)
  // or above their size limit (unless it was) is made red, or if it is red or cannot
  // be, its edges are frozen; so are edges whose midpoint would exceed the valence
  // cap, and a tet split but not red around a node that would exceed it, where it
  // grows, is made red or frozen. The marking is closed again until nothing breaks.
  // Levels repeat while they split an edge longer than its limit; from the fourth on,
  // one that splits under 1/64 of the long edges it marks is the last.
  // The three edges of the face opposite each corner.
  static constexpr int kFaceEdges[4][3] = {{3, 4, 5}, {1, 2, 5}, {0, 2, 4}, {0, 1, 3}};

  // A red level works on the tets it may split and their edges only: the tets with an
  // edge longer than its limit, and the tets a marking reaches from them. Edges and
  // tets get level ids (tets: slots) in the order the level first meets them, so that
  // a level which splits a few edges of a large mesh costs one pass over its tets
  // (and the new tet array) rather than one over every edge and tet for each round.
  // What a level does is what a pass over every edge and tet would do: the rules below
  // read only tets around marked edges, loops whose order matters run in tet or vertex
  // order, and the new vertices are numbered as before (midpoints in the order of their
  // edges' sorted end pairs, centroids in tet order).
  struct RedLevel {
    std::vector<std::array<uint32_t, 2>> ends;  // of each edge (a < b)
    std::vector<double> limit;                  // of each edge: the smallest of its tets'
    std::vector<uint32_t> tets_first{0};        // tets of edge e: tets[first[e], first[e+1])
    std::vector<uint32_t> tets;
    std::vector<uint8_t> marked, frozen;
    std::vector<uint32_t> slot_of;    // of each tet of the mesh, or kInvalidIndex
    std::vector<uint32_t> slot_tet;   // the tet in each slot
    std::vector<uint32_t> slot_edge;  // 6 per slot: edge ids, in the order of kTetEdge
    std::vector<int8_t> passed;       // of each slot: the mask whose pieces last passed
    std::vector<uint8_t> queued;      // of each slot: on the closure's work list
    std::vector<uint32_t> fresh;      // slots made since the last pass in tet order
    // Edge ids by end pair: open addressing on a << 32 | b (never 0, as a < b).
    std::vector<uint64_t> keys;
    std::vector<uint32_t> ids;
    int shift = 64;
  };

  // Plan ids: a vertex id v < V; V + 2e, the midpoint of edge e; V + 2s + 1, the
  // centroid of the tet in slot s (a level has at most 6 edges per slot and 40M
  // slots, so these fit in 32 bits).
  Vec3 plan_position(const RedLevel& level, uint32_t v) const {
    const uint32_t n = static_cast<uint32_t>(pos_.size());
    if (v < n) return pos_[v];
    const uint32_t d = v - n;
    if ((d & 1) == 0) {
      const auto& e = level.ends[d >> 1];
      return (pos_[e[0]] + pos_[e[1]]) * 0.5;
    }
    const Tet& q = tet_[level.slot_tet[d >> 1]].v;
    return (pos_[q[0]] + pos_[q[1]] + pos_[q[2]] + pos_[q[3]]) * 0.25;
  }

  static int slot_mask(const RedLevel& level, uint32_t s) {
    int mask = 0;
    for (int k = 0; k < 6; ++k) mask |= level.marked[level.slot_edge[6 * size_t{s} + k]] << k;
    return mask;
  }

  static uint64_t edge_hash(uint64_t key, int shift) {
    return (key * 0x9E3779B97F4A7C15ull) >> shift;
  }

  // The id of edge (a, b), made (with its tets, its limit and whether it is kept) when
  // first asked for.
  uint32_t level_edge(RedLevel* level, uint32_t a, uint32_t b) const {
    if (a > b) std::swap(a, b);
    const uint64_t key = uint64_t{a} << 32 | b;
    if (2 * (level->ends.size() + 1) > level->keys.size()) {  // grow: at most half full
      const size_t capacity = std::max<size_t>(1024, 2 * level->keys.size());
      level->keys.assign(capacity, 0);
      level->ids.assign(capacity, 0);
      level->shift = 64 - __builtin_ctzll(capacity);
      for (uint32_t e = 0; e < level->ends.size(); ++e) {
        const uint64_t k = uint64_t{level->ends[e][0]} << 32 | level->ends[e][1];
        uint64_t h = edge_hash(k, level->shift);
        while (level->keys[h] != 0) h = (h + 1) & (capacity - 1);
        level->keys[h] = k, level->ids[h] = e;
      }
    }
    const uint64_t mask = level->keys.size() - 1;
    uint64_t h = edge_hash(key, level->shift);
    for (; level->keys[h] != 0; h = (h + 1) & mask)
      if (level->keys[h] == key) return level->ids[h];
    const uint32_t e = static_cast<uint32_t>(level->ends.size());
    level->keys[h] = key, level->ids[h] = e;
    level->ends.push_back({a, b});
    double limit = std::numeric_limits<double>::infinity();
    for (uint32_t t : star_[a])
      if (tet_has(tet_[t].v, b)) {
        level->tets.push_back(t);
        limit = std::min(limit, uniform_sizing_ ? params_.sizing.uniform : size_limit(t));
      }
    level->tets_first.push_back(static_cast<uint32_t>(level->tets.size()));
    level->limit.push_back(limit);
    level->marked.push_back(0);
    level->frozen.push_back(
        !kept_edges_.empty() &&
        std::binary_search(kept_edges_.begin(), kept_edges_.end(), std::make_pair(a, b)));
    return e;
  }

  // The slot of tet t, made (with its edges) when first asked for.
  uint32_t level_slot(RedLevel* level, uint32_t t) const {
    if (level->slot_of[t] != kInvalidIndex) return level->slot_of[t];
    const uint32_t s = static_cast<uint32_t>(level->slot_tet.size());
    level->slot_of[t] = s;
    level->slot_tet.push_back(t);
    const Tet& v = tet_[t].v;
    for (const auto& k : kTetEdge) {
      const uint32_t e = level_edge(level, v[k[0]], v[k[1]]);
      level->slot_edge.push_back(e);
    }
    level->passed.push_back(-1);
    level->queued.push_back(0);
    level->fresh.push_back(s);
    return s;
  }

  // The pieces of the tet in `slot` under its marked edges, positively oriented, in
  // plan ids.
  void red_pieces(const RedLevel& level, uint32_t slot, std::vector<Tet>* out) const {
    out->clear();
    const uint32_t n = static_cast<uint32_t>(pos_.size());
    const Tet& v = tet_[level.slot_tet[slot]].v;
    const uint32_t* te = &level.slot_edge[6 * size_t{slot}];
    uint32_t mid[6];
    int mask = 0;
    for (int k = 0; k < 6; ++k) {
      mid[k] = n + 2 * te[k];
      mask |= level.marked[te[k]] << k;
    }
    auto bisect = [&](const Tet& q, uint32_t a, uint32_t b, uint32_t m, Tet* x, Tet* y) {
      *x = q, *y = q;
      for (int c = 0; c < 4; ++c) {
        if (q[c] == b) (*x)[c] = m;
        if (q[c] == a) (*y)[c] = m;
      }
    };
    auto edge_of = [&](int k, int s) { return v[kTetEdge[k][s]]; };
    if (mask == 0) {
      out->push_back(v);
    } else if ((mask & (mask - 1)) == 0) {  // one edge
      const int k = __builtin_ctz(mask);
      Tet x, y;
      bisect(v, edge_of(k, 0), edge_of(k, 1), mid[k], &x, &y);
      out->push_back(x), out->push_back(y);
    } else if (mask == 0b100001 || mask == 0b010010 || mask == 0b001100) {  // opposite
      const int k1 = __builtin_ctz(mask), k2 = 5 - k1;
      Tet x, y, p[4];
      bisect(v, edge_of(k1, 0), edge_of(k1, 1), mid[k1], &x, &y);
      bisect(x, edge_of(k2, 0), edge_of(k2, 1), mid[k2], &p[0], &p[1]);
      bisect(y, edge_of(k2, 0), edge_of(k2, 1), mid[k2], &p[2], &p[3]);
      out->insert(out->end(), p, p + 4);
    } else if (mask == 63) {
      for (int i = 0; i < 4; ++i) {
        Tet c = v;
        for (int j = 0; j < 4; ++j)
          if (j != i) c[j] = mid[local_edge(i, j)];
        out->push_back(c);
      }
      // The octahedron, cut along the diagonal whose four tets have the best worst
      // stretch (the first of equals).
      double best = -std::numeric_limits<double>::infinity();
      Tet inner[4];
      for (int k = 0; k < 3; ++k) {
        const uint32_t p = mid[k], q = mid[5 - k];
        // The other four midpoints in a cycle (consecutive ones share a corner).
        static constexpr int kRing[3][4] = {{1, 2, 4, 3}, {0, 2, 5, 3}, {0, 1, 5, 4}};
        const uint32_t ring[4] = {mid[kRing[k][0]], mid[kRing[k][1]], mid[kRing[k][2]],
                                  mid[kRing[k][3]]};
        Tet cut[4];
        double worst = std::numeric_limits<double>::infinity();
        for (int s = 0; s < 4; ++s) {
          cut[s] = {p, q, ring[s], ring[(s + 1) % 4]};
          orient_plan(level, &cut[s]);
          const Tet& c = cut[s];
          worst = std::min(worst, tet_shape(plan_position(level, c[0]), plan_position(level, c[1]),
                                            plan_position(level, c[2]), plan_position(level, c[3]))
                                      .stretch);
        }
        if (worst > best) best = worst, std::copy(cut, cut + 4, inner);
      }
      out->insert(out->end(), inner, inner + 4);
    } else if (face_mask_corner(mask) < 4) {  // the three edges of the face opposite d
      const int d = face_mask_corner(mask);
      int face[3], r = 0;
      for (int c = 0; c < 4; ++c)
        if (c != d) face[r++] = c;
      const int a = face[0], b = face[1], c = face[2];
      Tet x = v;  // corner a
      x[b] = mid[local_edge(a, b)], x[c] = mid[local_edge(a, c)];
      out->push_back(x);
      x = v;  // corner b
      x[a] = mid[local_edge(a, b)], x[c] = mid[local_edge(b, c)];
      out->push_back(x);
      x = v;  // corner c
      x[a] = mid[local_edge(a, c)], x[b] = mid[local_edge(b, c)];
      out->push_back(x);
      x = v;  // the middle triangle: a -> ab, b -> bc, c -> ca keeps the orientation
      x[a] = mid[local_edge(a, b)], x[b] = mid[local_edge(b, c)], x[c] = mid[local_edge(a, c)];
      out->push_back(x);
    } else {
      // Any other marking (a face with two marked edges, whose third may not be
      // split): each face is cut by the rule of face_triangles(), the same from both
      // its tets, and joined to the tet's centroid.
      const uint32_t g = n + 2 * slot + 1;
      for (int d = 0; d < 4; ++d) {
        const int* f = kFaceEdges[d];
        int corner[3], r = 0;
        for (int c = 0; c < 4; ++c)
          if (c != d) corner[r++] = c;
        std::array<uint32_t, 3> tri[4];
        const int count = face_triangles(
            level, v[corner[0]], v[corner[1]], v[corner[2]], {mid[f[0]], mid[f[1]], mid[f[2]]},
            {level.marked[te[f[0]]] != 0, level.marked[te[f[1]]] != 0, level.marked[te[f[2]]] != 0},
            tri);
        for (int k = 0; k < count; ++k) {
          Tet x = {tri[k][0], tri[k][1], tri[k][2], g};
          orient_plan(level, &x);
          out->push_back(x);
        }
      }
    }
  }

  // The index in kTetEdge of the edge of corners i and j (i != j).
  static int local_edge(int i, int j) {
    if (i > j) std::swap(i, j);
    return i == 0 ? j - 1 : i + j;  // (0,1)0 (0,2)1 (0,3)2 (1,2)3 (1,3)4 (2,3)5
  }

  // The corner opposite the face whose three edges are the mask, or 4.
  static int face_mask_corner(int mask) {
    for (int d = 0; d < 4; ++d) {
      const int* f = kFaceEdges[d];
      if (mask == (1 << f[0] | 1 << f[1] | 1 << f[2])) return d;
    }
    return 4;
  }

  // The triangles of face (a, b, c) (a < b < c by local slot, edges in the order of
  // kFaceEdges: ab, ac, bc) under its marked edges, whose midpoints are mid: none
  // marked, itself; one, halved; three, its four triangles; two, the triangle at
  // their common corner and the rest cut along the shorter diagonal (ties: by ids).
  // Every rule reads only the face, so both tets of a face cut it alike.
  int face_triangles(const RedLevel& level, uint32_t a, uint32_t b, uint32_t c,
                     std::array<uint32_t, 3> mid, std::array<bool, 3> marked,
                     std::array<uint32_t, 3>* tri) const {
    const uint32_t ab = mid[0], ac = mid[1], bc = mid[2];
    const int count = marked[0] + marked[1] + marked[2];
    if (count == 0) {
      tri[0] = {a, b, c};
      return 1;
    }
    if (count == 3) {
      tri[0] = {a, ab, ac}, tri[1] = {ab, b, bc}, tri[2] = {ac, bc, c}, tri[3] = {ab, bc, ac};
      return 4;
    }
    if (count == 1) {
      if (marked[0]) tri[0] = {a, ab, c}, tri[1] = {ab, b, c};
      if (marked[1]) tri[0] = {a, b, ac}, tri[1] = {ac, b, c};
      if (marked[2]) tri[0] = {a, b, bc}, tri[1] = {a, bc, c};
      return 2;
    }
    // Two: corner o between midpoints m1 (on o-x) and m2 (on o-y).
    uint32_t o, x, y, m1, m2;
    if (!marked[2])
      o = a, x = b, y = c, m1 = ab, m2 = ac;  // ab, ac
    else if (!marked[1])
      o = b, x = a, y = c, m1 = ab, m2 = bc;  // ab, bc
    else
      o = c, x = a, y = b, m1 = ac, m2 = bc;  // ac, bc
    tri[0] = {o, m2, m1};
    // Diagonal x-m2 or m1-y.
    const double dx = squared_length(plan_position(level, x) - plan_position(level, m2));
    const double dy = squared_length(plan_position(level, y) - plan_position(level, m1));
    if (dx < dy || (dx == dy && x < y)) {
      tri[1] = {x, m1, m2}, tri[2] = {x, m2, y};
    } else {
      tri[1] = {x, m1, y}, tri[2] = {m1, m2, y};
    }
    return 3;
  }

  void orient_plan(const RedLevel& level, Tet* t) const {
    const Vec3 a = plan_position(level, (*t)[0]);
    if (dot(cross(plan_position(level, (*t)[1]) - a, plan_position(level, (*t)[2]) - a),
            plan_position(level, (*t)[3]) - a) < 0)
      std::swap((*t)[2], (*t)[3]);
  }

#ifndef NDEBUG
  // The planned valence of each touched vertex, midpoint and centroid, counted again
  // from the pieces of the tets around it: what red_level() counts from the split
  // tets' new edges alone (checked in builds with assertions).
  bool plan_valences_agree(const RedLevel& level, const std::vector<uint32_t>& touched,
                           const std::vector<uint32_t>& after_old,
                           const std::vector<uint32_t>& mid_after,
                           const std::vector<uint32_t>& cen_after) const {
    const uint32_t n = static_cast<uint32_t>(pos_.size());
    std::vector<Tet> pieces;
    std::vector<uint32_t> around;
    // The neighbours of plan vertex x in the pieces of the given tets.
    auto count = [&](uint32_t x, const std::vector<uint32_t>& tets) {
      around.clear();
      for (uint32_t t : tets) {
        const uint32_t s = level.slot_of[t];
        if (s == kInvalidIndex || slot_mask(level, s) == 0)
          pieces.assign(1, tet_[t].v);
        else
          red_pieces(level, s, &pieces);
        for (const Tet& c : pieces)
          if (tet_has(c, x))
            for (uint32_t w : c)
              if (w != x) around.push_back(w);
      }
      sort_unique(around);
      return around.size();
    };
    for (uint32_t v : touched)
      if (count(v, star_[v]) != after_old[v]) return false;
    std::vector<uint32_t> tets;
    for (uint32_t e = 0; e < mid_after.size(); ++e) {
      if (!level.marked[e]) continue;
      tets.assign(level.tets.begin() + level.tets_first[e],
                  level.tets.begin() + level.tets_first[e + 1]);
      if (count(n + 2 * e, tets) != mid_after[e]) return false;
    }
    for (uint32_t s = 0; s < cen_after.size(); ++s) {
      tets.assign(1, level.slot_tet[s]);
      const size_t c = count(n + 2 * s + 1, tets);
      if (c != cen_after[s]) return false;
    }
    return true;
  }
#endif

  // The red levels' progress during round `round` of level `level` (from 0): a level
  // a share of the levels expected, each round closer to the next; past them (a
  // marking held back round long edges can go on for many levels, each splitting a
  // few tets) each level halves what is left, so that the estimate still moves and
  // reaches 1 only when the levels end.
  double red_levels_fraction(size_t level, int round) const {
    const double expected = red_levels_expected_;
    const auto start = [&](double k) {
      return k <= expected - 1 ? k / expected : 1 - std::exp2(expected - 1 - k) / expected;
    };
    const double k = static_cast<double>(level);
    return start(k) + (start(k + 1) - start(k)) * (1 - 1.0 / (round + 1));
  }

  // One red level (see above); false if it split nothing.
  bool red_level(SimplifyResult* result) {
    const size_t tets = tet_.size();
    const uint32_t n = static_cast<uint32_t>(pos_.size());
    // An edge longer than its limit (the smallest of its tets') is longer than the
    // limit of one of its tets, so it is an edge of one of these.
    std::vector<uint32_t> long_tets;
    for (uint32_t t = 0; t < tets; ++t) {
      const Tet& v = tet_[t].v;
      const double l = uniform_sizing_ ? params_.sizing.uniform : size_limit(t);
      if (tet_longest_edge2(pos_[v[0]], pos_[v[1]], pos_[v[2]], pos_[v[3]]) > l * l)
        long_tets.push_back(t);
    }
    if (long_tets.empty()) return false;
    RedLevel level;
    level.slot_of.assign(tets, kInvalidIndex);
    std::vector<uint32_t> marked_edges;
    double ratio2 = 1;  // the largest squared length over limit of a marked edge
    for (uint32_t t : long_tets)
      for (const auto& k : kTetEdge) {
        const uint32_t e = level_edge(&level, tet_[t].v[k[0]], tet_[t].v[k[1]]);
        if (level.marked[e] || level.frozen[e]) continue;
        const auto& ab = level.ends[e];
        const double length2 = squared_length(pos_[ab[0]] - pos_[ab[1]]);
        if (length2 > level.limit[e] * level.limit[e]) {
          level.marked[e] = 1;
          marked_edges.push_back(e);
          ratio2 = std::max(ratio2, length2 / (level.limit[e] * level.limit[e]));
        }
      }
    if (marked_edges.empty()) return false;
    // Progress: each level halves the edges it splits, so the first one's longest edge
    // over its limit says about how many levels there will be.
    if (result->red_levels == 0)
      red_levels_expected_ = std::max(1.0, std::ceil(0.5 * std::log2(ratio2)));
    std::vector<uint32_t> work;  // slots
    auto push_edge_tets = [&](uint32_t e) {
      for (uint32_t k = level.tets_first[e]; k < level.tets_first[e + 1]; ++k) {
        const uint32_t s = level_slot(&level, level.tets[k]);
        if (!level.queued[s]) level.queued[s] = 1, work.push_back(s);
      }
    };
    auto mark = [&](uint32_t e) {
      if (level.marked[e] || level.frozen[e]) return;
      level.marked[e] = 1;
      push_edge_tets(e);
    };
    auto freeze = [&](uint32_t e) {
      if (level.frozen[e]) return;
      level.frozen[e] = 1;
      if (level.marked[e]) level.marked[e] = 0, push_edge_tets(e);
    };
    // (Copies: making slots moves slot_edge.)
    auto edges_of = [&](uint32_t s, uint32_t* te) {
      std::copy_n(&level.slot_edge[6 * size_t{s}], 6, te);
    };
    // Tet s made red if none of its edges is frozen, else none of them split.
    auto red_or_none = [&](uint32_t s) {
      uint32_t te[6];
      edges_of(s, te);
      bool can_red = true;
      for (int k = 0; k < 6; ++k) can_red = can_red && !level.frozen[te[k]];
      for (int k = 0; k < 6; ++k) can_red ? mark(te[k]) : freeze(te[k]);
    };
    for (uint32_t e : marked_edges) push_edge_tets(e);
    // Visits the slots in tet order, as a pass over every tet would: slots made during
    // the pass are visited in it if their tet comes after the one being visited.
    std::vector<uint32_t> order;  // slots by tet
    auto by_tet = [&](uint32_t x, uint32_t y) { return level.slot_tet[x] < level.slot_tet[y]; };
    auto in_tet_order = [&](auto&& visit) {
      const size_t before = order.size();
      std::sort(level.fresh.begin(), level.fresh.end(), by_tet);
      order.insert(order.end(), level.fresh.begin(), level.fresh.end());
      std::inplace_merge(order.begin(), order.begin() + before, order.end(), by_tet);
      level.fresh.clear();
      std::priority_queue<uint64_t, std::vector<uint64_t>, std::greater<uint64_t>> later;
      for (size_t i = 0;;) {
        uint32_t s;
        if (!later.empty() &&
            (i == order.size() || (later.top() >> 32) < level.slot_tet[order[i]])) {
          s = static_cast<uint32_t>(later.top());
          later.pop();
        } else if (i < order.size()) {
          s = order[i++];
        } else {
          break;
        }
        const size_t made = level.fresh.size();
        visit(s);
        for (size_t k = made; k < level.fresh.size(); ++k) {
          const uint32_t f = level.fresh[k];
          if (level.slot_tet[f] > level.slot_tet[s])
            later.push(uint64_t{level.slot_tet[f]} << 32 | f);
        }
      }
    };
    // Valences: of each vertex, memoised (0: not yet counted); planned, of the
    // vertices the split tets touch, of the midpoints and of the centroids.
    std::vector<uint32_t> valence_before(n, 0), after_old(n, 0);
    std::vector<uint8_t> is_touched(n, 0);
    std::vector<uint32_t> touched, mid_after, cen_after;
    auto before_of = [&](uint32_t v) {
      if (valence_before[v] == 0) valence_before[v] = valence(v);
      return valence_before[v];
    };
    auto touch = [&](uint32_t v) {
      if (!is_touched[v]) is_touched[v] = 1, touched.push_back(v), after_old[v] = before_of(v);
    };
    std::vector<uint64_t> plan_edges;
    std::vector<Tet> pieces;
    constexpr int kMostRounds = 64;  // (the bundled motor at size 8: 6 and 9)
    for (int round = 0;; ++round) {
      if (round == kMostRounds || cancelled()) return false;
      // Within a level, each round of the planning closes more of the gap to the next.
      report("red levels", red_levels_fraction(result->red_levels, round));
      // Close the marking: a face with two marked edges gets its third.
      while (!work.empty()) {
        const uint32_t s = work.back();
        work.pop_back();
        level.queued[s] = 0;
        uint32_t te[6];
        edges_of(s, te);
        for (const auto& f : kFaceEdges) {
          const uint32_t e0 = te[f[0]], e1 = te[f[1]], e2 = te[f[2]];
          if (level.marked[e0] + level.marked[e1] + level.marked[e2] == 2)
            mark(!level.marked[e0] ? e0 : !level.marked[e1] ? e1 : e2);
        }
      }
      // Shapes. A tet split but not red whose pieces fail is made red if it can be (a
      // red split's corner pieces are its parent's shape, and its inner ones the best
      // of three); a red one that fails is not split.
      bool changed = false;
      in_tet_order([&](uint32_t s) {
        const int mask = slot_mask(level, s);
        if (mask == 0 || mask == level.passed[s]) return;
        red_pieces(level, s, &pieces);
        const TetRecord& r = tet_[level.slot_tet[s]];
        const double floor = std::min(params_.min_stretch, r.stretch);
        bool ok = true;
        for (const Tet& c : pieces) {
          const Vec3 p0 = plan_position(level, c[0]), p1 = plan_position(level, c[1]),
                     p2 = plan_position(level, c[2]), p3 = plan_position(level, c[3]);
          const TetShape shape = tet_shape(p0, p1, p2, p3);
          // (The margin takes the rounding of a corner piece's stretch, its parent's.)
          // (Pieces of a tet below kMinStretch: also clear of being read as flat.)
          if (shape.stretch < floor * (1 - 1e-9) || (floor < kMinStretch && !reads_back(shape)) ||
              (!(r.allowance & kMayBeBig) && shape.size > size_limit(p0, p1, p2, p3, r.material)))
            ok = false;
        }
        if (ok) {
          level.passed[s] = static_cast<int8_t>(mask);
        } else {
          if (mask == 63) {
            uint32_t te[6];
            edges_of(s, te);
            for (int k = 0; k < 6; ++k) freeze(te[k]);
          } else {
            red_or_none(s);
          }
          changed = true;
        }
      });
      if (changed) continue;
      const uint32_t slots = static_cast<uint32_t>(level.slot_tet.size());
      // The planned pieces, once per round: their count (more than the run may make
      // stops it before planning them all), and their edges to midpoints and centroids.
      size_t piece_count = tets;  // a piece per tet, and the more of the split ones
      plan_edges.clear();
      for (uint32_t s = 0; s < slots && piece_count <= max_tets_; ++s) {
        if (slot_mask(level, s) == 0) continue;
        red_pieces(level, s, &pieces);
        piece_count += pieces.size() - 1;
        for (const Tet& c : pieces)
          for (const auto& k : kTetEdge) {
            uint64_t a = c[k[0]], b = c[k[1]];
            if (a > b) std::swap(a, b);
            if (b >= n) plan_edges.push_back(a << 32 | b);  // a midpoint or centroid
          }
      }
      if (piece_count > max_tets_) {  // subdivide() stops with an error
        red_over_max_ = true;
        return false;
      }
      // Valences, from the planned pieces' edges. A node past its cap may not gain
      // neighbours: it gains one in a tet split but not red (a red tet's corner only
      // trades its neighbours for the midpoints of its edges), so those tets are made
      // red, or not split. A midpoint or centroid past its cap is not made.
      // A node keeps its edges but the marked ones (the pieces of a tet join two of its
      // corners only by an edge of it, not marked) and gains those to the midpoints and
      // centroids of the pieces around it: only the tets that are split are read.
      for (uint32_t v : touched) is_touched[v] = 0;
      touched.clear();
      mid_after.assign(level.ends.size(), 0);
      cen_after.assign(slots, 0);
      for (uint32_t e = 0; e < level.ends.size(); ++e)
        if (level.marked[e]) {
          touch(level.ends[e][0]), touch(level.ends[e][1]);
          --after_old[level.ends[e][0]], --after_old[level.ends[e][1]];
        }
      sort_unique(plan_edges);
      auto gain = [&](uint32_t x) {
        if (x < n) {
          touch(x);
          ++after_old[x];
        } else {
          ++((x - n) & 1 ? cen_after : mid_after)[(x - n) >> 1];
        }
      };
      for (uint64_t ab : plan_edges) gain(static_cast<uint32_t>(ab >> 32)), gain(ab & 0xffffffffu);
      assert(plan_valences_agree(level, touched, after_old, mid_after, cen_after));
      std::sort(touched.begin(), touched.end());
      for (uint32_t v : touched) {
        if (after_old[v] <= valence_before[v] || after_old[v] <= valence_cap(pos_[v])) continue;
        for (uint32_t t : star_[v]) {
          const uint32_t s = level.slot_of[t];
          if (s == kInvalidIndex) continue;
          const int mask = slot_mask(level, s);
          if (mask != 0 && mask != 63) red_or_none(s), changed = true;
        }
      }
      for (uint32_t e = 0; e < mid_after.size(); ++e)
        if (level.marked[e] && mid_after[e] > valence_cap(plan_position(level, n + 2 * e)))
          freeze(e), changed = true;
      for (uint32_t s = 0; s < slots; ++s)
        if (cen_after[s] > valence_cap(plan_position(level, n + 2 * s + 1))) {
          uint32_t te[6];
          edges_of(s, te);
          for (int k = 0; k < 6; ++k) freeze(te[k]);
          changed = true;
        }
      if (!changed) break;
    }
    // The marked edges, in the order of their sorted end pairs.
    std::vector<uint32_t> split_edges;
    for (uint32_t e = 0; e < level.ends.size(); ++e)
      if (level.marked[e]) split_edges.push_back(e);
    std::sort(split_edges.begin(), split_edges.end(),
              [&](uint32_t x, uint32_t y) { return level.ends[x] < level.ends[y]; });
    // A level that splits no edge longer than its limit (only edges the marking's
    // closure added, around frozen ones) would only refine; the levels end.
    size_t long_splits = 0;
    for (uint32_t e : split_edges)
      long_splits += squared_length(pos_[level.ends[e][0]] - pos_[level.ends[e][1]]) >
                     level.limit[e] * level.limit[e];
    if (long_splits == 0) return false;
    // From the fourth level on, one that splits under 1/64 of the long edges it marked
    // is the last: the levels after it would each re-plan every tet still long round
    // edges the rules freeze, to split a few more (docs/PERFORMANCE.md: on the bundled
    // motor at size 2, 640k long tets of 7.2M a level, 3 to 6 s each, to split 5,000
    // down to 50 edges). The bisection that follows splits what is left where it can.
    if (result->red_levels >= 3 && 64 * long_splits < marked_edges.size()) red_levels_end_ = true;
    // Apply: the pieces in plan ids first (plan_position() reads pos_ as it is).
    std::vector<TetRecord> next;
    std::vector<uint8_t> is_piece;
    next.reserve(tets + 8 * split_edges.size());
    is_piece.reserve(next.capacity());
    for (uint32_t t = 0; t < tets; ++t) {
      const uint32_t s = level.slot_of[t];
      if (s == kInvalidIndex || slot_mask(level, s) == 0) {
        next.push_back(tet_[t]);
        is_piece.push_back(0);
        continue;
      }
      red_pieces(level, s, &pieces);
      for (const Tet& c : pieces) {
        next.push_back(tet_[t]);  // material and allowance: a piece may break what t broke
        next.back().v = c;
        is_piece.push_back(1);
      }
    }
    if (next.size() > max_tets_) {  // subdivide() stops with an error
      red_over_max_ = true;
      return false;
    }
    // New ids: midpoints in the order of their edges, then centroids in tet order.
    std::vector<uint32_t> mid_id(level.ends.size(), 0), cen_id(level.slot_tet.size(), 0);
    std::vector<Vec3> added;
    for (uint32_t e : split_edges) {
      mid_id[e] = static_cast<uint32_t>(n + added.size());
      added.push_back(plan_position(level, n + 2 * e));
    }
    if (added.empty()) return false;
    const size_t splits = added.size();
    for (size_t k = 0; k < next.size(); ++k) {
      if (!is_piece[k]) continue;
      for (uint32_t v : next[k].v)
        if (v >= n && ((v - n) & 1) && cen_id[(v - n) >> 1] == 0) {
          cen_id[(v - n) >> 1] = static_cast<uint32_t>(n + added.size());
          added.push_back(plan_position(level, v));
        }
    }
    pos_.insert(pos_.end(), added.begin(), added.end());
    mark_.resize(pos_.size(), 0);
    input_valence_.resize(pos_.size(), 0);
    for (size_t k = 0; k < next.size(); ++k) {
      if (!is_piece[k]) continue;
      TetRecord& r = next[k];
      for (uint32_t& v : r.v)
        if (v >= n) v = ((v - n) & 1 ? cen_id : mid_id)[(v - n) >> 1];
      r.stretch = tet_shape(pos_[r.v[0]], pos_[r.v[1]], pos_[r.v[2]], pos_[r.v[3]]).stretch;
    }
    tet_.swap(next);
    for (auto& star : star_) star.clear();  // (keeping their memory: most grow again)
    star_.resize(pos_.size());
    for (uint32_t t = 0; t < tet_.size(); ++t)
      for (uint32_t v : tet_[t].v) star_[v].push_back(t);
    result->splits += splits;
    result->red_splits += splits;
    result->red_centroids += added.size() - splits;
    ++result->red_levels;
    const uint32_t cap = params_.max_valence;
    for (uint32_t v : touched)
      if (after_old[v] > cap && after_old[v] > valence_before[v]) ++result->splits_past_valence;
    for (uint32_t x : mid_after) result->splits_past_valence += x > cap;
    for (uint32_t x : cen_after) result->splits_past_valence += x > cap;
    return true;
  }

  Status too_many_tets() {
    if (max_tets_ < kMaxTets) {
      over_factor_ = true;
      const uint32_t f = params_.past_valence_tets_factor;
      return Status::error("its subdivision passed " + std::to_string(max_tets_) + " tets, " +
                           (f == 1 ? std::string("as many as") : std::to_string(f) + " times") +
                           " the first run's");
    }
    return Status::bad_value("size " + number(params_.sizing.smallest_size()) +
                             ": subdivision exceeded " + std::to_string(kMaxTets) +
                             " tets; choose a larger size or --no-subdivide");
  }

  Status subdivide(SimplifyResult* result) {
    // Refuse sizes that would explode the mesh before doing any work. The estimate
    // assumes every split is made; the valence and stretch rules refuse many (box2
    // at size 0.0225: 37 M estimated, 1.95 M made), so it only refuses when far
    // beyond the limit, which the loop below enforces exactly.
    constexpr double kEstimateMargin = 4;
    const double predicted = predicted_splits_;
    if (predicted + tet_.size() > kEstimateMargin * static_cast<double>(kMaxTets)) {
      const std::string count = predicted < 1e15
                                    ? "about " + std::to_string(static_cast<long long>(predicted))
                                    : "more than 10^15";
      return Status::bad_value("size " + number(params_.sizing.smallest_size()) +
                               " would subdivide the mesh into " + count + " tets (limit " +
                               std::to_string(kMaxTets) +
                               "); choose a larger size or --no-subdivide");
    }
    std::vector<uint32_t> valence_now = input_valence_;
    if (past_valence_) {
      // Edges whose red split would give their midpoint more neighbours than tau_VL
      // are bisected first (see hot_edge()).
      if (Status s = bisect(result, &valence_now, Bisect::kHotEdges); !s) return s;
      red_levels_end_ = false;
      for (int level = 0; level < kMostRedLevels && !red_levels_end_ && red_level(result);
           ++level) {
      }
      report("red levels", 1);
    }
    if (red_over_max_) return too_many_tets();
    if (result->red_levels > 0) {
      valence_now.resize(pos_.size());
      for (uint32_t v = 0; v < pos_.size(); ++v) valence_now[v] = valence(v);
    }
    return bisect(result, &valence_now, Bisect::kHalfSize);
  }

  // Longest-edge bisection of the edges push_if_long() queues (see subdivide()), with
  // valence_now the valence of every node.
  Status bisect(SimplifyResult* result, std::vector<uint32_t>* valences, Bisect mode) {
    std::vector<uint32_t>& valence_now = *valences;
    // The bisection of the hot edges reports no progress and counts no skipped split
    // (the half-size bisection that follows counts what it skips); its splits are also
    // counted in hot_splits.
    const bool hot = mode == Bisect::kHotEdges;
    std::vector<Split> heap;
    std::vector<uint32_t> nb;
    for (uint32_t v = 0; v < pos_.size(); ++v) {
      neighbors(v, &nb);
      for (uint32_t w : nb)
        if (w > v) push_if_long(heap, v, w, mode);
    }
    double fraction = 0;  // of the splits made, out of those and the edges still queued
    std::vector<uint32_t> ring, opposite;
    std::vector<double> piece_stretch;  // of the two pieces of each ring tet
    size_t iterations = 0;
    while (!heap.empty()) {
      if ((++iterations & 4095) == 0) {
        if (cancelled()) break;
        // (Splits queue new long edges, so this can fall: it is shown as it rose.)
        fraction =
            std::max(fraction, double(result->splits) / double(result->splits + heap.size()));
        if (!hot) report("subdivide", fraction);
      }
      std::pop_heap(heap.begin(), heap.end(), SplitLess());
      const Split e = heap.back();
      heap.pop_back();
      if (!kept_edges_.empty() &&
          std::binary_search(kept_edges_.begin(), kept_edges_.end(), std::make_pair(e.a, e.b))) {
        result->splits_skipped_inside += !hot;  // (counted by the last bisection)
        continue;
      }
      ring.clear();
      const bool from_b = ring_from_other_end(star_[e.a].size(), star_[e.b].size());
      for (uint32_t t : star_[from_b ? e.b : e.a])
        if (tet_has(tet_[t].v, from_b ? e.a : e.b)) ring.push_back(t);
      if (ring.empty()) continue;  // already split

      const Vec3 m = (pos_[e.a] + pos_[e.b]) * 0.5;
      bool ok = true;
      opposite.clear();
      piece_stretch.clear();
      for (uint32_t t : ring) {
        const double floor = std::min(params_.min_stretch, tet_[t].stretch);
        for (uint32_t replaced : {e.a, e.b}) {
          Vec3 p[4];
          for (int c = 0; c < 4; ++c) p[c] = tet_[t].v[c] == replaced ? m : pos_[tet_[t].v[c]];
          const TetShape child = tet_shape(p[0], p[1], p[2], p[3]);
          piece_stretch.push_back(child.stretch);
          if (child.stretch < floor || (floor < kMinStretch && !reads_back(child))) ok = false;
          // A piece may only be above its own size limit if its parent already was
          // above its own (with a size field the limits of parent and piece differ).
          if (!(tet_[t].allowance & kMayBeBig) &&
              child.size > size_limit(p[0], p[1], p[2], p[3], tet_[t].material))
            ok = false;
        }
        for (uint32_t w : tet_[t].v)
          if (w != e.a && w != e.b) opposite.push_back(w);
      }
      if (!ok) {
        result->splits_skipped += !hot;
        continue;
      }
      sort_unique(opposite);
      bool past = opposite.size() + 2 > params_.max_valence;
      if (opposite.size() + 2 > valence_cap(m)) ok = false;
      for (uint32_t w : opposite) {
        past |= valence_now[w] + 1 > params_.max_valence;
        if (valence_now[w] + 1 > valence_cap(pos_[w])) ok = false;
      }
      if (!ok) {
        result->splits_skipped += !hot;
        result->splits_skipped_valence += !hot;
        continue;
      }
      if (tet_.size() + ring.size() > max_tets_) return too_many_tets();

      const uint32_t mid = static_cast<uint32_t>(pos_.size());
      pos_.push_back(m);
      star_.emplace_back();
      mark_.push_back(0);
      input_valence_.push_back(0);
      valence_now.push_back(static_cast<uint32_t>(opposite.size() + 2));
      for (uint32_t w : opposite) ++valence_now[w];
      for (size_t n = 0; n < ring.size(); ++n) {
        const uint32_t t = ring[n];
        const uint32_t child = static_cast<uint32_t>(tet_.size());
        // The upper piece copies t's material and allowance: a piece of t may break
        // what t broke.
        TetRecord upper = tet_[t];
        for (uint32_t& v : upper.v)
          if (v == e.a) v = mid;
        upper.stretch = piece_stretch[2 * n];
        for (uint32_t& v : tet_[t].v)
          if (v == e.b) v = mid;
        tet_[t].stretch = piece_stretch[2 * n + 1];
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
      result->hot_splits += hot;
      result->splits_past_valence += past;
      push_if_long(heap, e.a, mid, mode);
      push_if_long(heap, mid, e.b, mode);
      for (uint32_t w : opposite) push_if_long(heap, mid, w, mode);
    }
    // The stars are no longer sorted: run() renumbers (reorder_for_locality()) after
    // any split, which rebuilds them.
    if (!hot) report("subdivide", 1);
    return Status();
  }

  // After a subdivision that took nodes past tau_VL: edge removals round each node past
  // both tau_VL and its input valence (shed_valence(), improve.h), whose tets meet every
  // threshold. The tets are then those it returns, each allowed to break what it
  // breaks: only pieces of input tets can (subdivision makes no piece flatter than
  // both tau_ST and its parent, nor above its own size unless its parent was, and a
  // removal makes none).
  void shed_valence_by_flips(SimplifyResult* result) {
    std::vector<uint32_t> over;
    for (uint32_t v = 0; v < pos_.size(); ++v) {
      const uint32_t n = valence(v);
      if (n > params_.max_valence && n > input_valence_[v]) over.push_back(v);
    }
    result->nodes_past_valence = over.size();
    if (over.empty()) return;
    report("edge removals", 0);
    TetMesh mesh = mesh_now();
    result->valence_edge_removals = shed_valence(&mesh, params_, over, cancel_, patches_);
    report("edge removals", 1);
    tet_.assign(mesh.tets.size(), TetRecord{});
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      tet_[t].v = mesh.tets[t];
      tet_[t].material = mesh.materials[t];
      const TetShape s = shape(t);
      tet_[t].stretch = s.stretch;
      tet_[t].allowance = static_cast<uint8_t>((s.stretch < params_.min_stretch ? kMayBeThin : 0) |
                                               (s.size > size_limit(t) ? kMayBeBig : 0));
    }
    // The stars are rebuilt by reorder_for_locality(), which follows.
  }

  // --------------------------------------------------------- classification
  // `mesh` holds the current arrays: result->base, taken after subdivision.
  void classify(const TetMesh& mesh) {
    std::vector<uint32_t> neighbors_of_tets;
    const FaceProblem problem = build_face_neighbors(mesh, &neighbors_of_tets);
    assert(problem.kind == FaceProblem::Kind::kNone);  // the input was validated
    (void)problem;
    const std::vector<SurfaceTriangle> surface = extract_surface(mesh, neighbors_of_tets);
    ClassifyOptions options;
    options.crease_angle_degrees = params_.crease_angle_degrees;
    // The input's surface groups: each triangle's (1 + group, 0 for none).
    std::vector<uint32_t> patch;
    if (patches_ && patches_->any()) {
      patch.resize(surface.size());
      const auto& p = mesh.positions;
      for (size_t i = 0; i < surface.size(); ++i) {
        const SurfaceTriangle& t = surface[i];
        patch[i] = patches_->locate(p[t.v[0]], p[t.v[1]], p[t.v[2]], t.inner, t.outer) + 1;
      }
    }
    Classification c = classify_vertices(mesh, surface, options, patch.empty() ? nullptr : &patch);
    state_.assign(pos_.size(), VertexState{});
    redone_.assign(pos_.size(), Redone{});
    for (uint32_t v = 0; v < pos_.size(); ++v) state_[v].kind = c.kind[v];
    // The input groups' faces inside a material stay as they are: their corners are
    // corners (subdivision split none of their edges, so they are faces of `mesh`).
    if (patches_ && !patches_->inside_entries().empty())
      for (const auto& f : inside_faces(mesh, *patches_))
        for (uint32_t v : f) state_[v].kind = FeatureKind::kCorner;
    feature_neighbors_.assign(pos_.size(), {});
    for (const auto& e : c.feature_edges) {
      feature_neighbors_[e[0]].push_back(e[1]);
      feature_neighbors_[e[1]].push_back(e[0]);
    }
    ring_mark_.assign(pos_.size(), 0);
    ring_slot_.assign(pos_.size(), 0);
    quadric_.assign(pos_.size(), Quadric());
    for (const SurfaceTriangle& s : surface) {
      if (s.outer == kOutsideMaterial)
        for (uint32_t v : s.v) state_[v].outer = 1;
      const Vec3& p = pos_[s.v[0]];
      Vec3 n = cross(pos_[s.v[1]] - p, pos_[s.v[2]] - p);
      const double len = length(n);
      if (!(len > 0)) continue;
      n = n * (1.0 / len);
      const Quadric q = Quadric::plane(n, -dot(n, p));
      for (uint32_t v : s.v) quadric_[v].add(q);
    }
    if (!patch.empty()) add_border_quadrics(surface, patch);
    material_ids_ = mesh.materials;
    sort_unique(material_ids_);
    material_tets_.assign(material_ids_.size(), 0);
    for (int32_t m : mesh.materials) ++material_tets_[material_index(m)];
    across_ = std::move(neighbors_of_tets);
    if (params_.keep_boundary_embedded) piece_ = vertex_pieces(mesh);
  }

  // The border between two surface groups of one material pair may lie on a smooth
  // surface, where the triangles' planes do not hold it in place: each border edge
  // adds the plane through it across the surface (normal: the edge x the mean of the
  // two triangles' normals), so that the border, too, moves at most the tolerance
  // (as Garland and Heckbert hold open boundaries).
  void add_border_quadrics(const std::vector<SurfaceTriangle>& surface,
                           const std::vector<uint32_t>& patch) {
    const std::vector<SurfaceEdgeUse> uses = surface_edge_uses(surface);
    auto unit_normal = [&](const SurfaceTriangle& t) {
      const Vec3& p = pos_[t.v[0]];
      const Vec3 n = cross(pos_[t.v[1]] - p, pos_[t.v[2]] - p);
      const double len = length(n);
      return len > 0 ? n * (1.0 / len) : Vec3{};
    };
    for (size_t i = 0; i < uses.size();) {
      size_t j = i + 1;
      while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
      if (j - i == 2) {
        const SurfaceTriangle& s = surface[uses[i].triangle];
        const SurfaceTriangle& t = surface[uses[i + 1].triangle];
        if (s.inner == t.inner && s.outer == t.outer &&
            patch[uses[i].triangle] != patch[uses[i + 1].triangle]) {
          const Vec3& pa = pos_[uses[i].a];
          const Vec3 across = cross(pos_[uses[i].b] - pa, unit_normal(s) + unit_normal(t));
          const double len = length(across);
          if (len > 0) {
            const Vec3 n = across * (1.0 / len);
            const Quadric q = Quadric::plane(n, -dot(n, pa));
            quadric_[uses[i].a].add(q);
            quadric_[uses[i].b].add(q);
          }
        }
      }
      i = j;
    }
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
        common |= static_cast<bool>(int{w != i} & int{w != j} & int{mark_[w] == near_i} &
                                    int{ring_mark_[w] != in_ring});
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
    // The whole complex first. In every run measured (the bundled models at several
    // sizes, stretches down to 0.001, crease angles 40 and 179) this check never
    // rejected an edge that a later check here, or the geometry, would have passed:
    // around interior ends, all-positive new tets already rule out a pinched star, and
    // edges on the boundary are the surface complex's. It stays as the paper's rule
    // and a guard; no test can isolate it for the same reason.
    if (!link_condition(
            i, j, [](uint32_t) { return true; }, state_[i].outer, state_[j].outer))
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
        if (!link_condition(i, j, in_m, state_[i].outer || touches_other(0, m),
                            state_[j].outer || touches_other(1, m)))
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

  // Whether edge (i, j), with the ring of tets around it listed in ring_tets_, lies on
  // a boundary or interface triangle. The tets around an edge inside one material form
  // a closed ring, in which every face (i, j, x) is shared by two of them; the edge lies
  // on a surface if the ring is open (a face on the boundary) or holds two materials (a
  // face between them).
  bool ring_is_surface(uint32_t i, uint32_t j) {
    ring_others_.clear();
    for (uint32_t t : ring_tets_) {
      const TetRecord& r = tet_[t];
      if (r.material != tet_[ring_tets_[0]].material) return true;
      for (uint32_t x : r.v)
        if (x != i && x != j) ring_others_.push_back(x);
    }
    std::sort(ring_others_.begin(), ring_others_.end());
    for (size_t k = 0; k < ring_others_.size(); k += 2)
      if (k + 1 == ring_others_.size() || ring_others_[k] != ring_others_[k + 1]) return true;
    return false;
  }

  // |f*(a,b)|: the distinct vertices x of the triangles (a, b, x) around edge (a, b),
  // from the ring of tets around it; they are left marked with the current stamp.
  uint32_t triangle_count(const std::vector<uint32_t>& ring, uint32_t a, uint32_t b) {
    const uint32_t s = next_stamp();
    uint32_t n = 0;
    for (uint32_t t : ring)
      for (uint32_t w : tet_[t].v)
        if (w != a && w != b && mark_[w] != s) mark_[w] = s, ++n;
    return n;
  }

  // The tets of t*(a) U t*(b) that survive the collapse, in blocks of kLanes: first
  // the whole star of a in star order, the lanes of the ring around the edge skipped,
  // then the tets of b off the ring. The blocks of a stay valid, with their faces
  // opposite a, until the mesh changes (refresh_around()), so the edges of one vertex
  // evaluated in a row (after a collapse, in a sweep, at the start) share them.
  // gather_first_end() lists the ring in ring_tets_; the stretches of t*(a) U t*(b)
  // go to their mean.
  void gather_first_end(uint32_t a, uint32_t b) {
    const auto& star = star_[a];
    const bool fresh = first_end_ != a;
    if (fresh) {
      first_end_ = a;
      first_blocks_ = (star.size() + kLanes - 1) / kLanes;
      reserve_blocks(first_blocks_);
      std::fill(block_built_.begin(), block_built_.begin() + first_blocks_, 0);
      first_sum_ = 0;
    }
    // Branch-free: every star tet is written to the ring list, which keeps it only if
    // it holds b (whether it does is not predictable).
    ring_tets_.resize(star.size());
    size_t ring_size = 0;
    for (size_t n = 0; n < star.size(); ++n) {
      const TetRecord& r = tet_[star[n]];
      if (fresh) first_sum_ += r.stretch;
      const bool ring = tet_has(r.v, b);
      ring_tets_[ring_size] = star[n];
      ring_size += ring;
      moving_[n / kLanes].skip[n % kLanes] = static_cast<double>(ring);
    }
    for (size_t n = star.size(); n < first_blocks_ * kLanes; ++n)
      moving_[n / kLanes].skip[n % kLanes] = 1;
    ring_tets_.resize(ring_size);
  }

  // ... then b's, once the ring passed the topology and valence rules. Returns the
  // mean stretch of t*(a) U t*(b).
  double gather_second_end(uint32_t a, uint32_t b) {
    double sum = first_sum_;
    size_t count = star_[a].size();
    second_end_ = b;
    // Branch-free, as the ring above: the tets holding a add +0 and are overwritten.
    const auto& star = star_[b];
    second_tets_.resize(star.size());
    size_t kept = 0;
    for (uint32_t t : star) {
      const TetRecord& r = tet_[t];
      const bool ring = tet_has(r.v, a);
      sum += r.stretch * static_cast<double>(!ring);  // exact: x 1 or x 0
      second_tets_[kept] = t;
      kept += !ring;
    }
    second_tets_.resize(kept);
    count += kept;
    moving_count_ = star_[a].size() - ring_tets_.size() + second_tets_.size();
    moving_blocks_ = first_blocks_ + (second_tets_.size() + kLanes - 1) / kLanes;
    reserve_blocks(moving_blocks_);
    for (size_t k = first_blocks_; k < moving_blocks_; ++k) block_built_[k] = 0;
    return sum / static_cast<double>(count);
  }

  void reserve_blocks(size_t n) {
    if (moving_.size() < n) {
      moving_.resize(n);
      block_built_.resize(n, 0);
    }
  }

  // The centroid of lane l's tet of block b with its moving corner at k.
  static Vec3 lane_centroid(const TetBlock& b, int l, const Vec3& k) {
    return tet_centroid({b.f0x[l], b.f0y[l], b.f0z[l]}, {b.f1x[l], b.f1y[l], b.f1z[l]},
                        {b.f2x[l], b.f2y[l], b.f2z[l]}, k);
  }

  // Fills block k of the moving tets (see gather_first_end()).
  void build_block(size_t k) {
    TetBlock& b = moving_[k];
    const bool first = k < first_blocks_;
    const auto& tets = first ? star_[first_end_] : second_tets_;
    const size_t begin = (first ? k : k - first_blocks_) * kLanes;
    const uint32_t v = first ? first_end_ : second_end_;
    const double side = first ? 0 : 1;
    // Every lane is filled the same way, without branches: lanes past the last tet
    // (skipped) hold a harmless copy of the first.
    for (int l = 0; l < kLanes; ++l) {
      const bool real = begin + l < tets.size();
      const TetRecord& r = tet_[tets[real ? begin + l : begin]];
      const int slot = (r.v[1] == v) | (r.v[2] == v) << 1 | (-static_cast<int>(r.v[3] == v) & 3);
      const int* f = kTetFace[slot];  // outward: its normal points away from slot
      const Vec3 &p0 = pos_[r.v[f[0]]], &p1 = pos_[r.v[f[1]]], &p2 = pos_[r.v[f[2]]];
      b.f0x[l] = p0.x, b.f0y[l] = p0.y, b.f0z[l] = p0.z;
      b.f1x[l] = p1.x, b.f1y[l] = p1.y, b.f1z[l] = p1.z;
      b.f2x[l] = p2.x, b.f2y[l] = p2.y, b.f2z[l] = p2.z;
      b.side[l] = side;
      b.steady[l] = static_cast<double>(r.allowance == 0);
      b.material[l] = r.material;
      b.stretch_now[l] = r.stretch;
      // Without region rules, the limit does not depend on k; with them, it is
      // completed per candidate (check_position()).
      b.material_limit[l] =
          uniform_sizing_ ? params_.sizing.uniform : params_.sizing.material_size(r.material);
      b.limit[l] = b.material_limit[l];
      if (!first) b.skip[l] = static_cast<double>(!real);
    }
    kernels_.fixed_faces(b);
    block_built_[k] = 1;
  }

  // Geometry of candidate position k for collapse (a, b), with q the sum of their
  // quadrics: tolerance, stretch and size of every tet around k (gather_*() must
  // have listed them). On success sets *priority (eq. 3). Cheapest first: a pass
  // without square roots rejects inverted, oversized and clearly flat tets (a bound
  // on the stretch), a block of tets at a time, then a pass computes the exact
  // stretch of eq. (2) only when every tet passed the first. If k is the position of
  // end `unmoved` (0: a, 1: b, else none), the tets of that end keep their shape:
  // one that meets every threshold needs only its size, for eq. (3).
  Reject check_position(const Quadric& q, const Vec3& k, int unmoved, double old_stretch_mean,
                        double* priority) {
    if (q.error(k) > tolerance2_ + q.rounding(k)) return Reject::kTolerance;
    if (moving_count_ == 0) return Reject::kTopology;
    // The bound: with a_1..a_4 the face areas, (sum a)^2 >= sum a^2, so
    // d_t^2 = 6 (6V)^2 / (s^2 A^2) <= 6 (6V)^2 / (s^2 sum a^2); a tet whose bound is
    // below tau_ST^2 (with a margin far above the rounding) fails the exact test too.
    const double floor2 = params_.min_stretch * params_.min_stretch * (1 - 1e-9);
    // size_limit() of each lane's tet with k in place, a block at a time: the same
    // centroid (tet_centroid(), the same in any order of the corners).
    auto region_limits = [&](TetBlock& b) {
      double cx[kLanes], cy[kLanes], cz[kLanes];  // the centroids with k in place
      for (int l = 0; l < kLanes; ++l) {
        const Vec3 c = lane_centroid(b, l, k);
        cx[l] = c.x, cy[l] = c.y, cz[l] = c.z;
        b.limit[l] = b.material_limit[l];
      }
      params_.sizing.apply_regions(kLanes, cx, cy, cz, b.limit);
    };
    for (size_t k_block = 0; k_block < moving_blocks_; ++k_block) {
      if (!block_built_[k_block]) build_block(k_block);
      TetBlock& b = moving_[k_block];
      if (late_limits_) {
        for (double& limit : b.limit) limit = std::numeric_limits<double>::infinity();
      } else if (region_sizing_) {  // else set by build_block()
        region_limits(b);
      }
      kernels_.first_pass(b, k.x, k.y, k.z, unmoved, floor2);
      for (int l = 0; l < kLanes; ++l)
        if (b.code[l] != 0) return b.code[l] == 2 ? Reject::kSize : Reject::kStretch;
    }
    // With a size map, whose lookups cost more than the pass, the sizes are checked only
    // for a candidate that passed without them (the same candidates pass; one both
    // too flat and too big counts as too flat), and only for the lanes that are tets of
    // t*(k) (not the ring's, which go, nor padding: nothing reads their limits).
    for (size_t k_block = 0; late_limits_ && k_block < moving_blocks_; ++k_block) {
      TetBlock& b = moving_[k_block];
      double cx[kLanes], cy[kLanes], cz[kLanes], limit[kLanes];
      int lane[kLanes], n = 0;
      for (int l = 0; l < kLanes; ++l) {
        b.limit[l] = b.material_limit[l];
        if (b.skip[l] != 0) continue;
        const Vec3 c = lane_centroid(b, l, k);
        cx[n] = c.x, cy[n] = c.y, cz[n] = c.z;
        limit[n] = b.material_limit[l];
        lane[n++] = l;
      }
      params_.sizing.apply_regions(size_t(n), cx, cy, cz, limit);
      for (int i = 0; i < n; ++i) b.limit[lane[i]] = limit[i];
      kernels_.first_pass(b, k.x, k.y, k.z, unmoved, floor2);
      for (int l = 0; l < kLanes; ++l)
        if (b.code[l] != 0) return b.code[l] == 2 ? Reject::kSize : Reject::kStretch;
    }
    double stretch_sum = 0, size_sum = 0, limit_sum = 0;
    for (size_t k_block = 0; k_block < moving_blocks_; ++k_block) {
      TetBlock& b = moving_[k_block];
      kernels_.exact_pass(b);
      for (int l = 0; l < kLanes; ++l) {
        if (b.skip[l]) continue;
        if (b.side[l] == unmoved && b.steady[l] != 0) {
          stretch_sum += b.stretch_now[l];
        } else {
          if (!(b.stretch[l] >= params_.min_stretch)) return Reject::kStretch;
          stretch_sum += b.stretch[l];
        }
        size_sum += b.size[l];
        limit_sum += b.limit[l];
      }
    }
    // Delta s = tau_SZ / mean size of t*(k); Delta d = mean stretch of t*(k) over the mean
    // stretch of t*(i) U t*(j). With a size field, tau_SZ is averaged over t*(k).
    const double delta_s = limit_sum / size_sum;
    const double delta_d = (stretch_sum / static_cast<double>(moving_count_)) / old_stretch_mean;
    *priority = delta_s * delta_d;
    return Reject::kNone;
  }

  // Full evaluation of collapsing edge (a, b). Returns kNone and fills `out` if valid.
  Reject evaluate(uint32_t a, uint32_t b, Collapse* out) {
    const FeatureKind ka = state_[a].kind, kb = state_[b].kind;
    const bool a_on = ka != FeatureKind::kInterior, b_on = kb != FeatureKind::kInterior;
    bool surface_edge = false;
    if (a_on && b_on && ka == FeatureKind::kCorner && kb == FeatureKind::kCorner)
      return Reject::kTopology;
    // The new node keeps every neighbour of either end but the other end and the
    // common ones, which are at most all but one of the other end's: its valence is at
    // least the larger end's less one. With an interior end nothing is checked before
    // the valence, so this rejects what the walk below would, as it would count it,
    // without walking a star of thousands of tets (a node every tet of a fan has).
    if ((!a_on || !b_on) &&
        std::max(state_[a].valence, state_[b].valence) > params_.max_valence + 1)
      return Reject::kValence;
    gather_first_end(a, b);
    if (a_on && b_on) {
      // The paper's rule: an interior edge joining two surface nodes is never collapsed.
      surface_edge = ring_is_surface(a, b);
      if (!surface_edge) return Reject::kTopology;
      // Two curve/corner nodes may only merge along their curve.
      if (ka <= FeatureKind::kCurve && kb <= FeatureKind::kCurve && !is_feature_edge(a, b))
        return Reject::kTopology;
    }

    // The paper's valence of the new node, |v*(i)| + |v*(j)| - (|f*(i,j)| + 2), with
    // f*(i,j) the triangles (i, j, x) around the edge. It is the exact valence when
    // the link condition holds and an overestimate otherwise, so never too low.
    // With an interior end, every face (a, b, x) is shared by two ring tets: the x's
    // form closed cycles, as many as the ring's tets.
    const uint32_t triangles = ka == FeatureKind::kInterior || kb == FeatureKind::kInterior
                                   ? static_cast<uint32_t>(ring_tets_.size())
                                   : triangle_count(ring_tets_, a, b);
    assert(triangles == triangle_count(ring_tets_, a, b));
    if (state_[a].valence + state_[b].valence - triangles - 2 > params_.max_valence)
      return Reject::kValence;
    const double old_mean = gather_second_end(a, b);

    // Candidates: the more constrained end if the dimensions differ, else the midpoint
    // and then each end.
    uint32_t kept_options[3];
    int unmoved[3];  // the end that stays: 0 (a), 1 (b) or -1 (neither)
    Vec3 positions[3];
    int options = 0;
    if (ka != kb) {
      const uint32_t keep = ka < kb ? a : b;
      kept_options[0] = keep;
      unmoved[0] = keep == a ? 0 : 1;
      positions[0] = pos_[keep];
      options = 1;
    } else {
      kept_options[0] = std::min(a, b);
      unmoved[0] = -1;
      positions[0] = (pos_[a] + pos_[b]) * 0.5;
      kept_options[1] = a;
      unmoved[1] = 0;
      positions[1] = pos_[a];
      kept_options[2] = b;
      unmoved[2] = 1;
      positions[2] = pos_[b];
      options = 3;
    }
    // An interior node's quadric is zero (it lies on no boundary or interface triangle,
    // and only ever absorbs another interior node's): not read, it adds nothing.
    Quadric quadric;
    if (ka != FeatureKind::kInterior) quadric = quadric_[a];
    if (kb != FeatureKind::kInterior) quadric.add(quadric_[b]);
    Reject first = Reject::kNone;
    for (int c = 0; c < options; ++c) {
      double priority = 0;
      const Reject r = check_position(quadric, positions[c], unmoved[c], old_mean, &priority);
      if (r == Reject::kNone) {
        // The link conditions do not depend on the position or the priority: they are
        // checked when the collapse reaches the top of the queue (see simplify()).
        out->surface_edge = surface_edge;
        out->priority = priority;
        out->kept = kept_options[c];
        out->removed = out->kept == a ? b : a;
        out->position = positions[c];
        out->midpoint = unmoved[c] == -1;
        out->version_kept = state_[out->kept].version;
        out->version_removed = state_[out->removed].version;
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
      case Reject::kOverlap:
        ++rejections_.overlap;
        break;
      case Reject::kNone:
        break;
    }
  }

  // Starts loading what evaluating edge (a, b) reads, when its stars are cold (a stale
  // queue entry, far from the last collapse): the records of both stars, then the
  // corners' positions, each level requested at once rather than one by one.
  void load_edge(uint32_t a, uint32_t b) {
    for (uint32_t v : {a, b}) {
      __builtin_prefetch(&quadric_[v]);
      for (uint32_t t : star_[v]) __builtin_prefetch(&tet_[t]);
    }
    for (uint32_t v : {a, b})
      for (uint32_t t : star_[v])
        for (uint32_t w : tet_[t].v) __builtin_prefetch(&pos_[w]);
  }

  // Evaluates collapse (a, b), counted in *evaluations, and queues it if valid.
  void evaluate_and_push(uint32_t a, uint32_t b, uint64_t* evaluations) {
    ++*evaluations;
    Collapse c;
    const Reject r = evaluate(a, b, &c);
    if (r != Reject::kNone) {
      count(r);
      return;
    }
    heap_.push_back(c);  // without the position
    std::push_heap(heap_.begin() + 1, heap_.end(), CollapseLess());
  }

  // --------------------------------------------------------------- collapse
  // In tet `tet` (if any), the neighbour `from` becomes `to`.
  void replace_across(uint32_t tet, uint32_t from, uint32_t to) {
    if (tet == kInvalidIndex) return;
    uint32_t* across = &across_[4 * size_t{tet}];
    int c = 0;
    while (across[c] != from) ++c;
    across[c] = to;
    if (to == kInvalidIndex && guard_boundary_) glued_outer_.push_back(4 * tet + c);
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
        __builtin_prefetch(&state_[x]);
      }
    }
    // Valences: i gets the neighbours of both ends (the paper's formula, exact under the
    // link condition); each vertex x of a triangle (i, j, x) loses one (j).
    const uint32_t triangles = triangle_count(retired_tets_, i, j);
    state_[i].valence = state_[i].valence + state_[j].valence - triangles - 2;
    const uint32_t around_edge = stamp_;  // triangle_count() marked the x's
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
        if (mark_[x] == around_edge) mark_[x] = 0, --state_[x].valence;
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
    state_[j].alive = 0;
    quadric_[i].add(quadric_[j]);
    state_[i].outer |= state_[j].outer;
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
    first_end_ = kInvalidIndex;  // the mesh changed: the cached star blocks are gone
    neighbors(k, &ring_);
    ring_.push_back(k);
    // The versions say which collapse last changed a vertex, and whether it was made
    // by it (the centre, bit 0); see the stale entries in simplify().
    const uint32_t stamp = static_cast<uint32_t>(2 * collapses_);
    for (uint32_t v : ring_) {
      state_[v].version = stamp | (v == k);
      if (!state_[v].dirty) {
        state_[v].dirty = 1;
        dirty_list_.push_back(v);
      }
    }
    ring_.pop_back();
    for (uint32_t w : ring_) evaluate_and_push(k, w, &evaluations_.new_node);
  }

  // Whether evaluate(a, b) was already called on the mesh as it is now (neither end
  // changed since). Its result is then known: if valid, its entry is in the queue, or
  // was popped and refused by topology_ok(), which would refuse it again (it reads the
  // two stars, unchanged, and how many tets each material has left, which only falls),
  // or by the outer boundary's guard (which might pass it now, if faces near it have
  // moved: such an edge waits, as every refused edge does, until one of its ends
  // changes; trying the guard's refusals again whenever the queue ran dry, on
  // tests/data/gmsh/gap.msh at size 6 and tolerance 1, 2 and 4, passed none of them);
  // so evaluating it again would change nothing but the counts. Two such cases are
  // recognised: the collapse that last changed both ends made a, so refresh_around()
  // evaluated (a, b) right after it (the versions say so); or it is the last stale entry
  // of a evaluated again (redone_). Not (b, a): the result may differ in its last bits
  // (the sums run in another order) or in the end kept.
  bool evaluated_as_is(uint32_t a, uint32_t b) const {
    if (!skip_repeats_) return false;
    const uint32_t va = state_[a].version, vb = state_[b].version;
    const Redone& r = redone_[a];
    return ((va & 1) && vb == va - 1) ||
           (r.removed == b && r.version_kept == va && r.version_removed == vb);
  }

  // In a run past the valence, before the priority order starts: each node still past
  // both tau_VL and its input valence sheds neighbours by collapses of the edges of its
  // link (two of its neighbours in a triangle with it, which it then neighbours as
  // one) while it is past tau_VL, each time the valid one of highest priority. They are
  // checked as every collapse is, and are the first steps of the history. Rounds over
  // the nodes left, in id order, until one collapses nothing; returns how many nodes
  // are still past both.
  size_t bring_back_valences(SimplifyResult* result) {
    std::vector<Collapse> valid;
    std::vector<uint32_t> over, left;
    for (uint32_t h = 0; h < pos_.size(); ++h)
      if (state_[h].alive && past_valence(h)) over.push_back(h);
    const bool any = !over.empty();
    if (any) report("valence collapses", 0);
    while (!over.empty() && !cancelled()) {
      const size_t collapses_before = result->valence_collapses;
      left.clear();
      for (uint32_t h : over) {
        while (state_[h].alive && state_[h].valence > params_.max_valence &&
               collapse_in_link(h, &valid, result)) {
        }
        if (state_[h].alive && past_valence(h)) left.push_back(h);
      }
      over.swap(left);
      if (result->valence_collapses == collapses_before) break;
    }
    for (uint32_t h : over) left_past_.push_back(position_key(pos_[h]));
    if (any) report("valence collapses", 1);
    return over.size();
  }

  bool past_valence(uint32_t v) const {
    return state_[v].valence > params_.max_valence && state_[v].valence > input_valence_[v];
  }

  // One collapse of an edge of h's link, the valid one of highest priority; false if
  // there is none.
  bool collapse_in_link(uint32_t h, std::vector<Collapse>* valid, SimplifyResult* result) {
    edges_.clear();
    for (uint32_t t : star_[h]) {
      const Tet& q = tet_[t].v;
      for (int x = 0; x < 4; ++x)
        for (int y = x + 1; y < 4; ++y)
          if (q[x] != h && q[y] != h)
            edges_.push_back({std::min(q[x], q[y]), std::max(q[x], q[y])});
    }
    sort_unique(edges_);
    valid->clear();
    first_end_ = kInvalidIndex;
    for (const auto& [c, d] : edges_) {
      // The valence rule first, from the tets round the edge (at least the triangles
      // round it, less one on a surface), which most of these edges fail.
      uint32_t ring = 0;
      for (uint32_t t : star_[c]) ring += tet_has(tet_[t].v, d);
      if (state_[c].valence + state_[d].valence > params_.max_valence + ring + 3) continue;
      ++evaluations_.valence;
      Collapse collapse;
      const Reject r = evaluate(c, d, &collapse);
      if (r == Reject::kNone)
        valid->push_back(collapse);
      else
        count(r);
    }
    std::sort(valid->begin(), valid->end(),
              [](const Collapse& x, const Collapse& y) { return CollapseLess()(y, x); });
    for (const Collapse& c : *valid) {
      if (!checked_apply(c, result)) continue;
      first_end_ = kInvalidIndex;
      ++result->valence_collapses;
      return true;
    }
    return false;
  }

  // The checks made on a collapse about to be made (the link conditions and feature
  // rules, then the outer boundary's guard), and the collapse if they pass; false, and
  // the rejection counted, if not.
  bool checked_apply(const Collapse& c, SimplifyResult* result) {
    if (!topology_ok(c.kept, c.removed, c.surface_edge)) {
      count(Reject::kTopology);
      return false;
    }
    const bool moves_boundary = guard_boundary_ && changes_outer_boundary(c);
    if (moves_boundary && !outer_boundary_stays_embedded(c.kept, c.removed, c.position)) {
      count(Reject::kOverlap);
      return false;
    }
    glued_outer_.clear();
    apply(c, &result->history);
    if (guard_boundary_) update_outer_grid(c, moves_boundary);
    return true;
  }

  // Re-evaluates every edge with a dirty end, once.
  void sweep() {
    ++evaluations_.sweeps;
    std::vector<uint32_t> list;
    list.swap(dirty_list_);
    std::sort(list.begin(), list.end());
    for (uint32_t v : list) {
      if (!state_[v].alive) continue;
      neighbors(v, &around_);
      std::sort(around_.begin(), around_.end());
      for (uint32_t w : around_) {
        if (w < v && state_[w].dirty) continue;  // done from w's side
        if (evaluated_as_is(v, w)) {
          ++evaluations_.repeated;
          continue;
        }
        evaluate_and_push(v, w, &evaluations_.sweep);
      }
    }
    for (uint32_t v : list) state_[v].dirty = 0;
  }

  void simplify(SimplifyResult* result) {
    guard_boundary_ = params_.keep_boundary_embedded;
    if (guard_boundary_) {
      seen_.assign(tet_.size(), 0);
      vertex_seen_.assign(pos_.size(), 0);
      build_outer_grid();
    }
    heap_.assign(1, QueuedCollapse{});  // heap_[0]: see heap_
    dirty_list_.clear();
    alive_tets_ = tet_.size();
    const size_t initial_tets = alive_tets_;
    for (uint32_t v = 0; v < pos_.size(); ++v) state_[v].valence = valence(v);
    if (result->splits_past_valence > 0) {
      result->nodes_left_past_valence = bring_back_valences(result);
      if (result->nodes_left_past_valence > 0) return;  // given up: see ::simplify()
    }
    // Its own phase, with its progress: evaluating every edge takes a while (0.5 s on the
    // bundled motor at size 8, 4 s on 2.6M tets) before the first collapse.
    std::vector<uint32_t> nb;
    for (uint32_t v = 0; v < pos_.size(); ++v) {
      if ((v & 4095) == 0) {  // before the priority order's first collapse
        report("evaluate edges", double(v) / double(pos_.size()));
        if (cancelled()) {
          result->cancelled = true;
          return;
        }
      }
      neighbors(v, &nb);
      for (uint32_t w : nb)
        if (w > v) evaluate_and_push(v, w, &evaluations_.initial);
    }
    report("evaluate edges", 1);
    report("simplify", 0);
    size_t pops = 0;
    while (true) {
      if (params_.target_elements > 0 && alive_tets_ <= params_.target_elements) break;
      if (heap_.size() == 1) {
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
      std::pop_heap(heap_.begin() + 1, heap_.end(), CollapseLess());
      const QueuedCollapse q = heap_.back();
      heap_.pop_back();
      if (!state_[q.kept].alive || !state_[q.removed].alive) continue;
      if (q.version_kept != state_[q.kept].version ||
          q.version_removed != state_[q.removed].version) {
        // Stale: evaluate again now, unless a sweep already did or this very evaluation
        // was already made on the mesh as it is.
        if (evaluated_as_is(q.kept, q.removed)) {
          ++evaluations_.repeated;
          continue;
        }
        if (state_[q.kept].dirty || state_[q.removed].dirty) {
          load_edge(q.kept, q.removed);
          evaluate_and_push(q.kept, q.removed, &evaluations_.stale);
          redone_[q.kept] = {q.removed, state_[q.kept].version, state_[q.removed].version};
        }
        continue;
      }
      // Current: neither end moved since the evaluation.
      Collapse c;
      static_cast<QueuedCollapse&>(c) = q;
      c.position = q.midpoint ? (pos_[q.kept] + pos_[q.removed]) * 0.5 : pos_[q.kept];
      if (!checked_apply(c, result)) continue;
      refresh_around(c.kept);
    }
    report("simplify", 1);
  }

  // ------------------------------------------------------- the outer boundary
  // Every new tet is positive, yet a collapse may still push the outer boundary
  // through another part of it: two sheets nearer than the tolerance (across a thin
  // gap or slot) are each held only to their own planes. The tets then overlap with no
  // face between them, which every reader of TetLOD refuses (find_overlap(),
  // core/overlap.h). With every tet positive, the number of tets over a point is the
  // winding number of the outer boundary around it (the degree of the map), so tets
  // overlap only where the boundary is not embedded: where it crosses itself, or folds
  // over along an edge, which no crossing shows (the tets around that edge then fill
  // more than a full turn). So a collapse that moves the outer boundary is refused if
  // one of the faces it makes would clearly cross another (the reader's test, within a
  // piece: tets joined through vertices, as the reader checks), or the tets around an
  // edge of those faces would fill more than a full turn, or, where more than two outer
  // faces meet at such an edge (bodies meeting along it), their wedges would overlap.
  // Bodies meshed apart (other pieces) are held to less: a face the collapse makes may
  // cross one of theirs only if a face it replaces crossed it already (where they meet
  // on a curved surface, their two meshes' chords cross by design), so no collapse
  // pushes one body into another that it did not cross. Nor may the new faces sweep
  // past a whole small body or cavity, crossing none of its faces: no corner of another
  // outer face may come to lie inside the new tets (unless it lay inside the tets
  // around the ends already). Checked on the collapses about to be made, after every
  // other test; the outer faces are kept in a grid.

  // Whether collapse c moves the outer boundary's faces: it removes a vertex on it, or
  // moves one.
  bool changes_outer_boundary(const Collapse& c) const {
    return state_[c.removed].outer ||
           (state_[c.kept].outer && std::memcmp(&pos_[c.kept], &c.position, sizeof(Vec3)) != 0);
  }

  // Face 4 t + c: the face of tet t opposite its corner c.
  Triangle3 face_triangle(uint32_t face) const {
    const Tet& q = tet_[face / 4].v;
    const int c = face % 4;
    return {pos_[q[(c + 1) % 4]], pos_[q[(c + 2) % 4]], pos_[q[(c + 3) % 4]]};
  }

  static void box_of(const Triangle3& t, Vec3* lo, Vec3* hi) {
    for (int k = 0; k < 3; ++k) {
      (*lo)[k] = std::min({t[0][k], t[1][k], t[2][k]});
      (*hi)[k] = std::max({t[0][k], t[1][k], t[2][k]});
    }
  }

  static bool boxes_meet(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
    return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y && alo.z <= bhi.z &&
           blo.z <= ahi.z;
  }

  void insert_outer_face(uint32_t face) {
    Vec3 lo, hi;
    box_of(face_triangle(face), &lo, &hi);
    outer_grid_.insert(face, lo, hi);
  }

  // Lays the grid out again over the outer faces as they are now: cells about their
  // mean extent (they grow as the run coarsens the boundary), stale entries gone.
  void build_outer_grid() {
    if (!outer_grid_laid_) {
      outer_grid_laid_ = true;
      // Every position stays in this box: a new node is an end or a midpoint.
      outer_lo_ = outer_hi_ = pos_[0];
      for (const Vec3& p : pos_) {
        for (int k = 0; k < 3; ++k)
          outer_lo_[k] = std::min(outer_lo_[k], p[k]), outer_hi_[k] = std::max(outer_hi_[k], p[k]);
      }
    }
    struct Entry {
      uint32_t face;
      Vec3 lo, hi;
    };
    std::vector<Entry> faces;
    double extent_sum = 0;
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      if (!tet_[t].alive) continue;
      for (uint32_t f = 4 * t; f < 4 * t + 4; ++f) {
        if (across_[f] != kInvalidIndex) continue;
        Entry e{f, {}, {}};
        box_of(face_triangle(f), &e.lo, &e.hi);
        extent_sum += std::max({e.hi.x - e.lo.x, e.hi.y - e.lo.y, e.hi.z - e.lo.z});
        faces.push_back(e);
      }
    }
    const double cell = faces.empty() ? 1.0 : extent_sum / double(faces.size());
    outer_grid_.reset(outer_lo_, outer_hi_, cell, std::max<size_t>(4096, 2 * faces.size()));
    for (const Entry& e : faces) outer_grid_.insert(e.face, e.lo, e.hi);
    outer_entries_at_build_ = std::max<size_t>(outer_grid_.entries(), 4096);
  }

  // After collapse c: the outer faces it changed or made go into the grid where they
  // are now. If it moved the boundary, they are the outer faces at the new node; else
  // only the faces glued to the outside in place of a removed tet's (apply()), which
  // kept their corners and became faces of another tet.
  void update_outer_grid(const Collapse& c, bool moved_boundary) {
    if (moved_boundary) {
      for (uint32_t t : star_[c.kept]) {
        const Tet& q = tet_[t].v;
        for (int k = 0; k < 4; ++k)
          if (q[k] != c.kept && across_[4 * t + k] == kInvalidIndex) insert_outer_face(4 * t + k);
      }
    } else {
      for (uint32_t f : glued_outer_) insert_outer_face(f);
    }
    if (outer_grid_.entries() > 2 * outer_entries_at_build_) build_outer_grid();
  }

  // A tet as it would be after the collapse: corner ids (the kept end for the new
  // node) and positions.
  struct WouldBeTet {
    std::array<uint32_t, 4> v;
    std::array<Vec3, 4> p;
  };

  WouldBeTet would_be(uint32_t t, uint32_t kept, uint32_t removed, const Vec3& k) const {
    WouldBeTet n;
    for (int c = 0; c < 4; ++c) {
      const uint32_t x = tet_[t].v[c];
      const bool end = x == kept || x == removed;
      n.v[c] = end ? kept : x;
      n.p[c] = end ? k : pos_[x];
    }
    return n;
  }

  // A sum of angles in [0, pi] (the dihedral angles of tets at an edge), kept as a
  // vector in the plane turned by each in turn: it has gone past a whole turn when it
  // comes back from below the axis to above it.
  struct Turn {
    double x = 1, y = 0;
    bool past = false;
    // The angle between n1 and n2: the normals of a tet's two faces at the edge, both
    // the edge's direction crossed with the way from the edge to the face's third corner.
    void add(const Vec3& n1, const Vec3& n2) {
      const double c = dot(n1, n2), s = length(cross(n1, n2));
      const double turned_x = x * c - y * s, turned_y = x * s + y * c;
      past |= y < 0 && turned_y >= 0;
      const double scale = std::max(std::fabs(turned_x), std::fabs(turned_y));
      if (!(scale > 0)) return;  // no angle (a flat tet), as atan2(0, 0) is 0
      x = turned_x / scale;
      y = turned_y / scale;
    }
    // A full turn, or all but 1e-8 of it (find_overlap() refuses more than a turn).
    bool full() const { return past || (y < 0 && x > 0 && -y < 1e-8 * x); }
  };

  // Adds the dihedral angle of tet n at its edge (corner a, corner b) to `turn`.
  static void add_angle(const WouldBeTet& n, int a, int b, Turn* turn) {
    int other[2], count = 0;
    for (int k = 0; k < 4; ++k)
      if (k != a && k != b) other[count++] = k;
    const Vec3 &pa = n.p[a], edge = n.p[b] - pa;
    turn->add(cross(edge, n.p[other[0]] - pa), cross(edge, n.p[other[1]] - pa));
  }

  // The corner off outer face c of tet t (the face holds end v of the collapse, not the
  // other end) of the tet that holds the face after the collapse, at its position then:
  // t's own corner, or, if t goes (it holds both ends), that of the tet across t's face
  // opposite v, onto which the face is glued. None (a zero vector, `known` false) if
  // that tet goes too, or if there is none (the face and its twin then go).
  struct Apex {
    Vec3 at;
    bool known = false;
  };
  Apex apex_after(uint32_t t, int c, uint32_t v, uint32_t other, uint32_t kept, uint32_t removed,
                  const Vec3& k) const {
    const Tet& q = tet_[t].v;
    if (!tet_has(q, other)) return {pos_[q[c]], true};
    int corner_v = 0;
    while (q[corner_v] != v) ++corner_v;
    const uint32_t across = across_[4 * t + corner_v];
    if (across == kInvalidIndex) return {};
    const Tet& r = tet_[across].v;
    if (tet_has(r, kept) && tet_has(r, removed)) return {};
    for (uint32_t y : r) {
      if (y == other) continue;
      if (!tet_has(q, y)) return {y == v ? k : pos_[y], true};
    }
    return {};
  }

  // Whether the wedges round edge (p, q) overlap, `faces` being its outer faces after the
  // collapse (wedges_overlap(), as the reader checks them), or cannot be told (a face
  // whose tet is not known): only where more than two meet.
  bool wedges_at_edge_overlap(const Vec3& p, const Vec3& q, const std::vector<EdgeFace>& faces,
                              bool all_known) const {
    if (faces.size() <= 2) return false;
    return !all_known || wedges_overlap(p, q, faces);
  }

  // Whether collapsing (kept, removed) onto position k leaves the outer boundary
  // embedded (see above).
  bool outer_boundary_stays_embedded(uint32_t kept, uint32_t removed, const Vec3& k) {
    // The faces the collapse makes: the outer faces around either end that hold only
    // that end, with it at k (those that hold both go); and the tets that stay there.
    fan_.clear();
    fan_corners_.clear();
    fan_apex_.clear();
    staying_tets_.clear();
    Vec3 swept_lo = k, swept_hi = k;  // the box of the outer faces at the ends, before and after
    for (int side = 0; side < 2; ++side) {
      const uint32_t v = side == 0 ? kept : removed, other = side == 0 ? removed : kept;
      for (uint32_t t : star_[v]) {
        const Tet& q = tet_[t].v;
        const bool ring = tet_has(q, other);
        if (!ring) staying_tets_.push_back(would_be(t, kept, removed, k));
        for (int c = 0; c < 4; ++c) {
          if (q[c] == v || across_[4 * t + c] != kInvalidIndex) continue;
          for (int n = 1; n < 4; ++n) {
            const Vec3& x = pos_[q[(c + n) % 4]];
            for (int a = 0; a < 3; ++a)
              swept_lo[a] = std::min(swept_lo[a], x[a]), swept_hi[a] = std::max(swept_hi[a], x[a]);
          }
          if (ring && q[c] != other) continue;  // holds both ends
          std::array<uint32_t, 3> ids;
          Triangle3 tri;
          for (int n = 0; n < 3; ++n) {
            const uint32_t x = q[(c + 1 + n) % 4];
            ids[n] = x == v ? kept : x;
            tri[n] = x == v ? k : pos_[x];
          }
          fan_.push_back(tri);
          fan_corners_.push_back(ids);
          fan_apex_.push_back(apex_after(t, c, v, other, kept, removed, k));
        }
      }
    }
    if (fan_.empty()) return true;
    fan_planes_.resize(fan_.size());
    fan_lo_.resize(fan_.size());
    fan_hi_.resize(fan_.size());
    Vec3 lo, hi;  // the box of them all
    for (size_t f = 0; f < fan_.size(); ++f) {
      fan_planes_[f] = plane_of(fan_[f]);
      box_of(fan_[f], &fan_lo_[f], &fan_hi_[f]);
      for (int a = 0; a < 3; ++a) {
        lo[a] = f == 0 ? fan_lo_[f][a] : std::min(lo[a], fan_lo_[f][a]);
        hi[a] = f == 0 ? fan_hi_[f][a] : std::max(hi[a], fan_hi_[f][a]);
      }
    }
    return !new_faces_fold(kept, removed, k) &&
           !new_faces_cross_others(kept, removed, lo, hi, swept_lo, swept_hi);
  }

  // Whether the new faces (fan_ and the rest, as outer_boundary_stays_embedded() lists
  // them) cross one another, or the tets round one of their edges would fill a turn, or
  // wedges would overlap where more than two outer faces meet at one of their edges.
  bool new_faces_fold(uint32_t kept, uint32_t removed, const Vec3& k) {
    // The new faces among themselves.
    for (size_t f = 0; f < fan_.size(); ++f)
      for (size_t g = f + 1; g < fan_.size(); ++g)
        if (boxes_meet(fan_lo_[f], fan_hi_[f], fan_lo_[g], fan_hi_[g]) &&
            triangles_cross(fan_[f], fan_planes_[f], fan_[g], fan_planes_[g]))
          return true;
    // Round each of their edges. Every new face holds the new node: its edges to the
    // other corners (rim_), round which the tets that stay turn, are summed in one pass
    // over those tets; a far edge (a, b), over a's tets but those around the collapsed
    // edge, with either end at k.
    rim_.clear();
    edges_.clear();
    for (const auto& ids : fan_corners_) {
      int at_k = 0;  // each holds the new node once
      while (ids[at_k] != kept) ++at_k;
      const uint32_t a = ids[(at_k + 1) % 3], b = ids[(at_k + 2) % 3];
      rim_.push_back(a);
      rim_.push_back(b);
      edges_.push_back({std::min(a, b), std::max(a, b)});
    }
    sort_unique(rim_);
    sort_unique(edges_);
    turns_.assign(rim_.size(), Turn());
    for (const WouldBeTet& n : staying_tets_) {
      int at_k = 0;
      while (n.v[at_k] != kept) ++at_k;
      for (int c = 0; c < 4; ++c) {
        if (c == at_k) continue;
        const auto it = std::lower_bound(rim_.begin(), rim_.end(), n.v[c]);
        if (it != rim_.end() && *it == n.v[c]) add_angle(n, at_k, c, &turns_[it - rim_.begin()]);
      }
    }
    for (const Turn& turn : turns_)
      if (turn.full()) return true;
    // Where bodies meet along an edge (more than two outer faces there), their wedges
    // must not overlap. At the new node's edges the outer faces are the new ones.
    for (uint32_t a : rim_) {
      edge_faces_.clear();
      bool known = true;
      for (size_t f = 0; f < fan_.size(); ++f) {
        const auto& ids = fan_corners_[f];
        if (ids[0] != a && ids[1] != a && ids[2] != a) continue;
        const uint32_t w = ids[0] != a && ids[0] != kept
                               ? ids[0]
                               : (ids[1] != a && ids[1] != kept ? ids[1] : ids[2]);
        known &= fan_apex_[f].known;
        edge_faces_.push_back({pos_[w], fan_apex_[f].at});
      }
      if (wedges_at_edge_overlap(k, pos_[a], edge_faces_, known)) return true;
    }
    for (const auto& e : edges_) {
      Turn turn;
      edge_faces_.clear();
      bool known = true;
      for (uint32_t t : star_[e.first]) {
        const Tet& q = tet_[t].v;
        if (!tet_has(q, e.second) || (tet_has(q, kept) && tet_has(q, removed))) continue;
        const WouldBeTet n = would_be(t, kept, removed, k);
        int a = 0, b = 0;
        while (n.v[a] != e.first) ++a;
        while (n.v[b] != e.second) ++b;
        add_angle(n, a, b, &turn);
        // Its outer faces at the edge that hold no end (those that do are new).
        for (int c = 0; c < 4; ++c) {
          if (c == a || c == b || across_[4 * t + c] != kInvalidIndex) continue;
          const int w = 6 - a - b - c;  // the face's third corner
          if (q[w] == kept || q[w] == removed) continue;
          edge_faces_.push_back({n.p[w], n.p[c]});
        }
      }
      if (turn.full()) return true;
      for (size_t f = 0; f < fan_.size(); ++f) {
        const auto& ids = fan_corners_[f];
        const bool has_a = ids[0] == e.first || ids[1] == e.first || ids[2] == e.first;
        const bool has_b = ids[0] == e.second || ids[1] == e.second || ids[2] == e.second;
        if (!has_a || !has_b) continue;
        known &= fan_apex_[f].known;
        edge_faces_.push_back({k, fan_apex_[f].at});  // the third corner is the new node
      }
      if (wedges_at_edge_overlap(pos_[e.first], pos_[e.second], edge_faces_, known)) return true;
    }
    return false;
  }

  // Whether a new face would clearly cross another outer face: of the piece, or of
  // another piece where none of the faces the collapse replaces crossed that face
  // already; or a corner of another outer face would be swept inside the new tets
  // (a small body, or a cavity, that the faces sweep past whole, crossing none).
  // [lo, hi] is the box of the new faces, [swept_lo, swept_hi] that of the outer faces
  // at the ends before and after, which holds what they sweep.
  bool new_faces_cross_others(uint32_t kept, uint32_t removed, const Vec3& lo, const Vec3& hi,
                              const Vec3& swept_lo, const Vec3& swept_hi) {
    // The other outer faces near them: no crossing. Past the budget (a
    // hostile mesh crowding faces into a few cells), refuse rather than not check.
    candidates_.clear();
    if (!outer_grid_.gather(swept_lo, swept_hi, params_.boundary_guard_budget, &candidates_))
      return true;
    staying_lo_.resize(staying_tets_.size());
    staying_hi_.resize(staying_tets_.size());
    for (size_t n = 0; n < staying_tets_.size(); ++n) {
      const auto& p = staying_tets_[n].p;
      for (int a = 0; a < 3; ++a) {
        staying_lo_[n][a] = std::min({p[0][a], p[1][a], p[2][a], p[3][a]});
        staying_hi_[n][a] = std::max({p[0][a], p[1][a], p[2][a], p[3][a]});
      }
    }
    const uint32_t piece = piece_[kept];
    // Each tet once (an entry is in every cell its face touched, and the face may
    // have moved since): all its outer faces as they are now, but those at an
    // end (the fan has them, or they go).
    if (++seen_stamp_ == 0) {
      std::fill(seen_.begin(), seen_.end(), 0);
      std::fill(vertex_seen_.begin(), vertex_seen_.end(), 0);
      seen_stamp_ = 1;
    }
    for (uint32_t entry : candidates_) {
      const uint32_t t = entry / 4;
      if (seen_[t] == seen_stamp_ || !tet_[t].alive) continue;
      seen_[t] = seen_stamp_;
      const Tet& q = tet_[t].v;
      for (int c = 0; c < 4; ++c) {
        if (across_[4 * t + c] != kInvalidIndex) continue;
        bool at_end = false;
        for (int n = 1; n < 4; ++n) at_end |= q[(c + n) % 4] == kept || q[(c + n) % 4] == removed;
        if (at_end) continue;
        const Triangle3 tri = face_triangle(4 * t + c);
        Vec3 tlo, thi;
        box_of(tri, &tlo, &thi);
        if (!boxes_meet(tlo, thi, swept_lo, swept_hi)) continue;
        for (int n = 1; n < 4; ++n) {
          const uint32_t w = q[(c + n) % 4];
          if (vertex_seen_[w] == seen_stamp_) continue;
          vertex_seen_[w] = seen_stamp_;
          if (swept_inside(pos_[w], kept, removed)) return true;
        }
        if (!boxes_meet(tlo, thi, lo, hi)) continue;
        TrianglePlane plane;
        bool have_plane = false;
        for (size_t f = 0; f < fan_.size(); ++f) {
          if (!boxes_meet(fan_lo_[f], fan_hi_[f], tlo, thi)) continue;
          if (!have_plane) plane = plane_of(tri), have_plane = true;
          if (triangles_cross(fan_[f], fan_planes_[f], tri, plane)) {
            // Bodies meshed apart may cross where they meet (find_overlap() reads them
            // so: the chords of two meshes of one curved surface): a collapse may keep
            // such a crossing, not make one.
            if (piece_[q[0]] == piece || !crossed_now(kept, removed, tri, plane)) return true;
            break;
          }
        }
      }
    }
    return false;
  }

  // Whether p (a corner of an outer face, not at the ends) would lie inside a new tet
  // (staying_tets_) and does not lie inside a tet around the ends now: the new faces
  // would sweep past it. Inside: more than 1e-9 of the tet's volume from each face.
  bool swept_inside(const Vec3& p, uint32_t kept, uint32_t removed) const {
    auto inside = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
      const double margin = 1e-9 * signed_volume6(a, b, c, d);
      return margin > 0 && signed_volume6(p, b, c, d) > margin &&
             signed_volume6(a, p, c, d) > margin && signed_volume6(a, b, p, d) > margin &&
             signed_volume6(a, b, c, p) > margin;
    };
    for (size_t n = 0; n < staying_tets_.size(); ++n) {
      const Vec3 &lo = staying_lo_[n], &hi = staying_hi_[n];
      if (p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y || p.z < lo.z || p.z > hi.z)
        continue;
      const auto& q = staying_tets_[n].p;
      if (!inside(q[0], q[1], q[2], q[3])) continue;
      for (uint32_t v : {kept, removed}) {
        for (uint32_t t : star_[v]) {
          const Tet& r = tet_[t].v;
          if (inside(pos_[r[0]], pos_[r[1]], pos_[r[2]], pos_[r[3]])) return false;
        }
      }
      return true;
    }
    return false;
  }

  // Whether an outer face at `kept` or `removed` (those the collapse replaces), as it is
  // now, clearly crosses `tri`.
  bool crossed_now(uint32_t kept, uint32_t removed, const Triangle3& tri,
                   const TrianglePlane& plane) const {
    for (uint32_t v : {kept, removed}) {
      for (uint32_t t : star_[v]) {
        for (int c = 0; c < 4; ++c) {
          if (tet_[t].v[c] == v || across_[4 * t + c] != kInvalidIndex) continue;
          const Triangle3 old = face_triangle(4 * t + c);
          if (triangles_cross(old, plane_of(old), tri, plane)) return true;
        }
      }
    }
    return false;
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

  // The tets, and those above the size as count_violations() counts them (the size of
  // tet_shape()), without the rest of the shape.
  size_t tets_above_size(size_t* tets) const {
    size_t n = 0;
    *tets = 0;
    for (uint32_t t = 0; t < tet_.size(); ++t) {
      if (!tet_[t].alive) continue;
      ++*tets;
      const Tet& q = tet_[t].v;
      const Vec3 &a = pos_[q[0]], &b = pos_[q[1]], &c = pos_[q[2]], &d = pos_[q[3]];
      n += std::sqrt(tet_longest_edge2(a, b, c, d)) > size_limit(t);
    }
    return n;
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
      if (!state_[x].alive || star_[x].empty()) continue;
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
  const bool past_valence_;                 // subdivision may take nodes past tau_VL
  const std::vector<PositionKey>* pinned_;  // but not these
  size_t max_tets_ = kMaxTets;
  bool red_over_max_ = false;  // a red level would have made more than max_tets_
  bool over_factor_ = false;   // subdivision stopped at max_tets_, a run past the valence's bound
  const SurfacePatches* patches_ = nullptr;  // the input's surface groups, or none
  // Called once subdivision is done, if a split was refused for a node's valence, with
  // the subdivided tets and how many are above the size (see ::simplify()).
  std::function<void(size_t tets, size_t above_size)> after_subdivide_;
  // The edges (a < b, sorted) of patches_' faces inside a material, before
  // subdivision (whose splits keep the ids of the vertices there).
  std::vector<std::pair<uint32_t, uint32_t>> kept_edges_;

 public:
  void set_patches(const SurfacePatches* patches) {
    patches_ = patches;
  }
  // The most tets subdivision may make (a run past the valence: a multiple of the
  // first run's; see ::simplify()).
  void set_max_tets(size_t max_tets) {
    max_tets_ = max_tets;
  }
  void set_after_subdivide(std::function<void(size_t, size_t)> f) {
    after_subdivide_ = std::move(f);
  }
  // The nodes bring_back_valences() left past the valence, by position.
  const std::vector<PositionKey>& left_past() const {
    return left_past_;
  }

 private:
  double tolerance2_ = 0;

  std::vector<Vec3> pos_;
  std::vector<TetRecord> tet_;
  std::vector<std::vector<uint32_t>> star_;  // sorted tet ids per vertex
  std::vector<uint32_t> input_valence_;
  std::vector<PositionKey> left_past_;
  std::vector<int32_t> material_ids_;  // sorted
  std::vector<size_t> material_tets_;  // alive tets per material, by index in material_ids_

  // What the queue and the evaluations read of each vertex, in one record (classify()
  // on): both ends of every popped entry and every evaluation are read at random, so
  // one cache line instead of one per array.
  struct VertexState {
    // Changed whenever its star changes (its queued entries go stale): twice the number
    // of the collapse that last changed it, plus 1 if that collapse made it.
    uint32_t version = 0;
    uint32_t valence = 0;  // |v*(v)|, kept up to date by apply()
    FeatureKind kind = FeatureKind::kInterior;
    uint8_t alive = 1;
    uint8_t dirty = 0;  // its star changed since the last sweep
    uint8_t outer = 0;  // on the boundary of the whole mesh
  };
  std::vector<VertexState> state_;
  // The last stale entry of each vertex (as `kept`) evaluated again, and at which
  // versions: another entry of the same edge, popped while neither end changed, would
  // give the same result again (see simplify()).
  struct Redone {
    uint32_t removed = kInvalidIndex;
    uint32_t version_kept = 0, version_removed = 0;
  };
  std::vector<Redone> redone_;
  bool skip_repeats_ = true;
  std::vector<std::vector<uint32_t>> feature_neighbors_;
  std::vector<Quadric> quadric_;

  // The queue: a max-heap in heap_[1..] (heap_[0] is unused), in storage that starts
  // on a cache line, so that the two children of every entry lie in one line and a
  // pop reads one line a level instead of two.
  std::vector<QueuedCollapse, LineAligned<QueuedCollapse>> heap_;
  std::vector<uint32_t> dirty_list_;
  RejectionCounts rejections_;
  EvaluationCounts evaluations_;
  size_t collapses_ = 0;
  size_t alive_tets_ = 0;

  // Scratch, reused to keep the hot loop free of allocation.
  std::vector<uint32_t> mark_;
  uint32_t stamp_ = 0;
  std::vector<uint32_t> ring_mark_;
  uint32_t ring_stamp_ = 0;
  std::vector<int32_t> edge_materials_;
  std::vector<uint32_t> ring_, around_, ring_others_;
  // The tets of t*(a) U t*(b) that survive the collapse (see gather_first_end()).
  std::vector<TetBlock> moving_;
  std::vector<uint8_t> block_built_;
  size_t first_blocks_ = 0, moving_blocks_ = 0, moving_count_ = 0;
  uint32_t first_end_ = kInvalidIndex, second_end_ = kInvalidIndex;
  double first_sum_ = 0;               // stretches of the star of first_end_
  std::vector<uint32_t> second_tets_;  // the tets of b off the ring
  std::vector<uint32_t> ring_tets_;    // the tets around the edge evaluated
  bool uniform_sizing_ = false;        // only the uniform size is set: no per-tet field lookups
  bool region_sizing_ = false;         // radial or box rules: sizes depend on the position
  bool late_limits_ = false;           // a size map: sizes checked last (check_position())
  double red_levels_expected_ = 1;     // about how many red levels, for the progress
  bool red_levels_end_ = false;        // the last red level is made (red_level())
  double predicted_splits_ = 0;        // tets subdivision would add, about: sum of (2 s / tau_SZ)^3
  const VectorKernels& kernels_ = vector_kernels();
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
  // The outer boundary's guard (outer_boundary_stays_embedded()).
  bool guard_boundary_ = false;
  FaceGrid outer_grid_;  // outer faces (4 t + corner), where they were when added
  size_t outer_entries_at_build_ = 0;
  Vec3 outer_lo_, outer_hi_;  // the box of every position, then and later
  bool outer_grid_laid_ = false;
  std::vector<uint32_t> piece_;  // vertex_pieces() of the mesh classified
  std::vector<Triangle3> fan_;   // the outer faces a collapse would make
  std::vector<std::array<uint32_t, 3>> fan_corners_;
  std::vector<Apex> fan_apex_;        // the corner off each of them, of its tet then
  std::vector<EdgeFace> edge_faces_;  // outer faces at one edge (wedges_at_edge_overlap())
  std::vector<TrianglePlane> fan_planes_;
  std::vector<Vec3> fan_lo_, fan_hi_;
  std::vector<WouldBeTet> staying_tets_;
  std::vector<uint32_t> rim_;  // the new faces' corners but the new node
  std::vector<Turn> turns_;    // round the edge from the new node to each of rim_
  std::vector<std::pair<uint32_t, uint32_t>> edges_;
  std::vector<uint32_t> candidates_;
  std::vector<uint32_t> glued_outer_;  // outer faces apply() glued in place of others
  std::vector<uint32_t> seen_;         // per tet: seen_stamp_ if looked at in this check
  std::vector<uint32_t> vertex_seen_;  // per vertex: likewise
  uint32_t seen_stamp_ = 0;
  std::vector<Vec3> staying_lo_, staying_hi_;  // the boxes of staying_tets_
};

}  // namespace

namespace {

Status run_engine(const TetMesh& input, const SimplifyParams& params, bool past_valence,
                  const ProgressCallback& progress, const std::atomic<bool>* cancel,
                  const SurfacePatches* patches, SimplifyResult* result,
                  std::vector<PositionKey>* pinned = nullptr, size_t max_tets = kMaxTets,
                  std::function<void(size_t, size_t)> after_subdivide = {}) {
  *result = SimplifyResult{};
  Engine engine(input, params, progress, cancel, past_valence, pinned);
  engine.set_patches(patches);
  engine.set_max_tets(max_tets);
  engine.set_after_subdivide(std::move(after_subdivide));
  const Status s = engine.run(result);
  if (pinned) {
    pinned->insert(pinned->end(), engine.left_past().begin(), engine.left_past().end());
    sort_unique(*pinned);
  }
  return s;
}

double run_seconds(const SimplifyResult& r) {
  return r.seconds_subdivide + r.seconds_classify + r.seconds_simplify;
}

// The runs past the valence of simplify() (see there): each with the nodes the one
// before left past it pinned, up to kRuns.
struct PastRuns {
  static constexpr int kRuns = 4;
  static constexpr size_t kMostLeft = 16;  // a run that leaves more is not made again
  Status status;
  SimplifyResult last;
  std::vector<PositionKey> pinned;  // after the last run: the nodes every run left
  size_t pinned_in_last = 0;        // of them, those pinned in the last run
  int runs = 0;
  double seconds_before_last = 0;

  void make(const TetMesh& input, const SimplifyParams& params, const ProgressCallback& progress,
            const std::atomic<bool>* cancel, const SurfacePatches* patches, size_t max_tets) {
    for (runs = 1;; ++runs) {
      pinned_in_last = pinned.size();
      status = run_engine(input, params, true, progress, cancel, patches, &last, &pinned, max_tets);
      if (!status || last.cancelled || last.nodes_left_past_valence == 0 || runs == kRuns ||
          last.nodes_left_past_valence > kMostLeft)
        break;
      seconds_before_last += run_seconds(last);
    }
  }
};

// PastRuns::make() on a thread of its own, started while the first run of simplify()
// collapses. Its progress is kept, to be passed on from the calling thread (as
// simplify() promises) once the first run is done; stop_and_join() cancels it.
class PastRunsAlongside {
 public:
  PastRunsAlongside() = default;
  PastRunsAlongside(const PastRunsAlongside&) = delete;
  PastRunsAlongside& operator=(const PastRunsAlongside&) = delete;
  ~PastRunsAlongside() { stop_and_join(); }

  bool started() const { return thread_.joinable(); }

  // Where the runs are, for the first run's progress (SimplifyProgress::other_phase);
  // nothing if they were not started.
  void where(SimplifyProgress* p) {
    if (!started()) return;
    std::lock_guard<std::mutex> lock(mutex_);
    p->other_phase = done_ ? "done" : reported_ ? latest_.phase : "starting";
    p->other_fraction = done_ ? 1 : reported_ ? latest_.fraction : 0;
  }

  // Leaves it not started if no thread can be made (simplify() then makes the runs
  // after the first, as without a second processor).
  void start(const TetMesh& input, const SimplifyParams& params, const SurfacePatches* patches,
             size_t max_tets) {
    try {
      thread_ = std::thread(
          [this, &input, params, patches, max_tets] { run(input, params, patches, max_tets); });
    } catch (const std::system_error&) {
    }
  }

  void stop_and_join() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }

  // Waits for the runs to end, passing their progress on from this thread and their
  // cancellation from `cancel`.
  PastRuns& finish(const ProgressCallback& progress, const std::atomic<bool>* cancel) {
    for (bool done = false; !done;) {
      SimplifyProgress p;
      bool fresh = false;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait_for(lock, std::chrono::milliseconds(50), [this] { return fresh_ || done_; });
        p = latest_;
        fresh = fresh_;
        fresh_ = false;
        done = done_;
      }
      if (fresh && progress) progress(p);
      if (cancel && cancel->load(std::memory_order_relaxed)) stop_.store(true);
    }
    thread_.join();
    return runs_;
  }

 private:
  // The thread: the runs, then done_.
  void run(const TetMesh& input, const SimplifyParams& params, const SurfacePatches* patches,
           size_t max_tets) {
    try {
      runs_.make(
          input, params,
          [this](const SimplifyProgress& p) {
            std::lock_guard<std::mutex> lock(mutex_);
            latest_ = p;
            fresh_ = reported_ = true;
            changed_.notify_one();
          },
          &stop_, patches, max_tets);
    } catch (const std::bad_alloc&) {
      runs_.status = Status::error("the run past the valence ran out of memory");
    } catch (const std::exception& e) {
      runs_.status = Status::error(std::string("the run past the valence failed: ") + e.what());
    }
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
    changed_.notify_one();
  }

  PastRuns runs_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  SimplifyProgress latest_;
  bool fresh_ = false, reported_ = false, done_ = false;
};

// simplify() on a mesh round the origin (far_shift() is zero).
Status simplify_near_origin(const TetMesh& input, const SimplifyParams& params,
                            SimplifyResult* result, const ProgressCallback& progress,
                            const std::atomic<bool>* cancel, const SurfacePatches* patches) {
  Status s;
  // Subdivision keeps every node within tau_VL, which on a coarse, graded input leaves
  // long edges unsplit (longest-edge bisection adds a neighbour to every node opposite
  // a split edge), and so tets above the size. If the run leaves such tets, another
  // run subdivides first by red levels (Engine::red_level(): a red tet's corners gain
  // no neighbours), then by bisection, and lets both take nodes up to twice tau_VL
  // (in a trial on the bundled motor at size 12, red levels within tau_VL left 3,068
  // tets above the size; with the cap doubled, none); edge removals, then collapses
  // in the links of the nodes it took past both tau_VL and their input valence, bring
  // those back before the priority order starts. If one is left, that run is given up
  // and made again with the nodes left pinned (subdivision keeps them within tau_VL;
  // they are found by position: no collapse moves a node it leaves past the valence),
  // up to PastRuns::kRuns runs in all, if it left at most PastRuns::kMostLeft (on the
  // bundled motor, a run that left more was never brought to none within four runs).
  // A run that brings every node back is the result if it leaves fewer tets above the
  // size. Either way no node is past both when the priority order starts, and a
  // collapse raises no node's valence but the one it makes, which stays within tau_VL.
  //
  // The choice is made on whole runs, so that a run stopped at an element count is
  // the chosen run stopped there: with params.target_elements, the runs that choose
  // go to the end, and the chosen one is made again with the target.
  if (!params.subdivide || !params.subdivide_past_valence)  // one run, nothing to choose
    return run_engine(input, params, false, progress, cancel, patches, result);
  SimplifyParams whole = params;
  whole.target_elements = 0;
  // A run past the valence may subdivide into at most params.past_valence_tets_factor
  // times the tets of the first run's subdivision.
  const auto max_tets_for = [&params](size_t first_tets) {
    return static_cast<size_t>(
        std::min<double>(kMaxTets, double(params.past_valence_tets_factor) * double(first_tets)));
  };
  // The runs past the valence start on a thread of their own as soon as the first
  // run's subdivision shows they may be needed: tets above the size (which collapses
  // never make) and a split refused for a node's valence. Their result does not depend
  // on when they start, so the outcome is the same as one run after the other.
  PastRunsAlongside alongside;
  std::function<void(size_t, size_t)> after_subdivide;
  ProgressCallback first_progress = progress;  // with where the other runs are
  if (params.past_valence_alongside && std::thread::hardware_concurrency() >= 2) {
    after_subdivide = [&](size_t tets, size_t above_size) {
      if (above_size > 0) alongside.start(input, whole, patches, max_tets_for(tets));
    };
    if (progress) {
      first_progress = [&](const SimplifyProgress& p) {
        SimplifyProgress with_other = p;
        alongside.where(&with_other);
        progress(with_other);
      };
    }
  }
  s = run_engine(input, whole, false, first_progress, cancel, patches, result, nullptr, kMaxTets,
                 after_subdivide);
  if (!s || result->cancelled || result->violations.above_size == 0 ||
      result->splits_skipped_valence == 0) {
    alongside.stop_and_join();
    if (s && !result->cancelled && params.target_elements > 0)
      s = run_engine(input, params, false, progress, cancel, patches, result);
    return s;
  }
  PastValence p;
  p.tried = true;
  p.alongside = alongside.started();
  p.above_size_within = result->violations.above_size;
  const size_t max_tets = max_tets_for(result->base.tet_count());
  PastRuns sequential;
  if (!alongside.started()) sequential.make(input, whole, progress, cancel, patches, max_tets);
  PastRuns& runs = alongside.started() ? alongside.finish(progress, cancel) : sequential;
  SimplifyResult& past = runs.last;
  p.runs = runs.runs;
  p.pinned = runs.pinned_in_last;
  p.nodes = past.nodes_past_valence;
  p.red_levels = past.red_levels;
  p.red_splits = past.red_splits;
  p.hot_splits = past.hot_splits;
  p.nodes_left = past.nodes_left_past_valence;
  if (!runs.status || past.cancelled) {  // the first result stands, cancelled if the other was
    p.stopped = true;
    p.stopped_why = runs.status.message();
    p.stopped_by_factor = past.over_tets_factor;
    p.seconds_other = runs.seconds_before_last + run_seconds(past);
    result->cancelled = past.cancelled;
    result->past_valence = p;
    return s;
  }
  if (p.nodes_left == 0) p.above_size_past = past.violations.above_size;
  p.taken = p.nodes_left == 0 && p.above_size_past < p.above_size_within;
  p.seconds_other = runs.seconds_before_last + run_seconds(p.taken ? *result : past);
  if (p.taken) *result = std::move(past);
  if (params.target_elements > 0)
    s = run_engine(input, params, p.taken, progress, cancel, patches, result,
                   p.taken ? &runs.pinned : nullptr, p.taken ? max_tets : kMaxTets);
  result->past_valence = p;
  return s;
}

// The sizing rules of `sizing` moved by -shift (a size map is made again over its
// mesh moved so); `sizing` itself is shared, never changed.
Status shifted_sizing(const SizingField& sizing, const Vec3& shift, SizingField* out) {
  *out = sizing;
  for (SizingField::Radial& r : out->radial) r.center = r.center - shift;
  for (SizingField::Box& b : out->boxes) {
    b.low = b.low - shift;
    b.high = b.high - shift;
  }
  if (!sizing.map) return Status();
  TetMesh source = sizing.map->source();
  for (Vec3& p : source.positions) p = p - shift;
  std::shared_ptr<const SizeMap> map;
  const Status s = SizeMap::build(source, sizing.map->sizes(), &map);
  out->map = map;
  return s;
}

}  // namespace

Status simplify(const TetMesh& input, const SimplifyParams& params, SimplifyResult* result,
                const ProgressCallback& progress, const std::atomic<bool>* cancel,
                const SurfacePatches* patches) {
  Status s = check_params(params);
  if (!s) return s;
  // A mesh far from the origin is simplified where its coordinates keep their
  // precision, round it (far_shift()), and moved back. There the quadric error's
  // expanded form cancels to about 1e-16 |p|^2 (a part 1e7 away passed every tolerance
  // test), and a run past the valence that brings every node back at the origin gave up
  // at 1e6 (the motor at size 10 left 5,416 tets above the size at 1e7, none at the
  // origin).
  const Vec3 shift = far_shift(input);
  if (shift == Vec3{})
    return simplify_near_origin(input, params, result, progress, cancel, patches);
  TetMesh local = input;
  for (Vec3& p : local.positions) p = p - shift;
  SimplifyParams local_params = params;
  if (s = shifted_sizing(params.sizing, shift, &local_params.sizing); !s) return s;
  std::optional<SurfacePatches> local_patches;
  if (patches) {
    std::vector<SurfacePatches::Entry> entries = patches->entries();
    entries.insert(entries.end(), patches->inside_entries().begin(),
                   patches->inside_entries().end());
    for (SurfacePatches::Entry& e : entries)
      for (Vec3& p : e.p) p = p - shift;
    local_patches.emplace(patches->groups(), std::move(entries));
  }
  s = simplify_near_origin(local, local_params, result, progress, cancel,
                           local_patches ? &*local_patches : nullptr);
  for (TetMesh* mesh : {&result->base, &result->output})
    for (Vec3& p : mesh->positions) p = p + shift;
  for (CollapseHistory::Step& step : result->history.steps) {
    step.old_position = step.old_position + shift;
    step.new_position = step.new_position + shift;
  }
  return s;
}

// A tet above the size has an edge longer than the size, so longer than half of it:
// collapses never make one, so subdivision did not split it (it was off, stopped, or
// refused the split).
std::string above_size_reason(const SimplifyParams& params, const SimplifyResult& result) {
  if (!params.subdivide)
    return "subdivision was off, so the input's tets larger than the size stay unless a valid "
           "collapse removes them.";
  if (result.cancelled && result.history.step_count() == 0)
    return "the run was cancelled before any collapse: subdivision may not have split every "
           "long edge.";
  const std::string inside =
      result.splits_skipped_inside == 0
          ? std::string()
          : std::to_string(result.splits_skipped_inside) +
                (result.splits_skipped_inside == 1 ? " edge longer than half the size is an edge"
                                                   : " edges longer than half the size are edges") +
                " of the input's surface groups inside a material, which are kept as they "
                "are, so not split";
  if (result.splits_skipped == 0)  // else not expected: every long edge was split
    return inside.empty() ? "subdivision split every long edge it found."
                          : "these tets hold edges subdivision left unsplit: " + inside + ".";
  const size_t valence = result.splits_skipped_valence;
  const size_t shape = result.splits_skipped - valence;
  const bool both = shape > 0 && valence > 0;
  std::string why =
      "these tets hold edges longer than half the size that subdivision left unsplit (" +
      std::to_string(result.splits_skipped) + " such edges in the mesh): splitting ";
  if (shape > 0)
    why += (both ? std::to_string(shape) + " of them" : std::string("them")) +
           " would have made a piece flatter than the stretch threshold (or than its parent) "
           "or larger than its own size";
  if (both) why += ", and ";
  if (valence > 0)
    why += (both ? std::to_string(valence) : std::string("them")) +
           " would have raised a node's valence above the valence threshold";
  why += ". A finer input mesh";
  if (shape > 0)
    why += valence > 0 ? ", a lower stretch threshold" : " or a lower stretch threshold";
  if (valence > 0) why += " or a higher valence threshold";
  why += " leaves fewer.";
  if (!inside.empty()) why += " Besides, " + inside + ".";
  return why;
}

std::string past_valence_summary(const SimplifyResult& result) {
  const PastValence& p = result.past_valence;
  if (!p.tried) return "";
  const std::string within = "subdivision within the valence threshold left " +
                             std::to_string(p.above_size_within) + " tets above the size; ";
  std::string did;  // what the last run's subdivision did
  if (p.hot_splits > 0)
    did = "bisected " + std::to_string(p.hot_splits) +
          (p.hot_splits == 1 ? " edge whose red split" : " edges whose red split") +
          " would have given the midpoint more neighbours than the threshold";
  if (p.red_levels > 0)
    did += (did.empty() ? "" : ", then ") + std::string("split ") + std::to_string(p.red_splits) +
           " edges in " + std::to_string(p.red_levels) +
           (p.red_levels == 1 ? " red level" : " red levels") + " (Bey's 1:8 refinement)";
  // (It may take nodes past the threshold: "took N" if it did.)
  const std::string subdivision = p.nodes > 0
                                      ? (did.empty() ? "" : did + " and ") + "took " +
                                            std::to_string(p.nodes) + " nodes past the threshold"
                                      : (did.empty() ? std::string("was allowed past the threshold")
                                                     : did + ", allowed past the threshold,");
  const bool comma = subdivision.back() == ',';
  const std::string past =
      p.runs == 1 ? "a run whose subdivision " + subdivision + " "
                  : std::to_string(p.runs) +
                        " runs, each but the first with the nodes the one before could not bring "
                        "back kept within the threshold; the last one's subdivision " +
                        subdivision + (comma ? " and it " : ", and it ");
  if (p.stopped)
    return within + past + "stopped before its end" +
           (p.stopped_why.empty() ? std::string() : ": " + p.stopped_why);
  if (p.nodes_left > 0)
    return within + past + (p.runs == 1 ? "was given up: " : "was given up as the others: ") +
           std::to_string(p.nodes_left) + (p.nodes_left == 1 ? " node" : " nodes") +
           " could not be brought back" +
           (p.runs == PastRuns::kRuns
                ? " (the last of " + std::to_string(PastRuns::kRuns) + " runs)"
            : p.nodes_left > PastRuns::kMostLeft
                ? " (more than " + std::to_string(PastRuns::kMostLeft) +
                      ": a run that leaves so many is not made again)"
                : std::string());
  const std::string back =
      p.nodes == 0 ? std::string()
      : p.taken    ? "brought them all back by " + std::to_string(result.valence_edge_removals) +
                      " edge removals and " + std::to_string(result.valence_collapses) +
                      " collapses (the history's first) and "
                : std::string("brought them all back but ");
  return within + past + back + "left " + std::to_string(p.above_size_past) +
         (p.taken ? ", so it is the result" : ", not fewer, so the first run is the result");
}

}  // namespace tetlod
