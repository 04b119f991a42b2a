#include "app/cli_util.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <utility>

#include "core/adjacency.h"
#include "core/io/text_lines.h"
#include "core/lod.h"
#include "core/utf8.h"
#include "core/validate.h"

namespace tetlod::app {

bool wants_help(const Args& args) {
  for (const std::string& a : args)
    if (a == "-h" || a == "--help") return true;
  return false;
}

bool normalize_args(const std::string& command, Args* args) {
  // The options that take no value, in every command: "--json=1" would leave "1" as an
  // input file's name.
  static const char* const kFlags[] = {
      "--by-id",      "--check",      "--help",         "--improve",       "--json",
      "--msh-binary", "--no-legend",  "--no-subdivide", "--one-thread",    "--simplify",
      "--surfaces",   "--vtk-binary", "--wireframe",    "--within-valence"};
  Args split;
  split.reserve(args->size());
  for (const std::string& a : *args) {
    const size_t equals = a.find('=');
    const bool named =
        (a.size() > 2 && a.compare(0, 2, "--") == 0 && equals != std::string::npos && equals > 2 &&
         std::all_of(a.begin() + 2, a.begin() + static_cast<long>(equals),
                     [](char c) { return (c >= 'a' && c <= 'z') || c == '-'; })) ||
        a.compare(0, 3, "-o=") == 0;
    if (named && std::any_of(std::begin(kFlags), std::end(kFlags), [&](const char* f) {
          return a.compare(0, equals, f) == 0 && std::strlen(f) == equals;
        })) {
      std::fprintf(stderr, "tetlod %s: %s takes no value (got '%s')\n", command.c_str(),
                   a.substr(0, equals).c_str(), a.c_str());
      return false;
    }
    if (named) {
      split.push_back(a.substr(0, equals));
      split.push_back(a.substr(equals + 1));
    } else {
      split.push_back(a);
    }
  }
  static const char* const kAddUp[] = {"--material-size", "--size-field", "--conductor", "--eps",
                                       "--ground"};
  std::vector<std::string> seen;
  for (const std::string& a : split) {
    const bool option = a == "-o" || (a.size() > 2 && a.compare(0, 2, "--") == 0);
    if (!option) continue;
    const std::string name = a == "--output" ? "-o" : a;
    const bool adds_up = std::any_of(std::begin(kAddUp), std::end(kAddUp),
                                     [&](const char* f) { return name == f; }) ||
                         (command == "view" && name == "--hide");
    if (adds_up || name == "--help") continue;
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
      std::fprintf(stderr,
                   "tetlod %s: %s given twice: give it once (--material-size, --size-field, "
                   "--conductor, --eps, --ground and view's --hide add up)\n",
                   command.c_str(), name.c_str());
      return false;
    }
    seen.push_back(name);
  }
  // Render's (and report's) alternatives, as their usage shows them: one would be
  // dropped without a word (--view with --camera drew the camera's picture).
  static const char* const kEitherOr[][2] = {
      {"--view", "--camera"}, {"--cut", "--cut-plane"}, {"--materials", "--hide"}};
  for (const auto& pair : kEitherOr) {
    if (std::find(seen.begin(), seen.end(), pair[0]) != seen.end() &&
        std::find(seen.begin(), seen.end(), pair[1]) != seen.end()) {
      std::fprintf(stderr, "tetlod %s: give %s or %s, not both\n", command.c_str(), pair[0],
                   pair[1]);
      return false;
    }
  }
  *args = std::move(split);
  return true;
}

void more_than_one_input(const char* command, const Args& args, const std::string& first,
                         const std::string& second) {
  const bool has_output = std::find(args.begin(), args.end(), "-o") != args.end() ||
                          std::find(args.begin(), args.end(), "--output") != args.end();
  const bool to_dir = std::strcmp(command, "report") == 0;
  const std::string hint = has_output
                               ? "it takes one"
                               : std::string("the output ") + (to_dir ? "directory" : "file") +
                                     " goes after -o: -o " + second;
  std::fprintf(stderr, "tetlod %s: two inputs given, '%s' and '%s' (%s); see 'tetlod %s --help'\n",
               command, first.c_str(), second.c_str(), hint.c_str(), command);
}

