// tetlod simplify IN -o OUT --size S [...]   and   tetlod lod HISTORY (--elements N | --step K) -o
// OUT
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/simplify_options.h"
#include "app/terminal_progress.h"
#include "core/adjacency.h"
#include "core/improve.h"
#include "core/lod.h"
#include "core/mesh_stats.h"
#include "core/simplify.h"

namespace tetlod::app {
namespace {

constexpr const char* kSimplifyUsageHead =
    "usage: tetlod simplify IN -o OUT SIZING [--stretch D] [--valence V] [--tolerance T]\n"
    "                       [--no-subdivide] [--within-valence] [--past-valence-factor F]\n"
    "                       [--one-thread]\n"
    "       SIZING: one or more of --size S, --material-size M=S,..., --size-field SPEC,\n"
    "               --size-map FILE.sol [--size-map-mesh MESH]\n"
    "                       [--elements N] [--history FILE]\n"
    "                       [--crease-angle DEG] [--improve] [--check]\n"
    "                       [--msh-version V] [--msh-binary] [--vtk-binary] [--surfaces]\n"
    "\n"
    "Subdivides IN (every edge longer than half its target size), then collapses edges in\n"
    "order of the paper's priority index while every threshold holds:\n";
constexpr const char* kSimplifyUsageTail =
    "  --elements N      write the level of the history nearest N elements\n"
    "  --history FILE    save the collapse history (see 'tetlod lod')\n"
    "  --improve         then improve the shapes of the level written, within the same\n"
    "                    thresholds: edge removals and flips inside one material, and\n"
    "                    vertex moves; boundaries and interfaces stay where they are\n"
    "                    (beyond the paper; the history is not changed)\n"
    "  --check           exit with status 3 if the mesh written breaks a threshold (input\n"
    "                    tets it could not remove: the line 'breaking a threshold' says\n"
    "                    how many); the files are written all the same\n";

void print_simplify_usage(std::FILE* stream) {
  std::fputs(kSimplifyUsageHead, stream);
  std::fputs(kSimplifyFlagsHelp, stream);
  std::fputs(kSimplifyUsageTail, stream);
  std::fputs(kWriteFlagsHelp, stream);
  std::fputs(
      "Prints the Table I rows before and after, the rejection counts and the phase times.\n",
      stream);
}

constexpr const char* kLodUsage =
    "usage: tetlod lod HISTORY (--elements N | --step K) -o OUT [--msh-version V] [--msh-binary]\n"
    "                  [--vtk-binary] [--surfaces] [--check]\n"
    "                  [--improve [--size S [--stretch D] [--valence V] [--material-size ...]\n"
    "                   [--size-field ...] [--crease-angle DEG]]]\n"
    "\n"
    "Writes a level of a saved collapse history (tetlod simplify --history) without\n"
    "simplifying again: the step nearest N elements, or step K (0 = the subdivided input;\n"
    "a K past the last step, or an N past the input's count, is taken as the nearest end,\n"
    "with a message).\n"
    "  --improve         improve the level's shapes first, as 'tetlod simplify --improve',\n"
    "                    within the thresholds saved in the history; a threshold given\n"
    "                    here replaces its saved value (--size the uniform size,\n"
    "                    --material-size the material sizes, --size-field the region\n"
    "                    rules; a size map saved with the history is kept). Histories\n"
    "                    saved before 2026-11-24 have none: give the ones it was made\n"
    "                    with. The thresholds are written as 'tetlod simplify' takes\n"
    "                    them (--stretch 0.00012 <= D < 1, 4 <= --valence V <= 255)\n"
    "  --check           exit with status 3 if the level written breaks a threshold saved\n"
    "                    in the history (or, with --improve, those it improves within);\n"
    "                    the file is written all the same\n";

void print_lod_usage(std::FILE* stream) {
  std::fputs(kLodUsage, stream);
  std::fputs(kWriteFlagsHelp, stream);
}

// Runs improve_mesh() on `mesh`, timed, keeping the faces inside a material of the
// input's surface groups.
ImproveResult improve_timed(TetMesh* mesh, const SimplifyParams& params,
                            const SurfacePatches& patches, double* seconds) {
  const auto start = std::chrono::steady_clock::now();
  const ImproveResult r = improve_mesh(mesh, params, 4, nullptr, &patches);
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

void print_improve(const ImproveResult& r, double seconds) {
  const ThresholdCounts& b0 = r.breaks_before;
  const ThresholdCounts& b1 = r.breaks_after;
  std::printf(
      "improve (the level written): %d round%s, %zu edge removals, %zu 2-3 flips, %zu vertex "
      "moves; stretch mean %.4f -> %.4f, min %.4f -> %.4f; breaking a threshold: %zu -> %zu "
      "tets below the stretch, %zu -> %zu above the size, %zu -> %zu nodes above the "
      "valence; %.3f s\n",
      r.rounds, r.rounds == 1 ? "" : "s", r.edge_removals, r.flips_23, r.moves,
      r.mean_stretch_before, r.mean_stretch_after, r.min_stretch_before, r.min_stretch_after,
      b0.below_stretch, b1.below_stretch, b0.above_size, b1.above_size, b0.above_valence,
      b1.above_valence, seconds);
}

// --check: status 3, said on stderr, where the mesh written (`out`) breaks a threshold.
int check_written(const char* command, const std::string& out, const ThresholdCounts& breaks) {
  if (breaks.total() == 0) return kExitOk;
  std::fprintf(stderr, "tetlod %s: --check: %s breaks a threshold: %s\n", command, out.c_str(),
               describe_breaks(breaks).c_str());
  return kExitBreaks;
}

MeshStats stats_of(const TetMesh& mesh) {
  return compute_mesh_stats(mesh, build_vertex_tets(mesh));
}

}  // namespace

int cmd_simplify(const Args& args) {
  if (wants_help(args)) {
    print_simplify_usage(stdout);
    return kExitOk;
  }
  std::string in, out, history_path;
  SimplifyOptions options;
  WriteOptions write_options;
  bool check = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    OptionResult parsed = parse_simplify_option(args, &i, "simplify", &options);
    if (parsed == OptionResult::kNotMine)
      parsed = parse_write_option(args, &i, "simplify", &write_options);
    if (parsed == OptionResult::kError) return kExitUsage;
    if (parsed == OptionResult::kParsed) continue;
    if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &out)) return kExitUsage;
    } else if (a == "--history") {
      if (!parse_option_value(args, &i, "--history", &history_path)) return kExitUsage;
    } else if (a == "--check") {
      check = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod simplify: unknown option '%s'\n\n", a.c_str());
      print_simplify_usage(stderr);
      return kExitUsage;
    } else if (in.empty()) {
      in = a;
    } else {
      more_than_one_input("simplify", args, in, a);
      return kExitUsage;
    }
  }
  if (in.empty() || out.empty()) {
    std::fputs("tetlod simplify: need IN and -o OUT\n\n", stderr);
    print_simplify_usage(stderr);
    return kExitUsage;
  }
  if (!options.size_given) {
    std::fprintf(stderr,
                 "tetlod simplify: give a target size (--size, --material-size, --size-field or "
                 "--size-map)\n");
    return kExitUsage;
  }
  if (!mesh_output_path_ok(out, "simplify", write_options)) return kExitUsage;
  if (!history_path.empty() && !is_history_path(history_path)) {
    std::fprintf(stderr, "tetlod simplify: --history %s: a collapse history file ends in .tlh\n",
                 history_path.c_str());
    return kExitUsage;
  }
  if (!output_directory_ok(out) || (!history_path.empty() && !output_directory_ok(history_path)))
    return kExitBadInput;

  TetMesh input;
  ReadInfo info;
  if (!load_mesh(in, &input, &info, write_options.surface_groups)) return kExitBadInput;
  if (const int code = finish_simplify_options(input, info.material_names, "simplify", &options,
                                               &info.validation))
    return code;
  // The file's own surface groups: the simplifier keeps their borders as it keeps
  // those between materials, and their triangles inside a material as they are (so
  // does --improve), so that the output has them too (with --surfaces).
  SurfacePatches patches;
  if (!info.surface_groups.empty()) patches = SurfacePatches(input, info.surface_groups);
  if (write_options.surface_groups) print_patch_notes(patches, "simplify");
  // Keeping the groups inside a material keeps the mesh fine there: only when groups
  // may be written (--surfaces, or a history, whose levels lod can write with them).
  if (!write_options.surface_groups && history_path.empty()) patches.drop_inside();
  if (!patches.inside_entries().empty()) {
    std::string names;
    for (const SurfacePatches::Group& g : patches.groups())
      if (g.inside > 0)
        names += (names.empty() ? "" : ", ") +
                 (g.name.empty() ? std::to_string(g.tag) : "'" + g.name + "'");
    std::fprintf(stderr,
                 "tetlod simplify: note: the surface groups inside a material (%s; %zu "
                 "triangles) are kept as they are: the mesh is not coarsened on them (without "
                 "--surfaces and --history it is)\n",
                 names.c_str(), patches.inside_entries().size());
  }
  // Material ids near the top of the tag range can leave no room to number the surface
  // groups; the simplified mesh has the input's material pairs: say so before the work.
  if (write_options.surface_groups &&
      first_surface_tag(input) > std::numeric_limits<int32_t>::max() - (1 << 16)) {
    SurfaceGroups probe;
    if (const Status s = group_surface(input, &probe, patches); !s) {
      std::fprintf(stderr, "tetlod simplify: %s: %s\n", out.c_str(), s.message().c_str());
      return kExitBadInput;
    }
  }
  write_options.material_names = &info.material_names;  // no material disappears
  const SimplifyParams& params = options.params;
  const long long elements = options.elements;
  const bool improve = options.improve;

  std::printf("input %s\n", in.c_str());
  print_property_table(stats_of(input), &info.material_names);
  // The size: the uniform one, the local sizing, or the smaller of the two (sizing.h).
  std::printf("\nthresholds: %s\n", describe_thresholds(params).c_str());
  // What the input breaks already: the final mesh's line below says how much of that
  // is left (a collapse never makes a tet or node that breaks them).
  const ThresholdCounts input_breaks = threshold_breaks(input, params);
  std::printf("input, breaking them: %s\n", describe_breaks(input_breaks).c_str());
  // Said before the run, which may be long: a layer a few tolerances thick can come out
  // much thinner or thicker with hardly a change of volume.
  if (const std::string thin =
          thin_materials(material_surfaces(input), params.tolerance, &info.material_names);
      !thin.empty()) {
    std::fprintf(stderr,
                 "tetlod simplify: note: thin for the tolerance (%g): %s (twice the volume over "
                 "the surface's area); boundaries and interfaces may move by up to the "
                 "tolerance, a large part of such a layer: a --tolerance of a tenth of its "
                 "thickness keeps each side within a tenth of it ('tetlod compare IN OUT' says "
                 "how far they moved)\n",
                 params.tolerance, thin.c_str());
  }

  SimplifyResult result;
  TerminalProgress progress("tetlod simplify");
  const Status status =
      simplify(input, params, &result, progress.simplify_callback(), nullptr, &patches);
  progress.clear();
  if (!status) {
    std::fprintf(stderr, "tetlod simplify: %s\n", status.message().c_str());
    return exit_code_of_failed_run(status.bad_value());
  }

  TetMesh output = std::move(result.output);
  size_t step = result.history.step_count();
  if (elements > 0) {
    Lod lod(result.base, &result.history);
    step = lod.step_for_elements(static_cast<size_t>(elements));
    lod.seek(step);
    output = lod.extract();
  }
  std::string beyond = beyond_levels_note(elements > 0 ? elements : -1, step,
                                          result.history.step_count(), output.tet_count());
  if (!beyond.empty()) beyond = "; " + beyond;
  // A level before the last may break what the final mesh does not (tets not yet
  // collapsed): what it breaks is said apart.
  const bool before_last = step < result.history.step_count();
  ThresholdCounts level_breaks;
  if (before_last && !improve) level_breaks = threshold_breaks(output, params);
  ImproveResult improved;
  double seconds_improve = 0;
  if (improve) improved = improve_timed(&output, params, patches, &seconds_improve);
  std::printf("\noutput %s (step %zu of %zu%s)\n", out.c_str(), step, result.history.step_count(),
              beyond.c_str());
  print_property_table(stats_of(output), &info.material_names);
  if (const std::string changes =
          volume_changes(material_volumes(input), material_volumes(output), &info.material_names);
      !changes.empty()) {
    std::fprintf(stderr,
                 "tetlod simplify: note: volumes changed by more than %g %%: %s; the tolerance "
                 "(%g) lets boundaries and interfaces move that far, which thins or thickens a "
                 "part a few times as thick: a smaller --tolerance keeps it\n",
                 kVolumeNotePercent, changes.c_str(), params.tolerance);
  }
  if (const std::string changes = group_area_changes(input, output, patches); !changes.empty()) {
    std::fprintf(stderr,
                 "tetlod simplify: note: surface groups' areas changed by more than %g %%: %s; "
                 "the tolerance (%g) lets their borders move that far, which changes a small "
                 "group's area (a port): a smaller --tolerance keeps it\n",
                 kVolumeNotePercent, changes.c_str(), params.tolerance);
  }
  const std::string kept_unsplit =
      result.splits_skipped_inside == 0
          ? std::string()
          : "; and " + std::to_string(result.splits_skipped_inside) +
                (result.splits_skipped_inside == 1 ? " edge" : " edges") +
                " of surface groups inside a material, which are kept as they are";
  if (params.subdivide) {
    std::printf(
        "\nsubdivision: %zu splits (%zu edges longer than half the size left unsplit to keep the "
        "thresholds: %zu for a piece's stretch or size, %zu for a node's valence%s), %zu tets\n",
        result.splits, result.splits_skipped, result.splits_skipped - result.splits_skipped_valence,
        result.splits_skipped_valence, kept_unsplit.c_str(), result.base.tet_count());
  } else {
    std::printf("\nsubdivision: off (--no-subdivide), %zu tets\n", result.base.tet_count());
  }
  std::printf("collapses: %zu\nrejected evaluations: %s\n", result.history.step_count(),
              describe_rejections(result.rejections).c_str());
  const std::string past = past_valence_summary(result);
  if (!past.empty()) std::printf("past the valence: %s\n", past.c_str());
  // Faces kept inside a material can be why (a 90-triangle sheet in a motor's air left
  // 69 nodes next to it that no edge removal or collapse could bring back: the first
  // run's 8,504 tets above the size stood; not keeping the sheet, none).
  const PastValence& pv = result.past_valence;
  if (pv.tried && !pv.taken && !pv.stopped && pv.nodes_left > 0 &&
      !patches.inside_entries().empty())
    std::printf(
        "  (the input's surface groups inside a material are kept as they are (%zu faces), "
        "which can leave nodes next to them that no edge removal or collapse may bring back; "
        "without --surfaces and --history they are not kept, and the run past the valence "
        "may then be taken)\n",
        patches.inside_entries().size());
  if (result.past_valence.tried && !result.past_valence.stopped)
    std::printf(
        "  (--within-valence makes the first run only, which left %zu tets above the size, "
        "and not the other)\n",
        result.past_valence.above_size_within);
  if (result.past_valence.stopped_by_factor)
    std::printf("  (--past-valence-factor raises that bound: it was %u)\n",
                options.params.past_valence_tets_factor);
  const EvaluationCounts& e = result.evaluations;
  std::printf(
      "evaluations: %llu of every edge at the start, %llu of new nodes' edges, %llu of stale "
      "queue entries, %llu in %llu sweeps%s (%llu in all; %llu more not made again, as made "
      "already on the same mesh)\n",
      static_cast<unsigned long long>(e.initial), static_cast<unsigned long long>(e.new_node),
      static_cast<unsigned long long>(e.stale), static_cast<unsigned long long>(e.sweep),
      static_cast<unsigned long long>(e.sweeps),
      e.valence == 0 ? ""
                     : (", " + std::to_string(e.valence) +
                        " in the links of nodes subdivision took past the valence")
                           .c_str(),
      static_cast<unsigned long long>(e.total()), static_cast<unsigned long long>(e.repeated));
  const ThresholdViolations& v = result.violations;
  std::printf("final mesh%s, breaking a threshold: %s\n",
              before_last ? " (the history's last step)"
              : improve   ? " (before --improve)"
                          : "",
              describe_violations(v).c_str());
  if (v.above_size > 0) std::printf("why: %s\n", above_size_reason(params, result).c_str());
  if (improve) {
    print_improve(improved, seconds_improve);
  } else if (before_last) {
    std::printf("the level written (step %zu), breaking a threshold: %s\n", step,
                describe_breaks(level_breaks).c_str());
  }
  if (params.subdivide) std::printf("time: subdivide %.3f s, ", result.seconds_subdivide);
  std::printf("%sclassify %.3f s, simplify %.3f s (%s kernels)",
              params.subdivide ? "" : "time: ", result.seconds_classify, result.seconds_simplify,
              result.kernels);
  if (result.past_valence.tried)
    std::printf("; and %.3f s for the %s", result.past_valence.seconds_other,
                result.past_valence.runs > 1 ? "runs that are not the result"
                                             : "run that is not the result");
  if (result.past_valence.alongside) std::printf(", made at the same time on a second thread");
  std::printf("\n");

  // The mesh and the history are written together, or neither.
  OutputFiles files;
  StagedMesh staged;
  Status s = stage_output_mesh(&files, out, output, write_options, &staged, &patches);
  if (s && !history_path.empty())
    s = stage_history(&files, history_path, result.base, result.history, &params,
                      &info.material_names, &patches);
  if (s) s = files.commit();
  if (!s) {
    std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  print_staged_mesh_notes(staged);
  if (!history_path.empty()) std::printf("history: %s\n", history_path.c_str());
  if (!check) return kExitOk;
  return check_written("simplify", out,
                       improve ? improved.breaks_after
                       : before_last
                           ? level_breaks
                           : ThresholdCounts{v.below_stretch, v.above_size, v.above_valence});
}

