// VTK XML unstructured grids (.vtu), as in "VTK File Formats", section "XML File
// Formats" (https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html).
// The reader is a minimal XML tokenizer: tags, attributes, comments and processing
// instructions; the numbers of an ASCII DataArray are read with a TextScanner over
// its content so that messages keep file line numbers. Binary arrays are read too:
// inline (format="binary", base64) and appended raw data (format="appended" with
// <AppendedData encoding="raw">), each a header of header_type (UInt32 or UInt64)
// and the values in byte_order, optionally in blocks compressed with zlib
// (compressor="vtkZLibDataCompressor"), as ParaView and meshio write them.
#include <zlib.h>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include "core/io/binary_values.h"
#include "core/io/mesh_formats.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"
#include "core/metrics.h"

namespace tetlod::io {
namespace {

struct Attribute {
  std::string_view name;
  std::string_view value;
};

struct Tag {
  std::string_view name;
  bool closing = false;
  bool self_closing = false;
  std::vector<Attribute> attributes;

  std::string_view attribute(std::string_view key) const {
    for (const Attribute& a : attributes) {
      if (a.name == key) return a.value;
    }
    return {};
  }
};

bool starts_with(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

bool is_xml_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// The value type of a DataArray's type attribute.
BinaryType vtu_type(std::string_view name) {
  struct Entry {
    const char* name;
    BinaryType type;
  };
  static constexpr Entry kTypes[] = {
      {"Int8", {BinaryType::kSigned, 1}},   {"UInt8", {BinaryType::kUnsigned, 1}},
      {"Int16", {BinaryType::kSigned, 2}},  {"UInt16", {BinaryType::kUnsigned, 2}},
      {"Int32", {BinaryType::kSigned, 4}},  {"UInt32", {BinaryType::kUnsigned, 4}},
      {"Int64", {BinaryType::kSigned, 8}},  {"UInt64", {BinaryType::kUnsigned, 8}},
      {"Float32", {BinaryType::kFloat, 4}}, {"Float64", {BinaryType::kFloat, 8}}};
  for (const Entry& e : kTypes)
    if (name == e.name) return e.type;
  return {};
}

// Decodes base64 text (whitespace ignored). The header and the values of an array
// may be encoded separately, each with its own padding: the decoded pieces are
// concatenated. False on a character outside the alphabet or a cut group.
bool decode_base64(std::string_view text, std::string* out) {
  static const auto table = [] {
    std::array<int8_t, 256> t{};
    t.fill(-1);
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int i = 0; i < 64; ++i) t[uint8_t(alphabet[i])] = int8_t(i);
    return t;
  }();
  out->clear();
  out->reserve(text.size() / 4 * 3);
  uint32_t group = 0;
  int filled = 0, padding = 0;
  for (char c : text) {
    if (is_xml_space(c)) continue;
    if (c == '=') {
      if (filled < 2) return false;
      ++padding;
      ++filled;
    } else {
      const int8_t v = table[uint8_t(c)];
      if (v < 0 || padding > 0) return false;
      group = group << 6 | uint32_t(v);
      ++filled;
    }
    if (filled == 4) {
      group <<= 6 * padding;
      const int bytes = 3 - padding;
      for (int k = 0; k < bytes; ++k) out->push_back(char(group >> (16 - 8 * k) & 0xff));
      group = 0;
      filled = padding = 0;
    }
  }
  return filled == 0;
}

class VtuParser {
 public:
  VtuParser(std::string_view text, const std::string& name, ParsedMesh* out)
      : scanner_(text, name), out_(out) {}

  Status parse() {
    Tag tag;
    std::vector<std::string_view> open;  // names of the open elements
    bool seen_root = false;
    while (error_.ok() && !root_closed_ && next_tag(&tag)) {
      if (tag.closing) {
        if (open.empty() || open.back() != tag.name) {
          fail("the closing tag </" + std::string(tag.name) + "> does not match <" +
               (open.empty() ? std::string() : std::string(open.back())) + ">");
          break;
        }
        open.pop_back();
        root_closed_ = open.empty();
        continue;
      }
      if (open.empty()) {
        if (seen_root) {
          fail("a second root element <" + std::string(tag.name) + ">");
        } else if (tag.name != "VTKFile") {
          fail("not a VTK XML file: the root element is <" + std::string(tag.name) + ">");
        } else if (tag.attribute("type") != "UnstructuredGrid") {
          fail("only UnstructuredGrid .vtu files are supported, found type=\"" +
               std::string(tag.attribute("type")) + "\"");
        } else {
          read_encoding(tag);
        }
        seen_root = true;
      } else {
        open_element(tag, open.back());
      }
      if (!tag.self_closing) {
        open.push_back(tag.name);
      } else if (open.empty()) {
        root_closed_ = true;  // <VTKFile .../>
      }
    }
    if (!error_.ok()) return error_;
    if (!seen_root) return make_error(scanner_.current_line(), "not a VTK XML file: no <VTKFile>");
    if (!root_closed_) {
      return make_error(
          scanner_.current_line(),
          "unexpected end of file inside <" + std::string(open.back()) + "> (truncated file?)");
    }
    for (const PendingArray& array : appended_arrays_) {
      if (!read_appended(array)) break;
    }
    if (error_.ok()) build_tets();
    return error_;
  }

 private:
  Status make_error(size_t line, const std::string& message) const {
    return Status::error(scanner_.name() + ":" + std::to_string(line) + ": " + message);
  }

  bool fail(const std::string& message) { return fail_at(scanner_.current_line(), message); }

  bool fail_at(size_t line, const std::string& message) {
    if (error_.ok()) error_ = make_error(line, message);
    return false;
  }

