#include "core/adjacency.h"

#include <algorithm>
#include <cassert>

namespace tetlod {

VertexTets build_vertex_tets(const TetMesh& mesh) {
  VertexTets vt;
  const size_t vertex_count = mesh.vertex_count();
  vt.offsets.assign(vertex_count + 1, 0);
  for (const Tet& t : mesh.tets)
    for (uint32_t v : t) ++vt.offsets[v + 1];
  for (size_t v = 0; v < vertex_count; ++v) vt.offsets[v + 1] += vt.offsets[v];
  vt.tets.resize(vt.offsets[vertex_count]);
  std::vector<uint32_t> cursor(vt.offsets.begin(), vt.offsets.end() - 1);
  for (uint32_t t = 0; t < mesh.tet_count(); ++t)
    for (uint32_t v : mesh.tets[t]) vt.tets[cursor[v]++] = t;
  return vt;
}

namespace {

// A tet face keyed by its two larger vertex ids, stored in the bucket of its smallest.
struct HalfFace {
  uint64_t key;     // (middle id << 32) | largest id
  uint32_t half;    // 4 * tet + corner opposite the face
  uint32_t parity;  // 0 if the outward face, rotated to start at its smallest id, is increasing
};

inline bool face_less(const HalfFace& x, const HalfFace& y) {
  return x.key != y.key ? x.key < y.key : x.half < y.half;
}

}  // namespace

FaceProblem build_face_neighbors(const TetMesh& mesh, std::vector<uint32_t>* neighbors) {
  const size_t vertex_count = mesh.vertex_count();
  const size_t tet_count = mesh.tet_count();
  assert(tet_count < (size_t{1} << 30));
  neighbors->assign(4 * tet_count, kInvalidIndex);

  auto smallest_of_face = [&](const Tet& t, int corner) {
    const int* f = kTetFace[corner];
    return std::min({t[f[0]], t[f[1]], t[f[2]]});
  };

  std::vector<uint32_t> offsets(vertex_count + 1, 0);
  for (const Tet& t : mesh.tets)
    for (int i = 0; i < 4; ++i) ++offsets[smallest_of_face(t, i) + 1];
  for (size_t v = 0; v < vertex_count; ++v) offsets[v + 1] += offsets[v];
  std::vector<HalfFace> faces(offsets[vertex_count]);
  std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
  for (uint32_t ti = 0; ti < tet_count; ++ti) {
    const Tet& t = mesh.tets[ti];
    for (int i = 0; i < 4; ++i) {
      const int* f = kTetFace[i];
      uint32_t p = t[f[0]], q = t[f[1]], r = t[f[2]];
      // Rotate (an even permutation) so that p is the smallest.
      while (p > q || p > r) {
        const uint32_t tmp = p;
        p = q;
        q = r;
        r = tmp;
      }
      HalfFace& h = faces[cursor[p]++];
      h.key = (uint64_t{std::min(q, r)} << 32) | std::max(q, r);
      h.half = 4 * ti + static_cast<uint32_t>(i);
      h.parity = q < r ? 0 : 1;
    }
  }

  for (size_t v = 0; v < vertex_count; ++v) {
    HalfFace* first = faces.data() + offsets[v];
    HalfFace* last = faces.data() + offsets[v + 1];
    if (last - first <= 64) {
      for (HalfFace* a = first + 1; a < last; ++a) {  // insertion sort: buckets are small
        const HalfFace key = *a;
        HalfFace* b = a;
        while (b > first && face_less(key, *(b - 1))) {
          *b = *(b - 1);
          --b;
        }
        *b = key;
      }
    } else {
      std::sort(first, last, [](const HalfFace& x, const HalfFace& y) { return face_less(x, y); });
    }
    for (HalfFace* a = first; a < last;) {
      HalfFace* b = a + 1;
      while (b < last && b->key == a->key) ++b;
      const long run = b - a;
      if (run > 2) return {FaceProblem::Kind::kNonManifold, a[0].half / 4, a[2].half / 4};
      if (run == 2) {
        if (a[0].parity == a[1].parity) {
          return {FaceProblem::Kind::kOverlap, a[0].half / 4, a[1].half / 4};
        }
        (*neighbors)[a[0].half] = a[1].half / 4;
        (*neighbors)[a[1].half] = a[0].half / 4;
      }
      a = b;
    }
  }
  return {};
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
