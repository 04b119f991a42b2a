#include "app/simplify_options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "app/cli_util.h"
#include "core/io/sol.h"
#include "core/size_map.h"

namespace tetlod::app {

const char* const kSimplifyFlagsHelp =
    "  --size S          tau_SZ: no tet's longest edge above S (model units); may be\n"
    "                    left out with a local sizing below: a tet no rule reaches\n"
    "                    then has no size limit\n"
    "  --stretch D       tau_ST: no tet's stretch below D, 0.00012 <= D < 1 (default 0.15;\n"
    "                    stats, which only counts, takes any 0 < D < 1)\n"
    "  --valence V       tau_VL: no node with more than V edge neighbours, 4 <= V <= 255\n"
    "                    (default 25)\n"
    "  --tolerance T     tau_TL: boundaries and interfaces kept within T (a length; the\n"
    "                    quadric error, a sum of squared distances, stays <= T^2)\n"
    "                    (default 0.001 x the bounding-box diagonal)\n"
    "  --material-size M=S,...   a size per material: a tet's is its material's, so an\n"
    "                            edge on an interface takes the smaller; M is its id or\n"
    "                            its name in the input (copper=2; a name may hold\n"
    "                            commas: 'Cu, 20C=2')\n"
    "  --size-field SPEC         region sizes, ';'-separated: radial:cx,cy,cz,s0,growth\n"
    "                            axis:cx,cy,cz,dx,dy,dz,s0,growth  box:x0,y0,z0,x1,y1,z1,s\n"
    "                    (radial, axis: size s0 + growth x the distance from the point c,\n"
    "                    or from the line through c along d; box: s inside it)\n"
    "                    the size of a tet is the smallest of --size and every rule above,\n"
    "                    taken at its centroid (a box holds the tets whose centroid it holds,\n"
    "                    its faces included); an edge's limit, for subdivision, is the\n"
    "                    smallest of its tets'\n"
    "  --size-map FILE   sizes at the input's vertices (a Medit .sol or .solb file, as\n"
    "                    MMG3D takes them), linear in each input tet: with the sizes\n"
    "                    above, no tet above the map's value at its centroid\n"
    "  --size-map-mesh MESH  the mesh whose vertices those sizes are at, if not the\n"
    "                    input (a background mesh over the same domain: the level an\n"
    "                    analysis was solved on, when the input is the dense original)\n"
    "  --no-subdivide    skip the subdivision step\n"
    "  --within-valence  one run only: where tets stay above the size, no other run whose\n"
    "                    subdivision (red levels, then bisection) may take nodes past the\n"
    "                    valence for edge removals and collapses to bring back (faster; it\n"
    "                    may leave more tets above the size)\n"
    "  --past-valence-factor F   that other run stops, and the first stands, once its\n"
    "                    subdivision passes F times the first run's tets (default 8;\n"
    "                    a bound on its time and memory)\n"
    "  --one-thread      make that other run after the first (by default it starts on a\n"
    "                    second thread, where there are two processors, as soon as the\n"
    "                    first run's subdivision leaves tets above the size: the same\n"
    "                    result, sooner)\n"
    "  --crease-angle DEG  dihedral angle (degrees) above which an edge is a feature\n"
    "                    (default 40)\n";

const char* const kWriteFlagsHelp =
    "  --msh-version V   Gmsh version to write: 4.1 (default) or 2.2\n"
    "  --msh-binary      write .msh in binary, as gmsh -bin does (default: ASCII)\n"
    "  --vtk-binary      write .vtk and .vtu in binary, as ParaView does (default: ASCII)\n"
    "  --surfaces        also write the boundary and interface triangles, for boundary\n"
    "                    conditions: the input's own surface groups (Gmsh physical\n"
    "                    surfaces, Medit triangle references, TetGen .face markers,\n"
    "                    Abaqus element-face *SURFACEs, .vtk/.vtu triangle cells and\n"
    "                    Nastran CTRIA3s by their number) under their names and tags\n"
    "                    with their triangles inside a material (simplify then keeps\n"
    "                    those as they are, not coarsened, as with --history),\n"
    "                    the rest a group per material pair\n"
    "                    (boundary_<m>, interface_<a>_<b>, numbered above the materials):\n"
    "                    .msh physical surfaces, .mesh triangle references, a TetGen\n"
    "                    .face file, .inp node sets and element-face surfaces, .vtk/.vtu\n"
    "                    triangle cells with the tag as material, Nastran CTRIA3s with\n"
    "                    the tag as PID\n";

OptionResult parse_write_option(const Args& args, size_t* i, const char* command,
                                WriteOptions* options) {
  const std::string& a = args[*i];
  if (a == "--surfaces") {
    options->surface_groups = true;
    return OptionResult::kParsed;
  }
  if (a == "--msh-binary") {
    options->gmsh_binary = true;
    return OptionResult::kParsed;
  }
  if (a == "--vtk-binary") {
    options->vtk_binary = true;
    return OptionResult::kParsed;
  }
  if (a != "--msh-version") return OptionResult::kNotMine;
  std::string v;
  if (!parse_option_value(args, i, "--msh-version", &v)) return OptionResult::kError;
  if (v == "2.2" || v == "22") {
    options->gmsh_version = 22;
  } else if (v == "4.1" || v == "41") {
    options->gmsh_version = 41;
  } else {
    std::fprintf(stderr, "tetlod %s: --msh-version must be 2.2 or 4.1, not '%s'\n", command,
                 v.c_str());
    return OptionResult::kError;
  }
  return OptionResult::kParsed;
}

bool parse_option_value(const Args& args, size_t* i, const char* name, std::string* value) {
  if (*i + 1 >= args.size()) {
    std::fprintf(stderr, "tetlod: %s needs a value\n", name);
    return false;
  }
  // Values may start with '-' ("--cut -x=0.5", "-1"); "--..." and "-o" are options.
  if (args[*i + 1].rfind("--", 0) == 0 || args[*i + 1] == "-o") {
    std::fprintf(stderr, "tetlod: %s needs a value, not the option '%s'\n", name,
                 args[*i + 1].c_str());
    return false;
  }
  *value = args[++*i];
  return true;
}

OptionResult parse_simplify_option(const Args& args, size_t* i, const char* command,
                                   SimplifyOptions* options) {
  const std::string& a = args[*i];
  SimplifyParams& params = options->params;
  std::string v;
  auto bad_value = [&](const std::string& what) {
    std::fprintf(stderr, "tetlod %s: %s '%s' is not %s\n", command, a.c_str(), v.c_str(),
                 what.c_str());
    return OptionResult::kError;
  };
  auto value = [&]() { return parse_option_value(args, i, a.c_str(), &v); };
  if (a == "--size") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_double(v);
    if (!d || *d <= 0) return bad_value("a size, a finite number > 0");
    params.sizing.uniform = *d;
    options->size_given = true;
  } else if (a == "--stretch") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_double(v);
    // (stats only counts the tets below it: any stretch will do.)
    const bool counting_only = std::strcmp(command, "stats") == 0;
    if (!d || *d <= 0 || *d >= 1 || (!counting_only && *d < kMinStretch))
      return bad_value(counting_only
                           ? "a stretch strictly between 0 and 1"
                           : "a stretch from 0.00012 to below 1 (below 0.00012, tets too flat "
                             "to read back, lost in rounding, would pass)");
    params.min_stretch = *d;
  } else if (a == "--valence") {
    if (!value()) return OptionResult::kError;
    const auto n = parse_integer(v);
    if (!n || *n < 4 || *n > kMaxValence)
      return bad_value("a valence, a whole number of neighbours in [4, " +
                       std::to_string(kMaxValence) + "]");
    params.max_valence = static_cast<uint32_t>(*n);
  } else if (a == "--tolerance") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_double(v);
    if (!d || *d < 0) return bad_value("a length >= 0");
    params.tolerance = *d;
    options->tolerance_given = true;
  } else if (a == "--crease-angle") {
    if (!value()) return OptionResult::kError;
    const auto d = parse_double(v);
    if (!d || *d <= 0 || *d >= 180) return bad_value("an angle strictly between 0 and 180 degrees");
    params.crease_angle_degrees = *d;
  } else if (a == "--no-subdivide") {
    params.subdivide = false;
  } else if (a == "--within-valence") {
    params.subdivide_past_valence = false;
  } else if (a == "--one-thread") {
    params.past_valence_alongside = false;
  } else if (a == "--past-valence-factor") {
    if (!value()) return OptionResult::kError;
    const auto n = parse_integer(v);
    if (!n || *n < 1 || *n > 1000) return bad_value("a whole number in [1, 1000]");
    params.past_valence_tets_factor = static_cast<uint32_t>(*n);
  } else if (a == "--material-size" || a == "--size-field") {
    if (!value()) return OptionResult::kError;
    if (a == "--material-size") {
      // Items that name their material wait for the names (finish_simplify_options()).
      std::string ids;
      const size_t named_before = options->named_material_sizes.size();
      for (const std::string& item : split_value_items(v, '=')) {
        std::string material;
        double size = 0;
        const bool has_size = split_material_value(item, '=', &material, &size);
        if (is_material_name(material)) {
          if (!has_size || !(size > 0)) {
            std::fprintf(stderr,
                         "tetlod %s: --material-size %s: size '%s' must be a finite number > 0\n",
                         command, item.c_str(), item.substr(material.size() + 1).c_str());
            return OptionResult::kError;
          }
          options->named_material_sizes.push_back({material, size});
        } else {
          ids += (ids.empty() ? "" : ",") + item;
        }
      }
      // Only named items: done (an empty specification is parse_material_sizes()'s error).
      if (ids.empty() && options->named_material_sizes.size() > named_before) {
        options->size_given = true;
        return OptionResult::kParsed;
      }
      v = ids;
    }
    const Status s = a == "--material-size" ? parse_material_sizes(v, &params.sizing)
                                            : parse_size_field(v, &params.sizing);
    if (!s) {
      std::fprintf(stderr, "tetlod %s: %s\n", command, s.message().c_str());
      return OptionResult::kError;
    }
    options->size_given = true;
  } else if (a == "--size-map" || a == "--size-map-mesh") {
    std::string& path = a == "--size-map" ? options->size_map_path : options->size_map_mesh_path;
    if (!value()) return OptionResult::kError;
    if (a == "--size-map" && !has_extension(v, ".sol") && !has_extension(v, ".solb"))
      return bad_value(
          "a size map: a Medit .sol or .solb file (the mesh its sizes are at goes "
          "in --size-map-mesh)");
    path = v;  // read by finish_simplify_options(), with the input
    if (a == "--size-map") options->size_given = true;
  } else if (a == "--improve") {
    options->improve = true;
  } else if (a == "--elements") {
    if (!value()) return OptionResult::kError;
    const auto n = parse_integer(v);
    if (!n || *n < 1) return bad_value("a number of elements >= 1");
    options->elements = *n;
  } else {
    return OptionResult::kNotMine;
  }
  return OptionResult::kParsed;
}

