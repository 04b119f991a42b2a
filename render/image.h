// RGBA8 images: PNG export (atomic), PNG import, comparison with a tolerance, and a
// small CPU canvas (rectangles and stb_easy_font text) for charts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace tetlod::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // rows top to bottom, 4 bytes per pixel

  Image() = default;
  Image(int w, int h, uint32_t fill_rgba = 0xffffffffu);
  uint8_t* pixel(int x, int y) { return rgba.data() + 4 * (size_t(y) * size_t(width) + size_t(x)); }
  const uint8_t* pixel(int x, int y) const {
    return rgba.data() + 4 * (size_t(y) * size_t(width) + size_t(x));
  }
};

// PNG bytes of `image` (stb_image_write).
std::vector<uint8_t> encode_png(const Image& image);
// Writes a PNG to a temporary file next to `path`, then renames it over `path`, so
// a failure never leaves a half-written file.
Status write_png(const std::string& path, const Image& image);
Status read_png(const std::string& path, Image* image);

struct ImageDifference {
  size_t differing_pixels = 0;  // pixels with any channel off by more than the tolerance
  int max_channel_difference = 0;
  bool same_size = true;
};

// Compares per channel. `diff`, if given, shows differing pixels in red over a faded
// copy of `expected`.
ImageDifference compare_images(const Image& expected, const Image& actual, int tolerance,
                               Image* diff);

// CPU drawing for charts. Colours are 0xRRGGBBAA.
void fill_rect(Image* image, int x0, int y0, int x1, int y1, uint32_t rgba);
// Text with stb_easy_font at (x, y) top-left, each font pixel `scale` image pixels.
void draw_text(Image* image, int x, int y, const std::string& text, uint32_t rgba, int scale);
// `utf8` in the font's characters (printable ASCII), at most `max_chars` of them,
// then "...": accented Latin letters lose their accents (u for u-umlaut, ss for
// sharp s), the micro sign and a mu outside Greek words become u, Greek letters
// (accented too) and Cyrillic ones (Russian, Ukrainian, Belarusian) are romanised
// (Zh, Shch, Th), any other character is one '?'. Bytes that are not valid UTF-8
// are '?' each.
std::string ascii_label(const std::string& utf8, size_t max_chars);
// Width and height in pixels of `text` at `scale`.
int text_width(const std::string& text, int scale);
int text_height(const std::string& text, int scale);

}  // namespace tetlod::render
