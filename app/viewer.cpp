// The viewer's frame loop, in the order of imgui's example_glfw_opengl3: window and
// context, renderer, ImGui (context, GLFW backend, OpenGL3 backend); each frame:
// events, finished background work, ImGui frame, camera input (only when ImGui does
// not want the mouse), the scripted action if any, the panels, their commands, the
// scrubber, then draw the scene, the panels, swap. Shut down in reverse, cancelling
// and joining the worker first.
//
// Threads: the UI thread owns the window, the GL context, the Lod and its
// LodSurface. One worker at a time loads a file or simplifies (core's simplify()
// with a progress callback and a cancel flag) and also builds the next Scene (Lod
// at its first displayed step + LodSurface), so swapping a result in costs one
// upload. Statistics of a level and saving a level run in std::async tasks on a
// compacted copy of it. The Analysis panel's electrostatic solves run in their own
// worker (SolveJob), on a compacted copy of the displayed level, and then (once per
// mesh and set-up) on the finest level; the field |E| comes back per tet id of the
// Lod and colours the surface while the displayed level is the solved one.
#include "app/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <unistd.h>

#include "app/cli_util.h"
#include "app/commands.h"
#include "app/orbit_camera.h"
#include "app/simplify_options.h"
#include "core/adjacency.h"
#include "core/electrostatics.h"
#include "core/improve.h"
#include "core/io/mesh_io.h"
#include "core/io/output_files.h"
#include "core/lod.h"
#include "core/mesh_stats.h"
#include "core/metrics.h"
#include "core/simplify.h"
#include "core/sizing.h"
#include "core/validate.h"
#include "render/gl_context.h"
#include "render/group_overlay.h"
#include "render/image.h"
#include "render/lod_surface.h"
#include "render/renderer.h"
#include "ui/viewer_ui.h"

namespace tetlod::app {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Frames a second while a simplification or solve runs and nothing moves (see frame()):
// a little above the 30 the viewer must keep to while a simplification runs (issue 5),
// so that the waits' timer jitter does not take it below.
constexpr double kWorkingFps = 32;

// A loaded mesh and what is displayed of it: the LOD over the last simplification
// result, or over the input alone (an empty history) before any.
struct Scene {
  std::string path;
  std::shared_ptr<const TetMesh> input;
  std::shared_ptr<const SimplifyResult> result;  // null: no simplification yet
  std::string above_size_reason;                 // of the result ("" if nothing is above)
  std::string volume_changes;                    // of the result (cli_util.h; "" if none)
  std::string area_changes;                      // of its surface groups (likewise)
  std::string thin_materials;                    // thin for its tolerance (cli_util.h; "")
  ThresholdCounts input_breaks;                  // what the input broke of the result's thresholds
  SimplifyParams params;                         // of the result's run, if params_known
  bool params_known = false;                     // run here, or saved in the history file read
  // The input file's own surface groups (ReadInfo::surface_groups) on its surface:
  // Simplify keeps their borders, and Save's boundary groups write them. `patches`
  // are those the shown levels keep (the result's run dropped the groups inside a
  // material if the panel said so), `input_patches` all of them, for the next run.
  std::shared_ptr<const SurfacePatches> patches, input_patches;
  // The input file's names of its materials (ReadInfo::material_names), for Save.
  std::shared_ptr<const std::vector<MaterialName>> material_names;
  bool from_history = false;  // the result was read from a history file, not run here
  // Sizes at the input's vertices given with it (`--size-map`), and the file's name.
  std::shared_ptr<const SizeMap> size_map;
  std::string size_map_name;
  CollapseHistory empty_history;
  std::unique_ptr<Lod> lod;
  render::LodSurface surface;
  render::SurfaceFilter filter;  // the surface was built with this
  Vec3 lo, hi;                   // bounds of the input
  std::vector<int32_t> materials;
  // The size and tolerance opening the input sets: three times its median tet size
  // (core/sizing.h suggested_size: well above twice its typical edge, so that
  // subdivision, which splits edges above half the size, does not make a first
  // Simplify's result larger than the input) and 0.001 x its bounding-box diagonal
  // (the default of `tetlod simplify`).
  double default_size = 0, default_tolerance = 0;
  bool default_size_raised = false;  // above 3 x the median: a graded mesh (suggested_size)
};

// The bounds of the input's tets of the shown materials (`hidden` sorted), for the
// camera to frame what is on screen (as `tetlod render --view`); the whole mesh's if
// every material is hidden.
void shown_bounds(const TetMesh& mesh, const std::vector<int32_t>& hidden, Vec3* lo, Vec3* hi) {
  if (hidden.empty()) return mesh_bounds(mesh, lo, hi);
  bool any = false;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    if (std::binary_search(hidden.begin(), hidden.end(), mesh.materials[t])) continue;
    for (uint32_t v : mesh.tets[t]) {
      const Vec3& p = mesh.positions[v];
      if (!any) *lo = *hi = p;
      any = true;
      *lo = {std::min(lo->x, p.x), std::min(lo->y, p.y), std::min(lo->z, p.z)};
      *hi = {std::max(hi->x, p.x), std::max(hi->y, p.y), std::max(hi->z, p.z)};
    }
  }
  if (!any) mesh_bounds(mesh, lo, hi);
}

render::SurfaceFilter make_filter(const ui::ViewSettings& view) {
  render::SurfaceFilter filter;
  filter.hidden_materials = view.hidden_materials;
  filter.cut = view.cut;
  const double sign = view.cut_flip ? -1 : 1;
  Vec3 normal{0, 0, 0};
  (view.cut_axis == ui::CutAxis::kX   ? normal.x
   : view.cut_axis == ui::CutAxis::kY ? normal.y
                                      : normal.z) = sign;
  filter.cut_plane.normal = normal;
  filter.cut_plane.offset = sign * view.cut_offset;
  filter.highlight = view.highlight;
  filter.highlight_below = view.highlight_below;
  return filter;
}

bool same_filter(const render::SurfaceFilter& a, const render::SurfaceFilter& b) {
  return a.hidden_materials == b.hidden_materials && a.cut == b.cut &&
         (!a.cut || (a.cut_plane.normal.x == b.cut_plane.normal.x &&
                     a.cut_plane.normal.y == b.cut_plane.normal.y &&
                     a.cut_plane.normal.z == b.cut_plane.normal.z &&
                     a.cut_plane.offset == b.cut_plane.offset)) &&
         a.highlight == b.highlight && (!a.highlight || a.highlight_below == b.highlight_below);
}

// `field_max` > 0: the field |E| is on the surface, drawn over [0, field_max]; else a
// field colour mode falls back to stretch (nothing solved, or a stale solve). Sizes
// are drawn over `size_range`, the drawn faces' (render::scalar_range()).
render::DrawSettings make_draw_settings(const ui::ViewSettings& view, double field_max,
                                        std::pair<double, double> size_range) {
  render::DrawSettings draw;
  draw.color_mode = view.color_mode;
  draw.color_map = view.color_map;
  draw.range_min = view.range_min;
  draw.range_max = std::max(view.range_max, view.range_min + 1e-6f);
  if (view.color_mode == render::ColorMode::kSize) {
    draw.range_min = size_range.first;
    draw.range_max = size_range.second;
  }
  if (view.color_mode == render::ColorMode::kField) {
    if (field_max > 0) {
      draw.range_min = 0;
      draw.range_max = field_max;
      draw.field_percentile = view.field_percentile;
    } else {
      draw.color_mode = render::ColorMode::kStretch;
    }
  }
  draw.wireframe = view.wireframe;
  draw.legend = view.legend;
  draw.highlight_below = view.highlight ? view.highlight_below : 0;
  return draw;
}

bool same_draw(const render::DrawSettings& a, const render::DrawSettings& b) {
  return a.color_mode == b.color_mode && a.color_map == b.color_map && a.range_min == b.range_min &&
         a.range_max == b.range_max && a.wireframe == b.wireframe && a.legend == b.legend &&
         a.highlight_below == b.highlight_below && a.field_percentile == b.field_percentile;
}

bool same_camera(const render::Camera& a, const render::Camera& b) {
  return a.eye.x == b.eye.x && a.eye.y == b.eye.y && a.eye.z == b.eye.z &&
         a.target.x == b.target.x && a.target.y == b.target.y && a.target.z == b.target.z &&
         a.fov_y_degrees == b.fov_y_degrees;
}

// Builds a scene (on a worker thread): the Lod at its first or last step and the
// surface for `view`.
std::unique_ptr<Scene> make_scene(const std::string& path, std::shared_ptr<const TetMesh> input,
                                  std::shared_ptr<const SimplifyResult> result,
                                  const ui::ViewSettings& view) {
  auto scene = std::make_unique<Scene>();
  scene->path = path;
  scene->input = std::move(input);
  scene->result = std::move(result);
  mesh_bounds(*scene->input, &scene->lo, &scene->hi);
  const double diagonal = length(scene->hi - scene->lo);
  scene->default_size = suggested_size(*scene->input, &scene->default_size_raised);
  if (!(scene->default_size > 0)) scene->default_size = diagonal / 25;  // no tets, or flat ones
  scene->default_tolerance = 1e-3 * diagonal;
  scene->materials = scene->input->materials;
  std::sort(scene->materials.begin(), scene->materials.end());
  scene->materials.erase(std::unique(scene->materials.begin(), scene->materials.end()),
                         scene->materials.end());
  if (scene->result) {
    scene->lod = std::make_unique<Lod>(scene->result->base, &scene->result->history);
    scene->lod->seek(scene->lod->step_count());  // show the result first
  } else {
    scene->lod = std::make_unique<Lod>(*scene->input, &scene->empty_history);
  }
  scene->filter = make_filter(view);
  scene->surface.reset(render::lod_state(*scene->lod), scene->filter);
  return scene;
}

// A simplification's own time: subdivide, classify and simplify (not the display's
// set-up, make_scene()).
double run_seconds(const SimplifyResult& result) {
  return result.seconds_classify + result.seconds_subdivide + result.seconds_simplify;
}

// One background job: a load or a simplification, then make_scene().
struct Job {
  bool is_load = false;
  std::string path;
  std::string size_map_path;       // a load's --size-map, if any
  std::string size_map_mesh_path;  // and its --size-map-mesh
  std::thread thread;
  std::atomic<bool> cancel{false};
  std::atomic<bool> done{false};
  Clock::time_point start = Clock::now();
  std::mutex mutex;  // guards the fields below
  std::string phase = "starting";
  bool past_valence = false;  // SimplifyProgress::past_valence
  double fraction = 0;
  std::string other_phase;  // SimplifyProgress::other_phase ("" for none)
  double other_fraction = 0;
  size_t collapses = 0;
  std::unique_ptr<Scene> scene;
  std::string error;
  std::vector<std::string> notes;  // a load's ReadInfo notes
  bool cancelled = false;
};

// (Surfaces by name and potential: their nodes are those of the level solved.)
bool same_problem(const ElectrostaticsProblem& a, const ElectrostaticsProblem& b) {
  const auto same_surfaces = [&] {
    if (a.surfaces.size() != b.surfaces.size()) return false;
    for (size_t k = 0; k < a.surfaces.size(); ++k) {
      const auto &x = a.surfaces[k], &y = b.surfaces[k];
      if (x.name != y.name || x.potential != y.potential || x.ground != y.ground) return false;
    }
    return true;
  };
  return a.conductors == b.conductors && a.ground_materials == b.ground_materials &&
         a.ground_boundary == b.ground_boundary && a.permittivities == b.permittivities &&
         a.default_permittivity == b.default_permittivity && same_surfaces();
}

// `problem` with the nodes of its surfaces, the input's surface groups `groups` (one
// per surface, indices into patches.groups()), as they lie on `mesh` (a level). An
// error names a group with no face there.
Status hold_groups(const TetMesh& mesh, const SurfacePatches& patches,
                   const std::vector<uint32_t>& groups, ElectrostaticsProblem* problem) {
  if (groups.empty()) return Status();
  std::vector<uint32_t> neighbors;
  build_face_neighbors(mesh, &neighbors);
  const LocatedGroups located = locate_groups(mesh, patches, true, neighbors);
  for (size_t k = 0; k < groups.size(); ++k) {
    std::vector<uint32_t>& vertices = problem->surfaces[k].vertices;
    vertices.clear();
    for (uint32_t i : located.in_group[groups[k]])
      vertices.insert(vertices.end(), located.surface[i].v.begin(), located.surface[i].v.end());
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    if (vertices.empty())
      return Status::error("surface group '" + problem->surfaces[k].name +
                           "' has no face on this mesh");
  }
  return Status();
}

// One electrostatic solve of the displayed level, then (if asked) of the finest.
struct SolveJob {
  size_t generation = 0, step = 0;
  ElectrostaticsProblem problem;         // its surfaces without their nodes (hold_groups())
  std::vector<uint32_t> surface_groups;  // of problem.surfaces, in the input's
  std::shared_ptr<const SurfacePatches> patches;  // groups
  std::thread thread;
  std::atomic<bool> cancel{false};
  std::atomic<bool> done{false};
  Clock::time_point start = Clock::now();
  int line = 0;      // the script line that asked, if any
  std::mutex mutex;  // guards `what` and `progress`
  std::string what = "displayed level";
  SolveProgress progress;
  // Results, read after `done`.
  Status status;
  ElectrostaticsSolution solution;  // potential and field cleared: only the figures
  size_t tets = 0;
  std::vector<float> tet_values;    // |E| per tet id of the Lod (0 for retired tets)
  std::vector<float> sorted_field;  // |E| of the solved tets outside electrodes, ascending
  bool solve_finest = false;
  Status finest_status;
  bool has_finest = false;
  double finest_capacitance = 0;
};

// The last finished solve of the displayed level.
struct AnalysisResult {
  size_t generation = 0, step = 0, tets = 0;
  ElectrostaticsProblem problem;
  ElectrostaticsSolution solution;
  std::vector<float> tet_values, sorted_field;
};

std::filesystem::path recent_files_path() {
  const char* config = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  if (config && *config) return std::filesystem::path(config) / "tetlod" / "recent.txt";
  if (home && *home) return std::filesystem::path(home) / ".config" / "tetlod" / "recent.txt";
  return {};
}

struct FrameRecord {
  double frame_ms = 0;   // since the previous frame started, less waited_ms
  double waited_ms = 0;  // then waited to keep to kWorkingFps (see Viewer::frame())
  double scrub_ms = 0;   // seek + surface update + upload
  double draw_ms = 0;    // 3D view draw + present (CPU side: the driver may defer work)
  double ui_ms = 0;      // ImGui frame + its draw
  double swap_ms = 0;    // swap buffers
  size_t step = 0;
};

