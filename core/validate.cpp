#include "core/validate.h"

#include "core/adjacency.h"
#include "core/metrics.h"
#include "core/overlap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <tuple>
#include <utility>

namespace tetlod {
namespace {

std::string where(const std::string& source, const std::vector<uint32_t>& tet_lines, size_t tet) {
  // (A reader of binary data gives line 0: there is no line to name.)
  if (tet < tet_lines.size() && tet_lines[tet] > 0)
    return source + ":" + std::to_string(tet_lines[tet]) + ": ";
  return source + ": ";
}

std::string tet_name(size_t tet) {
  return "tetrahedron " + std::to_string(tet + 1);
}

// Equal for equal positions (-0 is 0), scattered otherwise.
uint64_t position_hash(const Vec3& p) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (const double c : {p.x, p.y, p.z}) {
    uint64_t bits;
    const double value = c == 0 ? 0.0 : c;
    std::memcpy(&bits, &value, sizeof bits);
    h = (h ^ bits) * 0xff51afd7ed558ccdull;
    h ^= h >> 29;
  }
  return h;
}

}  // namespace

Status validate_mesh(TetMesh* mesh, const std::string& source,
                     const std::vector<uint32_t>& tet_lines, ValidationReport* report,
                     std::vector<uint32_t>* face_neighbors) {
  ValidationReport local;
  ValidationReport& rep = report ? *report : local;
  rep = ValidationReport{};
  const size_t vertex_count = mesh->positions.size();
  const size_t tet_count = mesh->tets.size();

  if (mesh->materials.size() != tet_count) {
    return Status::error(source + ": " + std::to_string(tet_count) + " tetrahedra but " +
                         std::to_string(mesh->materials.size()) + " material ids");
  }
  if (tet_count == 0) return Status::error(source + ": the mesh has no tetrahedra");
  if (vertex_count >= kInvalidIndex) return Status::error(source + ": too many vertices");
  if (tet_count >= (size_t{1} << 30)) return Status::error(source + ": too many tetrahedra");

  for (size_t i = 0; i < vertex_count; ++i) {
    if (!is_finite(mesh->positions[i])) {
      return Status::error(source + ": vertex " + std::to_string(i + 1) +
                           " has a non-finite coordinate");
    }
  }

  for (size_t t = 0; t < tet_count; ++t) {
    const Tet& tet = mesh->tets[t];
    for (int k = 0; k < 4; ++k) {
      if (tet[k] >= vertex_count) {
        return Status::error(where(source, tet_lines, t) + tet_name(t) + " uses vertex " +
                             std::to_string(uint64_t{tet[k]} + 1) + " but there are only " +
                             std::to_string(vertex_count) + " vertices");
      }
      for (int l = 0; l < k; ++l) {
        if (tet[k] == tet[l]) {
          // By the node's position: its number here is the order read, not the file's id.
          const Vec3& p = mesh->positions[tet[k]];
          char text[96];
          std::snprintf(text, sizeof text, "(%.17g, %.17g, %.17g)", p.x, p.y, p.z);
          return Status::error(where(source, tet_lines, t) + tet_name(t) +
                               " repeats vertex: it names the node at " + text + " twice");
        }
      }
    }
    if (mesh->materials[t] < 0) {
      return Status::error(where(source, tet_lines, t) + tet_name(t) + " has material id " +
                           std::to_string(mesh->materials[t]) + " (must be >= 0)");
    }
  }

  // Orientation and degeneracy. Positions are read in tet order, that is in random
  // order: prefetch those of a few tets ahead.
  constexpr size_t kPrefetchDistance = 8;
  constexpr double kMinEdge = 1e-60, kMaxEdge = 1e60;
  for (size_t t = 0; t < tet_count; ++t) {
    if (t + kPrefetchDistance < tet_count) {
      for (uint32_t v : mesh->tets[t + kPrefetchDistance]) __builtin_prefetch(&mesh->positions[v]);
    }
    Tet& tet = mesh->tets[t];
    const Vec3& a = mesh->positions[tet[0]];
    const Vec3& b = mesh->positions[tet[1]];
    const Vec3& c = mesh->positions[tet[2]];
    const Vec3& d = mesh->positions[tet[3]];
    const double volume6 = signed_volume6(a, b, c, d);
    const double longest2 =
        std::max({squared_length(b - a), squared_length(c - a), squared_length(d - a),
                  squared_length(c - b), squared_length(d - b), squared_length(d - c)});
    // Face areas square the squared lengths: beyond these the metrics (stretch,
    // quadrics) under- or overflow, and a regular tet would measure as flat.
    if (!(longest2 >= kMinEdge * kMinEdge && longest2 <= kMaxEdge * kMaxEdge)) {
      // (Its length without squaring, which over- or underflows out there.)
      double longest = 0;
      const Vec3* corners[4] = {&a, &b, &c, &d};
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const Vec3 e = *corners[j] - *corners[i];
          longest = std::max(longest, std::hypot(std::hypot(e.x, e.y), e.z));
        }
      char text[64];
      std::snprintf(text, sizeof text, "%g", longest);
      return Status::error(where(source, tet_lines, t) + tet_name(t) + " has edges of length " +
                           text + ", outside [1e-60, 1e60] where TetLOD's metrics are exact; " +
                           "rescale the mesh");
    }
    const double scale = longest2 * std::sqrt(longest2);
    if (!(std::abs(volume6) > kFlatVolume6 * scale)) {
      // Zero, or so small next to its longest edge (cubed) that its shape is lost in
      // rounding: a tet 1e6 long and 1e-6 thin has a volume, but no shape.
      if (volume6 == 0)
        return Status::error(where(source, tet_lines, t) + tet_name(t) +
                             " is degenerate (zero volume)");
      char text[96];
      std::snprintf(text, sizeof text, "%.3g of its longest edge cubed",
                    std::abs(volume6) / 6 / scale);
      return Status::error(where(source, tet_lines, t) + tet_name(t) +
                           " is degenerate (nearly flat: its volume is " + text +
                           ", below 1.7e-13)");
    }
    if (volume6 < 0) {
      std::swap(tet[2], tet[3]);
      ++rep.reoriented_tets;
    }
  }

  // Every face is shared by at most two tets, lying on opposite sides of it.
  {
    std::vector<uint32_t> neighbors;
    const FaceProblem problem = build_face_neighbors(*mesh, &neighbors);
    if (problem.kind == FaceProblem::Kind::kNonManifold) {
      return Status::error(where(source, tet_lines, problem.tet_b) + tet_name(problem.tet_b) +
                           " shares a face with two other tetrahedra (including " +
                           tet_name(problem.tet_a) + "): the mesh is not a manifold");
    }
    if (problem.kind == FaceProblem::Kind::kOverlap) {
      // Two tets with the same vertex set share all four faces from the same side.
      Tet x = mesh->tets[problem.tet_a], y = mesh->tets[problem.tet_b];
      std::sort(x.begin(), x.end());
      std::sort(y.begin(), y.end());
      if (x == y) {
        const uint32_t first = std::min(problem.tet_a, problem.tet_b);
        const uint32_t second = std::max(problem.tet_a, problem.tet_b);
        return Status::error(where(source, tet_lines, second) + tet_name(second) + " duplicates " +
                             tet_name(first));
      }
      return Status::error(where(source, tet_lines, problem.tet_b) + tet_name(problem.tet_b) +
                           " overlaps " + tet_name(problem.tet_a) +
                           " (both lie on the same side of their shared face)");
    }
    // Tets that overlap with no face between them (see core/overlap.h).
    const OverlapFinding overlap = find_overlap(*mesh, neighbors);
    rep.overlap_check_cut_short = overlap.cut_short;
    if (overlap.kind == OverlapFinding::Kind::kCrossing) {
      return Status::error(where(source, tet_lines, overlap.tet_b) + tet_name(overlap.tet_b) +
                           " overlaps " + tet_name(overlap.tet_a) +
                           ": boundary faces of the two cross, so the mesh folds over itself " +
                           "(as when a vertex number is wrong)");
    }
    if (overlap.kind == OverlapFinding::Kind::kInside) {
      const uint32_t first = std::min(overlap.tet_a, overlap.tet_b);
      const uint32_t second = std::max(overlap.tet_a, overlap.tet_b);
      return Status::error(where(source, tet_lines, second) + tet_name(second) + " overlaps " +
                           tet_name(first) +
                           " with no face between them: the mesh covers that space twice " +
                           "(as when a vertex number is wrong, or a body is written twice)");
    }
    // By tet and corner: dropping unused vertices below does not change them.
    if (face_neighbors) *face_neighbors = std::move(neighbors);
  }

  // Drop unused vertices, keeping the order of the used ones.
  std::vector<uint32_t> remap(vertex_count, kInvalidIndex);
  for (const Tet& tet : mesh->tets)
    for (uint32_t v : tet) remap[v] = 0;
  uint32_t next = 0;
  for (size_t i = 0; i < vertex_count; ++i) {
    if (remap[i] == 0) {
      remap[i] = next;
      mesh->positions[next] = mesh->positions[i];
      ++next;
    }
  }
  if (next != vertex_count) {
    rep.removed_unused_vertices = vertex_count - next;
    rep.kept_vertices.reserve(next);
    for (size_t i = 0; i < vertex_count; ++i)
      if (remap[i] != kInvalidIndex) rep.kept_vertices.push_back(uint32_t(i));
    mesh->positions.resize(next);
    for (Tet& tet : mesh->tets)
      for (uint32_t& v : tet) v = remap[v];
  }

  // Vertices at exactly the position of another: the mesh is not conforming there
  // (two regions meshed apart). Counted, with the first such position, for a note.
  // Sorted by a hash of the position, then by the position where hashes are equal.
  const std::vector<Vec3>& p = mesh->positions;
  std::vector<std::pair<uint64_t, uint32_t>> keys(p.size());
  for (uint32_t v = 0; v < p.size(); ++v) keys[v] = {position_hash(p[v]), v};
  std::sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    const Vec3 &pa = p[a.second], &pb = p[b.second];
    return std::tie(pa.x, pa.y, pa.z) < std::tie(pb.x, pb.y, pb.z);
  });
  for (size_t i = 1; i < keys.size(); ++i) {
    if (keys[i].first != keys[i - 1].first || !(p[keys[i].second] == p[keys[i - 1].second]))
      continue;
    if (rep.coincident_vertices++ == 0) rep.coincident_position = p[keys[i].second];
  }
  return Status();
}

}  // namespace tetlod
