// spheres: three concentric icospheres (r1 < r2 < r3) in the box [-4, 4]^3.
#include <cassert>
#include <cmath>
#include <map>
#include <utility>

#include "core/generate/model_generator.h"

namespace tetlod {

Icosphere make_icosphere(int level, double radius) {
  assert(level >= 0 && radius > 0);
  // The icosahedron with vertices (0, +-1, +-phi) and cyclic permutations.
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> unit = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                            {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                            {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  std::vector<std::array<uint32_t, 3>> triangles = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto normalized = [](const Vec3& v) { return v * (1.0 / length(v)); };
  for (Vec3& v : unit) v = normalized(v);

  for (int l = 0; l < level; ++l) {
    // Each edge gets one midpoint, shared by its two triangles.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const std::pair<uint32_t, uint32_t> key(std::min(a, b), std::max(a, b));
      auto [it, inserted] = midpoints.emplace(key, static_cast<uint32_t>(unit.size()));
      if (inserted) unit.push_back(normalized((unit[a] + unit[b]) * 0.5));
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> finer;
    finer.reserve(4 * triangles.size());
    for (const auto& t : triangles) {
      const uint32_t ab = midpoint(t[0], t[1]);
      const uint32_t bc = midpoint(t[1], t[2]);
      const uint32_t ca = midpoint(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }

  Icosphere sphere;
  sphere.vertices.reserve(unit.size());
  for (const Vec3& v : unit) sphere.vertices.push_back(v * radius);
  sphere.triangles = std::move(triangles);
  return sphere;
}

Plc build_spheres_plc(int sphere_level) {
  Plc plc;
  const double h = kSpheresBoxHalfWidth;
  // Box corner (i, j, k) at (+-h, +-h, +-h).
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) plc.add_point({i ? h : -h, j ? h : -h, k ? h : -h});
  auto corner = [](uint32_t i, uint32_t j, uint32_t k) { return i + 2 * j + 4 * k; };
  constexpr int32_t kBoxMarker = 1;
  for (uint32_t s = 0; s < 2; ++s) {
    plc.add_facet({corner(s, 0, 0), corner(s, 1, 0), corner(s, 1, 1), corner(s, 0, 1)}, kBoxMarker);
    plc.add_facet({corner(0, s, 0), corner(1, s, 0), corner(1, s, 1), corner(0, s, 1)}, kBoxMarker);
    plc.add_facet({corner(0, 0, s), corner(1, 0, s), corner(1, 1, s), corner(0, 1, s)}, kBoxMarker);
  }

  const double radii[3] = {kSpheresRadius1, kSpheresRadius2, kSpheresRadius3};
  for (int s = 0; s < 3; ++s) {
    const Icosphere sphere = make_icosphere(sphere_level, radii[s]);
    const uint32_t first = static_cast<uint32_t>(plc.points.size());
    for (const Vec3& v : sphere.vertices) plc.add_point(v);
    for (const auto& t : sphere.triangles) {
      plc.add_facet({first + t[0], first + t[1], first + t[2]}, 2 + s);
    }
  }

  // Seeds on the ray through an icosphere vertex: every icosphere reaches exactly its
  // radius along that ray and is convex, so a seed between two radii lies between the
  // two polyhedra at any level.
  const Vec3 ray = make_icosphere(0, 1.0).vertices[0];
  plc.add_region(ray * 0.0, kSpheresCore);
  plc.add_region(ray * (0.5 * (kSpheresRadius1 + kSpheresRadius2)), kSpheresInner);
  plc.add_region(ray * (0.5 * (kSpheresRadius2 + kSpheresRadius3)), kSpheresOuter);
  plc.add_region(ray * (0.5 * (kSpheresRadius3 + kSpheresBoxHalfWidth)), kSpheresBox);
  return plc;
}

}  // namespace tetlod
