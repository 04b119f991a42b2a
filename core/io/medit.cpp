// Medit / Gamma Mesh Format, ASCII (.mesh) and binary (.meshb). Entry widths of the skipped
// keywords follow the keyword table of libMeshb (L. Maréchal, INRIA), for Dimension 3.
#include <array>
#include <cstring>
#include <limits>

#include "core/io/binary_values.h"
#include "core/io/gmf_binary.h"
#include "core/io/mesh_formats.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"

namespace tetlod::io {
namespace {

struct SkippedKeyword {
  const char* name;
  bool has_count;         // "Keyword count" then count entries; else one entry
  int numbers_per_entry;  // for Dimension 3
};

constexpr SkippedKeyword kSkippedKeywords[] = {
    {"Edges", true, 3},
    {"Quadrilaterals", true, 5},
    {"Prisms", true, 7},
    {"Pentahedra", true, 7},
    {"Pyramids", true, 6},
    {"Hexahedra", true, 9},
    {"Corners", true, 1},
    {"Ridges", true, 1},
    {"RequiredVertices", true, 1},
    {"RequiredEdges", true, 1},
    {"RequiredTriangles", true, 1},
    {"RequiredQuadrilaterals", true, 1},
    {"RequiredTetrahedra", true, 1},
    {"Normals", true, 3},
    {"Tangents", true, 3},
    {"NormalAtVertices", true, 2},
    {"NormalAtTriangleVertices", true, 3},
    {"NormalAtQuadrilateralVertices", true, 4},
    {"TangentAtVertices", true, 2},
    {"TangentAtEdges", true, 3},
    {"TangentAtEdgeVertices", true, 3},
    {"EdgesP2", true, 4},
    {"QuadrilateralsQ2", true, 10},
    {"HexahedraQ2", true, 28},
    {"VerticesOnGeometricVertices", true, 2},
    {"VerticesOnGeometricEdges", true, 4},
    {"VerticesOnGeometricTriangles", true, 5},
    {"EdgesOnGeometricEdges", true, 2},
    {"TrianglesOnGeometricTriangles", true, 2},
    {"AngleOfCornerBound", false, 1},
    {"BoundingBox", false, 6},
    {"Iterations", false, 1},
    {"Time", false, 1},
    {"FloatingPointPrecision", false, 1},
};

// Keywords followed by one string, possibly quoted with spaces inside.
constexpr const char* kStringKeywords[] = {"Identifier", "Geometry", "MeshSupportOfVertices"};

const SkippedKeyword* find_skipped(std::string_view keyword) {
  for (const SkippedKeyword& skipped : kSkippedKeywords) {
    if (TextScanner::equals_ignore_case(keyword, skipped.name)) return &skipped;
  }
  return nullptr;
}

bool is_string_keyword(std::string_view keyword) {
  for (const char* name : kStringKeywords) {
    if (TextScanner::equals_ignore_case(keyword, name)) return true;
  }
  return false;
}

bool skip_string(TextScanner& scanner, std::string_view keyword) {
  std::string_view token;
  const std::string what = "the string after " + std::string(keyword);
  if (!scanner.next_token(&token)) return scanner.fail("unexpected end of file, expected " + what);
  if (token[0] != '"' || (token.size() > 1 && token.back() == '"')) return true;
  while (scanner.next_token(&token)) {
    if (token.back() == '"') return true;
  }
  return scanner.fail("unexpected end of file inside " + what);
}

bool read_vertices(TextScanner& scanner, TetMesh& mesh) {
  uint64_t count = 0;
  // An entry "x y z ref" takes at least 8 bytes.
  if (!scanner.read_count(&count, "vertex count", 8)) return false;
  if (count >= kInvalidIndex) return scanner.fail("too many vertices");
  mesh.positions.reserve(count);
  int64_t reference = 0;
  for (uint64_t i = 0; i < count; ++i) {
    Vec3 p;
    if (!scanner.read_double(&p.x, "x coordinate") || !scanner.read_double(&p.y, "y coordinate") ||
        !scanner.read_double(&p.z, "z coordinate") ||
        !scanner.read_int(&reference, "vertex reference")) {
      return false;
    }
    mesh.positions.push_back(p);
  }
  return true;
}

// Appends a Tetrahedra section's entries (meshio writes one section per cell block), or a
// TetrahedraP2 section's (Gmsh's second-order export: the 4 corners, then the 6 mid-edge
// nodes, which are not kept; validation drops them as unused) by their corners.
bool read_tets(TextScanner& scanner, ParsedMesh* out, int nodes_per_entry) {
  uint64_t count = 0;
  // An entry "a b c d ref" takes at least 10 bytes (a P2 one, 22).
  if (!scanner.read_count(&count, "tetrahedron count", 2 * uint64_t(nodes_per_entry) + 2))
    return false;
  TetMesh& mesh = out->mesh;
  if (count >= kInvalidIndex - mesh.tets.size()) return scanner.fail("too many tetrahedra");
  mesh.tets.reserve(mesh.tets.size() + count);
  mesh.materials.reserve(mesh.materials.size() + count);
  out->tet_lines.reserve(out->tet_lines.size() + count);
  for (uint64_t i = 0; i < count; ++i) {
    Tet tet;
    for (int k = 0; k < 4; ++k) {
      int64_t index = 0;
      if (!scanner.read_int(&index, "vertex index")) return false;
      if (k == 0) out->tet_lines.push_back(line_number(scanner.line()));
      if (index < 1 || index > int64_t{kInvalidIndex}) {
        return scanner.fail("vertex index " + std::to_string(index) +
                            " is out of range (Medit indices start at 1)");
      }
      tet[k] = uint32_t(index - 1);
    }
    for (int k = 4; k < nodes_per_entry; ++k) {
      int64_t index = 0;
      if (!scanner.read_int(&index, "mid-edge vertex index")) return false;
      if (index < 1 || index > int64_t{kInvalidIndex}) {
        return scanner.fail("vertex index " + std::to_string(index) +
                            " is out of range (Medit indices start at 1)");
      }
    }
    int64_t material = 0;
    if (!scanner.read_int_in_range(&material, "tetrahedron reference (material)",
                                   std::numeric_limits<int32_t>::min(),
                                   std::numeric_limits<int32_t>::max())) {
      return false;
    }
    mesh.tets.push_back(tet);
    mesh.materials.push_back(int32_t(material));
  }
  return true;
}

// A Triangles section's entries "a b c ref", kept with a reference >= 1 (a boundary
// condition's id, as MMG and TetLOD write them) for ParsedMesh::surface_groups; or a
// TrianglesP2 section's "a b c ab bc ca ref", by their corners.
struct PendingTriangle {
  int64_t v[3];
  int64_t ref;
};
bool read_triangles(TextScanner& scanner, std::vector<PendingTriangle>* out,
                    SurfaceElements* surface, int nodes_per_entry) {
  uint64_t count = 0;
  if (!scanner.read_count(&count, "triangle count", 2 * uint64_t(nodes_per_entry) + 2))
    return false;
  surface->count(count);
  for (uint64_t i = 0; i < count; ++i) {
    PendingTriangle t;
    for (int64_t& v : t.v)
      if (!scanner.read_int(&v, "triangle vertex index")) return false;
    for (int k = 3; k < nodes_per_entry; ++k) {
      int64_t mid = 0;
      if (!scanner.read_int(&mid, "mid-edge vertex index")) return false;
    }
    if (!scanner.read_int(&t.ref, "triangle reference")) return false;
    if (t.ref >= 1 && t.ref <= std::numeric_limits<int32_t>::max()) out->push_back(t);
  }
  return true;
}

// What a Medit file (ASCII or binary) holds besides its vertices and tets: the
// triangles for the surface groups, and what the notes tell of.
struct Sections {
  bool seen_vertices = false;
  bool seen_tets = false;
  std::string skipped_volumes;  // "28 Prisms, 3 Hexahedra"
  uint64_t quadratic_tets = 0;  // TetrahedraP2, read by their corners
  uint64_t edges = 0;           // Edges and EdgesP2, not kept
  std::vector<PendingTriangle> triangles;
  SurfaceElements surface;  // kept only as groups (the CLI says so)

