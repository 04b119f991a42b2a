#include "core/generate/plc.h"

#include <cassert>

namespace tetlod {

void Plc::add_polygon(const uint32_t* vertices, size_t count) {
  assert(count >= 1);
  polygon_vertices.insert(polygon_vertices.end(), vertices, vertices + count);
  polygon_first_vertex.push_back(static_cast<uint32_t>(polygon_vertices.size()));
}

void Plc::close_facet(int32_t marker) {
  assert(polygon_count() > facet_first_polygon.back());
  facet_first_polygon.push_back(static_cast<uint32_t>(polygon_count()));
  facet_markers.push_back(marker);
}

}  // namespace tetlod
