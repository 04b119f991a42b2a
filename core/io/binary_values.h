// Numbers stored as raw bytes in binary mesh files (internal to core/io): the
// value types of VTK's arrays and their conversion, in either byte order.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

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

}  // namespace tetlod::io
