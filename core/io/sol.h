// Medit .sol files of sizes at vertices, as MMG3D takes a size map with a mesh
// (`mmg3d mesh.mesh -sol sizes.sol`): ASCII, '#' comments, keywords in any case.
//
//   MeshVersionFormatted 2
//   Dimension 3
//   SolAtVertices
//   <number of vertices>
//   1 1              one field, of type 1 (a scalar: the size)
//   <size of vertex 1>
//   ...
//   End              (optional)
//
// The binary .solb (libMeshb's layout, versions 1 to 4 in either byte order, as MMG
// and FreeFEM write it) is read too, told from ASCII by its first four bytes.
// A tensor (type 3, an anisotropic metric) or a vector field, several fields, and
// fields on other entities (SolAtTetrahedra, ...) are refused with an error that
// says so; so are sizes that are not finite numbers > 0. Every error reads
// "path:line: message" ("path: byte N: message" in a binary file).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"

namespace tetlod {

// `count_at`, if given, receives where the vertex count is ("path:line", or "path:
// byte N" in a .solb), for an error about it that only the caller can find (a count
// other than the mesh's).
Status read_sol_sizes(const std::string& path, std::vector<double>* sizes,
                      std::string* count_at = nullptr);
// The same on a file's text held in memory (tests, fuzzing); `name` for messages.
Status parse_sol_sizes(std::string_view text, const std::string& name, std::vector<double>* sizes,
                       std::string* count_at = nullptr);

}  // namespace tetlod
