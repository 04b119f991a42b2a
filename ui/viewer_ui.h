// The viewer's Dear ImGui panels (issue 5). Panels read a ViewerStatus the app fills
// in each frame, edit plain settings structs, and emit Commands; they make no GL
// calls and own no model state, so UI state and model state never need syncing
// (the pattern of imgui's example_glfw_opengl3).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/electrostatics.h"
#include "core/improve.h"
#include "core/mesh_stats.h"
#include "core/simplify.h"
#include "core/size_map.h"
#include "render/colormap.h"
#include "render/renderer.h"

namespace tetlod::ui {

enum class CutAxis { kX = 0, kY = 1, kZ = 2 };

// How the displayed level is shown. The app turns it into a render::SurfaceFilter
// (which needs a surface rebuild when it changes) and render::DrawSettings (which
// does not).
struct ViewSettings {
  render::ColorMode color_mode = render::ColorMode::kStretch;
  render::ColorMap color_map = render::ColorMap::kViridis;
  float range_min = 0, range_max = 1;  // stretch at the ends of the colour map
  // Field mode: the colour map spans [0, this percentile of |E| over the solved tets]
  // (100: the maximum). Below 100 a few singular tets at conductor edges do not wash
  // out the rest (on the bundled motor the maximum is 1.6 times the 99th percentile,
  // and most of the picture is dark at the maximum).
  float field_percentile = 99;
  bool wireframe = false;
  bool legend = true;
  bool cut = false;
  CutAxis cut_axis = CutAxis::kX;
  float cut_offset = 0;                   // position along the axis, model units
  bool cut_flip = false;                  // keep the other side
  std::vector<int32_t> hidden_materials;  // sorted
  // The input's surface groups drawn over the surface (indices into
  // ViewerStatus::surface_groups), sorted.
  std::vector<uint32_t> shown_groups;
  bool highlight = false;
  float highlight_below = 0.2f;  // tets with stretch below this are highlighted
};

// The panel's Sizing choices, in its order (kMap offered only with a size map).
// kRegionAndMaterial: region rules and per-material sizes together, as `tetlod
// simplify --size-field ... --material-size ...` (the smallest applies).
enum class SizingMode {
  kUniform = 0,
  kRegion = 1,
  kPerMaterial = 2,
  kRegionAndMaterial = 3,
  kMap = 4
};
inline bool uses_region(SizingMode m) {
  return m == SizingMode::kRegion || m == SizingMode::kRegionAndMaterial;
}
inline bool uses_material_sizes(SizingMode m) {
  return m == SizingMode::kPerMaterial || m == SizingMode::kRegionAndMaterial;
}

// The four thresholds of the paper (tau_TL, tau_SZ, tau_ST, tau_VL) and the sizing,
// as doubles, so that a value typed here or set by a script gives the run `tetlod
// simplify` makes with it.
struct ThresholdSettings {
  double tolerance = 0.05;  // tau_TL, model units
  double size = 10.0;       // tau_SZ, uniform mode (and the cap in the other modes)
  double stretch = 0.15;    // tau_ST
  int valence = 25;         // tau_VL
  SizingMode sizing_mode = SizingMode::kUniform;
  std::string region_spec;  // uses_region(): the syntax of core/sizing.h parse_size_field()
  std::vector<std::pair<int32_t, double>> material_sizes;  // uses_material_sizes()
  // uses_material_sizes(): `size` also caps every material (as --size with
  // --material-size); off, a material without a size of its own (or of a region rule)
  // has no size limit. (kRegion and kMap always cap with `size`.)
  bool material_cap = false;
  // kMap: sizes at the input's vertices (`tetlod view FILE --size-map S.sol`, or saved in
  // the history opened), with `size` as a cap; the mode is offered only with one.
  std::shared_ptr<const SizeMap> size_map;
  std::string size_map_name;  // where it came from, for the panel
  bool subdivide = true;
  // Dihedral angle (degrees) above which a boundary or interface edge is a feature
  // curve, kept as one (--crease-angle; core/classify.h).
  double crease_angle = SimplifyParams{}.crease_angle_degrees;
  // The input's surface groups inside a material (a sheet, a port inside the air):
  // kept as they are, faces of every level, so that Save can write them (as `tetlod
  // simplify --surfaces` keeps them); off, coarsened like the rest of the material,
  // and not written (as `tetlod simplify` without --surfaces or --history).
  bool keep_inside_groups = true;
};

// Turns the settings into core parameters. False with a message naming every bad
// value, joined by "; " (a region spec that does not parse, a size <= 0, a stretch
// outside (0, 1), a valence below 4, ...).
bool to_simplify_params(const ThresholdSettings& settings, SimplifyParams* params,
                        std::string* error);
// The range of a threshold slider (ImGui's SliderScalar over doubles).
struct SliderRange {
  double min = 0, max = 1;
};
// The size and tolerance sliders follow the loaded model's extent, its bounding-box
// `diagonal` (model units), on a logarithmic scale, so that a model in metres and one a
// million times larger are equally easy to set: size from diagonal / 10^4 to the
// diagonal, tolerance from diagonal x 10^-7 to diagonal / 10. Each range is widened to
// hold `current` (a default, a history's or a script's value), so that showing it
// never moves it; a value typed with ctrl-click is clamped to the range. A diagonal
// that is not > 0 (no mesh, a flat one) is taken as 1.
SliderRange size_slider_range(double diagonal, double current);
SliderRange tolerance_slider_range(double diagonal, double current);
// The printf format of a logarithmic slider over `range`: "%.4g", or more digits where
// the range starts below 10^-4, since ImGui's logarithmic slider takes values below
// 10^-(the format's digits) as zero (a tolerance slider from 1e-8 with "%.4g" could not
// go below 1e-4). `prefix` goes before the number ("cap ").
std::string log_slider_format(const SliderRange& range, const std::string& prefix = "");

// The reverse, for the panel to show the thresholds a history was made with: the
// settings that give `params` back. False, leaving `settings`
// alone, where the panel cannot hold them: a size map with region rules or material
// sizes.
bool from_simplify_params(const SimplifyParams& params, ThresholdSettings* settings);

// Whether the panel's settings give the run `run` was made with (the same thresholds
// and sizing; false where the settings do not make parameters at all).
bool same_thresholds(const ThresholdSettings& settings, const SimplifyParams& run);

// The Analysis panel's set-up (issue 6): an electrostatic problem over the materials
// of the loaded mesh (core/electrostatics.h).
enum class MaterialRole { kDielectric = 0, kConductor = 1, kGround = 2 };
struct MaterialAnalysis {
  int32_t material = 0;
  MaterialRole role = MaterialRole::kDielectric;
  double potential = 1;     // kConductor
  double permittivity = 1;  // kDielectric (conductors and ground hold every node fixed)
};
// An input surface group's part (a Gmsh physical surface as a port or a boundary):
// free (kDielectric: its nodes are not held), or its nodes held as a conductor's or a
// ground's (`tetlod solve --conductor NAME=V`).
struct GroupAnalysis {
  MaterialRole role = MaterialRole::kDielectric;
  double potential = 1;  // kConductor
};
struct AnalysisSettings {
  std::vector<MaterialAnalysis> materials;  // by id, one per material of the loaded mesh
  std::vector<GroupAnalysis> groups;        // one per ViewerStatus::surface_groups
  bool ground_boundary = false;             // hold the outer boundary at 0 too
};

// The problem the settings describe, but for the surface groups (whose nodes depend on
// the level: the viewer adds them). It is not checked here: the solver's own checks
// give the messages the panel shows (no conductor, a conductor touching the ground,
// eps <= 0, ...).
ElectrostaticsProblem to_electrostatics_problem(const AnalysisSettings& settings);
// The settings of a problem (the script's 'analysis' line): materials in `materials`
// that the problem does not name become dielectrics of permittivity 1.
AnalysisSettings analysis_settings_from(const ElectrostaticsProblem& problem,
                                        const std::vector<int32_t>& materials);

enum class CommandKind {
  kOpen,          // path
  kSimplify,      // with the current ThresholdSettings
  kCancel,        // the running simplification
  kJumpElements,  // value: target number of elements
  kFit,           // fit the camera to the shown materials, from the current direction
  kAxisView,      // value: 0 iso, 1 x, 2 y, 3 z
  kSave,          // path: the displayed level; value: kSaveImproved | kSaveSurfaces | kSaveBinary
  kScreenshot,    // path, width, height (0: window size), with_ui
  kSolve,         // the displayed level, with the current AnalysisSettings
  kCancelSolve,
};

// The bits of a kSave command's value.
inline constexpr long long kSaveImproved = 1;  // improve the shapes first (improve.h)
inline constexpr long long kSaveSurfaces = 2;  // with surface groups (WriteOptions)
inline constexpr long long kSaveBinary = 4;    // .msh, .vtk, .vtu in binary (WriteOptions)

struct Command {
  Command() = default;
  Command(CommandKind kind_in, std::string path_in = {}, long long value_in = 0)
      : kind(kind_in), path(std::move(path_in)), value(value_in) {}

