#include "app/render_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/terminal_progress.h"
#include "core/improve.h"
#include "core/lod.h"

namespace tetlod::app {

const char* const kRenderFlagsHelp =
    "  --width W --height H   image size in pixels, 16 to 4096\n"
    "  --color stretch|material|size   face colour: the tet's stretch (default), material,\n"
    "                         or size (its longest edge, in the mesh's units)\n"
    "  --colormap viridis|turbo   colour map for stretch or size (default viridis)\n"
    "  --range LO,HI          stretch or size at the ends of the colour map (default: 0,1\n"
    "                         for stretch, the drawn tets' smallest and largest size)\n"
    "  --materials 1,2,3      show only these materials (ids, or the input's names)\n"
    "  --hide 1,air           hide these materials (e.g. the air); in a list of names\n"
    "                         a comma inside a name is written \\,\n"
    "  --cut AXIS=VALUE       keep whole tets with centroid AXIS <= VALUE (AXIS x, y or z;\n"
    "                         -x=V keeps x >= V); the faces the cut exposes are drawn\n"
    "  --cut-plane NX,NY,NZ,D keep whole tets with centroid c where dot(n, c) <= D\n"
    "  --view iso|x|y|z       camera direction, framed on the shown materials (default iso)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ   camera at E looking at T\n"
    "  --wireframe            draw the edges of the drawn faces\n"
    "  --highlight-below D    show tets with stretch < D in magenta, also through the surface\n"
    "  --groups all|G,...     draw the input's surface groups (Gmsh physical surfaces,\n"
    "                         Medit triangle references, Abaqus *SURFACEs, ...), by name\n"
    "                         or tag, each in its colour over the faces and listed in the\n"
    "                         key; those hidden behind the surface show through\n"
    "  --no-legend            no colour bar or material key\n";

namespace {

std::optional<std::vector<double>> parse_doubles(const std::string& text) {
  std::vector<double> values;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const auto d = parse_double(text.substr(start, comma - start));
    if (!d) return std::nullopt;
    values.push_back(*d);
    start = comma + 1;
  }
  return values;
}

}  // namespace

