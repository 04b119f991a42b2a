// Small helpers shared by the subcommands: option parsing and mesh loading that
// reports errors on stderr.
#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/mesh_stats.h"
#include "core/simplify.h"

namespace tetlod::app {

// True if `args` holds -h or --help.
bool wants_help(const Args& args);

// The command line as every command reads it: "--name=value" becomes "--name" "value";
// an option given twice is refused (one that adds up: --material-size, --size-field,
// --conductor, --eps, --ground, and view's --hide), as "-o" twice always was: a second
// --size silently replaced the first; so are render's alternatives given together
// (--view and --camera, --cut and --cut-plane, --materials and --hide). On a refusal prints "tetlod
// <command>: ..." and returns false (a usage error).
bool normalize_args(const std::string& command, Args* args);

// Prints "tetlod <command>: two inputs given, 'first' and 'second' (...)", which says
// where an output goes: most often -o was forgotten.
// (`args`: the command's, to say so where an output was given.)
void more_than_one_input(const char* command, const Args& args, const std::string& first,
                         const std::string& second);

// Parses a finite double / a whole number; nullopt if `text` is not one entirely.
std::optional<double> parse_double(const std::string& text);
std::optional<long long> parse_integer(const std::string& text);

// Reads a mesh; on failure prints "tetlod: <message>" to stderr and returns false
// (for a collapse history, what to do with it instead).
// reader_notes() and validation_notes() go to stderr too.
// What validation repaired or could not check in a mesh it accepted, one note each
// (reoriented tets, vertices at the position of another, an overlap check cut short,
// dropped vertices), in words that agree with the counts.
std::vector<std::string> validation_notes(const ValidationReport& report);

// The reader's notes (info.notes), and, unless the caller writes the surface groups
// again (`surfaces_written`), one that the file's surface elements were not kept as
// elements.
std::vector<std::string> reader_notes(const ReadInfo& info, bool surfaces_written);

bool load_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info,
               bool surfaces_written = false);

// Whether `path` ends in `extension` (lower case, with the dot), ignoring case.
bool has_extension(const std::string& path, const char* extension);

// A collapse history file (tetlod simplify --history, the viewer's save), by its
// extension: .tlh, in any case.
bool is_history_path(const std::string& path);

// Checks, before any work, that `path` can be written as a mesh (a known extension,
// and one that can hold what `options` asks for); if not prints "tetlod <command>:
// ..." and returns false (a usage error).
// `flag`: how the output was given, for the message ("" for convert's positional OUT).
bool mesh_output_path_ok(const std::string& path, const char* command,
                         const WriteOptions& options = {}, const char* flag = "-o");

// Checks, before any work, that the directory `path` goes in can be written
// (check_output_directory(), core/io/output_files.h); if not prints the error and
// returns false (bad input: exit 1, as the failed write would have been).
bool output_directory_ok(const std::string& path, bool make_directories = false);

// Writes `mesh` to `path` with `options` as stage_mesh() (core/io/mesh_io.h). Once
// the files are committed, print_staged_mesh_notes() prints the surface groups
// written, a line "surface groups (tag name: triangles): 5 boundary_1: 1200, ...",
// and, on stderr, a note when a TetGen .face file beside the .node/.ele written
// without surface groups was already there (stage_mesh() replaces it by
// this mesh's faces without markers).
struct StagedMesh {
  SurfaceGroups groups;  // group_surface(mesh) when asked for
  bool has_groups = false;
  std::string stale_face;  // the .face left beside a TetGen pair, or ""
};
// `patches`: the input file's surface groups, written under their own names and tags,
// with their triangles inside a material (group_surface() with them and `inside`:
// `mesh` is the input, or made from it by simplify() and improve_mesh() with them), or
// null. `face_neighbors`: those of `mesh`'s tets if the caller has them
// (ReadInfo::face_neighbors), or null.
Status stage_output_mesh(OutputFiles* files, const std::string& path, const TetMesh& mesh,
                         WriteOptions options, StagedMesh* staged,
                         const SurfacePatches* patches = nullptr,
                         const std::vector<uint32_t>* face_neighbors = nullptr);

// Prints a note for each input surface group (SurfacePatches of the input) that
// cannot be written as it is: some of its triangles are in a smaller group, or are
// not faces of the mesh (those inside a material are written).
void print_patch_notes(const SurfacePatches& patches, const char* command);
void print_staged_mesh_notes(const StagedMesh& staged);

// A collapse history file opened to read levels from.
struct OpenedHistory {
  OpenedHistory() = default;
  OpenedHistory(const OpenedHistory&) = delete;  // `lod` points into `history`
  OpenedHistory& operator=(const OpenedHistory&) = delete;
  std::string path;
  CollapseHistory history;
  std::optional<SimplifyParams> params;  // the thresholds saved with it, if any
  std::vector<MaterialName> names;       // the material names saved with it, if any
  SurfacePatches patches;                // the input's surface groups saved with it, if any
  std::unique_ptr<Lod> lod;              // over `history`, from its base mesh
};

// Reads the history at `path`; on failure prints "tetlod <command>: <message>" to
// stderr and returns false.
bool open_history(const std::string& path, const char* command, OpenedHistory* opened);

// The level at `step` (clamped to the last), validated as a mesh file is (a forged
// history could make tets overlap); on failure prints "tetlod <command>: corrupt
// history: ..." and returns false. `seek_seconds`, if given: moving the Lod there.
bool history_level(OpenedHistory* opened, const char* command, size_t step, TetMesh* level,
                   double* seek_seconds = nullptr);