class Viewer {
 public:
  explicit Viewer(const ViewerOptions& options)
      : options_(options),
        hidden_names_(options.hidden_names),
        size_map_path_(options.size_map_path),
        size_map_mesh_path_(options.size_map_mesh_path) {
    view_.hidden_materials = options.hidden_materials;
    std::sort(view_.hidden_materials.begin(), view_.hidden_materials.end());
  }
  int run();

  void on_drop(const char* path) { dropped_.push_back(path); }
  // Keys pressed (or repeating) since the last frame, in order: a tap shorter than a
  // frame is seen (ImGui 1.86 reads the keys' state once a frame, and missed such taps).
  void on_key(int key, int action) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT) pressed_keys_.push_back(key);
  }

 private:
  bool init();
  void shutdown();
  void frame();

  // Starts loading `path`; an error (also shown in the panel) if it cannot start.
  Status start_load(const std::string& path);
  void start_simplify();
  void poll_job();
  void swap_in(std::unique_ptr<Scene> scene, bool is_load);
  void hide_by_name();
  void execute(const ui::Command& command);
  void handle_camera_input();
  void apply_view_changes();
  void start_surface_rebuild(const render::SurfaceFilter& filter);
  void follow_scrubber();
  void update_stats();
  // Draws the surface groups ticked in the View section on the level shown: built off
  // the UI thread once the level settles, none drawn while it or the view changes.
  void update_groups();
  // Analysis.
  Status start_solve(int line);
  // The Analysis panel's problem, its held surface groups' nodes left out (indices into
  // the input's groups in `groups`, if given: hold_groups()).
  ElectrostaticsProblem analysis_problem(std::vector<uint32_t>* groups = nullptr) const;
  void poll_solve();
  bool field_shown() const;  // the last solve is of the displayed level
  // The input file's names of its materials (none without a mesh or names).
  const std::vector<MaterialName>& material_names() const;
  double field_range_max() const;
  // The drawn faces' sizes, while the faces are coloured by size.
  std::pair<double, double> size_range() const;
  void sync_field_colors();
  Status report_analysis(const std::string& path) const;
  struct ViewPixels {
    int x = 0, y = 0, width = 1, height = 1;  // origin bottom left
  };
  ViewPixels view_pixels(int fb_width, int fb_height) const;
  // The view's aspect (width / height) and where its legend goes: the camera frames the
  // model clear of it.
  std::pair<double, render::LegendSpace> framing() const;
  // Frames the shown materials from `view`, or from the current direction if null,
  // clear of the legend (framing()).
  void frame_view(const render::ViewDirection* view);
  // A view nobody has moved since it was framed is framed again when the view's shape
  // or the legend's space changes (a resize, a colour mode with a key).
  void keep_framed();
  void draw_scene(int fb_width, int fb_height);
  // The tet under the pointer: the shown tet drawn at display pixel (x, y), or
  // kInvalidIndex (outside the view, over nothing). O(drawn faces).
  uint32_t tet_at(float x, float y) const;
  // What the tooltip and 'report-tet' say of a tet of the displayed level (a pass over
  // the level's tets for the valence: a few ms on 1M tets, once a pick).
  struct TetInfo {
    int32_t material = 0;
    double stretch = 0, size = 0, volume = 0;
    uint32_t valence = 0;    // the most edge neighbours of its four nodes
    double min_stretch = 0;  // the run's thresholds (0, +inf and 0: no run known)
    double max_size = std::numeric_limits<double>::infinity();
    uint32_t max_valence = 0;
    bool has_field = false;  // |E| of the last solve, which is of this level
    double field = 0;
  };
  TetInfo tet_info(uint32_t tet) const;
  // The tooltip of the tet under the pointer once it rests over the view.
  void update_hover();
  Status report_tet(const std::string& path) const;
  Status screenshot(const std::string& path, int width, int height);
  Status save_level(const std::string& path, bool improve, bool surfaces, bool binary);
  void fill_status();
  void add_recent(const std::string& path);
  void upload_all();

  // Script.
  bool settled() const;
  void run_script();
  Status run_action(const ScriptAction& action);
  void bench_frame();
  void fail_script(int line, const std::string& message);

  ViewerOptions options_;
  std::vector<std::string> hidden_names_;  // --hide by name, until the first mesh is read
  std::string size_map_path_;              // --size-map, until the first load starts
  std::string size_map_mesh_path_;         // and --size-map-mesh, as long
  std::string hide_note_;                  // the names it lacked, for the status line
  bool opened_mesh_ = false;               // a mesh was opened (--hide applied to it)
  // Opening a file cancelled the running simplification: said until the load ends.
  std::string run_cancelled_note_;
  std::unique_ptr<render::WindowContext> window_;
  std::unique_ptr<render::Renderer> renderer_;
  bool imgui_glfw_ = false, imgui_gl_ = false;

  OrbitCamera camera_;
  std::pair<double, render::LegendSpace> framed_with_;  // framing() at the last framing
  ui::ViewSettings view_;
  ui::ThresholdSettings thresholds_;
  ui::AnalysisSettings analysis_;
  ui::PanelState panel_;
  ui::ViewerStatus status_;
  std::vector<ui::Command> commands_;
  std::vector<std::string> dropped_;
  std::vector<int> pressed_keys_;  // see on_key()

  std::unique_ptr<Scene> scene_;
  size_t scene_generation_ = 0;
  std::unique_ptr<Job> job_;
  // A simplification that goes on while another file loads (start_load()): cancelled
  // once that file is read, back in job_ if it cannot be.
  std::unique_ptr<Job> parked_run_;
  bool parked_wait_ = false;  // wait_for_job_ of the parked run (a script's simplify wait=0)
  std::string last_job_error_;

  // Statistics of the displayed level (computed in a task on a compacted copy), and
  // what it breaks of the run's thresholds, in words ("" if nothing or none known).
  struct LevelStats {
    MeshStats stats;
    std::string breaks;
  };
  std::future<LevelStats> stats_future_;
  // The surface groups drawn (groups_key_, if groups_drawn_), and those being built.
  struct GroupsKey {
    size_t step = 0, generation = 0;
    std::vector<uint32_t> shown;
    render::SurfaceFilter filter;
  };
  bool same_groups(const GroupsKey& a, const GroupsKey& b) const {
    return a.step == b.step && a.generation == b.generation && a.shown == b.shown &&
           same_filter(a.filter, b.filter);
  }
  GroupsKey groups_now() const;  // of the level and view shown
  bool groups_wanted() const;    // whether any group is ticked (and the input has groups)
  GroupsKey groups_key_, groups_future_key_;
  size_t status_groups_generation_ = size_t(-1);  // of the groups fill_status() listed
  bool groups_drawn_ = false;
  std::future<render::GroupOverlay> groups_future_;
  size_t stats_future_step_ = 0, stats_future_generation_ = 0;
  bool has_stats_ = false;
  MeshStats stats_;
  std::string stats_breaks_;
  size_t stats_step_ = 0, stats_generation_ = 0;
  Clock::time_point last_lod_move_ = Clock::now();

  // Analysis: the running solve, the last result, the finest level's C per set-up.
  std::unique_ptr<SolveJob> solve_job_;
  std::unique_ptr<AnalysisResult> analysis_result_;
  std::string analysis_error_;
  // Why the last solve is not of the current scene ("the mesh was simplified again",
  // "another mesh was opened"); "" while it is, or if nothing was solved.
  std::string analysis_superseded_;
  struct Finest {
    size_t generation = 0;
    ElectrostaticsProblem problem;
    double capacitance = 0;
  };
  std::optional<Finest> finest_;
  bool surface_has_field_ = false;  // the surface carries analysis_result_'s |E|

  struct Saved {
    Status status;
    std::string note;    // what --improve did, for the message
    std::string breaks;  // what the level breaks of the run's thresholds ("" if nothing)
  };
  std::future<Saved> save_future_;
  std::string save_path_;
  bool thresholds_from_history_ = false;  // the panel shows the opened history's thresholds
  int save_line_ = 0;                     // the script line that asked, if any

  // A surface being rebuilt off the UI thread, for a new filter (see apply_view_changes())
  // or for a far move of the level (see follow_scrubber()).
  std::future<std::unique_ptr<render::LodSurface>> surface_future_;
  size_t surface_step_ = 0, surface_generation_ = 0;
  render::SurfaceFilter surface_filter_;
  // While the level's rebuild after a far move runs: the step the surface on screen
  // shows (the LOD is already at the new one).
  std::optional<size_t> jump_from_;
  // Measured for follow_scrubber()'s choice between walking and rebuilding (running
  // means; the starting values err towards rebuilding): tets an incremental update
  // touches per step, seconds a touched tet costs it, seconds a rebuild costs per tet of
  // the level (on screen: from its start to its surface's upload).
  double tets_per_step_ = 30;
  double seconds_per_touched_tet_ = 1e-6;
  double seconds_per_level_tet_ = 1e-6;
  Clock::time_point rebuild_start_;
  size_t rebuild_tets_ = 0;

  // Drawing.
  bool needs_redraw_ = true;
  bool interacting_ = false;  // the scene changed this frame (camera, scrub, filter)
  double drawn_scale_ = 0;
  int drawn_width_ = 0, drawn_height_ = 0;
  render::DrawSettings drawn_settings_;
  render::Camera drawn_camera_;
  uint64_t drawn_pictures_ = 0;  // redraws of the scene: a new picture each
  // The pointer resting over the view, and the tet under it once picked.
  struct Hover {
    float x = -1, y = -1;  // display pixels
    Clock::time_point since;
    bool picked = false;
    uint64_t picture = 0;  // drawn_pictures_ when picked
    uint32_t tet = kInvalidIndex;
    TetInfo info;  // of `tet`, at the pick
  };
  Hover hover_;
  bool hover_waiting_ = false;  // resting, not picked yet: not idle
  std::string ui_capture_path_;
  int ui_capture_countdown_ = -1;
  int ui_capture_line_ = 0;

  // Timing.
  int busy_frames_ = 3;  // frames to draw before waiting for events when idle
  bool last_slept_ = false;
  bool throttle_ = false;  // the next frame waits for kWorkingFps (see frame())
  Clock::time_point last_frame_start_ = Clock::now();
  double frame_ms_ = 0, fps_ = 0;
  FrameRecord current_;

  // Script.
  size_t script_index_ = 0;
  int wait_frames_ = 0;
  bool script_mouse_ = false;  // a script's 'mouse X Y' holds the pointer at this place
  float script_mouse_x_ = 0, script_mouse_y_ = 0;
  Clock::time_point wait_until_;
  int pending_job_line_ = 0;           // the open/simplify line whose job must succeed
  bool wait_for_job_ = true;           // the script waits for a running job to finish
  bool wait_for_solve_ = true;         // and for a running solve
  bool started_without_wait_ = false;  // a simplify or solve line had wait=0
  bool quit_ = false;
  int exit_code_ = kExitOk;
  struct Bench {
    bool active = false;
    long long frames = 0, frame = 0;
    bool backward = false;
    bool scrub = true;  // drag the scrubber; else just time frames
    std::string out;
    int line = 0;
    std::vector<FrameRecord> records;
  } bench_;
};

void drop_callback(GLFWwindow* window, int count, const char** paths) {
  auto* viewer = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  if (viewer && count > 0) viewer->on_drop(paths[0]);
}

// Set before ImGui's backend installs its own, which then calls it after its own work.
void key_callback(GLFWwindow* window, int key, int, int action, int) {
  auto* viewer = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  if (viewer) viewer->on_key(key, action);
}

bool Viewer::init() {
  std::string error;
  window_ = render::WindowContext::create(options_.width, options_.height, "TetLOD", true, &error);
  if (!window_) {
    std::fprintf(stderr,
                 "tetlod view: %s\n"
                 "tetlod view: the viewer needs a display; without one use 'tetlod report' or "
                 "'tetlod render' (or run it under xvfb-run)\n",
                 error.c_str());
    return false;
  }
  auto* glfw_window = static_cast<GLFWwindow*>(window_->native_window());
  // Interactive: in step with the display. Scripted (tests, benchmarks): as fast as
  // frames can be made, so the frame times measure their cost.
  glfwSwapInterval(options_.has_script ? 0 : 1);
  glfwSetWindowUserPointer(glfw_window, this);
  glfwSetDropCallback(glfw_window, drop_callback);
  glfwSetKeyCallback(glfw_window, key_callback);
  renderer_ = std::make_unique<render::Renderer>(window_->gl());
  if (!renderer_->init(&error)) {
    std::fprintf(stderr, "tetlod view: %s\n", error.c_str());
    return false;
  }
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
  ImGui::StyleColorsDark();
  if (!ui::add_name_glyphs(ui::kNameGlyphFont))
    std::fprintf(stderr,
                 "tetlod view: note: %s cannot be read (Debian's fonts-dejavu-core): names "
                 "show Latin-1 letters only\n",
                 ui::kNameGlyphFont);
  imgui_glfw_ = ImGui_ImplGlfw_InitForOpenGL(glfw_window, true);
  imgui_gl_ = imgui_glfw_ && ImGui_ImplOpenGL3_Init("#version 330");
  if (!imgui_gl_) {
    std::fputs("tetlod view: Dear ImGui could not start its OpenGL 3 backend\n", stderr);
    return false;
  }
  if (options_.remember_recent) {
    std::ifstream in(recent_files_path());
    for (std::string line; std::getline(in, line) && panel_.recent_files.size() < 10;)
      if (!line.empty()) panel_.recent_files.push_back(line);
  }
  std::printf("tetlod view: %s\n", window_->description().c_str());
  return true;
}

void Viewer::shutdown() {
  for (std::unique_ptr<Job>* job : {&job_, &parked_run_}) {
    if (!*job) continue;
    (*job)->cancel = true;
    if ((*job)->thread.joinable()) (*job)->thread.join();
    job->reset();
  }
  if (solve_job_) {
    solve_job_->cancel = true;
    if (solve_job_->thread.joinable()) solve_job_->thread.join();
    solve_job_.reset();
  }
  if (stats_future_.valid()) stats_future_.wait();
  if (save_future_.valid()) save_future_.wait();
  if (surface_future_.valid()) surface_future_.wait();
  if (imgui_gl_) ImGui_ImplOpenGL3_Shutdown();
  if (imgui_glfw_) ImGui_ImplGlfw_Shutdown();
  if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
  renderer_.reset();
  window_.reset();
}