std::optional<double> parse_double(const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(const std::string& text) {
  long long value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::vector<std::string> validation_notes(const ValidationReport& report) {
  std::vector<std::string> notes;
  char text[512];
  if (const size_t n = report.reoriented_tets; n > 0) {
    std::snprintf(text, sizeof text, "%zu negatively oriented %s reoriented", n,
                  n == 1 ? "tetrahedron was" : "tetrahedra were");
    notes.push_back(text);
  }
  if (const size_t n = report.coincident_vertices; n > 0) {
    const Vec3& at = report.coincident_position;
    std::snprintf(text, sizeof text,
                  "%zu %s at the position of another (the first at (%g, %g, %g)): the mesh is "
                  "not conforming there, so its parts are simplified as separate bodies (in "
                  "Gmsh, BooleanFragments or Coherence makes the volumes share their faces)",
                  n, n == 1 ? "vertex is" : "vertices are", at.x, at.y, at.z);
    notes.push_back(text);
  }
  if (report.overlap_check_cut_short) {
    notes.push_back(
        "the check for tetrahedra that overlap with no face between them stopped early (too "
        "many boundary faces close together); the part it saw passed");
  }
  if (const size_t n = report.removed_unused_vertices; n > 0) {
    std::snprintf(text, sizeof text, "%zu %s used by no tetrahedron %s dropped", n,
                  n == 1 ? "vertex" : "vertices", n == 1 ? "was" : "were");
    notes.push_back(text);
  }
  return notes;
}

std::vector<std::string> reader_notes(const ReadInfo& info, bool surfaces_written) {
  std::vector<std::string> notes = info.notes;
  if (info.surface_elements_not_kept == 0 || surfaces_written) return notes;
  std::string groups;
  bool named = false;
  for (const InputSurfaceGroup& group : info.surface_groups) named = named || !group.name.empty();
  const size_t shown = std::min<size_t>(info.surface_groups.size(), 10);
  for (size_t g = 0; g < shown; ++g) {
    const InputSurfaceGroup& group = info.surface_groups[g];
    groups += (g == 0 ? "" : ", ") +
              (group.name.empty() ? std::to_string(group.tag) : "'" + group.name + "'");
  }
  if (info.surface_groups.size() > shown)
    groups += " and " + std::to_string(info.surface_groups.size() - shown) + " more";
  // Those in no group (a partitioned Gmsh file's partition boundaries, say) are not kept
  // at all.
  uint64_t grouped = 0;
  for (const InputSurfaceGroup& group : info.surface_groups) grouped += group.triangles.size();
  if (!groups.empty() && info.surface_elements_not_kept > grouped)
    groups += " (" + std::to_string(info.surface_elements_not_kept - grouped) +
              " of them in no group, not kept at all)";
  notes.push_back(
      std::to_string(info.surface_elements_not_kept) +
      (info.surface_elements_not_kept == 1 ? " surface element is not kept as an element"
                                           : " surface elements are not kept as elements") +
      (groups.empty() ? std::string() : ", only as the surface groups " + groups) +
      ": TetLOD keeps the tetrahedra and their volume groups; --surfaces, or the viewer's "
      "boundary groups, writes the boundary and interface triangles again" +
      (groups.empty()
           ? std::string(", a group per material pair")
           : std::string(", these groups under their ") + (named ? "names and tags" : "tags") +
                 " (simplified too), the rest by material pair"));
  return notes;
}

bool load_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info, bool surfaces_written) {
  if (is_history_path(path)) {
    std::fprintf(stderr,
                 "tetlod: %s is a collapse history, not a mesh: write one of its levels with "
                 "'tetlod lod %s --elements N -o LEVEL.mesh' (render and view open it too)\n",
                 path.c_str(), path.c_str());
    return false;
  }
  const Status status = read_mesh(path, mesh, info);
  if (!status) {
    std::fprintf(stderr, "tetlod: %s\n", status.message().c_str());
    return false;
  }
  // The reader's notes first: they may explain the validation's (skipped elements
  // leave their vertices unused).
  for (const std::string& note : reader_notes(*info, surfaces_written))
    std::fprintf(stderr, "tetlod: %s: note: %s\n", path.c_str(), note.c_str());
  for (const std::string& note : validation_notes(info->validation))
    std::fprintf(stderr, "tetlod: %s: note: %s\n", path.c_str(), note.c_str());
  return true;
}

BeyondLevels beyond_levels(long long elements, size_t step, size_t step_count, size_t tets) {
  if (elements < 0) return BeyondLevels::kNo;
  if (step == step_count && tets > size_t(elements)) return BeyondLevels::kPastTheLast;
  if (step == 0 && tets < size_t(elements)) return BeyondLevels::kBeforeTheFirst;
  return BeyondLevels::kNo;
}

std::string beyond_levels_note(long long elements, size_t step, size_t step_count, size_t tets) {
  switch (beyond_levels(elements, step, step_count, tets)) {
    case BeyondLevels::kPastTheLast:
      return "the last: no level has fewer elements than this one";
    case BeyondLevels::kBeforeTheFirst:
      return "the first: no level has more elements than this one";
    case BeyondLevels::kNo:
      break;
  }
  return "";
}

bool has_extension(const std::string& path, const char* extension) {
  const size_t n = std::strlen(extension);
  if (path.size() < n) return false;
  for (size_t i = 0; i < n; ++i) {
    if (std::tolower(static_cast<unsigned char>(path[path.size() - n + i])) != extension[i])
      return false;
  }
  return true;
}

bool is_history_path(const std::string& path) {
  return has_extension(path, ".tlh");
}

bool mesh_output_path_ok(const std::string& path, const char* command, const WriteOptions& options,
                         const char* flag) {
  const Status status = check_mesh_path(path, options);
  if (status) {
    // A binary flag for another format would be ignored: say so rather than write text.
    const char* unused =
        options.gmsh_binary && !has_extension(path, ".msh") ? "--msh-binary"
        : options.vtk_binary && !has_extension(path, ".vtk") && !has_extension(path, ".vtu")
            ? "--vtk-binary"
            : nullptr;
    if (!unused) return true;
    std::fprintf(stderr, "tetlod %s: %s: %s%s%s is not a %s file, which the flag is for\n", command,
                 unused, flag, *flag ? " " : "", path.c_str(),
                 unused[2] == 'm' ? ".msh" : ".vtk or .vtu");
    return false;
  }
  std::fprintf(stderr, "tetlod %s: %s%s%s\n", command, flag, *flag ? " " : "",
               status.message().c_str());
  if (is_history_path(path))
    std::fprintf(stderr,
                 "(a collapse history is written by 'tetlod simplify --history FILE.tlh')\n");
  return false;
}

bool output_directory_ok(const std::string& path, bool make_directories) {
  const Status status = check_output_directory(path, make_directories);
  if (!status) std::fprintf(stderr, "tetlod: %s\n", status.message().c_str());
  return bool(status);
}

Status stage_output_mesh(OutputFiles* files, const std::string& path, const TetMesh& mesh,
                         WriteOptions options, StagedMesh* staged, const SurfacePatches* patches,
                         const std::vector<uint32_t>* face_neighbors) {
  staged->has_groups = options.surface_groups;
  if (!options.surface_groups && (has_extension(path, ".node") || has_extension(path, ".ele"))) {
    const std::string face =
        path.substr(0, path.size() - (has_extension(path, ".ele") ? 4 : 5)) + ".face";
    std::error_code ec;
    if (std::filesystem::exists(face, ec)) staged->stale_face = face;
  }
  if (options.surface_groups) {
    if (Status s =
            patches ? group_surface(mesh, &staged->groups, *patches, true, face_neighbors)
                    : group_surface(mesh, &staged->groups, SurfacePatches(), false, face_neighbors);
        !s)
      return Status::error(path + ": " + s.message());
    options.groups = &staged->groups;
  }
  return stage_mesh(files, path, mesh, options);
}

void print_patch_notes(const SurfacePatches& patches, const char* command) {
  for (const SurfacePatches::Group& g : patches.groups()) {
    const std::string label = g.name.empty()
                                  ? "with tag " + std::to_string(g.tag) + " (unnamed)"
                                  : "'" + g.name + "' (tag " + std::to_string(g.tag) + ")";
    const size_t all = g.triangles + g.inside + g.shared + g.missing;
    // What is written of the group: its surface triangles and those inside a material.
    const size_t written = g.triangles + g.inside;
    // "every triangle of surface group X" or "N of the M triangles of ...", and whether
    // its verb is singular.
    const auto some = [&](size_t n) {
      const bool whole = n == all;
      return std::make_pair(whole ? "every triangle of surface group " + label
                                  : std::to_string(n) + " of the " + std::to_string(all) +
                                        " triangles of surface group " + label,
                            whole || n == 1);
    };
    const char* outcome = written == 0 ? "not written" : "written without them";
    if (g.shared > 0) {
      const auto [what, one] = some(g.shared);
      std::fprintf(stderr,
                   "tetlod %s: note: %s %s also in a smaller group, which holds %s (a triangle "
                   "is written in one group): %s\n",
                   command, what.c_str(), one ? "is" : "are", one ? "it" : "them", outcome);
    }
    if (g.missing > 0 && written == 0 && g.missing == all) {
      std::fprintf(stderr,
                   "tetlod %s: note: no triangle of surface group %s is a face of the mesh: not "
                   "written\n",
                   command, label.c_str());
    } else if (g.missing > 0) {
      const auto [what, one] = some(g.missing);
      std::fprintf(stderr, "tetlod %s: note: %s %s not %s of the mesh: %s\n", command, what.c_str(),
                   one ? "is" : "are", one ? "a face" : "faces", outcome);
    }
  }
}

void print_staged_mesh_notes(const StagedMesh& staged) {
  if (!staged.stale_face.empty()) {
    std::fprintf(stderr,
                 "tetlod: note: %s, which was beside the pair written, now lists this mesh's "
                 "faces without group markers (--surfaces writes them with markers)\n",
                 staged.stale_face.c_str());
  }
  if (!staged.has_groups) return;
  std::string line;
  for (const SurfaceGroup& group : staged.groups.groups) {
    line += (line.empty() ? "" : ", ") + std::to_string(group.tag) + " " + group.name + ": " +
            std::to_string(group.triangles.size());
  }
  std::printf("surface groups (tag name: triangles): %s\n", line.empty() ? "none" : line.c_str());
}

bool open_history(const std::string& path, const char* command, OpenedHistory* opened) {
  TetMesh base;
  opened->path = path;
  int format = 0;
  const Status s = read_history(path, &base, &opened->history, &opened->params, &opened->names,
                                &opened->patches, &format);
  if (!s) {
    std::fprintf(stderr, "tetlod %s: %s\n", command, s.message().c_str());
    return false;
  }
  if (const std::string note = unchecked_history_note(format); !note.empty())
    std::fprintf(stderr, "tetlod %s: note: %s is %s\n", command, path.c_str(), note.c_str());
  opened->lod = std::make_unique<Lod>(std::move(base), &opened->history);
  return true;
}

bool history_level(OpenedHistory* opened, const char* command, size_t step, TetMesh* level,
                   double* seek_seconds) {
  const auto start = std::chrono::steady_clock::now();
  opened->lod->seek(step);
  if (seek_seconds)
    *seek_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  *level = opened->lod->extract();
  // The reader has checked that every level is made of positive tets; a forged file
  // could still make tets overlap: hand on only what TetLOD would read from a file.
  ValidationReport report;
  const Status s = validate_mesh(
      level, opened->path + " (level at step " + std::to_string(opened->lod->step()) + ")", {},
      &report);
  if (!s) {
    std::fprintf(stderr, "tetlod %s: corrupt history: %s\n", command, s.message().c_str());
    return false;
  }
  return true;
}

bool load_history_level(const std::string& path, const char* command, long long step,
                        long long elements, HistoryLevel* level) {
  OpenedHistory opened;
  if (!open_history(path, command, &opened)) return false;
  const Lod& lod = *opened.lod;
  level->params = opened.params;
  level->names = opened.names;
  level->patches = std::move(opened.patches);
  level->step_count = lod.step_count();
  level->step = step >= 0       ? std::min<size_t>(static_cast<size_t>(step), lod.step_count())
                : elements >= 0 ? lod.step_for_elements(static_cast<size_t>(elements))
                                : lod.step_count();
  return history_level(&opened, command, level->step, &level->mesh, &level->seek_seconds);
}

std::string material_name_of(const std::vector<MaterialName>* names, int32_t m) {
  const std::string* name = find_material_name(names, m);
  return name ? *name : "";
}

bool is_material_name(const std::string& text) {
  return !text.empty() && !parse_integer(text).has_value();
}

namespace {

// The pieces of `text` between its commas, untrimmed; "\\," is a comma inside a piece.
std::vector<std::string> comma_pieces(const std::string& text) {
  std::vector<std::string> pieces(1);
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size() && text[i + 1] == ',') {
      pieces.back() += ',';
      ++i;
    } else if (text[i] == ',') {
      pieces.emplace_back();
    } else {
      pieces.back() += text[i];
    }
  }
  return pieces;
}

