// VTK XML unstructured grids (.vtu), ASCII data only, as in "VTK File Formats",
// section "XML File Formats" (https://docs.vtk.org/en/latest/design_documents/
// VTKFileFormats.html). The reader is a minimal XML tokenizer: tags, attributes,
// comments and processing instructions; the numbers of a DataArray are read with a
// TextScanner over its content so that messages keep file line numbers.
#include <charconv>
#include <limits>

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
    build_tets();
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
      fail("appended data is not supported; save the .vtu with ASCII data");
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
    } else if (tag.name == "DataArray") {
      read_data_array(tag, parent);
    }
  }

  enum class Target { kNone, kPoints, kConnectivity, kOffsets, kTypes, kMaterial };

  Target target_of(const Tag& tag, std::string_view parent) const {
    const std::string_view name = tag.attribute("Name");
    if (parent == "Points") return Target::kPoints;
    if (parent == "Cells") {
      if (name == "connectivity") return Target::kConnectivity;
      if (name == "offsets") return Target::kOffsets;
      if (name == "types") return Target::kTypes;
    }
    if (parent == "CellData" && name == "material") return Target::kMaterial;
    return Target::kNone;
  }

  void read_data_array(const Tag& tag, std::string_view parent) {
    std::string_view content;
    const size_t line = scanner_.current_line();
    if (!tag.self_closing) {
      const std::string_view rest = scanner_.remaining_text();
      const size_t end = rest.find("</DataArray");
      if (end == std::string_view::npos) {
        fail("unexpected end of file inside <DataArray> (truncated file?)");
        return;
      }
      content = rest.substr(0, end);
    }
    const Target target = target_of(tag, parent);
    if (target != Target::kNone) {
      if (!seen_piece_) {
        fail("<DataArray> outside a <Piece>");
        return;
      }
      const std::string_view format = tag.attribute("format");
      if (format != "ascii") {
        fail("DataArray \"" + std::string(tag.attribute("Name")) + "\" has format=\"" +
             std::string(format) +
             "\"; only ASCII .vtu is supported (not binary, appended or compressed data)");
        return;
      }
      TextScanner values(content, scanner_.name(), 0, line);
      values.set_number_may_end_text(true);
      if (!read_values(values, tag, target)) return;
    }
    scanner_.advance(content.size());
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
    uint64_t start = 0;
    for (size_t c = 0; c < cell_count_; ++c) {
      const uint64_t end = offsets_[c];
      if (end < start || end > connectivity_.size()) {
        fail_at(offsets_line_, "offset " + std::to_string(end) + " of cell " + std::to_string(c) +
                                   " is out of order or past the connectivity array");
        return;
      }
      const int64_t type = types_[c];
      if (type == kVtkTetra || type == kVtkQuadraticTetra) {
        const uint64_t size = end - start;
        const size_t line = start < connectivity_lines_.size() ? connectivity_lines_[start] : 0;
        if (size != (type == kVtkTetra ? 4u : 10u)) {
          fail_at(line, "cell " + std::to_string(c) + " of type " + std::to_string(type) + " has " +
                            std::to_string(size) + " points");
          return;
        }
        const uint32_t* v = connectivity_.data() + start;
        mesh.tets.push_back({v[0], v[1], v[2], v[3]});
        mesh.materials.push_back(has_materials_ ? materials_[c] : 0);
        out_->tet_lines.push_back(line_number(line));
      }
      start = end;
    }
  }

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
  std::vector<int32_t> materials_;
};

// Appends values `per_line` to a line, indented for readability.
template <typename Value, typename Function>
void append_rows(std::string* out, size_t count, size_t per_line, Function value_of) {
  for (size_t i = 0; i < count; ++i) {
    out->append(i % per_line == 0 ? "          " : " ");
    append_number(out, Value(value_of(i)));
    if (i % per_line == per_line - 1 || i + 1 == count) out->push_back('\n');
  }
}

}  // namespace

Status parse_vtu(std::string_view text, const std::string& name, ParsedMesh* out) {
  VtuParser parser(text, name, out);
  return parser.parse();
}

void write_vtu(const TetMesh& mesh, std::string* out) {
  write_vtu(mesh, MeshFields(), out);
}

void write_vtu(const TetMesh& mesh, const MeshFields& fields, std::string* out) {
  const size_t tet_count = mesh.tet_count();
  out->reserve(out->size() + mesh.vertex_count() * 72 + tet_count * 96);
  out->append(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"");
  append_number(out, mesh.vertex_count());
  out->append("\" NumberOfCells=\"");
  append_number(out, tet_count);
  out->append(
      "\">\n"
      "      <Points>\n"
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n");
  for (const Vec3& p : mesh.positions) {
    out->append("          ");
    append_line(out, p.x, p.y, p.z);
  }
  out->append(
      "        </DataArray>\n"
      "      </Points>\n"
      "      <Cells>\n"
      "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const Tet& tet : mesh.tets) {
    out->append("          ");
    append_line(out, tet[0], tet[1], tet[2], tet[3]);
  }
  out->append(
      "        </DataArray>\n"
      "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  append_rows<uint64_t>(out, tet_count, 16, [](size_t t) { return 4 * (t + 1); });
  out->append(
      "        </DataArray>\n"
      "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  append_rows<int32_t>(out, tet_count, 32, [](size_t) { return 10; });
  out->append(
      "        </DataArray>\n"
      "      </Cells>\n");
  auto append_arrays = [&](const std::vector<ScalarArray>& arrays) {
    for (const ScalarArray& array : arrays) {
      out->append("        <DataArray type=\"Float64\" Name=\"");
      out->append(array.name);
      out->append("\" format=\"ascii\">\n");
      append_rows<double>(out, array.values->size(), 8,
                          [&](size_t i) { return (*array.values)[i]; });
      out->append("        </DataArray>\n");
    }
  };
  if (!fields.point_data.empty()) {
    out->append("      <PointData Scalars=\"");
    out->append(fields.point_data[0].name);
    out->append("\">\n");
    append_arrays(fields.point_data);
    out->append("      </PointData>\n");
  }
  out->append(
      "      <CellData Scalars=\"material\">\n"
      "        <DataArray type=\"Int32\" Name=\"material\" format=\"ascii\">\n");
  append_rows<int32_t>(out, tet_count, 16, [&](size_t t) { return mesh.materials[t]; });
  out->append(
      "        </DataArray>\n"
      "        <DataArray type=\"Float64\" Name=\"stretch\" format=\"ascii\">\n");
  append_rows<double>(out, tet_count, 8,
                      [&](size_t t) { return tet_shape(mesh, mesh.tets[t]).stretch; });
  out->append("        </DataArray>\n");
  append_arrays(fields.cell_data);
  out->append(
      "      </CellData>\n"
      "    </Piece>\n"
      "  </UnstructuredGrid>\n"
      "</VTKFile>\n");
}

}  // namespace tetlod::io
