// VTK legacy unstructured grids (.vtk), ASCII and BINARY, as in "The VTK User's
// Guide", chapter 19 "VTK File Formats", with both cell layouts: "CELLS n size"
// followed by "k i1 .. ik" (file version <= 4.2) and "CELLS n+1 size" followed by
// OFFSETS and CONNECTIVITY arrays (file version 5.1). In a binary file the keyword
// lines stay text and each array's values follow its line as big-endian numbers.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "core/io/binary_values.h"
#include "core/io/mesh_formats.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"
#include "core/metrics.h"

namespace tetlod::io {
namespace {

constexpr const char* kMaterialArray = "material";

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

// The value types of a binary legacy file's arrays.
BinaryType binary_type(std::string_view name) {
  struct Entry {
    const char* name;
    BinaryType type;
  };
  // "long" as VTK reads it on Linux and macOS (a C long of 8 bytes), and as meshio
  // writes 64-bit arrays in the 4.2 layout.
  static constexpr Entry kTypes[] = {
      {"char", {BinaryType::kSigned, 1}},         {"unsigned_char", {BinaryType::kUnsigned, 1}},
      {"short", {BinaryType::kSigned, 2}},        {"unsigned_short", {BinaryType::kUnsigned, 2}},
      {"int", {BinaryType::kSigned, 4}},          {"unsigned_int", {BinaryType::kUnsigned, 4}},
      {"long", {BinaryType::kSigned, 8}},         {"unsigned_long", {BinaryType::kUnsigned, 8}},
      {"vtktypeint32", {BinaryType::kSigned, 4}}, {"vtktypeuint32", {BinaryType::kUnsigned, 4}},
      {"vtktypeint64", {BinaryType::kSigned, 8}}, {"vtktypeuint64", {BinaryType::kUnsigned, 8}},
      {"vtkidtype", {BinaryType::kSigned, 8}},    {"float", {BinaryType::kFloat, 4}},
      {"double", {BinaryType::kFloat, 8}}};
  for (const Entry& e : kTypes)
    if (TextScanner::equals_ignore_case(name, e.name)) return e.type;
  return {};
}

// Legacy binary files are big-endian.
double binary_real(const char* p, BinaryType type) {
  return binary_real(value_bits(p, type.size, true), type);
}

bool binary_integer(const char* p, BinaryType type, int64_t* value) {
  return binary_integer(value_bits(p, type.size, true), type, value);
}

std::string value_text(const char* p, BinaryType type) {
  return binary_value_text(value_bits(p, type.size, true), type);
}

class VtkLegacyParser {
 public:
  VtkLegacyParser(std::string_view text, const std::string& name, ParsedMesh* out)
      : text_(text), scanner_(text, name), out_(out) {}

  Status parse() {
    if (!parse_header()) return scanner_.status();
    std::string_view keyword;
    while (!scanner_.failed() && scanner_.next_token(&keyword)) {
      auto is = [&](const char* word) { return TextScanner::equals_ignore_case(keyword, word); };
      if (is("POINTS")) {
        parse_points();
      } else if (is("CELLS")) {
        parse_cells();
      } else if (is("CELL_TYPES")) {
        parse_cell_types();
      } else if (is("CELL_DATA") || is("POINT_DATA")) {
        start_data_section(is("CELL_DATA"));
      } else if (is("FIELD")) {
        parse_field();
      } else if (is("METADATA")) {
        skip_metadata();
      } else {
        parse_attribute(keyword);
      }
    }
    if (!scanner_.failed() && data_section_ != DataSection::kNone && section_arrays_ == 0) {
      scanner_.fail_at_line(section_line_, "the data section has no arrays (truncated file?)");
    }
    if (scanner_.failed() || !build_tets()) return scanner_.status();
    return Status();
  }

 private:
  enum class DataSection { kNone, kPoints, kCells };

  bool parse_header() {
    const std::string_view magic = "# vtk DataFile Version";
    const std::string_view first = scanner_.rest_of_line();
    if (first.size() < magic.size() ||
        !TextScanner::equals_ignore_case(first.substr(0, magic.size()), magic)) {
      return scanner_.fail("not a VTK legacy file: expected '# vtk DataFile Version' first");
    }
    scanner_.rest_of_line();  // the title
    std::string_view token;
    if (!scanner_.next_token(&token))
      return scanner_.fail("unexpected end of file, expected ASCII");
    binary_ = TextScanner::equals_ignore_case(token, "BINARY");
    if (!binary_ && !TextScanner::equals_ignore_case(token, "ASCII")) {
      return scanner_.fail("expected ASCII or BINARY, found " + TextScanner::quote(token));
    }
    if (!scanner_.expect_keyword("DATASET")) return false;
    if (!scanner_.next_token(&token)) {
      return scanner_.fail("unexpected end of file, expected the dataset type");
    }
    if (!TextScanner::equals_ignore_case(token, "UNSTRUCTURED_GRID")) {
      return scanner_.fail("only DATASET UNSTRUCTURED_GRID is supported, found " +
                           TextScanner::quote(token));
    }
    // Line numbers mean nothing once binary data has begun.
    if (binary_) scanner_.report_byte_offsets(text_.data());
    return true;
  }

  // The values of an array in a binary file: `count` values of `type_name` that
  // start after the current line. Fails unless the type is readable and the values
  // fit in the rest of the file; on success *data points at the first one, and
  // end_binary() moves past the last.
  bool begin_binary(uint64_t count, std::string_view type_name, const char* what, BinaryType* type,
                    const char** data) {
    // After a SCALARS or other attribute line, whose words were read with the line.
    const bool line_read = line_read_;
    line_read_ = false;
    *type = binary_type(type_name);
    if (type->size == 0) {
      return scanner_.fail(std::string(what) + " of type " + TextScanner::quote(type_name) +
                           " cannot be read from a binary file");
    }
    if (!line_read && !trim_line(scanner_.rest_of_line()).empty()) {
      return scanner_.fail(std::string("unexpected text before the binary ") + what);
    }
    if (count > scanner_.remaining_bytes() / type->size) {
      scanner_.advance(scanner_.remaining_bytes());
      return scanner_.fail(std::string("the file ends inside the binary ") + what +
                           " (truncated file?)");
    }
    *data = scanner_.remaining_text().data();
    return true;
  }