OptionResult parse_render_option(const Args& args, size_t* i, const char* command,
                                 RenderOptions* options) {
  const std::string& a = args[*i];
  if (a == "--simplify") {
    options->simplify = options->simplify_beyond_elements = true;
    return OptionResult::kParsed;
  }
  const OptionResult simplify_flag =
      parse_simplify_option(args, i, command, &options->simplify_options);
  if (simplify_flag != OptionResult::kNotMine) {
    options->simplify = true;
    // A history's level takes --elements and --improve (with its saved thresholds).
    options->simplify_beyond_elements |= a != "--elements" && a != "--improve";
    return simplify_flag;
  }
  render::SnapshotSettings& s = options->snapshot;
  std::string v;
  auto bad_value = [&](const char* what) {
    std::fprintf(stderr, "tetlod %s: %s '%s' is not %s\n", command, a.c_str(), v.c_str(), what);
    return OptionResult::kError;
  };
  auto value = [&]() { return parse_option_value(args, i, a.c_str(), &v); };
  if (a == "--width" || a == "--height") {
    if (!value()) return OptionResult::kError;
    const auto n = parse_integer(v);
    if (!n || *n < 16 || *n > 4096) return bad_value("a size in pixels from 16 to 4096");
    (a == "--width" ? s.width : s.height) = static_cast<int>(*n);
  } else if (a == "--color") {
    if (!value()) return OptionResult::kError;
    if (v == "stretch") {
      s.draw.color_mode = render::ColorMode::kStretch;
    } else if (v == "material") {
      s.draw.color_mode = render::ColorMode::kMaterial;
    } else if (v == "size") {
      s.draw.color_mode = render::ColorMode::kSize;
    } else {
      return bad_value("stretch, material or size");
    }
  } else if (a == "--colormap") {
    if (!value()) return OptionResult::kError;
    if (v == "viridis") {
      s.draw.color_map = render::ColorMap::kViridis;
    } else if (v == "turbo") {
      s.draw.color_map = render::ColorMap::kTurbo;
    } else {
      return bad_value("viridis or turbo");
    }
  } else if (a == "--range") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_doubles(v);
    if (!d || d->size() != 2 || (*d)[0] >= (*d)[1]) return bad_value("LO,HI with LO < HI");
    s.draw.range_min = (*d)[0];
    s.draw.range_max = (*d)[1];
    s.size_range_from_faces = false;
  } else if (a == "--materials" || a == "--hide") {
    if (!value()) return OptionResult::kError;
    const bool shown = a == "--materials";
    if (const std::string why =
            parse_materials(v, shown ? &options->shown_materials : &options->hidden_materials,
                            shown ? &options->shown_names : &options->hidden_names);
        !why.empty()) {
      std::fprintf(stderr, "tetlod %s: %s '%s': %s; it takes material ids or names\n", command,
                   a.c_str(), v.c_str(), why.c_str());
      return OptionResult::kError;
    }
  } else if (a == "--cut") {
    if (!value()) return OptionResult::kError;
    const size_t eq = v.find('=');
    std::string axis = v.substr(0, std::min(eq, v.size()));
    double sign = 1;
    if (!axis.empty() && axis[0] == '-') {
      sign = -1;
      axis.erase(0, 1);
    }
    const auto offset = eq == std::string::npos ? std::nullopt : parse_double(v.substr(eq + 1));
    if (!offset || axis.size() != 1 || axis[0] < 'x' || axis[0] > 'z')
      return bad_value("AXIS=VALUE with AXIS x, y, z, -x, -y or -z");
    Vec3 normal;
    normal[axis[0] - 'x'] = sign;
    s.filter.cut = true;
    s.filter.cut_plane = {normal, sign * *offset};
  } else if (a == "--cut-plane") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_doubles(v);
    if (!d || d->size() != 4) return bad_value("NX,NY,NZ,D");
    const Vec3 normal{(*d)[0], (*d)[1], (*d)[2]};
    Vec3 unit;
    if (!unit_direction(normal, &unit)) return bad_value("a plane with a non-zero normal");
    // N.x = D is unit.x = D / |N|, and |N| = N.unit does not overflow.
    const double offset = (*d)[3] / dot(normal, unit);
    if (!std::isfinite(offset)) return bad_value("a plane at a finite distance from the origin");
    s.filter.cut = true;
    s.filter.cut_plane = {unit, offset};
  } else if (a == "--view") {
    if (!value()) return OptionResult::kError;
    if (v == "iso") {
      s.view.direction = render::ViewDirection::kIso;
    } else if (v == "x") {
      s.view.direction = render::ViewDirection::kX;
    } else if (v == "y") {
      s.view.direction = render::ViewDirection::kY;
    } else if (v == "z") {
      s.view.direction = render::ViewDirection::kZ;
    } else {
      return bad_value("iso, x, y or z");
    }
    s.view.custom = false;
  } else if (a == "--camera") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_doubles(v);
    if (!d || d->size() != 6) return bad_value("EX,EY,EZ,TX,TY,TZ");
    s.view.custom = true;
    s.view.eye = {(*d)[0], (*d)[1], (*d)[2]};
    s.view.target = {(*d)[3], (*d)[4], (*d)[5]};
    if (s.view.eye == s.view.target) return bad_value("a camera whose eye differs from its target");
  } else if (a == "--wireframe") {
    s.draw.wireframe = true;
  } else if (a == "--groups") {
    if (!value()) return OptionResult::kError;
    if (v.find_first_not_of(" \t") == std::string::npos)
      return bad_value("a list of surface groups, or all");
    options->groups = v;
  } else if (a == "--no-legend") {
    s.draw.legend = false;
  } else if (a == "--highlight-below") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_double(v);
    if (!d || *d <= 0 || *d > 1) return bad_value("a stretch in (0, 1]");
    s.filter.highlight = true;
    s.filter.highlight_below = *d;
  } else {
    return OptionResult::kNotMine;
  }
  return OptionResult::kParsed;
}

bool resolve_materials(const TetMesh& mesh, const std::vector<MaterialName>& names,
                       const char* command, RenderOptions* options) {
  for (const bool shown : {true, false}) {
    for (const std::string& name : shown ? options->shown_names : options->hidden_names) {
      int32_t id = 0;
      if (!material_by_name(name, names, command, shown ? "--materials" : "--hide", &id))
        return false;
      (shown ? options->shown_materials : options->hidden_materials).push_back(id);
    }
  }
  options->shown_names.clear();
  options->hidden_names.clear();
  std::vector<int32_t> present = mesh.materials;
  std::sort(present.begin(), present.end());
  present.erase(std::unique(present.begin(), present.end()), present.end());
  auto check = [&](const std::vector<int32_t>& ids) {
    for (const int32_t id : ids) {
      if (!std::binary_search(present.begin(), present.end(), id)) {
        std::string list;
        for (const int32_t m : present) list += " " + std::to_string(m);
        std::fprintf(stderr, "tetlod %s: material %d is not in the mesh (materials:%s)\n", command,
                     id, list.c_str());
        return false;
      }
    }
    return true;
  };
  if (!check(options->shown_materials) || !check(options->hidden_materials)) return false;
  std::vector<int32_t>& hidden = options->snapshot.filter.hidden_materials;
  hidden = options->hidden_materials;
  if (!options->shown_materials.empty()) {
    for (const int32_t m : present)
      if (std::find(options->shown_materials.begin(), options->shown_materials.end(), m) ==
          options->shown_materials.end())
        hidden.push_back(m);
  }
  return true;
}

