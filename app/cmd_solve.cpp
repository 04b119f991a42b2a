// tetlod solve MESH --conductor M=V[,...] --ground boundary|M[,...] [--eps M=E[,...]] [-o F.vtu]
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/simplify_options.h"
#include "app/terminal_progress.h"
#include "core/electrostatics.h"

namespace tetlod::app {
namespace {

// Above this many nodes, --solver direct gets a note on its time.
constexpr size_t kDirectNoteNodes = 20000;

constexpr const char* kSolveUsage =
    "usage: tetlod solve MESH --conductor M=V[,M=V...] [--ground boundary|M[,...]]\n"
    "                    [--eps M=E[,M=E...]] [-o FIELD.vtu [--vtk-binary]]\n"
    "                    [--solver auto|direct|cg]\n"
    "                    [--preconditioner jacobi|ic] [--tolerance T]\n"
    "\n"
    "Electrostatics with linear finite elements: -div(eps grad u) = 0, every node of a\n"
    "conductor material M held at potential V, every node of a ground material (or of\n"
    "the outer boundary, 'boundary') at 0, zero normal flux elsewhere. Prints the energy\n"
    "W = 1/2 int eps |grad u|^2, the capacitance C = 2 W / V^2 (V: highest minus lowest\n"
    "potential), the solver's iterations and residual, and the time. C is in the units\n"
    "of eps times length: with relative permittivities, in eps0 times the mesh's unit.\n"
    "  --conductor M=V,...  conductor materials and their potentials\n"
    "  --ground G,...       'boundary' and/or materials held at 0 (needed unless the\n"
    "                       conductors hold two potentials)\n"
    "  --eps M=E,...        permittivity per material, E > 0 (default 1 for the rest)\n"
    "  a material M is its id or its name in the input (a Gmsh physical group, an\n"
    "  Abaqus set): --conductor inner_conductor=1 --ground shield (in --ground a comma\n"
    "  inside a name is written \\,; in M=V lists it is written as it is); a name that\n"
    "  is no material's may be one of the input's surface groups (a Gmsh physical\n"
    "  surface, an Abaqus *SURFACE, ...: 'tetlod stats MESH' lists them), whose nodes\n"
    "  are then held: --conductor port=1 --ground outer\n"
    "  -o FIELD.vtu         write the potential (point data) and |E| (cell data) for ParaView\n"
    "  --vtk-binary         write it with raw appended binary data (default: ASCII)\n"
    "  --solver S           auto (direct up to 2000 unknowns, else cg), direct (its\n"
    "                       time grows about as the square of the unknowns), cg\n"
    "  --preconditioner P   for cg: jacobi (default) or ic (incomplete Cholesky)\n"
    "  --tolerance T        cg stops at relative residual T (default 1e-10)\n"
    "Example, the bundled two-layer spherical capacitor:\n"
    "  tetlod solve assets/spheres.mesh --conductor 1=1 --ground 4 --eps 2=2,3=5\n";

bool next_value(const Args& args, size_t* i, std::string* value) {
  if (*i + 1 >= args.size()) {
    std::fprintf(stderr, "tetlod solve: %s needs a value\n", args[*i].c_str());
    return false;
  }
  *value = args[++*i];
  return true;
}

std::optional<int32_t> parse_material(const std::string& text) {
  const auto n = parse_integer(text);
  if (!n || *n < 0 || *n > 0x7fffffff) return std::nullopt;
  return static_cast<int32_t>(*n);
}

// A material as given: an id ("3") or the input's name for it ("shield"), looked up
// once the mesh is read (resolve()).
using MaterialText = std::string;

// Whether `text` can be a material: an id >= 0, or a name (anything that does not
// start like a number).
bool material_text_ok(const std::string& text) {
  return is_material_name(text) || parse_material(text).has_value();
}

// "M=X,M=X": materials (ids or names) and finite numbers. On error prints a message
// naming the flag and the item.
bool parse_pairs(const std::string& flag, const std::string& text,
                 std::vector<std::pair<MaterialText, double>>* pairs) {
  for (const std::string& item : split_value_items(text, '=')) {
    std::string material;
    double value = 0;
    if (item.empty()) {
      std::fprintf(stderr, "tetlod solve: %s '%s': %s\n", flag.c_str(), text.c_str(), kEmptyItem);
      return false;
    }
    if (!split_material_value(item, '=', &material, &value) || !material_text_ok(material)) {
      std::fprintf(stderr,
                   "tetlod solve: %s '%s': '%s' is not MATERIAL=NUMBER (a material id >= 0 or "
                   "name, and a finite number)\n",
                   flag.c_str(), text.c_str(), item.c_str());
      return false;
    }
    pairs->push_back({material, value});
  }
  return true;
}

bool parse_ground(const std::string& text, bool* boundary, std::vector<MaterialText>* materials) {
  for (const std::string& item : split_items(text)) {
    if (item.empty()) {
      std::fprintf(stderr, "tetlod solve: --ground '%s': %s\n", text.c_str(), kEmptyItem);
      return false;
    }
    if (item == "boundary") {
      *boundary = true;
    } else if (material_text_ok(item)) {
      materials->push_back(item);
    } else {
      std::fprintf(stderr,
                   "tetlod solve: --ground '%s': '%s' is neither 'boundary' nor a material id or "
                   "name\n",
                   text.c_str(), item.c_str());
      return false;
    }
  }
  return true;
}

// The vertices of `mesh` at the corners of `group`'s triangles, sorted; false, with
// the first corner that is none, if a corner is no vertex of the mesh. `order_cache`:
// the mesh's vertices sorted by position, made on the first call (empty until then).
bool group_vertices(const TetMesh& mesh, const InputSurfaceGroup& group,
                    std::vector<uint32_t>* vertices, Vec3* missing,
                    std::vector<uint32_t>* order_cache) {
  const auto less = [](const Vec3& a, const Vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  std::vector<uint32_t>& order = *order_cache;
  if (order.empty()) {
    order.resize(mesh.vertex_count());
    for (uint32_t v = 0; v < order.size(); ++v) order[v] = v;
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return less(mesh.positions[a], mesh.positions[b]); });
  }
  vertices->clear();
  for (const auto& triangle : group.triangles) {
    for (const Vec3& p : triangle) {
      const auto at =
          std::lower_bound(order.begin(), order.end(), p,
                           [&](uint32_t v, const Vec3& q) { return less(mesh.positions[v], q); });
      if (at == order.end() || mesh.positions[*at] != p) {
        *missing = p;
        return false;
      }
      vertices->push_back(*at);
    }
  }
  std::sort(vertices->begin(), vertices->end());
  vertices->erase(std::unique(vertices->begin(), vertices->end()), vertices->end());
  return true;
}

// `text` as a material (an id, or a name in `names`: `*id`) or, for a name no material
// has, as one of the input's surface groups (`*surface`, its vertices). False with a
// message naming both kinds where it is neither.
bool resolve(const MaterialText& text, const std::vector<MaterialName>& names,
             const std::string& option, const TetMesh& mesh,
             const std::vector<InputSurfaceGroup>& groups, int32_t* id,
             ElectrostaticsProblem::HeldSurface* surface = nullptr,
             std::vector<uint32_t>* order_cache = nullptr) {
  if (const auto number = parse_material(text)) {
    *id = *number;
    return true;
  }
  std::string why;
  if (find_material(text, names, id, &why)) return true;
  if (surface) {
    for (const InputSurfaceGroup& group : groups) {
      // An unnamed group (a Medit reference) as surface_<tag>.
      if (group.name != text &&
          !(group.name.empty() && text == "surface_" + std::to_string(group.tag)))
        continue;
      Vec3 missing;
      if (!group_vertices(mesh, group, &surface->vertices, &missing, order_cache)) {
        std::fprintf(stderr,
                     "tetlod solve: %s: surface group '%s' has a corner (%.17g %.17g %.17g) that "
                     "is no vertex of the mesh\n",
                     option.c_str(), text.c_str(), missing.x, missing.y, missing.z);
        return false;
      }
      surface->name = text;
      return true;
    }
  }
  std::string surfaces;
  for (const InputSurfaceGroup& group : groups)
    if (surfaces.size() < 400)
      surfaces += (surfaces.empty() ? "" : ", ") +
                  (group.name.empty() ? "surface_" + std::to_string(group.tag) : group.name);
  std::fprintf(stderr, "tetlod solve: %s: %s%s\n", option.c_str(), why.c_str(),
               !surface ? ""
               : surfaces.empty()
                   ? "; the input names no surface group either"
                   : ("; nor is it a surface group (the input's: " + surfaces + ")").c_str());
  return false;
}

}  // namespace