  void end_binary(uint64_t count, const BinaryType& type) { scanner_.advance(count * type.size); }

  static std::string_view trim_line(std::string_view s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    return s;
  }

  // `count` integers into `out` (cleared), each in [min_value, max_value].
  bool read_binary_integers(uint64_t count, std::string_view type_name, const char* what,
                            int64_t min_value, int64_t max_value, std::vector<int64_t>* out) {
    BinaryType type;
    const char* data = nullptr;
    if (!begin_binary(count, type_name, what, &type, &data)) return false;
    out->clear();
    out->reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      int64_t value = 0;
      if (!binary_integer(data + i * type.size, type, &value) || value < min_value ||
          value > max_value) {
        const std::string text = value_text(data + i * type.size, type);
        end_binary(i, type);
        return scanner_.fail(std::string(what) + ": value " + std::to_string(i + 1) + " of " +
                             std::to_string(count) + ", " + text + ", is not an integer from " +
                             std::to_string(min_value) + " to " + std::to_string(max_value));
      }
      out->push_back(value);
    }
    end_binary(count, type);
    return true;
  }

  bool skip_binary(uint64_t count, std::string_view type_name, const char* what) {
    BinaryType type;
    const char* data = nullptr;
    if (!begin_binary(count, type_name, what, &type, &data)) return false;
    end_binary(count, type);
    return true;
  }

