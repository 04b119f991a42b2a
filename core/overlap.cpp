#include "core/overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/triangle_cross.h"
#include "core/triangle_grid.h"

namespace tetlod {
namespace {

// A face that belongs to one tet, outward (kTetFace): the face opposite `corner`.
struct BoundaryFace {
  uint32_t v[3];
  uint32_t tet;
  int corner;
};

// The solid angle of triangle abc seen from the origin, signed: positive if the
// origin lies behind it (Van Oosterom and Strackee, IEEE Trans. Biomed. Eng. 30(2),
// 1983).
double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = length(a), lb = length(b), lc = length(c);
  const double numerator = dot(a, cross(b, c));
  const double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * std::atan2(numerator, denominator);
}

// Union-find with path halving; the root of a set is its smallest member.
uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

void unite(std::vector<uint32_t>& parent, uint32_t u, uint32_t v) {
  const uint32_t a = find_root(parent, u), b = find_root(parent, v);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

// Sorts (key, value) pairs by key, keeping the order of equal keys: a least
// significant digit radix sort, 11 bits a pass, as many passes as the largest key needs.
void sort_by_key(std::vector<std::pair<uint64_t, uint32_t>>* items) {
  uint64_t bits_used = 0;
  for (const auto& item : *items) bits_used |= item.first;
  std::vector<std::pair<uint64_t, uint32_t>> sorted(items->size());
  constexpr int kDigit = 11;
  constexpr uint64_t kMask = (1u << kDigit) - 1;
  for (int shift = 0; shift < 64 && (bits_used >> shift) != 0; shift += kDigit) {
    std::vector<size_t> start(kMask + 2, 0);
    for (const auto& item : *items) ++start[(item.first >> shift & kMask) + 1];
    for (size_t d = 0; d <= kMask; ++d) start[d + 1] += start[d];
    for (const auto& item : *items) sorted[start[item.first >> shift & kMask]++] = item;
    items->swap(sorted);
  }
}

// Boxes in the cells of a sparse grid: cells about the mean box's size (coarser if a
// few large boxes would fill too many: at most 16 cells a box on average), each box in
// every cell it covers, listed by sorting (cell, box) keys. For the pairs of boxes that
// overlap, and the boxes that hold a point.
class BoxGrid {
 public:
  BoxGrid(std::vector<Vec3> lo, std::vector<Vec3> hi) : lo_(std::move(lo)), hi_(std::move(hi)) {
    const size_t count = lo_.size();
    if (count == 0) return;
    all_lo_ = lo_[0];
    Vec3 all_hi = hi_[0];
    double extent_sum = 0;
    for (size_t i = 0; i < count; ++i) {
      double extent = 0;
      for (int k = 0; k < 3; ++k) {
        all_lo_[k] = std::min(all_lo_[k], lo_[i][k]);
        all_hi[k] = std::max(all_hi[k], hi_[i][k]);
        extent = std::max(extent, hi_[i][k] - lo_[i][k]);
      }
      extent_sum += extent;
    }
    cell_ = std::max(extent_sum / double(count), 1e-300);
    for (int k = 0; k < 3; ++k) cell_ = std::max(cell_, (all_hi[k] - all_lo_[k]) / (kMaxCells - 1));
    uint64_t from[3], to[3];
    for (;;) {
      double entries = 0;
      for (size_t i = 0; i < count; ++i) entries += double(cells_of(i, from, to));
      if (entries <= 16.0 * double(count) + 1024 || !std::isfinite(cell_)) break;
      cell_ *= 2;
    }
    // Keys: x, then y, then z, in as few bits as the grid needs (fewer sort passes).
    const auto bits_for = [](uint64_t n) {
      int bits = 1;
      while ((uint64_t{1} << bits) <= n) ++bits;
      return bits;
    };
    shift_y_ = bits_for(index(all_hi[0], 0));
    shift_z_ = shift_y_ + bits_for(index(all_hi[1], 1));
    first_cell_.resize(count);
    for (size_t i = 0; i < count; ++i) {
      cells_of(i, from, to);
      for (int k = 0; k < 3; ++k) first_cell_[i][k] = static_cast<uint32_t>(from[k]);
      for (uint64_t z = from[2]; z <= to[2]; ++z)
        for (uint64_t y = from[1]; y <= to[1]; ++y)
          for (uint64_t x = from[0]; x <= to[0]; ++x)
            keys_.push_back({key(x, y, z), static_cast<uint32_t>(i)});
    }
    sort_by_key(&keys_);  // (cell, box): boxes in order within a cell
  }

  // Calls visit(i, j), with i < j, once for each pair of boxes that overlap (closed
  // boxes), in the first cell they share, until it returns false. Every pair that shares
  // a cell counts against `pair_budget`; returns false if it ran out.
  template <class Visit>
  bool for_each_overlapping_pair(size_t pair_budget, Visit visit) const {
    // Each cell's boxes are copied together first: the pairs then read them from cache.
    struct Box {
      Vec3 lo, hi;
      std::array<uint32_t, 3> first_cell;
      uint32_t index;
    };
    std::vector<Box> boxes;
    size_t pairs = 0;
    for (size_t begin = 0, end = 0; begin < keys_.size(); begin = end) {
      const uint64_t key = keys_[begin].first;
      while (end < keys_.size() && keys_[end].first == key) ++end;
      pairs += (end - begin) * (end - begin - 1) / 2;
      if (pairs > pair_budget) return false;
      const uint32_t here[3] = {
          uint32_t(key & ((uint64_t{1} << shift_y_) - 1)),
          uint32_t(key >> shift_y_ & ((uint64_t{1} << (shift_z_ - shift_y_)) - 1)),
          uint32_t(key >> shift_z_)};
      boxes.clear();
      for (size_t e = begin; e < end; ++e) {
        const uint32_t i = keys_[e].second;
        boxes.push_back({lo_[i], hi_[i], first_cell_[i], i});
      }
      for (size_t a = 0; a < boxes.size(); ++a) {
        const Box& s = boxes[a];
        for (size_t b = a + 1; b < boxes.size(); ++b) {
          const Box& t = boxes[b];  // t.index > s.index
          // The first cell both boxes cover is this one (the cell index is monotone).
          bool visit_here = true;
          for (int k = 0; k < 3; ++k) {
            visit_here &= s.lo[k] <= t.hi[k] && t.lo[k] <= s.hi[k];
            visit_here &= std::max(s.first_cell[k], t.first_cell[k]) == here[k];
          }
          if (visit_here && !visit(s.index, t.index)) return true;
        }
      }
    }
    return true;
  }

  // Calls visit(i) for each box i that holds p (closed boxes), in increasing order of i.
  template <class Visit>
  void for_each_holding(const Vec3& p, Visit visit) const {
    if (keys_.empty()) return;
    const uint64_t at = key(index(p.x, 0), index(p.y, 1), index(p.z, 2));
    auto it = std::lower_bound(keys_.begin(), keys_.end(), std::make_pair(at, uint32_t{0}));
    for (; it != keys_.end() && it->first == at; ++it) {
      const Vec3 &lo = lo_[it->second], &hi = hi_[it->second];
      if (lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z)
        visit(it->second);
    }
  }

 private:
  static constexpr double kMaxCells = 1 << 20;  // along an axis

  uint64_t index(double x, int k) const {
    const double f = std::floor((x - all_lo_[k]) / cell_);
    return f >= 0 ? (f < kMaxCells - 1 ? uint64_t(f) : uint64_t(kMaxCells - 1)) : uint64_t{0};
  }
  uint64_t key(uint64_t x, uint64_t y, uint64_t z) const {
    return x | y << shift_y_ | z << shift_z_;
  }
  uint64_t cells_of(size_t i, uint64_t* from, uint64_t* to) const {
    uint64_t n = 1;
    for (int k = 0; k < 3; ++k) {
      from[k] = index(lo_[i][k], k);
      to[k] = index(hi_[i][k], k);
      n *= to[k] - from[k] + 1;
    }
    return n;
  }

  std::vector<Vec3> lo_, hi_;
  Vec3 all_lo_;
  double cell_ = 1;
  int shift_y_ = 1, shift_z_ = 2;
  std::vector<std::array<uint32_t, 3>> first_cell_;
  std::vector<std::pair<uint64_t, uint32_t>> keys_;
};

// The bounding boxes of triangles.
BoxGrid grid_of_triangles(const std::vector<Triangle3>& triangles) {
  std::vector<Vec3> lo(triangles.size()), hi(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Triangle3& t = triangles[i];
    for (int k = 0; k < 3; ++k) {
      lo[i][k] = std::min({t[0][k], t[1][k], t[2][k]});
      hi[i][k] = std::max({t[0][k], t[1][k], t[2][k]});
    }
  }
  return BoxGrid(std::move(lo), std::move(hi));
}

// Whether the tets around boundary edge (a, b) fill more than a full turn there, summing
// their dihedral angles at the edge from boundary face f to the other boundary face
// (they then wrap round the edge and overlap): the first tet that takes the sum past a
// full turn, else kInvalidIndex. `*steps` counts the tets; the walk stops at
// `max_steps`.
uint32_t tet_past_a_turn(const TetMesh& mesh, const std::vector<uint32_t>& neighbors,
                         const BoundaryFace& f, uint32_t a, uint32_t b, size_t max_steps,
                         size_t* steps) {
  const std::vector<Vec3>& pos = mesh.positions;
  const Vec3 &pa = pos[a], edge = pos[b] - pos[a];
  uint32_t t = f.tet;
  int came = f.corner;  // the corner opposite the face the walk came in through
  double sum = 0;
  while (*steps < max_steps) {
    ++*steps;
    const Tet& q = mesh.tets[t];
    int other[2], n = 0;
    for (int k = 0; k < 4; ++k)
      if (q[k] != a && q[k] != b && n < 2) other[n++] = k;
    const Vec3 n1 = cross(edge, pos[q[other[0]]] - pa), n2 = cross(edge, pos[q[other[1]]] - pa);
    sum += std::atan2(length(cross(n1, n2)), dot(n1, n2));
    if (sum > 2 * M_PI * (1 + 1e-9)) return t;
    const int out = other[0] == came ? other[1] : other[0];
    const uint32_t next = neighbors[4 * size_t{t} + out];
    if (next == kInvalidIndex) break;  // the other boundary face
    const uint32_t shared = q[came];   // the face left through is (a, b, shared)
    const Tet& r = mesh.tets[next];
    came = 0;
    while (r[came] == a || r[came] == b || r[came] == shared) ++came;
    t = next;
  }
  return kInvalidIndex;
}

// Pieces: tets joined through shared vertices, numbered in the order of their first
// tet; piece_of[t] is the piece of tet t. Returns the first tet of each piece.
std::vector<uint32_t> number_pieces(const TetMesh& mesh, std::vector<uint32_t>* piece_of) {
  const std::vector<uint32_t> root = vertex_pieces(mesh);
  std::vector<uint32_t> piece_of_root(root.size(), kInvalidIndex), first_tet;
  piece_of->resize(mesh.tets.size());
  for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
    uint32_t& p = piece_of_root[root[mesh.tets[t][0]]];
    if (p == kInvalidIndex) {
      p = static_cast<uint32_t>(first_tet.size());
      first_tet.push_back(t);
    }
    (*piece_of)[t] = p;
  }
  return first_tet;
}

// Boundary faces in groups (surfaces, pieces): the faces of each group and its box.
struct FaceGroups {
  std::vector<uint32_t> start, faces;  // faces[start[g] .. start[g + 1]) are group g's
  std::vector<Vec3> lo, hi;

