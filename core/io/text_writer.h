// Appending numbers to file text (internal to core/io). Doubles are written as the
// shortest text that reads back to the same value (std::to_chars), which is exact
// like "%.17g" and shorter.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace tetlod::io {

inline void append_number(std::string* out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

inline void append_number(std::string* out, int64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

inline void append_number(std::string* out, uint32_t value) {
  append_number(out, int64_t{value});
}
inline void append_number(std::string* out, int32_t value) {
  append_number(out, int64_t{value});
}
inline void append_number(std::string* out, uint64_t value) {
  append_number(out, int64_t(value));
}

// Appends the values separated by single spaces, then a line break.
template <typename... Values>
void append_line(std::string* out, Values... values) {
  bool first = true;
  ((out->append(first ? "" : " "), append_number(out, values), first = false), ...);
  out->push_back('\n');
}

}  // namespace tetlod::io