  // Volume elements other than tets are not read: the notes say so.
  void skip_volumes(const char* name, uint64_t count) {
    if (count > 0)
      skipped_volumes += (skipped_volumes.empty() ? "" : ", ") + std::to_string(count) + " " + name;
  }
};

// After the last section: the errors for what is missing, the surface groups and the
// notes.
Status finish(const std::string& name, Sections& s, ParsedMesh* out) {
  if (!s.seen_vertices) return Status::error(name + ": no Vertices section");
  if (!s.seen_tets) {
    return Status::error(
        name + ": no Tetrahedra section" +
        (s.skipped_volumes.empty()
             ? std::string()
             : " (TetLOD reads 4-node tetrahedra only, not " + s.skipped_volumes + ")"));
  }
  // The referenced triangles, by reference, as surface groups (positions: the indices
  // are checked here, the vertices before validation may drop unused ones).
  size_t outside = 0;
  for (const PendingTriangle& t : s.triangles) {
    std::array<Vec3, 3> corners;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      ok = ok && t.v[k] >= 1 && uint64_t(t.v[k]) <= out->mesh.positions.size();
      if (ok) corners[size_t(k)] = out->mesh.positions[size_t(t.v[k] - 1)];
    }
    if (!ok) {
      ++outside;
      continue;
    }
    s.surface.add_triangle(int32_t(t.ref), corners[0], corners[1], corners[2]);
  }
  s.surface.finish(out);
  if (outside > 0) {
    out->notes.push_back(std::to_string(outside) +
                         " triangles name a vertex that is not in Vertices: not kept");
  }
  if (s.quadratic_tets > 0) {
    out->notes.push_back(std::to_string(s.quadratic_tets) +
                         " TetrahedraP2 (10-node) were read as 4-node tetrahedra (by their "
                         "corners; their mid-edge points are dropped)");
  }
  if (s.edges > 0) {
    out->notes.push_back(std::to_string(s.edges) +
                         (s.edges == 1 ? " edge (Edges) is" : " edges (Edges) are") +
                         " not kept: TetLOD keeps the tetrahedra, and Triangles as surface "
                         "groups");
  }
  if (!s.skipped_volumes.empty()) {
    out->notes.push_back("skipped " + s.skipped_volumes +
                         ": TetLOD reads 4-node tetrahedra only, so a region meshed with other "
                         "elements is not in the mesh");
  }
  return Status();
}

// Medit binary (.meshb): libMeshb's layout (core/io/gmf_binary.h).
// The keywords with entries of integers only that a reader counts (surface elements
// and other volumes, for the notes): name, integers per entry.
struct CountedKeyword {
  int64_t code;
  const char* name;
  int integers;
};
constexpr CountedKeyword kCountedKeywords[] = {
    {kGmfEdges, "Edges", 3},
    {kGmfEdgesP2, "EdgesP2", 4},
    {kGmfQuadrilaterals, "Quadrilaterals", 5},
    {kGmfQuadrilateralsQ2, "QuadrilateralsQ2", 10},
    {kGmfPrisms, "Prisms", 7},
    {kGmfPyramids, "Pyramids", 6},
    {kGmfHexahedra, "Hexahedra", 9},
    {kGmfHexahedraQ2, "HexahedraQ2", 28},
};

class MeditBinaryReader {
 public:
  MeditBinaryReader(std::string_view data, const std::string& name, ParsedMesh* out)
      : gmf_(data, name, "Medit", ".meshb", ".mesh"), name_(name), out_(out) {}