  FaceGroups(const std::vector<BoundaryFace>& all, const std::vector<uint32_t>& group_of,
             size_t group_count, const std::vector<Vec3>& pos)
      : start(group_count + 1, 0),
        faces(all.size()),
        lo(group_count, Vec3{INFINITY, INFINITY, INFINITY}),
        hi(group_count, Vec3{-INFINITY, -INFINITY, -INFINITY}) {
    for (uint32_t g : group_of) ++start[g + 1];
    for (size_t g = 0; g < group_count; ++g) start[g + 1] += start[g];
    std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
    for (uint32_t f = 0; f < all.size(); ++f) {
      const uint32_t g = group_of[f];
      faces[cursor[g]++] = f;
      for (uint32_t v : all[f].v) {
        for (int k = 0; k < 3; ++k) {
          lo[g][k] = std::min(lo[g][k], pos[v][k]);
          hi[g][k] = std::max(hi[g][k], pos[v][k]);
        }
      }
    }
  }
  size_t size(size_t g) const { return start[g + 1] - start[g]; }
  // How many times group g's faces wind around p: the sum of their solid angles over
  // 4 pi (the generalised winding number; an integer for a closed surface).
  double winding(size_t g, const Vec3& p, const std::vector<BoundaryFace>& all,
                 const std::vector<Vec3>& pos) const {
    double angle = 0;
    for (uint32_t n = start[g]; n < start[g + 1]; ++n) {
      const BoundaryFace& f = all[faces[n]];
      angle += solid_angle(pos[f.v[0]] - p, pos[f.v[1]] - p, pos[f.v[2]] - p);
    }
    return angle / (4 * M_PI);
  }
};

// A tet other than `except` that holds p, the deepest inside if several do (by the
// smallest of p's four barycentric coordinates); `except` if none holds it.
uint32_t tet_holding(const TetMesh& mesh, const Vec3& p, uint32_t except) {
  uint32_t best = except;
  double best_depth = 0;
  const std::vector<Vec3>& pos = mesh.positions;
  for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
    if (t == except) continue;
    const Tet& q = mesh.tets[t];
    const Vec3 &a = pos[q[0]], &b = pos[q[1]], &c = pos[q[2]], &d = pos[q[3]];
    const double whole = signed_volume6(a, b, c, d);
    const double depth = std::min({signed_volume6(p, b, c, d), signed_volume6(a, p, c, d),
                                   signed_volume6(a, b, p, d), signed_volume6(a, b, c, p)}) /
                         whole;
    if (depth > best_depth) best_depth = depth, best = t;
  }
  return best;
}

