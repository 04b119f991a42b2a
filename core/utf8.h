// UTF-8 decoding, shared by the readers (valid_utf8(), io/mesh_formats.h) and the
// renderer's labels (render::ascii_label()).
#pragma once

#include <cstddef>
#include <string_view>

namespace tetlod {

// The code point of the well-formed UTF-8 sequence at text[*at], advancing *at past
// it; -1, advancing *at by one byte, if none starts there (a stray continuation byte,
// a cut sequence, an overlong form, a surrogate, anything past U+10FFFF).
inline long next_code_point(std::string_view text, size_t* at) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(*at);
  const int length = lead < 0x80                   ? 1
                     : lead >= 0xc2 && lead < 0xe0 ? 2
                     : lead >= 0xe0 && lead < 0xf0 ? 3
                     : lead >= 0xf0 && lead < 0xf5 ? 4
                                                   : 0;
  if (length == 0 || *at + size_t(length) > text.size()) return ++*at, -1;
  long code = length == 1 ? lead : lead & (0x7f >> length);
  for (int k = 1; k < length; ++k) {
    if ((byte(*at + size_t(k)) & 0xc0) != 0x80) return ++*at, -1;
    code = code << 6 | (byte(*at + size_t(k)) & 0x3f);
  }
  const long smallest[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[length] || code > 0x10ffff || (code >= 0xd800 && code < 0xe000))
    return ++*at, -1;
  *at += size_t(length);
  return code;
}

}  // namespace tetlod