  bool parse_points() {
    uint64_t count = 0;
    std::string_view type;
    // "x y z " takes at least 6 bytes.
    if (!scanner_.read_count(&count, "point count", 6)) return false;
    if (seen_points_) return scanner_.fail("a second POINTS section");
    if (count >= kInvalidIndex) return scanner_.fail("too many points");
    if (!scanner_.next_token(&type))
      return scanner_.fail("unexpected end of file, expected a type");
    seen_points_ = true;
    std::vector<Vec3>& positions = out_->mesh.positions;
    if (binary_) {
      BinaryType binary;
      const char* data = nullptr;
      if (binary_type(type).kind != BinaryType::kFloat) {
        return scanner_.fail("binary POINTS of type " + TextScanner::quote(type) +
                             " are not supported (float or double)");
      }
      if (!begin_binary(3 * count, type, "POINTS", &binary, &data)) return false;
      positions.resize(count);
      for (uint64_t i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) {
          const double x = binary_real(data + (3 * i + k) * binary.size, binary);
          if (!std::isfinite(x)) {
            end_binary(3 * i + k, binary);
            return scanner_.fail("point " + std::to_string(i) +
                                 " has a coordinate that is not "
                                 "a finite number");
          }
          positions[i][k] = x;
        }
      }
      end_binary(3 * count, binary);
      return true;
    }
    positions.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      Vec3 p;
      if (!scanner_.read_double(&p.x, "x coordinate") ||
          !scanner_.read_double(&p.y, "y coordinate") ||
          !scanner_.read_double(&p.z, "z coordinate")) {
        return false;
      }
      positions.push_back(p);
    }
    return true;
  }

  bool read_vertex_index(uint32_t* vertex) {
    int64_t value = 0;
    if (!scanner_.read_int_in_range(&value, "point index", 0, int64_t{kInvalidIndex} - 1)) {
      return false;
    }
    *vertex = uint32_t(value);
    return true;
  }

  bool parse_cells() {
    uint64_t first = 0, second = 0;
    if (!scanner_.read_count(&first, "cell count", 2) ||
        !scanner_.read_count(&second, "cell list size", 2)) {
      return false;
    }
    if (seen_cells_) return scanner_.fail("a second CELLS section");
    seen_cells_ = true;
    std::string_view token;
    if (scanner_.peek_token(&token) && TextScanner::equals_ignore_case(token, "OFFSETS")) {
      return parse_cells_51(first, second);
    }
    const uint64_t cell_count = first, size = second;
    if (cell_count >= kInvalidIndex) return scanner_.fail("too many cells");
    if (binary_) return parse_cells_binary(cell_count, size);
    cell_starts_.reserve(cell_count + 1);
    cell_lines_.reserve(cell_count);
    connectivity_.reserve(size);
    cell_starts_.push_back(0);
    uint64_t used = 0;
    for (uint64_t c = 0; c < cell_count; ++c) {
      uint64_t point_count = 0;
      if (!scanner_.read_count(&point_count, "point count of a cell", 2)) return false;
      cell_lines_.push_back(line_number(scanner_.line()));
      used += point_count + 1;
      if (used > size) {
        return scanner_.fail("the cells use more than the " + std::to_string(size) +
                             " numbers announced after CELLS");
      }
      for (uint64_t k = 0; k < point_count; ++k) {
        uint32_t vertex = 0;
        if (!read_vertex_index(&vertex)) return false;
        connectivity_.push_back(vertex);
      }
      cell_starts_.push_back(connectivity_.size());
    }
    if (used != size) {
      return scanner_.fail("the cells use " + std::to_string(used) + " numbers, CELLS announced " +
                           std::to_string(size));
    }
    return true;
  }

  // "k i1 .. ik" for each cell, as 32-bit integers.
  bool parse_cells_binary(uint64_t cell_count, uint64_t size) {
    std::vector<int64_t> numbers;
    if (!read_binary_integers(size, "int", "CELLS", 0, int64_t{kInvalidIndex} - 1, &numbers)) {
      return false;
    }
    cell_starts_.reserve(cell_count + 1);
    connectivity_.reserve(size);
    cell_starts_.push_back(0);
    uint64_t at = 0;
    for (uint64_t c = 0; c < cell_count; ++c) {
      if (at >= size || uint64_t(numbers[at]) > size - at - 1) {
        return scanner_.fail("the cells use more than the " + std::to_string(size) +
                             " numbers announced after CELLS");
      }
      const uint64_t point_count = uint64_t(numbers[at++]);
      for (uint64_t k = 0; k < point_count; ++k) connectivity_.push_back(uint32_t(numbers[at++]));
      cell_starts_.push_back(connectivity_.size());
    }
    if (at != size) {
      return scanner_.fail("the cells use " + std::to_string(at) + " numbers, CELLS announced " +
                           std::to_string(size));
    }
    return true;
  }

  // After the offsets: the last one ends the connectivity; its keyword and type follow.
  bool end_offsets(uint64_t size, std::string_view* type) {
    if (!cell_starts_.empty() && cell_starts_.back() != size) {
      return scanner_.fail("the last offset is " + std::to_string(cell_starts_.back()) +
                           ", CELLS announced " + std::to_string(size) + " indices");
    }
    if (cell_starts_.empty()) cell_starts_.push_back(0);
    if (!scanner_.expect_keyword("CONNECTIVITY") || !scanner_.next_token(type)) {
      return scanner_.fail("unexpected end of file, expected the CONNECTIVITY type");
    }
    return true;
  }

  bool parse_cells_51(uint64_t offset_count, uint64_t size) {
    std::string_view type;
    if (!scanner_.expect_keyword("OFFSETS") || !scanner_.next_token(&type)) {
      return scanner_.fail("unexpected end of file, expected the OFFSETS type");
    }
    if (offset_count >= kInvalidIndex) return scanner_.fail("too many cells");
    if (binary_) return parse_cells_51_binary(offset_count, size, type);
    cell_starts_.reserve(offset_count);
    for (uint64_t i = 0; i < offset_count; ++i) {
      int64_t offset = 0;
      const int64_t previous = cell_starts_.empty() ? 0 : int64_t(cell_starts_.back());
      if (!scanner_.read_int_in_range(&offset, "offset", previous, int64_t(size))) return false;
      if (i == 0 && offset != 0) return scanner_.fail("the first offset must be 0");
      cell_starts_.push_back(uint64_t(offset));
    }
    if (!end_offsets(size, &type)) return false;
    connectivity_.reserve(size);
    cell_lines_.reserve(cell_starts_.size() - 1);
    size_t cell = 0;
    for (uint64_t i = 0; i < size; ++i) {
      uint32_t vertex = 0;
      if (!read_vertex_index(&vertex)) return false;
      while (cell + 1 < cell_starts_.size() && cell_starts_[cell] == i) {
        cell_lines_.push_back(line_number(scanner_.line()));
        ++cell;
      }
      connectivity_.push_back(vertex);
    }
    while (cell_lines_.size() + 1 < cell_starts_.size()) {
      cell_lines_.push_back(line_number(scanner_.line()));
    }
    return true;
  }

  bool parse_cells_51_binary(uint64_t offset_count, uint64_t size, std::string_view type) {
    std::vector<int64_t> numbers;
    if (!read_binary_integers(offset_count, type, "OFFSETS", 0, int64_t(size), &numbers)) {
      return false;
    }
    for (uint64_t i = 0; i < offset_count; ++i) {
      if ((i == 0 && numbers[i] != 0) || (i > 0 && numbers[i] < numbers[i - 1])) {
        return scanner_.fail("the offsets must start at 0 and never decrease (offset " +
                             std::to_string(i) + ")");
      }
      cell_starts_.push_back(uint64_t(numbers[i]));
    }
    if (!end_offsets(size, &type)) return false;
    if (!read_binary_integers(size, type, "CONNECTIVITY", 0, int64_t{kInvalidIndex} - 1,
                              &numbers)) {
      return false;
    }
    connectivity_.assign(numbers.begin(), numbers.end());
    return true;
  }

  size_t cell_count() const { return cell_starts_.empty() ? 0 : cell_starts_.size() - 1; }

  bool parse_cell_types() {
    uint64_t count = 0;
    if (!scanner_.read_count(&count, "cell type count", 2)) return false;
    if (!seen_cells_) return scanner_.fail("CELL_TYPES before CELLS");
    if (seen_types_) return scanner_.fail("a second CELL_TYPES section");
    if (count != cell_count()) {
      return scanner_.fail("CELL_TYPES has " + std::to_string(count) + " entries for " +
                           std::to_string(cell_count()) + " cells");
    }
    seen_types_ = true;
    if (binary_) {
      return read_binary_integers(count, "int", "CELL_TYPES", std::numeric_limits<int32_t>::min(),
                                  std::numeric_limits<int32_t>::max(), &cell_types_);
    }
    cell_types_.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      int64_t type = 0;
      if (!scanner_.read_int(&type, "cell type")) return false;
      cell_types_.push_back(type);
    }
    return true;
  }

  bool start_data_section(bool cells) {
    uint64_t count = 0;
    if (!scanner_.read_count(&count, cells ? "cell data count" : "point data count", 0)) {
      return false;
    }
    const uint64_t expected = cells ? cell_count() : out_->mesh.positions.size();
    if (count != expected) {
      return scanner_.fail(std::string(cells ? "CELL_DATA" : "POINT_DATA") + " has " +
                           std::to_string(count) + " entries for " + std::to_string(expected) +
                           (cells ? " cells" : " points"));
    }
    data_section_ = cells ? DataSection::kCells : DataSection::kPoints;
    section_count_ = count;
    section_arrays_ = 0;
    section_line_ = scanner_.line();
    return true;
  }

  // Bounds value_count = tuples * components by what the rest of the file holds.
  bool check_value_count(uint64_t tuples, uint64_t components, uint64_t* value_count) {
    if (components != 0 && tuples > scanner_.remaining_bytes() / components) {
      return scanner_.fail("the array is larger than the rest of the file can hold");
    }
    *value_count = tuples * components;
    return true;
  }

  // Whether a cell array other than "material" is read as the material: a name
  // vtk_material_rank() knows, better than what was read, of an integer type.
  bool takes_material(std::string_view name, std::string_view type, uint64_t components) const {
    const int rank = vtk_material_rank(name);
    if (rank <= 0 || rank >= material_rank_ || components != 1) return false;
    return integer_type(type);
  }

  // The material array, of rank `rank` (vtk_material_rank): replaces one of a worse
  // rank read before.
  bool read_materials(uint64_t count, std::string_view type, int rank) {
    material_rank_ = rank;
    cell_materials_.clear();
    if (binary_) {
      std::vector<int64_t> values;
      if (!read_binary_integers(count, type, "material array", std::numeric_limits<int32_t>::min(),
                                std::numeric_limits<int32_t>::max(), &values)) {
        return false;
      }
      cell_materials_.assign(values.begin(), values.end());
      has_materials_ = true;
      return true;
    }
    cell_materials_.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      int64_t material = 0;
      if (!scanner_.read_integral(&material, "material id", std::numeric_limits<int32_t>::min(),
                                  std::numeric_limits<int32_t>::max())) {
        return false;
      }
      cell_materials_.push_back(int32_t(material));
    }
    has_materials_ = true;
    return true;
  }

  // SCALARS, VECTORS and the other attributes of a POINT_DATA or CELL_DATA section.
  bool parse_attribute(std::string_view keyword) {
    auto is = [&](const char* word) { return TextScanner::equals_ignore_case(keyword, word); };
    uint64_t components = 0;
    size_t header_words = 0;
    if (is("SCALARS")) {
      header_words = 2;
    } else if (is("COLOR_SCALARS") || is("LOOKUP_TABLE") || is("TEXTURE_COORDINATES")) {
      header_words = is("TEXTURE_COORDINATES") ? 3 : 2;
    } else if (is("VECTORS") || is("NORMALS")) {
      header_words = 2;
      components = 3;
    } else if (is("TENSORS") || is("TENSORS6")) {
      header_words = 2;
      components = is("TENSORS") ? 9 : 6;
    } else if (is("GLOBAL_IDS") || is("PEDIGREE_IDS")) {
      header_words = 2;
      components = 1;
    } else {
      return scanner_.fail("unknown keyword " + TextScanner::quote(keyword));
    }
    if (data_section_ == DataSection::kNone) {
      return scanner_.fail(TextScanner::quote(keyword) + " outside POINT_DATA or CELL_DATA");
    }
    const size_t line = scanner_.line();
    const std::vector<std::string_view> words = split(scanner_.rest_of_line());
    line_read_ = true;
    if (words.size() < header_words) {
      return scanner_.fail_at_line(line, "incomplete " + std::string(keyword) + " line");
    }
    ++section_arrays_;
    auto number_word = [&](size_t i, uint64_t max_value, uint64_t* value) {
      const std::string_view word = words[i];
      const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), *value);
      if (error != std::errc() || end != word.data() + word.size() || *value < 1 ||
          *value > max_value) {
        return scanner_.fail_at_line(
            line, "expected a count from 1 to " + std::to_string(max_value) + " in the " +
                      std::string(keyword) + " line, found " + TextScanner::quote(word));
      }
      return true;
    };
    uint64_t tuples = section_count_;
    if (data_section_ == DataSection::kCells && !is("LOOKUP_TABLE"))
      cell_arrays_.emplace_back(words[0]);
    if (is("SCALARS")) {
      components = 1;
      if (words.size() > 2 && !number_word(2, 4, &components)) return false;
      std::string_view token;
      if (scanner_.peek_token(&token) && TextScanner::equals_ignore_case(token, "LOOKUP_TABLE")) {
        scanner_.next_token(&token);
        scanner_.rest_of_line();
      }
      if (data_section_ == DataSection::kCells && words[0] == kMaterialArray) {
        if (components != 1) return scanner_.fail_at_line(line, "material must have 1 component");
        return read_materials(section_count_, words[1], 0);
      }
      if (data_section_ == DataSection::kCells && takes_material(words[0], words[1], components))
        return read_materials(section_count_, words[1], vtk_material_rank(words[0]));
    } else if (is("COLOR_SCALARS")) {
      if (!number_word(1, 4, &components)) return false;
    } else if (is("LOOKUP_TABLE")) {
      // A table definition: "LOOKUP_TABLE name size" and size RGBA entries.
      if (!number_word(1, std::numeric_limits<uint32_t>::max(), &tuples)) return false;
      components = 4;
    } else if (is("TEXTURE_COORDINATES")) {
      if (!number_word(1, 3, &components)) return false;
    }
    uint64_t value_count = 0;
    if (!check_value_count(tuples, components, &value_count)) return false;
    if (!binary_) return scanner_.skip_numbers(value_count, std::string(keyword).c_str());
    // Colours are unsigned chars in a binary file; the others name their type.
    const bool colours = is("COLOR_SCALARS") || is("LOOKUP_TABLE");
    const std::string_view type =
        colours ? "unsigned_char" : words[is("TEXTURE_COORDINATES") ? 2 : 1];
    if (is("TEXTURE_COORDINATES") && words.size() < 3) {
      return scanner_.fail_at_line(line, "incomplete TEXTURE_COORDINATES line");
    }
    return skip_binary(value_count, type, std::string(keyword).c_str());
  }

  // "FIELD name n" then n arrays "name components tuples type" and their values.
  bool parse_field() {
    std::string_view field_name;
    uint64_t array_count = 0;
    if (!scanner_.next_token(&field_name)) {
      return scanner_.fail("unexpected end of file, expected the FIELD name");
    }
    if (!scanner_.read_count(&array_count, "field array count", 8)) return false;
    ++section_arrays_;
    for (uint64_t a = 0; a < array_count; ++a) {
      std::string_view array_name, type;
      uint64_t components = 0, tuples = 0, value_count = 0;
      // VTK 9 follows each array with a METADATA block.
      if (scanner_.peek_token(&array_name) &&
          TextScanner::equals_ignore_case(array_name, "METADATA")) {
        scanner_.next_token(&array_name);
        skip_metadata();
      }
      if (!scanner_.next_token(&array_name)) {
        return scanner_.fail("unexpected end of file, expected a field array");
      }
      if (data_section_ == DataSection::kCells) cell_arrays_.emplace_back(array_name);
      if (!scanner_.read_count(&components, "component count", 1) ||
          !scanner_.read_count(&tuples, "tuple count", 0) || !scanner_.next_token(&type)) {
        return scanner_.failed() ? false : scanner_.fail("unexpected end of file, expected a type");
      }
      const bool strings = TextScanner::equals_ignore_case(type, "string") ||
                           TextScanner::equals_ignore_case(type, "utf8_string");
      if (data_section_ == DataSection::kCells && components == 1 && !strings &&
          (array_name == kMaterialArray || takes_material(array_name, type, components))) {
        if (tuples != section_count_) {
          return scanner_.fail("the material array has " + std::to_string(tuples) + " values for " +
                               std::to_string(section_count_) + " cells");
        }
        if (!read_materials(tuples, type, vtk_material_rank(array_name))) return false;
        continue;
      }
      if (!check_value_count(tuples, components, &value_count)) return false;
      // The names TetLOD writes (kVtkNameTagArray) in the dataset's field data.
      const bool dataset = data_section_ == DataSection::kNone && components == 1;
      if (dataset && strings && array_name == kVtkNameArray) {
        if (!read_strings(value_count, &names_)) return false;
      } else if (dataset && array_name == kVtkNameTagArray && integer_type(type)) {
        if (!read_integers(value_count, type, &name_tags_)) return false;
      } else if (dataset && array_name == kVtkNameDimArray && integer_type(type)) {
        if (!read_integers(value_count, type, &name_dims_)) return false;
      } else if (strings) {
        if (!read_strings(value_count, nullptr)) return false;
      } else if (binary_ ? !skip_binary(value_count, type, "field array")
                         : !scanner_.skip_numbers(value_count, "field array")) {
        return false;
      }
    }
    return true;
  }

  // The values of a string array (VTK writes names and records so, as the Exodus
  // reader's QA and information records): as text, one string a line (spaces and
  // other characters %-encoded), empty lines for empty strings; in a binary file,
  // each string after its length, big-endian, in 1, 2, 4 or 8 bytes as the first
  // byte's two high bits say (3, 2, 1, 0), the length in the remaining bits. Into
  // `out` (decoded), or skipped when it is null.
  bool read_strings(uint64_t count, std::vector<std::string>* out) {
    if (!trim_line(scanner_.rest_of_line()).empty()) {
      return scanner_.fail("unexpected text after the string array's line");
    }
    for (uint64_t i = 0; i < count; ++i) {
      const std::string_view rest = scanner_.remaining_text();
      size_t header = 0;
      uint64_t length = 0;
      if (!rest.empty() && binary_) {
        const unsigned kind = uint8_t(rest[0]) >> 6;
        header = kind == 3 ? 1 : kind == 2 ? 2 : kind == 1 ? 4 : 8;
        if (header <= rest.size()) {
          length = value_bits(rest.data(), header, true);
          if (kind != 0) length &= (uint64_t{1} << (8 * header - 2)) - 1;
        }
      }
      if (rest.empty() || header > rest.size() || length > rest.size() - header) {
        scanner_.advance(rest.size());
        return scanner_.fail("the file ends inside a string array (truncated file?)");
      }
      if (binary_) {
        if (out) out->emplace_back(rest.substr(header, length));
        scanner_.advance(header + length);
      } else {
        const std::string_view line = scanner_.rest_of_line();
        if (out) out->push_back(decode_legacy_string(line));
      }
    }
    return true;
  }

  // %XX as the byte XX (VTK's encoding of spaces and other bytes in text files).
  static std::string decode_legacy_string(std::string_view text) {
    std::string out;
    auto hex = [](char c) {
      return c >= '0' && c <= '9'   ? c - '0'
             : c >= 'A' && c <= 'F' ? c - 'A' + 10
             : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                    : -1;
    };
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '%' && i + 2 < text.size() && hex(text[i + 1]) >= 0 && hex(text[i + 2]) >= 0) {
        out.push_back(char(hex(text[i + 1]) * 16 + hex(text[i + 2])));
        i += 2;
      } else {
        out.push_back(text[i]);
      }
    }
    return out;
  }

  // `count` integers of `type` (ASCII: any integer; binary: the type's values).
  bool read_integers(uint64_t count, std::string_view type, std::vector<int64_t>* out) {
    out->clear();
    if (binary_) {
      return read_binary_integers(count, type, "integer array", std::numeric_limits<int64_t>::min(),
                                  std::numeric_limits<int64_t>::max(), out);
    }
    out->reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      int64_t value = 0;
      if (!scanner_.read_int(&value, "integer array value")) return false;
      out->push_back(value);
    }
    return true;
  }

  // An integer type of the legacy format (vtktypeint8 ... vtktypeuint64 too).
  static bool integer_type(std::string_view type) {
    for (const char* name : {"char", "unsigned_char", "short", "unsigned_short", "int",
                             "unsigned_int", "long", "unsigned_long", "vtkIdType"}) {
      if (TextScanner::equals_ignore_case(type, name)) return true;
    }
    return TextScanner::equals_ignore_case(type.substr(0, std::min<size_t>(type.size(), 10)),
                                           "vtktypeint") ||
           TextScanner::equals_ignore_case(type.substr(0, std::min<size_t>(type.size(), 11)),
                                           "vtktypeuint");
  }

  // VTK 9 writes "METADATA" and information lines up to an empty line.
  void skip_metadata() {
    scanner_.rest_of_line();
    while (scanner_.remaining_bytes() > 0) {
      const std::vector<std::string_view> words = split(scanner_.rest_of_line());
      if (words.empty()) break;
    }
  }

  bool build_tets() {
    if (!seen_points_) return scanner_.fail("no POINTS section");
    if (!seen_cells_) return scanner_.fail("no CELLS section");
    if (!seen_types_) return scanner_.fail("no CELL_TYPES section");
    TetMesh& mesh = out_->mesh;
    std::vector<uint64_t> counts_by_type(128, 0);
    SurfaceElements surface;
    for (size_t c = 0; c < cell_count(); ++c) {
      const uint64_t size = cell_starts_[c + 1] - cell_starts_[c];
      const int64_t type = cell_types_[c];
      if (type >= 0 && type < 128) ++counts_by_type[size_t(type)];
      bool tet = false;
      const bool tet_size = vtk_tet_cell(type, size, &tet);
      const int triangle = vtk_triangle_points(type);
      if (is_vtk_surface_cell(type)) surface.count();
      if (!tet && triangle < 0) continue;
      if (tet ? !tet_size : triangle > 0 ? size != uint64_t(triangle) : size < 3) {
        return scanner_.fail_at_line(binary_ ? 0 : cell_lines_[c],
                                     "cell " + std::to_string(c) + " of type " +
                                         std::to_string(type) + " has " + std::to_string(size) +
                                         " points");
      }
      const uint32_t* v = connectivity_.data() + cell_starts_[c];
      for (int k = 0; k < (tet ? 4 : 3); ++k) {
        if (v[k] >= mesh.positions.size()) {
          return scanner_.fail_at_line(binary_ ? 0 : cell_lines_[c],
                                       "cell " + std::to_string(c) + " uses point " +
                                           std::to_string(v[k]) + ", but there are only " +
                                           std::to_string(mesh.positions.size()) +
                                           " points (numbered from 0)");
        }
      }
      if (!tet) {
        if (has_materials_ && cell_materials_[c] >= 1) {
          surface.add_triangle(cell_materials_[c], mesh.positions[v[0]], mesh.positions[v[1]],
                               mesh.positions[v[2]]);
        }
        continue;
      }
      mesh.tets.push_back({v[0], v[1], v[2], v[3]});
      mesh.materials.push_back(has_materials_ ? cell_materials_[c] : 0);
      if (!binary_) out_->tet_lines.push_back(cell_lines_[c]);
    }
    surface.finish(out_);
    add_vtk_cell_notes(counts_by_type, out_);
    if (has_materials_) finish_vtk_materials(material_rank_, out_);
    if (!has_materials_) out_->notes.push_back(no_material_note(cell_arrays_));
    apply_vtk_names(name_tags_, name_dims_, names_, out_);
    return true;
  }

  std::string_view text_;
  std::vector<int64_t> name_tags_;  // the field data's kVtkNameTagArray
  std::vector<int64_t> name_dims_;  // kVtkNameDimArray
  std::vector<std::string> names_;  // and kVtkNameArray
  TextScanner scanner_;
  ParsedMesh* out_;
  bool binary_ = false;     // BINARY: arrays as big-endian values
  bool line_read_ = false;  // the line before the next binary array is already read
  bool seen_points_ = false;
  bool seen_cells_ = false;
  bool seen_types_ = false;
  std::vector<uint64_t> cell_starts_;  // cell c is connectivity_[starts[c], starts[c + 1])
  std::vector<uint32_t> connectivity_;
  std::vector<uint32_t> cell_lines_;
  std::vector<int64_t> cell_types_;
  DataSection data_section_ = DataSection::kNone;
  uint64_t section_count_ = 0;
  size_t section_arrays_ = 0;
  size_t section_line_ = 0;
  bool has_materials_ = false;
  int material_rank_ = 1 << 30;  // of the array in cell_materials_ (none yet: worst)
  std::vector<int32_t> cell_materials_;
  std::vector<std::string> cell_arrays_;  // names of the cell arrays, in file order
};

}  // namespace

