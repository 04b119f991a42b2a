// Reading and writing tetrahedral meshes in the formats analysts' tools use.
// The format is chosen from the file extension (ASCII case-insensitive):
//   .mesh          Medit ASCII (MMG, CGAL, TetWild, Gmsh); material = tet reference
//   .meshb         Medit binary (libMeshb: MMG, TetWild, meshio); as .mesh
//   .msh           Gmsh 2.2 or 4.1 (read: from $MeshFormat, ASCII or binary in either
//                  byte order; write: 4.1 unless WriteOptions::gmsh_version == 22,
//                  ASCII unless WriteOptions::gmsh_binary); material = physical tag,
//                  else the elementary tag
//   .node / .ele   TetGen pair (either name selects both); material = first region
//                  attribute; 0- or 1-based numbering; a .face file of the same
//                  base name beside them, if any, gives surface groups
//   .vtk           VTK legacy unstructured grid (read: ASCII or binary; write: ASCII
//                  unless WriteOptions::vtk_binary), cell data "material", "stretch"
//   .vtu           VTK XML unstructured grid (read: ASCII, binary or appended data,
//                  zlib-compressed or not; write: ASCII, or raw appended data with
//                  WriteOptions::vtk_binary), cell data "material", "stretch"
//   .bdf / .nas    Nastran bulk data: GRID and CTETRA entries (small, large and free
//                  field); material = the CTETRA's property id (PID); written with
//                  GRID* (16-character coordinates: exact when the shortest exact
//                  form fits, else 10 or more significant digits; after BEGIN BULK)
//   .inp           Abaqus / CalculiX input: *NODE, tetrahedral *ELEMENT types, element
//                  sets and *SOLID SECTION (see io/abaqus.cpp for how materials are
//                  found), element-face *SURFACE as surface groups; written with one
//                  set MATERIAL_<id> per material. The format has no end marker: a
//                  file cut between lines reads as less
// Every read ends with validate_mesh(); every error reads "path:line: message"
// ("path: byte N: message" past the header of a binary .msh or .vtk).
// Writes go to a temporary file in the same directory that is renamed over the
// target, so a failed write never leaves a half-written file.
//
// Reading, format by format:
//  - Medit: keywords are case-insensitive, '#' starts a comment. Vertices and
//    Tetrahedra are read, and Triangles with a reference >= 1 as surface groups (one
//    per reference, unnamed); the other sections of a 3D mesh (Edges,
//    Corners, Ridges, Required*, Normals, Tangents, Prisms, Hexahedra, P2
//    elements, ...) are skipped by their entry width; an unknown keyword is an
//    error. `End` is optional.
//  - Gmsh: element type 4 is a tet; type 11 (10-node tet) gives its four corners;
//    other element types are skipped. Material = the first physical tag (2.2: the
//    first element tag when not 0; 4.1: the volume entity's first physical tag in
//    $Entities), else the elementary (entity) tag. A 3D physical group named
//    "material_<n>" in $PhysicalNames gives material n whatever its tag; other
//    names of 3D groups are kept as ReadInfo::material_names. Node and
//    element tags may be sparse or huge: vertices come out ordered by node tag,
//    tets by element tag. The triangles (of any order) of physical surfaces are kept
//    by their corners' positions as ReadInfo::surface_groups (in every physical
//    group of their entity; not followed through partitions).
//  - TetGen: `.node` header "n 3 nattr nmarker", `.ele` header "m 4|10 nattr";
//    0- or 1-based numbering from the first index in .node, '#' comments; the
//    first region attribute must be an integer (no attribute: material 0). Either
//    orientation is accepted. A `.face` file beside them (read_mesh(): same base
//    name; none is fine), header "f 0|1", one face a line "i a b c [marker]"
//    numbered as .node (6 nodes after a 10-node .ele; TetGen -nn's two adjacent
//    tets after the marker are skipped): faces with a marker >= 1 are surface
//    groups by marker (tag = marker, unnamed), as Medit references are; marker 0,
//    or no markers, none. A malformed .face is an error naming it.
//  - Abaqus: each element-based *SURFACE ("element or element set, Sn"; S1 = nodes
//    1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1) is a surface group named after it,
//    tags M + 1, M + 2, ... (M: the largest material number) in the order of the
//    file; <X>_FACES is named X when a node set
//    X exists and no surface X (as TetLOD writes a group X). Node surfaces, other
//    forms and references to elements or sets that are not there are skipped, and
//    faces of elements that are not tets dropped, with a note. Then the *ELSETs of
//    triangle elements (CPS3, S3, ...; as Gmsh exports physical surfaces) are
//    groups too (io/abaqus.cpp).
//  - VTK legacy (3.0 and 5.1 cell layouts) and VTK XML: cell type 10 (tet) and 24
//    (quadratic tet: its four corners) are read, other cells skipped; material =
//    cell data array "material" (legacy: SCALARS or FIELD), else 0. The names of
//    materials and surface groups: the dataset's field data arrays "group_tag",
//    "group_dim" and "group_name", as TetLOD writes them (kVtkNameTagArray in mesh_formats.h);
//    other field data, and string arrays anywhere, are skipped.
// A file cut short either fails to read or, when the cut removed only text that
// carries no mesh data (Medit `End`, trailing comments, cell data after
// "material", sections after $EndElements in .msh), reads as the full mesh. A
// number that touches the end of the file without a line break after it is taken
// as cut off and is an error. (VTK legacy has no end marker and its material array
// is optional: a cut just before that array reads as a mesh without materials.)
//
// Writing: tets keep their orientation (positive, which is also TetGen's own
// output orientation, checked with TetGen 1.5); numbers use the shortest text that
// reads back to the same double (std::to_chars), so every format round-trips
// positions, tets (order and vertex order) and materials exactly.
//  - Gmsh material ids: Gmsh physical tags must be > 0. Material m > 0 is written
//    as physical tag m (and volume entity m), so other tools see the same ids.
//    Material 0 is written as the smallest positive tag no material uses, and every
//    physical group is named "material_<m>" in $PhysicalNames, which our reader
//    maps back, unless WriteOptions::material_names gives it a name (m > 0 only).
//    4.1 files carry $Entities with bounding boxes, one volume entity per material.
//  - TetGen: the pair is written 1-based with one region attribute (the material).
//    With surface groups, a .face file too (boundary markers: the groups' tags);
//    without, a .face already beside the pair (which the reader
//    would take with the pair) is replaced by this mesh's faces without markers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/io/output_files.h"
#include "core/status.h"
#include "core/surface.h"
#include "core/tet_mesh.h"
#include "core/validate.h"