std::string trimmed(const std::string& text) {
  return std::string(io::trim_blanks(text));
}

}  // namespace

std::vector<std::string> split_items(const std::string& text) {
  std::vector<std::string> items;
  for (const std::string& piece : comma_pieces(text)) items.push_back(trimmed(piece));
  return items;
}

std::vector<std::string> split_value_items(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::string item;
  bool open = false;  // `item` holds pieces without the separator, not yet an item
  for (const std::string& piece : comma_pieces(text)) {
    // An empty piece (a comma at either end, two in a row) is an empty item, not part
    // of a name: ",3=0" was the name ",3".
    if (trimmed(piece).empty()) {
      if (open) items.push_back(trimmed(item));
      open = false;
      items.emplace_back();
      continue;
    }
    item = open ? item + "," + piece : piece;
    open = piece.find(separator) == std::string::npos;
    if (!open) items.push_back(trimmed(item));
  }
  if (open) items.push_back(trimmed(item));
  return items;
}

bool split_material_value(const std::string& item, char separator, std::string* material,
                          double* value) {
  const size_t at = item.rfind(separator);
  *material = at == std::string::npos ? "" : item.substr(0, at);
  if (at == std::string::npos) return false;
  const std::optional<double> v = parse_double(item.substr(at + 1));
  if (!v) return false;
  *value = *v;
  return true;
}