int Viewer::run() {
  if (!init()) {
    shutdown();
    return kExitBadInput;
  }
  if (!options_.mesh_path.empty()) {
    (void)start_load(options_.mesh_path);  // nothing runs yet: it starts
    pending_job_line_ = options_.has_script ? -1 : 0;
  }
  while (!quit_ && !window_->should_close()) frame();
  shutdown();
  return exit_code_;
}

void Viewer::frame() {
  // A simplification or solve running and nothing moving on the last frame: at most
  // kWorkingFps frames a second (an event wakes it at once), so that redrawing the same
  // picture leaves the cores to the worker: on a software renderer (llvmpipe, as on
  // machines without a GPU) every frame takes milliseconds on every core.
  const Clock::time_point end = Clock::now();  // of the last frame
  const double early = 1 / kWorkingFps - seconds_between(last_frame_start_, end);
  const bool throttled = throttle_ && early > 0;
  if (throttled) glfwWaitEventsTimeout(early);
  const Clock::time_point start = Clock::now();
  const double waited_ms = throttled ? 1e3 * seconds_between(end, start) : 0;
  const double interval_ms = 1e3 * seconds_between(last_frame_start_, start);
  current_.frame_ms = interval_ms - waited_ms;
  current_.waited_ms = waited_ms;
  last_frame_start_ = start;
  if (bench_.active) bench_.records.push_back(current_);
  current_ = {};

  // Idle (nothing moving, no work in flight, no script): sleep until an event or a
  // quarter second passes, so an idle viewer leaves the cores to others.
  const bool idle = !job_ && !solve_job_ && !interacting_ && !needs_redraw_ &&
                    !options_.has_script && !stats_future_.valid() && !save_future_.valid() &&
                    !groups_future_.valid() && !surface_future_.valid() &&
                    ui_capture_countdown_ < 0 && !hover_waiting_ &&
                    (!scene_ || scene_->lod->step() == static_cast<size_t>(panel_.target_step));
  busy_frames_ = idle ? busy_frames_ - 1 : 3;
  const bool slept = last_slept_;
  last_slept_ = busy_frames_ < 0;
  if (busy_frames_ < 0) {
    glfwWaitEventsTimeout(0.25);
    busy_frames_ = 3;  // a few frames for ImGui to follow the event
  } else {
    window_->poll_events();
  }
  for (const std::string& path : dropped_) (void)start_load(path);  // the panel says why not
  dropped_.clear();
  poll_job();
  poll_solve();
  update_stats();
  if (save_future_.valid() &&
      save_future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    const Saved saved = save_future_.get();
    const Status& s = saved.status;
    if (s) {
      status_.message = "saved " + save_path_ + saved.note;
      status_.load_error.clear();  // an earlier error is not of this
      if (!saved.breaks.empty()) {
        status_.message += "; it breaks the run's thresholds: " + saved.breaks;
        std::fprintf(stderr, "tetlod view: note: %s, saved, breaks the run's thresholds: %s\n",
                     save_path_.c_str(), saved.breaks.c_str());
      }
    } else if (save_line_ > 0) {
      fail_script(save_line_, s.message());
    } else {
      status_.load_error = s.message();
    }
    save_line_ = 0;
  }

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (script_mouse_) ImGui::GetIO().MousePos = ImVec2(script_mouse_x_, script_mouse_y_);
  ImGui::NewFrame();
  interacting_ = false;
  handle_camera_input();
  run_script();
  fill_status();
  commands_.clear();
  ui::draw_viewer_panels(status_, &view_, &thresholds_, &analysis_, &panel_, &commands_);
  for (const ui::Command& command : commands_) execute(command);
  apply_view_changes();
  follow_scrubber();
  sync_field_colors();
  update_groups();
  keep_framed();

  int width = 0, height = 0;
  window_->framebuffer_size(&width, &height);
  const Clock::time_point draw_start = Clock::now();
  if (width > 0 && height > 0) draw_scene(width, height);
  current_.draw_ms = 1e3 * seconds_between(draw_start, Clock::now());
  if (width > 0 && height > 0) update_hover();
  const Clock::time_point ui_start = Clock::now();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  current_.ui_ms = 1e3 * seconds_between(ui_start, Clock::now());

  if (ui_capture_countdown_ == 0) {
    const render::GlApi& gl = window_->gl();
    render::Image image(width, height);
    std::vector<uint8_t> bottom_up(image.rgba.size());
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    const size_t row = size_t(width) * 4;
    for (int y = 0; y < height; ++y)
      std::copy_n(bottom_up.data() + size_t(height - 1 - y) * row, row,
                  image.rgba.data() + size_t(y) * row);
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    const Status s = render::write_png(ui_capture_path_, image);
    if (s) {
      status_.message = "screenshot " + ui_capture_path_;
      status_.load_error.clear();
    } else if (ui_capture_line_ > 0) {
      fail_script(ui_capture_line_, s.message());
    } else {
      status_.load_error = s.message();
    }
  }
  if (ui_capture_countdown_ >= 0) --ui_capture_countdown_;
  const Clock::time_point swap_start = Clock::now();
  window_->swap_buffers();
  current_.swap_ms = 1e3 * seconds_between(swap_start, Clock::now());
  if (scene_) current_.step = scene_->lod->step();

  // Frame-time readout (smoothed over about ten frames): the time between frame
  // starts, except after waiting for events, where it is this frame's own time.
  const double total =
      slept || throttled ? 1e3 * seconds_between(start, Clock::now()) : interval_ms;
  frame_ms_ = frame_ms_ == 0 ? total : 0.9 * frame_ms_ + 0.1 * total;
  fps_ = frame_ms_ > 0 ? 1e3 / frame_ms_ : 0;
  throttle_ = (job_ || solve_job_) && !interacting_ && ui_capture_countdown_ < 0 &&
              (!scene_ || scene_->lod->step() == static_cast<size_t>(panel_.target_step));
}

// Why opening `path` would fail before reading a byte, or "".
std::string open_problem(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return path + ": cannot read: it is a directory";
  if (!is_history_path(path)) {
    if (Status s = check_mesh_path(path); !s)
      return s.message() + "; the viewer also opens .tlh collapse histories";
  }
  if (access(path.c_str(), R_OK) != 0) return path + ": cannot open: " + std::strerror(errno);
  return "";
}

Status Viewer::start_load(const std::string& path) {
  panel_.output_used = false;  // what the panel says next is of this file, not of a save
  if (job_ && job_->is_load) {
    status_.load_error = "still loading " + job_->path;
    return Status::error(status_.load_error);
  }
  if (job_) {
    // A simplification of the old mesh is no longer wanted once the new one is read
    // (poll_job() cancels it then, and says so); until then, and if the file cannot be
    // read, it goes on. A path that cannot be opened at all (missing, a directory,
    // unreadable, not a mesh's or a history's extension) is said at once.
    if (std::string problem = open_problem(path); !problem.empty()) {
      status_.load_error = problem + ui::still_running_text(true, solve_job_ != nullptr);
      return Status::error(status_.load_error);
    }
    parked_run_ = std::move(job_);
    parked_wait_ = wait_for_job_;
  }
  job_ = std::make_unique<Job>();
  job_->is_load = true;
  job_->path = path;
  job_->size_map_path = std::move(size_map_path_);  // for the first mesh opened only
  job_->size_map_mesh_path = std::move(size_map_mesh_path_);
  size_map_path_.clear();
  size_map_mesh_path_.clear();
  Job* job = job_.get();
  ui::ViewSettings view = view_;
  if (opened_mesh_) view.hidden_materials.clear();  // as swap_in() will
  job->thread = std::thread([job, view] {
    {
      std::lock_guard<std::mutex> lock(job->mutex);
      job->phase = "reading";
    }
    // A collapse history (tetlod simplify --history, or saved here): its finest
    // level is the input (shared, not copied), and its levels are there at once.
    std::shared_ptr<const TetMesh> mesh;
    std::shared_ptr<SimplifyResult> history;
    std::optional<SimplifyParams> saved_params;
    std::shared_ptr<const SurfacePatches> patches;
    std::shared_ptr<const SizeMap> size_map;
    std::shared_ptr<const std::vector<MaterialName>> material_names;
    Status s;
    if (is_history_path(job->path)) {
      history = std::make_shared<SimplifyResult>();
      std::vector<MaterialName> saved_names;
      SurfacePatches saved_patches;
      int format = 0;
      s = read_history(job->path, &history->base, &history->history, &saved_params, &saved_names,
                       &saved_patches, &format);
      if (s && (saved_patches.any() || !saved_patches.inside_entries().empty()))
        patches = std::make_shared<const SurfacePatches>(std::move(saved_patches));
      if (s && !saved_names.empty())
        material_names = std::make_shared<const std::vector<MaterialName>>(std::move(saved_names));
      mesh = std::shared_ptr<const TetMesh>(history, &history->base);
      if (s && !job->size_map_path.empty())
        s = Status::error("--size-map " + job->size_map_path + ": " + job->path +
                          " is a history, which keeps the size map it was made with, if any");
      if (s) {
        std::lock_guard<std::mutex> lock(job->mutex);
        job->notes.push_back(saved_params ? "made with " + describe_thresholds(*saved_params)
                                          : "saved without its thresholds");
        if (const std::string note = unchecked_history_note(format); !note.empty())
          job->notes.push_back(note);
      }
    } else {
      auto read = std::make_shared<TetMesh>();
      ReadInfo info;
      s = read_mesh(job->path, read.get(), &info);
      // Not a mesh's extension (or a directory): in open_problem()'s words, which say
      // that the viewer also opens histories, which read_mesh()'s list of formats lacks.
      if (!s && !check_mesh_path(job->path)) s = Status::error(open_problem(job->path));
      if (s) {
        std::lock_guard<std::mutex> lock(job->mutex);
        job->notes = reader_notes(info, false);
        for (std::string& note : validation_notes(info.validation))
          job->notes.push_back(std::move(note));
      }
      if (s && !info.surface_groups.empty())
        patches = std::make_shared<const SurfacePatches>(*read, info.surface_groups);
      if (s && !info.material_names.empty()) {
        material_names =
            std::make_shared<const std::vector<MaterialName>>(std::move(info.material_names));
      }
      if (s && !job->size_map_path.empty()) {
        {
          std::lock_guard<std::mutex> lock(job->mutex);
          job->phase = "reading the size map";
        }
        const std::string& other_path = job->size_map_mesh_path;
        if (other_path.empty()) {
          s = read_size_map(job->size_map_path, *read, &info.validation, &size_map);
        } else {
          // Sizes at a background mesh's vertices, as `simplify --size-map-mesh` reads them.
          TetMesh other;
          ReadInfo other_info;
          s = read_mesh(other_path, &other, &other_info);
          if (!s) s = Status::error("--size-map-mesh: " + s.message());
          if (s)
            s = read_size_map(job->size_map_path, other, &other_info.validation, &size_map,
                              "--size-map-mesh " + other_path);
          if (s) {
            const std::string note =
                outside_background_note(*read, other, "--size-map-mesh " + other_path);
            std::lock_guard<std::mutex> lock(job->mutex);
            if (!note.empty()) job->notes.push_back(note);
          }
        }
      }
      mesh = std::move(read);
    }
    if (!s) {
      std::lock_guard<std::mutex> lock(job->mutex);
      job->error = s.message();
    } else {
      {
        std::lock_guard<std::mutex> lock(job->mutex);
        job->phase = "preparing the surface";
      }
      ui::ViewSettings v = view;
      v.cut = false;  // the cut position belongs to the old model
      auto scene = make_scene(job->path, std::move(mesh), history, v);
      scene->from_history = history != nullptr;
      scene->input_patches = patches;
      scene->patches = std::move(patches);
      scene->material_names = std::move(material_names);
      if (size_map) {
        scene->size_map = std::move(size_map);
        scene->size_map_name = std::filesystem::path(job->size_map_path).filename().string();
      }
      if (saved_params) {
        scene->params = *saved_params;
        scene->params_known = true;
      }
      std::lock_guard<std::mutex> lock(job->mutex);
      job->scene = std::move(scene);
    }
    job->done = true;
  });
  return Status();
}

void Viewer::start_simplify() {
  if (!scene_) return;
  if (job_) {
    status_.simplify_error = job_->is_load ? "wait for the load to finish" : "already simplifying";
    return;
  }
  SimplifyParams params;
  std::string error;
  if (!ui::to_simplify_params(thresholds_, &params, &error)) {
    last_job_error_ = "thresholds: " + error;
    status_.simplify_error = ui::simplify_error_text(last_job_error_);
    return;
  }
  status_.simplify_error.clear();
  job_ = std::make_unique<Job>();
  job_->path = scene_->path;
  Job* job = job_.get();
  std::shared_ptr<const TetMesh> input = scene_->input;  // always the loaded input
  const auto input_patches = scene_->input_patches;
  std::shared_ptr<const SurfacePatches> patches = input_patches;
  if (patches && !thresholds_.keep_inside_groups && !patches->inside_entries().empty()) {
    auto outside_only = std::make_shared<SurfacePatches>(*patches);
    outside_only->drop_inside();
    patches = std::move(outside_only);
  }
  auto material_names = scene_->material_names;
  const ui::ViewSettings view = view_;
  job->thread = std::thread([job, input, patches, input_patches, material_names, params, view] {
    auto result = std::make_shared<SimplifyResult>();
    const Status s = simplify(
        *input, params, result.get(),
        [job](const SimplifyProgress& p) {
          std::lock_guard<std::mutex> lock(job->mutex);
          job->phase = p.phase;
          job->past_valence = p.past_valence;
          job->fraction = p.fraction;
          job->other_phase = p.other_phase ? p.other_phase : "";
          job->other_fraction = p.other_fraction;
          job->collapses = p.collapses;
        },
        &job->cancel, patches.get());
    if (!s) {
      std::lock_guard<std::mutex> lock(job->mutex);
      job->error = s.message();
    } else if (result->cancelled) {
      std::lock_guard<std::mutex> lock(job->mutex);
      job->cancelled = true;
    } else {
      {
        std::lock_guard<std::mutex> lock(job->mutex);
        job->phase = "preparing the levels";
        job->fraction = 1;
      }
      const std::string reason =
          result->violations.above_size > 0 ? above_size_reason(params, *result) : "";
      const ThresholdCounts input_breaks = threshold_breaks(*input, params);
      const std::string changes = volume_changes(
          material_volumes(*input), material_volumes(result->output), material_names.get());
      const std::string thin =
          thin_materials(material_surfaces(*input), params.tolerance, material_names.get());
      auto scene = make_scene(job->path, input, std::move(result), view);
      scene->above_size_reason = reason;
      scene->volume_changes = changes;
      if (patches)
        scene->area_changes = group_area_changes(*input, scene->result->output, *patches);
      scene->thin_materials = thin;
      scene->input_breaks = input_breaks;
      scene->params = params;
      scene->params_known = true;
      scene->patches = patches;
      scene->input_patches = input_patches;
      scene->material_names = material_names;
      std::lock_guard<std::mutex> lock(job->mutex);
      job->scene = std::move(scene);
    }
    job->done = true;
  });
}

