// libMeshb's binary files (internal to core/io): the meshes (.meshb) and solution
// fields (.solb) of the Gamma Mesh Format. A 4-byte 1, whose byte order is the
// file's; the version (1: 4-byte reals; 2: 8-byte reals; 3: and 8-byte keyword
// positions; 4: and 8-byte integers); then keywords, Dimension first: a 4-byte code,
// the file position of the next keyword (0 after the last), for a keyword with
// entries their count (an integer), then the entries. Keywords a reader does not read
// are skipped by that position, so any keyword of any libMeshb version can be there.
// Every error reads "name: byte N: message".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/io/binary_values.h"
#include "core/status.h"

namespace tetlod::io {

// libMeshb's keyword codes that TetLOD's readers meet.
enum GmfCode : int64_t {
  kGmfDimension = 3,
  kGmfVertices = 4,
  kGmfEdges = 5,
  kGmfTriangles = 6,
  kGmfQuadrilaterals = 7,
  kGmfTetrahedra = 8,
  kGmfPrisms = 9,
  kGmfHexahedra = 10,
  kGmfTrianglesP2 = 24,
  kGmfEdgesP2 = 25,
  kGmfSolAtPyramids = 26,
  kGmfQuadrilateralsQ2 = 27,
  kGmfTetrahedraP2 = 30,
  kGmfHexahedraQ2 = 33,
  kGmfPyramids = 49,
  kGmfEnd = 54,
  kGmfSolAtVertices = 62,
  kGmfSolAtEdges = 63,
  kGmfSolAtHexahedra = 68,
  kGmfFloatingPointPrecision = 155,
};

class GmfBinary {
 public:
  // Messages name the file as a binary `kind` (say "Medit") with extension `binary`
  // (".meshb"), whose ASCII form is `ascii` (".mesh").
  GmfBinary(std::string_view data, const std::string& name, const char* kind, const char* binary,
            const char* ascii)
      : data_(data), name_(name), kind_(kind), binary_(binary), ascii_(ascii) {}

  // Reads the header, then calls section(keyword, body, end) -> bool for each keyword
  // but End, its body being [body, end) (false: stop, with status_ set by fail()).
  template <typename Section>
  Status walk(Section&& section) {
    const std::string full = std::string("binary ") + kind_ + " (" + binary_ + ")";
    if (data_.size() < 8) return error(0, "too short for a " + full + " file");
    const uint64_t code = value_bits(data_.data(), 4, false);
    if (code == 0x01000000) {
      big_endian_ = true;
    } else if (code != 1) {
      const bool text = data_.find("MeshVersionFormatted") < 256;
      return error(0, text ? std::string("not a binary ") + kind_ +
                                 " file: it is an ASCII one (name it " + ascii_ + ")"
                           : "not a " + full + " file: it starts with " + std::to_string(code) +
                                 ", not the 4-byte 1 in either byte order");
    }
    const int64_t version = integer(4, 4);
    if (version < 1 || version > 4) {
      return error(4, "version " + std::to_string(version) + " (libMeshb knows 1 to 4)");
    }
    real_size_ = version == 1 ? 4 : 8;
    position_size_ = version >= 3 ? 8 : 4;
    integer_size_ = version == 4 ? 8 : 4;
    size_t at = 8;
    for (bool first = true;; first = false) {
      // libMeshb refuses a file without the End keyword too.
      if (at == data_.size())
        return error(at, "the file ends before the End keyword (truncated file?)");
      if (data_.size() - at < 4 + position_size_) {
        return error(at, "the file ends inside a keyword's header (truncated file?)");
      }
      const int64_t keyword = integer(at, 4);
      const int64_t next = integer(at + 4, position_size_);
      if (first && keyword != kGmfDimension) {
        return error(
            at, "the first keyword is code " + std::to_string(keyword) + ", not Dimension (3)");
      }
      if (keyword == kGmfEnd) break;
      // Positions only go forward, past this keyword's header, so a hostile file can
      // neither loop nor make a section end before it starts.
      const size_t body = at + 4 + position_size_;
      if (next != 0 && (next < int64_t(body) || uint64_t(next) > data_.size())) {
        return error(at + 4, "keyword " + std::to_string(keyword) +
                                 ": the next keyword's position " + std::to_string(next) +
                                 (next < int64_t(body) ? " is not after this one"
                                                       : " is past the end of the file (" +
                                                             std::to_string(data_.size()) +
                                                             " bytes; truncated file?)"));
      }
      const size_t end = next == 0 ? data_.size() : size_t(next);
      if (!section(keyword, body, end)) return status_;
      if (next == 0) break;  // the last keyword, as libMeshb reads it
      at = size_t(next);
    }
    return Status();
  }