const char* const kEmptyItem = "an empty item (a comma at either end, or two in a row)";

std::string parse_materials(const std::string& text, std::vector<int32_t>* ids,
                            std::vector<std::string>* names) {
  ids->clear();
  names->clear();
  if (trimmed(text).empty()) return "no material given";
  for (const std::string& item : split_items(text)) {
    if (item.empty()) return kEmptyItem;
    if (is_material_name(item)) {
      names->push_back(item);
    } else {
      const auto n = parse_integer(item);
      if (!n || *n < 0 || *n > 0x7fffffff) return "'" + item + "' is not a material id >= 0";
      ids->push_back(static_cast<int32_t>(*n));
    }
  }
  return "";
}

std::string find_surface_groups(const std::string& text, const SurfacePatches& patches,
                                std::vector<uint32_t>* groups) {
  groups->clear();
  const std::vector<SurfacePatches::Group>& all = patches.groups();
  if (all.empty()) return "the input has no surface groups";
  if (trimmed(text).empty()) return "no surface group given";
  if (trimmed(text) == "all") {
    for (uint32_t g = 0; g < all.size(); ++g) groups->push_back(g);
    return "";
  }
  for (const std::string& item : split_items(text)) {
    if (item.empty()) return kEmptyItem;
    const auto tag = parse_integer(item);
    size_t found = 0;
    for (uint32_t g = 0; g < all.size(); ++g) {
      // An unnamed group (a Medit reference) by its tag, or as the key calls it.
      const std::string unnamed = "surface_" + std::to_string(all[g].tag);
      if (all[g].name == item || (tag && all[g].tag == *tag) ||
          (all[g].name.empty() && (item == unnamed || item == "surface " + unnamed.substr(8)))) {
        groups->push_back(g);
        ++found;
      }
    }
    if (found == 0) {
      std::string list;
      for (const SurfacePatches::Group& g : all) {
        if (list.size() > 400) {
          list += ", ...";
          break;
        }
        list += (list.empty() ? "" : ", ") + std::to_string(g.tag) +
                (g.name.empty() ? "" : " '" + g.name + "'");
      }
      return "the input has no surface group '" + item + "' (it has " + list + ")";
    }
  }
  std::sort(groups->begin(), groups->end());
  groups->erase(std::unique(groups->begin(), groups->end()), groups->end());
  return "";
}

