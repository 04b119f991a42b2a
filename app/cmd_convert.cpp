// tetlod convert IN OUT [--msh-version 2.2|4.1]
#include <cstdio>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"

namespace tetlod::app {
namespace {

constexpr const char* kConvertUsage =
    "usage: tetlod convert IN OUT [--msh-version 2.2|4.1]\n"
    "\n"
    "Converts a tetrahedral mesh between formats, chosen by extension, keeping the\n"
    "material of every tetrahedron:\n"
    "  .mesh (Medit)  .msh (Gmsh 2.2/4.1)  .node/.ele (TetGen)  .vtk (legacy)  .vtu\n"
    "  .bdf/.nas (Nastran bulk data; material = PID)  .inp (Abaqus, CalculiX)\n"
    "Binary .msh, .vtk and .vtu files are read; every format is written as text.\n"
    "The output is written to a temporary file and renamed, never left half-written.\n"
    "  --msh-version V   Gmsh version to write: 4.1 (default) or 2.2\n";

}  // namespace

int cmd_convert(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kConvertUsage, stdout);
    return kExitOk;
  }
  std::string in, out;
  WriteOptions options;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--msh-version") {
      if (i + 1 >= args.size()) {
        std::fprintf(stderr, "tetlod convert: --msh-version needs a value\n");
        return kExitUsage;
      }
      const std::string& v = args[++i];
      if (v == "2.2" || v == "22") {
        options.gmsh_version = 22;
      } else if (v == "4.1" || v == "41") {
        options.gmsh_version = 41;
      } else {
        std::fprintf(stderr, "tetlod convert: --msh-version must be 2.2 or 4.1, not '%s'\n",
                     v.c_str());
        return kExitUsage;
      }
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod convert: unknown option '%s'\n\n%s", a.c_str(), kConvertUsage);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else if (out.empty()) {
      out = a;
    } else {
      std::fprintf(stderr, "tetlod convert: too many files\n\n%s", kConvertUsage);
      return kExitUsage;
    }
  }
  if (out.empty()) {
    std::fprintf(stderr, "tetlod convert: need IN and OUT\n\n%s", kConvertUsage);
    return kExitUsage;
  }
  if (!mesh_output_path_ok(out, "convert")) return kExitUsage;
  TetMesh mesh;
  ReadInfo info;
  if (!load_mesh(in, &mesh, &info)) return kExitBadInput;
  const Status status = write_mesh(out, mesh, options);
  if (!status) {
    std::fprintf(stderr, "tetlod: %s\n", status.message().c_str());
    return kExitBadInput;
  }
  std::printf("%s -> %s: %zu vertices, %zu tetrahedra\n", in.c_str(), out.c_str(),
              mesh.vertex_count(), mesh.tet_count());
  return kExitOk;
}

}  // namespace tetlod::app
