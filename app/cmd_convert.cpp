// tetlod convert IN OUT (or IN -o OUT) [--msh-version 2.2|4.1] [--msh-binary] [--vtk-binary]
// [--surfaces]
#include <cstdio>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/simplify_options.h"

namespace tetlod::app {
namespace {

constexpr const char* kConvertUsage =
    "usage: tetlod convert IN OUT [--msh-version 2.2|4.1] [--msh-binary] [--vtk-binary]\n"
    "                             [--surfaces]\n"
    "       (OUT may also be given as -o OUT)\n"
    "\n"
    "Converts a tetrahedral mesh between formats, chosen by extension, keeping the\n"
    "material of every tetrahedron, and the materials' names where both formats\n"
    "have them (Gmsh physical volumes, Abaqus element sets and sections, the field\n"
    "data TetLOD writes in .vtk and .vtu):\n"
    "  .mesh (Medit)  .meshb (Medit binary)  .msh (Gmsh 2.2/4.1)  .node/.ele (TetGen)\n"
    "  .vtk (legacy)  .vtu  .bdf/.nas (Nastran bulk data; material = PID)\n"
    "  .inp (Abaqus, CalculiX)\n"
    "Binary .msh, .vtk and .vtu files are read; .meshb is written binary, .msh too with\n"
    "--msh-binary, .vtk and .vtu with --vtk-binary, every other format as text.\n"
    "The output is written to a temporary file and renamed, never left half-written.\n";

void print_convert_usage(std::FILE* stream) {
  std::fputs(kConvertUsage, stream);
  std::fputs(kWriteFlagsHelp, stream);
}

}  // namespace

int cmd_convert(const Args& args) {
  if (wants_help(args)) {
    print_convert_usage(stdout);
    return kExitOk;
  }
  std::string in, out;
  WriteOptions options;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const OptionResult parsed = parse_write_option(args, &i, "convert", &options);
    if (parsed == OptionResult::kError) return kExitUsage;
    if (parsed == OptionResult::kParsed) continue;
    if (a == "-o" || a == "--output") {  // as simplify and lod take it
      if (i + 1 == args.size()) {
        std::fprintf(stderr, "tetlod convert: %s needs a file\n", a.c_str());
        return kExitUsage;
      }
      if (!out.empty()) {
        std::fputs("tetlod convert: give the output once\n", stderr);
        return kExitUsage;
      }
      out = args[++i];
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod convert: unknown option '%s'\n\n", a.c_str());
      print_convert_usage(stderr);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else if (out.empty()) {
      out = a;
    } else {
      std::fputs("tetlod convert: too many files\n\n", stderr);
      print_convert_usage(stderr);
      return kExitUsage;
    }
  }
  if (out.empty()) {
    std::fputs("tetlod convert: need IN and OUT\n\n", stderr);
    print_convert_usage(stderr);
    return kExitUsage;
  }
  if (!mesh_output_path_ok(out, "convert", options, "")) return kExitUsage;
  if (!output_directory_ok(out)) return kExitBadInput;
  TetMesh mesh;
  ReadInfo info;
  info.keep_face_neighbors = options.surface_groups;  // validation's, for the groups
  if (!load_mesh(in, &mesh, &info, options.surface_groups)) return kExitBadInput;
  const std::vector<uint32_t>* neighbors = options.surface_groups ? &info.face_neighbors : nullptr;
  // The file's own surface groups, written under their names and tags.
  SurfacePatches patches;
  if (options.surface_groups && !info.surface_groups.empty()) {
    patches = SurfacePatches(mesh, info.surface_groups, neighbors);
    print_patch_notes(patches, "convert");
  }
  options.material_names = &info.material_names;
  OutputFiles files;
  StagedMesh staged;
  Status status = stage_output_mesh(&files, out, mesh, options, &staged, &patches, neighbors);
  if (status) status = files.commit();
  if (!status) {
    std::fprintf(stderr, "tetlod: %s\n", status.message().c_str());
    return kExitBadInput;
  }
  std::printf("%s -> %s: %zu vertices, %zu tetrahedra\n", in.c_str(), out.c_str(),
              mesh.vertex_count(), mesh.tet_count());
  print_staged_mesh_notes(staged);
  return kExitOk;
}

}  // namespace tetlod::app