bool find_material(const std::string& name, const std::vector<MaterialName>& names, int32_t* id,
                   std::string* why) {
  const MaterialName* found = nullptr;
  int folded = 0;
  // A name that two materials share (two Nastran comments, two Gmsh groups) names
  // neither: the id says which.
  std::string shared;
  for (const MaterialName& m : names)
    if (m.name == name) shared += (shared.empty() ? "" : " and ") + std::to_string(m.material);
  if (shared.find(" and ") != std::string::npos) {
    *why = "the mesh names materials " + shared + " '" + name + "': give the number";
    return false;
  }
  for (const MaterialName& m : names) {
    if (m.name == name) {
      *id = m.material;
      return true;
    }
    if (m.name.size() == name.size() &&
        std::equal(name.begin(), name.end(), m.name.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) ==
                 std::tolower(static_cast<unsigned char>(b));
        })) {
      found = &m;
      ++folded;
    }
  }
  if (folded == 1) {
    *id = found->material;
    return true;
  }
  std::string list;
  bool comma = false;  // a name with a comma: in a list of names it is written "\,"
  for (const MaterialName& m : names) {
    list += (list.empty() ? "" : ", ") + std::to_string(m.material) + " " + m.name;
    comma = comma || m.name.find(',') != std::string::npos;
  }
  *why =
      "the mesh has no material named '" + name + "' (" +
      (list.empty()
           ? std::string("its materials have no names: give their numbers")
           : (folded > 1 ? "several names differ from it only in case: " : "its names: ") + list) +
      ")" + (comma ? "; in a list of names, a comma in a name is written \\," : "");
  return false;
}