bool is_vtk_surface_cell(int64_t type) {
  switch (type) {
    case 5:   // triangle
    case 6:   // triangle strip
    case 7:   // polygon
    case 8:   // pixel
    case 9:   // quad
    case 22:  // quadratic triangle
    case 23:  // quadratic quad
    case 28:  // biquadratic quad
    case 30:  // quadratic-linear quad
    case 34:  // biquadratic triangle
    case 36:  // quadratic polygon
    case 61:  // higher-order triangle (generic)
    case 62:  // higher-order quadrilateral (generic)
    case 63:  // higher-order polygon (generic)
    case 69:  // Lagrange triangle
    case 70:  // Lagrange quadrilateral
    case 76:  // Bezier triangle
    case 77:  // Bezier quadrilateral
      return true;
    default:
      return false;
  }
}

bool vtk_tet_cell(int64_t type, uint64_t size, bool* is_tet) {
  *is_tet = type == kVtkTetra || type == kVtkQuadraticTetra || type == kVtkLagrangeTetra ||
            type == kVtkBezierTetra;
  if (type == kVtkTetra) return size == 4;
  if (type == kVtkQuadraticTetra) return size == 10;
  if (!*is_tet) return false;
  for (uint64_t n = 1; n <= 64; ++n) {  // order n: (n + 1)(n + 2)(n + 3) / 6 points
    const uint64_t points = (n + 1) * (n + 2) * (n + 3) / 6;
    if (points == size) return true;
    if (points > size) break;
  }
  return false;
}

