// tetlod simplify IN -o OUT --size S [...]   and   tetlod lod HISTORY (--elements N | --step K) -o
// OUT
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "core/adjacency.h"
#include "core/lod.h"
#include "core/mesh_stats.h"
#include "core/simplify.h"

namespace tetlod::app {
namespace {

constexpr const char* kSimplifyUsage =
    "usage: tetlod simplify IN -o OUT --size S [--stretch D] [--valence V] [--tolerance T]\n"
    "                       [--no-subdivide] [--material-size M=S,...] [--size-field SPEC]\n"
    "                       [--elements N] [--history FILE] [--crease-angle DEG]\n"
    "\n"
    "Subdivides IN (every edge longer than half its target size), then collapses edges in\n"
    "order of the paper's priority index while every threshold holds:\n"
    "  --size S          tau_SZ: no tet's longest edge above S (model units)\n"
    "  --stretch D       tau_ST: no tet's stretch below D, 0 < D < 1 (default 0.15)\n"
    "  --valence V       tau_VL: no node with more than V edge neighbours, V >= 4 (default 25)\n"
    "  --tolerance T     tau_TL: boundaries and interfaces kept within T (a length; the\n"
    "                    quadric error, a sum of squared distances, stays <= T^2)\n"
    "                    (default 0.001 x the bounding-box diagonal)\n"
    "  --material-size M=S,...   a size per material (the smaller one on an interface)\n"
    "  --size-field SPEC         region sizes, ';'-separated: radial:cx,cy,cz,s0,growth\n"
    "                            axis:cx,cy,cz,dx,dy,dz,s0,growth  box:x0,y0,z0,x1,y1,z1,s\n"
    "                    the size of a tet is the smallest of --size and every rule above\n"
    "  --no-subdivide    skip the subdivision step\n"
    "  --elements N      write the level of the history nearest N elements\n"
    "  --history FILE    save the collapse history (see 'tetlod lod')\n"
    "  --crease-angle A  dihedral angle (degrees) above which an edge is a feature (default 40)\n"
    "Prints the Table I rows before and after, the rejection counts and the phase times.\n";

constexpr const char* kLodUsage =
    "usage: tetlod lod HISTORY (--elements N | --step K) -o OUT\n"
    "\n"
    "Writes a level of a saved collapse history (tetlod simplify --history) without\n"
    "simplifying again: the step nearest N elements, or step K (0 = the subdivided input).\n";

MeshStats stats_of(const TetMesh& mesh) {
  return compute_mesh_stats(mesh, build_vertex_tets(mesh));
}

bool parse_option_value(const Args& args, size_t* i, const char* name, std::string* value) {
  if (*i + 1 >= args.size()) {
    std::fprintf(stderr, "tetlod: %s needs a value\n", name);
    return false;
  }
  *value = args[++*i];
  return true;
}

double bounding_diagonal(const TetMesh& mesh) {
  Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Vec3& p : mesh.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return length(hi - lo);
}

}  // namespace

int cmd_simplify(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kSimplifyUsage, stdout);
    return kExitOk;
  }
  std::string in, out, history_path;
  SimplifyParams params;
  bool tolerance_given = false, size_given = false;
  long long elements = -1;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string v;
    auto bad_value = [&](const char* what) {
      std::fprintf(stderr, "tetlod simplify: %s '%s' is not %s\n", a.c_str(), v.c_str(), what);
      return kExitUsage;
    };
    if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &out)) return kExitUsage;
    } else if (a == "--size") {
      if (!parse_option_value(args, &i, "--size", &v)) return kExitUsage;
      const auto d = parse_double(v);
      if (!d || *d <= 0) return bad_value("a size > 0");
      params.sizing.uniform = *d;
      size_given = true;
    } else if (a == "--stretch") {
      if (!parse_option_value(args, &i, "--stretch", &v)) return kExitUsage;
      const auto d = parse_double(v);
      if (!d || *d <= 0 || *d >= 1) return bad_value("a stretch strictly between 0 and 1");
      params.min_stretch = *d;
    } else if (a == "--valence") {
      if (!parse_option_value(args, &i, "--valence", &v)) return kExitUsage;
      const auto n = parse_integer(v);
      if (!n || *n < 4 || *n > 100000) return bad_value("a valence >= 4");
      params.max_valence = static_cast<uint32_t>(*n);
    } else if (a == "--tolerance") {
      if (!parse_option_value(args, &i, "--tolerance", &v)) return kExitUsage;
      const auto d = parse_double(v);
      if (!d || *d < 0) return bad_value("a length >= 0");
      params.tolerance = *d;
      tolerance_given = true;
    } else if (a == "--crease-angle") {
      if (!parse_option_value(args, &i, "--crease-angle", &v)) return kExitUsage;
      const auto d = parse_double(v);
      if (!d || *d <= 0 || *d >= 180) return bad_value("an angle between 0 and 180 degrees");
      params.crease_angle_degrees = *d;
    } else if (a == "--no-subdivide") {
      params.subdivide = false;
    } else if (a == "--material-size") {
      if (!parse_option_value(args, &i, "--material-size", &v)) return kExitUsage;
      const Status s = parse_material_sizes(v, &params.sizing);
      if (!s) {
        std::fprintf(stderr, "tetlod simplify: %s\n", s.message().c_str());
        return kExitUsage;
      }
      size_given = true;
    } else if (a == "--size-field") {
      if (!parse_option_value(args, &i, "--size-field", &v)) return kExitUsage;
      const Status s = parse_size_field(v, &params.sizing);
      if (!s) {
        std::fprintf(stderr, "tetlod simplify: %s\n", s.message().c_str());
        return kExitUsage;
      }
      size_given = true;
    } else if (a == "--elements") {
      if (!parse_option_value(args, &i, "--elements", &v)) return kExitUsage;
      const auto n = parse_integer(v);
      if (!n || *n < 1) return bad_value("a number of elements >= 1");
      elements = *n;
    } else if (a == "--history") {
      if (!parse_option_value(args, &i, "--history", &history_path)) return kExitUsage;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod simplify: unknown option '%s'\n\n%s", a.c_str(), kSimplifyUsage);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else {
      std::fprintf(stderr, "tetlod simplify: more than one input given\n\n%s", kSimplifyUsage);
      return kExitUsage;
    }
  }
  if (in.empty() || out.empty()) {
    std::fprintf(stderr, "tetlod simplify: need IN and -o OUT\n\n%s", kSimplifyUsage);
    return kExitUsage;
  }
  if (!size_given) {
    std::fprintf(stderr,
                 "tetlod simplify: give a target size (--size, --material-size or "
                 "--size-field)\n");
    return kExitUsage;
  }

  TetMesh input;
  ReadInfo info;
  if (!load_mesh(in, &input, &info)) return kExitBadInput;
  if (!tolerance_given) params.tolerance = 1e-3 * bounding_diagonal(input);

  std::printf("input %s\n", in.c_str());
  print_property_table(stats_of(input));
  std::printf("\nthresholds: size %g%s, stretch %g, valence %u, tolerance %g%s\n",
              params.sizing.uniform,
              params.sizing.material_sizes.empty() && params.sizing.radial.empty() &&
                      params.sizing.boxes.empty()
                  ? ""
                  : " (with local sizing)",
              params.min_stretch, params.max_valence, params.tolerance,
              params.subdivide ? "" : ", no subdivision");

  SimplifyResult result;
  const Status status = simplify(input, params, &result);
  if (!status) {
    std::fprintf(stderr, "tetlod simplify: %s\n", status.message().c_str());
    return kExitBadInput;
  }

  TetMesh output = std::move(result.output);
  size_t step = result.history.step_count();
  if (elements > 0) {
    Lod lod(result.base, &result.history);
    step = lod.step_for_elements(static_cast<size_t>(elements));
    lod.seek(step);
    output = lod.extract();
  }
  std::printf("\noutput %s (step %zu of %zu)\n", out.c_str(), step, result.history.step_count());
  print_property_table(stats_of(output));
  const RejectionCounts& r = result.rejections;
  std::printf(
      "\nsubdivision: %zu splits (%zu long edges left unsplit to keep the thresholds), %zu tets\n"
      "collapses: %zu\nrejected evaluations: tolerance %llu, stretch %llu, size %llu, valence "
      "%llu, topology %llu\n",
      result.splits, result.splits_skipped, result.base.tet_count(), result.history.step_count(),
      static_cast<unsigned long long>(r.tolerance), static_cast<unsigned long long>(r.stretch),
      static_cast<unsigned long long>(r.size), static_cast<unsigned long long>(r.valence),
      static_cast<unsigned long long>(r.topology));
  const ThresholdViolations& v = result.violations;
  std::printf(
      "final mesh, breaking a threshold: %zu tets below the stretch, %zu above the size, "
      "%zu nodes above the valence (%zu of them made by TetLOD)\n",
      v.below_stretch, v.above_size, v.above_valence, v.created);
  std::printf("time: subdivide %.3f s, classify %.3f s, simplify %.3f s\n",
              result.seconds_subdivide, result.seconds_classify, result.seconds_simplify);

  Status s = write_mesh(out, output);
  if (!s) {
    std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  if (!history_path.empty()) {
    s = write_history(history_path, result.base, result.history);
    if (!s) {
      std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
      return kExitBadInput;
    }
    std::printf("history: %s\n", history_path.c_str());
  }
  return kExitOk;
}

