// Reading and writing tetrahedral meshes in the formats analysts' tools use.
// The format is chosen from the file extension:
//   .mesh          Medit ASCII (MMG, CGAL, TetWild, Gmsh); material = tet reference
//   .msh           Gmsh ASCII 2.2 or 4.1 (read: from $MeshFormat; write: 4.1 unless
//                  WriteOptions::gmsh_version == 22); material = physical tag, else
//                  the elementary tag
//   .node / .ele   TetGen pair (either name selects both); material = first region
//                  attribute; 0- or 1-based numbering
//   .vtk           VTK legacy ASCII unstructured grid, cell data "material", "stretch"
//   .vtu           VTK XML ASCII unstructured grid, cell data "material", "stretch"
// Every read ends with validate_mesh(); every error reads "path:line: message".
// Writes go to a temporary file in the same directory that is renamed over the
// target, so a failed write never leaves a half-written file.
#pragma once

#include <string>
#include <string_view>

#include "core/status.h"
#include "core/tet_mesh.h"
#include "core/validate.h"

namespace tetlod {

enum class MeshFormat { kMedit, kGmsh22, kGmsh41, kTetGen, kVtkLegacy, kVtu };

const char* format_name(MeshFormat format);

struct ReadInfo {
  MeshFormat format = MeshFormat::kMedit;
  ValidationReport validation;
};

Status read_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info = nullptr);

struct WriteOptions {
  int gmsh_version = 41;  // 41 or 22, for .msh
};

Status write_mesh(const std::string& path, const TetMesh& mesh, const WriteOptions& options = {});

}  // namespace tetlod