int cmd_lod(const Args& args) {
  if (wants_help(args)) {
    print_lod_usage(stdout);
    return kExitOk;
  }
  std::string history_path, out;
  WriteOptions write_options;
  long long elements = -1, step = -1;
  bool improve = false, thresholds_given = false, check = false;
  SimplifyOptions options;         // the thresholds for --improve
  std::vector<std::string> given;  // which of them, by flag
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::string v;
    // The thresholds (not --elements, which here may be 0, nor the simplifier's own
    // --tolerance, --no-subdivide, --within-valence, --past-valence-factor and
    // --one-thread, which a level does not use).
    if (a == "--size-map" || a == "--size-map-mesh") {
      std::fprintf(stderr,
                   "tetlod lod: %s: --improve keeps to the size map saved in the history, if "
                   "it was made with one\n",
                   a.c_str());
      return kExitUsage;
    }
    if (a != "--elements" && a != "--tolerance" && a != "--no-subdivide" &&
        a != "--within-valence" && a != "--past-valence-factor" && a != "--one-thread" &&
        a != "--improve") {
      const OptionResult parsed = parse_simplify_option(args, &i, "lod", &options);
      if (parsed == OptionResult::kError) return kExitUsage;
      if (parsed == OptionResult::kParsed) {
        thresholds_given = true;
        given.push_back(a);
        continue;
      }
    }
    const OptionResult written = parse_write_option(args, &i, "lod", &write_options);
    if (written == OptionResult::kError) return kExitUsage;
    if (written == OptionResult::kParsed) continue;
    if (a == "--improve") {
      improve = true;
    } else if (a == "--check") {
      check = true;
    } else if (a == "-o" || a == "--output") {
      if (!parse_option_value(args, &i, "-o", &out)) return kExitUsage;
    } else if (a == "--elements" || a == "--step") {
      if (!parse_option_value(args, &i, a.c_str(), &v)) return kExitUsage;
      // A step from 0; a number of elements from 1, as simplify and render take it.
      const auto n = parse_integer(v);
      const int64_t least = a == "--step" ? 0 : 1;
      if (!n || *n < least) {
        std::fprintf(stderr, "tetlod lod: %s '%s' is not a whole number >= %d\n", a.c_str(),
                     v.c_str(), int(least));
        return kExitUsage;
      }
      (a == "--step" ? step : elements) = *n;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "tetlod lod: unknown option '%s'\n\n%s", a.c_str(), kLodUsage);
      return kExitUsage;
    } else if (history_path.empty()) {
      history_path = a;
    } else {
      more_than_one_input("lod", args, history_path, a);
      return kExitUsage;
    }
  }
  if (elements >= 0 && step >= 0) {
    std::fprintf(stderr, "tetlod lod: give --elements or --step, not both\n\n%s", kLodUsage);
    return kExitUsage;
  }
  if (history_path.empty() || out.empty() || (elements < 0 && step < 0)) {
    std::fprintf(stderr, "tetlod lod: need HISTORY, -o OUT and one of --elements, --step\n\n%s",
                 kLodUsage);
    return kExitUsage;
  }
  if (!mesh_output_path_ok(out, "lod", write_options)) return kExitUsage;
  if (!output_directory_ok(out)) return kExitBadInput;
  // (A history may have any name: "-o" over it, or a file of a .node/.ele output's
  // set, would replace the history by one level.)
  for (const std::string& written : mesh_output_files(out)) {
    std::error_code same_error;
    if (std::filesystem::equivalent(history_path, written, same_error)) {
      std::fprintf(stderr,
                   "tetlod lod: -o %s would write %s, the history being read: the level would "
                   "replace it\n",
                   out.c_str(), written.c_str());
      return kExitUsage;
    }
  }
  if (thresholds_given && !improve) {
    std::fprintf(stderr,
                 "tetlod lod: thresholds (and --crease-angle) are only used with --improve\n\n%s",
                 kLodUsage);
    return kExitUsage;
  }
  HistoryLevel level;
  if (!load_history_level(history_path, "lod", step, elements, &level)) return kExitBadInput;
  if (check && !improve && !level.params) {
    std::fprintf(stderr,
                 "tetlod lod: --check: %s was saved without its thresholds (as every history "
                 "before 2026-11-24 was): check the level with 'tetlod stats OUT --size S ... "
                 "--check'\n",
                 history_path.c_str());
    return kExitUsage;
  }
  // The thresholds to improve within: those saved in the history, each one given here
  // replacing its own (--size the uniform size, --material-size the material sizes,
  // --size-field the region rules); with none saved, those given, which need a size.
  std::string source = "saved in the history";
  if (improve && level.params) {
    SimplifyParams merged = *level.params;
    const SimplifyParams& g = options.params;
    for (const std::string& flag : given) {
      if (flag == "--size") merged.sizing.uniform = g.sizing.uniform;
      if (flag == "--material-size") merged.sizing.material_sizes = g.sizing.material_sizes;
      if (flag == "--size-field") {
        merged.sizing.radial = g.sizing.radial;
        merged.sizing.boxes = g.sizing.boxes;
      }
      if (flag == "--stretch") merged.min_stretch = g.min_stretch;
      if (flag == "--valence") merged.max_valence = g.max_valence;
      if (flag == "--crease-angle") merged.crease_angle_degrees = g.crease_angle_degrees;
    }
    options.params = merged;
    options.tolerance_given = true;  // a level does not use it
    if (!given.empty()) {
      std::sort(given.begin(), given.end());
      given.erase(std::unique(given.begin(), given.end()), given.end());
      std::string flags;
      for (const std::string& flag : given) flags += (flags.empty() ? "" : ", ") + flag;
      source += ", but " + flags + " given here";
    }
  } else if (improve) {
    if (!options.size_given) {
      std::fprintf(stderr,
                   "tetlod lod: %s was saved without its thresholds (as every history before "
                   "2026-11-24 was): "
                   "--improve needs the ones it was made with (--size S [--stretch D] "
                   "[--valence V] ...)\n",
                   history_path.c_str());
      return kExitUsage;
    }
    source = "given here; the history has none saved";
  }
  if (improve) {
    if (const Status p = check_params(options.params); !p) {
      std::fprintf(stderr, "tetlod lod: %s\n", p.message().c_str());
      return kExitUsage;
    }
  }
  std::string beyond = step >= 0 ? std::string()
                                 : beyond_levels_note(elements, level.step, level.step_count,
                                                      level.mesh.tet_count());
  if (!beyond.empty()) beyond = " (" + beyond + ")";
  if (improve)
    if (const int code = finish_simplify_options(level.mesh, level.names, "lod", &options))
      return code;
  ImproveResult improved;
  double seconds_improve = 0;
  const size_t level_tets = level.mesh.tet_count(), level_nodes = level.mesh.vertex_count();
  if (improve) {
    std::printf("improving within %s (%s)\n", describe_thresholds(options.params, false).c_str(),
                source.c_str());
    improved = improve_timed(&level.mesh, options.params, level.patches, &seconds_improve);
  }
  write_options.material_names = &level.names;
  OutputFiles files;
  StagedMesh staged;
  // The history's surface groups inside a material are faces of every level (improved
  // or not).
  Status s = stage_output_mesh(&files, out, level.mesh, write_options, &staged, &level.patches);
  if (s) s = files.commit();
  if (!s) {
    std::fprintf(stderr, "tetlod: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  // The level's counts (the improvement's own line gives those written, if they differ).
  std::printf(
      "%s: step %zu of %zu%s, %zu elements, %zu nodes (moved there in %.4f s)%s\n", out.c_str(),
      level.step, level.step_count,
      step > static_cast<long long>(level.step_count) ? " (the last: --step is past it)"
                                                      : beyond.c_str(),
      level_tets, level_nodes, level.seek_seconds,
      improve && level.mesh.tet_count() != level_tets
          ? (", improved to " + std::to_string(level.mesh.tet_count()) + " elements").c_str()
          : "");
  ThresholdCounts breaks;
  if (improve) {
    print_improve(improved, seconds_improve);
    breaks = improved.breaks_after;
  } else if (level.params) {
    // A level before the last may break what the final mesh does not: tets not yet
    // collapsed, and after a run past the valence, before its first collapses, nodes
    // subdivision took past it (docs/RESULTS.md).
    breaks = threshold_breaks(level.mesh, *level.params);
    std::printf("this level, breaking the thresholds saved in the history: %s\n",
                describe_breaks(breaks).c_str());
  }
  print_staged_mesh_notes(staged);
  return check ? check_written("lod", out, breaks) : kExitOk;
}

}  // namespace tetlod::app
