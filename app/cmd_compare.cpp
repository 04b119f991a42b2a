// tetlod compare BEFORE AFTER [--tolerance T] [--check] [--by-id] [--json]
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli_util.h"
#include "app/commands.h"
#include "core/mesh_compare.h"
#include "core/vec3.h"

namespace tetlod::app {
namespace {

constexpr const char* kCompareUsage =
    "usage: tetlod compare BEFORE AFTER [--tolerance T] [--check] [--by-id] [--json]\n"
    "\n"
    "How AFTER, a mesh made from BEFORE by any tool (tetlod simplify, a remesher, ...),\n"
    "keeps what BEFORE has: each material's volume before and after, and for each\n"
    "surface between two materials (or a material and the outside) how far it moved: a\n"
    "two-sided estimate of the Hausdorff distance between the two meshes' triangles of\n"
    "that pair (from the corners, edge midpoints and centroids of one side's triangles\n"
    "to the nearest triangle of the pair on the other side); and the surfaces or\n"
    "materials only one of them has; and where a material's number of connected pieces\n"
    "(tets joined through shared faces: two touching only at an edge or a corner are two\n"
    "pieces) or a surface's Euler characteristic changed. Where both files name their\n"
    "materials (Gmsh\n"
    "physical groups, Abaqus sets, ...), a material of AFTER is matched to the one of\n"
    "BEFORE with its name, whatever its id; otherwise (and for materials without a\n"
    "name both files have) by id.\n"
    "  --tolerance T   the distance a surface may move (with --check)\n"
    "  --check         exit with status 3 if a material or surface is lost or new, a\n"
    "                  material is in another number of pieces or a surface has another\n"
    "                  Euler characteristic (V - E + F: pinched, punctured, merged), or\n"
    "                  (with --tolerance) a surface moved further than T\n"
    "  --by-id         match materials by id even where both files name them\n"
    "  --json          machine-readable output on stdout (volumes and distances to\n"
    "                  17 digits; a change is a fraction, or \"lost\" or \"new\")\n";

std::string pair_text(const MaterialPair& p, const std::vector<MaterialName>* names) {
  auto one = [&](int32_t m) {
    if (m == kOutsideMaterial) return std::string("outside");
    const std::string name = material_name_of(names, m);
    return std::to_string(m) + (name.empty() ? "" : " " + name);
  };
  return one(p.first) + " | " + one(p.second);
}

}  // namespace

int cmd_compare(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kCompareUsage, stdout);
    return kExitOk;
  }
  std::string paths[2];
  int given = 0;
  bool check = false, by_id = false, json = false;
  double tolerance = -1;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--check") {
      check = true;
    } else if (a == "--by-id") {
      by_id = true;
    } else if (a == "--json") {
      json = true;
    } else if (a == "--tolerance") {
      const auto t = i + 1 < args.size() ? parse_double(args[i + 1]) : std::nullopt;
      if (!t || !(*t >= 0) || !std::isfinite(*t)) {
        std::fprintf(stderr, "tetlod compare: --tolerance '%s' is not a finite length >= 0\n\n%s",
                     i + 1 < args.size() ? args[i + 1].c_str() : "", kCompareUsage);
        return kExitUsage;
      }
      tolerance = *t;
      ++i;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod compare: unknown option '%s'\n\n%s", a.c_str(), kCompareUsage);
      return kExitUsage;
    } else if (given < 2) {
      paths[given++] = a;
    } else {
      std::fprintf(stderr, "tetlod compare: more than two meshes given\n\n%s", kCompareUsage);
      return kExitUsage;
    }
  }
  if (given < 2) {
    std::fprintf(stderr, "tetlod compare: need BEFORE and AFTER\n\n%s", kCompareUsage);
    return kExitUsage;
  }
  TetMesh before, after;
  ReadInfo info_before, info_after;
  if (!load_mesh(paths[0], &before, &info_before) || !load_mesh(paths[1], &after, &info_after))
    return kExitBadInput;
  std::string matched = "by id";
  if (!by_id) {
    const MaterialMatch match =
        match_materials_by_name(info_before.material_names, after, info_after.material_names);
    renumber_materials(match, &after, &info_after.material_names);
    if (!match.why_by_id.empty()) {
      matched += " (" + match.why_by_id + ")";
    } else if (match.by_name == 0) {
      matched += " (no name of AFTER's is one of BEFORE's)";
    } else {
      matched = "by name";
      for (size_t i = 0; i < match.renumbered.size(); ++i)
        matched += (i == 0 ? ": AFTER's " : ", ") + std::to_string(match.renumbered[i].first) +
                   " is " + std::to_string(match.renumbered[i].second);
    }
    // A name only AFTER has (renamed, or a new material): by id, said.
    if (!match.names_only_after.empty()) {
      matched += match.by_name == 0 ? "; " : "; by id, ";
      matched += "names BEFORE does not have: ";
      for (size_t i = 0; i < match.names_only_after.size(); ++i)
        matched += (i == 0 ? "" : ", ") + std::to_string(match.names_only_after[i].material) +
                   " '" + match.names_only_after[i].name + "'";
    }
  }
  // Labels: BEFORE's names, then AFTER's for materials BEFORE does not name.
  std::vector<MaterialName> label_names = info_before.material_names;
  for (const MaterialName& n : info_after.material_names)
    if (!find_material_name(&info_before.material_names, n.material)) label_names.push_back(n);
  sort_by_material(&label_names);
  const std::vector<MaterialName>* names = &label_names;
  const MeshComparison c = compare_meshes(before, after);
  // Below these, a difference is rounding (sums of tet volumes, positions moved and back):
  // printed as 0.
  Vec3 lo, hi;
  mesh_bounds(before, &lo, &hi);
  const double rounding_distance = 1e-12 * length(hi - lo), rounding_fraction = 1e-12;

  // Each material's change (a fraction; lost and new apart), each surface's distance,
  // rounding taken as 0.
  size_t materials_lost = 0, materials_new = 0;
  std::vector<double> change(c.volumes.size(), 0);
  for (size_t i = 0; i < c.volumes.size(); ++i) {
    const MaterialVolumes& v = c.volumes[i];
    materials_new += v.before == 0;
    materials_lost += v.before != 0 && v.after == 0;
    if (v.before != 0 && v.after != 0) {
      const double fraction = (v.after - v.before) / v.before;
      change[i] = std::abs(fraction) <= rounding_fraction ? 0 : fraction;
    }
  }
  // Topology: the materials and surfaces whose pieces or Euler characteristic changed.
  // (c.pieces and c.volumes list the same materials, by id: the i-th of one is the
  // i-th of the other; a linear search per material was quadratic in JSON.)
  const auto piece_of = [&c](size_t i, int32_t m) -> const MaterialPieces* {
    return i < c.pieces.size() && c.pieces[i].material == m ? &c.pieces[i] : nullptr;
  };
  size_t topology_changes = 0;
  // (A material lost or new is counted as such.)
  for (const MaterialPieces& p : c.pieces)
    topology_changes += p.before > 0 && p.after > 0 && p.before != p.after;
  for (const PairEuler& e : c.euler) topology_changes += e.before != e.after;
  std::vector<double> moved;
  double worst = 0;
  std::string worst_pair = "-";
  for (const PairDeviation& d : c.pairs) {
    moved.push_back(d.distance <= rounding_distance ? 0 : d.distance);
    if (moved.back() > worst) worst = moved.back(), worst_pair = pair_text(d.pair, names);
  }

  if (json) {
    const auto number = [](double x) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", x);
      return std::string(text);
    };
    const auto pair_json = [](const MaterialPair& p) {
      return "\"inner\": " + std::to_string(p.first) + ", \"outer\": " +
             (p.second == kOutsideMaterial ? std::string("\"outside\"") : std::to_string(p.second));
    };
    std::printf("{\n  \"before\": {\"file\": \"%s\", \"tets\": %zu},\n",
                json_escape(paths[0]).c_str(), before.tet_count());
    std::printf("  \"after\": {\"file\": \"%s\", \"tets\": %zu},\n", json_escape(paths[1]).c_str(),
                after.tet_count());
    std::printf("  \"materials_matched\": \"%s\",\n  \"materials\": [",
                json_escape(matched).c_str());
    for (size_t i = 0; i < c.volumes.size(); ++i) {
      const MaterialVolumes& v = c.volumes[i];
      const std::string name = material_name_of(names, v.material);
      const MaterialPieces* pieces = piece_of(i, v.material);
      const std::string pieces_json =
          pieces ? ", \"pieces_before\": " + std::to_string(pieces->before) +
                       ", \"pieces_after\": " + std::to_string(pieces->after)
                 : std::string();
      std::printf(
          "%s\n    {\"material\": %d, %s\"volume_before\": %.17g, "
          "\"volume_after\": %.17g, \"change\": %s%s}",
          i ? "," : "", v.material,
          name.empty() ? "" : ("\"name\": \"" + json_escape(name) + "\", ").c_str(), v.before,
          v.after,
          v.before == 0  ? "\"new\""
          : v.after == 0 ? "\"lost\""
                         : number(change[i]).c_str(),
          pieces_json.c_str());
    }
    std::printf("\n  ],\n  \"surfaces\": [");
    for (size_t i = 0; i < c.pairs.size(); ++i)
      std::printf("%s\n    {%s, \"moved\": %.17g, \"euler_before\": %ld, \"euler_after\": %ld}",
                  i ? "," : "", pair_json(c.pairs[i].pair).c_str(), moved[i], c.euler[i].before,
                  c.euler[i].after);
    std::printf("\n  ],\n  \"surfaces_lost\": [");
    for (size_t i = 0; i < c.lost.size(); ++i)
      std::printf("%s{%s}", i ? ", " : "", pair_json(c.lost[i]).c_str());
    std::printf("],\n  \"surfaces_new\": [");
    for (size_t i = 0; i < c.added.size(); ++i)
      std::printf("%s{%s}", i ? ", " : "", pair_json(c.added[i]).c_str());
    std::printf(
        "],\n  \"largest\": %.17g,\n  \"materials_lost\": %zu,\n  \"materials_new\": %zu,\n"
        "  \"topology_changes\": %zu\n}\n",
        worst, materials_lost, materials_new, topology_changes);
  } else {
    std::printf("%s (%zu tets) -> %s (%zu tets)\nmaterials matched %s\n\n", paths[0].c_str(),
                before.tet_count(), paths[1].c_str(), after.tet_count(), matched.c_str());
    std::printf("%-24s %16s %16s %12s\n", "material", "volume before", "volume after", "change");
    for (size_t i = 0; i < c.volumes.size(); ++i) {
      const MaterialVolumes& v = c.volumes[i];
      const std::string name = material_name_of(names, v.material);
      const std::string label = std::to_string(v.material) + (name.empty() ? "" : " " + name);
      char text[32];
      if (v.before == 0)
        std::snprintf(text, sizeof text, "new");
      else if (v.after == 0)
        std::snprintf(text, sizeof text, "lost");
      else if (change[i] == 0)
        std::snprintf(text, sizeof text, "0 %%");
      else
        std::snprintf(text, sizeof text, "%+.3g %%", 100 * change[i]);
      std::printf("%-24s %16.9g %16.9g %12s\n", label.c_str(), v.before, v.after, text);
    }
    std::printf("\n%-40s %12s\n", "surface (material | material)", "moved up to");
    for (size_t i = 0; i < c.pairs.size(); ++i)
      std::printf("%-40s %12.6g\n", pair_text(c.pairs[i].pair, names).c_str(), moved[i]);
    for (const MaterialPair& p : c.lost)
      std::printf("%-40s %12s\n", pair_text(p, names).c_str(), "lost");
    for (const MaterialPair& p : c.added)
      std::printf("%-40s %12s\n", pair_text(p, names).c_str(), "new");
    std::printf("\n");
    for (const MaterialPieces& p : c.pieces)
      if (p.before > 0 && p.after > 0 && p.before != p.after) {
        const std::string name = material_name_of(names, p.material);
        std::printf("topology: material %d%s in %ld %s before, %ld after\n", p.material,
                    name.empty() ? "" : (" " + name).c_str(), p.before,
                    p.before == 1 ? "piece" : "pieces", p.after);
      }
    for (const PairEuler& e : c.euler)
      if (e.before != e.after)
        std::printf("topology: surface %s has Euler characteristic %ld before, %ld after\n",
                    pair_text(e.pair, names).c_str(), e.before, e.after);
    if (topology_changes == 0)
      std::printf(
          "topology: every material in as many pieces, every surface with its Euler "
          "characteristic\n");
    std::printf(
        "largest: %.6g (%s); surfaces lost %zu, new %zu; materials lost %zu, new %zu; "
        "topology changes %zu\n",
        worst, worst_pair.c_str(), c.lost.size(), c.added.size(), materials_lost, materials_new,
        topology_changes);
  }
  if (!check) return kExitOk;
  std::string why;
  if (c.lost.size() + c.added.size() + materials_lost + materials_new > 0)
    why = "a material or surface is lost or new";
  else if (topology_changes > 0)
    why = "a material's number of pieces or a surface's Euler characteristic changed";
  else if (tolerance >= 0 && worst > tolerance)
    why = "a surface moved further than the tolerance";
  if (why.empty()) return kExitOk;
  std::fprintf(stderr, "tetlod compare: %s: %s\n", paths[1].c_str(), why.c_str());
  return kExitBreaks;
}

}  // namespace tetlod::app
