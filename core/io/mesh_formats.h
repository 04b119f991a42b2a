// The per-format parsers and writers behind mesh_io.h (internal to core/io).
// Parsers fill a ParsedMesh without validating it: mesh_io.cpp runs
// validate_mesh() on the result with the per-tet line numbers. Writers append the
// file text to `out`; they expect a mesh whose indices and materials were checked.
#pragma once

#include <array>
#include <cstdint>
#include <iterator>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/status.h"
#include "core/surface.h"
#include "core/tet_mesh.h"
#include "core/utf8.h"

namespace tetlod::io {

struct ParsedMesh {
  TetMesh mesh;
  std::vector<uint32_t> tet_lines;                // 1-based line of each tet in the file
  std::vector<std::string> notes;                 // what a user should know of how it was read
  std::vector<InputSurfaceGroup> surface_groups;  // the file's own (ReadInfo)
  std::vector<MaterialName> material_names;       // ReadInfo's: sorted, present materials
  uint64_t surface_elements_not_kept = 0;         // ReadInfo's
};

Status parse_medit(std::string_view text, const std::string& name, ParsedMesh* out);
// The binary .meshb (libMeshb's versions 1 to 4, either byte order).
Status parse_medit_binary(std::string_view data, const std::string& name, ParsedMesh* out);
// `version` receives 22 or 41.
Status parse_gmsh(std::string_view text, const std::string& name, ParsedMesh* out, int* version);
// `face_name`: of the .face file beside them (`face_text`), or null for none.
Status parse_tetgen(std::string_view node_text, const std::string& node_name,
                    std::string_view ele_text, const std::string& ele_name, ParsedMesh* out,
                    std::string_view face_text = {}, const std::string* face_name = nullptr);
Status parse_vtk_legacy(std::string_view text, const std::string& name, ParsedMesh* out);
Status parse_vtu(std::string_view text, const std::string& name, ParsedMesh* out);
Status parse_nastran(std::string_view text, const std::string& name, ParsedMesh* out);
Status parse_abaqus(std::string_view text, const std::string& name, ParsedMesh* out);

// `surfaces` (group_surface() of the mesh, or null for none): the surface groups
// to write as well, in the format's way (mesh_io.h).
void write_medit(const TetMesh& mesh, const SurfaceGroups* surfaces, std::string* out);
// Little-endian, version 2 (or 3 and 4 when positions or vertex numbers need 8 bytes).
// `min_version` (2 to 4): write at least that version. For tests: the files that need
// versions 3 and 4 (2^31 bytes, vertex numbers past 2^31 - 1) are too large to make.
void write_medit_binary(const TetMesh& mesh, const SurfaceGroups* surfaces, std::string* out,
                        int min_version = 2);
// `version` is 22 or 41; `binary`: file type 1 (WriteOptions::gmsh_binary).
// `names`: WriteOptions::material_names, or null.
void write_gmsh(const TetMesh& mesh, int version, bool binary, const SurfaceGroups* surfaces,
                const std::vector<MaterialName>* names, std::string* out);
void write_tetgen_node(const TetMesh& mesh, std::string* out);
void write_tetgen_ele(const TetMesh& mesh, std::string* out);
// Every surface triangle, with its group's tag as its boundary marker, or, without
// `markers`, none (a .face that describes the mesh's faces and gives no groups).
void write_tetgen_face(const SurfaceGroups& surfaces, std::string* out, bool markers = true);
// `binary` (WriteOptions::vtk_binary): .vtk BINARY (big-endian, as the format has it);
// .vtu with its arrays in raw appended data (little-endian, UInt64 headers, as
// ParaView's "binary, appended, not encoded" writes them).
// `names`: WriteOptions::material_names, or null; with the groups' names, in the
// field data (kVtkNameTagArray).
void write_vtk_legacy(const TetMesh& mesh, const SurfaceGroups* surfaces,
                      const std::vector<MaterialName>* names, bool binary, std::string* out);
void write_vtu(const TetMesh& mesh, const SurfaceGroups* surfaces,
               const std::vector<MaterialName>* names, bool binary, std::string* out);
// `names`: WriteOptions::material_names, or null (in comments, as the groups' names).
void write_nastran(const TetMesh& mesh, const SurfaceGroups* surfaces,
                   const std::vector<MaterialName>* names, std::string* out);
void write_abaqus(const TetMesh& mesh, const SurfaceGroups* surfaces,
                  const std::vector<MaterialName>* names, std::string* out);
// With extra point and cell arrays (sizes and names checked by the caller).
void write_vtu(const TetMesh& mesh, const MeshFields& fields, bool binary, std::string* out);

// VTK cell types read as tets (vtk.cpp, vtu.cpp): the quadratic, Lagrange and Bezier
// tets give their corners first.
inline constexpr int64_t kVtkTetra = 10;
inline constexpr int64_t kVtkQuadraticTetra = 24;
inline constexpr int64_t kVtkLagrangeTetra = 71;
inline constexpr int64_t kVtkBezierTetra = 78;
// Whether a cell of `type` with `size` points is a tet TetLOD reads (by its first four
// points): a tet, a quadratic one of 10 points, a Lagrange or Bezier one of any order
// (a tetrahedral number of points: 4, 10, 20, 35, ...). `*is_tet` says whether the type is
// one of these, whatever its size.
bool vtk_tet_cell(int64_t type, uint64_t size, bool* is_tet);

// The surface cells of a .vtk or .vtu: triangles and quadrilaterals of any order
// (and strips, polygons, pixels). Each is counted (SurfaceElements); a triangle whose
// value in the material array is >= 1 is kept, by its corners (the first three
// points of every triangle type), in the surface group of that number, as Gmsh's VTK
// export and meshio write a physical surface's number there.
bool is_vtk_surface_cell(int64_t type);
// The number of points a triangle cell of `type` has (0: any >= 3, for the Lagrange
// and Bezier kinds), or -1 if `type` is not a triangle.
int vtk_triangle_points(int64_t type);

// A reader's surface elements: counted (ParsedMesh::surface_elements_not_kept), and
// the triangles of those in a group kept by their corners, by group tag.
class SurfaceElements {
 public:
  void count(uint64_t n = 1) { elements_ += n; }
  // A triangle of the group `tag` (>= 1); count() it too.
  void add_triangle(int32_t tag, const Vec3& a, const Vec3& b, const Vec3& c) {
    triangles_[tag].push_back({a, b, c});
  }
  // The count, and the groups by increasing tag (unnamed).
  void finish(ParsedMesh* out);

