// Flags shared by `tetlod render` and `tetlod report`: what to show, how, from
// where; plus opening the offscreen renderer with clear errors.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/simplify_options.h"
#include "render/gl_context.h"
#include "render/renderer.h"
#include "render/snapshot.h"

namespace tetlod::app {

struct RenderOptions {
  render::SnapshotSettings snapshot;
  std::vector<int32_t> shown_materials;   // --materials: only these (empty: all)
  std::vector<int32_t> hidden_materials;  // --hide
  // The materials of --materials and --hide given by name, for resolve_materials().
  std::vector<std::string> shown_names, hidden_names;
  std::string groups;                     // --groups: the input's surface groups to draw
  std::vector<uint32_t> surface_groups;   // those, by resolve_groups()
  bool simplify = false;                  // --simplify, or any simplifier flag
  bool simplify_beyond_elements = false;  // ... other than --elements and --improve
  SimplifyOptions simplify_options;
};

extern const char* const kRenderFlagsHelp;

// For an input that is a collapse history (already simplified), simplifier flags
// other than --elements and --improve (which uses the history's saved thresholds:
// history_improve_params()) are a usage error: false, with a message to stderr that
// names the file and says which flags choose its levels (`choose`).
bool history_flags_ok(const std::string& in, const char* command, const RenderOptions& options,
                      const char* choose);

// The thresholds to improve a level of the history `in` with: those saved in it
// (`saved`); if it has none, prints "tetlod <command>: ..." and returns false (a
// usage error: it was saved before 2026-11-24, use 'tetlod lod --improve --size ...').
bool history_improve_params(const std::string& in, const char* command,
                            const std::optional<SimplifyParams>& saved);

// Parses one view flag at args[*i] (see kRenderFlagsHelp) or a simplifier flag.
OptionResult parse_render_option(const Args& args, size_t* i, const char* command,
                                 RenderOptions* options);

// Turns --materials / --hide into the filter's hidden list for `mesh`, whose
// materials have `names` (the input's). False with a message if a material given by
// id or name is not in the mesh.
bool resolve_materials(const TetMesh& mesh, const std::vector<MaterialName>& names,
                       const char* command, RenderOptions* options);

// Resolves --groups against `patches`, the input's surface groups. False with a
// message if it names a group the input does not have.
bool resolve_groups(const SurfacePatches& patches, const char* command, RenderOptions* options);
// Sets `renderer`'s surface groups to those of --groups on `mesh` (none without it),
// and returns them (their triangles on `mesh`, and how many are drawn).
std::vector<render::GroupOverlay::Group> show_surface_groups(render::Renderer* renderer,
                                                             const render::PreparedMesh& mesh,
                                                             const SurfacePatches& patches,
                                                             const RenderOptions& options);

// Notes on stderr the groups of show_surface_groups() that have no face drawn.
void note_undrawn_groups(const char* command,
                         const std::vector<render::GroupOverlay::Group>& groups);

// An offscreen context with an initialised renderer.
struct OffscreenRenderer {
  std::unique_ptr<render::GlContext> context;
  std::unique_ptr<render::Renderer> renderer;
};
// False with "tetlod <command>: ..." on stderr if no context can be made.
bool open_offscreen_renderer(const char* command, OffscreenRenderer* out);

// The mesh `options` asks for: `input` itself or, with --simplify, the simplified
// mesh (or the level nearest --elements); --simplify needs a size, checked before.
// 0, or the exit code with a message on stderr: kExitUsage for a --material-size the
// mesh has no material for, kExitBadInput if the simplifier refuses the mesh.
// `patches`: the input file's surface groups, whose borders the simplifier keeps (as
// `tetlod simplify` does), or null.
int simplified_mesh(const TetMesh& input, const std::vector<MaterialName>& names,
                    const char* command, RenderOptions* options, TetMesh* out,
                    const SurfacePatches* patches = nullptr);

}  // namespace tetlod::app
