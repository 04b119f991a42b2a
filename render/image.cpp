#include "render/image.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/io/output_files.h"
#include "core/utf8.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

namespace tetlod::render {

Image::Image(int w, int h, uint32_t fill_rgba) : width(w), height(h) {
  rgba.resize(size_t(w) * size_t(h) * 4);
  for (size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = uint8_t(fill_rgba >> 24);
    rgba[i + 1] = uint8_t(fill_rgba >> 16);
    rgba[i + 2] = uint8_t(fill_rgba >> 8);
    rgba[i + 3] = uint8_t(fill_rgba);
  }
}

std::vector<uint8_t> encode_png(const Image& image) {
  std::vector<uint8_t> bytes;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        const auto* p = static_cast<const uint8_t*>(data);
        out->insert(out->end(), p, p + size);
      },
      &bytes, image.width, image.height, 4, image.rgba.data(), image.width * 4);
  return bytes;
}

Status write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0) return Status::error(path + ": empty image");
  const std::vector<uint8_t> bytes = encode_png(image);
  if (bytes.empty()) return Status::error(path + ": PNG encoding failed");
  return write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Status read_png(const std::string& path, Image* image) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) return Status::error(path + ": cannot read PNG: " + stbi_failure_reason());
  image->width = w;
  image->height = h;
  image->rgba.assign(data, data + size_t(w) * size_t(h) * 4);
  stbi_image_free(data);
  return Status();
}

ImageDifference compare_images(const Image& expected, const Image& actual, int tolerance,
                               Image* diff) {
  ImageDifference result;
  if (expected.width != actual.width || expected.height != actual.height) {
    result.same_size = false;
    result.differing_pixels = size_t(std::max(expected.width, actual.width)) *
                              size_t(std::max(expected.height, actual.height));
    return result;
  }
  if (diff) *diff = Image(expected.width, expected.height);
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x) {
      const uint8_t* e = expected.pixel(x, y);
      const uint8_t* a = actual.pixel(x, y);
      int worst = 0;
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(e[c]) - int(a[c])));
      result.max_channel_difference = std::max(result.max_channel_difference, worst);
      const bool differs = worst > tolerance;
      if (differs) ++result.differing_pixels;
      if (diff) {
        uint8_t* d = diff->pixel(x, y);
        if (differs) {
          d[0] = 255, d[1] = 0, d[2] = 0;
        } else {
          for (int c = 0; c < 3; ++c) d[c] = uint8_t(191 + e[c] / 4);
        }
        d[3] = 255;
      }
    }
  return result;
}

void fill_rect(Image* image, int x0, int y0, int x1, int y1, uint32_t rgba) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, image->width), y1 = std::min(y1, image->height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      uint8_t* p = image->pixel(x, y);
      p[0] = uint8_t(rgba >> 24), p[1] = uint8_t(rgba >> 16), p[2] = uint8_t(rgba >> 8);
      p[3] = uint8_t(rgba);
    }
}

namespace {

// stb_easy_font emits quads of 4 vertices {x, y, z, rgba} (16 bytes each).
struct FontVertex {
  float x, y, z;
  uint8_t color[4];
};

std::vector<FontVertex> font_quads(const std::string& text) {
  std::vector<FontVertex> vertices(std::max<size_t>(text.size(), 1) * 300 / 4);
  std::string copy = text;
  const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, vertices.data(),
                                        int(vertices.size() * sizeof(FontVertex)));
  vertices.resize(size_t(quads) * 4);
  return vertices;
}

}  // namespace

void draw_text(Image* image, int x, int y, const std::string& text, uint32_t rgba, int scale) {
  const std::vector<FontVertex> v = font_quads(text);
  for (size_t q = 0; q + 3 < v.size(); q += 4) {
    const float qx0 = std::min(v[q].x, v[q + 2].x), qx1 = std::max(v[q].x, v[q + 2].x);
    const float qy0 = std::min(v[q].y, v[q + 2].y), qy1 = std::max(v[q].y, v[q + 2].y);
    fill_rect(image, x + int(qx0 * scale), y + int(qy0 * scale), x + int(qx1 * scale),
              y + int(qy1 * scale), rgba);
  }
}