// find_overlap()'s checks, in turn, on one mesh: each returns true when the search is
// over (something found, or a budget spent), with the result in found_.
class OverlapSearch {
 public:
  OverlapSearch(const TetMesh& mesh, const std::vector<uint32_t>& neighbors)
      : mesh_(mesh), neighbors_(neighbors), pos_(mesh.positions) {
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
      for (int c = 0; c < 4; ++c) {
        if (neighbors[4 * size_t{t} + c] != kInvalidIndex) continue;
        const Tet& q = mesh.tets[t];
        faces_.push_back({{q[kTetFace[c][0]], q[kTetFace[c][1]], q[kTetFace[c][2]]}, t, c});
      }
    }
    // Budgets: pairs of faces that share a cell, tets passed round boundary edges (a
    // boundary edge has about three), and solid angles (about 100 ns each).
    pair_budget_ = 64 * faces_.size() + (size_t{1} << 22);
    walk_budget_ = 32 * faces_.size() + (size_t{1} << 20);
    winding_budget_ = 8 * faces_.size() + (size_t{1} << 20);
    number_surfaces();
    // Pieces are vertex-disjoint and each has a surface of its own: with one surface
    // the mesh is one piece, and its tets are not numbered.
    if (first_face_.size() > 1) first_tet_ = number_pieces(mesh, &piece_);
  }

  OverlapFinding run() {
    if (crossing_within_a_piece() || overlap_at_an_edge() || sheet_wound_twice()) return found_;
    piece_inside_another();
    return found_;
  }

 private:
  uint32_t piece_of(uint32_t t) const { return piece_.empty() ? 0u : piece_[t]; }

  bool finding(OverlapFinding::Kind kind, uint32_t a, uint32_t b) {
    found_.kind = kind;
    found_.tet_a = a;
    found_.tet_b = b;
    return true;
  }

  bool cut_short() {
    found_.cut_short = true;
    return true;
  }

  // Surfaces: boundary faces joined through shared vertices, numbered in face order.
  void number_surfaces() {
    surface_of_.resize(faces_.size());
    std::vector<uint32_t> root(pos_.size());
    std::iota(root.begin(), root.end(), 0u);
    for (const BoundaryFace& f : faces_) {
      for (int k = 1; k < 3; ++k) unite(root, f.v[0], f.v[k]);
    }
    std::vector<uint32_t> surface_of_root(pos_.size(), kInvalidIndex);
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      uint32_t& s = surface_of_root[find_root(root, faces_[f].v[0])];
      if (s == kInvalidIndex) {
        s = static_cast<uint32_t>(first_face_.size());
        first_face_.push_back(f);
      }
      surface_of_[f] = s;
    }
  }

  // Two boundary faces of one piece that clearly cross. Past the budget, what was
  // checked passed and the other checks still run.
  bool crossing_within_a_piece() {
    std::vector<Triangle3> tri(faces_.size());
    std::vector<TrianglePlane> planes(faces_.size());
    for (size_t f = 0; f < faces_.size(); ++f) {
      for (int k = 0; k < 3; ++k) tri[f][k] = pos_[faces_[f].v[k]];
      planes[f] = plane_of(tri[f]);
    }
    const BoxGrid grid = grid_of_triangles(tri);
    bool crossed = false;
    const bool complete = grid.for_each_overlapping_pair(pair_budget_, [&](uint32_t i, uint32_t j) {
      const BoundaryFace &s = faces_[i], &t = faces_[j];
      int shared = 0;
      for (uint32_t v : s.v) shared += v == t.v[0] || v == t.v[1] || v == t.v[2];
      if (shared >= 2 || !triangles_cross(tri[i], planes[i], tri[j], planes[j])) return true;
      if (piece_of(s.tet) != piece_of(t.tet)) return true;
      crossed =
          finding(OverlapFinding::Kind::kCrossing, std::min(s.tet, t.tet), std::max(s.tet, t.tet));
      return false;
    });
    found_.cut_short = !complete;
    return crossed;
  }

  // At each boundary edge: with two faces, the tets round it must fill less than a
  // turn, and the two faces are of one sheet (joined in sheet_); with more, where
  // bodies meet along it, their wedges must not overlap.
  bool overlap_at_an_edge() {
    std::vector<std::pair<uint64_t, uint32_t>> edges;  // (edge, face)
    edges.reserve(3 * faces_.size());
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const uint64_t u = faces_[f].v[k], v = faces_[f].v[(k + 1) % 3];
        edges.push_back({std::min(u, v) << 32 | std::max(u, v), f});
      }
    }
    sort_by_key(&edges);
    sheet_.resize(faces_.size());
    std::iota(sheet_.begin(), sheet_.end(), 0u);
    size_t walked = 0;
    for (size_t e = 0; e + 1 < edges.size(); ++e) {
      // The walks round the edges below start at random tets: load a few ahead.
      if (e + 16 < edges.size()) {
        const uint32_t ahead = faces_[edges[e + 16].second].tet;
        __builtin_prefetch(&mesh_.tets[ahead]);
        __builtin_prefetch(&neighbors_[4 * size_t{ahead}]);
      }
      const bool first_of_edge = e == 0 || edges[e - 1].first != edges[e].first;
      const bool two = edges[e].first == edges[e + 1].first && first_of_edge &&
                       (e + 2 == edges.size() || edges[e + 2].first != edges[e].first);
      const uint32_t u = uint32_t(edges[e].first >> 32), v = uint32_t(edges[e].first);
      if (!two) {
        if (!first_of_edge) continue;
        size_t end = e;
        while (end < edges.size() && edges[end].first == edges[e].first) ++end;
        if (end - e >= 3 && wedges_overlap_at(u, v, edges, e, end)) return true;
        continue;
      }
      unite(sheet_, edges[e].second, edges[e + 1].second);
      // Tets that wrap round the edge overlap there, and the sheet goes through itself
      // along it, where no face crosses another.
      const BoundaryFace& f = faces_[edges[e].second];
      const uint32_t past_turn = tet_past_a_turn(mesh_, neighbors_, f, u, v, walk_budget_, &walked);
      if (walked >= walk_budget_) return cut_short();
      if (past_turn != kInvalidIndex)
        return finding(OverlapFinding::Kind::kInside, f.tet, past_turn);
    }
    return false;
  }

  // Whether the wedges of the faces edges[begin .. end) at edge (u, v) overlap.
  bool wedges_overlap_at(uint32_t u, uint32_t v,
                         const std::vector<std::pair<uint64_t, uint32_t>>& edges, size_t begin,
                         size_t end) {
    std::vector<EdgeFace> around;
    for (size_t k = begin; k < end; ++k) {
      const BoundaryFace& f = faces_[edges[k].second];
      const uint32_t w =
          f.v[0] != u && f.v[0] != v ? f.v[0] : (f.v[1] != u && f.v[1] != v ? f.v[1] : f.v[2]);
      around.push_back({pos_[w], pos_[mesh_.tets[f.tet][f.corner]]});
    }
    size_t a = 0, b = 0;
    if (!wedges_overlap(pos_[u], pos_[v], around, &a, &b)) return false;
    const uint32_t ta = faces_[edges[begin + a].second].tet,
                   tb = faces_[edges[begin + b].second].tet;
    return finding(OverlapFinding::Kind::kInside, std::min(ta, tb), std::max(ta, tb));
  }

  // Parts of the boundary inside others of the same piece. With no crossings, the
  // number of times the piece's boundary winds around a point just inside a face is
  // the same for every face of its sheet (faces joined through edges that have no
  // other boundary face), and is 1 where no tets overlap: one point per sheet.
  bool sheet_wound_twice() {
    const FaceGroups surfaces(faces_, surface_of_, first_face_.size(), pos_);
    const BoxGrid surface_grid(surfaces.lo, surfaces.hi);  // which surfaces a point may be in
    for (uint32_t first = 0; first < faces_.size(); ++first) {
      if (find_root(sheet_, first) != first) continue;  // not the first face of its sheet
      const BoundaryFace& f = faces_[first];
      const Vec3 &a = pos_[f.v[0]], &b = pos_[f.v[1]], &c = pos_[f.v[2]];
      const Vec3 normal = cross(b - a, c - a);  // outward, |normal| = twice the area
      const double edge = std::sqrt(
          std::max({squared_length(b - a), squared_length(c - b), squared_length(a - c)}));
      const Vec3 point = (a + b + c) * (1.0 / 3) - normal * (1e-6 * edge / length(normal));
      double winding = 0;
      bool over_budget = false;
      surface_grid.for_each_holding(point, [&](uint32_t other) {
        if (over_budget || piece_of(faces_[first_face_[other]].tet) != piece_of(f.tet)) return;
        work_ += 1 + surfaces.size(other);
        over_budget = work_ > winding_budget_;
        if (!over_budget) winding += surfaces.winding(other, point, faces_, pos_);
      });
      if (over_budget) return cut_short();
      if (winding > 1.5)
        return finding(OverlapFinding::Kind::kInside, f.tet, tet_holding(mesh_, point, f.tet));
    }
    return false;
  }

  // A piece inside another: a point well inside it, the centroid of its first tet
  // with no vertex on the boundary (else of its first tet), around which another
  // piece winds.
  void piece_inside_another() {
    const size_t piece_count = first_tet_.size();
    if (piece_count < 2) return;
    std::vector<uint32_t> piece_of_face(faces_.size());
    for (size_t f = 0; f < faces_.size(); ++f) piece_of_face[f] = piece_[faces_[f].tet];
    const FaceGroups pieces(faces_, piece_of_face, piece_count, pos_);
    const BoxGrid piece_grid(pieces.lo, pieces.hi);
    std::vector<char> on_boundary(pos_.size(), 0);
    for (const BoundaryFace& f : faces_)
      for (uint32_t v : f.v) on_boundary[v] = 1;
    std::vector<uint32_t> inner_tet(first_tet_);
    std::vector<char> has_inner(piece_count, 0);
    for (uint32_t t = 0; t < mesh_.tets.size(); ++t) {
      const Tet& q = mesh_.tets[t];
      if (has_inner[piece_[t]] || on_boundary[q[0]] || on_boundary[q[1]] || on_boundary[q[2]] ||
          on_boundary[q[3]])
        continue;
      has_inner[piece_[t]] = 1;
      inner_tet[piece_[t]] = t;
    }
    for (size_t p = 0; p < piece_count; ++p) {
      const Tet& q = mesh_.tets[inner_tet[p]];
      const Vec3 point = (pos_[q[0]] + pos_[q[1]] + pos_[q[2]] + pos_[q[3]]) * 0.25;
      bool over_budget = false, inside = false;
      piece_grid.for_each_holding(point, [&](uint32_t other) {
        if (over_budget || inside || other == p) return;
        work_ += 1 + pieces.size(other);
        over_budget = work_ > winding_budget_;
        inside = !over_budget && pieces.winding(other, point, faces_, pos_) > 0.5;
      });
      if (over_budget) {
        cut_short();
        return;
      }
      if (inside) {
        finding(OverlapFinding::Kind::kInside, inner_tet[p],
                tet_holding(mesh_, point, inner_tet[p]));
        return;
      }
    }
  }

  const TetMesh& mesh_;
  const std::vector<uint32_t>& neighbors_;
  const std::vector<Vec3>& pos_;
  std::vector<BoundaryFace> faces_;
  size_t pair_budget_ = 0, walk_budget_ = 0, winding_budget_ = 0;
  size_t work_ = 0;                                // solid angles summed, against winding_budget_
  std::vector<uint32_t> surface_of_, first_face_;  // first_face_: of each surface
  std::vector<uint32_t> piece_, first_tet_;        // piece_: of each tet (if numbered)
  std::vector<uint32_t> sheet_;                    // union-find of faces into sheets
  OverlapFinding found_;
};

}  // namespace

