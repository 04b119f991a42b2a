#include "core/io/sol.h"

#include <cstdint>
#include <cstdio>

#include "core/io/file_access.h"
#include "core/io/text_scanner.h"

namespace tetlod {

Status parse_sol_sizes(std::string_view text, const std::string& name, std::vector<double>* sizes) {
  using io::TextScanner;
  TextScanner scanner(text, name, '#');
  std::string_view keyword;
  if (!scanner.next_token(&keyword) ||
      !TextScanner::equals_ignore_case(keyword, "MeshVersionFormatted")) {
    const bool binary = text.size() >= 4 && (text.substr(0, 4) == std::string_view("\1\0\0\0", 4) ||
                                             text.substr(0, 4) == std::string_view("\0\0\0\1", 4));
    scanner.fail(binary ? "a binary solution file (.solb): write the sizes as ASCII .sol"
                        : "not a Medit .sol file: expected 'MeshVersionFormatted' first");
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
      if (!scanner.read_count(&fields, "number of fields", 2)) break;
      if (fields != 1) {
        scanner.fail(std::to_string(fields) +
                     " fields at each vertex: TetLOD reads one, the size (type 1)");
        break;
      }
      if (!scanner.read_int(&type, "field type")) break;
      if (type != 1) {
        scanner.fail(type == 3   ? "a tensor field (type 3, an anisotropic metric): TetLOD reads "
                                   "isotropic sizes, one number a vertex (type 1)"
                     : type == 2 ? "a vector field (type 2): TetLOD reads sizes, one number a "
                                   "vertex (type 1)"
                                 : "field type " + std::to_string(type) +
                                       ": TetLOD reads sizes, one number a vertex (type 1)");
        break;
      }
      read.reserve(count);
      for (uint64_t i = 0; i < count; ++i) {
        double size = 0;
        if (!scanner.read_double(&size, "size")) break;
        if (!(size > 0)) {
          char shown[32];
          std::snprintf(shown, sizeof shown, "%g", size);
          scanner.fail("size " + std::to_string(i + 1) + " is " + shown + ": sizes must be > 0");
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

Status read_sol_sizes(const std::string& path, std::vector<double>* sizes) {
  std::string text;
  if (Status s = io::read_file(path, &text); !s) return s;
  return parse_sol_sizes(text, path, sizes);
}

}  // namespace tetlod