  CommandKind kind = CommandKind::kFit;
  std::string path;
  long long value = 0;
  int width = 0, height = 0;
  bool with_ui = false;
};

// Editable state of the panels themselves (text fields, the scrubber target).
struct PanelState {
  char open_path[1024] = "";
  std::vector<std::string> recent_files;  // most recent first
  long long target_step = 0;              // the LOD scrubber; the app follows it
  int jump_elements = 0;
  bool jump_editing = false;  // the box of elements has the keyboard
  size_t jump_synced = 0;     // the elements at the target step it last followed
  char save_path[1024] = "level.mesh";
  bool save_improved = false;  // improve the level's shapes before saving (improve.h)
  bool save_surfaces = false;  // with the boundary and interface triangles (surface.h)
  bool save_binary = false;    // .msh, .vtk and .vtu in binary
  char screenshot_path[1024] = "screenshot.png";
  int screenshot_size[2] = {0, 0};  // width, height; 0: the 3D view's size
  bool output_used = false;  // Save or Screenshot clicked last: the Output section says how it went
  bool screenshot_ui = false;
  bool show_stats = true;
  bool panel_collapsed = false;  // the side panel folded to its title bar: the 3D view widens
};

// What the panels show, filled in by the app each frame.
struct ViewerStatus {
  std::string mesh_name;  // path of the loaded mesh ("" if none)
  size_t input_tets = 0, input_vertices = 0;
  std::vector<int32_t> materials;  // ids present in the input
  // Triangles of the input's surface groups inside a material (0: none, and the
  // Thresholds panel does not offer to keep them).
  size_t inside_group_triangles = 0;
  // The input file's names of its materials (a Gmsh physical volume's, an Abaqus
  // section's), sorted by id; materials without a name are not listed.
  std::vector<MaterialName> material_names;
  float bounds_min[3] = {0, 0, 0}, bounds_max[3] = {1, 1, 1};  // of the input
  std::string load_error;  // last failed load or action, shown until replaced
  // The last Simplify's error (bad thresholds, or the run's), in the panel's words
  // (simplify_error_text()), shown under the Simplify button until the next run or
  // another mesh.
  std::string simplify_error;
  std::string message;  // last success message (saved, screenshot, ...)
  // What the reader noted of the loaded file (repairs, what it does not keep, names),
  // until another is loaded.
  std::vector<std::string> load_notes;
  // The input file's surface groups (Gmsh physical surfaces, ...; SurfacePatches::
  // groups(), in order): the View section offers to draw them.
  struct SurfaceGroupItem {
    std::string label;  // its name, or "surface <tag>"
    int32_t tag = 0;
    size_t triangles = 0;  // of the input
  };
  std::vector<SurfaceGroupItem> surface_groups;
  bool loading = false;
  std::string loading_path;
  // The thresholds opening the mesh set (the viewer's defaults for it).
  double default_size = 0, default_tolerance = 0;
  bool default_size_raised = false;  // above 3 x the median tet size (a graded mesh)