OverlapFinding find_overlap(const TetMesh& mesh, const std::vector<uint32_t>& neighbors) {
  // The search's tests multiply up to eight coordinates, which overflow beyond about
  // 2^127 (a valid mesh 2^130 across was found overlapping by a hostile-input test).
  // A power of two scales a mesh exactly, so one far from 1 is searched at a scale
  // near 1: the same geometry, the same tets and faces.
  double largest = 0;
  for (const Vec3& p : mesh.positions)
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  int exponent = 0;
  std::frexp(largest, &exponent);
  if (largest > 0 && std::isfinite(largest) && std::abs(exponent) > 64) {
    TetMesh scaled;
    scaled.tets = mesh.tets;
    scaled.materials = mesh.materials;
    scaled.positions.reserve(mesh.positions.size());
    for (const Vec3& p : mesh.positions)
      scaled.positions.push_back(
          {std::ldexp(p.x, -exponent), std::ldexp(p.y, -exponent), std::ldexp(p.z, -exponent)});
    return OverlapSearch(scaled, neighbors).run();
  }
  return OverlapSearch(mesh, neighbors).run();
}

bool wedges_overlap(const Vec3& u, const Vec3& v, const std::vector<EdgeFace>& faces, size_t* a,
                    size_t* b) {
  const Vec3 axis = v - u;
  const double axis2 = squared_length(axis);
  if (faces.empty() || !(axis2 > 0)) return false;
  // A frame across the edge: r1 towards the first face's third corner, r2 = axis x r1.
  auto across = [&](const Vec3& p) {
    const Vec3 d = p - u;
    return d - axis * (dot(d, axis) / axis2);
  };
  const Vec3 r1 = across(faces[0].w), r2 = cross(axis, r1);
  struct Event {
    double angle;
    int step;  // +1 a start, -1 an end
    size_t face;
  };
  std::vector<Event> events;
  for (size_t i = 0; i < faces.size(); ++i) {
    const Vec3 dw = across(faces[i].w), dx = across(faces[i].x);
    const double angle = std::atan2(dot(dw, r2), dot(dw, r1));
    events.push_back({angle, dot(cross(dw, dx), axis) > 0 ? 1 : -1, i});
  }
  std::sort(events.begin(), events.end(), [](const Event& x, const Event& y) {
    return x.angle != y.angle ? x.angle < y.angle : x.step < y.step;
  });
  // Touching faces (within 1e-9 radians): ends first.
  for (size_t i = 0; i + 1 < events.size(); ++i) {
    for (size_t j = i + 1; j < events.size() && events[j].angle - events[i].angle <= 1e-9; ++j)
      if (events[j].step < events[i].step) std::swap(events[i], events[j]);
  }
  // Round the circle from where the fewest wedges are open: none may open while one is.
  size_t start = 0;
  for (int depth = 0, lowest = 0, i = 0; i < int(events.size()); ++i) {
    depth += events[i].step;
    if (depth < lowest) lowest = depth, start = size_t(i) + 1;
  }
  size_t open = SIZE_MAX;
  for (size_t n = 0; n < events.size(); ++n) {
    const Event& e = events[(start + n) % events.size()];
    if (e.step < 0) {
      open = SIZE_MAX;
    } else if (open != SIZE_MAX) {
      if (a) *a = open;
      if (b) *b = e.face;
      return true;
    } else {
      open = e.face;
    }
  }
  return false;
}

std::vector<uint32_t> vertex_pieces(const TetMesh& mesh) {
  std::vector<uint32_t> root(mesh.positions.size());  // stays in cache, unlike tets
  std::iota(root.begin(), root.end(), 0u);
  for (const Tet& q : mesh.tets) {
    for (int k = 1; k < 4; ++k) unite(root, q[0], q[k]);
  }
  for (uint32_t v = 0; v < root.size(); ++v) root[v] = find_root(root, v);
  return root;
}

}  // namespace tetlod