int vtk_triangle_points(int64_t type) {
  switch (type) {
    case 5:
      return 3;
    case 22:
      return 6;
    case 34:
      return 7;
    case 69:  // Lagrange triangle
    case 76:  // Bezier triangle
      return 0;
    default:
      return -1;
  }
}

void SurfaceElements::finish(ParsedMesh* out) {
  out->surface_elements_not_kept = elements_;
  for (auto& [tag, triangles] : triangles_) {
    InputSurfaceGroup group;
    group.tag = tag;
    group.triangles = std::move(triangles);
    out->surface_groups.push_back(std::move(group));
  }
  triangles_.clear();
}

void add_vtk_cell_notes(const std::vector<uint64_t>& counts_by_type, ParsedMesh* out) {
  // The types a note below names (`said`); the rest are named by their number.
  std::vector<bool> said(counts_by_type.size(), false);
  auto count = [&](std::initializer_list<int> types) {
    uint64_t n = 0;
    for (int t : types) {
      if (size_t(t) >= counts_by_type.size()) continue;
      n += counts_by_type[size_t(t)];
      said[size_t(t)] = true;
    }
    return n;
  };
  const struct {
    const char* name;
    uint64_t n;
  } skipped[] = {{"hexahedra", count({11, 12, 25, 29, 33, 67, 72, 79})},
                 {"wedges", count({13, 26, 31, 32, 65, 73, 80})},
                 {"pyramids", count({14, 27, 37, 66, 74, 81})},
                 {"polyhedra", count({15, 16, 41, 42})},
                 {"higher-order tetrahedra of the generic kind", count({64})}};
  std::string list;
  for (const auto& s : skipped)
    if (s.n > 0) list += (list.empty() ? "" : ", ") + std::to_string(s.n) + " " + s.name;
  if (!list.empty()) {
    out->notes.push_back("skipped " + list +
                         ": TetLOD reads tetrahedra only, so a region meshed with other cells is "
                         "not in the mesh");
  }
  if (const uint64_t quadratic = count({int(kVtkQuadraticTetra)}); quadratic > 0) {
    out->notes.push_back(std::to_string(quadratic) +
                         " quadratic (10-node) tetrahedra were read as 4-node ones (by their "
                         "corners; their mid-edge points are dropped)");
  }
  if (const uint64_t high = count({int(kVtkLagrangeTetra), int(kVtkBezierTetra)}); high > 0) {
    out->notes.push_back(std::to_string(high) +
                         " Lagrange or Bezier tetrahedra were read as 4-node ones (by their "
                         "corners; their other points are dropped)");
  }
  // Vertices, poly-vertices, lines, poly-lines and higher-order lines.
  if (const uint64_t lines = count({1, 2, 3, 4, 21, 35, 60, 68, 75}); lines > 0) {
    out->notes.push_back(std::to_string(lines) +
                         " vertex and line cells are not kept: TetLOD keeps the tetrahedra, and "
                         "the triangles of surface groups");
  }
  // Any other type (one VTK may add, or none at all) but tets and the surface cells
  // (counted apart): named by its number.
  std::string others;
  for (size_t type = 0; type < counts_by_type.size(); ++type) {
    if (counts_by_type[type] == 0 || said[type] || int64_t(type) == kVtkTetra ||
        is_vtk_surface_cell(int64_t(type)))
      continue;
    others += (others.empty() ? "" : ", ") + std::string("type ") + std::to_string(type) + ": " +
              std::to_string(counts_by_type[type]);
  }
  if (!others.empty()) {
    out->notes.push_back("cells of types TetLOD does not know are not kept (" + others + ")");
  }
}

