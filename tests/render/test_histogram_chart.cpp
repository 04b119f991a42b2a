// The report's stretch histogram chart (render/histogram_chart.h), drawn on the CPU.
#include "render/histogram_chart.h"

#include <gtest/gtest.h>

#include <vector>

namespace tetlod::render {
namespace {

// The rows holding the count label's ink in the column band of bar b (of `count`
// bars of a chart `width` pixels wide with margins 10 * scale), above the bar.
int label_height(const Image& image, int b, int count, int scale) {
  const int left = 10 * scale, right = image.width - 10 * scale;
  const double bin_width = double(right - left) / count;
  const int x0 = left + int(b * bin_width) + scale, x1 = left + int((b + 1) * bin_width) - scale;
  int top = image.height, bottom = -1;
  // Title and labels are the dark ink; the bars are coloured, the background white.
  const int axis = image.height - 16 * scale;  // labels below it are the bin edges
  for (int y = 3 * 12 * scale / 2; y < axis; ++y) {
    for (int x = x0 - scale; x <= x1 + scale; ++x) {
      const uint8_t* p = image.pixel(x, y);
      if (p[0] == 0x20 && p[1] == 0x20 && p[2] == 0x24) {
        top = std::min(top, y);
        bottom = std::max(bottom, y);
      }
    }
  }
  return bottom < 0 ? 0 : bottom - top + 1;
}

// Counts of 1 to 4 digits: every label is drawn, and all at one size (they were
// drawn larger where a short count fitted the bar, smaller where it did not).
TEST(HistogramChart, CountLabelsShareOneSize) {
  const std::vector<uint64_t> bins = {1, 161, 510, 2539, 7621, 7731, 5565, 1943, 397, 44};
  const Image chart = draw_histogram_chart(bins, ColorMap::kViridis, 480, 240, "stretch");
  const int scale = 2;  // min(480 / 180, 240 / 110)
  std::vector<int> heights;
  for (int b = 0; b < int(bins.size()); ++b) heights.push_back(label_height(chart, b, 10, scale));
  for (int b = 0; b < int(bins.size()); ++b) {
    EXPECT_GT(heights[size_t(b)], 0) << "no label on bar " << b;
    EXPECT_EQ(heights[size_t(b)], heights[4]) << "bar " << b << ": " << heights[size_t(b)];
  }
  // With only short counts the labels keep the chart's scale.
  const Image small = draw_histogram_chart({1, 16, 51, 25, 76, 77, 55, 19, 39, 44},
                                           ColorMap::kViridis, 480, 240, "stretch");
  EXPECT_GT(label_height(small, 4, 10, scale), heights[4]);
}

}  // namespace
}  // namespace tetlod::render