namespace {

// ASCII for U+00C0..U+00FF (the Latin-1 letters), by code point.
const char* const kLatin1Folded[64] = {
    "A", "A", "A", "A", "A", "A", "AE", "C", "E", "E", "E", "E", "I", "I", "I",  "I",
    "D", "N", "O", "O", "O", "O", "O",  "x", "O", "U", "U", "U", "U", "Y", "TH", "ss",
    "a", "a", "a", "a", "a", "a", "ae", "c", "e", "e", "e", "e", "i", "i", "i",  "i",
    "d", "n", "o", "o", "o", "o", "o",  "/", "o", "u", "u", "u", "u", "y", "th", "y"};

// Latin letters for U+0410..U+044F (the Russian alphabet, upper case then lower),
// by code point, as in the usual romanisation (BGN/PCGN without diacritics).
const char* const kCyrillic[64] = {
    "A", "B", "V", "G", "D", "E",  "Zh", "Z",  "I",  "Y",    "K", "L", "M", "N", "O",  "P",
    "R", "S", "T", "U", "F", "Kh", "Ts", "Ch", "Sh", "Shch", "'", "Y", "'", "E", "Yu", "Ya",
    "a", "b", "v", "g", "d", "e",  "zh", "z",  "i",  "y",    "k", "l", "m", "n", "o",  "p",
    "r", "s", "t", "u", "f", "kh", "ts", "ch", "sh", "shch", "'", "y", "'", "e", "yu", "ya"};

// Latin letters for U+0391..U+03A9 (the Greek capitals; U+03A2 is unassigned), by
// code point; the small letters U+03B1..U+03C9 are 0x20 above their capitals
// (final sigma, U+03C2, too).
const char* const kGreek[25] = {"A", "B", "G", "D", "E", "Z", "I", "Th", "I", "K",  "L",  "M", "N",
                                "X", "O", "P", "R", "S", "S", "T", "Y",  "F", "Ch", "Ps", "O"};

// `letters` in lower case.
std::string lower(std::string letters) {
  for (char& c : letters)
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  return letters;
}

// The ASCII spelling of a code point outside printable ASCII, or "?".
std::string fold(long c) {
  if (c >= 0xc0 && c <= 0xff) return kLatin1Folded[c - 0xc0];
  if (c == 0xb5 || c == 0x3bc) return "u";  // micro sign, Greek mu ("um")
  if (c >= 0x410 && c <= 0x44f) return kCyrillic[c - 0x410];
  if (c == 0x401) return "Yo";  // Ukrainian and Belarusian letters, and Yo
  if (c == 0x451) return "yo";
  if (c == 0x404 || c == 0x454) return c == 0x404 ? "Ye" : "ye";
  if (c == 0x406 || c == 0x456) return c == 0x406 ? "I" : "i";
  if (c == 0x407 || c == 0x457) return c == 0x407 ? "Yi" : "yi";
  if (c == 0x40e || c == 0x45e) return c == 0x40e ? "U" : "u";
  if (c == 0x490 || c == 0x491) return c == 0x490 ? "G" : "g";
  if (c >= 0x391 && c <= 0x3a9 && c != 0x3a2) return kGreek[c - 0x391];
  if (c >= 0x3b1 && c <= 0x3c9) return lower(kGreek[c - 0x3b1]);
  // Greek letters with tonos or dialytika (most Greek words have one).
  switch (c) {
    case 0x386:
      return "A";
    case 0x388:
      return "E";
    case 0x389:
    case 0x38a:
    case 0x3aa:
      return "I";
    case 0x38c:
    case 0x38f:
      return "O";
    case 0x38e:
    case 0x3ab:
      return "Y";
    case 0x3ac:
      return "a";
    case 0x3ad:
      return "e";
    case 0x3ae:
    case 0x3af:
    case 0x390:
    case 0x3ca:
      return "i";
    case 0x3cc:
    case 0x3ce:
      return "o";
    case 0x3cd:
    case 0x3b0:
    case 0x3cb:
      return "y";
    default:
      return "?";
  }
}

bool is_greek(long c) {
  return c >= 0x370 && c <= 0x3ff;
}

}  // namespace

std::string ascii_label(const std::string& utf8, size_t max_chars) {
  std::string out;
  size_t at = 0;
  long previous = 0;
  while (at < utf8.size()) {
    const long c = next_code_point(utf8, &at);
    std::string piece = c >= 32 && c <= 126 ? std::string(1, char(c)) : fold(c);
    if (c == 0x3bc) {  // mu: "m" in a Greek word, else "u" (the micro prefix)
      size_t ahead = at;
      const long next = ahead < utf8.size() ? next_code_point(utf8, &ahead) : 0;
      if (is_greek(previous) || (next != 0x3bc && is_greek(next))) piece = "m";
    }
    if (out.size() + piece.size() > max_chars) return out + "...";
    out += piece;
    previous = c;
  }
  return out;
}

int text_width(const std::string& text, int scale) {
  std::string copy = text;
  return stb_easy_font_width(copy.data()) * scale;
}

int text_height(const std::string& text, int scale) {
  std::string copy = text;
  return stb_easy_font_height(copy.data()) * scale;
}

}  // namespace tetlod::render