  Status read() {
    const Status walked = gmf_.walk(
        [this](int64_t keyword, size_t body, size_t end) { return section(keyword, body, end); });
    if (!walked) return walked;
    return finish(name_, sections_, out_);
  }

 private:
  bool fail(size_t at, const std::string& message) { return gmf_.fail(at, message); }
  int64_t integer(size_t at, size_t size) const { return gmf_.integer(at, size); }
  double real(size_t at) const { return gmf_.real(at); }
  bool count(size_t* at, size_t end, size_t entry_size, const char* what, uint64_t* n) {
    return gmf_.count(at, end, entry_size, what, n);
  }

  // A vertex index (1-based) at `at`, checked as the ASCII reader does.
  bool vertex_index(size_t at, uint32_t* index) {
    const int64_t value = integer(at, gmf_.integer_size());
    if (value < 1 || value > int64_t{kInvalidIndex}) {
      return fail(at, "vertex index " + std::to_string(value) +
                          " is out of range (Medit indices start at 1)");
    }
    *index = uint32_t(value - 1);
    return true;
  }

  bool section(int64_t keyword, size_t at, size_t end) {
    uint64_t n = 0;
    switch (keyword) {
      case kGmfDimension:
        return gmf_.dimension(at, end, "meshes");
      case kGmfFloatingPointPrecision:
        return gmf_.precision(at, end, sections_.seen_vertices ? "Vertices" : nullptr);
      case kGmfVertices: {
        if (sections_.seen_vertices) return fail(at, "a second Vertices section");
        sections_.seen_vertices = true;
        const size_t entry = 3 * gmf_.real_size() + gmf_.integer_size();
        if (!count(&at, end, entry, "Vertices", &n)) return false;
        if (n >= kInvalidIndex) return fail(at, "too many vertices");
        auto& positions = out_->mesh.positions;
        positions.resize(n);
        for (uint64_t i = 0; i < n; ++i, at += entry) {
          Vec3& p = positions[i];
          p = {real(at), real(at + gmf_.real_size()), real(at + 2 * gmf_.real_size())};
          if (!is_finite(p))
            return fail(at, "vertex " + std::to_string(i + 1) + ": a coordinate is not finite");
        }
        return true;
      }
      case kGmfTetrahedra:
      case kGmfTetrahedraP2: {
        sections_.seen_tets = true;
        const size_t nodes = keyword == kGmfTetrahedra ? 4 : 10;
        const size_t entry = (nodes + 1) * gmf_.integer_size();
        if (!count(&at, end, entry, keyword == kGmfTetrahedra ? "Tetrahedra" : "TetrahedraP2", &n))
          return false;
        TetMesh& mesh = out_->mesh;
        if (n >= kInvalidIndex - mesh.tets.size()) return fail(at, "too many tetrahedra");
        mesh.tets.reserve(mesh.tets.size() + n);
        mesh.materials.reserve(mesh.materials.size() + n);
        for (uint64_t i = 0; i < n; ++i, at += entry) {
          Tet tet;
          for (size_t k = 0; k < nodes; ++k) {
            uint32_t index = 0;
            if (!vertex_index(at + k * gmf_.integer_size(), &index)) return false;
            if (k < 4) tet[k] = index;
          }
          const int64_t material = integer(at + nodes * gmf_.integer_size(), gmf_.integer_size());
          if (material < std::numeric_limits<int32_t>::min() ||
              material > std::numeric_limits<int32_t>::max()) {
            return fail(at + nodes * gmf_.integer_size(), "tetrahedron reference (material) " +
                                                              std::to_string(material) +
                                                              " is out of range");
          }
          mesh.tets.push_back(tet);
          mesh.materials.push_back(int32_t(material));
        }
        if (keyword == kGmfTetrahedraP2) sections_.quadratic_tets += n;
        return true;
      }
      case kGmfTriangles:
      case kGmfTrianglesP2: {
        const size_t nodes = keyword == kGmfTriangles ? 3 : 6;
        const size_t entry = (nodes + 1) * gmf_.integer_size();
        if (!count(&at, end, entry, keyword == kGmfTriangles ? "Triangles" : "TrianglesP2", &n))
          return false;
        sections_.surface.count(n);
        for (uint64_t i = 0; i < n; ++i, at += entry) {
          PendingTriangle t;
          for (size_t k = 0; k < 3; ++k)
            t.v[k] = integer(at + k * gmf_.integer_size(), gmf_.integer_size());
          t.ref = integer(at + nodes * gmf_.integer_size(), gmf_.integer_size());
          if (t.ref >= 1 && t.ref <= std::numeric_limits<int32_t>::max())
            sections_.triangles.push_back(t);
        }
        return true;
      }
      default:
        for (const CountedKeyword& counted : kCountedKeywords) {
          if (keyword != counted.code) continue;
          if (!count(&at, end, size_t(counted.integers) * gmf_.integer_size(), counted.name, &n))
            return false;
          if (keyword == kGmfQuadrilaterals || keyword == kGmfQuadrilateralsQ2) {
            sections_.surface.count(n);
          } else if (keyword == kGmfEdges || keyword == kGmfEdgesP2) {
            sections_.edges += n;
          } else {
            sections_.skip_volumes(counted.name, n);
          }
        }
        return true;  // any other keyword: skipped
    }
  }

