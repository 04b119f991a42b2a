#include "core/io/sol.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/io/file_access.h"
#include "core/io/gmf_binary.h"
#include "core/io/text_scanner.h"

namespace tetlod {
namespace {

// Why a field of `fields` fields of type `type` (the first) is not a size field, or "".
std::string not_sizes(int64_t fields, int64_t type) {
  if (fields != 1)
    return std::to_string(fields) + " fields at each vertex: TetLOD reads one, the size (type 1)";
  if (type == 1) return "";
  return type == 3   ? "a tensor field (type 3, an anisotropic metric): TetLOD reads isotropic "
                       "sizes, one number a vertex (type 1)"
         : type == 2 ? "a vector field (type 2): TetLOD reads sizes, one number a vertex (type 1)"
                     : "field type " + std::to_string(type) +
                           ": TetLOD reads sizes, one number a vertex (type 1)";
}

std::string not_positive(uint64_t i, double size) {
  char shown[32];
  std::snprintf(shown, sizeof shown, "%g", size);
  return "size " + std::to_string(i + 1) + " is " + shown +
         (std::isfinite(size) ? ": sizes must be > 0" : ": sizes must be finite");
}

// A binary .solb (libMeshb's layout, core/io/gmf_binary.h), as MMG and FreeFEM write
// it: SolAtVertices's body is the vertex count (an integer), the number of fields and
// their types (4-byte integers each), then the values (reals).
Status parse_solb_sizes(std::string_view data, const std::string& name, std::vector<double>* sizes,
                        std::string* count_at) {
  io::GmfBinary gmf(data, name, "solution", ".solb", ".sol");
  std::vector<double> read;
  bool seen = false;
  const Status walked = gmf.walk([&](int64_t keyword, size_t at, size_t end) {
    switch (keyword) {
      case io::kGmfDimension:
        return gmf.dimension(at, end, "sizes");
      case io::kGmfFloatingPointPrecision:
        return gmf.precision(at, end, seen ? "SolAtVertices" : nullptr);
      case io::kGmfSolAtVertices: {
        if (seen) return gmf.fail(at, "a second SolAtVertices section");
        seen = true;
        const size_t w = gmf.integer_size();
        if (end - at < w + 4)
          return gmf.fail(at, "SolAtVertices: its header ends early (truncated file?)");
        const int64_t count = gmf.integer(at, w);
        if (count_at) *count_at = name + ": byte " + std::to_string(at);
        const int64_t fields = gmf.integer(at + w, 4);
        if (fields < 1) return gmf.fail(at + w, not_sizes(fields, 0));
        if (end - at < w + 8)
          return gmf.fail(at + w + 4, "SolAtVertices: no field type (truncated file?)");
        if (const std::string why = not_sizes(fields, gmf.integer(at + w + 4, 4)); !why.empty())
          return gmf.fail(at + w, why);
        const size_t first = at + w + 8;
        if (count < 0)
          return gmf.fail(at, "SolAtVertices: a vertex count of " + std::to_string(count));
        if (uint64_t(count) > (end - first) / gmf.real_size()) {
          return gmf.fail(at, "SolAtVertices: " + std::to_string(count) + " sizes of " +
                                  std::to_string(gmf.real_size()) + " bytes do not fit in the " +
                                  std::to_string(end - first) +
                                  " bytes before the next keyword (truncated file?)");
        }
        const uint64_t n = uint64_t(count);
        at = first;
        read.reserve(n);
        for (uint64_t i = 0; i < n; ++i, at += gmf.real_size()) {
          const double size = gmf.real(at);
          if (!(size > 0) || !std::isfinite(size)) return gmf.fail(at, not_positive(i, size));
          read.push_back(size);
        }
        return true;
      }
      default:
        if (keyword == io::kGmfSolAtPyramids ||
            (keyword >= io::kGmfSolAtEdges && keyword <= io::kGmfSolAtHexahedra)) {
          static const char* const kOn[] = {"Edges",      "Triangles", "Quadrilaterals",
                                            "Tetrahedra", "Prisms",    "Hexahedra"};
          const char* on =
              keyword == io::kGmfSolAtPyramids ? "Pyramids" : kOn[keyword - io::kGmfSolAtEdges];
          return gmf.fail(at, std::string("SolAt") + on +
                                  ": sizes on other entities than vertices are not "
                                  "read (SolAtVertices)");
        }
        return true;  // any other keyword: skipped
    }
  });
  if (!walked) return walked;
  if (!seen) return Status::error(name + ": no SolAtVertices section");
  *sizes = std::move(read);
  return Status();
}

}  // namespace

Status parse_sol_sizes(std::string_view text, const std::string& name, std::vector<double>* sizes,
                       std::string* count_at) {
  using io::TextScanner;
  // A binary file starts with libMeshb's 4-byte 1, in either byte order.
  if (text.size() >= 4 && (text.substr(0, 4) == std::string_view("\1\0\0\0", 4) ||
                           text.substr(0, 4) == std::string_view("\0\0\0\1", 4)))
    return parse_solb_sizes(text, name, sizes, count_at);
  TextScanner scanner(text, name, '#');
  std::string_view keyword;
  if (!scanner.next_token(&keyword) ||
      !TextScanner::equals_ignore_case(keyword, "MeshVersionFormatted")) {
    scanner.fail("not a Medit .sol file: expected 'MeshVersionFormatted' first");
    return scanner.status();
  }
  int64_t value = 0;
  if (!scanner.read_int_in_range(&value, "MeshVersionFormatted value", 1, 4))
    return scanner.status();
  std::vector<double> read;
  bool seen = false;
  while (!scanner.failed() && scanner.next_token(&keyword)) {
    auto is = [&](const char* word) { return TextScanner::equals_ignore_case(keyword, word); };
    if (is("End")) break;
    if (is("Dimension")) {
      if (scanner.read_int(&value, "dimension") && value != 3)
        scanner.fail("only 3-dimensional sizes are read (Dimension " + std::to_string(value) + ")");
    } else if (is("SolAtVertices")) {
      if (seen) {
        scanner.fail("a second SolAtVertices section");
        break;
      }
      seen = true;
      uint64_t count = 0, fields = 0;
      int64_t type = 0;
      // An entry is a number and a line break: at least 2 bytes.
      if (!scanner.read_count(&count, "vertex count", 2)) break;
      if (count_at) *count_at = name + ":" + std::to_string(scanner.line());
      if (!scanner.read_count(&fields, "number of fields", 2)) break;
      if (fields == 1 && !scanner.read_int(&type, "field type")) break;
      if (const std::string why = not_sizes(int64_t(fields), type); !why.empty()) {
        scanner.fail(why);
        break;
      }
      read.reserve(count);
      for (uint64_t i = 0; i < count; ++i) {
        double size = 0;
        if (!scanner.read_double(&size, "size")) break;
        if (!(size > 0)) {
          scanner.fail(not_positive(i, size));
          break;
        }
        read.push_back(size);
      }
    } else if (TextScanner::looks_numeric(keyword)) {
      scanner.fail("found the number " + TextScanner::quote(keyword) +
                   " where a keyword was expected (is the vertex count above right?)");
    } else if (keyword.size() > 5 &&
               TextScanner::equals_ignore_case(keyword.substr(0, 5), "SolAt")) {
      scanner.fail(TextScanner::quote(keyword) +
                   ": sizes on other entities than vertices are not read (SolAtVertices)");
    } else {
      scanner.fail("unknown keyword " + TextScanner::quote(keyword));
    }
  }
  if (scanner.failed()) return scanner.status();
  if (!seen) return Status::error(name + ": no SolAtVertices section");
  *sizes = std::move(read);
  return Status();
}

Status read_sol_sizes(const std::string& path, std::vector<double>* sizes, std::string* count_at) {
  std::string text;
  if (Status s = io::read_file(path, &text); !s) return s;
  return parse_sol_sizes(text, path, sizes, count_at);
}

}  // namespace tetlod