namespace tetlod {

enum class MeshFormat {
  kMedit,
  kGmsh22,
  kGmsh41,
  kTetGen,
  kVtkLegacy,
  kVtu,
  kNastran,
  kAbaqus,
  kMeditBinary
};

const char* format_name(MeshFormat format);

// The longest material or surface group name read (longer ones are cut, with a note):
// Gmsh reads a $PhysicalNames line into 256 bytes, so "DIM TAG \"NAME\"" with a
// ten-digit tag leaves 240 for the name (Gmsh 4.8.4 loads 252 with tag 1, not 253).
inline constexpr size_t kMaxNameBytes = 240;

struct ReadInfo {
  MeshFormat format = MeshFormat::kMedit;
  ValidationReport validation;
  // What a user should know of how the file was read, e.g. that no array of a .vtu
  // held the material (callers print them as notes).
  std::vector<std::string> notes;
  // The file's own surface groups (Gmsh physical surfaces of triangles, Medit
  // triangles with a reference >= 1, TetGen .face markers >= 1, Abaqus element-face
  // *SURFACE and triangle element sets, .vtk and .vtu triangle cells by their number
  // >= 1 in the material array, Nastran CTRIA3/CTRIA6/CTRIAR by their PID >= 1), for
  // SurfacePatches (core/surface.h) when writing surface groups.
  std::vector<InputSurfaceGroup> surface_groups;
  // The names the file gives the materials of its tets, by material id (none for a
  // name that only says the number, such as Gmsh's "material_<n>"; formats without
  // names give none). Here and in surface_groups a name's control characters are '_'.
  std::vector<MaterialName> material_names;
  // The surface elements the file holds (Gmsh, VTK and Nastran triangles and
  // quadrangles, Medit Triangles and Quadrilaterals, TetGen faces with a marker >= 1,
  // Abaqus triangle elements): TetLOD keeps only their groups (surface_groups), not
  // the elements (callers say so unless they write the surface groups again).
  uint64_t surface_elements_not_kept = 0;
  // Set by the caller: also keep the face neighbours of the mesh's tets
  // (build_face_neighbors(), core/adjacency.h) that validation builds, in
  // face_neighbors, for a caller that needs them (SurfacePatches, group_surface()).
  bool keep_face_neighbors = false;
  std::vector<uint32_t> face_neighbors;
};

// Reads `path`; `*mesh` is replaced only on success. For .msh, info->format tells
// the version found.
Status read_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info = nullptr);

// Parses a file's text held in memory (tests, fuzzing). `name` stands for the path
// in messages. kGmsh22 and kGmsh41 both read either version; kTetGen needs two
// texts: use read_tetgen_from_memory().
Status read_mesh_from_memory(std::string_view data, MeshFormat format, const std::string& name,
                             TetMesh* mesh, ReadInfo* info = nullptr);