int cmd_lod(const Args& args) {
  if (wants_help(args)) {
    std::fputs(kLodUsage, stdout);
    return kExitOk;
  }
  std::string history_path, out;
  long long elements = -1, step = -1;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string v;
    if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &out)) return kExitUsage;
    } else if (a == "--elements" || a == "--step") {
      if (!parse_option_value(args, &i, a.c_str(), &v)) return kExitUsage;
      const auto n = parse_integer(v);
      if (!n || *n < 0) {
        std::fprintf(stderr, "tetlod lod: %s '%s' is not a whole number >= 0\n", a.c_str(),
                     v.c_str());
        return kExitUsage;
      }
      (a == "--step" ? step : elements) = *n;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod lod: unknown option '%s'\n\n%s", a.c_str(), kLodUsage);
      return kExitUsage;
    } else if (history_path.empty()) {
      history_path = a;
    } else {
      std::fprintf(stderr, "tetlod lod: more than one history given\n\n%s", kLodUsage);
      return kExitUsage;
    }
  }
  if (history_path.empty() || out.empty() || (elements < 0) == (step < 0)) {
    std::fprintf(stderr, "tetlod lod: need HISTORY, -o OUT and one of --elements, --step\n\n%s",
                 kLodUsage);
    return kExitUsage;
  }
  TetMesh base;
  CollapseHistory history;
  Status s = read_history(history_path, &base, &history);
  if (!s) {
    std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  Lod lod(std::move(base), &history);
  const size_t target = step >= 0 ? std::min<size_t>(static_cast<size_t>(step), lod.step_count())
                                  : lod.step_for_elements(static_cast<size_t>(elements));
  const auto start = std::chrono::steady_clock::now();
  lod.seek(target);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const TetMesh level = lod.extract();
  s = write_mesh(out, level);
  if (!s) {
    std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  std::printf("%s: step %zu of %zu, %zu elements, %zu nodes (moved there in %.4f s)\n", out.c_str(),
              target, lod.step_count(), level.tet_count(), level.vertex_count(), seconds);
  return kExitOk;
}

}  // namespace tetlod::app
