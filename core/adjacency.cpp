#include "core/adjacency.h"

#include <algorithm>
#include <cassert>

namespace tetlod {

// Speed notes (docs/PERFORMANCE.md, "Core: read, adjacency, metrics"): on large meshes
// these passes are bound by random memory access, because mesh generators number tets
// and vertices with little spatial locality. Every pass below either streams through
// the tets in order or walks vertex buckets in order while prefetching the tets it is
// about to read; no pass scatters wide records over memory.

namespace {

// How far ahead, in tets or bucket entries, the passes prefetch what they will touch.
constexpr uint32_t kPrefetchDistance = 16;

// Counting sort of tets into vertex buckets: `bucket_of(tet, emit)` calls emit(v) for
// each vertex v whose bucket should hold the tet. Each bucket lists its tets in
// increasing order.
template <class BucketOf>
void bucket_tets(const TetMesh& mesh, BucketOf bucket_of, std::vector<uint32_t>* offsets,
                 std::vector<uint32_t>* tets) {
  const size_t vertex_count = mesh.vertex_count();
  offsets->assign(vertex_count + 1, 0);
  uint32_t* count = offsets->data() + 1;
  for (const Tet& t : mesh.tets) bucket_of(t, [&](uint32_t v) { ++count[v]; });
  for (size_t v = 0; v < vertex_count; ++v) (*offsets)[v + 1] += (*offsets)[v];
  tets->resize((*offsets)[vertex_count]);
  std::vector<uint32_t> cursor(offsets->begin(), offsets->end() - 1);
  uint32_t* out = tets->data();
  const uint32_t tet_count = static_cast<uint32_t>(mesh.tet_count());
  for (uint32_t ti = 0; ti < tet_count; ++ti) {
    if (ti + kPrefetchDistance < tet_count) {
      bucket_of(mesh.tets[ti + kPrefetchDistance],
                [&](uint32_t v) { __builtin_prefetch(&out[cursor[v]], 1); });
    }
    bucket_of(mesh.tets[ti], [&](uint32_t v) { out[cursor[v]++] = ti; });
  }
}

// For a tet corner c and a face i != c (the face opposite corner i, which contains
// corner c), the two corners that follow c when the outward face kTetFace[i] is rotated
// to start at c.
struct FaceAfter {
  int corner[4][4][2];
};
constexpr FaceAfter make_face_after() {
  FaceAfter table{};
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int c = kTetFace[i][k];
      table.corner[c][i][0] = kTetFace[i][(k + 1) % 3];
      table.corner[c][i][1] = kTetFace[i][(k + 2) % 3];
    }
  }
  return table;
}
constexpr FaceAfter kFaceAfter = make_face_after();

// A tet face seen from its smallest vertex v: keyed by its two other vertex ids.
struct HalfFace {
  uint64_t key;     // (middle id << 32) | largest id
  uint32_t half;    // 4 * tet + corner opposite the face
  uint32_t parity;  // 0 if the outward face, rotated to start at v, is increasing
};

inline bool face_less(const HalfFace& x, const HalfFace& y) {
  return x.key != y.key ? x.key < y.key : x.half < y.half;
}

// Calls emit(face) for each face of tet `ti` whose smallest vertex is v, a corner of it.
template <class Emit>
inline void faces_from_smallest(const Tet& t, uint32_t ti, uint32_t v, Emit emit) {
  const int c = t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : 3;
  for (int i = 0; i < 4; ++i) {
    if (i == c) continue;
    const uint32_t q = t[kFaceAfter.corner[c][i][0]];
    const uint32_t r = t[kFaceAfter.corner[c][i][1]];
    if (q < v || r < v) continue;  // the face belongs to a smaller vertex's bucket
    emit(HalfFace{(uint64_t{std::min(q, r)} << 32) | std::max(q, r),
                  4 * ti + static_cast<uint32_t>(i), q < r ? 0u : 1u});
  }
}

// Pairs up the faces of one bucket (all faces whose smallest vertex is one vertex) in an
// open-addressing hash table. Slots are tagged with the bucket's generation, so the
// table is emptied for the next bucket by bumping the generation, not by clearing it.
class FaceMatcher {
 public:
  // Prepares an empty table for a bucket of at most `face_count` faces.
  void begin_bucket(size_t face_count) {
    size_t capacity = 64;
    while (capacity < 2 * face_count) capacity *= 2;
    if (slots_.size() < capacity) {
      slots_.assign(capacity, Slot{});
      generation_ = 0;
    }
    mask_ = slots_.size() - 1;
    if (++generation_ == kGenerationLimit) {
      std::fill(slots_.begin(), slots_.end(), Slot{});
      generation_ = 1;
    }
  }

  // Adds a face; when it is the second side of a face already added, writes both tets
  // into `neighbors`. Returns false if the face already has two tets, or one on the same
  // side: the table is then unreliable until the next bucket.
  bool add(const HalfFace& f, uint32_t* neighbors) {
    const uint32_t live = generation_ << 2;
    size_t i = hash(f.key) & mask_;
    while ((slots_[i].tag & ~3u) == live && slots_[i].key != f.key) i = (i + 1) & mask_;
    Slot& s = slots_[i];
    if ((s.tag & ~3u) != live) {
      s = {f.key, f.half, live | f.parity};
      return true;
    }
    const uint32_t state = s.tag & 3u;  // the parity of the face seen, or kPaired
    neighbors[s.half] = f.half / 4;
    neighbors[f.half] = s.half / 4;
    s.tag = live | kPaired;
    return state == (f.parity ^ 1u);
  }

