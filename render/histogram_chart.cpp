#include "render/histogram_chart.h"

#include <algorithm>
#include <cstdio>

namespace tetlod::render {
namespace {

uint32_t to_rgba(const Rgb& c) {
  auto byte = [](float v) { return uint32_t(std::clamp(v, 0.0f, 1.0f) * 255 + 0.5f); };
  return byte(c[0]) << 24 | byte(c[1]) << 16 | byte(c[2]) << 8 | 0xffu;
}

constexpr uint32_t kInk = 0x202024ffu;
constexpr uint32_t kAxis = 0x909090ffu;

}  // namespace

Image draw_histogram_chart(const std::vector<uint64_t>& bins, ColorMap map, int width, int height,
                           const std::string& title) {
  Image image(width, height);
  const int scale = std::max(1, std::min(width / 180, height / 110));
  const int line = 12 * scale;
  const int left = 10 * scale, right = width - 10 * scale;
  const int top = 2 * line + 4 * scale;  // title, then room for the count labels
  const int bottom = height - line - 4 * scale;
  draw_text(&image, left, 4 * scale, title, kInk, scale);
  if (bins.empty() || right <= left || bottom <= top) return image;

  const uint64_t largest = std::max<uint64_t>(1, *std::max_element(bins.begin(), bins.end()));
  const int count = static_cast<int>(bins.size());
  const double bin_width = double(right - left) / count;
  auto bar_x = [&](int b, int* x0, int* x1) {
    *x0 = left + int(b * bin_width) + scale;
    *x1 = left + int((b + 1) * bin_width) - scale;
  };
  // The counts above the bars, all at one size: the largest at which every count
  // that fits its bar at all fits it (one that does not fit even the smallest is left out).
  int label_scale = scale;
  for (int b = 0; b < count; ++b) {
    int x0 = 0, x1 = 0;
    bar_x(b, &x0, &x1);
    const std::string label = std::to_string(bins[size_t(b)]);
    while (label_scale > 1 && text_width(label, label_scale) > x1 - x0 + 2 * scale) --label_scale;
  }
  for (int b = 0; b < count; ++b) {
    int x0 = 0, x1 = 0;
    bar_x(b, &x0, &x1);
    const int bar = int(double(bottom - top) * double(bins[size_t(b)]) / double(largest) + 0.5);
    const Rgb c = colormap_rgb(map, (b + 0.5) / count);
    fill_rect(&image, x0, bottom - bar, x1, bottom, to_rgba(c));
    const std::string label = std::to_string(bins[size_t(b)]);
    const int w = text_width(label, label_scale);
    if (w <= x1 - x0 + 2 * scale)
      draw_text(&image, (x0 + x1 - w) / 2, bottom - bar - 10 * label_scale, label, kInk,
                label_scale);
  }
  fill_rect(&image, left, bottom, right, bottom + scale, kAxis);
  for (int b = 0; b <= count; b += 2) {
    char edge[16];
    std::snprintf(edge, sizeof edge, "%.1f", double(b) / count);
    const int x = left + int(b * bin_width);
    const int w = text_width(edge, scale);
    draw_text(&image, std::clamp(x - w / 2, 0, width - w), bottom + 3 * scale, edge, kInk, scale);
  }
  return image;
}

}  // namespace tetlod::render