  // The next start or end tag, skipping text, comments, <?...?> and <!...>. False
  // at the end of the text or on an error.
  bool next_tag(Tag* tag) {
    while (true) {
      std::string_view rest = scanner_.remaining_text();
      const size_t open = rest.find('<');
      if (open == std::string_view::npos) {
        scanner_.advance(rest.size());
        return false;
      }
      scanner_.advance(open);
      rest = scanner_.remaining_text();
      const char* terminator = nullptr;
      if (starts_with(rest, "<!--")) {
        terminator = "-->";
      } else if (starts_with(rest, "<?")) {
        terminator = "?>";
      } else if (starts_with(rest, "<![CDATA[")) {
        return fail("CDATA sections are not supported");
      } else if (starts_with(rest, "<!")) {
        terminator = ">";
      }
      if (terminator) {
        const size_t end = rest.find(terminator);
        if (end == std::string_view::npos) return fail("unterminated markup (truncated file?)");
        scanner_.advance(end + std::string_view(terminator).size());
        continue;
      }
      return parse_tag(rest, tag);
    }
  }

  bool parse_tag(std::string_view rest, Tag* tag) {
    const size_t line = scanner_.current_line();
    auto truncated = [&] { return fail_at(line, "unexpected end of file inside a tag"); };
    *tag = Tag();
    size_t i = 1;
    if (i < rest.size() && rest[i] == '/') {
      tag->closing = true;
      ++i;
    }
    const size_t name_start = i;
    while (i < rest.size() && !is_xml_space(rest[i]) && rest[i] != '/' && rest[i] != '>') ++i;
    tag->name = rest.substr(name_start, i - name_start);
    while (true) {
      while (i < rest.size() && is_xml_space(rest[i])) ++i;
      if (i >= rest.size()) return truncated();
      if (rest[i] == '>') break;
      if (rest[i] == '/') {
        if (i + 1 >= rest.size()) return truncated();
        if (rest[i + 1] != '>') return fail_at(line, "unexpected '/' in a tag");
        tag->self_closing = true;
        ++i;
        break;
      }
      const size_t attribute_start = i;
      while (i < rest.size() && rest[i] != '=' && !is_xml_space(rest[i]) && rest[i] != '>') ++i;
      const std::string_view attribute_name = rest.substr(attribute_start, i - attribute_start);
      while (i < rest.size() && is_xml_space(rest[i])) ++i;
      if (i >= rest.size()) return truncated();
      if (rest[i] != '=' || attribute_name.empty()) {
        return fail_at(line, "malformed attribute in <" + std::string(tag->name) + ">");
      }
      ++i;
      while (i < rest.size() && is_xml_space(rest[i])) ++i;
      if (i >= rest.size()) return truncated();
      const char quote = rest[i];
      if (quote != '"' && quote != '\'') {
        return fail_at(line, "unquoted attribute value in <" + std::string(tag->name) + ">");
      }
      const size_t value_end = rest.find(quote, i + 1);
      if (value_end == std::string_view::npos) return truncated();
      tag->attributes.push_back({attribute_name, rest.substr(i + 1, value_end - i - 1)});
      i = value_end + 1;
    }
    if (tag->name.empty()) return fail_at(line, "a tag without a name");
    if (tag->closing && (tag->self_closing || !tag->attributes.empty())) {
      return fail_at(line, "malformed closing tag </" + std::string(tag->name) + ">");
    }
    scanner_.advance(i + 1);
    return true;
  }

  // An unsigned attribute value no larger than `max_value`.
  bool read_count_attribute(const Tag& tag, const char* key, uint64_t max_value, uint64_t* value) {
    const std::string_view text = tag.attribute(key);
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), *value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
      return fail(std::string("<") + std::string(tag.name) + "> needs a count " + key +
                  ", found \"" + std::string(text.substr(0, 40)) + "\"");
    }
    if (*value > max_value) {
      return fail(std::string(key) + " " + std::to_string(*value) +
                  " is larger than the rest of the file can hold");
    }
    return true;
  }

  void open_element(const Tag& tag, std::string_view parent) {
    if (tag.name == "AppendedData") {
      open_appended_data(tag);
    } else if (tag.name == "Piece") {
      if (seen_piece_) {
        fail("more than one <Piece> is not supported");
        return;
      }
      seen_piece_ = true;
      // A point takes at least 6 bytes ("0 0 0 "), a cell at least 4 (offset, type).
      const uint64_t remaining = scanner_.remaining_bytes();
      if (read_count_attribute(tag, "NumberOfPoints",
                               std::min<uint64_t>(remaining / 6, kInvalidIndex - 1),
                               &point_count_)) {
        read_count_attribute(tag, "NumberOfCells",
                             std::min<uint64_t>(remaining / 4, kInvalidIndex - 1), &cell_count_);
      }
    } else if (tag.name == "DataArray" || (tag.name == "Array" && parent == "FieldData")) {
      // VTK writes String arrays as <Array>.
      read_data_array(tag, parent);
    }
  }

  // kNameTags, kNameDims, kNames: the names TetLOD writes in the dataset's field data
  // (kVtkNameTagArray, kVtkNameDimArray, kVtkNameArray: integers, integers, and
  // strings as their bytes).
  enum class Target {
    kNone,
    kPoints,
    kConnectivity,
    kOffsets,
    kTypes,
    kMaterial,
    kNameTags,
    kNameDims,
    kNames
  };