  GmfBinary gmf_;
  const std::string& name_;
  ParsedMesh* out_;
  Sections sections_;
};

// Appends `size` bytes of `bits`, least significant first (.meshb files TetLOD
// writes are little-endian, as libMeshb writes them on x86 and ARM).
void put(std::string* out, uint64_t bits, size_t size) {
  char bytes[8];
  for (size_t i = 0; i < size; ++i) bytes[i] = char(bits >> (8 * i));
  out->append(bytes, size);
}
void put_real(std::string* out, double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, 8);
  put(out, bits, 8);
}

}  // namespace

Status parse_medit(std::string_view text, const std::string& name, ParsedMesh* out) {
  TextScanner scanner(text, name, '#');
  std::string_view keyword;
  if (!scanner.next_token(&keyword) ||
      !TextScanner::equals_ignore_case(keyword, "MeshVersionFormatted")) {
    // A binary file named .mesh starts with libMeshb's 4-byte 1 (in either byte order).
    const bool binary = text.size() >= 8 && (text.substr(0, 4) == std::string_view("\1\0\0\0", 4) ||
                                             text.substr(0, 4) == std::string_view("\0\0\0\1", 4));
    scanner.fail(binary ? "not an ASCII Medit file: it starts as a binary one does (name it .meshb)"
                        : "not a Medit file: expected 'MeshVersionFormatted' first");
    return scanner.status();
  }
  int64_t value = 0;
  if (!scanner.read_int_in_range(&value, "MeshVersionFormatted value", 1, 4)) {
    return scanner.status();
  }
  Sections sections;

  while (!scanner.failed() && scanner.next_token(&keyword)) {
    auto is = [&](const char* word) { return TextScanner::equals_ignore_case(keyword, word); };
    if (is("End")) break;
    if (is("Dimension")) {
      if (scanner.read_int(&value, "dimension") && value != 3) {
        scanner.fail("only 3-dimensional meshes are supported (Dimension " + std::to_string(value) +
                     ")");
      }
    } else if (is("Vertices")) {
      if (sections.seen_vertices) scanner.fail("a second Vertices section");
      sections.seen_vertices = true;
      read_vertices(scanner, out->mesh);
    } else if (is("Tetrahedra")) {
      sections.seen_tets = true;
      read_tets(scanner, out, 4);
    } else if (is("TetrahedraP2")) {
      sections.seen_tets = true;
      const size_t before = out->mesh.tets.size();
      if (read_tets(scanner, out, 10)) sections.quadratic_tets += out->mesh.tets.size() - before;
    } else if (is("Triangles")) {
      read_triangles(scanner, &sections.triangles, &sections.surface, 3);
    } else if (is("TrianglesP2")) {
      read_triangles(scanner, &sections.triangles, &sections.surface, 6);
    } else if (const SkippedKeyword* skipped = find_skipped(keyword)) {
      uint64_t count = 1;
      const uint64_t width = uint64_t(skipped->numbers_per_entry);
      if (skipped->has_count) scanner.read_count(&count, "entry count", 2 * width);
      if (!scanner.failed()) scanner.skip_numbers(count * width, skipped->name);
      // Surface elements are kept only as groups (Triangles), and the CLI says so.
      for (const char* kind : {"Quadrilaterals", "QuadrilateralsQ2"})
        if (std::string_view(skipped->name) == kind) sections.surface.count(count);
      for (const char* kind : {"Edges", "EdgesP2"})
        if (std::string_view(skipped->name) == kind) sections.edges += count;
      for (const char* volume : {"Prisms", "Pentahedra", "Pyramids", "Hexahedra", "HexahedraQ2"})
        if (std::string_view(skipped->name) == volume) sections.skip_volumes(volume, count);
    } else if (is_string_keyword(keyword)) {
      skip_string(scanner, keyword);
    } else if (TextScanner::looks_numeric(keyword)) {
      scanner.fail("found the number " + TextScanner::quote(keyword) +
                   " where a keyword was expected (is the count of the section above right?)");
    } else {
      scanner.fail("unknown keyword " + TextScanner::quote(keyword));
    }
  }
  if (scanner.failed()) return scanner.status();
  return finish(name, sections, out);
}

