// tetlod view [FILE] [--script SCRIPT] [--size WxH] [--hide M,...] [--size-map S.sol]
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/render_options.h"
#include "app/simplify_options.h"
#include "app/viewer.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"

namespace tetlod::app {
namespace {

constexpr const char* kViewUsage =
    "usage: tetlod view [FILE] [--script SCRIPT] [--size WxH] [--hide M,M,...]\n"
    "                   [--interactive-scale F] [--size-map S.sol [--size-map-mesh M]]\n"
    "\n"
    "Opens the interactive viewer (a window: needs a display) on FILE, or on the bundled\n"
    "motor model when none is given (with --script, none: the script opens one):\n"
    "threshold sliders, simplification in the background, a level-of-detail scrubber,\n"
    "statistics, save and screenshots. FILE may be a collapse history (.tlh, from\n"
    "'tetlod simplify --history' or saved in the viewer): its levels are there at once,\n"
    "without simplifying again (and its size map, if it was made with one).\n"
    "  --script SCRIPT        run the actions in SCRIPT in the window, one a line: open,\n"
    "                         thresholds, simplify, cancel, wait, scrub, cut, hide, show,\n"
    "                         color, colormap, range, field-range, wireframe, highlight,\n"
    "                         view, orbit, pan, zoom, mouse, screenshot, save, analysis,\n"
    "                         solve, report-analysis, report-tet, bench-scrub,\n"
    "                         bench-frames, quit\n"
    "                         (their arguments: app/viewer_script.h in the sources); a\n"
    "                         bad line is an error naming SCRIPT:LINE\n"
    "  --size WxH             window size (default 1280x800)\n"
    "  --hide M,M,...         materials hidden at start, by id or by the file's name for them\n"
    "                         (e.g. the motor's air: --hide 1; a Gmsh volume: --hide shield);\n"
    "                         one FILE lacks is an error, as in 'tetlod render'; a comma\n"
    "                         inside a name is written \\,\n"
    "  --interactive-scale F  resolution of the 3D view while it moves, in (0, 1] (0.5)\n"
    "  --size-map S.sol       sizes at FILE's vertices (as 'tetlod simplify --size-map'):\n"
    "                         the panel's sizing starts as that size map\n"
    "  --size-map-mesh M      the mesh whose vertices those sizes are at, if not FILE's\n"
    "                         (a background mesh over the same domain)\n"
    "Mouse: left drag orbits, right/middle or shift-left drag pans, the wheel zooms;\n"
    "keys F (fit), 0 (iso), 1/2/3 (x/y/z views); the level of detail: left/right one\n"
    "step, page up/down a hundredth of the history, home/end the finest/coarsest level.\n"
    "The pointer at rest over the mesh names the tet under it: its material, stretch,\n"
    "longest edge, its nodes' valence (with the last run's thresholds), volume and |E|.\n";

std::string default_model() {
  // The bundled motor, found next to the source tree the binary was built from, or
  // relative to the working directory.
  for (const std::string& candidate :
       {std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", std::string("assets/motor.mesh")}) {
    std::error_code ec;
    if (std::filesystem::exists(candidate, ec)) return candidate;
  }
  return "assets/motor.mesh";
}

}  // namespace

int cmd_view(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kViewUsage, stdout);
    return kExitOk;
  }
  ViewerOptions options;
  std::vector<int32_t> hidden;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string value;
    if (a == "--script") {
      if (!parse_option_value(args, &i, "--script", &value)) return kExitUsage;
      const Status s = parse_script(value, &options.script);
      if (!s) {
        std::fprintf(stderr, "tetlod view: %s\n", s.message().c_str());
        return kExitBadInput;
      }
      options.script_name = value;
      options.has_script = true;
      options.remember_recent = false;
    } else if (a == "--size") {
      if (!parse_option_value(args, &i, "--size", &value)) return kExitUsage;
      const size_t x = value.find('x');
      const auto w = parse_integer(value.substr(0, x));
      const auto h = x == std::string::npos ? std::nullopt : parse_integer(value.substr(x + 1));
      if (!w || !h || *w < 64 || *h < 64 || *w > 8192 || *h > 8192) {
        std::fprintf(stderr, "tetlod view: --size needs WxH (64..8192), got '%s'\n", value.c_str());
        return kExitUsage;
      }
      options.width = static_cast<int>(*w);
      options.height = static_cast<int>(*h);
    } else if (a == "--size-map") {
      if (!parse_option_value(args, &i, "--size-map", &options.size_map_path)) return kExitUsage;
      if (!has_extension(options.size_map_path, ".sol") &&
          !has_extension(options.size_map_path, ".solb")) {
        std::fprintf(stderr,
                     "tetlod view: --size-map '%s' is not a size map: a Medit .sol or .solb "
                     "file (the mesh its sizes are at goes in --size-map-mesh)\n",
                     options.size_map_path.c_str());
        return kExitUsage;
      }
    } else if (a == "--size-map-mesh") {
      if (!parse_option_value(args, &i, "--size-map-mesh", &options.size_map_mesh_path))
        return kExitUsage;
    } else if (a == "--hide") {
      if (!parse_option_value(args, &i, "--hide", &value)) return kExitUsage;
      std::vector<int32_t> ids;
      std::vector<std::string> names;
      if (const std::string why = parse_materials(value, &ids, &names); !why.empty()) {
        std::fprintf(stderr, "tetlod view: --hide '%s': %s; it takes material ids or names\n",
                     value.c_str(), why.c_str());
        return kExitUsage;
      }
      hidden.insert(hidden.end(), ids.begin(), ids.end());
      options.hidden_names.insert(options.hidden_names.end(), names.begin(), names.end());
    } else if (a == "--interactive-scale") {
      if (!parse_option_value(args, &i, "--interactive-scale", &value)) return kExitUsage;
      const auto f = parse_double(value);
      if (!f || !(*f > 0 && *f <= 1)) {
        std::fprintf(stderr, "tetlod view: --interactive-scale needs a number in (0, 1]\n");
        return kExitUsage;
      }
      options.interactive_scale = *f;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod view: unknown option '%s'\n\n%s", a.c_str(), kViewUsage);
      return kExitUsage;
    } else if (options.mesh_path.empty()) {
      options.mesh_path = a;
    } else {
      std::fprintf(stderr, "tetlod view: more than one FILE given\n\n%s", kViewUsage);
      return kExitUsage;
    }
  }
  if (!options.size_map_mesh_path.empty() && options.size_map_path.empty()) {
    std::fprintf(stderr, "tetlod view: --size-map-mesh %s: give the sizes too (--size-map)\n",
                 options.size_map_mesh_path.c_str());
    return kExitUsage;
  }
  if (!options.size_map_path.empty() && is_history_path(options.mesh_path)) {
    std::fprintf(stderr,
                 "tetlod view: --size-map %s: %s is a history, which keeps the size map it was "
                 "made with, if any\n",
                 options.size_map_path.c_str(), options.mesh_path.c_str());
    return kExitUsage;
  }
  if (options.mesh_path.empty() && !options.has_script) options.mesh_path = default_model();
  // As render's --hide: an id or a name the mesh lacks is a usage error, said before a
  // window opens. The mesh is read here for it (only with --hide); one that does not
  // read is left to the window, which says why. (With a script that opens the first
  // mesh, the window looks the names up in it and says which it lacks.)
  if (!options.mesh_path.empty() && (!hidden.empty() || !options.hidden_names.empty())) {
    TetMesh mesh;
    std::vector<MaterialName> names;
    Status s;
    if (is_history_path(options.mesh_path)) {
      CollapseHistory history;
      s = read_history(options.mesh_path, &mesh, &history, nullptr, &names);
    } else {
      ReadInfo info;
      s = read_mesh(options.mesh_path, &mesh, &info);
      names = std::move(info.material_names);
    }
    if (s) {
      RenderOptions check;
      check.hidden_materials = hidden;
      check.hidden_names = options.hidden_names;
      if (!resolve_materials(mesh, names, "view", &check)) return kExitUsage;
      hidden = check.hidden_materials;
      options.hidden_names.clear();
    }
  }
  options.hidden_materials = hidden;
  return run_viewer(options);
}

}  // namespace tetlod::app