  // Called once per array, in the order of the file.
  Target target_of(const Tag& tag, std::string_view parent) {
    const std::string_view name = tag.attribute("Name");
    if (parent == "Points") return Target::kPoints;
    if (parent == "FieldData") {
      const std::string_view type = tag.attribute("type");
      const bool integers = type.rfind("Int", 0) == 0 || type.rfind("UInt", 0) == 0;
      if (name == kVtkNameTagArray && integers) return Target::kNameTags;
      if (name == kVtkNameDimArray && integers) return Target::kNameDims;
      if (name == kVtkNameArray && type == "String") return Target::kNames;
      return Target::kNone;
    }
    if (parent == "Cells") {
      if (name == "connectivity") return Target::kConnectivity;
      if (name == "offsets") return Target::kOffsets;
      if (name == "types") return Target::kTypes;
    }
    if (parent == "CellData") {
      cell_arrays_.emplace_back(name);
      // "material" whatever its type; the other names vtk_material_rank() knows if
      // they hold integers and are better than an array taken before.
      const int rank = vtk_material_rank(name);
      const std::string_view type = tag.attribute("type");
      const bool integers = type.rfind("Int", 0) == 0 || type.rfind("UInt", 0) == 0;
      const std::string_view components = tag.attribute("NumberOfComponents");
      if (rank == 0 || (rank > 0 && rank < material_rank_ && integers &&
                        (components.empty() || components == "1"))) {
        material_rank_ = rank;
        return Target::kMaterial;
      }
    }
    return Target::kNone;
  }