int cmd_solve(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kSolveUsage, stdout);
    return kExitOk;
  }
  std::string in, out;
  ElectrostaticsProblem problem;
  // As given (ids or names): resolved into `problem` once the mesh is read.
  std::vector<std::pair<MaterialText, double>> conductors, permittivities;
  std::vector<MaterialText> grounds;
  SolveOptions options;
  bool ground_given = false, preconditioner_given = false, tolerance_given = false;
  bool binary = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string v;
    if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &out)) return kExitUsage;
      if (!has_extension(out, ".vtu")) {
        std::fprintf(stderr, "tetlod solve: -o '%s': the field is written as .vtu only\n",
                     out.c_str());
        return kExitUsage;
      }
    } else if (a == "--vtk-binary") {
      binary = true;
    } else if (a == "--conductor") {
      if (!next_value(args, &i, &v) || !parse_pairs(a, v, &conductors)) return kExitUsage;
    } else if (a == "--eps") {
      if (!next_value(args, &i, &v) || !parse_pairs(a, v, &permittivities)) {
        return kExitUsage;
      }
    } else if (a == "--ground") {
      if (!next_value(args, &i, &v) || !parse_ground(v, &problem.ground_boundary, &grounds))
        return kExitUsage;
      ground_given = true;
    } else if (a == "--solver") {
      if (!next_value(args, &i, &v)) return kExitUsage;
      if (v == "auto") {
        options.method = SolverMethod::kAuto;
      } else if (v == "direct") {
        options.method = SolverMethod::kDirect;
      } else if (v == "cg") {
        options.method = SolverMethod::kIterative;
      } else {
        std::fprintf(stderr, "tetlod solve: --solver '%s' is not auto, direct or cg\n", v.c_str());
        return kExitUsage;
      }
    } else if (a == "--preconditioner") {
      if (!next_value(args, &i, &v)) return kExitUsage;
      preconditioner_given = true;
      if (v == "jacobi") {
        options.preconditioner = Preconditioner::kJacobi;
      } else if (v == "ic") {
        options.preconditioner = Preconditioner::kIncompleteCholesky;
      } else {
        std::fprintf(stderr, "tetlod solve: --preconditioner '%s' is not jacobi or ic\n",
                     v.c_str());
        return kExitUsage;
      }
    } else if (a == "--tolerance") {
      if (!next_value(args, &i, &v)) return kExitUsage;
      const auto d = parse_double(v);
      if (!d || !(*d >= kMinSolverTolerance) || *d >= 1) {
        std::fprintf(stderr,
                     "tetlod solve: --tolerance '%s' is not a number in [%g, 1) (double "
                     "precision cannot reach a smaller relative residual)\n",
                     v.c_str(), kMinSolverTolerance);
        return kExitUsage;
      }
      options.tolerance = *d;
      tolerance_given = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod solve: unknown option '%s'\n\n%s", a.c_str(), kSolveUsage);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else {
      more_than_one_input("solve", args, in, a);
      return kExitUsage;
    }
  }
  // A ground is not needed when the conductors hold two potentials (a two-conductor
  // capacitor: --conductor 1=1,4=0).
  bool two_potentials = false;
  for (const auto& c : conductors)
    two_potentials = two_potentials || c.second != conductors.front().second;
  if (binary && out.empty()) {
    std::fputs("tetlod solve: --vtk-binary without -o FIELD.vtu: no field is written\n", stderr);
    return kExitUsage;
  }
  if (options.method == SolverMethod::kDirect && (preconditioner_given || tolerance_given)) {
    std::fprintf(stderr, "tetlod solve: --%s is for --solver cg, not direct\n",
                 preconditioner_given ? "preconditioner" : "tolerance");
    return kExitUsage;
  }
  if (in.empty() || conductors.empty() || (!ground_given && !two_potentials)) {
    std::fprintf(stderr,
                 "tetlod solve: need MESH, --conductor and --ground (or conductors at two "
                 "potentials)\n\n%s",
                 kSolveUsage);
    return kExitUsage;
  }

  if (!out.empty() && !output_directory_ok(out)) return kExitBadInput;

  TetMesh mesh;
  ReadInfo info;
  if (!load_mesh(in, &mesh, &info)) return kExitBadInput;
  // The materials given by name, now that the names are read; a name no material has
  // may be a surface group's.
  const std::vector<InputSurfaceGroup>& groups = info.surface_groups;
  // A conductor or ground: a material, or a surface group.
  std::vector<uint32_t> by_position;  // the vertices sorted by position, for the groups
  const auto hold = [&](const MaterialText& text, double potential, bool ground) {
    int32_t id = -1;
    ElectrostaticsProblem::HeldSurface surface;
    if (!resolve(text, info.material_names, ground ? "--ground" : "--conductor", mesh, groups, &id,
                 &surface, &by_position))
      return false;
    if (!surface.name.empty()) {
      surface.potential = potential;
      surface.ground = ground;
      problem.surfaces.push_back(std::move(surface));
    } else if (ground) {
      problem.ground_materials.push_back(id);
    } else {
      problem.conductors.push_back({id, potential});
    }
    return true;
  };
  for (const auto& [text, potential] : conductors)
    if (!hold(text, potential, false)) return kExitUsage;
  for (const MaterialText& text : grounds)
    if (!hold(text, 0.0, true)) return kExitUsage;
  for (const auto& [text, eps] : permittivities) {
    int32_t id = 0;
    if (!resolve(text, info.material_names, "--eps", mesh, groups, &id)) return kExitUsage;
    problem.permittivities.push_back({id, eps});
  }
  // What the options say, checked against the mesh: an error of theirs is one of usage
  // (a potential or permittivity out of range, a material twice or not in the mesh).
  if (const Status s = check_electrostatics_problem(problem, mesh); !s) {
    std::fprintf(stderr, "tetlod solve: %s\n", s.message().c_str());
    return kExitUsage;
  }
  // A sparse LDL^T of a 3D mesh's matrix grows about as the square of its unknowns in
  // time (docs/PERFORMANCE.md): asked for on a large mesh, say so before it starts.
  if (options.method == SolverMethod::kDirect && mesh.vertex_count() > kDirectNoteNodes) {
    std::fprintf(stderr,
                 "tetlod solve: note: --solver direct on %zu nodes: its time grows about as "
                 "the square of the unknowns (about a minute at 57,000 unknowns on our "
                 "machines, unfinished after nine at 280,000); cg (auto's choice above 2000) takes "
                 "seconds\n",
                 mesh.vertex_count());
  }
  const auto start = std::chrono::steady_clock::now();
  ElectrostaticsSolution solution;
  TerminalProgress progress("tetlod solve");
  const Status status =
      solve_electrostatics(mesh, problem, options, &solution, progress.solve_callback());
  progress.clear();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!status) {
    std::fprintf(stderr, "tetlod solve: %s: %s\n", in.c_str(), status.message().c_str());
    return kExitBadInput;
  }
  std::printf("mesh         %s: %zu nodes, %zu tets\n", in.c_str(), mesh.vertex_count(),
              mesh.tet_count());
  std::printf("unknowns     %zu (%zu nodes held), %zu matrix entries\n", solution.free_count,
              solution.dirichlet_count, solution.nonzeros);
  std::printf(
      "capacitance  C = %.10g (in eps x length: with relative eps, in eps0 x the mesh's "
      "length unit)\n",
      solution.capacitance);
  std::printf("energy       W = %.10g (V = %.10g)\n", solution.energy, solution.voltage);
  if (solution.method == SolverMethod::kDirect) {
    std::printf("solver       direct (LDL^T), relative residual %.3g%s\n",
                solution.relative_residual,
                preconditioner_given || tolerance_given
                    ? " (auto chose it for this size: --preconditioner and --tolerance are for "
                      "cg, --solver cg to use them)"
                    : "");
  } else {
    std::printf("solver       cg + %s, %d iterations, relative residual %.3g\n",
                options.preconditioner == Preconditioner::kJacobi ? "jacobi" : "ic",
                solution.iterations, solution.relative_residual);
  }
  std::printf(
      "time         %.3f s (setup %.3f, assemble %.3f, factor %.3f, solve and outputs %.3f)\n",
      seconds, solution.seconds_setup, solution.seconds_assemble, solution.seconds_factor,
      solution.seconds_solve);
  if (!out.empty()) {
    MeshFields fields;
    fields.point_data = {{"potential", &solution.potential}};
    fields.cell_data = {{"field magnitude", &solution.field_magnitude}};
    const Status s = write_vtu_with_fields(out, mesh, fields, binary);
    if (!s) {
      std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
      return kExitBadInput;
    }
    std::printf("field        %s (point data 'potential', cell data 'field magnitude')\n",
                out.c_str());
  }
  return kExitOk;
}

}  // namespace tetlod::app
