// A bar chart of the stretch histogram (core/mesh_stats.h bins), drawn on the CPU
// so reports need no plotting library: bars coloured by the colour map at the bin
// centre, counts above the bars, the bin edges below.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "render/image.h"

namespace tetlod::render {

// `bins` are counts over equal bins of [0, 1]. Precondition: width >= 160, height >= 100.
Image draw_histogram_chart(const std::vector<uint64_t>& bins, ColorMap map, int width, int height,
                           const std::string& title);

}  // namespace tetlod::render