Status read_size_map(const std::string& path, const TetMesh& mesh, const ValidationReport* read,
                     std::shared_ptr<const SizeMap>* map, const std::string& mesh_name) {
  std::vector<double> sizes;
  std::string count_at;
  if (Status s = read_sol_sizes(path, &sizes, &count_at); !s)
    return Status::error("--size-map: " + s.message());
  // One size a vertex of the file, in its order; the reader drops vertices no tet
  // uses, and their sizes with them.
  const size_t in_file = mesh.vertex_count() + (read ? read->removed_unused_vertices : 0);
  if (sizes.size() != in_file) {
    return Status::error("--size-map " + count_at + ": " + std::to_string(sizes.size()) +
                         " sizes, but " + mesh_name + " has " + std::to_string(in_file) +
                         " vertices (a size map gives one size to each of its vertices, in "
                         "their order)");
  }
  if (read && !read->kept_vertices.empty()) {
    std::vector<double> kept(read->kept_vertices.size());
    for (size_t v = 0; v < kept.size(); ++v) kept[v] = sizes[read->kept_vertices[v]];
    sizes = std::move(kept);
  }
  if (Status s = SizeMap::build(mesh, std::move(sizes), map); !s)
    return Status::error("--size-map " + path + ": " + s.message());
  return Status();
}