bool resolve_groups(const SurfacePatches& patches, const char* command, RenderOptions* options) {
  if (options->groups.empty()) return true;
  const std::string why = find_surface_groups(options->groups, patches, &options->surface_groups);
  if (why.empty()) return true;
  std::fprintf(stderr, "tetlod %s: --groups '%s': %s\n", command, options->groups.c_str(),
               why.c_str());
  return false;
}

std::vector<render::GroupOverlay::Group> show_surface_groups(render::Renderer* renderer,
                                                             const render::PreparedMesh& mesh,
                                                             const SurfacePatches& patches,
                                                             const RenderOptions& options) {
  render::GroupOverlay overlay = render::build_group_overlay(
      mesh.mesh, mesh.neighbors, patches, options.surface_groups, options.snapshot.filter);
  renderer->set_groups(overlay);
  return std::move(overlay.groups);
}

void note_undrawn_groups(const char* command,
                         const std::vector<render::GroupOverlay::Group>& groups) {
  for (const render::GroupOverlay::Group& g : groups) {
    if (g.count > 0) continue;
    if (g.triangles > 0)
      std::fprintf(stderr,
                   "tetlod %s: note: surface group '%s' is not drawn: its %zu faces are hidden "
                   "(--materials, --hide) or cut away\n",
                   command, g.label.c_str(), g.triangles);
    else
      std::fprintf(stderr, "tetlod %s: note: surface group '%s' has no face on this mesh\n",
                   command, g.label.c_str());
  }
}

bool open_offscreen_renderer(const char* command, OffscreenRenderer* out) {
  std::string error;
  out->context = render::create_offscreen_context(&error);
  if (!out->context) {
    std::fprintf(stderr, "tetlod %s: %s\n", command, error.c_str());
    return false;
  }
  out->renderer = std::make_unique<render::Renderer>(out->context->gl());
  if (!out->renderer->init(&error)) {
    std::fprintf(stderr, "tetlod %s: %s\n", command, error.c_str());
    out->renderer.reset();
    return false;
  }
  return true;
}

bool history_flags_ok(const std::string& in, const char* command, const RenderOptions& options,
                      const char* choose) {
  if (!options.simplify_beyond_elements) return true;
  std::fprintf(stderr,
               "tetlod %s: %s is a collapse history, already simplified: give only %s (its "
               "saved thresholds; for others, write the level with 'tetlod lod %s --improve "
               "...' first)\n",
               command, in.c_str(), choose, in.c_str());
  return false;
}

bool history_improve_params(const std::string& in, const char* command,
                            const std::optional<SimplifyParams>& saved) {
  if (saved) return true;
  std::fprintf(stderr,
               "tetlod %s: %s was saved without its thresholds (as every history before "
               "2026-11-24 was), which "
               "--improve needs: write the level with 'tetlod lod %s --improve --size S ...' "
               "and give that\n",
               command, in.c_str(), in.c_str());
  return false;
}

int simplified_mesh(const TetMesh& input, const std::vector<MaterialName>& names,
                    const char* command, RenderOptions* options, TetMesh* out,
                    const SurfacePatches* patches) {
  SimplifyOptions& so = options->simplify_options;
  if (const int code = finish_simplify_options(input, names, command, &so)) return code;
  SimplifyResult result;
  TerminalProgress progress(std::string("tetlod ") + command);
  const Status status =
      simplify(input, so.params, &result, progress.simplify_callback(), nullptr, patches);
  progress.clear();
  if (!status) {
    std::fprintf(stderr, "tetlod %s: %s\n", command, status.message().c_str());
    return exit_code_of_failed_run(status.bad_value());
  }
  if (so.elements > 0) {
    Lod lod(result.base, &result.history);
    lod.seek(lod.step_for_elements(static_cast<size_t>(so.elements)));
    *out = lod.extract();
  } else {
    *out = std::move(result.output);
  }
  if (so.improve) improve_mesh(out, so.params, 4, nullptr, patches);
  return 0;
}

}  // namespace tetlod::app