 private:
  static constexpr uint32_t kPaired = 2;
  static constexpr uint32_t kGenerationLimit = 1u << 30;
  struct Slot {
    uint64_t key = 0;
    uint32_t half = 0;
    uint32_t tag = 0;  // generation << 2 | (parity of the one face seen, or kPaired)
  };
  static size_t hash(uint64_t key) {
    return static_cast<size_t>((key * 0x9e3779b97f4a7c15ull) >> 32);
  }
  std::vector<Slot> slots_;
  size_t mask_ = 0;
  uint32_t generation_ = 0;
};

// Reports the problem of one bucket exactly as a sort of its faces by (key, half)
// finds it first: the smallest key with a problem; three tets before two on one side.
FaceProblem bucket_problem(std::vector<HalfFace>* faces) {
  std::sort(faces->begin(), faces->end(), face_less);
  const HalfFace* first = faces->data();
  const HalfFace* last = first + faces->size();
  for (const HalfFace* a = first; a < last;) {
    const HalfFace* b = a + 1;
    while (b < last && b->key == a->key) ++b;
    if (b - a > 2) return {FaceProblem::Kind::kNonManifold, a[0].half / 4, a[2].half / 4};
    if (b - a == 2 && a[0].parity == a[1].parity) {
      return {FaceProblem::Kind::kOverlap, a[0].half / 4, a[1].half / 4};
    }
    a = b;
  }
  assert(false && "FaceMatcher reported a problem the sort does not find");
  return {};
}

// Matches tet faces given, for every vertex v, a bucket of tets that holds every tet
// with a face whose smallest vertex is v (extra tets are skipped). Each face is matched
// in the bucket of its smallest vertex, so buckets are independent and small.
FaceProblem match_faces(const TetMesh& mesh, const std::vector<uint32_t>& offsets,
                        const std::vector<uint32_t>& bucket, std::vector<uint32_t>* neighbors) {
  const size_t vertex_count = mesh.vertex_count();
  assert(mesh.tet_count() < (size_t{1} << 30));
  neighbors->assign(4 * mesh.tet_count(), kInvalidIndex);
  uint32_t* out = neighbors->data();
  const Tet* tets = mesh.tets.data();
  const uint32_t* entries = bucket.data();
  const uint32_t entry_count = offsets[vertex_count];
  FaceMatcher matcher;
  for (uint32_t v = 0; v < vertex_count; ++v) {
    const uint32_t first = offsets[v], last = offsets[v + 1];
    matcher.begin_bucket(3 * size_t{last - first});
    bool ok = true;
    for (uint32_t e = first; e < last; ++e) {
      if (e + kPrefetchDistance < entry_count) {
        const uint32_t ahead = entries[e + kPrefetchDistance];
        __builtin_prefetch(&tets[ahead]);
        __builtin_prefetch(&out[4 * ahead], 1);
      }
      const uint32_t ti = entries[e];
      faces_from_smallest(tets[ti], ti, v, [&](const HalfFace& f) { ok &= matcher.add(f, out); });
    }
    if (!ok) {
      std::vector<HalfFace> faces;
      for (uint32_t e = first; e < last; ++e) {
        faces_from_smallest(tets[entries[e]], entries[e], v,
                            [&](const HalfFace& f) { faces.push_back(f); });
      }
      return bucket_problem(&faces);
    }
  }
  return {};
}

// The bucket of the smallest and of the second smallest vertex of each tet: of the four
// faces of a tet with vertices a < b < c < d, three have smallest vertex a, one b.
void bucket_by_two_smallest(const TetMesh& mesh, std::vector<uint32_t>* offsets,
                            std::vector<uint32_t>* tets) {
  bucket_tets(
      mesh,
      [](const Tet& t, auto emit) {
        const uint32_t lo01 = std::min(t[0], t[1]), hi01 = std::max(t[0], t[1]);
        const uint32_t lo23 = std::min(t[2], t[3]), hi23 = std::max(t[2], t[3]);
        emit(std::min(lo01, lo23));
        emit(std::min(std::max(lo01, lo23), std::min(hi01, hi23)));
      },
      offsets, tets);
}

}  // namespace

VertexTets build_vertex_tets(const TetMesh& mesh) {
  VertexTets vt;
  bucket_tets(
      mesh,
      [](const Tet& t, auto emit) {
        for (uint32_t v : t) emit(v);
      },
      &vt.offsets, &vt.tets);
  return vt;
}

FaceProblem build_face_neighbors(const TetMesh& mesh, std::vector<uint32_t>* neighbors) {
  std::vector<uint32_t> offsets, tets;
  bucket_by_two_smallest(mesh, &offsets, &tets);
  return match_faces(mesh, offsets, tets, neighbors);
}

MeshAdjacency build_adjacency(const TetMesh& mesh) {
  MeshAdjacency adjacency;
  adjacency.vertex_tets = build_vertex_tets(mesh);
  const FaceProblem problem = build_face_neighbors(mesh, &adjacency.tet_neighbors);
  assert(problem.kind == FaceProblem::Kind::kNone);
  (void)problem;
  return adjacency;
}

}  // namespace tetlod