std::vector<VtkNameRow> vtk_name_rows(const TetMesh& mesh, const SurfaceGroups* surfaces,
                                      const std::vector<MaterialName>* names) {
  std::vector<VtkNameRow> rows;
  auto add = [&](int32_t tag, int32_t dim, std::string name) {
    std::replace(name.begin(), name.end(), '\0', '_');
    rows.push_back({tag, dim, std::move(name)});
  };
  if (names) {
    std::vector<int32_t> present = mesh.materials;
    std::sort(present.begin(), present.end());
    for (const MaterialName& m : *names)
      if (!m.name.empty() && std::binary_search(present.begin(), present.end(), m.material))
        add(m.material, 3, m.name);
  }
  if (surfaces)
    for (const SurfaceGroup& g : surfaces->groups) add(g.tag, 2, g.name);
  return rows;
}

void apply_vtk_names(const std::vector<int64_t>& tags, const std::vector<int64_t>& dims,
                     const std::vector<std::string>& names, ParsedMesh* out) {
  if (tags.empty() && names.empty()) return;
  if (tags.size() != names.size()) {
    out->notes.push_back("the field data's " + std::string(kVtkNameTagArray) + " and " +
                         std::string(kVtkNameArray) + " arrays have " +
                         std::to_string(tags.size()) + " and " + std::to_string(names.size()) +
                         " values: their names are not read");
    return;
  }
  const bool has_dims = dims.size() == tags.size();
  if (!dims.empty() && !has_dims) {
    out->notes.push_back("the field data's " + std::string(kVtkNameDimArray) + " array has " +
                         std::to_string(dims.size()) + " values for " +
                         std::to_string(tags.size()) +
                         " names: each name goes to the material "
                         "and the surface group of its tag");
  }
  std::vector<int32_t> present = out->mesh.materials;
  std::sort(present.begin(), present.end());
  present.erase(std::unique(present.begin(), present.end()), present.end());
  // The groups by tag (a reader makes one group a tag).
  std::map<int32_t, InputSurfaceGroup*> groups;
  for (InputSurfaceGroup& g : out->surface_groups) groups[g.tag] = &g;
  std::map<int32_t, std::string> material_names;  // the first name of each
  for (size_t i = 0; i < tags.size(); ++i) {
    if (names[i].empty() || tags[i] < std::numeric_limits<int32_t>::min() ||
        tags[i] > std::numeric_limits<int32_t>::max())
      continue;
    const int32_t tag = int32_t(tags[i]);
    const bool material =
        (!has_dims || dims[i] == 3) && std::binary_search(present.begin(), present.end(), tag);
    const auto group = has_dims && dims[i] != 2 ? groups.end() : groups.find(tag);
    if (!material && group == groups.end()) continue;
    const std::string name = valid_utf8(names[i]);
    if (material) material_names.emplace(tag, name);
    if (group != groups.end() && group->second->name.empty()) group->second->name = name;
  }
  // The VTK readers give no other names: these are the file's, sorted by material.
  for (auto& [material, name] : material_names)
    out->material_names.push_back({material, std::move(name)});
}

