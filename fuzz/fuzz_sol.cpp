// libFuzzer target for the Medit .sol reader (--size-map) and the size map built from
// what it accepts: the sizes it returns are finite and > 0, and the map over a small
// mesh (the sizes laid on its vertices in turn) gives a finite value within their
// range at any point, the file's own numbers taken as coordinates (far outside too).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/sol.h"
#include "core/size_map.h"
#include "core/tet_mesh.h"

namespace {

// Two cubes cut into six tets each, positively oriented.
tetlod::TetMesh two_cubes() {
  tetlod::TetMesh mesh;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 0; i <= 2; ++i) mesh.positions.push_back({double(i), double(j), double(k)});
  auto id = [](int i, int j, int k) { return uint32_t((k * 2 + j) * 3 + i); };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < 2; ++i) {
    for (const auto& p : perms) {
      int c[3] = {i, 0, 0};
      tetlod::Tet t;
      t[0] = id(c[0], c[1], c[2]);
      for (int s = 0; s < 3; ++s) {
        ++c[p[s]];
        t[s + 1] = id(c[0], c[1], c[2]);
      }
      if (tetlod::signed_volume6(mesh, t) < 0) std::swap(t[2], t[3]);
      mesh.tets.push_back(t);
      mesh.materials.push_back(1);
    }
  }
  return mesh;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const tetlod::TetMesh mesh = two_cubes();
  std::vector<double> sizes;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (!tetlod::parse_sol_sizes(text, "fuzz.sol", &sizes).ok() || sizes.empty()) return 0;
  for (double s : sizes)
    if (!std::isfinite(s) || !(s > 0)) __builtin_trap();
  std::vector<double> laid(mesh.vertex_count());
  for (size_t v = 0; v < laid.size(); ++v) laid[v] = sizes[v % sizes.size()];
  std::shared_ptr<const tetlod::SizeMap> map;
  if (!tetlod::SizeMap::build(mesh, laid, &map).ok()) __builtin_trap();
  const double lo = *std::min_element(laid.begin(), laid.end());
  const double hi = *std::max_element(laid.begin(), laid.end());
  for (size_t i = 0; i + 2 < sizes.size() && i < 30; ++i) {
    for (const tetlod::Vec3& p :
         {tetlod::Vec3{sizes[i], sizes[i + 1], sizes[i + 2]},
          tetlod::Vec3{std::fmod(sizes[i], 2.0), std::fmod(sizes[i + 1], 1.0),
                       -std::fmod(sizes[i + 2], 1.0)}}) {
      const double v = map->at(p);
      if (!std::isfinite(v) || v < lo * (1 - 1e-12) || v > hi * (1 + 1e-12)) __builtin_trap();
    }
  }
  return 0;
}