void write_medit(const TetMesh& mesh, const SurfaceGroups* surfaces, std::string* out) {
  out->reserve(out->size() + mesh.vertex_count() * 64 + mesh.tet_count() * 40);
  out->append("MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n");
  append_line(out, mesh.vertex_count());
  for (const Vec3& p : mesh.positions) append_line(out, p.x, p.y, p.z, 0);
  if (surfaces) {  // reference = the group's tag, as MMG reads boundary references
    out->append("\nTriangles\n");
    append_line(out, surfaces->surface.size());
    for (const SurfaceGroup& group : surfaces->groups) {
      for (uint32_t i : group.triangles) {
        const auto& v = surfaces->surface[i].v;
        append_line(out, v[0] + 1, v[1] + 1, v[2] + 1, group.tag);
      }
    }
  }
  out->append("\nTetrahedra\n");
  append_line(out, mesh.tet_count());
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    append_line(out, tet[0] + 1, tet[1] + 1, tet[2] + 1, tet[3] + 1, mesh.materials[t]);
  }
  out->append("\nEnd\n");
}

Status parse_medit_binary(std::string_view data, const std::string& name, ParsedMesh* out) {
  return MeditBinaryReader(data, name, out).read();
}

void write_medit_binary(const TetMesh& mesh, const SurfaceGroups* surfaces, std::string* out,
                        int min_version) {
  uint64_t triangles = 0;
  if (surfaces)
    for (const SurfaceGroup& group : surfaces->groups) triangles += group.triangles.size();
  const uint64_t vertices = mesh.vertex_count(), tets = mesh.tet_count();
  // Version 2 (8-byte reals, 4-byte integers and positions), which every libMeshb
  // reads, while the file fits in 2^31 bytes; else 3 (8-byte positions); 4 (8-byte
  // integers) only for vertex numbers past 2^31 - 1.
  const int64_t int32_max = std::numeric_limits<int32_t>::max();
  const size_t integer = vertices >= uint64_t(int32_max) || min_version >= 4 ? 8 : 4;
  auto file_size = [&](uint64_t position) {
    return 8 + (4 + position + 4) + (4 + position + integer + vertices * (24 + integer)) +
           (triangles > 0 ? 4 + position + integer + triangles * 4 * integer : 0) +
           (4 + position + integer + tets * 5 * integer) + (4 + position);
  };
  const int version = integer == 8                                              ? 4
                      : file_size(4) <= uint64_t(int32_max) && min_version <= 2 ? 2
                                                                                : 3;
  const size_t position = version >= 3 ? 8 : 4;
  const size_t base = out->size();
  out->reserve(base + file_size(position));
  put(out, 1, 4);
  put(out, uint64_t(version), 4);
  // A keyword's header: its code, then where the next keyword starts (after `body`
  // bytes of count and entries); the End keyword's next position is 0.
  auto keyword = [&](int64_t code, uint64_t body) {
    put(out, uint64_t(code), 4);
    put(out, code == kGmfEnd ? 0 : out->size() - base + position + body, position);
  };
  keyword(kGmfDimension, 4);
  put(out, 3, 4);
  keyword(kGmfVertices, integer + vertices * (24 + integer));
  put(out, vertices, integer);
  for (const Vec3& p : mesh.positions) {
    put_real(out, p.x);
    put_real(out, p.y);
    put_real(out, p.z);
    put(out, 0, integer);
  }
  if (triangles > 0) {  // reference = the group's tag, as MMG reads boundary references
    keyword(kGmfTriangles, integer + triangles * 4 * integer);
    put(out, triangles, integer);
    for (const SurfaceGroup& group : surfaces->groups) {
      for (uint32_t i : group.triangles) {
        for (uint32_t v : surfaces->surface[i].v) put(out, uint64_t(v) + 1, integer);
        put(out, uint64_t(int64_t(group.tag)), integer);
      }
    }
  }
  keyword(kGmfTetrahedra, integer + tets * 5 * integer);
  put(out, tets, integer);
  for (size_t t = 0; t < tets; ++t) {
    for (uint32_t v : mesh.tets[t]) put(out, uint64_t(v) + 1, integer);
    put(out, uint64_t(int64_t(mesh.materials[t])), integer);
  }
  keyword(kGmfEnd, 0);
}

}  // namespace tetlod::io
