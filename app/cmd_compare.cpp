// tetlod compare BEFORE AFTER [--tolerance T] [--check] [--by-id]
#include <cmath>
#include <cstdio>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "core/mesh_compare.h"
#include "core/vec3.h"

namespace tetlod::app {
namespace {

constexpr const char* kCompareUsage =
    "usage: tetlod compare BEFORE AFTER [--tolerance T] [--check] [--by-id]\n"
    "\n"
    "How AFTER, a mesh made from BEFORE by any tool (tetlod simplify, a remesher, ...),\n"
    "keeps what BEFORE has: each material's volume before and after, and for each\n"
    "surface between two materials (or a material and the outside) how far it moved: a\n"
    "two-sided estimate of the Hausdorff distance between the two meshes' triangles of\n"
    "that pair (from the corners, edge midpoints and centroids of one side's triangles\n"
    "to the nearest triangle of the pair on the other side); and the surfaces or\n"
    "materials only one of them has. Where both files name their materials (Gmsh\n"
    "physical groups, Abaqus sets, ...), a material of AFTER is matched to the one of\n"
    "BEFORE with its name, whatever its id; otherwise (and for materials without a\n"
    "name both files have) by id.\n"
    "  --tolerance T   the distance a surface may move (with --check)\n"
    "  --check         exit with status 3 if a material or surface is lost or new, or\n"
    "                  (with --tolerance) a surface moved further than T\n"
    "  --by-id         match materials by id even where both files name them\n";

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
  bool check = false, by_id = false;
  double tolerance = -1;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--check") {
      check = true;
    } else if (a == "--by-id") {
      by_id = true;
    } else if (a == "--tolerance") {
      const auto t = i + 1 < args.size() ? parse_double(args[i + 1]) : std::nullopt;
      if (!t || !(*t >= 0) || !std::isfinite(*t)) {
        std::fprintf(stderr, "tetlod compare: --tolerance needs a length >= 0\n\n%s",
                     kCompareUsage);
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
    } else {
      matched = "by name";
      for (size_t i = 0; i < match.renumbered.size(); ++i)
        matched += (i == 0 ? ": AFTER's " : ", ") + std::to_string(match.renumbered[i].first) +
                   " is " + std::to_string(match.renumbered[i].second);
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

  std::printf("%s (%zu tets) -> %s (%zu tets)\nmaterials matched %s\n\n", paths[0].c_str(),
              before.tet_count(), paths[1].c_str(), after.tet_count(), matched.c_str());
  std::printf("%-24s %16s %16s %12s\n", "material", "volume before", "volume after", "change");
  size_t materials_lost = 0, materials_new = 0;
  for (const MaterialVolumes& v : c.volumes) {
    const std::string name = material_name_of(names, v.material);
    const std::string label = std::to_string(v.material) + (name.empty() ? "" : " " + name);
    char change[32];
    if (v.before == 0) {
      std::snprintf(change, sizeof change, "new");
      ++materials_new;
    } else if (v.after == 0) {
      std::snprintf(change, sizeof change, "lost");
      ++materials_lost;
    } else {
      const double fraction = (v.after - v.before) / v.before;
      if (std::abs(fraction) <= rounding_fraction)
        std::snprintf(change, sizeof change, "0 %%");
      else
        std::snprintf(change, sizeof change, "%+.3g %%", 100 * fraction);
    }
    std::printf("%-24s %16.9g %16.9g %12s\n", label.c_str(), v.before, v.after, change);
  }
  std::printf("\n%-40s %12s\n", "surface (material | material)", "moved up to");
  double worst = 0;
  std::string worst_pair = "-";
  for (const PairDeviation& d : c.pairs) {
    const double distance = d.distance <= rounding_distance ? 0 : d.distance;
    std::printf("%-40s %12.6g\n", pair_text(d.pair, names).c_str(), distance);
    if (distance > worst) worst = distance, worst_pair = pair_text(d.pair, names);
  }
  for (const MaterialPair& p : c.lost)
    std::printf("%-40s %12s\n", pair_text(p, names).c_str(), "lost");
  for (const MaterialPair& p : c.added)
    std::printf("%-40s %12s\n", pair_text(p, names).c_str(), "new");
  std::printf("\nlargest: %.6g (%s); surfaces lost %zu, new %zu; materials lost %zu, new %zu\n",
              worst, worst_pair.c_str(), c.lost.size(), c.added.size(), materials_lost,
              materials_new);
  if (!check) return kExitOk;
  std::string why;
  if (c.lost.size() + c.added.size() + materials_lost + materials_new > 0)
    why = "a material or surface is lost or new";
  else if (tolerance >= 0 && worst > tolerance)
    why = "a surface moved further than the tolerance";
  if (why.empty()) return kExitOk;
  std::fprintf(stderr, "tetlod compare: %s: %s\n", paths[1].c_str(), why.c_str());
  return kExitBreaks;
}

}  // namespace tetlod::app