std::string outside_background_note(const TetMesh& input, const TetMesh& background,
                                    const std::string& background_name) {
  Vec3 lo, hi, in_lo, in_hi;
  mesh_bounds(background, &lo, &hi);
  mesh_bounds(input, &in_lo, &in_hi);
  // A margin of 1e-6 of the larger box's diagonal: the same domain meshed twice.
  const double margin = 1e-6 * std::max(length(hi - lo), length(in_hi - in_lo));
  size_t outside = 0;
  for (const Vec3& p : input.positions)
    outside += p.x < lo.x - margin || p.y < lo.y - margin || p.z < lo.z - margin ||
               p.x > hi.x + margin || p.y > hi.y + margin || p.z > hi.z + margin;
  if (outside == 0) return "";
  char box[160];
  std::snprintf(box, sizeof box, "(%g, %g, %g) to (%g, %g, %g)", lo.x, lo.y, lo.z, hi.x, hi.y,
                hi.z);
  return std::to_string(outside) + " of the input's " + std::to_string(input.vertex_count()) +
         " vertices lie outside " + background_name + "'s box, " + box +
         ": the sizes there are those of the nearest of its tets (not the same domain, or "
         "not the same units?)";
}

namespace {

// A region rule that sets no tet's size does nothing, which is likely a mistake (a box
// in metres for a model in millimetres): a note on stderr says so. A box that holds no
// tet's centroid, or whose size is no smaller than the uniform size; a radial rule
// whose size is no smaller than the uniform size anywhere on the mesh (at least as far
// as a bound on its distance tells).
void unused_rule_notes(const TetMesh& input, const Vec3& lo, const Vec3& hi,
                       const SizingField& sizing, const char* command) {
  const auto point = [](const Vec3& p) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", p.x, p.y, p.z);
    return std::string(text);
  };
  const std::string extent = "the mesh spans " + point(lo) + " to " + point(hi);
  for (const SizingField::Box& b : sizing.boxes) {
    bool reached = false;
    for (size_t t = 0; t < input.tets.size() && !reached; ++t) {
      const Tet& v = input.tets[t];
      const Vec3 c = (input.positions[v[0]] + input.positions[v[1]] + input.positions[v[2]] +
                      input.positions[v[3]]) *
                     0.25;
      reached = c.x >= b.low.x && c.x <= b.high.x && c.y >= b.low.y && c.y <= b.high.y &&
                c.z >= b.low.z && c.z <= b.high.z;
    }
    if (!reached)
      std::fprintf(stderr,
                   "tetlod %s: note: --size-field box %s to %s holds no tet's centroid (%s): "
                   "it sets no size (a box in other units?)\n",
                   command, point(b.low).c_str(), point(b.high).c_str(), extent.c_str());
    else if (b.size >= sizing.uniform)
      std::fprintf(stderr,
                   "tetlod %s: note: --size-field box %s to %s gives size %g, not below --size "
                   "%g: it sets no size\n",
                   command, point(b.low).c_str(), point(b.high).c_str(), b.size, sizing.uniform);
  }
  if (!std::isfinite(sizing.uniform)) return;
  // A radial rule's least size on the mesh, at least: its size at the distance from
  // its point to the mesh's box; for an axis, from its line to the box's bounding
  // sphere (a bound, so an axis rule that reaches the mesh is never named).
  const Vec3 middle = 0.5 * (lo + hi);
  const double radius = 0.5 * length(hi - lo);
  for (const SizingField::Radial& r : sizing.radial) {
    double distance = 0;
    if (r.axis == Vec3{0, 0, 0}) {
      const Vec3 nearest{std::clamp(r.center.x, lo.x, hi.x), std::clamp(r.center.y, lo.y, hi.y),
                         std::clamp(r.center.z, lo.z, hi.z)};
      distance = length(nearest - r.center);
    } else {
      const Vec3 d = middle - r.center;
      distance = std::max(0.0, length(d - r.axis * dot(d, r.axis)) - radius);
    }
    const double least = r.size0 + r.growth * distance;
    if (least >= sizing.uniform)
      std::fprintf(stderr,
                   "tetlod %s: note: --size-field %s rule %s %s gives no size below --size %g "
                   "on the mesh (at least %g there; %s): it sets no size\n",
                   command, r.axis == Vec3{0, 0, 0} ? "radial" : "axis",
                   r.axis == Vec3{0, 0, 0} ? "around" : "along the line through",
                   point(r.center).c_str(), sizing.uniform, least, extent.c_str());
  }
}

}  // namespace

