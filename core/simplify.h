// Property-controlled simplification of a multi-material tet mesh (Date et al.,
// sections II and IV): subdivide every edge longer than half its target size, then
// collapse edges (i, j) -> k in order of the priority index while every threshold
// holds.
//
// The guarantee: no collapse and no split ever creates a tet with stretch below
// tau_ST or size above tau_SZ, no collapse a node with valence above tau_VL, and
// every material region, interface, junction curve and corner keeps its topology.
// Where subdivision may take a node past tau_VL (see simplify()), edge removals and
// the history's first collapses bring it back before the priority order starts, or
// that run is given up: the levels from there on, the final mesh among them, have no
// node past tau_VL that the input did not have. Nor does
// any collapse make tets of one body overlap (find_overlap(), overlap.h) where they
// did not: the outer boundary is never pushed through itself, nor one body meshed
// apart into another.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "core/lod.h"
#include "core/sizing.h"
#include "core/status.h"
#include "core/tet_mesh.h"

namespace tetlod {

class SurfacePatches;  // surface.h

struct SimplifyParams {
  double tolerance = 0.1;     // tau_TL: a length in model units; the quadric error of eq. (1),
                              // a sum of squared distances, must stay <= tau_TL^2
  double min_stretch = 0.15;  // tau_ST, in (0, 1)
  uint32_t max_valence = 25;  // tau_VL, >= 4
  SizingField sizing;         // tau_SZ per tet (see sizing.h); must set some limit
  bool subdivide = true;
  // Where the run leaves tets above the size, a second run whose subdivision (red
  // levels, then bisection) may take nodes past tau_VL, for edge removals and
  // collapses to bring back before the priority order starts (see simplify()); off:
  // never.
  bool subdivide_past_valence = true;
  // The most tets such a run may subdivide into, as a multiple of the first run's
  // subdivided tets (>= 1); past it, that run is stopped and the first stands. On the
  // bundled motor at size 6 it takes 5.1; a unit box at size 0.03 would take far more
  // (without this bound it ran for over 5 minutes in over 7 GB).
  uint32_t past_valence_tets_factor = 8;
  // Make that run on a second thread while the first collapses, once the first run's
  // subdivision leaves tets above the size (where there are two processors). The
  // result is the same; only the time to it is shorter. Off: one run after the other.
  bool past_valence_alongside = true;
  size_t target_elements = 0;          // stop once at most this many tets remain; 0: run to the end
  double crease_angle_degrees = 40.0;  // for the vertex classification (classify.h)
  // Refuse collapses that would push the outer boundary through itself (see
  // RejectionCounts::overlap). Off only to show, in tests and benchmarks, what it stops.
  bool keep_boundary_embedded = true;
  // The most entries of the outer faces' grid that one such check reads (a hostile mesh
  // may crowd thousands of faces near a collapse): past it, the collapse is refused.
  size_t boundary_guard_budget = size_t{1} << 16;
};

// The largest valence threshold taken. Analysis meshes have nodes of 20 to 60
// neighbours; the work of a collapse grows with its nodes' neighbours, and a threshold
// that lets nodes of many hundreds collapse made runs of minutes on a 1,000-tet input
// (a fan of thin tets round one edge, its ends of valence 1,002, at 1,500; 600 tets at
// 1,000). At this one such fans take seconds at most.
constexpr uint32_t kMaxValence = 255;

// The smallest stretch threshold taken. A tet of stretch d holds a ball of radius
// d·s/(2√6) (s its longest edge), so its volume is at least the regular tet's round
// that ball, d³·s³/(6√2): from this d on, every tet within the threshold has six times
// its volume above kFlatVolume6·s³ (metrics.h), more than validate_mesh() (every
// reader) takes as not flat, so a mesh TetLOD writes always reads back. (Below it, tets
// thin enough to be lost in rounding would pass; an analysis wants stretches of 0.1
// and more anyway. Subdivision's pieces of input tets already below it must read back
// too: reads_back(), metrics.h.)
constexpr double kMinStretch = 1.2e-4;

// Checks thresholds for absurd values (NaN, negative, stretch >= 1 or < kMinStretch,
// valence < 4 or > kMaxValence, no size limit at all) and names the offending one.
Status check_params(const SimplifyParams& params);

// Why candidate collapses were rejected (each evaluation counts its first failure).
struct RejectionCounts {
  uint64_t tolerance = 0;
  uint64_t stretch = 0;  // includes inverted and flat tets
  uint64_t size = 0;
  uint64_t valence = 0;
  uint64_t topology = 0;  // feature rules and link conditions
  // The outer boundary would cross itself or wrap round one of its edges: tets would
  // overlap with no face between them (two sheets nearer than the tolerance, as across
  // a thin gap); or a body's faces would cross those of another body meshed apart,
  // where they did not; or they would sweep past a whole small body or cavity, which
  // the new tets would then hold. Checked on the collapses about to be made, after the
  // others.
  uint64_t overlap = 0;
};

// How many collapse evaluations each part of the run made, valid or rejected (an
// evaluation walks the stars of both ends: the bulk of the simplify phase's time).
struct EvaluationCounts {
  uint64_t initial = 0;   // every edge of the subdivided mesh, once, at the start
  uint64_t new_node = 0;  // the edges of the node each collapse made, right after it
  uint64_t stale = 0;     // queued collapses popped after a neighbouring collapse
  uint64_t sweep = 0;     // the edges of the nodes collapses touched, when the queue ran dry
  uint64_t sweeps = 0;    // how many times the queue ran dry with such nodes left
  uint64_t valence = 0;   // of edges in the links of nodes subdivision took past tau_VL
  uint64_t repeated = 0;  // not made again (stale entries, sweeps): the same evaluation was
                          // already made on the mesh as it is, so its result is known
  uint64_t total() const { return initial + new_node + stale + sweep + valence; }
};

// Output tets and nodes that break a threshold. Only what the input already broke
// can: an input tet no valid collapse could remove, or a piece that subdivision cut
// from such a tet (a piece never has a lower stretch than its parent, and is
// smaller), or an input node whose valence no collapse lowered enough. `created`
// counts anything else and must be 0.
struct ThresholdViolations {
  size_t below_stretch = 0;  // tets with d_t < tau_ST
  size_t above_size = 0;     // tets with s_t > tau_SZ
  size_t above_valence = 0;  // nodes with valence > tau_VL
  size_t created = 0;        // of the above, ones the input did not already break
};

// The runs of simplify() (see there) whose subdivision may take nodes past tau_VL.
struct PastValence {
  bool tried = false;
  bool taken = false;       // the last such run is the result
  bool stopped = false;     // cancelled, or an error (more tets than allowed, say)
  std::string stopped_why;  // the error, if one stopped it
  // The error: its subdivision passed SimplifyParams::past_valence_tets_factor times
  // the first run's tets.
  bool stopped_by_factor = false;
  int runs = 0;           // made, each with the nodes the one before left pinned
  size_t pinned = 0;      // nodes pinned in the last
  size_t nodes = 0;       // nodes the last took past both tau_VL and their input valence
  size_t nodes_left = 0;  // of them, not brought back: it was given up
  size_t red_levels = 0;  // red levels of the last, and edges they split
  size_t red_splits = 0;
  size_t hot_splits = 0;         // edges the last bisected before its red levels
  size_t above_size_within = 0;  // tets above the size the first run left
  size_t above_size_past = 0;    // and the last run past the valence (if not given up)
  double seconds_other = 0;      // the runs that are not the result
  // Made on a second thread while the first run collapsed (SimplifyParams::
  // past_valence_alongside), so seconds_other overlaps the result's seconds.
  bool alongside = false;
};

struct SimplifyResult {
  TetMesh base;             // LOD step 0: the input after subdivision
  CollapseHistory history;  // every collapse, in order
  TetMesh output;           // the mesh after the last collapse, compacted
  RejectionCounts rejections;
  EvaluationCounts evaluations;
  ThresholdViolations violations;
  size_t splits = 0;          // subdivision splits done
  size_t splits_skipped = 0;  // long edges left unsplit because a split would break a threshold:
  size_t splits_skipped_valence = 0;  // of them, those only a node's valence stopped (the
                                      // others: a piece's stretch or size)
  // Subdivision past tau_VL (see simplify()): splits that took a node past it (and the
  // nodes a red level took past it, as a level splits many edges at once); nodes
  // then past both tau_VL and their input valence; the edge removals, then collapses
  // (the history's first), that brought them back; nodes left past both (0 in a result
  // simplify() returns, unless cancelled).
  size_t splits_past_valence = 0;
  size_t nodes_past_valence = 0;
  size_t valence_edge_removals = 0;
  size_t valence_collapses = 0;
  size_t nodes_left_past_valence = 0;
  // Red levels of a run past tau_VL (see simplify()): levels made, edges they split
  // (in `splits` too), and tets they cut from their centroid; and the edges bisected
  // before them (in `splits` too), whose red split would have given their midpoint
  // more neighbours than tau_VL.
  size_t red_levels = 0;
  size_t red_splits = 0;
  size_t red_centroids = 0;
  size_t hot_splits = 0;
  PastValence past_valence;
  // Long edges left unsplit (not in splits_skipped) because they are edges of an input
  // surface group's triangles inside a material, which the run keeps as they are.
  size_t splits_skipped_inside = 0;
  // Subdivision stopped (an error) at the tets a run past the valence may make
  // (SimplifyParams::past_valence_tets_factor times the first run's).
  bool over_tets_factor = false;
  bool cancelled = false;
  // The candidate tests' kernels: "avx2" or "baseline" (also where the environment
  // sets TETLOD_NO_AVX2). Both give the same result, bit for bit.
  const char* kernels = "";
  double seconds_classify = 0, seconds_subdivide = 0, seconds_simplify = 0;
};

struct SimplifyProgress {
  // "subdivide", "classify", "evaluate edges" (the first evaluation of every edge,
  // before the first collapse), "simplify"; in a run past the valence (SimplifyResult::
  // past_valence) also "red levels" before "subdivide", "edge removals" after it, and
  // "valence collapses" before "evaluate edges" where nodes are still past the valence.
  const char* phase = "";
  double fraction = 0;  // of the phase, in [0, 1]; an estimate for "simplify"
  size_t collapses = 0;
  bool past_valence = false;  // a run past the valence (after the first run's phases)
  // While the first run's phases are reported and a run past the valence is made at the
  // same time on a second thread (SimplifyParams::past_valence_alongside): where that
  // run is, its phase ("starting" before its first report, "done" once it has ended)
  // and the fraction of it; nullptr when no such run is being made.
  const char* other_phase = nullptr;
  double other_fraction = 0;
};
using ProgressCallback = std::function<void(const SimplifyProgress&)>;

// Runs the pipeline on a validated mesh. `progress` is called from the calling
// thread every few thousand operations; `cancel`, if set, stops the run at the next
// check and leaves a consistent result (result->cancelled). Same input and params
// give the same result, byte for byte. No globals: runs may proceed in parallel.
// `patches`, if given: the input file's surface groups (surface.h); their borders
// are then kept as curves, as those between material pairs are, so that every level
// can be grouped as the input was (group_surface() with them). Their triangles inside
// a material (inside_faces()) are kept as they are, in every level: subdivision does
// not split their edges, and their corners are corners, which no collapse moves or
// removes.
Status simplify(const TetMesh& input, const SimplifyParams& params, SimplifyResult* result,
                const ProgressCallback& progress = {}, const std::atomic<bool>* cancel = nullptr,
                const SurfacePatches* patches = nullptr);

// Why a result's final mesh still has tets above the size (violations.above_size > 0),
// for the user: what stopped subdivision and what would let it reach the size.
std::string above_size_reason(const SimplifyParams& params, const SimplifyResult& result);

// What subdivision past tau_VL did, in a sentence for the user; "" if it took no node
// past it.
std::string past_valence_summary(const SimplifyResult& result);

}  // namespace tetlod