std::string no_material_note(const std::vector<std::string>& arrays) {
  std::string names, known;
  constexpr size_t kListed = 10;  // a hostile file may have millions
  for (size_t i = 0; i < std::min(arrays.size(), kListed); ++i)
    names += (names.empty() ? "'" : ", '") + arrays[i] + "'";
  if (arrays.size() > kListed) names += " and " + std::to_string(arrays.size() - kListed) + " more";
  for (std::string_view k : kVtkMaterialNames)
    known += (known.empty() ? "'" : ", '") + std::string(k) + "'";
  if (arrays.empty())
    return "the file has no cell arrays, so every tet is material 0 (the material is read "
           "from " +
           known + ")";
  return "no cell array is read as the material, so every tet is material 0 (the file's "
         "cell arrays: " +
         names + "; the material is read from " + known +
         ", the first found, the others only if they hold integers)";
}

Status parse_vtk_legacy(std::string_view text, const std::string& name, ParsedMesh* out) {
  VtkLegacyParser parser(text, name, out);
  return parser.parse();
}

namespace {

// The values of a legacy file's lines: as text, a line of numbers; in a BINARY file,
// their big-endian bytes (32-bit integers as "int", double as "double"), the arrays' lines
// of keywords staying text, each on a line of its own after the data before it.
class LegacyRecords {
 public:
  LegacyRecords(std::string* out, bool binary) : out_(out), binary_(binary) {}
  template <typename... Values>
  void record(Values... values) {
    if (binary_) {
      (append_binary(out_, values, true), ...);
    } else {
      append_line(out_, values...);
    }
  }
  // A keyword line after an array's values.
  void keywords(std::string_view line) {
    if (binary_ && data_before_) out_->push_back('\n');
    out_->append(line);
    data_before_ = true;
  }

