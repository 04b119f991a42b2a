// The simplifier's command-line flags, shared by `simplify`, `render --simplify`
// and `report`, and the flags of how a mesh is written, shared by `convert`,
// `simplify` and `lod`, so every command reads them the same way.
#pragma once

#include <memory>
#include <string>

#include "app/commands.h"
#include "core/improve.h"
#include "core/io/mesh_io.h"
#include "core/simplify.h"

namespace tetlod::app {

struct SimplifyOptions {
  SimplifyParams params;
  bool size_given = false;       // --size, --material-size or --size-field
  bool tolerance_given = false;  // else 1e-3 x the bounding-box diagonal
  long long elements = -1;       // --elements N, or -1
  bool improve = false;          // --improve: improve_mesh() on the level written
  // --material-size items that name their material ("copper=2"): added to
  // params.sizing by finish_simplify_options(), once the names are read.
  std::vector<std::pair<std::string, double>> named_material_sizes;
  // --size-map FILE: read by finish_simplify_options() into params.sizing.map, with its
  // sizes at the vertices of --size-map-mesh MESH if given (a background mesh: the mesh
  // an analysis was solved on, say), else at the input's.
  std::string size_map_path, size_map_mesh_path;
};

// The flag lines of the usage text (the thresholds and sizing, without --elements).
extern const char* const kSimplifyFlagsHelp;

enum class OptionResult {
  kNotMine,  // args[*i] is not a simplifier flag
  kParsed,   // consumed (with its value; *i is left on the last consumed argument)
  kError,    // a message went to stderr prefixed with "tetlod <command>: "
};

// Parses one simplifier flag at args[*i] (--size --stretch --valence --tolerance
// --crease-angle --no-subdivide --material-size --size-field --size-map
// --size-map-mesh --elements --improve).
OptionResult parse_simplify_option(const Args& args, size_t* i, const char* command,
                                   SimplifyOptions* options);

// The flag lines of the usage text of the write flags.
extern const char* const kWriteFlagsHelp;

// Parses one flag of how the output mesh is written at args[*i]: --msh-version
// 2.2|4.1, --surfaces (WriteOptions::surface_groups).
OptionResult parse_write_option(const Args& args, size_t* i, const char* command,
                                WriteOptions* options);

// Reads "--flag VALUE": false with a message if VALUE is missing (or is another
// option, "--..." or "-o": "-o --size 5" lacks its file).
bool parse_option_value(const Args& args, size_t* i, const char* name, std::string* value);
// (An option given twice, an output among them, is refused before any command reads
// its options: normalize_args(), cli_util.h.)

// Fills in the defaults that depend on the input (the tolerance), looks up the
// materials --material-size names in `names` (the input's), and checks that every
// material of --material-size is in the input: false, with a message to stderr
// prefixed with "tetlod <command>: ", if one is not (a mistyped id would otherwise
// be ignored without a word).
// Reads a size map over `mesh` from the Medit .sol file at `path` (core/io/sol.h): one
// size a vertex of the file `mesh` was read from (`read`, its validation, maps them to
// the vertices the reader kept; null: none was dropped). Errors name the file, and the
// mesh as `mesh_name` ("the input").
Status read_size_map(const std::string& path, const TetMesh& mesh, const ValidationReport* read,
                     std::shared_ptr<const SizeMap>* map,
                     const std::string& mesh_name = "the input");

// A note if vertices of `input` lie outside `background`'s bounding box (a size map's
// background mesh over another domain, or in other units), else "".
std::string outside_background_note(const TetMesh& input, const TetMesh& background,
                                    const std::string& background_name);

// With --size-map, it reads the file and builds params.sizing.map over `input`;
// `read`, the input's validation (if it was read from a file), maps the file's sizes
// to the vertices the reader kept.
int finish_simplify_options(const TetMesh& input, const std::vector<MaterialName>& names,
                            const char* command, SimplifyOptions* options,
                            const ValidationReport* read = nullptr);

// The size threshold in words: "12", "12, less where the local sizing asks", or
// "from the local sizing" (no uniform size: --material-size or --size-field alone), or
// "no limit" (no size at all: `stats` with thresholds but no size).
std::string describe_size(const SizingField& sizing);

// "size 12, stretch 0.15, valence 25, tolerance 0.05" (", no subdivision", ",
// crease angle 30" when not the defaults); without the tolerance for what does not use
// it (improve.h).
std::string describe_thresholds(const SimplifyParams& params, bool with_tolerance = true);

// "tolerance 3, stretch 12, size 0, valence 5, topology 2": a run's rejected
// evaluations by reason, as simplify and report print them.
std::string describe_rejections(const RejectionCounts& r);
// "2 tets below the stretch, 0 above the size, 1 node above the valence (of these tets
// and nodes, 0 new: ...)": what a run's final mesh still breaks.
std::string describe_violations(const ThresholdViolations& v);
// "N tets below the stretch, N above the size, N nodes above the valence" ("1 tet",
// "1 node").
std::string describe_breaks(const ThresholdCounts& b);

}  // namespace tetlod::app
