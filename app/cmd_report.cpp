// tetlod report IN -o DIR [view flags] [--simplify flags] [--levels N,...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/render_options.h"
#include "app/terminal_progress.h"
#include "core/adjacency.h"
#include "core/improve.h"
#include "core/io/output_files.h"
#include "core/lod.h"
#include "core/mesh_stats.h"
#include "core/metrics.h"
#include "render/histogram_chart.h"

namespace tetlod::app {
namespace {

constexpr const char* kReportUsageHead =
    "usage: tetlod report IN -o DIR [--simplify --size S ... [--levels N,N,...]] [view flags]\n"
    "\n"
    "Writes DIR/report.html, a self-contained page (images embedded): the paper's Table I\n"
    "row for the input and for each level, a picture of each (like the paper's Fig. 4)\n"
    "and its stretch histogram. The pictures and charts are also written as PNG files.\n"
    "IN may be a saved collapse history (.tlh, from 'tetlod simplify --history'): then\n"
    "its levels are reported without simplifying again (--levels, and --improve within\n"
    "the thresholds saved in the history).\n"
    "  --levels N,...    levels of the collapse history nearest N elements each\n"
    "  --elements N      one more level, nearest N elements (as simplify's --elements)\n"
    "  --simplify        simplify with the flags of 'tetlod simplify' (--size, --stretch,\n"
    "                    --valence, --tolerance, --material-size, --size-field,\n"
    "                    --size-map, ...; as there, --stretch 0.00012 <= D < 1 and\n"
    "                    4 <= --valence V <= 255);\n"
    "                    with --improve, every level is drawn and measured after\n"
    "                    'tetlod simplify --improve' has improved its shapes\n"
    "View flags, as for 'tetlod render' (default picture 480 x 480):\n";

void print_usage(std::FILE* stream) {
  std::fputs(kReportUsageHead, stream);
  std::fputs(kRenderFlagsHelp, stream);
}

struct Level {
  std::string label;
  TetMesh mesh;
};

std::string base64(const std::vector<uint8_t>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t b0 = bytes[i];
    const uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    const uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const uint32_t v = b0 << 16 | b1 << 8 | b2;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string table_row(const std::string& label, const PropertyRow& r) {
  return "<tr><th>" + html_escape(label) + "</th><td>" + std::to_string(r.nodes) + "</td><td>" +
         std::to_string(r.edges) + "</td><td>" + std::to_string(r.elements) + "</td><td>" +
         format("%.4f", r.average_stretch) + "</td><td>" + format("%.4f", r.min_stretch) +
         "</td><td>" + std::to_string(r.max_valence) + "</td><td>" + format("%.5g", r.max_size) +
         "</td><td>" + format("%.6g", r.volume) + "</td></tr>\n";
}

constexpr const char* kTableHead =
    "<tr><th></th><th>#nodes</th><th>#edges</th><th>#elements</th><th>ave. stretch</th>"
    "<th>min. stretch</th><th>max. valence</th><th>max. size</th><th>volume</th></tr>\n";

std::string img(const std::vector<uint8_t>& png, const std::string& alt) {
  return "<img src=\"data:image/png;base64," + base64(png) + "\" alt=\"" + html_escape(alt) + "\">";
}

// The heading of the level nearest `n` elements, at `step`. When no level comes near
// (n is beyond the last or the first level), it says so, and so does a note.
std::string level_label(long long n, size_t step, const Lod& lod) {
  std::string label = "level ~" + std::to_string(n) + " (step " + std::to_string(step);
  const size_t tets = lod.tet_count_at(step);
  const BeyondLevels where = beyond_levels(n, step, lod.step_count(), tets);
  std::string beyond;
  if (where == BeyondLevels::kPastTheLast) {
    beyond = "no level has fewer than " + std::to_string(tets) + " tets";
    label += ", the last: " + beyond;
  } else if (where == BeyondLevels::kBeforeTheFirst) {
    beyond = "no level has more than " + std::to_string(tets) + " tets";
    label += ", the first: " + beyond;
  }
  if (!beyond.empty()) {
    std::fprintf(stderr, "tetlod report: note: level ~%lld: %s; the %s level is reported\n", n,
                 beyond.c_str(), step == 0 ? "first" : "last");
  }
  return label + ")";
}

// The levels nearest `levels` elements, largest count first, each shown once: a count
// whose level is the last step (or the previous count's level) is named in that level's
// heading instead of the same pictures twice; `last_also` gets those of the last step.
struct ChosenLevel {
  size_t step = 0;
  std::string label;
};
std::vector<ChosenLevel> choose_levels(std::vector<long long> levels, const Lod& lod,
                                       std::string* last_also) {
  std::sort(levels.begin(), levels.end(), std::greater<>());
  std::vector<ChosenLevel> chosen;
  for (const long long n : levels) {
    const size_t step = lod.step_for_elements(static_cast<size_t>(n));
    const std::string label = level_label(n, step, lod);  // (and its note, if any)
    const std::string also = "; also " + label;
    if (step == lod.step_count()) {
      *last_also += also;
    } else if (!chosen.empty() && chosen.back().step == step) {
      chosen.back().label += also;
    } else {
      chosen.push_back({step, label});
    }
  }
  return chosen;
}

std::optional<std::vector<long long>> parse_levels(const std::string& text) {
  std::vector<long long> levels;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const auto n = parse_integer(text.substr(start, comma - start));
    if (!n || *n < 1) return std::nullopt;
    levels.push_back(*n);
    start = comma + 1;
  }
  return levels;
}

}  // namespace

int cmd_report(const Args& args) {
  if (wants_help(args)) {
    print_usage(stdout);
    return kExitOk;
  }
  std::string in, dir;
  RenderOptions options;
  options.snapshot.width = options.snapshot.height = 480;
  std::vector<long long> levels;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const OptionResult parsed = parse_render_option(args, &i, "report", &options);
    if (parsed == OptionResult::kError) return kExitUsage;
    if (parsed == OptionResult::kParsed) continue;
    std::string v;
    if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &dir)) return kExitUsage;
    } else if (a == "--levels") {
      if (!parse_option_value(args, &i, "--levels", &v)) return kExitUsage;
      const auto parsed_levels = parse_levels(v);
      if (!parsed_levels) {
        std::fprintf(stderr, "tetlod report: --levels '%s' is not a list of element counts >= 1\n",
                     v.c_str());
        return kExitUsage;
      }
      levels = *parsed_levels;
      options.simplify = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod report: unknown option '%s'\n\n", a.c_str());
      print_usage(stderr);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else {
      more_than_one_input("report", args, in, a);
      return kExitUsage;
    }
  }
  if (in.empty() || dir.empty()) {
    std::fputs("tetlod report: need IN and -o DIR\n\n", stderr);
    print_usage(stderr);
    return kExitUsage;
  }
  if (!output_directory_ok(dir, true)) return kExitBadInput;
  const bool from_history = is_history_path(in);
  if (from_history &&
      !history_flags_ok(in, "report", options,
                        "--levels N,... (and --elements N) to choose its levels, and --improve"))
    return kExitUsage;
  if (!from_history && options.simplify && !options.simplify_options.size_given) {
    std::fputs(
        "tetlod report: --simplify and --levels need a target size (--size, --material-size, "
        "--size-field or --size-map)\n",
        stderr);
    return kExitUsage;
  }
  if (options.simplify_options.elements > 0) levels.push_back(options.simplify_options.elements);

  TetMesh input;
  std::vector<MaterialName> names;  // of the input file's materials
  SurfacePatches patches;           // the input file's surface groups
  OpenedHistory history;
  if (from_history) {
    // The levels of a saved run: its finest level (the subdivided input), those
    // nearest --levels, and its last, all without simplifying again.
    if (!open_history(in, "report", &history)) return kExitBadInput;
    if (options.simplify_options.improve && !history_improve_params(in, "report", history.params))
      return kExitUsage;
    if (!history_level(&history, "report", 0, &input)) return kExitBadInput;
    names = history.names;
  } else {
    ReadInfo info;
    if (!load_mesh(in, &input, &info)) return kExitBadInput;
    names = std::move(info.material_names);
    if ((options.simplify || !options.groups.empty()) && !info.surface_groups.empty())
      patches = SurfacePatches(input, info.surface_groups);
    // No groups are written, nor drawn inside a material: the mesh may coarsen there.
    if (options.groups.empty()) patches.drop_inside();
  }
  if (!resolve_materials(input, names, "report", &options) ||
      !resolve_groups(from_history ? history.patches : patches, "report", &options))
    return kExitUsage;
  if (const Status s = render::check_drawable(input); !s) {
    std::fprintf(stderr, "tetlod report: %s: %s\n", in.c_str(), s.message().c_str());
    return kExitBadInput;
  }
  OffscreenRenderer offscreen;
  if (!open_offscreen_renderer("report", &offscreen)) return kExitBadInput;
  offscreen.renderer->set_material_names(names);

  std::vector<Level> meshes;
  std::string thresholds, run_summary;
  if (from_history) {
    const size_t last = history.lod->step_count();
    if (history.params)
      thresholds = describe_thresholds(*history.params) + " (saved in the history)" +
                   (options.simplify_options.improve ? "; levels improved (--improve)" : "");
    meshes.push_back({"step 0 (the subdivided input)", std::move(input)});
    std::string last_also;
    std::vector<ChosenLevel> chosen = choose_levels(levels, *history.lod, &last_also);
    chosen.push_back({last, "last step (" + std::to_string(last) + ")" + last_also});
    for (const ChosenLevel& c : chosen) {
      Level level;
      level.label = c.label;
      if (!history_level(&history, "report", c.step, &level.mesh)) return kExitBadInput;
      if (options.simplify_options.improve) {
        improve_mesh(&level.mesh, *history.params, 4, nullptr, &history.patches);
        level.label += ", improved";
      }
      meshes.push_back(std::move(level));
    }
  } else if (options.simplify) {
    SimplifyOptions& so = options.simplify_options;
    if (const int code = finish_simplify_options(input, names, "report", &so)) return code;
    SimplifyResult result;
    TerminalProgress progress("tetlod report");
    const Status s =
        simplify(input, so.params, &result, progress.simplify_callback(), nullptr, &patches);
    progress.clear();
    if (!s) {
      std::fprintf(stderr, "tetlod report: %s\n", s.message().c_str());
      return exit_code_of_failed_run(s.bad_value());
    }
    // What the run did and what the final mesh still breaks, as `tetlod simplify`
    // prints it.
    const std::string past = past_valence_summary(result);
    run_summary =
        std::to_string(result.splits) + " splits, " + std::to_string(result.history.step_count()) +
        " collapses; rejected evaluations: " + describe_rejections(result.rejections) +
        ". Final mesh" + (so.improve ? std::string(" (before --improve)") : std::string()) + ": " +
        describe_violations(result.violations) + "." +
        (result.violations.above_size > 0
             ? " Above the size: " + above_size_reason(so.params, result)
             : std::string()) +
        (past.empty() ? std::string() : " Past the valence: " + past + ".");
    thresholds =
        describe_thresholds(so.params) + (so.improve ? "; levels improved (--improve)" : "");
    meshes.push_back({"input", input});
    Lod lod(result.base, &result.history);
    std::string last_also;
    for (const ChosenLevel& c : choose_levels(levels, lod, &last_also)) {
      lod.seek(c.step);
      meshes.push_back({c.label, lod.extract()});
    }
    meshes.push_back(
        {"simplified (step " + std::to_string(result.history.step_count()) + ")" + last_also,
         std::move(result.output)});
    if (so.improve) {
      for (size_t k = 1; k < meshes.size(); ++k) {
        improve_mesh(&meshes[k].mesh, so.params, 4, nullptr, &patches);
        meshes[k].label += ", improved";
      }
    }
  } else {
    meshes.push_back({"input", std::move(input)});
  }

  // Coloured by size, one colour range for every level (each its own made a coarser
  // level look finer): the sizes of the shown materials' tets over all of them, unless
  // --range gives one.
  if (options.snapshot.draw.color_mode == render::ColorMode::kSize &&
      options.snapshot.size_range_from_faces) {
    const std::vector<int32_t>& hidden = options.snapshot.filter.hidden_materials;
    double lo = INFINITY, hi = -INFINITY;
    for (const Level& level : meshes)
      for (size_t t = 0; t < level.mesh.tet_count(); ++t) {
        if (std::find(hidden.begin(), hidden.end(), level.mesh.materials[t]) != hidden.end())
          continue;
        const double size = tet_shape(level.mesh, level.mesh.tets[t]).size;
        lo = std::min(lo, size);
        hi = std::max(hi, size);
      }
    if (lo <= hi) {
      options.snapshot.draw.range_min = lo;
      options.snapshot.draw.range_max = hi > lo ? hi : lo + 1;
      options.snapshot.size_range_from_faces = false;
    }
  }

  const auto format_range = [](double lo, double hi) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4g to %.4g", lo, hi);
    return std::string(text);
  };

  // Every file is made in memory first, then all are written together (or none).
  std::vector<std::pair<std::string, std::vector<uint8_t>>> pictures;  // name, PNG
  std::string summary, figures;
  for (size_t k = 0; k < meshes.size(); ++k) {
    const Level& level = meshes[k];
    const MeshStats stats = compute_mesh_stats(level.mesh, build_vertex_tets(level.mesh));
    summary += table_row(level.label, stats.whole);

    const render::PreparedMesh prepared = render::prepare_mesh(level.mesh);
    const std::vector<render::GroupOverlay::Group> groups = show_surface_groups(
        offscreen.renderer.get(), prepared, from_history ? history.patches : patches, options);
    if (k == 0) note_undrawn_groups("report", groups);  // (as render says it)
    const render::Image picture =
        render::render_snapshot(offscreen.renderer.get(), prepared, options.snapshot);
    if (picture.width == 0) {
      std::fprintf(stderr, "tetlod report: %s\n", offscreen.renderer->last_error().c_str());
      return kExitBadInput;
    }
    if (k == 0 && offscreen.renderer->triangle_count() == 0) {  // as render says it
      std::fputs(
          "tetlod report: note: the pictures are empty: every tet is hidden (--materials, "
          "--hide) or cut away (--cut, --cut-plane)\n",
          stderr);
    }
    const render::Image chart = render::draw_histogram_chart(
        stats.stretch_histogram, options.snapshot.draw.color_map, 480, 260,
        "stretch histogram, " + std::to_string(stats.whole.elements) + " tets");
    const std::string stem = "level" + std::to_string(k);
    pictures.push_back({stem + ".png", render::encode_png(picture)});
    pictures.push_back({stem + "_histogram.png", render::encode_png(chart)});
    std::string materials = "<table>\n" + std::string(kTableHead);
    for (const MaterialRow& m : stats.per_material) {
      const std::string name = material_name_of(&names, m.material);
      materials += table_row(
          "material " + std::to_string(m.material) + (name.empty() ? "" : " " + name), m.row);
    }
    materials += "</table>\n";
    figures += "<section><h2>" + html_escape(level.label) + "</h2>\n<div class=\"figs\">" +
               img(pictures[pictures.size() - 2].second, level.label) +
               img(pictures.back().second, "stretch histogram") + "</div>\n" + materials +
               "</section>\n";
  }

  const std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>TetLOD report: " +
      html_escape(in) +
      "</title>\n<style>body{font-family:sans-serif;margin:2em;color:#222}"
      "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;"
      "padding:2px 8px;text-align:right}th:first-child{text-align:left}"
      ".figs img{margin-right:1em;vertical-align:top;border:1px solid #ddd}</style>\n"
      "</head><body>\n<h1>TetLOD report</h1>\n<p>Input: <code>" +
      html_escape(in) + "</code>" +
      (thresholds.empty() ? "" : "<br>Thresholds: " + html_escape(thresholds)) +
      (run_summary.empty() ? "" : "<br>Run: " + html_escape(run_summary)) +
      (from_history ? std::string("<br>The levels of a saved collapse history, without "
                                  "simplifying again") +
                          (thresholds.empty() ? " (saved without its thresholds)" : "")
                    : std::string()) +
      // The pictures leave hidden materials out; the tables and histograms count them.
      (options.snapshot.filter.hidden_materials.empty()
           ? std::string()
           : "<br>The pictures leave the hidden materials out; the tables and the stretch "
             "histograms count every tet, theirs too") +
      (options.snapshot.draw.color_mode == render::ColorMode::kSize
           ? "<br>Colour: each tet's size (longest edge), on one scale for every level, " +
                 html_escape(
                     format_range(options.snapshot.draw.range_min, options.snapshot.draw.range_max))
           : std::string()) +
      "</p>\n<h2>Properties (Table I)</h2>\n<table>\n" + kTableHead + summary + "</table>\n" +
      figures + "</body></html>\n";
  std::error_code ec;
  // The directories made for the report (DIR and any missing parents), deepest first.
  std::vector<std::filesystem::path> made;
  for (std::filesystem::path d = std::filesystem::absolute(dir, ec).lexically_normal();
       !d.empty() && !std::filesystem::exists(d, ec) && d != d.parent_path(); d = d.parent_path())
    made.push_back(d);
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    std::fprintf(stderr, "tetlod report: %s: cannot create the directory: %s\n", dir.c_str(),
                 ec.message().c_str());
    return kExitBadInput;
  }
  const std::string path = dir + "/report.html";
  Status s;
  {
    OutputFiles files;  // (its temporaries go when it does, if not committed)
    for (const auto& [name, png] : pictures) {
      if (s)
        s = files.stage(dir + "/" + name,
                        std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    }
    if (s) s = files.stage(path, html);
    if (s) s = files.commit();
  }
  if (!s) {
    std::fprintf(stderr, "tetlod report: %s\n", s.message().c_str());
    // Nothing was written, and the staged files' temporaries are gone: the directories
    // made for the report go too (a full disk left them behind; found by hostile-input
    // tests). remove() keeps one not empty.
    for (const std::filesystem::path& d : made) std::filesystem::remove(d, ec);
    return kExitBadInput;
  }
  // Pictures of an earlier, longer report in the same directory (levelN.png and
  // levelN_histogram.png past this report's last level) would read as part of this
  // one: removed. Nothing else in the directory is touched.
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    size_t digits = 5;  // after "level"
    while (digits < name.size() && name[digits] >= '0' && name[digits] <= '9') ++digits;
    const std::string tail = name.substr(std::min(digits, name.size()));
    if (name.compare(0, 5, "level") != 0 || digits == 5 || digits > 12 ||
        (tail != ".png" && tail != "_histogram.png") || !entry.is_regular_file(ec))
      continue;
    if (std::stoull(name.substr(5, digits - 5)) < meshes.size()) continue;
    stale.push_back(entry.path());
  }
  size_t removed = 0;
  for (const auto& p : stale) removed += std::filesystem::remove(p, ec);
  if (removed > 0)
    std::printf("removed %zu picture(s) of an earlier report with more levels\n", removed);
  std::printf("%s: %zu level(s)\n", path.c_str(), meshes.size());
  return kExitOk;
}

}  // namespace tetlod::app