// A level of a collapse history file.
struct HistoryLevel {
  TetMesh mesh;  // validated as a mesh file is (a forged history could make tets overlap)
  size_t step = 0, step_count = 0;
  double seek_seconds = 0;               // moving the Lod from step 0 to `step`
  std::optional<SimplifyParams> params;  // the thresholds saved with the history, if any
  std::vector<MaterialName> names;       // the material names saved with it, if any
  SurfacePatches patches;                // the input's surface groups saved with it, if any
};

// Reads the history at `path` and extracts step `step` (clamped to the last) if
// step >= 0, else the step nearest `elements` elements if elements >= 0, else the
// last step. On failure prints "tetlod <command>: <message>" to stderr and returns
// false.
bool load_history_level(const std::string& path, const char* command, long long step,
                        long long elements, HistoryLevel* level);

// Whether the level nearest N elements (at `step`, with `tets`) is the last or the
// first only because N lies beyond the history's levels (N < 0: no target).
enum class BeyondLevels { kNo, kPastTheLast, kBeforeTheFirst };
BeyondLevels beyond_levels(long long elements, size_t step, size_t step_count, size_t tets);
// For the level a command wrote for --elements N: "the last: no level has fewer
// elements ..." or "the first: ... more ..." when N lies beyond the history, else "".
std::string beyond_levels_note(long long elements, size_t step, size_t step_count, size_t tets);

// Prints the Table I rows (whole mesh, then each material) as an aligned table; with
// `names` (ReadInfo::material_names) a last column names the materials that have one.
void print_property_table(const MeshStats& stats, const std::vector<MaterialName>* names = nullptr);
// "material 2 (arm) -14.6 %, ..." for each material whose volume changed from `before` to
// `after` by more than kVolumeNotePercent of its own, "" if none: the tolerance lets
// boundaries and interfaces move, which thins (or thickens) a part a few tolerances thick.
inline constexpr double kVolumeNotePercent = 1;
std::string volume_changes(const std::vector<MaterialVolume>& before,
                           const std::vector<MaterialVolume>& after,
                           const std::vector<MaterialName>* names);

// "'port' -18.1 %, ..." for each of the input's surface groups (`patches`) whose area
// on `after` differs from that on `before` by more than kVolumeNotePercent, "" if none
// (or no groups): a port or a boundary condition's surface shrinks where the tolerance
// lets its border move; the volume note does not tell.
std::string group_area_changes(const TetMesh& before, const TetMesh& after,
                               const SurfacePatches& patches);

// The materials thinner than kThinLayerTolerances times `tolerance` (twice their volume
// over their surface's area, material_surfaces()), as "material 9 (barrier) about 0.3
// thick, ..." ("" if none; at most five named, then how many more): boundaries and
// interfaces may move by up to the tolerance, a large part of such a layer, and its
// volume may hardly change (both sides move), so the volume note does not tell.
inline constexpr double kThinLayerTolerances = 4;
std::string thin_materials(const std::vector<MaterialSurface>& surfaces, double tolerance,
                           const std::vector<MaterialName>* names);

// The input file's name of material m ("" if none); `names` may be null.
std::string material_name_of(const std::vector<MaterialName>* names, int32_t m);

// Where an option takes a material, its name in the input is taken too
// ("--conductor inner_conductor=1"): options are read before the mesh, so a name is
// kept as written and looked up here once the mesh is read. The id of the material
// named `name` (exactly, else ignoring ASCII case if only one matches); if there is
// none, prints "tetlod <command>: <option>: ..." listing the names and returns false.
bool material_by_name(const std::string& name, const std::vector<MaterialName>& names,
                      const char* command, const std::string& option, int32_t* id);
// The same lookup without printing: on failure *why says so and lists the names.
bool find_material(const std::string& name, const std::vector<MaterialName>& names, int32_t* id,
                   std::string* why);
// Whether `text`, where an option takes a material, is a name for material_by_name():
// not empty and not a whole number (an id, or a negative number refused as one).
// "2 pole magnet" is a name, and so is "1.5" (which no mesh names: refused by name).
bool is_material_name(const std::string& text);
// The items of a ','-separated list, each without leading and trailing blanks (as
// typed: "phase A=12, phase B=12"); "\\," is a comma inside an item (a name may have
// one: "Cu (OFHC)\\, 20 C").
std::vector<std::string> split_items(const std::string& text);
// The items "M=X" of such a list (`separator` '=', or ':' in viewer scripts), where a
// piece between commas without the separator is joined to the next, so that a name
// with a comma needs no escape: "Cu (OFHC), 20 C=0.3,air=5" is two items. A last
// piece without one is an item of its own, and an empty piece (a comma at either end,
// two in a row) an empty item, for the caller's error.
std::vector<std::string> split_value_items(const std::string& text, char separator);
// An item "M=X" of such a list (`separator` '=', or ':' in viewer scripts): the text
// before the last separator (a name may hold one, a number does not) into `material`,
// and the number after it into `value`. False if there is no separator or the value
// is no finite number (`material` is set all the same).
bool split_material_value(const std::string& item, char separator, std::string* material,
                          double* value);
// What an empty item in a comma-separated list is called in messages.
extern const char* const kEmptyItem;
// "1,copper,3", where an option takes materials: ids into `ids`, names into `names`
// (both cleared first). What is wrong, or "": an empty item, a number that is not an id.
std::string parse_materials(const std::string& text, std::vector<int32_t>* ids,
                            std::vector<std::string>* names);

// The input's surface groups a list names (`text`: "all", or tags and names with
// commas between, a comma inside a name written \,), as indices into
// patches.groups(), increasing and distinct. What is wrong, or "": an empty item, a
// group the input does not have (with those it has).
std::string find_surface_groups(const std::string& text, const SurfacePatches& patches,
                                std::vector<uint32_t>* groups);

// Escapes a string for a JSON string literal (without the quotes).
std::string json_escape(const std::string& text);

}  // namespace tetlod::app
