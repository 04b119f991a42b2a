// tetlod stats FILE [--json] [--size S --stretch D --valence V ... [--check]]
#include <chrono>
#include <cstdio>
#include <map>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/simplify_options.h"
#include "core/adjacency.h"
#include "core/classify.h"
#include "core/improve.h"
#include "core/mesh_stats.h"
#include "core/surface.h"

namespace tetlod::app {
namespace {

constexpr const char* kStatsUsage =
    "usage: tetlod stats FILE [--json] [--size S] [--stretch D] [--valence V]\n"
    "                         [--material-size M=S,...] [--size-field SPEC]\n"
    "                         [--size-map FILE.sol [--size-map-mesh MESH]] [--check]\n"
    "\n"
    "Prints the mesh properties of the paper's Table I -- #nodes, #edges, #elements,\n"
    "average and minimum stretch, maximum valence, maximum size (longest edge) -- for the\n"
    "whole mesh and for each material's sub-mesh, a stretch histogram (bins of 0.1), the\n"
    "boundary/interface triangles per material pair, the file's own surface groups (as\n"
    "--surfaces writes them) and the vertex classification.\n"
    "FILE: .mesh .meshb .msh .node/.ele .vtk .vtu .bdf/.nas .inp\n"
    "  --json   machine-readable output on stdout\n"
    "With thresholds (as 'tetlod simplify' takes them; --stretch 0.15 and --valence 25\n"
    "unless given, no size limit unless --size, --material-size, --size-field or\n"
    "--size-map, whose sizes are at FILE's vertices), it also counts the tets below the\n"
    "stretch or above their size and the nodes above the valence: a check of a mesh from\n"
    "any tool against an analysis' requirements. --stretch takes any 0 < D < 1; in\n"
    "--material-size, M is a material's id or name, and a comma inside a name is written\n"
    "as it is ('Cu, 20C=2').\n"
    "  --check  exit with status 3 if anything breaks them (implies the default\n"
    "           thresholds if none is given)\n";

struct SurfaceSummary {
  std::map<std::pair<int32_t, int32_t>, size_t> triangles_per_pair;
  size_t kind_counts[4] = {0, 0, 0, 0};
  size_t feature_edges = 0;
};

SurfaceSummary summarize_surface(const TetMesh& mesh, const std::vector<uint32_t>& neighbors) {
  SurfaceSummary summary;
  const std::vector<SurfaceTriangle> surface = extract_surface(mesh, neighbors);
  for (const SurfaceTriangle& t : surface) ++summary.triangles_per_pair[{t.inner, t.outer}];
  const Classification c = classify_vertices(mesh, surface);
  for (FeatureKind k : c.kind) ++summary.kind_counts[static_cast<int>(k)];
  summary.feature_edges = c.feature_edges.size();
  return summary;
}

std::string pair_name(const std::pair<int32_t, int32_t>& p) {
  return std::to_string(p.first) + "|" +
         (p.second == kOutsideMaterial ? std::string("outside") : std::to_string(p.second));
}

void print_row_json(const PropertyRow& r) {
  std::printf(
      "{\"nodes\": %zu, \"edges\": %zu, \"elements\": %zu, \"average_stretch\": %.17g, "
      "\"min_stretch\": %.17g, \"max_valence\": %u, \"max_size\": %.17g, \"volume\": %.17g}",
      r.nodes, r.edges, r.elements, r.average_stretch, r.min_stretch, r.max_valence, r.max_size,
      r.volume);
}

}  // namespace

int cmd_stats(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kStatsUsage, stdout);
    return kExitOk;
  }
  std::string path;
  bool json = false, check = false, thresholds_given = false;
  SimplifyOptions thresholds;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--json") {
      json = true;
    } else if (a == "--check") {
      check = true;
    } else if (a == "--size" || a == "--stretch" || a == "--valence" || a == "--material-size" ||
               a == "--size-field" || a == "--size-map" || a == "--size-map-mesh") {
      if (parse_simplify_option(args, &i, "stats", &thresholds) != OptionResult::kParsed)
        return kExitUsage;
      thresholds_given = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod stats: unknown option '%s'\n\n%s", a.c_str(), kStatsUsage);
      return kExitUsage;
    } else if (path.empty()) {
      path = a;
    } else {
      std::fprintf(stderr, "tetlod stats: more than one FILE given\n\n%s", kStatsUsage);
      return kExitUsage;
    }
  }
  if (path.empty()) {
    std::fprintf(stderr, "tetlod stats: no FILE given\n\n%s", kStatsUsage);
    return kExitUsage;
  }

  const auto start = std::chrono::steady_clock::now();
  TetMesh mesh;
  ReadInfo info;
  if (!load_mesh(path, &mesh, &info)) return kExitBadInput;
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const MeshStats stats = compute_mesh_stats(mesh, adjacency.vertex_tets);
  const SurfaceSummary surface = summarize_surface(mesh, adjacency.tet_neighbors);
  // The file's own surface groups, as laid on the mesh's surface (what --surfaces
  // writes of them).
  SurfacePatches patches;
  if (!info.surface_groups.empty()) {
    patches = SurfacePatches(mesh, info.surface_groups);
    print_patch_notes(patches, "stats");
  }
  // The name --surfaces writes each of them under (group_surface()): the file's, or
  // for an unnamed one (a Medit reference, a TetGen marker) its material pair's if it
  // is one pair's, else surface_<tag>; "" if none of it is written.
  std::vector<std::string> written_as;
  if (!patches.groups().empty()) {
    SurfaceGroups grouped;
    if (!group_surface(mesh, &grouped, patches, true).ok()) grouped.groups.clear();
    for (const SurfacePatches::Group& g : patches.groups()) {
      std::string name;
      for (const SurfaceGroup& out : grouped.groups)
        if (out.tag == g.tag) {
          name = out.name;
          break;
        }
      written_as.push_back(name);
    }
  }
  const bool counting = thresholds_given || check;
  if (counting)
    if (const int code = finish_simplify_options(mesh, info.material_names, "stats", &thresholds,
                                                 &info.validation))
      return code;
  const SimplifyParams& params = thresholds.params;
  const ThresholdCounts breaks = counting ? threshold_breaks(mesh, params) : ThresholdCounts{};
  const bool broken = breaks.total() > 0;
  const int exit_code = check && broken ? kExitBreaks : kExitOk;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (json) {
    std::printf("{\n  \"file\": \"%s\",\n  \"format\": \"%s\",\n", json_escape(path).c_str(),
                format_name(info.format));
    std::printf("  \"reoriented_tets\": %zu,\n  \"removed_unused_vertices\": %zu,\n",
                info.validation.reoriented_tets, info.validation.removed_unused_vertices);
    std::printf("  \"whole\": ");
    print_row_json(stats.whole);
    std::printf(",\n  \"materials\": [");
    for (size_t i = 0; i < stats.per_material.size(); ++i) {
      const int32_t m = stats.per_material[i].material;
      const std::string name = material_name_of(&info.material_names, m);
      std::printf("%s\n    {\"material\": %d, %s\"row\": ", i ? "," : "", m,
                  name.empty() ? "" : ("\"name\": \"" + json_escape(name) + "\", ").c_str());
      print_row_json(stats.per_material[i].row);
      std::printf("}");
    }
    std::printf("\n  ],\n  \"stretch_histogram\": {\"bin_width\": %.17g, \"counts\": [",
                1.0 / kStretchBins);
    for (int b = 0; b < kStretchBins; ++b) {
      std::printf("%s%llu", b ? ", " : "",
                  static_cast<unsigned long long>(stats.stretch_histogram[b]));
    }
    std::printf("]},\n  \"surface_triangles\": {");
    bool first = true;
    for (const auto& [pair, count] : surface.triangles_per_pair) {
      std::printf("%s\"%s\": %zu", first ? "" : ", ", pair_name(pair).c_str(), count);
      first = false;
    }
    std::printf("},\n  \"surface_groups\": [");
    for (size_t i = 0; i < patches.groups().size(); ++i) {
      const SurfacePatches::Group& g = patches.groups()[i];
      std::printf(
          "%s\n    {\"tag\": %d, \"name\": \"%s\", \"written_as\": \"%s\", \"triangles\": %zu, "
          "\"in_a_smaller_group\": %zu, \"inside_a_material\": %zu, \"not_faces\": %zu}",
          i ? "," : "", g.tag, json_escape(g.name).c_str(), json_escape(written_as[i]).c_str(),
          g.triangles, g.shared, g.inside, g.missing);
    }
    std::printf(patches.groups().empty() ? "]" : "\n  ]");
    std::printf(
        ",\n  \"vertices\": {\"corner\": %zu, \"curve\": %zu, \"surface\": %zu, "
        "\"interior\": %zu},\n  \"feature_edges\": %zu,\n",
        surface.kind_counts[0], surface.kind_counts[1], surface.kind_counts[2],
        surface.kind_counts[3], surface.feature_edges);
    if (counting) {
      std::printf("  \"thresholds\": \"%s\",\n",
                  json_escape(describe_thresholds(params, /*with_tolerance=*/false)).c_str());
      std::printf(
          "  \"breaking\": {\"below_stretch\": %zu, \"above_size\": %zu, "
          "\"above_valence\": %zu},\n",
          breaks.below_stretch, breaks.above_size, breaks.above_valence);
    }
    std::printf("  \"seconds\": %.6f\n}\n", seconds);
    return exit_code;
  }

  std::printf("%s (%s)\n\n", path.c_str(), format_name(info.format));
  print_property_table(stats, &info.material_names);
  std::printf("\nstretch histogram (whole mesh)\n");
  uint64_t most = 1;
  for (uint64_t c : stats.stretch_histogram) most = std::max(most, c);
  for (int b = 0; b < kStretchBins; ++b) {
    const uint64_t c = stats.stretch_histogram[b];
    const int bar = static_cast<int>(50.0 * static_cast<double>(c) / static_cast<double>(most));
    std::printf("  %.1f-%.1f %10llu  %s\n", b / 10.0, (b + 1) / 10.0,
                static_cast<unsigned long long>(c), std::string(bar, '#').c_str());
  }
  std::printf("\nsurface triangles per material pair:");
  for (const auto& [pair, count] : surface.triangles_per_pair)
    std::printf(" %s=%zu", pair_name(pair).c_str(), count);
  if (!patches.groups().empty()) {
    std::printf("\nthe file's surface groups (tag name: triangles on the surface):");
    const char* separator = " ";
    for (size_t i = 0; i < patches.groups().size(); ++i) {
      const SurfacePatches::Group& g = patches.groups()[i];
      const std::string name = !g.name.empty() ? g.name
                               : written_as[i].empty()
                                   ? std::string("(unnamed)")
                                   : "(unnamed, written as " + written_as[i] + ")";
      std::printf("%s%d %s: %zu", separator, g.tag, name.c_str(), g.triangles);
      if (g.inside > 0) std::printf(" (+%zu inside a material)", g.inside);
      separator = ", ";
    }
  }
  std::printf("\nvertices: %zu corner, %zu curve, %zu surface, %zu interior; %zu feature edges\n",
              surface.kind_counts[0], surface.kind_counts[1], surface.kind_counts[2],
              surface.kind_counts[3], surface.feature_edges);
  if (counting) {
    std::printf("\nthresholds: %s\n",
                describe_thresholds(params, /*with_tolerance=*/false).c_str());
    std::printf("breaking them: %s\n", describe_breaks(breaks).c_str());
  }
  std::printf("(%.3f s)\n", seconds);
  if (exit_code == kExitBreaks)
    std::fprintf(stderr, "tetlod stats: %s breaks the thresholds\n", path.c_str());
  return exit_code;
}

}  // namespace tetlod::app
