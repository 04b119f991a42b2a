// tetlod generate MODEL [--max-volume V | --tets N] [--quality Q] [--sphere-level L] -o FILE
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "core/generate/model_generator.h"

namespace tetlod::app {
namespace {

constexpr const char* kGenerateUsage =
    "usage: tetlod generate MODEL [--max-volume V | --tets N] [--quality Q]\n"
    "                       [--sphere-level L] -o FILE\n"
    "\n"
    "Builds a multi-material test model procedurally and meshes it with TetGen\n"
    "(switches p q A a). The same options give the same mesh, byte for byte.\n"
    "\n"
    "models:\n"
    "  motor    permanent-magnet motor in an air box, millimetres; materials\n"
    "           1 air, 2 air gap, 3 shaft, 4 rotor iron, 5 magnets (8), 6 stator iron,\n"
    "           7 coils (12)\n"
    "  spheres  spheres r = 1, 2, 3 in the box [-4,4]^3; materials 1 r<1, 2 1<r<2,\n"
    "           3 2<r<3, 4 outside r = 3\n"
    "  box2     [0,2]x[0,1]x[0,1], material 1 for x<1 and 2 for x>1\n"
    "\n"
    "options:\n"
    "  --max-volume V    largest tet volume (TetGen a), in the model's units cubed\n"
    "  --tets N          aim for about N tets (TetGen is run up to 4 times)\n"
    "                    without either: the density of the bundled asset\n"
    "  --quality Q       radius-edge ratio bound (TetGen q), in [1.2, 100]; default 2\n"
    "  --sphere-level L  icosphere subdivisions for spheres, 0..5; default 3\n"
    "  -o, --output FILE the mesh to write; the format follows the extension\n"
    "                    (.mesh .meshb .msh .node/.ele .vtk .vtu .bdf/.nas .inp)\n";

// A bad value names itself; a command line of the wrong shape also gets the usage.
int usage_error(const std::string& message, bool with_usage = false) {
  if (with_usage)
    std::fprintf(stderr, "tetlod generate: %s\n\n%s", message.c_str(), kGenerateUsage);
  else
    std::fprintf(stderr, "tetlod generate: %s (see 'tetlod generate --help')\n", message.c_str());
  return kExitUsage;
}

}  // namespace

int cmd_generate(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kGenerateUsage, stdout);
    return kExitOk;
  }
  std::string model_text;
  std::string output;
  GenerateOptions options;
  bool sphere_level_given = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool takes_value = a == "--max-volume" || a == "--tets" || a == "--quality" ||
                             a == "--sphere-level" || a == "-o" || a == "--output";
    if (takes_value && i + 1 >= args.size()) return usage_error(a + " needs a value");
    if (a == "--max-volume") {
      const std::string& v = args[++i];
      const auto value = parse_double(v);
      if (!value || !(*value > 0)) {
        return usage_error("--max-volume must be a positive number, not '" + v + "'");
      }
      options.max_volume = *value;
    } else if (a == "--tets") {
      const std::string& v = args[++i];
      const auto value = parse_integer(v);
      if (!value || *value < 1 || *value > static_cast<long long>(kMaxTets)) {
        return usage_error("--tets must be a whole number from 1 to " + std::to_string(kMaxTets) +
                           ", not '" + v + "'");
      }
      options.target_tets = static_cast<size_t>(*value);
    } else if (a == "--quality") {
      const std::string& v = args[++i];
      const auto value = parse_double(v);
      if (!value || !(*value >= kMinQuality && *value <= kMaxQuality)) {
        return usage_error("--quality must be a number from 1.2 to 100, not '" + v + "'");
      }
      options.quality = *value;
    } else if (a == "--sphere-level") {
      const std::string& v = args[++i];
      const auto value = parse_integer(v);
      if (!value || *value < 0 || *value > kMaxSphereLevel) {
        return usage_error("--sphere-level must be a whole number from 0 to " +
                           std::to_string(kMaxSphereLevel) + ", not '" + v + "'");
      }
      options.sphere_level = static_cast<int>(*value);
      sphere_level_given = true;
    } else if (a == "-o" || a == "--output") {
      if (args[i + 1].rfind("--", 0) == 0)
        return usage_error("-o needs a file, not the option '" + args[i + 1] + "'");
      output = args[++i];
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "'", true);
    } else if (model_text.empty()) {
      model_text = a;
    } else {
      return usage_error("unexpected argument '" + a + "'", true);
    }
  }
  if (model_text.empty()) return usage_error("no MODEL given", true);
  Model model;
  if (!parse_model_name(model_text, &model)) {
    return usage_error("unknown model '" + model_text + "' (motor, spheres, box2)");
  }
  if (output.empty()) return usage_error("no output file given (-o FILE)", true);
  if (const Status s = check_mesh_path(output); !s) return usage_error("-o " + s.message());
  if (sphere_level_given && model != Model::kSpheres)
    return usage_error("--sphere-level applies to the spheres model only");
  if (options.max_volume > 0 && options.target_tets > 0) {
    return usage_error("give --max-volume or --tets, not both");
  }
  if (Status s = check_generate_options(model, options); !s) return usage_error(s.message());
  if (!output_directory_ok(output)) return kExitBadInput;

  const auto start = std::chrono::steady_clock::now();
  TetMesh mesh;
  GenerateInfo info;
  if (Status s = generate_model(model, options, &mesh, &info); !s) {
    std::fprintf(stderr, "tetlod generate: %s: %s\n", model_name(model), s.message().c_str());
    return kExitBadInput;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (Status s = write_mesh(output, mesh); !s) {
    std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
    return kExitBadInput;
  }

  const std::set<int32_t> materials(mesh.materials.begin(), mesh.materials.end());
  std::printf(
      "%s: %zu vertices, %zu tetrahedra, %zu materials, max volume %g, %d TetGen run%s, "
      "%.2f s -> %s\n",
      model_name(model), mesh.vertex_count(), mesh.tet_count(), materials.size(), info.max_volume,
      info.meshing_runs, info.meshing_runs == 1 ? "" : "s", seconds, output.c_str());
  if (options.target_tets > 0) {
    const double ratio = static_cast<double>(mesh.tet_count()) / options.target_tets;
    if (ratio > 1.25 || ratio < 0.8) {
      std::fprintf(stderr, "tetlod generate: note: %zu tetrahedra, %zu asked for%s\n",
                   mesh.tet_count(), options.target_tets,
                   ratio > 1 ? "; the model's features need about this many at least" : "");
    }
  }
  return kExitOk;
}

}  // namespace tetlod::app
