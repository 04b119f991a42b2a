// TetGen .node/.ele pairs, as described in the TetGen 1.5 manual, section 5.2
// (file formats). TetGen writes tets positively oriented in TetLOD's convention
// (dot(b-a, cross(c-a, d-a)) > 0; checked with libtet 1.5), so the pair is
// written in the orientation the mesh has.
//
// A .face file beside the pair: "count markers(0|1)" then one face per line,
// "index a b c [marker]", numbered like the .node file; after a 10-node .ele a face
// has 6 nodes (TetGen -o2: its corners first), and TetGen -nn adds the two tets
// beside it, which are skipped. Faces with a marker >= 1 are surface groups by
// marker (unnamed), as TetGen writes facet markers and TetLOD group tags; a note
// counts the faces with markers below 0 or above 2^31 - 1 (0 is no marker).
//
// As TetGen does, a header's trailing fields may be left out ("5" is "5 3 0 0" in a
// .node file, "5 4 0" in a .ele, "5 0" in a .face), and numbers after them are ignored.
#include <array>
#include <limits>

#include "core/io/mesh_formats.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"

namespace tetlod::io {
namespace {

// Reads a region attribute that must hold an integer material id ("3" or "3.0").
bool read_material(TextScanner& scanner, int32_t* material) {
  int64_t value = 0;
  if (!scanner.read_integral(&value, "region attribute (material)",
                             std::numeric_limits<int32_t>::min(),
                             std::numeric_limits<int32_t>::max())) {
    return false;
  }
  *material = int32_t(value);
  return true;
}

// The rest of a header's line after its first number (the count). TetGen reads a
// header line and gives missing trailing fields their defaults ("5" is "5 3 0 0" in
// a .node file), so the optional fields are read from this line only.
TextScanner rest_of_header(TextScanner& scanner) {
  const size_t line = scanner.line();
  const bool line_ends = scanner.remaining_text().find('\n') != std::string_view::npos;
  TextScanner fields(scanner.rest_of_line(), scanner.name(), '#', line);
  fields.set_number_may_end_text(line_ends);
  return fields;
}

// Reads an optional non-negative header field; `value` keeps its default when the
// line has ended.
bool read_header_field(TextScanner& fields, int64_t* value, const char* what) {
  if (fields.at_end()) return true;
  if (!fields.read_int(value, what)) return false;
  if (*value >= 0) return true;
  return fields.fail(std::string(what) + " " + std::to_string(*value) + " is negative");
}

// After the fields a header declares, TetGen ignores the rest of its line: so does this,
// for numbers ("5 3 0 0 0" is "5 3 0 0"), as on the data lines below. Anything else is
// an error.
bool expect_end_of_header(TextScanner& fields, const char* fields_text) {
  std::string_view token;
  while (fields.next_token(&token)) {
    if (!TextScanner::looks_numeric(token)) {
      return fields.fail("unexpected " + TextScanner::quote(token) + " in the header (" +
                         fields_text + ")");
    }
  }
  return true;
}

// TetGen reads the fields a line's header declares and ignores any after them (a
// marker column the header leaves out): so does this, for numbers. Anything else
// after them is an error.
bool skip_extra_fields(TextScanner& scanner, const char* item) {
  const size_t line = scanner.line();
  const std::string_view rest = scanner.rest_of_line();
  if (rest.find_first_not_of(" \t\r") == std::string_view::npos) return true;
  TextScanner fields(rest, scanner.name(), '#', line);
  std::string_view token;
  while (fields.next_token(&token)) {
    if (!TextScanner::looks_numeric(token)) {
      return scanner.fail_at_line(line, "unexpected " + TextScanner::quote(token) + " after the " +
                                            item + " (wrong count in the header?)");
    }
  }
  return true;
}

bool expect_end_of_file(TextScanner& scanner, const char* items) {
  std::string_view token;
  if (!scanner.next_token(&token)) return true;
  return scanner.fail("unexpected " + TextScanner::quote(token) + " after the last " + items +
                      " (wrong count in the header?)");
}

// Reads the .node file; `base` receives the first index (0 or 1).
bool read_nodes(TextScanner& scanner, TetMesh& mesh, int64_t* base) {
  uint64_t count = 0;
  int64_t dimension = 3, attributes = 0, markers = 0;
  if (!scanner.read_count(&count, "point count", 0)) return false;
  const uint64_t rest = scanner.remaining_bytes();  // (the header's rest included)
  TextScanner header = rest_of_header(scanner);
  if (!read_header_field(header, &dimension, "dimension") ||
      !read_header_field(header, &attributes, "attribute count") ||
      !read_header_field(header, &markers, "boundary marker count") ||
      !expect_end_of_header(header, "'points dimension attributes markers'")) {
    return scanner.adopt_failure(header);
  }
  if (dimension != 3) {
    header.fail("only 3-dimensional points are supported (dimension " + std::to_string(dimension) +
                ")");
    return scanner.adopt_failure(header);
  }
  if (markers > 1) {
    header.fail("boundary marker count must be 0 or 1");
    return scanner.adopt_failure(header);
  }
  // A point line "i x y z\n" takes at least 8 bytes (checked after the dimension: a 2-D
  // file's shorter lines were said to be too few for its count).
  if (count > (rest + 1) / 8) {
    header.fail("point count " + std::to_string(count) +
                " is larger than the rest of the file can hold (wrong count or truncated file?)");
    return scanner.adopt_failure(header);
  }
  if (count == 0) return scanner.fail("no points (points in a .poly file are not supported)");
  if (count >= kInvalidIndex) return scanner.fail("too many points");
  mesh.positions.reserve(count);
  for (uint64_t i = 0; i < count; ++i) {
    int64_t index = 0;
    if (!scanner.read_int(&index, "point index")) return false;
    if (i == 0) {
      if (index != 0 && index != 1) {
        return scanner.fail("the first point index is " + std::to_string(index) +
                            "; it must be 0 or 1");
      }
      *base = index;
    } else if (index != *base + int64_t(i)) {
      return scanner.fail("expected point index " + std::to_string(*base + int64_t(i)) +
                          ", found " + std::to_string(index));
    }
    Vec3 p;
    if (!scanner.read_double(&p.x, "x coordinate") || !scanner.read_double(&p.y, "y coordinate") ||
        !scanner.read_double(&p.z, "z coordinate") ||
        !scanner.skip_numbers(uint64_t(attributes) + uint64_t(markers), "point attributes") ||
        !skip_extra_fields(scanner, "point")) {
      return false;
    }
    mesh.positions.push_back(p);
  }
  return expect_end_of_file(scanner, "point");
}

// Reads the .ele file; `nodes_per_tet` receives 4 or 10.
bool read_elements(TextScanner& scanner, int64_t base, ParsedMesh* out, int64_t* nodes_per_tet) {
  uint64_t count = 0;
  int64_t attributes = 0;
  int64_t& corners = *nodes_per_tet;
  corners = 4;
  if (!scanner.read_count(&count, "tetrahedron count", 10)) return false;
  TextScanner header = rest_of_header(scanner);
  if (!read_header_field(header, &corners, "nodes per tetrahedron") ||
      !read_header_field(header, &attributes, "attribute count") ||
      !expect_end_of_header(header, "'tetrahedra nodes-per-tetrahedron attributes'")) {
    return scanner.adopt_failure(header);
  }
  if (corners != 4 && corners != 10) {
    header.fail("nodes per tetrahedron must be 4 or 10, found " + std::to_string(corners));
    return scanner.adopt_failure(header);
  }
  if (count >= kInvalidIndex) return scanner.fail("too many tetrahedra");
  TetMesh& mesh = out->mesh;
  mesh.tets.reserve(count);
  mesh.materials.reserve(count);
  out->tet_lines.reserve(count);
  for (uint64_t i = 0; i < count; ++i) {
    int64_t index = 0;
    if (!scanner.read_int(&index, "tetrahedron index")) return false;
    if (index != base + int64_t(i)) {
      return scanner.fail("expected tetrahedron index " + std::to_string(base + int64_t(i)) +
                          ", found " + std::to_string(index));
    }
    out->tet_lines.push_back(line_number(scanner.line()));
    Tet tet;
    // The corners, then (TetGen -o2) the mid-side points: read by the corners, but each
    // must be a point, as a corner must.
    for (int k = 0; k < corners; ++k) {
      int64_t vertex = 0;
      if (!scanner.read_int(&vertex, "vertex index")) return false;
      if (vertex < base || vertex - base >= int64_t(mesh.positions.size())) {
        return scanner.fail("vertex index " + std::to_string(vertex) + " is out of range (the " +
                            "points are numbered from " + std::to_string(base) + " to " +
                            std::to_string(base + int64_t(mesh.positions.size()) - 1) + ")");
      }
      if (k < 4) tet[k] = uint32_t(vertex - base);
    }
    int32_t material = 0;
    if ((attributes > 0 && !read_material(scanner, &material)) ||
        !scanner.skip_numbers(uint64_t(attributes > 0 ? attributes - 1 : 0), "attributes") ||
        !skip_extra_fields(scanner, "tetrahedron")) {
      return false;
    }
    mesh.tets.push_back(tet);
    mesh.materials.push_back(material);
  }
  return expect_end_of_file(scanner, "tetrahedron");
}

// Reads the .face file into out->surface_groups (see the top of the file).
// `nodes_per_tet`: of the .ele file (4 or 10).
Status read_faces(TextScanner& scanner, int64_t base, int64_t nodes_per_tet, ParsedMesh* out) {
  uint64_t count = 0;
  int64_t markers = 0;
  // A face line "i a b c\n" takes at least 8 bytes.
  if (!scanner.read_count(&count, "face count", 8)) return scanner.status();
  TextScanner header = rest_of_header(scanner);
  if (!read_header_field(header, &markers, "boundary marker count") ||
      !expect_end_of_header(header, "'faces markers'")) {
    scanner.adopt_failure(header);
    return scanner.status();
  }
  if (markers > 1) {
    header.fail("boundary marker count must be 0 or 1");
    scanner.adopt_failure(header);
    return scanner.status();
  }
  const std::vector<Vec3>& positions = out->mesh.positions;
  const int nodes_per_face = nodes_per_tet == 10 ? 6 : 3;
  const std::string form = std::string("'index a b c") + (nodes_per_face == 6 ? " d e f" : "") +
                           (markers == 1 ? " marker" : "") + "'";
  SurfaceElements surface;  // the faces with a marker, kept only as groups (the CLI says so)
  uint64_t unkept = 0;      // faces whose marker is not a group tag
  std::string first_unkept;
  uint64_t undeclared = 0;  // faces with a marker column the header does not declare
  size_t first_undeclared = 0;
  for (uint64_t i = 0; i < count; ++i) {
    int64_t index = 0;
    if (!scanner.read_int(&index, "face index")) return scanner.status();
    if (index != base + int64_t(i)) {
      scanner.fail("expected face index " + std::to_string(base + int64_t(i)) + ", found " +
                   std::to_string(index));
      return scanner.status();
    }
    // The rest of the face's line; a number at its end is cut off only if the text
    // ends there.
    const size_t line = scanner.line();
    const bool line_ends = scanner.remaining_text().find('\n') != std::string_view::npos;
    TextScanner fields(scanner.rest_of_line(), scanner.name(), '#', line);
    fields.set_number_may_end_text(line_ends);
    auto read_field = [&](int64_t* value, const char* what) {
      if (fields.at_end()) {
        return fields.fail("face " + std::to_string(index) + " ends before its " + what +
                           " (one face per line: " + form + ")");
      }
      return fields.read_int(value, what);
    };
    std::array<Vec3, 3> corners;
    int64_t vertex[3] = {0, 0, 0};
    for (int k = 0; k < nodes_per_face; ++k) {
      int64_t v = 0;
      if (!read_field(&v, "vertex index")) return fields.status();
      if (v < base || v - base >= int64_t(positions.size())) {
        fields.fail("vertex index " + std::to_string(v) + " is out of range (the points are " +
                    "numbered from " + std::to_string(base) + " to " +
                    std::to_string(base + int64_t(positions.size()) - 1) +
                    "; is the .face file another mesh's?)");
        return fields.status();
      }
      if (k < 3) {
        vertex[k] = v;
        corners[size_t(k)] = positions[size_t(v - base)];
      }
    }
    if (vertex[0] == vertex[1] || vertex[1] == vertex[2] || vertex[0] == vertex[2]) {
      fields.fail("face " + std::to_string(index) + " repeats a vertex");
      return fields.status();
    }
    int64_t marker = 0;
    if (markers == 1 && !read_field(&marker, "boundary marker")) return fields.status();
    // Nothing more, or the two tets beside the face (TetGen -nn); without markers in
    // the header, one number there is a marker column the header leaves out: TetGen
    // ignores it, and a note says so.
    if (!fields.at_end()) {
      int64_t tet = 0;
      std::string_view extra;
      if (!fields.read_int(&tet, "adjacent tetrahedron")) return fields.status();
      if (markers == 0 && fields.at_end()) {
        if (undeclared++ == 0) first_undeclared = line;
        continue;
      }
      if (!read_field(&tet, "second adjacent tetrahedron")) return fields.status();
      if (fields.next_token(&extra)) {
        fields.fail("unexpected " + TextScanner::quote(extra) + " after face " +
                    std::to_string(index) + " (one face per line: " + form +
                    ", then at most the two tets beside it)");
        return fields.status();
      }
    }
    if (marker == 0) continue;  // no marker
    if (marker < 0 || marker > std::numeric_limits<int32_t>::max()) {
      if (unkept++ == 0)
        first_unkept = "line " + std::to_string(line) + ", marker " + std::to_string(marker);
      continue;
    }
    surface.count();
    surface.add_triangle(int32_t(marker), corners[0], corners[1], corners[2]);
  }
  if (undeclared > 0) {
    out->notes.push_back(std::to_string(undeclared) +
                         (undeclared == 1 ? " face of " : " faces of ") + scanner.name() +
                         " (the first at line " + std::to_string(first_undeclared) + ") " +
                         (undeclared == 1 ? "has" : "have") +
                         " a number after the corners, but the header declares no boundary "
                         "markers ('count 0' or 'count'): ignored, as TetGen ignores it (make "
                         "the header 'count 1' to read the markers as surface groups)");
  }
  if (unkept > 0) {
    out->notes.push_back(std::to_string(unkept) + (unkept == 1 ? " face of " : " faces of ") +
                         scanner.name() + (unkept == 1 ? " has a marker" : " have markers") +
                         " outside 1 to 2147483647 (the first at " + first_unkept +
                         "); no surface group holds " + (unkept == 1 ? "it" : "them"));
  }
  surface.finish(out);
  expect_end_of_file(scanner, "face");
  return scanner.status();
}

}  // namespace

Status parse_tetgen(std::string_view node_text, const std::string& node_name,
                    std::string_view ele_text, const std::string& ele_name, ParsedMesh* out,
                    std::string_view face_text, const std::string* face_name) {
  TextScanner nodes(node_text, node_name, '#');
  int64_t base = 0;
  if (!read_nodes(nodes, out->mesh, &base)) return nodes.status();
  TextScanner elements(ele_text, ele_name, '#');
  int64_t nodes_per_tet = 4;
  if (!read_elements(elements, base, out, &nodes_per_tet)) return elements.status();
  if (nodes_per_tet == 10 && !out->mesh.tets.empty()) {
    out->notes.push_back(std::to_string(out->mesh.tets.size()) +
                         " 10-node tetrahedra (TetGen -o2) were read as 4-node ones (by their "
                         "corners; their mid-edge nodes are dropped)");
  }
  if (face_name) {
    TextScanner faces(face_text, *face_name, '#');
    if (Status status = read_faces(faces, base, nodes_per_tet, out); !status) return status;
  }
  return Status();
}

void write_tetgen_node(const TetMesh& mesh, std::string* out) {
  out->reserve(out->size() + mesh.vertex_count() * 64);
  append_line(out, mesh.vertex_count(), 3, 0, 0);  // count, dimension, attributes, markers
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions[v];
    append_line(out, v + 1, p.x, p.y, p.z);
  }
}

void write_tetgen_ele(const TetMesh& mesh, std::string* out) {
  out->reserve(out->size() + mesh.tet_count() * 48);
  append_line(out, mesh.tet_count(), 4, 1);  // count, nodes per tet, attributes
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    append_line(out, t + 1, tet[0] + 1, tet[1] + 1, tet[2] + 1, tet[3] + 1, mesh.materials[t]);
  }
}

void write_tetgen_face(const SurfaceGroups& surfaces, std::string* out, bool markers) {
  out->reserve(out->size() + surfaces.surface.size() * 32);
  append_line(out, surfaces.surface.size(), markers ? 1 : 0);  // count, boundary markers
  size_t face = 0;
  for (const SurfaceGroup& group : surfaces.groups) {
    for (uint32_t i : group.triangles) {
      const auto& v = surfaces.surface[i].v;
      if (markers)
        append_line(out, ++face, v[0] + 1, v[1] + 1, v[2] + 1, group.tag);
      else
        append_line(out, ++face, v[0] + 1, v[1] + 1, v[2] + 1);
    }
  }
}

}  // namespace tetlod::io