void Viewer::poll_job() {
  if (!job_ || !job_->done) return;
  job_->thread.join();
  std::unique_ptr<Job> job = std::move(job_);
  if (!job->error.empty() && !job->is_load) {  // the previous result stays
    status_.simplify_error = ui::simplify_error_text(job->error);
    last_job_error_ = job->error;
    return;
  }
  if (!job->error.empty()) {
    // The current mesh stays as it was, and so do a simplification and a solve of it.
    status_.load_error =
        job->error + ui::still_running_text(parked_run_ != nullptr, solve_job_ != nullptr);
    if (parked_run_) {
      job_ = std::move(parked_run_);
      wait_for_job_ = parked_wait_;  // a script's open line fails now, not after the run
    }
    status_.message.clear();
    last_job_error_ = status_.load_error;
    return;
  }
  if (parked_run_) {  // the new mesh is read: the old mesh's run is no longer wanted
    parked_run_->cancel = true;
    parked_run_->thread.join();
    parked_run_.reset();
    run_cancelled_note_ = "the running simplification was cancelled: another file was opened";
    std::fprintf(stderr, "tetlod view: %s\n", run_cancelled_note_.c_str());
  }
  if (job->cancelled) {
    status_.message = "simplification cancelled; the previous result stays";
    last_job_error_ = "cancelled";
    return;
  }
  last_job_error_.clear();
  status_.load_error.clear();
  const double total = seconds_between(job->start, Clock::now());
  swap_in(std::move(job->scene), job->is_load);
  char text[160];
  if (job->is_load) {
    std::snprintf(text, sizeof(text), " in %.2f s", total);
    status_.message = "loaded " + job->path + text;
    if (!run_cancelled_note_.empty()) status_.message += "; " + run_cancelled_note_;
    run_cancelled_note_.clear();
    if (!hide_note_.empty()) status_.message += "; " + hide_note_;
    hide_note_.clear();
    status_.load_notes = job->notes;
    for (const std::string& note : job->notes)
      std::fprintf(stderr, "tetlod view: %s: note: %s\n", job->path.c_str(), note.c_str());
  } else {
    // The Thresholds panel shows the run's own time (subdivide, classify, simplify);
    // the rest is building the levels' display.
    std::snprintf(text, sizeof(text), "simplified: %.2f s in all, of which the run %.2f s", total,
                  run_seconds(*scene_->result));
    status_.message = text;
    if (options_.has_script) std::printf("tetlod view: %s\n", text);  // for benchmarks
    if (!scene_->volume_changes.empty()) {  // as tetlod simplify says it (and the panel)
      std::fprintf(stderr, "tetlod view: note: volumes changed by more than %g %%: %s\n",
                   kVolumeNotePercent, scene_->volume_changes.c_str());
    }
    if (!scene_->area_changes.empty()) {
      std::fprintf(stderr,
                   "tetlod view: note: surface groups' areas changed by more than %g %%: %s\n",
                   kVolumeNotePercent, scene_->area_changes.c_str());
    }
    if (!scene_->thin_materials.empty()) {
      std::fprintf(stderr, "tetlod view: note: thin for the tolerance (%g): %s\n",
                   scene_->params.tolerance, scene_->thin_materials.c_str());
    }
  }
}

// --hide by name: looked up in the first mesh opened, whose names they are. A name it
// lacks is said on stderr (with the names it has) and in the status line.
void Viewer::hide_by_name() {
  const std::vector<MaterialName>& names = material_names();
  for (const std::string& name : hidden_names_) {
    int32_t m = 0;
    if (material_by_name(name, names, "view", "--hide", &m)) {
      auto& hidden = view_.hidden_materials;
      if (!std::binary_search(hidden.begin(), hidden.end(), m))
        hidden.insert(std::lower_bound(hidden.begin(), hidden.end(), m), m);
    } else {
      hide_note_ += (hide_note_.empty() ? "--hide: no material named '" : ", '") + name + "'";
    }
  }
  hidden_names_.clear();
}

void Viewer::swap_in(std::unique_ptr<Scene> scene, bool is_load) {
  scene_ = std::move(scene);
  ++scene_generation_;
  jump_from_.reset();
  has_stats_ = false;
  surface_has_field_ = false;
  if (solve_job_) solve_job_->cancel = true;  // its level is gone; poll_solve() says so
  if (analysis_result_)
    analysis_superseded_ = is_load ? "another mesh was opened" : "the mesh was simplified again";
  panel_.target_step = static_cast<long long>(scene_->lod->step());
  panel_.jump_elements = static_cast<int>(
      std::min<size_t>(scene_->lod->alive_tet_count(), std::numeric_limits<int>::max()));
  status_.simplify_error.clear();  // of another run, or of the mesh before
  if (is_load) {
    // Every material shown (an id names another material in another mesh), except in
    // the first mesh opened, which --hide's ids and names are for; centre the cut; frame
    // the model.
    auto& hidden = view_.hidden_materials;
    if (opened_mesh_) hidden.clear();
    view_.shown_groups.clear();  // another file's groups
    analysis_.groups.clear();
    opened_mesh_ = true;
    hide_by_name();
    hidden.erase(std::remove_if(hidden.begin(), hidden.end(),
                                [&](int32_t m) {
                                  return !std::binary_search(scene_->materials.begin(),
                                                             scene_->materials.end(), m);
                                }),
                 hidden.end());
    const Vec3 center = 0.5 * (scene_->lo + scene_->hi);
    view_.cut_offset = static_cast<float>(view_.cut_axis == ui::CutAxis::kX   ? center.x
                                          : view_.cut_axis == ui::CutAxis::kY ? center.y
                                                                              : center.z);
    // Every threshold and the sizing start again from the defaults for this mesh
    // (region rules and material ids belong to the old one); subdivide and keeping the groups
    // inside materials stay.
    const bool subdivide = thresholds_.subdivide, keep_inside = thresholds_.keep_inside_groups;
    thresholds_ = ui::ThresholdSettings{};
    thresholds_.subdivide = subdivide;
    thresholds_.keep_inside_groups = keep_inside;
    thresholds_.tolerance = scene_->default_tolerance;
    thresholds_.size = scene_->default_size;
    // A history's own thresholds, where the panel can hold them.
    thresholds_from_history_ = scene_->from_history && scene_->params_known &&
                               ui::from_simplify_params(scene_->params, &thresholds_);
    // Where the rest does not fit the panel, the crease angle still does.
    if (scene_->from_history && scene_->params_known && !thresholds_from_history_)
      thresholds_.crease_angle = scene_->params.crease_angle_degrees;
    // A size map given with the mesh: its sizing, capped where the map never reaches.
    if (scene_->size_map) {
      thresholds_.sizing_mode = ui::SizingMode::kMap;
      thresholds_.size_map = scene_->size_map;
      thresholds_.size_map_name = scene_->size_map_name;
      thresholds_.size = scene_->size_map->largest();
    }
    const render::ViewDirection iso = render::ViewDirection::kIso;
    frame_view(&iso);
    add_recent(scene_->path);
    std::snprintf(panel_.open_path, sizeof(panel_.open_path), "%s", scene_->path.c_str());
  }
  // apply_view_changes() rebuilds the surface if the view changed meanwhile.
  upload_all();
}

void Viewer::upload_all() {
  std::vector<int32_t> shown;
  for (const int32_t m : scene_->materials)
    if (!std::binary_search(view_.hidden_materials.begin(), view_.hidden_materials.end(), m))
      shown.push_back(m);
  renderer_->set_legend_materials(std::move(shown));
  renderer_->set_material_names(scene_->material_names ? *scene_->material_names
                                                       : std::vector<MaterialName>());
  renderer_->update_triangles(scene_->surface.triangles(), scene_->surface.take_triangle_dirty());
  renderer_->update_highlight(scene_->surface.highlight(), scene_->surface.take_highlight_dirty(),
                              scene_->surface.highlighted_tets());
  needs_redraw_ = true;
}

void Viewer::add_recent(const std::string& path) {
  std::error_code ec;
  const std::string absolute = std::filesystem::absolute(path, ec).lexically_normal().string();
  const std::string entry = ec ? path : absolute;
  auto& recent = panel_.recent_files;
  recent.erase(std::remove(recent.begin(), recent.end(), entry), recent.end());
  recent.insert(recent.begin(), entry);
  if (recent.size() > 10) recent.resize(10);
  if (!options_.remember_recent) return;
  const std::filesystem::path file = recent_files_path();
  if (file.empty()) return;
  std::filesystem::create_directories(file.parent_path(), ec);
  std::ofstream out(file, std::ios::trunc);
  for (const std::string& r : recent) out << r << '\n';
}

void Viewer::execute(const ui::Command& command) {
  switch (command.kind) {
    case ui::CommandKind::kOpen:
      (void)start_load(command.path);  // the panel says why not
      break;
    case ui::CommandKind::kSimplify:
      start_simplify();
      break;
    case ui::CommandKind::kCancel:
      if (job_ && !job_->is_load) job_->cancel = true;
      break;
    case ui::CommandKind::kJumpElements:
      if (scene_)
        panel_.target_step = static_cast<long long>(
            scene_->lod->step_for_elements(static_cast<size_t>(std::max(0LL, command.value))));
      break;
    case ui::CommandKind::kFit:  // reframes from the current direction (the views set one)
      if (scene_) frame_view(nullptr);
      break;
    case ui::CommandKind::kAxisView:
      if (scene_) {
        const render::ViewDirection views[] = {render::ViewDirection::kIso,
                                               render::ViewDirection::kX, render::ViewDirection::kY,
                                               render::ViewDirection::kZ};
        frame_view(&views[std::clamp<long long>(command.value, 0, 3)]);
      }
      break;
    case ui::CommandKind::kSave: {
      const Status s = save_level(command.path, (command.value & ui::kSaveImproved) != 0,
                                  (command.value & ui::kSaveSurfaces) != 0,
                                  (command.value & ui::kSaveBinary) != 0);
      if (!s) status_.load_error = s.message();
      break;
    }
    case ui::CommandKind::kSolve: {
      const Status s = start_solve(0);
      if (!s) analysis_error_ = s.message();
      break;
    }
    case ui::CommandKind::kCancelSolve:
      if (solve_job_) solve_job_->cancel = true;
      break;
    case ui::CommandKind::kScreenshot:
      // As a script's screenshot line is checked: the panel wrote any name as a PNG,
      // and clamped a size of 100000 to 8192 without a word.
      if (std::string problem =
              screenshot_problem(command.path, command.with_ui ? 0 : command.width,
                                 command.with_ui ? 0 : command.height);
          !problem.empty()) {
        status_.load_error = problem;
        break;
      }
      if (command.with_ui) {
        ui_capture_path_ = command.path;
        ui_capture_countdown_ = 1;  // the next frame, whose UI no longer shows the click
        ui_capture_line_ = 0;
      } else {
        const Status s = screenshot(command.path, command.width, command.height);
        if (s) {
          status_.message = "screenshot " + command.path;
          status_.load_error.clear();
        } else {
          status_.load_error = s.message();
        }
      }
      break;
  }
}

void Viewer::handle_camera_input() {
  const ImGuiIO& io = ImGui::GetIO();
  std::vector<int> keys;
  keys.swap(pressed_keys_);
  if (!scene_) return;
  int width = 0, height = 0;
  window_->framebuffer_size(&width, &height);
  if (!io.WantCaptureMouse && ImGui::IsMousePosValid()) {
    const double dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    const bool pan = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
    if (dx != 0 || dy != 0) {
      if (pan) {
        camera_.pan(dx, dy, view_pixels(width, height).height);
      } else if (io.MouseDown[0]) {
        camera_.orbit(dx, dy);
      }
    }
    if (io.MouseWheel != 0) camera_.zoom(io.MouseWheel);
  }
  if (io.WantCaptureKeyboard) return;
  // The level of detail: held keys repeat, as on the strip's arrow buttons.
  const long long last = static_cast<long long>(scene_->lod->step_count());
  const long long page = std::max(1LL, last / 100);
  long long& step = panel_.target_step;
  for (const int key : keys) {
    if (key == GLFW_KEY_F) execute({ui::CommandKind::kFit});
    if (key >= GLFW_KEY_0 && key <= GLFW_KEY_3)
      execute({ui::CommandKind::kAxisView, "", key - GLFW_KEY_0});
    if (key == GLFW_KEY_LEFT) step -= 1;
    if (key == GLFW_KEY_RIGHT) step += 1;
    if (key == GLFW_KEY_PAGE_UP) step -= page;
    if (key == GLFW_KEY_PAGE_DOWN) step += page;
    if (key == GLFW_KEY_HOME) step = 0;
    if (key == GLFW_KEY_END) step = last;
    step = std::clamp(step, 0LL, last);
  }
}