  void read_data_array(const Tag& tag, std::string_view parent) {
    std::string_view content;
    const size_t line = scanner_.current_line();
    if (!tag.self_closing) {
      // The values end at the next tag: </DataArray>, or the <InformationKey>
      // elements VTK writes after them.
      const std::string_view rest = scanner_.remaining_text();
      const size_t end = rest.find('<');
      if (end == std::string_view::npos) {
        fail("unexpected end of file inside <DataArray> (truncated file?)");
        return;
      }
      content = rest.substr(0, end);
    }
    const Target target = target_of(tag, parent);
    const bool names =
        target == Target::kNameTags || target == Target::kNameDims || target == Target::kNames;
    if (target != Target::kNone) {
      if (!seen_piece_ && !names) {
        fail("<DataArray> outside a <Piece>");
        return;
      }
      const std::string_view format = tag.attribute("format");
      if (format == "binary" || format == "appended") {
        PendingArray array;
        array.target = target;
        array.type = target == Target::kNames ? BinaryType{BinaryType::kUnsigned, 1}
                                              : vtu_type(tag.attribute("type"));
        array.name = std::string(tag.attribute("Name"));
        array.components = std::string(tag.attribute("NumberOfComponents"));
        array.line = line;
        if (array.type.size == 0) {
          fail("DataArray \"" + array.name + "\" has type \"" + std::string(tag.attribute("type")) +
               "\", not a VTK numeric type");
          return;
        }
        if (format == "binary") {
          std::string raw;
          if (!decode_base64(content, &raw)) {
            fail_at(line, "DataArray \"" + array.name + "\" is not valid base64");
            return;
          }
          if (!read_binary_array(array, raw)) return;
        } else {
          uint64_t offset = 0;
          const std::string_view text = tag.attribute("offset");
          const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), offset);
          if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
            fail_at(line, "DataArray \"" + array.name +
                              "\" needs an offset into the appended "
                              "data, found \"" +
                              std::string(text.substr(0, 40)) + "\"");
            return;
          }
          array.offset = offset;
          appended_arrays_.push_back(std::move(array));
        }
        scanner_.advance(content.size());
        return;
      }
      if (format != "ascii") {
        fail("DataArray \"" + std::string(tag.attribute("Name")) + "\" has format=\"" +
             std::string(format) + "\", not ascii, binary or appended");
        return;
      }
      TextScanner values(content, scanner_.name(), 0, line);
      values.set_number_may_end_text(true);
      if (!read_values(values, tag, target)) return;
    }
    scanner_.advance(content.size());
  }

  // ---------------------------------------------------------------- binary data
  struct PendingArray {
    Target target = Target::kNone;
    BinaryType type;
    std::string name, components;
    size_t line = 0;
    uint64_t offset = 0;  // into the appended data
  };

  void read_encoding(const Tag& root) {
    const std::string_view order = root.attribute("byte_order");
    const std::string_view header = root.attribute("header_type");
    const std::string_view compressor = root.attribute("compressor");
    if (order == "BigEndian") {
      big_endian_ = true;
    } else if (!order.empty() && order != "LittleEndian") {
      fail("byte_order \"" + std::string(order) + "\" is not LittleEndian or BigEndian");
    }
    if (header == "UInt64") {
      header_size_ = 8;
    } else if (!header.empty() && header != "UInt32") {
      fail("header_type \"" + std::string(header) + "\" is not UInt32 or UInt64");
    }
    if (compressor == "vtkZLibDataCompressor") {
      zlib_ = true;
    } else if (!compressor.empty()) {
      fail("compressor \"" + std::string(compressor) +
           "\" is not supported (only vtkZLibDataCompressor); save the file uncompressed");
    }
  }

  // <AppendedData encoding="raw"> then '_' and the bytes. The arrays are read at the
  // end, by offset; the XML goes on at the last </AppendedData>, since raw bytes may
  // hold anything, even '<'.
  void open_appended_data(const Tag& tag) {
    appended_base64_ = tag.attribute("encoding") == "base64";
    if (!appended_base64_ && tag.attribute("encoding") != "raw") {
      fail("AppendedData encoding \"" + std::string(tag.attribute("encoding")) +
           "\" is not raw or base64");
      return;
    }
    if (tag.self_closing) return;
    const std::string_view rest = scanner_.remaining_text();
    const size_t underscore = rest.find('_');
    const size_t close = rest.rfind("</AppendedData>");
    if (underscore == std::string_view::npos || close == std::string_view::npos ||
        close < underscore) {
      fail(
          "<AppendedData> needs '_' before its data and a closing </AppendedData> "
          "(truncated file?)");
      return;
    }
    appended_ = rest.substr(underscore + 1, close - underscore - 1);
    seen_appended_ = true;
    scanner_.advance(close);
  }

  bool read_appended(const PendingArray& array) {
    if (!seen_appended_) {
      return fail_at(array.line, "DataArray \"" + array.name +
                                     "\" is appended but the file "
                                     "has no <AppendedData>");
    }
    if (array.offset > appended_.size()) {
      return fail_at(array.line, "DataArray \"" + array.name + "\" starts at offset " +
                                     std::to_string(array.offset) + ", past the " +
                                     std::to_string(appended_.size()) + " appended bytes");
    }
    if (!appended_base64_) return read_binary_array(array, appended_.substr(array.offset));
    std::string raw;
    if (!decode_appended_base64(array, appended_.substr(array.offset), &raw)) return false;
    return read_binary_array(array, raw);
  }

  // Base64 appended data: the header of a compressed array and its values are encoded
  // apart, so the header is decoded first to learn how many characters the values take.
  bool decode_appended_base64(const PendingArray& array, std::string_view text, std::string* raw) {
    auto chars_for = [](uint64_t bytes) { return (bytes + 2) / 3 * 4; };
    auto decode = [&](size_t at, uint64_t bytes, std::string* out) {
      const uint64_t chars = chars_for(bytes);
      if (at > text.size() || chars > text.size() - at ||
          !decode_base64(text.substr(at, chars), out) || out->size() < bytes) {
        return fail_at(array.line, "DataArray \"" + array.name +
                                       "\": the appended base64 data "
                                       "is cut short or not base64");
      }
      out->resize(bytes);
      return true;
    };
    std::string header, values;
    uint64_t header_bytes = header_size_, value_bytes = 0;
    if (zlib_) {
      if (!decode(0, 3 * header_size_, &header)) return false;
      const uint64_t blocks = header_value(header, 0);
      if (blocks > text.size() / header_size_) {
        return fail_at(array.line, "DataArray \"" + array.name + "\": the header gives " +
                                       std::to_string(blocks) +
                                       " compressed blocks, more than "
                                       "the file can hold");
      }
      header_bytes = (3 + blocks) * header_size_;
      if (!decode(0, header_bytes, &header)) return false;
      for (uint64_t b = 0; b < blocks && value_bytes <= text.size(); ++b) {
        value_bytes += std::min<uint64_t>(header_value(header, 3 + b), text.size() + 1);
      }
    } else {
      if (!decode(0, header_bytes, &header)) return false;
      value_bytes = header_value(header, 0);
      // VTK encodes an uncompressed array's header and values as one block (its header
      // alone would end in '=' padding: 4 or 8 bytes are not a multiple of 3).
      if (text[chars_for(header_bytes) - 1] != '=') {
        if (value_bytes > text.size()) value_bytes = text.size() + 1;  // cut short: fails below
        if (!decode(0, header_bytes + value_bytes, raw)) return false;
        return true;
      }
    }
    if (value_bytes > text.size()) value_bytes = text.size() + 1;  // cut short: fails below
    if (!decode(size_t(chars_for(header_bytes)), value_bytes, &values)) return false;
    *raw = header + values;
    return true;
  }

  uint64_t header_value(std::string_view raw, size_t index) const {
    return value_bits(raw.data() + index * header_size_, header_size_, big_endian_);
  }

  // The number of values an array must hold, or 0 if only a bound is known.
  uint64_t expected_values(const PendingArray& array, uint64_t* bound) const {
    *bound = 0;
    switch (array.target) {
      case Target::kPoints:
        return 3 * point_count_;
      case Target::kOffsets:
      case Target::kTypes:
      case Target::kMaterial:
        return cell_count_;
      case Target::kConnectivity:
        *bound = 64 * cell_count_;  // a generous bound on the points of all cells
        return 0;
      case Target::kNameTags:
      case Target::kNameDims:
      case Target::kNames:
        *bound = kMaxNameBytes;
        return 0;
      case Target::kNone:
        break;
    }
    return 0;
  }

  // The values of a binary array from its bytes (header first) into the target.
  bool read_binary_array(const PendingArray& array, std::string_view raw) {
    auto bad = [&](const std::string& what) {
      return fail_at(array.line, "DataArray \"" + array.name + "\": " + what);
    };
    uint64_t bound = 0;
    const uint64_t expected = expected_values(array, &bound);
    const size_t size = array.type.size;
    std::string inflated;
    std::string_view values;
    if (!zlib_) {
      if (raw.size() < header_size_) return bad("the file ends inside the header");
      const uint64_t bytes = header_value(raw, 0);
      if (bytes > raw.size() - header_size_) {
        return bad("the header gives " + std::to_string(bytes) + " bytes, the file holds " +
                   std::to_string(raw.size() - header_size_) + " (truncated file?)");
      }
      values = raw.substr(header_size_, bytes);
    } else {
      // Blocks, size of a block, size of the last one (0: full), compressed sizes.
      if (raw.size() < 3 * header_size_) return bad("the file ends inside the header");
      const uint64_t blocks = header_value(raw, 0);
      const uint64_t block_size = header_value(raw, 1);
      const uint64_t last_size = header_value(raw, 2);
      if (blocks > (raw.size() - 3 * header_size_) / header_size_) {
        return bad("the header gives " + std::to_string(blocks) +
                   " compressed blocks, more "
                   "than the file can hold");
      }
      const uint64_t limit = (expected != 0 ? expected : bound) * size;
      // Every block but the last is full: bounded first, so that the total cannot wrap.
      if (blocks > 0 && (block_size == 0 || last_size > block_size ||
                         (blocks > 1 && block_size > limit / (blocks - 1)))) {
        return bad("the compressed header's block sizes do not fit " + std::to_string(limit) +
                   " bytes of values");
      }
      const uint64_t total =
          blocks == 0 ? 0 : (blocks - 1) * block_size + (last_size == 0 ? block_size : last_size);
      if (total > limit || (expected != 0 && total != expected * size)) {
        return bad("the compressed header gives " + std::to_string(total) +
                   " bytes of values, not " + std::to_string(expected * size));
      }
      size_t at = size_t(3 + blocks) * header_size_;
      inflated.resize(total);
      uint64_t written = 0;
      for (uint64_t b = 0; b < blocks; ++b) {
        const uint64_t compressed = header_value(raw, 3 + b);
        if (compressed > raw.size() - at) return bad("the file ends inside compressed data");
        uLongf length = uLongf(b + 1 == blocks && last_size != 0 ? last_size : block_size);
        const uLongf wanted = length;
        const int status =
            uncompress(reinterpret_cast<Bytef*>(&inflated[written]), &length,
                       reinterpret_cast<const Bytef*>(raw.data() + at), uLong(compressed));
        if (status != Z_OK || length != wanted) {
          return bad("compressed block " + std::to_string(b) + " does not inflate to " +
                     std::to_string(wanted) + " bytes");
        }
        written += length;
        at += size_t(compressed);
      }
      values = inflated;
    }
    if (values.size() % size != 0) return bad("the byte count is not a whole number of values");
    const uint64_t count = values.size() / size;
    if (expected != 0 && count != expected) {
      return bad("holds " + std::to_string(count) + " values, not " + std::to_string(expected));
    }
    if (expected == 0 && count > bound) return bad("holds more values than the cells can use");
    return store_binary(array, values, count);
  }

  bool store_binary(const PendingArray& array, std::string_view values, uint64_t count) {
    const BinaryType type = array.type;
    auto bits = [&](uint64_t i) {
      return value_bits(values.data() + i * type.size, type.size, big_endian_);
    };
    auto integer = [&](uint64_t i, int64_t min_value, int64_t max_value, int64_t* value) {
      if (binary_integer(bits(i), type, value) && *value >= min_value && *value <= max_value)
        return true;
      return fail_at(array.line, "DataArray \"" + array.name + "\": value " +
                                     std::to_string(i + 1) + " of " + std::to_string(count) + ", " +
                                     binary_value_text(bits(i), type) +
                                     ", is not an integer from " + std::to_string(min_value) +
                                     " to " + std::to_string(max_value));
    };
    int64_t value = 0;
    switch (array.target) {
      case Target::kPoints: {
        if (array.components != "3")
          return fail_at(array.line, "Points must have NumberOfComponents=\"3\"");
        std::vector<Vec3>& positions = out_->mesh.positions;
        if (!positions.empty()) return fail_at(array.line, "a second Points array");
        positions.resize(point_count_);
        for (uint64_t i = 0; i < count; ++i) {
          const double x = binary_real(bits(i), type);
          if (!std::isfinite(x)) {
            return fail_at(array.line, "point " + std::to_string(i / 3) +
                                           " has a coordinate that is not a finite number");
          }
          positions[i / 3][int(i % 3)] = x;
        }
        return true;
      }
      case Target::kConnectivity:
        connectivity_.resize(count);
        for (uint64_t i = 0; i < count; ++i) {
          if (!integer(i, 0, int64_t{kInvalidIndex} - 1, &value)) return false;
          connectivity_[i] = uint32_t(value);
        }
        return true;
      case Target::kOffsets:
        offsets_line_ = array.line;
        offsets_.resize(count);
        for (uint64_t i = 0; i < count; ++i) {
          if (!integer(i, 0, int64_t{kInvalidIndex} * 10, &value)) return false;
          offsets_[i] = uint64_t(value);
        }
        return true;
      case Target::kTypes:
        types_.resize(count);
        for (uint64_t i = 0; i < count; ++i) {
          if (!integer(i, std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(),
                       &types_[i])) {
            return false;
          }
        }
        return true;
      case Target::kMaterial:
        materials_.resize(count);
        for (uint64_t i = 0; i < count; ++i) {
          if (!integer(i, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max(),
                       &value)) {
            return false;
          }
          materials_[i] = int32_t(value);
        }
        has_materials_ = true;
        return true;
      case Target::kNameTags:
      case Target::kNameDims: {
        std::vector<int64_t>& read = array.target == Target::kNameTags ? name_tags_ : name_dims_;
        read.resize(count);
        for (uint64_t i = 0; i < count; ++i) {
          if (!integer(i, std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(),
                       &read[i])) {
            return false;
          }
        }
        return true;
      }
      case Target::kNames:
        name_bytes_.assign(values.data(), count);
        return true;
      case Target::kNone:
        return true;
    }
    return true;
  }

  bool read_values(TextScanner& values, const Tag& tag, Target target) {
    const int32_t int32_min = std::numeric_limits<int32_t>::min();
    const int32_t int32_max = std::numeric_limits<int32_t>::max();
    bool ok = true;
    int64_t value = 0;
    switch (target) {
      case Target::kPoints: {
        const std::string_view components = tag.attribute("NumberOfComponents");
        if (components != "3") return fail("Points must have NumberOfComponents=\"3\"");
        std::vector<Vec3>& positions = out_->mesh.positions;
        if (!positions.empty()) return fail("a second Points array");
        positions.resize(point_count_);
        for (Vec3& p : positions) {
          ok = ok && values.read_double(&p.x, "x coordinate") &&
               values.read_double(&p.y, "y coordinate") && values.read_double(&p.z, "z coordinate");
        }
        break;
      }
      case Target::kConnectivity:
        // At least 2 bytes per index in the content.
        connectivity_.reserve(values.remaining_bytes() / 2 + 1);
        connectivity_lines_.reserve(values.remaining_bytes() / 2 + 1);
        while (ok && !values.at_end()) {
          ok = values.read_int_in_range(&value, "point index", 0, int64_t{kInvalidIndex} - 1);
          connectivity_.push_back(uint32_t(value));
          connectivity_lines_.push_back(line_number(values.line()));
        }
        break;
      case Target::kOffsets:
        offsets_line_ = values.current_line();
        offsets_.resize(cell_count_);
        for (uint64_t& offset : offsets_) {
          ok = ok && values.read_int_in_range(&value, "offset", 0, int64_t{kInvalidIndex} * 10);
          offset = uint64_t(value);
        }
        break;
      case Target::kTypes:
        types_.resize(cell_count_);
        for (int64_t& type : types_) ok = ok && values.read_int(&type, "cell type");
        break;
      case Target::kMaterial:
        materials_.resize(cell_count_);
        for (int32_t& material : materials_) {
          ok = ok && values.read_integral(&value, "material id", int32_min, int32_max);
          material = int32_t(value);
        }
        has_materials_ = true;
        break;
      case Target::kNameTags:
      case Target::kNameDims: {
        std::vector<int64_t>& read = target == Target::kNameTags ? name_tags_ : name_dims_;
        read.clear();
        while (ok && !values.at_end() && read.size() < kMaxNameBytes) {
          ok = values.read_int(&value, target == Target::kNameTags ? "tag" : "dimension");
          read.push_back(value);
        }
        break;
      }
      case Target::kNames:
        name_bytes_.clear();
        while (ok && !values.at_end() && name_bytes_.size() < kMaxNameBytes) {
          // VTK writes bytes past 127 as negative numbers (signed chars).
          ok = values.read_int_in_range(&value, "string byte", -128, 255);
          name_bytes_.push_back(char(value));
        }
        break;
      case Target::kNone:
        break;
    }
    if (ok && !values.at_end()) {
      std::string_view extra;
      values.next_token(&extra);
      values.fail("DataArray \"" + std::string(tag.attribute("Name")) +
                  "\" has more values than expected: " + TextScanner::quote(extra));
      ok = false;
    }
    if (!ok && error_.ok()) error_ = values.status();
    return ok;
  }

  void build_tets() {
    if (!seen_piece_) {
      fail("no <Piece>");
      return;
    }
    if (out_->mesh.positions.size() != point_count_) {
      fail("no <Points> array");
      return;
    }
    if (offsets_.size() != cell_count_ || types_.size() != cell_count_ ||
        (cell_count_ > 0 && connectivity_.empty())) {
      fail("<Cells> needs the DataArrays connectivity, offsets and types");
      return;
    }
    TetMesh& mesh = out_->mesh;
    std::vector<uint64_t> counts_by_type(128, 0);
    SurfaceElements surface;
    uint64_t start = 0;
    for (size_t c = 0; c < cell_count_; ++c) {
      const uint64_t end = offsets_[c];
      if (types_[c] >= 0 && types_[c] < 128) ++counts_by_type[size_t(types_[c])];
      if (end < start || end > connectivity_.size()) {
        fail_at(offsets_line_, "offset " + std::to_string(end) + " of cell " + std::to_string(c) +
                                   " is out of order or past the connectivity array");
        return;
      }
      const int64_t type = types_[c];
      const uint64_t size = end - start;
      bool tet = false;
      const bool tet_size = vtk_tet_cell(type, size, &tet);
      const int triangle = vtk_triangle_points(type);
      if (is_vtk_surface_cell(type)) surface.count();
      if (tet || triangle >= 0) {
        const size_t line = start < connectivity_lines_.size() ? connectivity_lines_[start] : 0;
        if (tet ? !tet_size : triangle > 0 ? size != uint64_t(triangle) : size < 3) {
          fail_at(line, "cell " + std::to_string(c) + " of type " + std::to_string(type) + " has " +
                            std::to_string(size) + " points");
          return;
        }
        const uint32_t* v = connectivity_.data() + start;
        for (int k = 0; k < (tet ? 4 : 3); ++k) {
          if (v[k] >= mesh.positions.size()) {
            fail_at(line, "cell " + std::to_string(c) + " uses point " + std::to_string(v[k]) +
                              ", but there are only " + std::to_string(mesh.positions.size()) +
                              " points (numbered from 0)");
            return;
          }
        }
        if (!tet) {
          if (has_materials_ && materials_[c] >= 1) {
            surface.add_triangle(materials_[c], mesh.positions[v[0]], mesh.positions[v[1]],
                                 mesh.positions[v[2]]);
          }
        } else {
          mesh.tets.push_back({v[0], v[1], v[2], v[3]});
          mesh.materials.push_back(has_materials_ ? materials_[c] : 0);
          out_->tet_lines.push_back(line_number(line));
        }
      }
      start = end;
    }
    surface.finish(out_);
    add_vtk_cell_notes(counts_by_type, out_);
    if (has_materials_) finish_vtk_materials(material_rank_, out_);
    if (!has_materials_) out_->notes.push_back(no_material_note(cell_arrays_));
    // The strings of a String array: each one's bytes and a 0.
    std::vector<std::string> names;
    for (size_t from = 0; from < name_bytes_.size();) {
      size_t to = name_bytes_.find('\0', from);
      if (to == std::string::npos) to = name_bytes_.size();
      names.push_back(name_bytes_.substr(from, to - from));
      from = to + 1;
    }
    apply_vtk_names(name_tags_, name_dims_, names, out_);
  }

  // The most bytes of names, or tags, read from the field data.
  static constexpr uint64_t kMaxNameBytes = uint64_t{1} << 24;

  TextScanner scanner_;
  ParsedMesh* out_;
  Status error_;
  bool root_closed_ = false;
  bool seen_piece_ = false;
  uint64_t point_count_ = 0;
  uint64_t cell_count_ = 0;
  std::vector<uint32_t> connectivity_;
  std::vector<uint32_t> connectivity_lines_;
  std::vector<uint64_t> offsets_;
  size_t offsets_line_ = 0;
  std::vector<int64_t> types_;
  bool has_materials_ = false;
  int material_rank_ = 1 << 30;  // vtk_material_rank() of the array taken (none yet: worst)
  std::vector<int32_t> materials_;
  std::vector<std::string> cell_arrays_;  // names of the <CellData> arrays, in file order
  std::vector<int64_t> name_tags_;        // Target::kNameTags
  std::vector<int64_t> name_dims_;        // Target::kNameDims
  std::string name_bytes_;                // Target::kNames
  // Binary data.
  bool big_endian_ = false;
  size_t header_size_ = 4;  // UInt32
  bool zlib_ = false;
  bool seen_appended_ = false;
  bool appended_base64_ = false;
  std::string_view appended_;  // the bytes after '_'
  std::vector<PendingArray> appended_arrays_;
};

}  // namespace

