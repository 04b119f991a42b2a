// box2: [0,2]x[0,1]x[0,1] split at x = 1 into two unit cubes, materials 1 and 2.
#include "core/generate/model_generator.h"

namespace tetlod {

Plc build_box2_plc() {
  Plc plc;
  // Point (i, j, k) at (i, j, k), i in 0..2, j and k in 0..1.
  auto id = [](uint32_t i, uint32_t j, uint32_t k) { return i + 3 * (j + 2 * k); };
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t j = 0; j < 2; ++j)
      for (uint32_t i = 0; i < 3; ++i) plc.add_point({double(i), double(j), double(k)});

  constexpr int32_t kBoundaryMarker = 1;
  constexpr int32_t kInterfaceMarker = 2;
  // The planes x = 0, 1, 2; x = 1 is the interface.
  for (uint32_t i = 0; i < 3; ++i) {
    plc.add_facet({id(i, 0, 0), id(i, 1, 0), id(i, 1, 1), id(i, 0, 1)},
                  i == 1 ? kInterfaceMarker : kBoundaryMarker);
  }
  // The four long sides, one quad per cube.
  for (uint32_t i = 0; i < 2; ++i) {
    plc.add_facet({id(i, 0, 0), id(i + 1, 0, 0), id(i + 1, 0, 1), id(i, 0, 1)}, kBoundaryMarker);
    plc.add_facet({id(i, 1, 0), id(i + 1, 1, 0), id(i + 1, 1, 1), id(i, 1, 1)}, kBoundaryMarker);
    plc.add_facet({id(i, 0, 0), id(i + 1, 0, 0), id(i + 1, 1, 0), id(i, 1, 0)}, kBoundaryMarker);
    plc.add_facet({id(i, 0, 1), id(i + 1, 0, 1), id(i + 1, 1, 1), id(i, 1, 1)}, kBoundaryMarker);
  }
  plc.add_region({0.5, 0.5, 0.5}, kBox2Left);
  plc.add_region({1.5, 0.5, 0.5}, kBox2Right);
  return plc;
}

}  // namespace tetlod