bool material_by_name(const std::string& name, const std::vector<MaterialName>& names,
                      const char* command, const std::string& option, int32_t* id) {
  std::string why;
  if (find_material(name, names, id, &why)) return true;
  std::fprintf(stderr, "tetlod %s: %s: %s\n", command, option.c_str(), why.c_str());
  return false;
}

void print_property_table(const MeshStats& stats, const std::vector<MaterialName>* names) {
  const bool named = names && !names->empty();
  std::printf("%-14s %9s %9s %10s %9s %9s %8s %11s %12s%s\n", "", "#nodes", "#edges", "#elements",
              "ave.str", "min.str", "max.val", "max.size", "volume", named ? "  name" : "");
  auto row = [](const std::string& label, const PropertyRow& r, const std::string& name) {
    std::printf("%-14s %9zu %9zu %10zu %9.4f %9.4f %8u %11.5g %12.6g%s\n", label.c_str(), r.nodes,
                r.edges, r.elements, r.average_stretch, r.min_stretch, r.max_valence, r.max_size,
                r.volume, name.empty() ? "" : ("  " + name).c_str());
  };
  row("whole mesh", stats.whole, "");
  for (const MaterialRow& m : stats.per_material)
    row("material " + std::to_string(m.material), m.row, material_name_of(names, m.material));
}