  // Simplification: running state and the last result.
  bool running = false;
  std::string phase;
  bool past_valence_run = false;  // the phase is a run past the valence's (simplify.h)
  double phase_fraction = 0;
  std::string other_phase;  // where the run past the valence alongside is ("" if none)
  double other_fraction = 0;
  size_t collapses = 0;
  double collapses_per_second = 0;
  double elapsed_seconds = 0;
  bool has_result = false;               // a run in this session (its statistics below)
  bool from_history = false;             // the levels are a history file's (no run statistics)
  std::string history_thresholds;        // the thresholds saved with it, in words; "" if none
  bool thresholds_from_history = false;  // opening it set the panel to them
  bool result_cancelled = false;
  RejectionCounts rejections;
  size_t splits = 0;
  bool subdivided = true;  // the last run subdivided first
  double simplify_seconds = 0;
  ThresholdViolations violations;  // of the last run's final mesh
  // The thresholds the last run was made with, in words ("size 23, stretch 0.15, valence
  // 25, tolerance 0.05"), and whether the panel's have changed since (then what the
  // final mesh breaks is not of the panel's).
  std::string result_thresholds;
  bool result_thresholds_changed = false;
  ThresholdCounts input_breaks;   // what its input broke of the same thresholds
  std::string above_size_reason;  // why it has tets above the size ("" if none)
  std::string past_valence;       // what subdivision past the valence did ("" if nothing)
  std::string volume_changes;     // materials whose volume the run changed by over 1 % ("")
  std::string area_changes;       // surface groups whose area it changed by over 1 % ("")
  // The run past the valence was given up while faces inside a material were kept.
  bool kept_faces_stopped_past_valence = false;
  std::string thin_materials;  // materials a few of its tolerances thick ("")

  // The displayed level.
  size_t step = 0, step_count = 0;
  size_t elements = 0;            // tets alive at `step`
  size_t elements_at_target = 0;  // at the scrubber's target
  size_t elements_at_end = 0;     // after the last collapse
  size_t visible_tets = 0, drawn_triangles = 0;
  bool drawing = false;  // the surface is being built anew (a far move, a new cut or filter)

  // Statistics of a level (possibly an older one while a new one is computed).
  bool has_stats = false;
  size_t stats_step = 0;
  MeshStats stats;
  std::string stats_breaks;  // what that level breaks of the run's thresholds ("" if nothing)