 private:
  std::string* out_;
  bool binary_;
  bool data_before_ = false;
};

// A string value of a legacy text file, as VTK writes it: every byte but the printable
// ASCII ones other than '%' as %XX.
std::string encode_legacy_string(std::string_view text) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (char c : text) {
    const auto byte = uint8_t(c);
    if (byte > 0x20 && byte < 0x7f && c != '%') {
      out.push_back(c);
    } else {
      out += {'%', kHex[byte >> 4], kHex[byte & 15]};
    }
  }
  return out;
}

}  // namespace

void write_vtk_legacy(const TetMesh& mesh, const SurfaceGroups* surfaces,
                      const std::vector<MaterialName>* names, bool binary, std::string* out) {
  const size_t tet_count = mesh.tet_count();
  size_t triangle_count = 0;
  if (surfaces) {
    for (const SurfaceGroup& group : surfaces->groups) triangle_count += group.triangles.size();
  }
  const size_t cell_count = tet_count + triangle_count;
  out->reserve(out->size() + mesh.vertex_count() * (binary ? 24 : 64) +
               tet_count * (binary ? 40 : 64) + triangle_count * (binary ? 36 : 48));
  LegacyRecords r(out, binary);
  out->append(binary ? "# vtk DataFile Version 3.0\nTetLOD tetrahedral mesh\nBINARY\n"
                     : "# vtk DataFile Version 3.0\nTetLOD tetrahedral mesh\nASCII\n");
  auto line = [](const char* keyword, size_t count, const char* after) {
    std::string text = keyword;
    append_number(&text, uint64_t(count));
    return text + after;
  };
  out->append("DATASET UNSTRUCTURED_GRID\n");
  r.keywords(line("POINTS ", mesh.vertex_count(), " double\n"));
  for (const Vec3& p : mesh.positions) r.record(p.x, p.y, p.z);
  std::string cells = line("CELLS ", cell_count, " ");
  append_line(&cells, uint64_t(5 * tet_count + 4 * triangle_count));
  r.keywords(cells);
  for (const Tet& tet : mesh.tets) r.record(int32_t{4}, tet[0], tet[1], tet[2], tet[3]);
  // The surface groups' triangles after the tets, as Gmsh's VTK export writes physical
  // surfaces: cell type 5, the group's tag in the material array.
  auto for_each_triangle = [&](auto visit) {
    if (!surfaces) return;
    for (const SurfaceGroup& group : surfaces->groups)
      for (uint32_t i : group.triangles) visit(surfaces->surface[i].v, group.tag);
  };
  for_each_triangle(
      [&](const std::array<uint32_t, 3>& v, int32_t) { r.record(int32_t{3}, v[0], v[1], v[2]); });
  r.keywords(line("CELL_TYPES ", cell_count, "\n"));
  for (size_t t = 0; t < tet_count; ++t) r.record(int32_t{10});
  for (size_t t = 0; t < triangle_count; ++t) r.record(int32_t{5});
  // The names of the materials and groups (vtk_name_rows()) as the dataset's field data,
  // after the cells: VTK reads a dataset's FIELD anywhere before CELL_DATA, but Gmsh's
  // reader (4.8) refuses any line between DATASET and POINTS.
  const std::vector<VtkNameRow> rows = vtk_name_rows(mesh, surfaces, names);
  if (!rows.empty()) {
    r.keywords("FIELD FieldData 3\n" + std::string(kVtkNameTagArray) + " 1 " +
               std::to_string(rows.size()) + " int\n");
    for (const VtkNameRow& row : rows) r.record(row.tag);
    r.keywords(std::string(kVtkNameDimArray) + " 1 " + std::to_string(rows.size()) + " int\n");
    for (const VtkNameRow& row : rows) r.record(row.dim);
    r.keywords(std::string(kVtkNameArray) + " 1 " + std::to_string(rows.size()) + " string\n");
    for (const VtkNameRow& row : rows) {
      if (!binary) {
        out->append(encode_legacy_string(row.name));
        out->push_back('\n');
        continue;
      }
      // Its length first, in 1, 2, 4 or 8 bytes, the two high bits saying which.
      const uint64_t n = row.name.size();
      if (n < (uint64_t{1} << 6)) {
        append_binary(out, uint8_t(0xc0 | n), true);
      } else if (n < (uint64_t{1} << 14)) {
        append_binary(out, uint16_t(0x8000 | n), true);
      } else if (n < (uint64_t{1} << 30)) {
        append_binary(out, uint32_t(0x40000000 | n), true);
      } else {
        append_binary(out, n, true);
      }
      out->append(row.name);
    }
  }
  r.keywords(line("CELL_DATA ", cell_count, "\nSCALARS material int 1\nLOOKUP_TABLE default\n"));
  for (int32_t material : mesh.materials) r.record(material);
  for_each_triangle([&](const std::array<uint32_t, 3>&, int32_t tag) { r.record(tag); });
  // The stretch as a FIELD array: VTK's legacy reader takes only the first SCALARS of
  // a section unless told to read them all, but every FIELD array. A triangle takes
  // the stretch of its tet (on its back side), so that ParaView colours it as the face
  // it lies on and its range is the tets'.
  r.keywords(line("FIELD FieldData 1\nstretch 1 ", cell_count, " double\n"));
  std::vector<double> stretch(tet_count);
  for (size_t t = 0; t < tet_count; ++t) stretch[t] = tet_shape(mesh, mesh.tets[t]).stretch;
  for (double d : stretch) r.record(d);
  if (surfaces) {
    for (const SurfaceGroup& group : surfaces->groups)
      for (uint32_t i : group.triangles) r.record(stretch[surfaces->surface[i].tet]);
  }
  if (binary) out->push_back('\n');
}

}  // namespace tetlod::io