std::string volume_changes(const std::vector<MaterialVolume>& before,
                           const std::vector<MaterialVolume>& after,
                           const std::vector<MaterialName>* names) {
  std::string text;
  size_t j = 0;
  for (const MaterialVolume& m : before) {
    while (j < after.size() && after[j].material < m.material) ++j;
    if (j == after.size() || after[j].material != m.material) continue;
    if (!(m.volume > 0)) continue;
    const double percent = 100 * (after[j].volume - m.volume) / m.volume;
    if (!(std::fabs(percent) > kVolumeNotePercent)) continue;
    const std::string name = material_name_of(names, m.material);
    char change[32];
    std::snprintf(change, sizeof change, " %+.1f %%", percent);
    text += (text.empty() ? "material " : ", material ") + std::to_string(m.material) +
            (name.empty() ? "" : " (" + name + ")") + change;
  }
  return text;
}

namespace {

// The area of each of the input's surface groups on `mesh`.
std::vector<double> group_areas(const TetMesh& mesh, const SurfacePatches& patches) {
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  const LocatedGroups located = locate_groups(mesh, patches, true, neighbors);
  std::vector<double> areas(located.in_group.size(), 0.0);
  for (size_t g = 0; g < areas.size(); ++g)
    for (uint32_t i : located.in_group[g]) {
      const auto& v = located.surface[i].v;
      const Vec3& a = mesh.positions[v[0]];
      areas[g] += 0.5 * length(cross(mesh.positions[v[1]] - a, mesh.positions[v[2]] - a));
    }
  return areas;
}

}  // namespace

std::string group_area_changes(const TetMesh& before, const TetMesh& after,
                               const SurfacePatches& patches) {
  if (!patches.any() && patches.inside_entries().empty()) return "";
  const std::vector<double> was = group_areas(before, patches), now = group_areas(after, patches);
  std::string text;
  size_t listed = 0, more = 0;
  for (size_t g = 0; g < was.size(); ++g) {
    if (!(was[g] > 0)) continue;
    const double percent = 100 * (now[g] - was[g]) / was[g];
    if (!(std::fabs(percent) > kVolumeNotePercent)) continue;
    if (listed == 10) {
      ++more;
      continue;
    }
    const SurfacePatches::Group& group = patches.groups()[g];
    char change[32];
    std::snprintf(change, sizeof change, " %+.1f %%", percent);
    text += (text.empty() ? "" : ", ") +
            (group.name.empty() ? "surface " + std::to_string(group.tag) : "'" + group.name + "'") +
            change;
    ++listed;
  }
  if (more > 0) text += " and " + std::to_string(more) + " more";
  return text;
}

std::string thin_materials(const std::vector<MaterialSurface>& surfaces, double tolerance,
                           const std::vector<MaterialName>* names) {
  std::string text;
  size_t listed = 0, more = 0;
  for (const MaterialSurface& m : surfaces) {
    const double thickness = m.thickness();
    if (!(thickness > 0 && thickness < kThinLayerTolerances * tolerance)) continue;
    if (listed == 5) {
      ++more;
      continue;
    }
    const std::string name = material_name_of(names, m.material);
    char about[48];
    std::snprintf(about, sizeof about, " about %.3g thick", thickness);
    text += (listed++ ? ", material " : "material ") + std::to_string(m.material) +
            (name.empty() ? "" : " (" + name + ")") + about;
  }
  if (more > 0) text += " and " + std::to_string(more) + " more";
  return text;
}

std::string json_escape(const std::string& text) {
  std::string out;
  for (size_t at = 0; at < text.size();) {
    const size_t start = at;
    const long code = next_code_point(text, &at);
    if (code < 0) {  // not UTF-8 (a Latin-1 name): U+FFFD, as JSON must be UTF-8
      out += "\xef\xbf\xbd";
    } else if (code == '"' || code == '\\') {
      out += '\\';
      out += static_cast<char>(code);
    } else if (code < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(code));
      out += buffer;
    } else {
      out.append(text, start, at - start);
    }
  }
  return out;
}

}  // namespace tetlod::app