// A new filter (cut, hidden materials, highlight) needs LodSurface::reset(), O(tets):
// done in a task on a copy of the current step's arrays, while the old surface stays
// on screen. When it is ready, the LOD has possibly moved on: the new surface is
// brought to the current step by the delta between the two steps.
void Viewer::apply_view_changes() {
  if (!scene_) return;
  if (surface_future_.valid()) {
    if (surface_future_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    std::unique_ptr<render::LodSurface> surface = surface_future_.get();
    // A far move's surface is taken even if the filter has changed since (the surface on
    // screen is of another step): then a rebuild for the new filter follows.
    const bool jump = jump_from_.has_value();
    jump_from_.reset();
    if (surface_generation_ == scene_generation_ &&
        (jump || same_filter(surface_filter_, make_filter(view_)))) {
      Lod& lod = *scene_->lod;
      const size_t now = lod.step();
      if (now != surface_step_) {
        lod.seek(surface_step_);
        LodDelta delta;
        lod.seek(now, &delta);
        surface->update(render::lod_state(lod), delta);
      }
      scene_->surface = std::move(*surface);
      scene_->filter = surface_filter_;
      surface_has_field_ = false;
      upload_all();
      interacting_ = true;
      if (rebuild_tets_ > 0) {
        seconds_per_level_tet_ =
            0.5 * seconds_per_level_tet_ +
            0.5 * seconds_between(rebuild_start_, Clock::now()) / double(rebuild_tets_);
      }
      if (!jump) return;
    }
  }
  const render::SurfaceFilter filter = make_filter(view_);
  if (same_filter(filter, scene_->filter)) return;
  start_surface_rebuild(filter);
}

void Viewer::start_surface_rebuild(const render::SurfaceFilter& filter) {
  const Lod& lod = *scene_->lod;
  rebuild_start_ = Clock::now();
  rebuild_tets_ = lod.alive_tet_count();
  auto arrays = std::make_shared<TetMesh>();
  arrays->positions = lod.positions();
  arrays->tets = lod.tets();
  arrays->materials = lod.materials();
  auto alive = std::make_shared<std::vector<uint8_t>>(lod.alive());
  surface_step_ = lod.step();
  surface_generation_ = scene_generation_;
  surface_filter_ = filter;
  surface_future_ = std::async(std::launch::async, [arrays, alive, filter] {
    auto surface = std::make_unique<render::LodSurface>();
    const render::LodState state{&arrays->positions, &arrays->tets, &arrays->materials,
                                 alive.get()};
    surface->reset(state, filter);
    return surface;
  });
}

void Viewer::follow_scrubber() {
  if (!scene_) return;
  Lod& lod = *scene_->lod;
  const size_t target = static_cast<size_t>(
      std::clamp<long long>(panel_.target_step, 0, static_cast<long long>(lod.step_count())));
  if (lod.step() == target || jump_from_) return;  // (the level jumped to is being drawn)
  // Moves are walked in chunks of steps until the frame's budget is spent, so that a drag
  // keeps the window responsive and the display catches up over a few frames. A far move
  // instead puts the LOD there at once and builds the level's surface anew off the UI
  // thread (LodSurface::reset(), O(its tets)), the old one staying on screen meanwhile:
  // when walking would take longer on screen than that rebuild, and longer than
  // kFarSeconds, so that a short move is still drawn as it goes. Both from this run's
  // measurements (a 1M-tet motor's finest level took a minute to reach from the coarsest
  // by walking, at a few budgets of 8 ms in frames of 150 ms; rebuilt, a second or two:
  // docs/PERFORMANCE.md).
  constexpr double kBudgetSeconds = 0.008;
  constexpr double kFarSeconds = 0.25;
  const size_t distance = target > lod.step() ? target - lod.step() : lod.step() - target;
  const double frame_seconds = std::max(kBudgetSeconds, frame_ms_ / 1e3);
  const double walk =
      double(distance) * tets_per_step_ * seconds_per_touched_tet_ * frame_seconds / kBudgetSeconds;
  const double rebuild = double(lod.tet_count_at(target)) * seconds_per_level_tet_;
  if (walk > std::max(rebuild, kFarSeconds) && !surface_future_.valid()) {
    jump_from_ = lod.step();
    lod.seek(target);
    start_surface_rebuild(scene_->filter);
    surface_has_field_ = false;
    return;
  }
  constexpr size_t kChunk = 48;
  const Clock::time_point start = Clock::now();
  const render::LodState state = render::lod_state(lod);
  LodDelta delta;
  surface_has_field_ = false;  // LodSurface::update() drops the |E| values
  size_t steps = 0, touched = 0;
  while (lod.step() != target) {
    const size_t step = lod.step();
    const size_t next = target > step ? std::min(target, step + kChunk)
                                      : (step - target > kChunk ? step - kChunk : target);
    lod.seek(next, &delta);
    scene_->surface.update(state, delta);
    steps += next > step ? next - step : step - next;
    touched += delta.appeared.size() + delta.vanished.size() + delta.changed.size();
    if (seconds_between(start, Clock::now()) > kBudgetSeconds) break;
  }
  tets_per_step_ = 0.8 * tets_per_step_ + 0.2 * double(touched) / double(steps);
  if (touched > 0) {
    seconds_per_touched_tet_ = 0.8 * seconds_per_touched_tet_ +
                               0.2 * seconds_between(start, Clock::now()) / double(touched);
  }
  renderer_->update_triangles(scene_->surface.triangles(), scene_->surface.take_triangle_dirty());
  renderer_->update_highlight(scene_->surface.highlight(), scene_->surface.take_highlight_dirty(),
                              scene_->surface.highlighted_tets());
  current_.scrub_ms = 1e3 * seconds_between(start, Clock::now());
  needs_redraw_ = true;
  interacting_ = true;
  last_lod_move_ = Clock::now();
}

void Viewer::update_stats() {
  if (stats_future_.valid() &&
      stats_future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    LevelStats level = stats_future_.get();
    if (stats_future_generation_ == scene_generation_) {
      stats_ = std::move(level.stats);
      stats_breaks_ = std::move(level.breaks);
      stats_step_ = stats_future_step_;
      stats_generation_ = stats_future_generation_;
      has_stats_ = true;
    }
  }
  if (!scene_ || stats_future_.valid()) return;
  const Lod& lod = *scene_->lod;
  if (has_stats_ && stats_step_ == lod.step() && stats_generation_ == scene_generation_) return;
  if (lod.step() != static_cast<size_t>(panel_.target_step)) return;  // still moving
  if (seconds_between(last_lod_move_, Clock::now()) < 0.15 && !options_.has_script) return;
  stats_future_step_ = lod.step();
  stats_future_generation_ = scene_generation_;
  // A level before the last may break what the final mesh does not (tets not yet
  // collapsed), as `tetlod lod` says: said with the statistics.
  std::optional<SimplifyParams> params;
  if (scene_->params_known && lod.step() < lod.step_count()) params = scene_->params;
  stats_future_ = std::async(std::launch::async, [mesh = lod.extract(), params] {
    LevelStats level;
    level.stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
    if (params) {
      const ThresholdCounts b = threshold_breaks(mesh, *params);
      if (b.total() > 0) level.breaks = describe_breaks(b);
    }
    return level;
  });
}

Viewer::GroupsKey Viewer::groups_now() const {
  GroupsKey now;
  if (scene_) {
    now.step = scene_->lod->step();
    now.generation = scene_generation_;
    now.shown = view_.shown_groups;
    now.filter = make_filter(view_);
  }
  return now;
}

bool Viewer::groups_wanted() const {
  return scene_ && !view_.shown_groups.empty() && scene_->input_patches;
}

void Viewer::update_groups() {
  if (!groups_wanted() && !groups_drawn_ && !groups_future_.valid()) return;  // (most frames)
  const GroupsKey now = groups_now();
  if (groups_future_.valid() &&
      groups_future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    const render::GroupOverlay overlay = groups_future_.get();
    if (scene_ && same_groups(groups_future_key_, now)) {
      renderer_->set_groups(overlay);
      groups_key_ = groups_future_key_;
      groups_drawn_ = true;
      needs_redraw_ = true;
    }
  }
  const bool wanted = groups_wanted();
  if (groups_drawn_ && (!wanted || !same_groups(groups_key_, now))) {
    renderer_->set_groups({});  // of another level or view
    groups_drawn_ = false;
    needs_redraw_ = true;
  }
  if (!wanted || groups_drawn_ || groups_future_.valid()) return;
  if (now.step != static_cast<size_t>(panel_.target_step) || jump_from_) return;  // moving
  groups_future_key_ = now;
  groups_future_ = std::async(
      std::launch::async, [mesh = scene_->lod->extract(), patches = scene_->input_patches, now] {
        std::vector<uint32_t> neighbors;
        build_face_neighbors(mesh, &neighbors);
        return render::build_group_overlay(mesh, neighbors, *patches, now.shown, now.filter);
      });
}

void Viewer::frame_view(const render::ViewDirection* view) {
  Vec3 lo, hi;
  shown_bounds(*scene_->input, view_.hidden_materials, &lo, &hi);
  framed_with_ = framing();
  const auto& [aspect, legend] = framed_with_;
  if (view)
    camera_.fit(lo, hi, *view, aspect, legend);
  else
    camera_.refit(lo, hi, aspect, legend);
  // The hidden materials too, which may be shown again without a new framing (their
  // faces were cut by the near and far planes of the shown ones').
  camera_.include_in_depth(scene_->lo, scene_->hi);
}

void Viewer::keep_framed() {
  if (!scene_ || camera_.moved()) return;
  const auto [aspect, legend] = framing();
  const render::LegendSpace& was = framed_with_.second;
  if (aspect != framed_with_.first || legend.bottom != was.bottom ||
      legend.key_width != was.key_width || legend.key_height != was.key_height)
    frame_view(nullptr);
}

std::pair<double, render::LegendSpace> Viewer::framing() const {
  int fb_width = 0, fb_height = 0;
  window_->framebuffer_size(&fb_width, &fb_height);
  const ViewPixels view = view_pixels(std::max(1, fb_width), std::max(1, fb_height));
  // As if the legend were on, and the colour bar kept clear of in material colours too:
  // the view may be framed while neither shows, then one turned on.
  render::DrawSettings draw = make_draw_settings(view_, field_range_max(), size_range());
  draw.legend = true;
  render::LegendSpace legend = renderer_->legend_space(draw, view.width, view.height);
  if (draw.color_mode == render::ColorMode::kMaterial) {
    render::DrawSettings by_stretch = draw;
    by_stretch.color_mode = render::ColorMode::kStretch;
    legend.bottom = renderer_->legend_space(by_stretch, view.width, view.height).bottom;
  }
  return {double(view.width) / view.height, legend};
}

Viewer::ViewPixels Viewer::view_pixels(int fb_width, int fb_height) const {
  const ImGuiIO& io = ImGui::GetIO();
  const float display_width = io.DisplaySize.x > 0 ? io.DisplaySize.x : float(fb_width);
  const float display_height = io.DisplaySize.y > 0 ? io.DisplaySize.y : float(fb_height);
  const ui::ViewRect rect = ui::scene_rect(display_width, display_height, panel_);
  const double sx = fb_width / double(display_width), sy = fb_height / double(display_height);
  ViewPixels v;
  v.x = static_cast<int>(std::lround(rect.x * sx));
  v.width = std::max(1, static_cast<int>(std::lround(rect.width * sx)));
  v.height = std::max(1, static_cast<int>(std::lround(rect.height * sy)));
  v.y = fb_height - static_cast<int>(std::lround((rect.y + rect.height) * sy));
  return v;
}

void Viewer::draw_scene(int fb_width, int fb_height) {
  const render::GlApi& gl = window_->gl();
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.Viewport(0, 0, fb_width, fb_height);
  gl.ClearColor(1, 1, 1, 1);  // the renderer's background, behind the panels
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!scene_) return;
  const ViewPixels view = view_pixels(fb_width, fb_height);
  const render::DrawSettings draw = make_draw_settings(view_, field_range_max(), size_range());
  const render::Camera camera = camera_.camera();
  const bool camera_moved = !same_camera(camera, drawn_camera_);
  if (camera_moved) interacting_ = true;
  const double scale = interacting_ ? options_.interactive_scale : 1.0;
  if (needs_redraw_ || camera_moved || scale != drawn_scale_ || view.width != drawn_width_ ||
      view.height != drawn_height_ || !same_draw(draw, drawn_settings_)) {
    const int w = std::max(1, static_cast<int>(std::lround(view.width * scale)));
    const int h = std::max(1, static_cast<int>(std::lround(view.height * scale)));
    render::DrawSettings scaled = draw;
    scaled.resolution = static_cast<float>(scale);
    renderer_->draw(scaled, camera, w, h);
    drawn_scale_ = scale;
    drawn_width_ = view.width;
    drawn_height_ = view.height;
    drawn_settings_ = draw;
    drawn_camera_ = camera;
    needs_redraw_ = false;
    ++drawn_pictures_;
  }
  renderer_->present_into(view.x, view.y, view.width, view.height);
}

uint32_t Viewer::tet_at(float x, float y) const {
  if (!scene_) return kInvalidIndex;
  const ImGuiIO& io = ImGui::GetIO();
  const ui::ViewRect rect = ui::scene_rect(io.DisplaySize.x, io.DisplaySize.y, panel_);
  const float px = x - rect.x, py = y - rect.y;
  if (!(px >= 0 && py >= 0 && px < rect.width && py < rect.height)) return kInvalidIndex;
  if (renderer_->over_legend(px / rect.width, py / rect.height)) return kInvalidIndex;
  return scene_->surface
      .pick(render::pixel_ray(camera_.camera(), px, py, static_cast<int>(rect.width),
                              static_cast<int>(rect.height)))
      .tet;
}