Status parse_vtu(std::string_view text, const std::string& name, ParsedMesh* out) {
  VtuParser parser(text, name, out);
  return parser.parse();
}

namespace {

// The DataArray elements of a file being written: as text, each with its values
// inside; in binary, each with its offset into the raw appended data, which
// finish() writes after the grid: per array a UInt64 count of bytes, then the
// values, little-endian.
class VtuArrays {
 public:
  VtuArrays(std::string* out, bool binary) : out_(out), binary_(binary) {}

  // An array of `count` values of `Value` (the XML type `type`), value_of(i) the i-th;
  // as text, `per_line` a line. `attributes`: more of the element's, after the name.
  template <typename Value, typename Function>
  void add(const char* type, std::string_view name, std::string_view attributes, size_t count,
           size_t per_line, Function value_of) {
    // VTK writes String arrays as <Array>, the numeric ones as <DataArray>.
    const char* element = std::string_view(type) == "String" ? "Array" : "DataArray";
    open(element, type, name, attributes);
    if (binary_) {
      append_binary(&appended_, uint64_t(count * sizeof(Value)), false);
      for (size_t i = 0; i < count; ++i) append_binary(&appended_, Value(value_of(i)), false);
      return;
    }
    for (size_t i = 0; i < count; ++i) {
      out_->append(i % per_line == 0 ? "          " : " ");
      append_number(out_, Value(value_of(i)));
      if (i % per_line == per_line - 1 || i + 1 == count) out_->push_back('\n');
    }
    out_->append("        </");
    out_->append(element);
    out_->append(">\n");
  }