 private:
  uint64_t elements_ = 0;
  std::map<int32_t, std::vector<std::array<Vec3, 3>>> triangles_;
};

// The cell array of a .vtk or .vtu that holds the material, by name, best first:
// TetLOD's "material"; what meshio writes for a mesh it read from Gmsh, Medit,
// TetGen or Nastran; VTK's Exodus reader's; TetGen's -k output; Gmsh's elementary
// entity, which meshio writes besides the physical group; last, the physical group
// Gmsh's own VTK export writes (CellEntityIds, -1 for an element in none). -1 for
// other names. Only "material" is read whatever its type; the others only when
// their type is an integer one.
inline constexpr std::string_view kVtkMaterialNames[] = {
    "material",    "gmsh:physical", "medit:ref",        "tetgen:ref",   "nastran:ref",
    "MaterialIds", "cell_scalars",  "gmsh:geometrical", "CellEntityIds"};
inline int vtk_material_rank(std::string_view name) {
  for (int i = 0; i < int(std::size(kVtkMaterialNames)); ++i)
    if (name == kVtkMaterialNames[i]) return i;
  return -1;
}
// After the materials were read from the array of rank `rank` (vtk_material_rank()):
// Gmsh's CellEntityIds give -1 to the tets in no physical group, which become
// material 0, with a note.
inline void finish_vtk_materials(int rank, ParsedMesh* out) {
  if (rank != vtk_material_rank("CellEntityIds")) return;
  size_t ungrouped = 0;
  for (int32_t& m : out->mesh.materials) {
    if (m < 0) {
      m = 0;
      ++ungrouped;
    }
  }
  std::string note =
      "the materials are Gmsh's physical groups (cell array CellEntityIds of its VTK export)";
  if (ungrouped > 0)
    note += "; " + std::to_string(ungrouped) + " tetrahedra in none (-1) are material 0";
  out->notes.push_back(note);
}

// The names of materials and surface groups in a .vtk or .vtu, as TetLOD writes them
// in the dataset's field data and reads them back: the arrays "group_tag" (integers),
// "group_dim" (integers: 3 for a material, 2 for a surface group, as Gmsh's physical
// dimensions: a material and a group may have the same number) and "group_name"
// (strings), row by row (ParaView shows them as a table in its spreadsheet view, Field
// Data). Files without "group_dim" (TetLOD's before 2026-11-28) name by tag both a
// material and a group that have it.
inline constexpr std::string_view kVtkNameTagArray = "group_tag";
inline constexpr std::string_view kVtkNameDimArray = "group_dim";
inline constexpr std::string_view kVtkNameArray = "group_name";
struct VtkNameRow {
  int32_t tag = 0;
  int32_t dim = 3;   // 3: a material; 2: a surface group
  std::string name;  // no NUL bytes
};
// The rows to write: the named materials of `mesh` (`names`: WriteOptions'), then
// the groups of `surfaces`; empty when there are none.
std::vector<VtkNameRow> vtk_name_rows(const TetMesh& mesh, const SurfaceGroups* surfaces,
                                      const std::vector<MaterialName>* names);
// After the reader made the mesh and its surface groups: the names of `tags` (read
// from the arrays) given to the materials (`dims` 3) and groups (2) of those tags, or
// with no `dims` to both; others are ignored, and arrays of unequal length are
// ignored with a note.
void apply_vtk_names(const std::vector<int64_t>& tags, const std::vector<int64_t>& dims,
                     const std::vector<std::string>& names, ParsedMesh* out);

// A name from a file as valid UTF-8: each byte that does not start or continue a
// well-formed sequence becomes '?' (so that JSON, meshio and Gmsh take what is
// written from it).
inline std::string valid_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const size_t start = i;
    if (next_code_point(text, &i) < 0)
      out.push_back('?');
    else
      out.append(text.substr(start, i - start));
  }
  return out;
}

// "2 C3D8, 1 C3D6": counts of the element kinds a reader skipped, for its note.
inline std::string count_list(const std::map<std::string, size_t>& counts) {
  std::string list;
  for (const auto& [kind, count] : counts)
    list += (list.empty() ? "" : ", ") + std::to_string(count) + " " + kind;
  return list;
}

// The notes a .vtk or .vtu reader gives of its cells by VTK type (`counts`, every
// cell): volume cells other than tets that it skipped, and quadratic tets read by
// their corners. Surface cells are counted by VtkSurfaceCells instead (the CLI's
// note); line and vertex cells are skipped without a note.
void add_vtk_cell_notes(const std::vector<uint64_t>& counts_by_type, ParsedMesh* out);

// The note a reader gives when a file has cell arrays but none of them is read as
// the material (`arrays`: their names, as in the file), so that every tet is
// material 0.
std::string no_material_note(const std::vector<std::string>& arrays);

// Saturating conversion of a line number for ParsedMesh::tet_lines.
inline uint32_t line_number(size_t line) {
  return line > 0xffffffffu ? 0xffffffffu : uint32_t(line);
}

}  // namespace tetlod::io