Viewer::TetInfo Viewer::tet_info(uint32_t tet) const {
  const Lod& lod = *scene_->lod;
  const Tet& t = lod.tets()[tet];
  const std::vector<Vec3>& p = lod.positions();
  const TetShape shape = tet_shape(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
  TetInfo info;
  info.material = lod.materials()[tet];
  info.stretch = shape.stretch;
  info.size = shape.size;
  info.volume = shape.volume;
  // The nodes' neighbours: the other corners of the level's tets that hold them.
  std::vector<uint32_t> neighbours[4];
  const std::vector<Tet>& tets = lod.tets();
  for (size_t other = 0; other < tets.size(); ++other) {
    if (!lod.alive()[other]) continue;
    const Tet& o = tets[other];
    for (int k = 0; k < 4; ++k)
      if (o[0] == t[k] || o[1] == t[k] || o[2] == t[k] || o[3] == t[k])
        for (const uint32_t v : o)
          if (v != t[k]) neighbours[k].push_back(v);
  }
  for (std::vector<uint32_t>& n : neighbours) {
    std::sort(n.begin(), n.end());
    info.valence =
        std::max(info.valence, static_cast<uint32_t>(std::unique(n.begin(), n.end()) - n.begin()));
  }
  if (scene_->params_known) {
    info.max_valence = scene_->params.max_valence;
    info.min_stretch = scene_->params.min_stretch;
    info.max_size = scene_->params.sizing.size_at(tet_centroid(p[t[0]], p[t[1]], p[t[2]], p[t[3]]),
                                                  info.material);
  }
  if (field_shown() && tet < analysis_result_->tet_values.size()) {
    info.has_field = true;
    info.field = analysis_result_->tet_values[tet];
  }
  return info;
}

void Viewer::update_hover() {
  // A pointer at rest over the view for a moment, no button down: the tet under it is
  // picked once (again when the picture changes) and named in a tooltip.
  constexpr double kRestSeconds = 0.3;
  hover_waiting_ = false;
  const ImGuiIO& io = ImGui::GetIO();
  const bool button = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
  // While a task rebuilds the surface (a far move of the level), the surface drawn is
  // of another state than the LOD's.
  if (!scene_ || io.WantCaptureMouse || button || !ImGui::IsMousePosValid() ||
      surface_future_.valid()) {
    hover_ = Hover();
    return;
  }
  const Clock::time_point now = Clock::now();
  if (io.MousePos.x != hover_.x || io.MousePos.y != hover_.y) {
    hover_ = Hover();
    hover_.x = io.MousePos.x;
    hover_.y = io.MousePos.y;
    hover_.since = now;
  }
  if (!hover_.picked || hover_.picture != drawn_pictures_) {
    if (seconds_between(hover_.since, now) < kRestSeconds) {
      hover_waiting_ = true;
      return;
    }
    hover_.tet = tet_at(hover_.x, hover_.y);
    hover_.picked = true;
    hover_.picture = drawn_pictures_;
    // The pick is of the picture drawn last (a new level or mesh is drawn before this
    // frame's pick); a tet of another state is not shown.
    const Lod& lod = *scene_->lod;
    if (hover_.tet >= lod.tets().size() || !lod.alive()[hover_.tet]) hover_.tet = kInvalidIndex;
    if (hover_.tet != kInvalidIndex) hover_.info = tet_info(hover_.tet);
  }
  if (hover_.tet == kInvalidIndex) return;
  const TetInfo& info = hover_.info;
  const ImVec4 warn(0.85f, 0.35f, 0.0f, 1.0f);
  const std::string* name = find_material_name(scene_->material_names.get(), info.material);
  ImGui::BeginTooltip();
  ImGui::Text("material %d%s%s", info.material, name ? " " : "", name ? name->c_str() : "");
  const bool flat = info.stretch < info.min_stretch;
  if (scene_->params_known) {
    ImGui::TextColored(flat ? warn : ImGui::GetStyleColorVec4(ImGuiCol_Text),
                       "stretch %.4g (threshold %.4g)", info.stretch, info.min_stretch);
  } else {
    ImGui::Text("stretch %.4g", info.stretch);
  }
  if (std::isfinite(info.max_size)) {
    ImGui::TextColored(info.size > info.max_size ? warn : ImGui::GetStyleColorVec4(ImGuiCol_Text),
                       "longest edge %.4g (size %.4g here)", info.size, info.max_size);
  } else {
    ImGui::Text("longest edge %.4g", info.size);
  }
  if (info.max_valence > 0) {
    ImGui::TextColored(
        info.valence > info.max_valence ? warn : ImGui::GetStyleColorVec4(ImGuiCol_Text),
        "node valence up to %u (threshold %u)", info.valence, info.max_valence);
  } else {
    ImGui::Text("node valence up to %u", info.valence);
  }
  ImGui::Text("volume %.4g", info.volume);
  if (info.has_field) ImGui::Text("|E| %.4g", info.field);
  ImGui::EndTooltip();
}

Status Viewer::report_tet(const std::string& path) const {
  if (!script_mouse_) return Status::error("no pointer to report the tet under: 'mouse X Y' first");
  const uint32_t tet = tet_at(script_mouse_x_, script_mouse_y_);
  if (tet == kInvalidIndex) return write_file_atomically(path, "tet none\n");
  const TetInfo info = tet_info(tet);
  std::string text;
  char line[256];
  const auto put = [&](const char* key, const char* format, auto value) {
    std::snprintf(line, sizeof(line), format, value);
    text += std::string(key) + ' ' + line + '\n';
  };
  put("tet", "%u", tet);
  put("material", "%d", info.material);
  put("stretch", "%.17g", info.stretch);
  put("size", "%.17g", info.size);
  put("volume", "%.17g", info.volume);
  put("valence", "%u", info.valence);
  if (scene_->params_known) {
    put("min_stretch", "%.17g", info.min_stretch);
    put("max_size", "%.17g", info.max_size);
    put("max_valence", "%u", info.max_valence);
  }
  if (info.has_field) put("field", "%.17g", info.field);
  // Last: a name may hold blanks (the rest of the line).
  if (const std::string* name = find_material_name(scene_->material_names.get(), info.material))
    text += "name " + *name + '\n';
  return write_file_atomically(path, text);
}

Status Viewer::screenshot(const std::string& path, int width, int height) {
  if (!scene_) return Status::error("nothing to take a screenshot of: no mesh loaded");
  sync_field_colors();              // a solve may have finished earlier this frame
  if (width <= 0 || height <= 0) {  // the size of the 3D view in the window
    int fb_width = 0, fb_height = 0;
    window_->framebuffer_size(&fb_width, &fb_height);
    const ViewPixels view = view_pixels(fb_width, fb_height);
    width = view.width;
    height = view.height;
  }
  renderer_->draw(make_draw_settings(view_, field_range_max(), size_range()), camera_.camera(),
                  width, height);
  const render::Image image = renderer_->read_pixels();
  needs_redraw_ = true;  // the targets now have the screenshot's size
  return render::write_png(path, image);
}

Status Viewer::save_level(const std::string& path, bool improve, bool surfaces, bool binary) {
  if (!scene_) return Status::error("nothing to save: no mesh loaded");
  if (save_future_.valid()) return Status::error("still saving " + save_path_);
  if (is_history_path(path)) {
    // The whole collapse history, for 'tetlod lod' or to open here again later.
    if (improve || surfaces)
      return Status::error(path + ": a history is saved as it is (no improve, no boundary groups)");
    if (!scene_->result) return Status::error(path + ": nothing simplified yet: no history");
    save_path_ = path;
    const std::optional<SimplifyParams> params =
        scene_->params_known ? std::optional<SimplifyParams>(scene_->params) : std::nullopt;
    save_future_ =
        std::async(std::launch::async, [path, params, result = scene_->result,
                                        names = scene_->material_names, patches = scene_->patches] {
          Saved saved;
          saved.status = write_history(path, result->base, result->history,
                                       params ? &*params : nullptr, names.get(), patches.get());
          saved.note =
              " (the collapse history, " + std::to_string(result->history.step_count()) + " steps)";
          return saved;
        });
    return Status();
  }
  // Improving uses the thresholds of the run that made the levels (here, or saved in
  // the history file), or the panel's when they are not known.
  SimplifyParams params = scene_->params;
  if (improve && !scene_->params_known) {
    std::string error;
    if (!ui::to_simplify_params(thresholds_, &params, &error))
      return Status::error("improve: thresholds: " + error);
  }
  // A level of a history file is checked as a mesh file would be before it is saved
  // (as `tetlod lod` does): the reader's replay proves its tets positive, but a forged
  // file could still make them overlap.
  const std::string level_name =
      scene_->from_history
          ? scene_->path + " (level at step " + std::to_string(scene_->lod->step()) + ")"
          : std::string();
  WriteOptions options;
  options.surface_groups = surfaces;
  options.gmsh_binary = options.vtk_binary = binary;
  if (Status s = check_mesh_path(path, options); !s) return s;
  save_path_ = path;
  // What the level saved breaks of the run's thresholds (a level before the last may:
  // tets not yet collapsed), said as `tetlod lod` says it.
  const bool known = scene_->params_known || improve;
  save_future_ = std::async(std::launch::async, [path, improve, params, level_name, options, known,
                                                 patches = scene_->patches,
                                                 material_names = scene_->material_names,
                                                 mesh = scene_->lod->extract()]() mutable {
    Saved saved;
    if (!level_name.empty()) {
      ValidationReport report;
      if (const Status s = validate_mesh(&mesh, level_name, {}, &report); !s) {
        saved.status = Status::error("corrupt history: " + s.message() + "; nothing saved");
        return saved;
      }
    }
    if (improve) {
      const ImproveResult r = improve_mesh(&mesh, params, 4, nullptr, patches.get());
      char note[160];
      std::snprintf(note, sizeof note, " (improved: mean stretch %.3f -> %.3f, min %.3f -> %.3f)",
                    r.mean_stretch_before, r.mean_stretch_after, r.min_stretch_before,
                    r.min_stretch_after);
      saved.note = note;
    }
    if (known) {
      const ThresholdCounts b = threshold_breaks(mesh, params);
      if (b.total() > 0) saved.breaks = describe_breaks(b);
    }
    options.material_names = material_names.get();
    if (!options.surface_groups) {
      saved.status = write_mesh(path, mesh, options);
      return saved;
    }
    // The input's own groups keep their names and tags: the levels keep their borders,
    // and their faces inside a material (improved or not).
    SurfaceGroups groups;
    if (Status s =
            patches ? group_surface(mesh, &groups, *patches, true) : group_surface(mesh, &groups);
        !s) {
      saved.status = Status::error(path + ": " + s.message());
      return saved;
    }
    options.groups = &groups;
    saved.status = write_mesh(path, mesh, options);
    size_t own = 0;
    if (patches)
      for (const SurfaceGroup& g : groups.groups)
        for (const SurfacePatches::Group& p : patches->groups()) own += g.tag == p.tag;
    saved.note += " (with " + std::to_string(groups.groups.size()) + " surface groups" +
                  (own == 0 ? std::string() : ", " + std::to_string(own) + " of them the input's") +
                  ")";
    return saved;
  });
  return Status();
}

// --- Analysis ----------------------------------------------------------------------

ElectrostaticsProblem Viewer::analysis_problem(std::vector<uint32_t>* groups) const {
  ElectrostaticsProblem problem = ui::to_electrostatics_problem(analysis_);
  if (groups) groups->clear();
  if (!scene_ || !scene_->input_patches) return problem;
  const std::vector<SurfacePatches::Group>& input = scene_->input_patches->groups();
  for (uint32_t g = 0; g < analysis_.groups.size() && g < input.size(); ++g) {
    const ui::GroupAnalysis& a = analysis_.groups[g];
    if (a.role == ui::MaterialRole::kDielectric) continue;
    ElectrostaticsProblem::HeldSurface held;
    held.name = render::surface_group_label(input[g]);
    held.ground = a.role == ui::MaterialRole::kGround;
    held.potential = held.ground ? 0 : a.potential;
    problem.surfaces.push_back(std::move(held));
    if (groups) groups->push_back(g);
  }
  return problem;
}

Status Viewer::start_solve(int line) {
  if (!scene_) return Status::error("nothing to solve: no mesh loaded");
  if (solve_job_) return Status::error("a solve is already running");
  analysis_error_.clear();
  auto job = std::make_unique<SolveJob>();
  job->generation = scene_generation_;
  job->step = scene_->lod->step();
  job->problem = analysis_problem(&job->surface_groups);
  job->patches = scene_->input_patches;
  job->line = line;
  // The finest level: step 0 of the history (the input itself when nothing was
  // simplified, where step 0 is the only one). Solved once per mesh and set-up.
  const bool finest_cached = finest_ && finest_->generation == scene_generation_ &&
                             same_problem(finest_->problem, job->problem);
  job->solve_finest = job->step != 0 && !finest_cached;
  auto mesh = std::make_shared<const TetMesh>(scene_->lod->extract());
  auto alive = std::make_shared<const std::vector<uint8_t>>(scene_->lod->alive());
  std::shared_ptr<const TetMesh> finest;
  if (job->solve_finest)
    finest = scene_->result ? std::shared_ptr<const TetMesh>(scene_->result, &scene_->result->base)
                            : scene_->input;
  SolveJob* j = job.get();
  j->thread = std::thread([j, mesh, alive, finest] {
    const SolveOptions options;
    const auto progress = [j](const SolveProgress& p) {
      std::lock_guard<std::mutex> lock(j->mutex);
      j->progress = p;
    };
    ElectrostaticsProblem problem = j->problem;
    j->status = hold_groups(*mesh, *j->patches, j->surface_groups, &problem);
    if (j->status)
      j->status = solve_electrostatics(*mesh, problem, options, &j->solution, progress, &j->cancel);
    if (j->status && !j->solution.cancelled) {
      // Extract() keeps the alive tets in id order: the k-th solved tet is the k-th
      // alive one.
      const std::vector<double>& field = j->solution.field_magnitude;
      j->tets = mesh->tet_count();
      j->tet_values.assign(alive->size(), 0.0f);
      for (size_t t = 0, k = 0; t < alive->size(); ++t)
        if ((*alive)[t]) j->tet_values[t] = static_cast<float>(field[k++]);
      // The colour map's percentiles are of the field where it lives: the tets of
      // conductors and grounds (|E| 0; 42 % of the bundled spheres' tets) are left out.
      std::vector<int32_t> electrodes = j->problem.ground_materials;
      for (const auto& [m, v] : j->problem.conductors) electrodes.push_back(m);
      std::sort(electrodes.begin(), electrodes.end());
      j->sorted_field.clear();
      for (size_t k = 0; k < field.size(); ++k)
        if (!std::binary_search(electrodes.begin(), electrodes.end(), mesh->materials[k]))
          j->sorted_field.push_back(static_cast<float>(field[k]));
      std::sort(j->sorted_field.begin(), j->sorted_field.end());
      j->solution.potential = {};
      j->solution.field_magnitude = {};
      if (finest && !j->cancel) {
        {
          std::lock_guard<std::mutex> lock(j->mutex);
          j->what = "finest level";
          j->progress = {};
        }
        const TetMesh fine = extract_alive(finest->positions, finest->tets, finest->materials,
                                           std::vector<uint8_t>(finest->tet_count(), 1));
        ElectrostaticsSolution fine_solution;
        j->finest_status = hold_groups(fine, *j->patches, j->surface_groups, &problem);
        if (j->finest_status)
          j->finest_status =
              solve_electrostatics(fine, problem, options, &fine_solution, progress, &j->cancel);
        j->has_finest = j->finest_status && !fine_solution.cancelled;
        j->finest_capacitance = fine_solution.capacitance;
      }
    }
    j->done = true;
  });
  solve_job_ = std::move(job);
  return Status();
}

void Viewer::poll_solve() {
  if (!solve_job_ || !solve_job_->done) return;
  solve_job_->thread.join();
  const std::unique_ptr<SolveJob> job = std::move(solve_job_);
  const auto fail = [&](const std::string& message) {
    analysis_error_ = message;
    if (job->line > 0) fail_script(job->line, "solve: " + message);
  };
  if (job->generation != scene_generation_) return fail("the mesh changed during the solve");
  if (!job->status) return fail(job->status.message());
  if (job->solution.cancelled) {  // asked for: not a script error; the last result stays
    analysis_error_ = "cancelled";
    return;
  }
  auto result = std::make_unique<AnalysisResult>();
  result->generation = job->generation;
  result->step = job->step;
  result->tets = job->tets;
  result->problem = job->problem;
  result->solution = job->solution;
  result->tet_values = std::move(job->tet_values);
  result->sorted_field = std::move(job->sorted_field);
  analysis_result_ = std::move(result);
  analysis_superseded_.clear();
  if (job->step == 0) {
    finest_ = Finest{job->generation, job->problem, job->solution.capacitance};
  } else if (job->has_finest) {
    finest_ = Finest{job->generation, job->problem, job->finest_capacitance};
  } else if (job->solve_finest && !job->finest_status) {
    analysis_error_ = "finest level: " + job->finest_status.message();
  }
  surface_has_field_ = false;  // new values for the surface
  needs_redraw_ = true;
}

const std::vector<MaterialName>& Viewer::material_names() const {
  static const std::vector<MaterialName> kNoNames;
  return scene_ && scene_->material_names ? *scene_->material_names : kNoNames;
}

bool Viewer::field_shown() const {
  return scene_ && analysis_result_ && analysis_result_->generation == scene_generation_ &&
         analysis_result_->step == scene_->lod->step();
}

double Viewer::field_range_max() const {
  if (!surface_has_field_ || analysis_result_->sorted_field.empty()) return 0;
  const std::vector<float>& sorted = analysis_result_->sorted_field;
  const double q = std::clamp(double(view_.field_percentile), 0.0, 100.0) / 100.0;
  const auto index = static_cast<size_t>(std::lround(q * double(sorted.size() - 1)));
  const double top = sorted[std::min(index, sorted.size() - 1)];
  return top > 0 ? top : 1;  // a zero field: any range shows it
}

std::pair<double, double> Viewer::size_range() const {
  if (!scene_ || view_.color_mode != render::ColorMode::kSize) return {0, 1};
  return render::scalar_range(scene_->surface.triangles());
}

// Puts the |E| values on the surface while the field colour mode is on and the
// displayed level is the solved one; takes them off otherwise. Colours by size in
// the size colour mode.
void Viewer::sync_field_colors() {
  if (!scene_) return;
  const bool by_size = view_.color_mode == render::ColorMode::kSize;
  if (by_size != scene_->surface.color_by_size()) {
    scene_->surface.set_color_by_size(by_size);
    renderer_->update_triangles(scene_->surface.triangles(), scene_->surface.take_triangle_dirty());
    needs_redraw_ = true;
  }
  const bool want = view_.color_mode == render::ColorMode::kField && field_shown();
  if (want == surface_has_field_ && want == scene_->surface.has_tet_values()) return;
  if (want) {
    scene_->surface.set_tet_values(analysis_result_->tet_values);
  } else {
    scene_->surface.clear_tet_values();
  }
  surface_has_field_ = want;
  renderer_->update_triangles(scene_->surface.triangles(), scene_->surface.take_triangle_dirty());
  needs_redraw_ = true;
}

Status Viewer::report_analysis(const std::string& path) const {
  if (!analysis_result_) return Status::error("no solve to report: 'solve' first");
  const AnalysisResult& r = *analysis_result_;
  const ElectrostaticsSolution& s = r.solution;
  std::string text;
  char line[256];
  const auto put = [&](const char* key, const char* format, auto value) {
    std::snprintf(line, sizeof(line), format, value);
    text += std::string(key) + ' ' + line + '\n';
  };
  put("step", "%zu", r.step);
  put("tets", "%zu", r.tets);
  put("unknowns", "%zu", s.free_count);
  put("capacitance", "%.17g", s.capacitance);
  put("energy", "%.17g", s.energy);
  put("voltage", "%.17g", s.voltage);
  put("solver", "%s", s.method == SolverMethod::kDirect ? "direct" : "cg");
  put("iterations", "%d", s.iterations);
  put("relative_residual", "%.3g", s.relative_residual);
  put("seconds", "%.4f", s.seconds_setup + s.seconds_assemble + s.seconds_factor + s.seconds_solve);
  put("field_max", "%.17g", r.sorted_field.empty() ? 0.0 : double(r.sorted_field.back()));
  if (finest_ && finest_->generation == r.generation && same_problem(finest_->problem, r.problem)) {
    put("finest_capacitance", "%.17g", finest_->capacitance);
    put("difference_percent", "%.17g",
        100 * (s.capacitance - finest_->capacitance) / finest_->capacitance);
  }
  return write_file_atomically(path, text);
}

void Viewer::fill_status() {
  ui::ViewerStatus& s = status_;
  s.fps = fps_;
  s.frame_ms = frame_ms_;
  s.scene_scale = drawn_scale_ > 0 ? drawn_scale_ : 1;
  s.loading = job_ && job_->is_load;
  s.loading_path = s.loading ? job_->path : "";
  s.running = job_ && !job_->is_load;
  if (job_) {
    std::lock_guard<std::mutex> lock(job_->mutex);
    s.phase = job_->phase;
    s.past_valence_run = job_->past_valence;
    s.phase_fraction = job_->fraction;
    s.other_phase = job_->other_phase;
    s.other_fraction = job_->other_fraction;
    s.collapses = job_->collapses;
    s.elapsed_seconds = seconds_between(job_->start, Clock::now());
    s.collapses_per_second = s.elapsed_seconds > 0 ? double(s.collapses) / s.elapsed_seconds : 0;
  }
  ui::ViewerStatus::Analysis& a = s.analysis;
  a.solving = solve_job_ != nullptr;
  if (solve_job_) {
    std::lock_guard<std::mutex> lock(solve_job_->mutex);
    a.solving_what = solve_job_->what;
    a.phase = solve_job_->progress.phase;
    a.fraction = solve_job_->progress.fraction;
    a.iteration = solve_job_->progress.iteration;
    a.elapsed_seconds = seconds_between(solve_job_->start, Clock::now());
  }
  a.error = analysis_error_;
  a.has_solution = analysis_result_ && scene_ && analysis_result_->generation == scene_generation_;
  if (!a.has_solution && analysis_result_ && !analysis_superseded_.empty()) {
    a.superseded = analysis_superseded_;
    a.earlier_capacitance = analysis_result_->solution.capacitance;
    a.earlier_tets = analysis_result_->tets;
  }
  if (a.has_solution) {
    const AnalysisResult& r = *analysis_result_;
    const ElectrostaticsSolution& sol = r.solution;
    a.stale = !field_shown();
    a.setup_changed = !same_problem(r.problem, analysis_problem());
    a.solved_step = r.step;
    a.solved_tets = r.tets;
    a.unknowns = sol.free_count;
    a.capacitance = sol.capacitance;
    a.energy = sol.energy;
    a.voltage = sol.voltage;
    a.direct = sol.method == SolverMethod::kDirect;
    a.iterations = sol.iterations;
    a.residual = sol.relative_residual;
    a.seconds = sol.seconds_setup + sol.seconds_assemble + sol.seconds_factor + sol.seconds_solve;
    a.field_max = r.sorted_field.empty() ? 0 : r.sorted_field.back();
    a.field_range_max = static_cast<float>(field_range_max());
    a.finest_is_displayed = r.step == 0;
    a.has_finest =
        finest_ && finest_->generation == r.generation && same_problem(finest_->problem, r.problem);
    if (a.has_finest) a.finest_capacitance = finest_->capacitance;
  }
  if (!scene_) return;
  const Scene& scene = *scene_;
  s.mesh_name = scene.path;
  s.input_tets = scene.input->tet_count();
  s.input_vertices = scene.input->vertex_count();
  s.default_size = scene.default_size;
  s.default_size_raised = scene.default_size_raised;
  s.default_tolerance = scene.default_tolerance;
  s.materials = scene.materials;
  s.inside_group_triangles = scene.input_patches ? scene.input_patches->inside_entries().size() : 0;
  s.material_names = scene.material_names ? *scene.material_names : std::vector<MaterialName>();
  if (status_groups_generation_ != scene_generation_) {  // (once a mesh: they may be many)
    status_groups_generation_ = scene_generation_;
    s.surface_groups.clear();
    if (scene.input_patches)
      for (const SurfacePatches::Group& g : scene.input_patches->groups())
        s.surface_groups.push_back({render::surface_group_label(g), g.tag, g.triangles});
  }
  for (int k = 0; k < 3; ++k) {
    s.bounds_min[k] = static_cast<float>(k == 0 ? scene.lo.x : k == 1 ? scene.lo.y : scene.lo.z);
    s.bounds_max[k] = static_cast<float>(k == 0 ? scene.hi.x : k == 1 ? scene.hi.y : scene.hi.z);
  }
  s.from_history = scene.from_history;
  s.thresholds_from_history = thresholds_from_history_;
  s.history_thresholds =
      scene.from_history && scene.params_known ? describe_thresholds(scene.params) : "";
  s.has_result = scene.result != nullptr && !scene.from_history;
  if (s.has_result) {
    s.rejections = scene.result->rejections;
    s.splits = scene.result->splits;
    s.subdivided = !scene.params_known || scene.params.subdivide;
    s.violations = scene.result->violations;
    s.result_thresholds = scene.params_known ? describe_thresholds(scene.params) : "";
    s.result_thresholds_changed =
        scene.params_known && !ui::same_thresholds(thresholds_, scene.params);
    s.input_breaks = scene.input_breaks;
    s.above_size_reason = scene.above_size_reason;
    s.volume_changes = scene.volume_changes;
    s.area_changes = scene.area_changes;
    s.thin_materials = scene.thin_materials;
    s.past_valence = past_valence_summary(*scene.result);
    // Faces kept inside a material can be why such a run was given up (tetlod simplify
    // says the same).
    const PastValence& pv = scene.result->past_valence;
    s.kept_faces_stopped_past_valence = pv.tried && !pv.taken && !pv.stopped && pv.nodes_left > 0 &&
                                        scene.patches && !scene.patches->inside_entries().empty();
    s.simplify_seconds = run_seconds(*scene.result);
    s.result_cancelled = scene.result->cancelled;
  }
  const Lod& lod = *scene.lod;
  s.step = jump_from_ ? *jump_from_ : lod.step();  // the step on screen
  s.drawing = surface_future_.valid();
  s.step_count = lod.step_count();
  s.elements = jump_from_ ? lod.tet_count_at(*jump_from_) : lod.alive_tet_count();
  s.elements_at_target = lod.tet_count_at(static_cast<size_t>(
      std::clamp<long long>(panel_.target_step, 0, static_cast<long long>(lod.step_count()))));
  s.elements_at_end = lod.tet_count_at(lod.step_count());
  s.visible_tets = scene.surface.visible_tets();
  s.drawn_triangles = scene.surface.triangles().size() / 3;
  s.has_stats = has_stats_ && stats_generation_ == scene_generation_;
  if (s.has_stats) {
    s.stats_step = stats_step_;
    s.stats = stats_;
    s.stats_breaks = stats_breaks_;
  }
}

// --- Scripted runs ---------------------------------------------------------------

void Viewer::fail_script(int line, const std::string& message) {
  std::fprintf(stderr, "tetlod view: %s:%d: %s\n", options_.script_name.c_str(), line,
               message.c_str());
  exit_code_ = kExitBadInput;
  quit_ = true;
}

bool Viewer::settled() const {
  if ((job_ && wait_for_job_) || (solve_job_ && wait_for_solve_) || save_future_.valid() ||
      surface_future_.valid() || stats_future_.valid() || ui_capture_countdown_ >= 0)
    return false;
  if (!scene_) return true;
  if (scene_->lod->step() != static_cast<size_t>(panel_.target_step)) return false;
  if (groups_wanted() && !(groups_drawn_ && same_groups(groups_key_, groups_now()))) return false;
  return has_stats_ && stats_generation_ == scene_generation_ && stats_step_ == scene_->lod->step();
}

void Viewer::run_script() {
  if (!options_.has_script || quit_) return;
  if (bench_.active) {
    bench_frame();
    return;
  }
  if (wait_frames_ > 0) {
    --wait_frames_;
    return;
  }
  if (Clock::now() < wait_until_) return;
  if (!settled()) return;
  if (pending_job_line_ != 0) {
    if (!last_job_error_.empty()) {
      const int line = pending_job_line_ > 0 ? pending_job_line_ : 0;
      if (line > 0) {
        fail_script(line, ui::script_error_text(last_job_error_));
      } else {
        std::fprintf(stderr, "tetlod view: %s\n", ui::script_error_text(last_job_error_).c_str());
        exit_code_ = kExitBadInput;
        quit_ = true;
      }
      return;
    }
    pending_job_line_ = 0;
  }
  if (script_index_ >= options_.script.size()) return;  // done: the window stays open
  const ScriptAction& action = options_.script[script_index_++];
  const Status s = run_action(action);
  if (!s) {
    fail_script(action.line, s.message());
    return;
  }
  wait_frames_ = std::max(wait_frames_, 1);  // one frame shows the result before the next action
}

Status Viewer::run_action(const ScriptAction& a) {
  using Kind = ScriptAction::Kind;
  const bool needs_scene = a.kind != Kind::kOpen && a.kind != Kind::kThresholds &&
                           a.kind != Kind::kQuit && a.kind != Kind::kWait &&
                           a.kind != Kind::kReportAnalysis;
  if (needs_scene && !scene_) return Status::error("no mesh loaded (give FILE or 'open PATH')");
  switch (a.kind) {
    case Kind::kOpen:
      last_job_error_.clear();
      // With may-fail a path that cannot be opened only shows in the panel (and a running
      // simplification goes on), as for a user.
      if (Status s = start_load(a.path); !s) return a.flag ? Status() : s;
      wait_for_job_ = true;
      pending_job_line_ = a.flag ? 0 : a.line;
      break;
    case Kind::kThresholds:
      if (a.size) thresholds_.size = *a.size;
      if (a.stretch) thresholds_.stretch = *a.stretch;
      if (a.tolerance) thresholds_.tolerance = *a.tolerance;
      if (a.valence) thresholds_.valence = static_cast<int>(*a.valence);
      if (a.subdivide) thresholds_.subdivide = *a.subdivide;
      if (a.keep_inside) thresholds_.keep_inside_groups = *a.keep_inside;
      if (a.crease_angle) thresholds_.crease_angle = *a.crease_angle;
      if (a.size_map) {
        if (*a.size_map && !thresholds_.size_map)
          return Status::error("sizing=map: no size map (give one with the mesh: --size-map)");
        thresholds_.sizing_mode = *a.size_map ? ui::SizingMode::kMap : ui::SizingMode::kUniform;
      }
      if (a.region) {
        thresholds_.sizing_mode = ui::SizingMode::kRegion;
        thresholds_.region_spec = *a.region;
      }
      if (a.material_sizes) {
        std::vector<std::pair<int32_t, double>> sizes;
        if (Status s = resolve_material_sizes(*a.material_sizes, &material_names(), &sizes); !s)
          return s;
        // As --material-size: a material the mesh lacks is a typo, not a size to ignore.
        for (const auto& [m, size] : sizes) {
          if (scene_ && !std::binary_search(scene_->materials.begin(), scene_->materials.end(), m))
            return Status::error("material-sizes: the mesh has no material " + std::to_string(m));
        }
        // With region= on the same line both apply, as --size-field with --material-size.
        thresholds_.sizing_mode =
            a.region ? ui::SizingMode::kRegionAndMaterial : ui::SizingMode::kPerMaterial;
        // As in the CLI: size= on the same line caps every material as well.
        thresholds_.material_cap = a.size.has_value();
        thresholds_.material_sizes = std::move(sizes);
      }
      break;
    case Kind::kSimplify:
      last_job_error_.clear();
      if (job_) return Status::error("a simplification or load is already running");
      start_simplify();
      if (!last_job_error_.empty()) return Status::error(ui::script_error_text(last_job_error_));
      wait_for_job_ = a.flag;
      pending_job_line_ = a.flag ? a.line : 0;
      started_without_wait_ |= !a.flag;
      break;
    case Kind::kCancel:
      if ((!job_ || job_->is_load) && !solve_job_) {
        // A run started with wait=0 may have ended before this line (it depends on the
        // machine's speed): then there is nothing to cancel, and the script goes on.
        if (!started_without_wait_) return Status::error("no simplification or solve is running");
        std::fprintf(stderr,
                     "tetlod view: %s:%d: note: nothing to cancel: what ran with wait=0 had "
                     "ended\n",
                     options_.script_name.c_str(), a.line);
        break;
      }
      if (job_ && !job_->is_load) {
        job_->cancel = true;
        wait_for_job_ = true;
      }
      if (solve_job_) {
        solve_job_->cancel = true;
        wait_for_solve_ = true;
      }
      break;
    case Kind::kScrubStep:
      panel_.target_step =
          std::min<long long>(a.count, static_cast<long long>(scene_->lod->step_count()));
      break;
    case Kind::kScrubElements:
      panel_.target_step =
          static_cast<long long>(scene_->lod->step_for_elements(static_cast<size_t>(a.count)));
      break;
    case Kind::kScrubEnd:
      panel_.target_step = static_cast<long long>(scene_->lod->step_count());
      break;
    case Kind::kCut:
      view_.cut = true;
      view_.cut_axis = static_cast<ui::CutAxis>(a.axis);
      view_.cut_offset = static_cast<float>(a.value);
      view_.cut_flip = a.flag;
      break;
    case Kind::kCutOff:
      view_.cut = false;
      break;
    case Kind::kHide:
    case Kind::kShow: {
      int32_t m = static_cast<int32_t>(a.count);
      if (!a.word.empty()) {
        std::string why;
        if (!find_material(a.word, material_names(), &m, &why)) return Status::error(why);
      }
      if (!std::binary_search(scene_->materials.begin(), scene_->materials.end(), m))
        return Status::error("material " + std::to_string(m) + " is not in the mesh");
      auto& hidden = view_.hidden_materials;
      hidden.erase(std::remove(hidden.begin(), hidden.end(), m), hidden.end());
      if (a.kind == Kind::kHide)
        hidden.insert(std::lower_bound(hidden.begin(), hidden.end(), m), m);
      break;
    }
    case Kind::kGroups:
      if (a.word == "none") {
        view_.shown_groups.clear();
      } else {
        static const SurfacePatches kNoGroups;
        std::vector<uint32_t> groups;
        const std::string why = find_surface_groups(
            a.word, scene_->input_patches ? *scene_->input_patches : kNoGroups, &groups);
        if (!why.empty()) return Status::error("groups " + a.word + ": " + why);
        view_.shown_groups = std::move(groups);
      }
      break;
    case Kind::kColor:
      view_.color_mode = a.word == "material" ? render::ColorMode::kMaterial
                         : a.word == "field"  ? render::ColorMode::kField
                         : a.word == "size"   ? render::ColorMode::kSize
                                              : render::ColorMode::kStretch;
      break;
    case Kind::kFieldRange:
      view_.field_percentile = static_cast<float>(a.value);
      break;
    case Kind::kAnalysis: {
      ElectrostaticsProblem problem = a.problem;
      // A name no material has may be one of the input's surface groups' (as for
      // `tetlod solve`): its nodes are held.
      const std::vector<SurfacePatches::Group> no_groups;
      const std::vector<SurfacePatches::Group>& input_groups =
          scene_->input_patches ? scene_->input_patches->groups() : no_groups;
      std::vector<ui::GroupAnalysis> groups(input_groups.size());
      std::vector<bool> held(input_groups.size(), false);
      for (const ScriptAction::NamedMaterial& n : a.named) {
        int32_t m = 0;
        std::string why;
        if (!find_material(n.name, material_names(), &m, &why)) {
          uint32_t g = 0;
          // (An unnamed group, a Medit reference, as the key calls it or as surface_<tag>.)
          const auto named = [&](const SurfacePatches::Group& x) {
            return render::surface_group_label(x) == n.name ||
                   (x.name.empty() && n.name == "surface_" + std::to_string(x.tag));
          };
          while (g < input_groups.size() && !named(input_groups[g])) ++g;
          if (g == input_groups.size() || n.key == "eps") {
            std::string names;
            for (const SurfacePatches::Group& x : input_groups)
              if (names.size() < 400)
                names += (names.empty() ? "" : ", ") + render::surface_group_label(x);
            return Status::error(
                n.key + ": " + why +
                (g < input_groups.size() ? "; '" + n.name +
                                               "' is a surface group, which holds no "
                                               "permittivity (eps is a material's)"
                 : names.empty() ? std::string("; the input names no surface group either")
                                 : "; nor is it a surface group (the input's: " + names + ")"));
          }
          if (held[g])
            return Status::error(n.key + ": surface group '" + n.name + "' is given twice");
          held[g] = true;
          groups[g].role =
              n.key == "ground" ? ui::MaterialRole::kGround : ui::MaterialRole::kConductor;
          groups[g].potential = n.value;
          continue;
        }
        if (n.key == "ground")
          problem.ground_materials.push_back(m);
        else
          (n.key == "eps" ? problem.permittivities : problem.conductors).push_back({m, n.value});
      }
      // The panel holds one role and one permittivity a material: a repeat is an error
      // here, as in `tetlod solve`, not the last one silently.
      if (Status s = check_repeated_materials(problem); !s) return s;
      std::vector<int32_t> named = problem.ground_materials;
      for (const auto& [m, v] : problem.conductors) named.push_back(m);
      for (const auto& [m, eps] : problem.permittivities) named.push_back(m);
      for (const int32_t m : named)
        if (!std::binary_search(scene_->materials.begin(), scene_->materials.end(), m))
          return Status::error("material " + std::to_string(m) + " is not in the mesh");
      analysis_ = ui::analysis_settings_from(problem, scene_->materials);
      analysis_.groups = std::move(groups);
      break;
    }
    case Kind::kSolve: {
      wait_for_solve_ = a.count != 0;
      started_without_wait_ |= a.count == 0;
      const Status s = start_solve(a.flag ? 0 : a.line);
      if (a.flag && !s) analysis_error_ = s.message();
      return a.flag ? Status() : s;
    }
    case Kind::kReportAnalysis:
      return report_analysis(a.path);
    case Kind::kReportTet:
      return report_tet(a.path);
    case Kind::kColormap:
      view_.color_map = a.word == "turbo" ? render::ColorMap::kTurbo : render::ColorMap::kViridis;
      break;
    case Kind::kRange:
      view_.range_min = static_cast<float>(a.value);
      view_.range_max = static_cast<float>(a.value2);
      break;
    case Kind::kWireframe:
      view_.wireframe = a.flag;
      break;
    case Kind::kLegend:
      view_.legend = a.flag;
      break;
    case Kind::kHighlight:
      view_.highlight = true;
      view_.highlight_below = static_cast<float>(a.value);
      break;
    case Kind::kHighlightOff:
      view_.highlight = false;
      break;
    case Kind::kView: {
      const char* names[] = {"iso", "x", "y", "z"};
      if (a.word == "fit") execute({ui::CommandKind::kFit});
      for (int k = 0; k < 4; ++k)
        if (a.word == names[k]) execute({ui::CommandKind::kAxisView, "", k});
      break;
    }
    case Kind::kOrbit:
      camera_.orbit(a.value, a.value2);
      break;
    case Kind::kMouse:
      script_mouse_ = true;
      script_mouse_x_ = static_cast<float>(a.value);
      script_mouse_y_ = static_cast<float>(a.value2);
      break;
    case Kind::kPan: {
      int fb_width = 0, fb_height = 0;
      window_->framebuffer_size(&fb_width, &fb_height);
      camera_.pan(a.value, a.value2, view_pixels(fb_width, fb_height).height);
      break;
    }
    case Kind::kZoom:
      camera_.zoom(a.value);
      break;
    case Kind::kScreenshot:
      if (a.flag) {
        ui_capture_path_ = a.path;
        ui_capture_countdown_ = 2;  // after the panels have laid themselves out
        ui_capture_line_ = a.line;
        return Status();
      }
      return screenshot(a.path, a.width, a.height);
    case Kind::kSave:
      save_line_ = a.line;
      return save_level(a.path, a.flag, a.surfaces, a.binary);
    case Kind::kWait:
      if (a.flag) {  // wait done: settled() holds the script until both have ended
        wait_for_job_ = true;
        wait_for_solve_ = true;
        break;
      }
      wait_frames_ = static_cast<int>(a.count);
      wait_until_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(a.value));
      break;
    case Kind::kBenchScrub:
    case Kind::kBenchFrames:
      if (a.kind == Kind::kBenchScrub && scene_->lod->step_count() == 0)
        return Status::error("no collapse history: simplify first");
      bench_ = {};
      bench_.active = true;
      bench_.scrub = a.kind == Kind::kBenchScrub;
      bench_.frames = a.count;
      bench_.out = a.path;
      bench_.line = a.line;
      if (bench_.scrub) panel_.target_step = 0;
      break;
    case Kind::kQuit:
      quit_ = true;
      break;
  }
  return Status();
}

