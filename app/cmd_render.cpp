// tetlod render FILE -o shot.png [view flags] [--simplify flags]
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/render_options.h"
#include "core/improve.h"

namespace tetlod::app {
namespace {

constexpr const char* kRenderUsageHead =
    "usage: tetlod render FILE -o SHOT.png [--width W --height H]\n"
    "                     [--color stretch|material|size]\n"
    "                     [--materials 1,2,3 | --hide 1] [--cut AXIS=VALUE | --cut-plane "
    "NX,NY,NZ,D]\n"
    "                     [--view iso|x|y|z | --camera EX,EY,EZ,TX,TY,TZ] [--wireframe]\n"
    "                     [--highlight-below D] [--groups all|G,...]\n"
    "                     [--simplify --size S ... [--elements N] [--improve]]\n"
    "\n"
    "Draws the boundary and interface faces of the visible tets offscreen (OpenGL 3.3 core\n"
    "through OSMesa, else EGL surfaceless; TETLOD_GL_BACKEND=osmesa|egl picks one: no\n"
    "display or GPU needed) and writes a PNG. FILE may be a collapse\n"
    "history (.tlh, from 'tetlod simplify --history'): then --elements N picks its level\n"
    "(default: the last), without simplifying again, and --improve improves it within the\n"
    "thresholds saved in the history. The picture is 800 x 800 unless --width and --height\n"
    "say otherwise.\n";
constexpr const char* kRenderUsageTail =
    "  --simplify        render the simplified mesh (any flag of 'tetlod simplify' asks\n"
    "                    for it too); takes the flags of 'tetlod simplify':\n"
    "                    --size, --stretch, --valence, --tolerance, --material-size,\n"
    "                    --size-field, --size-map, --size-map-mesh, --no-subdivide,\n"
    "                    --within-valence, --past-valence-factor, --one-thread,\n"
    "                    --crease-angle, --improve (as there: --stretch 0.00012 <= D < 1,\n"
    "                    4 <= --valence V <= 255), and\n"
    "  --elements N      the level of the collapse history nearest N elements\n";

void print_usage(std::FILE* stream) {
  std::fputs(kRenderUsageHead, stream);
  std::fputs(kRenderFlagsHelp, stream);
  std::fputs(kRenderUsageTail, stream);
}

}  // namespace

int cmd_render(const Args& args) {
  if (wants_help(args)) {
    print_usage(stdout);
    return kExitOk;
  }
  std::string in, out;
  RenderOptions options;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const OptionResult parsed = parse_render_option(args, &i, "render", &options);
    if (parsed == OptionResult::kError) return kExitUsage;
    if (parsed == OptionResult::kParsed) continue;
    if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &out)) return kExitUsage;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod render: unknown option '%s'\n\n", a.c_str());
      print_usage(stderr);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else {
      more_than_one_input("render", args, in, a);
      return kExitUsage;
    }
  }
  if (in.empty() || out.empty()) {
    std::fputs("tetlod render: need FILE and -o SHOT.png\n\n", stderr);
    print_usage(stderr);
    return kExitUsage;
  }
  if (options.snapshot.draw.color_mode == render::ColorMode::kMaterial &&
      !options.snapshot.size_range_from_faces) {
    std::fputs("tetlod render: --range is for --color stretch or size, not material\n", stderr);
    return kExitUsage;
  }
  if (!has_extension(out, ".png")) {
    std::fprintf(stderr, "tetlod render: -o %s: the picture is written as PNG: give a .png name\n",
                 out.c_str());
    return kExitUsage;
  }
  if (!output_directory_ok(out)) return kExitBadInput;
  const bool history = is_history_path(in);
  if (history &&
      !history_flags_ok(in, "render", options,
                        "--elements N to choose its level (default: the last), and --improve"))
    return kExitUsage;
  if (!history && options.simplify && !options.simplify_options.size_given) {
    if (options.simplify_beyond_elements) {
      std::fputs(
          "tetlod render: --simplify needs a target size (--size, --material-size, "
          "--size-field or --size-map)\n",
          stderr);
    } else {
      std::fprintf(stderr,
                   "tetlod render: %s: give --simplify with a target size (--size ...), or a "
                   "saved history (.tlh)\n",
                   options.simplify_options.improve
                       ? "--improve improves a level of a simplification"
                       : "--elements picks a level of a simplification");
    }
    return kExitUsage;
  }

  TetMesh mesh;
  std::vector<MaterialName> names;  // for the legend
  SurfacePatches patches;           // the file's surface groups
  if (history) {
    HistoryLevel level;
    if (!load_history_level(in, "render", -1, options.simplify_options.elements, &level))
      return kExitBadInput;
    mesh = std::move(level.mesh);
    names = level.names;
    patches = std::move(level.patches);
    if (options.simplify_options.improve) {
      if (!history_improve_params(in, "render", level.params)) return kExitUsage;
      improve_mesh(&mesh, *level.params, 4, nullptr, &patches);
    }
  } else {
    ReadInfo info;
    if (!load_mesh(in, &mesh, &info)) return kExitBadInput;
    names = info.material_names;
    if ((options.simplify || !options.groups.empty()) && !info.surface_groups.empty())
      patches = SurfacePatches(mesh, info.surface_groups);
    // No groups are written, nor drawn inside a material: the mesh may coarsen there.
    if (options.groups.empty()) patches.drop_inside();
  }
  if (!resolve_materials(mesh, names, "render", &options) ||
      !resolve_groups(patches, "render", &options))
    return kExitUsage;
  if (const Status s = render::check_drawable(mesh); !s) {
    std::fprintf(stderr, "tetlod render: %s: %s\n", in.c_str(), s.message().c_str());
    return kExitBadInput;
  }
  if (options.simplify && !history) {
    TetMesh simplified;
    if (const int code = simplified_mesh(mesh, names, "render", &options, &simplified, &patches))
      return code;
    mesh = std::move(simplified);
  }
  OffscreenRenderer offscreen;
  if (!open_offscreen_renderer("render", &offscreen)) return kExitBadInput;
  offscreen.renderer->set_material_names(std::move(names));

  const auto start = std::chrono::steady_clock::now();
  const render::PreparedMesh prepared = render::prepare_mesh(std::move(mesh));
  const std::vector<render::GroupOverlay::Group> groups =
      show_surface_groups(offscreen.renderer.get(), prepared, patches, options);
  const render::Image image =
      render::render_snapshot(offscreen.renderer.get(), prepared, options.snapshot);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (image.width == 0) {
    std::fprintf(stderr, "tetlod render: %s\n", offscreen.renderer->last_error().c_str());
    return kExitBadInput;
  }
  const Status s = render::write_png(out, image);
  if (!s) {
    std::fprintf(stderr, "tetlod render: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  std::printf("%s: %dx%d, %zu tets, %zu faces drawn, %.3f s (%s)\n", out.c_str(), image.width,
              image.height, prepared.mesh.tet_count(), offscreen.renderer->triangle_count(),
              seconds, offscreen.context->description().c_str());
  if (offscreen.renderer->triangle_count() == 0) {
    std::fputs(
        "tetlod render: note: the picture is empty: every tet is hidden (--materials, "
        "--hide) or cut away (--cut, --cut-plane)\n",
        stderr);
  }
  note_undrawn_groups("render", groups);
  // A legend that does not fit the picture is left out (render::Renderer::legend_space).
  const render::DrawSettings& draw = options.snapshot.draw;
  const render::LegendSpace legend =
      offscreen.renderer->legend_space(draw, image.width, image.height);
  const bool by_material = draw.color_mode == render::ColorMode::kMaterial;
  if (draw.legend && offscreen.renderer->triangle_count() > 0 &&
      (by_material ? legend.key_width == 0 : legend.bottom == 0)) {
    std::fprintf(stderr,
                 "tetlod render: note: the %s does not fit a %dx%d picture and is left out "
                 "(a larger --width and --height show it)\n",
                 by_material ? "material key" : "colour bar", image.width, image.height);
  }
  return kExitOk;
}

}  // namespace tetlod::app