  // The same, the text written by write_text() (lines, each indented as above).
  template <typename Value, typename Function, typename Text>
  void add_text(const char* type, std::string_view name, std::string_view attributes, size_t count,
                Function value_of, Text write_text) {
    if (binary_) return add<Value>(type, name, attributes, count, 1, value_of);
    open("DataArray", type, name, attributes);
    write_text();
    out_->append("        </DataArray>\n");
  }

  // After </UnstructuredGrid>.
  void finish() {
    if (!binary_) return;
    out_->append("  <AppendedData encoding=\"raw\">\n   _");
    out_->append(appended_);
    out_->append("\n  </AppendedData>\n");
  }

 private:
  void open(const char* element, const char* type, std::string_view name,
            std::string_view attributes) {
    out_->append("        <");
    out_->append(element);
    out_->append(" type=\"");
    out_->append(type);
    out_->append("\" Name=\"");
    out_->append(name);
    out_->append("\"");
    out_->append(attributes);
    if (binary_) {
      out_->append(" format=\"appended\" offset=\"");
      append_number(out_, uint64_t(appended_.size()));
      out_->append("\"/>\n");
    } else {
      out_->append(" format=\"ascii\">\n");
    }
  }

  std::string* out_;
  bool binary_;
  std::string appended_;
};

// The surface groups' triangles come after the tets, as for .vtk (write_vtk_legacy()):
// cell type 5, the group's tag as material, the stretch of the tet on its back side. The
// fields' cell arrays are the tets' only: a caller gives fields or surfaces.
void write_vtu_cells(const TetMesh& mesh, const MeshFields& fields, const SurfaceGroups* surfaces,
                     const std::vector<MaterialName>* names, bool binary, std::string* out) {
  const size_t tet_count = mesh.tet_count();
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<int32_t> tags;
  std::vector<uint32_t> triangle_tets;
  if (surfaces) {
    for (const SurfaceGroup& group : surfaces->groups) {
      for (uint32_t i : group.triangles) {
        triangles.push_back(surfaces->surface[i].v);
        tags.push_back(group.tag);
        triangle_tets.push_back(surfaces->surface[i].tet);
      }
    }
  }
  const size_t cell_count = tet_count + triangles.size();
  out->reserve(out->size() + mesh.vertex_count() * (binary ? 24 : 72) +
               cell_count * (binary ? 56 : 96));
  out->append(binary ? "<?xml version=\"1.0\"?>\n"
                       "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                       "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                     : "<?xml version=\"1.0\"?>\n"
                       "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
                       "byte_order=\"LittleEndian\">\n");
  out->append("  <UnstructuredGrid>\n");
  VtuArrays arrays(out, binary);
  // The names of the materials and groups (vtk_name_rows()) as the dataset's field
  // data; a String array holds each string's bytes and a 0 after it, written as
  // numbers in text (as VTK writes it).
  const std::vector<VtkNameRow> rows = vtk_name_rows(mesh, surfaces, names);
  if (!rows.empty()) {
    std::string bytes;
    for (const VtkNameRow& row : rows) bytes += row.name + '\0';
    const std::string tuples = " NumberOfTuples=\"" + std::to_string(rows.size()) + "\"";
    out->append("    <FieldData>\n");
    arrays.add<int32_t>("Int32", kVtkNameTagArray, tuples, rows.size(), 16,
                        [&](size_t i) { return rows[i].tag; });
    arrays.add<int32_t>("Int32", kVtkNameDimArray, tuples, rows.size(), 16,
                        [&](size_t i) { return rows[i].dim; });
    auto byte = [&](size_t i) { return uint8_t(bytes[i]); };
    if (binary) {
      arrays.add<uint8_t>("String", kVtkNameArray, tuples, bytes.size(), 32, byte);
    } else {  // as numbers, not characters
      arrays.add<int32_t>("String", kVtkNameArray, tuples, bytes.size(), 32, byte);
    }
    out->append("    </FieldData>\n");
  }
  out->append("    <Piece NumberOfPoints=\"");
  append_number(out, mesh.vertex_count());
  out->append("\" NumberOfCells=\"");
  append_number(out, cell_count);
  out->append(
      "\">\n"
      "      <Points>\n");
  const auto& p = mesh.positions;
  arrays.add_text<double>(
      "Float64", "Points", " NumberOfComponents=\"3\"", 3 * p.size(),
      [&](size_t i) { return p[i / 3][i % 3]; },
      [&] {
        for (const Vec3& q : p) {
          out->append("          ");
          append_line(out, q.x, q.y, q.z);
        }
      });
  out->append(
      "      </Points>\n"
      "      <Cells>\n");
  const size_t tet_ids = 4 * tet_count;
  arrays.add_text<int64_t>(
      "Int64", "connectivity", "", tet_ids + 3 * triangles.size(),
      [&](size_t i) {
        return i < tet_ids ? mesh.tets[i / 4][i % 4]
                           : triangles[(i - tet_ids) / 3][(i - tet_ids) % 3];
      },
      [&] {
        for (const Tet& tet : mesh.tets) {
          out->append("          ");
          append_line(out, tet[0], tet[1], tet[2], tet[3]);
        }
        for (const auto& v : triangles) {
          out->append("          ");
          append_line(out, v[0], v[1], v[2]);
        }
      });
  arrays.add<int64_t>("Int64", "offsets", "", cell_count, 16, [&](size_t c) {
    return c < tet_count ? 4 * (c + 1) : 4 * tet_count + 3 * (c + 1 - tet_count);
  });
  if (binary) {
    arrays.add<uint8_t>("UInt8", "types", "", cell_count, 32,
                        [&](size_t c) { return c < tet_count ? 10 : 5; });
  } else {  // as numbers, not characters
    arrays.add<int32_t>("UInt8", "types", "", cell_count, 32,
                        [&](size_t c) { return c < tet_count ? 10 : 5; });
  }
  out->append("      </Cells>\n");
  auto add_fields = [&](const std::vector<ScalarArray>& list) {
    for (const ScalarArray& array : list) {
      arrays.add<double>("Float64", array.name, "", array.values->size(), 8,
                         [&](size_t i) { return (*array.values)[i]; });
    }
  };
  if (!fields.point_data.empty()) {
    out->append("      <PointData Scalars=\"");
    out->append(fields.point_data[0].name);
    out->append("\">\n");
    add_fields(fields.point_data);
    out->append("      </PointData>\n");
  }
  out->append("      <CellData Scalars=\"material\">\n");
  arrays.add<int32_t>("Int32", "material", "", cell_count, 16, [&](size_t c) {
    return c < tet_count ? mesh.materials[c] : tags[c - tet_count];
  });
  std::vector<double> stretch(tet_count);
  for (size_t t = 0; t < tet_count; ++t) stretch[t] = tet_shape(mesh, mesh.tets[t]).stretch;
  arrays.add<double>("Float64", "stretch", "", cell_count, 8, [&](size_t c) {
    return stretch[c < tet_count ? c : triangle_tets[c - tet_count]];
  });
  add_fields(fields.cell_data);
  out->append(
      "      </CellData>\n"
      "    </Piece>\n"
      "  </UnstructuredGrid>\n");
  arrays.finish();
  out->append("</VTKFile>\n");
}

}  // namespace

void write_vtu(const TetMesh& mesh, const SurfaceGroups* surfaces,
               const std::vector<MaterialName>* names, bool binary, std::string* out) {
  write_vtu_cells(mesh, MeshFields(), surfaces, names, binary, out);
}

void write_vtu(const TetMesh& mesh, const MeshFields& fields, bool binary, std::string* out) {
  write_vtu_cells(mesh, fields, nullptr, nullptr, binary, out);
}

}  // namespace tetlod::io