Status read_tetgen_from_memory(std::string_view node_data, std::string_view ele_data,
                               const std::string& node_name, const std::string& ele_name,
                               TetMesh* mesh, ReadInfo* info = nullptr);
// The same with the .face file beside them, for its surface groups.
Status read_tetgen_from_memory(std::string_view node_data, std::string_view ele_data,
                               std::string_view face_data, const std::string& node_name,
                               const std::string& ele_name, const std::string& face_name,
                               TetMesh* mesh, ReadInfo* info = nullptr);

struct WriteOptions {
  int gmsh_version = 41;  // 41 or 22, for .msh
  // .msh in binary (file type 1, this machine's byte order), as Gmsh writes with -bin;
  // else ASCII.
  bool gmsh_binary = false;
  // .vtk and .vtu in binary (.vtk: BINARY, big-endian; .vtu: raw appended data), as
  // ParaView writes them by default; else ASCII.
  bool vtk_binary = false;
  // Also write the boundary and interface triangles, one group per material pair
  // (group_surface() in core/surface.h: "boundary_<m>", "interface_<a>_<b>", tags
  // above every material's), for boundary conditions:
  //  - .msh: triangles in physical surfaces of those tags and names (4.1: one surface
  //    entity per group), numbered after the tets;
  //  - .mesh, .meshb: a Triangles section, reference = the group's tag;
  //  - .node/.ele: a .face file beside them, boundary marker = the group's tag;
  //  - .inp: per group a *NSET and a *SURFACE of element faces (<NAME>_FACES);
  //  - .vtk, .vtu: triangle cells after the tets, the tag in the material array (as
  //    Gmsh's VTK export writes physical surfaces), the stretch of the tet behind
  //    each; the names in the field data (with the materials', below);
  //  - .bdf/.nas: a CTRIA3 per triangle after the CTETRAs, the tag as its PID.
  bool surface_groups = false;
  // With surface_groups: group_surface() of the very mesh written, for a caller that
  // also prints them; null to have the writer compute them.
  const SurfaceGroups* groups = nullptr;
  // Names for the materials (ReadInfo::material_names of the input, or null), where
  // the format has a place for them: .msh physical volume names ("material_<m>" for
  // a material without one, and always for material 0, whose Gmsh tag is not its
  // id); .inp element sets <NAME>_<m> (MATERIAL_<m> without); .vtk and .vtu field
  // data "group_tag", "group_dim" and "group_name", row by row, with the surface groups'. Names of
  // materials the mesh does not have are ignored; characters the format cannot hold become '_'.
  const std::vector<MaterialName>* material_names = nullptr;
};

// Whether `path` has an extension read_mesh() and write_mesh() know; the error names
// it and lists the ones they do (any case). With `options`, also whether they can be
// written there (the Gmsh version). For a command to check its output
// path up front, or to tell "not a mesh file" from a mesh file that failed to read.
Status check_mesh_path(const std::string& path, const WriteOptions& options = {});

// Writes `mesh` (valid: see tet_mesh.h) in the format of the extension of `path`.
// For .node/.ele both files of the pair are written (and the .face file with
// surface groups). An invalid mesh or an
// unwritable path gives an error naming the path, and leaves no file behind.
Status write_mesh(const std::string& path, const TetMesh& mesh, const WriteOptions& options = {});
// Every file write_mesh(path, ...) may write: `path`, or for .node/.ele the pair and
// the .face file beside them (for a command to check that none is one of its inputs).
std::vector<std::string> mesh_output_files(const std::string& path);
// The same, staged in `files` to be committed with the other outputs of a command
// (output_files.h): nothing is written until files->commit().
Status stage_mesh(OutputFiles* files, const std::string& path, const TetMesh& mesh,
                  const WriteOptions& options = {});

// A named scalar array to write along with a mesh, one value per point or per cell
// (e.g. a potential and a field magnitude). `values` must outlive the call.
struct ScalarArray {
  std::string name;  // shown in ParaView; XML-safe (letters, digits, '_', ' ', '|', '-')
  const std::vector<double>* values = nullptr;
};
struct MeshFields {
  std::vector<ScalarArray> point_data;  // values->size() == vertex_count()
  std::vector<ScalarArray> cell_data;   // values->size() == tet_count()
};

// Writes `mesh` as a .vtu (whatever the extension of `path`) with cell data
// "material" and "stretch" followed by `fields`, atomically as write_mesh(). The
// first point array is marked as the active scalars. A size mismatch, a name with
// other characters or a non-finite value gives an error naming the array. `binary`:
// as WriteOptions::vtk_binary.
Status write_vtu_with_fields(const std::string& path, const TetMesh& mesh, const MeshFields& fields,
                             bool binary = false);

}  // namespace tetlod