int finish_simplify_options(const TetMesh& input, const std::vector<MaterialName>& names,
                            const char* command, SimplifyOptions* options,
                            const ValidationReport* read) {
  if (!options->size_map_mesh_path.empty() && options->size_map_path.empty()) {
    std::fprintf(stderr, "tetlod %s: --size-map-mesh %s: give the sizes too (--size-map)\n",
                 command, options->size_map_mesh_path.c_str());
    return kExitUsage;
  }
  if (!options->size_map_path.empty()) {
    // The sizes are at the input's vertices, or at those of another mesh over the same
    // domain (where the input reaches past it, the nearest of its tets gives them).
    TetMesh other;
    ReadInfo other_info;
    const std::string& other_path = options->size_map_mesh_path;
    if (!other_path.empty()) {
      if (Status s = read_mesh(other_path, &other, &other_info); !s) {
        std::fprintf(stderr, "tetlod %s: --size-map-mesh: %s\n", command, s.message().c_str());
        return kExitBadInput;
      }
    }
    std::shared_ptr<const SizeMap> map;
    const Status s = other_path.empty()
                         ? read_size_map(options->size_map_path, input, read, &map)
                         : read_size_map(options->size_map_path, other, &other_info.validation,
                                         &map, "--size-map-mesh " + other_path);
    if (!s) {  // the file, or the mesh it goes with, is at fault
      std::fprintf(stderr, "tetlod %s: %s\n", command, s.message().c_str());
      return kExitBadInput;
    }
    if (!other_path.empty()) {
      const std::string note =
          outside_background_note(input, other, "--size-map-mesh " + other_path);
      if (!note.empty()) std::fprintf(stderr, "tetlod %s: note: %s\n", command, note.c_str());
    }
    options->params.sizing.map = std::move(map);
    options->size_map_path.clear();  // read once
    options->size_map_mesh_path.clear();
  }
  std::vector<std::pair<int32_t, double>>& sizes = options->params.sizing.material_sizes;
  for (const auto& [name, size] : options->named_material_sizes) {
    int32_t id = 0;
    if (!material_by_name(name, names, command, "--material-size " + name, &id)) return kExitUsage;
    for (const auto& given : sizes) {
      if (given.first == id) {
        std::fprintf(stderr, "tetlod %s: --material-size: material %d (%s) is given twice\n",
                     command, id, name.c_str());
        return kExitUsage;
      }
    }
    sizes.push_back({id, size});
  }
  options->named_material_sizes.clear();
  std::sort(sizes.begin(), sizes.end());
  if (!sizes.empty()) {
    const std::set<int32_t> present(input.materials.begin(), input.materials.end());
    for (const auto& [material, size] : sizes) {
      if (present.count(material)) continue;
      std::string list;
      for (int32_t m : present) list += (list.empty() ? "" : ", ") + std::to_string(m);
      std::fprintf(stderr,
                   "tetlod %s: --material-size %d=%g: the mesh has no material %d (its "
                   "materials: %s)\n",
                   command, material, size, material, list.c_str());
      return kExitUsage;
    }
  }
  if (input.positions.empty()) return kExitOk;
  Vec3 lo, hi;
  mesh_bounds(input, &lo, &hi);
  unused_rule_notes(input, lo, hi, options->params.sizing, command);
  if (!options->tolerance_given) {
    options->params.tolerance = 1e-3 * length(hi - lo);
    return kExitOk;
  }
  // A tolerance finer than the coordinates' rounding where the mesh is (far from the
  // origin next to its size) cannot hold: a midpoint or a collapsed node's position
  // is rounded by about that much.
  const double far = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x),
                               std::abs(hi.y), std::abs(hi.z)});
  const double rounding = 4 * std::numeric_limits<double>::epsilon() * far;
  if (rounding > options->params.tolerance && rounding > 1e-12 * length(hi - lo))
    std::fprintf(stderr,
                 "tetlod %s: note: --tolerance %g is finer than the rounding of the mesh's "
                 "coordinates (about %.2g, %g from the origin): surfaces may move that much "
                 "(translate the mesh nearer the origin to keep it)\n",
                 command, options->params.tolerance, rounding, far);
  return kExitOk;
}