  // The Analysis panel.
  struct Analysis {
    bool solving = false;
    std::string solving_what;  // "displayed level" or "finest level"
    std::string phase;
    double fraction = 0;
    int iteration = 0;
    double elapsed_seconds = 0;
    std::string error;  // of the last solve, shown until the next one
    bool has_solution = false;
    // No solution of this mesh, but one of the mesh before: why it no longer applies
    // ("the mesh was simplified again", ...) and what it gave.
    std::string superseded;
    double earlier_capacitance = 0;
    size_t earlier_tets = 0;
    bool stale = false;          // the displayed level (or mesh) is not the solved one
    bool setup_changed = false;  // the panel's set-up is not the solved one
    size_t solved_step = 0, solved_tets = 0, unknowns = 0;
    double capacitance = 0, energy = 0, voltage = 0;
    bool direct = false;
    int iterations = 0;
    double residual = 0, seconds = 0;
    float field_max = 0, field_range_max = 0;  // |E|: the maximum, the legend's top
    bool has_finest = false;
    double finest_capacitance = 0;
    bool finest_is_displayed = false;  // the solved level is the finest one
  } analysis;

  // Frame time, smoothed.
  double fps = 0, frame_ms = 0;
  double scene_scale = 1;  // resolution factor of the 3D view this frame
};

// The part of the window left for the 3D view beside the side panel (unless it is folded)
// and above the level-of-detail and statistics strips, in ImGui's coordinates (pixels from the top
// left).
struct ViewRect {
  float x = 0, y = 0, width = 0, height = 0;
};
ViewRect scene_rect(float display_width, float display_height, const PanelState& panel);

// The texts of a run's progress bars, which draw_viewer_panels() shows:
// - the bar at the top of the panel, always in sight and short enough for its width
//   ("simplifying: evaluate edges 69%", "simplify 6%, 19958 collapses", "past the
//   valence: red levels 50%");
// - the bar in the Thresholds section, whose collapses are on the line below it
//   ("evaluate edges 69%", "past the valence: valence collapses 20%");
// - the bar under either for the run past the valence made alongside on a second
//   thread ("past the valence: red levels 50%"; "" when there is none).
std::string top_progress_text(const ViewerStatus& status);
std::string section_progress_text(const ViewerStatus& status);
std::string other_run_progress_text(const ViewerStatus& status);

// After a run, what its final mesh still breaks of the run's thresholds and what the
// input broke ("Final mesh, for the run's thresholds (size 23, stretch 0.15, ...): 4
// tets below the stretch, ...; the input: 6 tets below the stretch, ..."), as the
// Thresholds section says it; once the panel's thresholds differ from the run's it
// says so ("..., not the panel's, changed since: ...").
std::string final_mesh_text(const ViewerStatus& status);

// The stretch colour range's ends, each in [0, 1], kept at least 0.01 apart (the legend's
// two decimals; a script's 'range' and render's --range refuse equal ends): the panel's
// range allowed MIN = MAX, a legend "0.20 stretch 0.20".
void keep_range_apart(float* low, float* high);

// The level-of-detail strip's text while there are no levels: "Simplify to get a
// collapse history (N elements).", or, after a run or a history without a collapse
// (a Simplify would give none either), that the thresholds allowed none.
std::string no_history_text(const ViewerStatus& status);

// What a failed open leaves running, said after its error ("...; the running solve goes
// on"): "" when nothing runs.
std::string still_running_text(bool simplification, bool solve);

// A simplifier's error as the panel shows it: where it names a command-line flag, the
// panel's own control instead ("... or --no-subdivide" becomes "... or untick
// \"Subdivide first\" above").
std::string simplify_error_text(const std::string& message);
// The same for a script, in its words ("... or 'thresholds subdivide=0'").
std::string script_error_text(const std::string& message);

// Draws every panel. `commands` receives what the user asked for this frame.
void draw_viewer_panels(const ViewerStatus& status, ViewSettings* view,
                        ThresholdSettings* thresholds, AnalysisSettings* analysis,
                        PanelState* panel, std::vector<Command>* commands);

// Dear ImGui's default font has Latin-1 only. Names from mesh files (a "mu-metal" with a
// Greek mu, Cyrillic or Polish names) need more: add_name_glyphs() adds the default font and
// merges into it the Latin Extended-A/B, Greek and Cyrillic glyphs of the TrueType
// font at `path` (kNameGlyphFont: DejaVu Sans, Debian's fonts-dejavu-core, which
// scripts/setup.sh installs), to the current context's atlas, before its first frame.
// False, with the default font alone, if the file cannot be read.
inline constexpr const char* kNameGlyphFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
bool add_name_glyphs(const std::string& path);

}  // namespace tetlod::ui