  Status error(size_t at, const std::string& message) const {
    return Status::error(name_ + ": byte " + std::to_string(at) + ": " + message);
  }
  bool fail(size_t at, const std::string& message) {
    status_ = error(at, message);
    return false;
  }

  // A signed integer of `size` bytes at `at` (which the caller checked is in the file).
  int64_t integer(size_t at, size_t size) const {
    int64_t value = 0;
    binary_integer(value_bits(data_.data() + at, size, big_endian_), {BinaryType::kSigned, size},
                   &value);
    return value;
  }
  double real(size_t at) const {
    return binary_real(value_bits(data_.data() + at, real_size_, big_endian_),
                       {BinaryType::kFloat, real_size_});
  }

  // The entry count at *at, whose `entry_size`-byte entries must end by `end`; *at
  // moves to the first entry.
  bool count(size_t* at, size_t end, size_t entry_size, const char* what, uint64_t* n) {
    if (end - *at < integer_size_) return fail(*at, std::string(what) + ": no entry count");
    const int64_t value = integer(*at, integer_size_);
    *at += integer_size_;
    if (value < 0 || uint64_t(value) > (end - *at) / entry_size) {
      return fail(*at - integer_size_, std::string(what) + ": " + std::to_string(value) +
                                           " entries of " + std::to_string(entry_size) +
                                           " bytes do not fit in the " + std::to_string(end - *at) +
                                           " bytes before the next keyword (truncated file?)");
    }
    *n = uint64_t(value);
    return true;
  }

  // Dimension's body at `at`: 3, or false with the error.
  bool dimension(size_t at, size_t end, const char* what) {
    if (end - at < 4) return fail(at, "Dimension: no value");
    const int64_t dimension = integer(at, 4);
    if (dimension != 3) {
      return fail(at, std::string("only 3-dimensional ") + what + " are supported (Dimension " +
                          std::to_string(dimension) + ")");
    }
    return true;
  }

  // FloatingPointPrecision's body at `at`: one integer, 32 or 64, the size of the reals
  // after it, whatever the version (libMeshb's GmfSetFloatPrecision(); it ignores other
  // values, and so do we). `reals_read` names a section already read with the reals'
  // size (an error if it changes), or is null.
  bool precision(size_t at, size_t end, const char* reals_read) {
    if (end - at < integer_size_) return fail(at, "FloatingPointPrecision: no value");
    const int64_t bits = integer(at, integer_size_);
    if (bits != 32 && bits != 64) return true;
    if (reals_read && size_t(bits / 8) != real_size_) {
      return fail(at, "FloatingPointPrecision " + std::to_string(bits) + " after the " +
                          reals_read + " section, read with " + std::to_string(8 * real_size_) +
                          "-bit reals");
    }
    real_size_ = size_t(bits / 8);
    return true;
  }

  size_t real_size() const { return real_size_; }
  size_t integer_size() const { return integer_size_; }

 private:
  std::string_view data_;
  const std::string& name_;
  const char* kind_;
  const char* binary_;
  const char* ascii_;
  Status status_;
  bool big_endian_ = false;
  size_t real_size_ = 8, position_size_ = 4, integer_size_ = 4;
};

}  // namespace tetlod::io