std::string describe_rejections(const RejectionCounts& r) {
  return "tolerance " + std::to_string(r.tolerance) + ", stretch " + std::to_string(r.stretch) +
         ", size " + std::to_string(r.size) + ", valence " + std::to_string(r.valence) +
         ", topology " + std::to_string(r.topology) + ", overlap " + std::to_string(r.overlap);
}

std::string describe_violations(const ThresholdViolations& v) {
  ThresholdCounts b;
  b.below_stretch = v.below_stretch;
  b.above_size = v.above_size;
  b.above_valence = v.above_valence;
  return describe_breaks(b) + " (of these tets and nodes, " + std::to_string(v.created) +
         " new: the others are input tets or nodes, or pieces of input tets, that already broke "
         "it)";
}

std::string describe_breaks(const ThresholdCounts& b) {
  return std::to_string(b.below_stretch) + (b.below_stretch == 1 ? " tet" : " tets") +
         " below the stretch, " + std::to_string(b.above_size) + " above the size, " +
         std::to_string(b.above_valence) + (b.above_valence == 1 ? " node" : " nodes") +
         " above the valence";
}

std::string describe_size(const SizingField& sizing) {
  // The local rules, in brief: a history's reader has no other way to learn them.
  std::vector<std::string> parts;
  char text[96];
  if (!sizing.material_sizes.empty()) {
    constexpr size_t kListed = 6;
    std::string listed = "material sizes";
    for (size_t k = 0; k < sizing.material_sizes.size() && k < kListed; ++k) {
      std::snprintf(text, sizeof text, "%s %d=%g", k ? "," : "", sizing.material_sizes[k].first,
                    sizing.material_sizes[k].second);
      listed += text;
    }
    if (sizing.material_sizes.size() > kListed)
      listed += " and " + std::to_string(sizing.material_sizes.size() - kListed) + " more";
    parts.push_back(listed);
  }
  if (const size_t rules = sizing.radial.size() + sizing.boxes.size(); rules > 0)
    parts.push_back(std::to_string(rules) + (rules == 1 ? " region rule" : " region rules"));
  if (sizing.map) {
    std::snprintf(text, sizeof text, "a size map, %g to %g", sizing.map->smallest(),
                  sizing.map->largest());
    parts.push_back(text);
  }
  std::string local;
  for (const std::string& part : parts) local += (local.empty() ? " (" : "; ") + part;
  if (!local.empty()) local += ")";
  if (!std::isfinite(sizing.uniform))
    return (sizing.has_local_rules() ? "from the local sizing" : "no limit") + local;
  std::snprintf(text, sizeof text, "%g", sizing.uniform);
  return text + std::string(sizing.has_local_rules() ? ", less where the local sizing asks" : "") +
         local;
}

std::string describe_thresholds(const SimplifyParams& params, bool with_tolerance) {
  char text[256];
  // The stretch as %g shows it, unless that is another number (0.9999999 read "1", a
  // stretch --stretch refuses): then in full.
  std::snprintf(text, sizeof text, "%g", params.min_stretch);
  if (std::strtod(text, nullptr) != params.min_stretch) {
    const auto end = std::to_chars(text, text + sizeof text - 1, params.min_stretch).ptr;
    *end = '\0';
  }
  const std::string stretch = text;
  std::snprintf(text, sizeof text, "stretch %s, valence %u", stretch.c_str(), params.max_valence);
  std::string result = "size " + describe_size(params.sizing) + ", " + text;
  if (with_tolerance) {
    std::snprintf(text, sizeof text, ", tolerance %g", params.tolerance);
    result += text;
  }
  if (!params.subdivide) result += ", no subdivision";
  if (params.crease_angle_degrees != SimplifyParams{}.crease_angle_degrees) {
    std::snprintf(text, sizeof text, ", crease angle %g", params.crease_angle_degrees);
    result += text;
  }
  return result;
}

}  // namespace tetlod::app
