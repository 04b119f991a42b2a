// Numbers stored as raw bytes in binary mesh files (internal to core/io): the
// value types of VTK's arrays and their conversion, in either byte order, and
// appending a number's bytes to a file being written.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

namespace tetlod::io {

struct BinaryType {
  enum Kind { kSigned, kUnsigned, kFloat } kind = kSigned;
  size_t size = 0;  // bytes; 0: not a type that can be read
};

// The bits of one value of `size` bytes at `p`.
inline uint64_t value_bits(const char* p, size_t size, bool big_endian) {
  uint64_t bits = 0;
  for (size_t i = 0; i < size; ++i) {
    const uint8_t byte = uint8_t(p[big_endian ? i : size - 1 - i]);
    bits = bits << 8 | byte;
  }
  return bits;
}

inline double binary_real(uint64_t bits, BinaryType type) {
  if (type.kind == BinaryType::kFloat) {
    if (type.size == 4) {
      const uint32_t b32 = uint32_t(bits);
      float f;
      std::memcpy(&f, &b32, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &bits, 8);
    return d;
  }
  if (type.kind == BinaryType::kUnsigned) return double(bits);
  const unsigned shift = unsigned(64 - 8 * type.size);
  return double(int64_t(bits << shift) >> shift);
}

// An integer; false if the value is not one or does not fit in int64.
inline bool binary_integer(uint64_t bits, BinaryType type, int64_t* value) {
  if (type.kind == BinaryType::kFloat) {
    const double d = binary_real(bits, type);
    if (!(d == std::floor(d) && std::abs(d) < 9.0e18)) return false;
    *value = int64_t(d);
    return true;
  }
  if (type.kind == BinaryType::kUnsigned) {
    if (bits > uint64_t(std::numeric_limits<int64_t>::max())) return false;
    *value = int64_t(bits);
    return true;
  }
  const unsigned shift = unsigned(64 - 8 * type.size);
  *value = int64_t(bits << shift) >> shift;
  return true;
}

// A value as text, for messages: an integer as it is, a real as "%.17g" would.
inline std::string binary_value_text(uint64_t bits, BinaryType type) {
  if (type.kind == BinaryType::kUnsigned) return std::to_string(bits);
  if (type.kind == BinaryType::kSigned) {
    int64_t value = 0;
    binary_integer(bits, type, &value);
    return std::to_string(value);
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", binary_real(bits, type));
  return text;
}

// Appends the bytes of `value` (an integer or floating-point number) in the given
// byte order.
template <typename T>
void append_binary(std::string* out, T value, bool big_endian) {
  static_assert(std::is_arithmetic_v<T> && sizeof(T) <= 8);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  // This machine's order: the first byte of a 2-byte 1.
  const uint16_t one = 1;
  char first;
  std::memcpy(&first, &one, 1);
  if ((first == 0) != big_endian)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out->append(bytes, sizeof(T));
}

}  // namespace tetlod::io