// Drags the scrubber from step 0 to the end over `frames` frames, then back, like
// a hand on the slider; the records hold each frame's time.
void Viewer::bench_frame() {
  Lod& lod = *scene_->lod;
  const long long last = static_cast<long long>(lod.step_count());
  if (!bench_.scrub) {
    if (++bench_.frame <= bench_.frames) return;
  } else if (bench_.frame < bench_.frames) {
    ++bench_.frame;
    const long long along = last * bench_.frame / bench_.frames;
    panel_.target_step = bench_.backward ? last - along : along;
    return;
  }
  // (At the end only once the end's surface is drawn, after a far move too.)
  if (bench_.scrub && (lod.step() != static_cast<size_t>(panel_.target_step) || jump_from_)) return;
  if (bench_.scrub && !bench_.backward) {
    bench_.backward = true;
    bench_.frame = 0;
    return;
  }
  bench_.active = false;
  std::vector<FrameRecord>& r = bench_.records;
  if (!r.empty()) r.erase(r.begin());  // the frame before the first move
  std::vector<double> frame_ms, scrub_ms, draw_ms, ui_ms, swap_ms, waited_ms;
  for (const FrameRecord& f : r) {
    frame_ms.push_back(f.frame_ms);
    waited_ms.push_back(f.waited_ms);
    scrub_ms.push_back(f.scrub_ms);
    draw_ms.push_back(f.draw_ms);
    ui_ms.push_back(f.ui_ms);
    swap_ms.push_back(f.swap_ms);
  }
  const auto quantile = [](std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(q * double(v.size())))];
  };
  double total = 0;
  for (const double f : frame_ms) total += f;
  int width = 0, height = 0;
  window_->framebuffer_size(&width, &height);
  const char* name = bench_.scrub ? "bench-scrub" : "bench-frames";
  std::printf(
      "%s: %zu steps (%zu -> %zu tets), %lld frames asked%s, %zu frames "
      "drawn, window %dx%d, 3D view at %.0f%% while moving%s\n"
      "%s: frame ms: median %.1f, p95 %.1f, max %.1f; mean %.1f fps\n"
      "%s: of which seek + update + upload ms: median %.2f, p95 %.2f, max %.2f; "
      "3D draw ms: median %.1f, max %.1f; UI ms: median %.1f; swap ms: median %.1f\n",
      name, lod.step_count(), lod.tet_count_at(0), lod.tet_count_at(lod.step_count()),
      bench_.frames, bench_.scrub ? " each way" : "", frame_ms.size(), width, height,
      100 * options_.interactive_scale, job_ ? ", a simplification running" : "", name,
      quantile(frame_ms, 0.5), quantile(frame_ms, 0.95), quantile(frame_ms, 1.0),
      total > 0 ? 1e3 * double(frame_ms.size()) / total : 0, name, quantile(scrub_ms, 0.5),
      quantile(scrub_ms, 0.95), quantile(scrub_ms, 1.0), quantile(draw_ms, 0.5),
      quantile(draw_ms, 1.0), quantile(ui_ms, 0.5), quantile(swap_ms, 0.5));
  if (quantile(waited_ms, 1.0) > 0) {
    double waited = 0;
    for (const double w : waited_ms) waited += w;
    std::printf(
        "%s: and between frames, waited ms (at most %.0f frames a second while a "
        "worker runs and nothing moves): median %.1f; with the waits, %.1f fps\n",
        name, kWorkingFps, quantile(waited_ms, 0.5),
        total + waited > 0 ? 1e3 * double(frame_ms.size()) / (total + waited) : 0);
  }
  if (!bench_.out.empty()) {
    std::ofstream out(bench_.out, std::ios::trunc);
    out << "frame,frame_ms,scrub_ms,draw_ms,ui_ms,swap_ms,step,waited_ms\n";
    for (size_t i = 0; i < r.size(); ++i)
      out << i << ',' << r[i].frame_ms << ',' << r[i].scrub_ms << ',' << r[i].draw_ms << ','
          << r[i].ui_ms << ',' << r[i].swap_ms << ',' << r[i].step << ',' << r[i].waited_ms << '\n';
    if (!out) fail_script(bench_.line, "cannot write " + bench_.out);
  }
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  // A line at a time, so that what it prints as it goes (the GL renderer, each run's
  // time) can be read while it runs, also through a pipe or a file.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  Viewer viewer(options);
  return viewer.run();
}

}  // namespace tetlod::app
