#include "ui/viewer_ui.h"

#include <imgui.h>

#include <algorithm>
#include <charconv>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

namespace tetlod::ui {
namespace {

// The input file's name of material m, or null.
const std::string* material_name(const ViewerStatus& status, int32_t m) {
  return find_material_name(&status.material_names, m);
}

// "3 shield" for a named material, else `unnamed` ("3" or "mat 3"); a long name is
// cut to `max_chars` characters and "...".
std::string material_label(const ViewerStatus& status, int32_t m, const char* unnamed_prefix,
                           size_t max_chars = 24) {
  const std::string* name = material_name(status, m);
  if (!name) return unnamed_prefix + std::to_string(m);
  std::string label = std::to_string(m) + " " + *name;
  if (name->size() > max_chars)
    label = std::to_string(m) + " " + name->substr(0, max_chars) + "...";
  return label;
}

constexpr float kPanelWidth = 380;        // the side panel
constexpr float kStatsHeight = 236;       // the statistics strip under the 3D view
constexpr float kLodHeight = 58;          // the level-of-detail strip above it
constexpr float kFoldedPanelHeight = 32;  // the side panel folded to its title bar, margins in
constexpr float kMargin = 6;
constexpr float kMinViewHeight = 120;  // the 3D view's least height, where the window allows

// Where the 3D view (and the strips under it) start: right of the side panel, or at the
// window's edge when the panel is folded to its title bar.
float scene_left(const PanelState& panel) {
  return panel.panel_collapsed ? 0.0f : kPanelWidth + 2 * kMargin;
}
// Lists of materials (shown, sized, analysed) hold at most this many, the lowest ids:
// a mesh can have thousands of materials (one per CAD volume), and a panel of
// thousands of rows would be unusable and slow every frame.
constexpr size_t kListedMaterials = 256;

// The materials the panels list: the first kListedMaterials of status.materials.
std::vector<int32_t> listed_materials(const ViewerStatus& status) {
  const size_t n = std::min(status.materials.size(), kListedMaterials);
  return {status.materials.begin(), status.materials.begin() + static_cast<long>(n)};
}

// TextDisabled, wrapped at the panel's edge.
void text_disabled_wrapped(const char* format, ...) IM_FMTARGS(1);
void text_disabled_wrapped(const char* format, ...) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  va_list args;
  va_start(args, format);
  ImGui::TextWrappedV(format, args);
  va_end(args);
  ImGui::PopStyleColor();
}

// Wrapped text in red: an error ("Error: ..."), where the action that failed is.
void text_error_wrapped(const char* label, const std::string& message) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
  ImGui::TextWrapped("%s: %s", label, message.c_str());
  ImGui::PopStyleColor();
}

// Wrapped text in orange: what a user should act on (a thinned part, a threshold broken).
void text_warning_wrapped(const char* format, ...) IM_FMTARGS(1);
void text_warning_wrapped(const char* format, ...) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
  va_list args;
  va_start(args, format);
  ImGui::TextWrappedV(format, args);
  va_end(args);
  ImGui::PopStyleColor();
}

// Under the progress bar of the first run, a bar for the run past the valence made at
// the same time on a second thread (nothing when none is).
void other_run_bar(const ViewerStatus& status) {
  if (status.other_phase.empty()) return;
  ImGui::ProgressBar(static_cast<float>(status.other_fraction), ImVec2(-1, 0),
                     other_run_progress_text(status).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Subdivision left tets above the size: a run allowed to take nodes past the\n"
        "valence threshold (then brought back) is made on a second thread while the\n"
        "first collapses; it is the result if it leaves fewer tets above the size.");
}

void copy_path(const std::string& from, char* to, size_t capacity) {
  std::snprintf(to, capacity, "%s", from.c_str());
}

// Under a list that was cut: how many materials it leaves out.
void unlisted_note(const ViewerStatus& status) {
  if (status.materials.size() > kListedMaterials)
    text_disabled_wrapped("and %zu more materials, not listed",
                          status.materials.size() - kListedMaterials);
}

void file_section(const ViewerStatus& status, PanelState* panel, std::vector<Command>* commands) {
  ImGui::TextWrapped("Mesh: %s", status.mesh_name.empty() ? "(none)" : status.mesh_name.c_str());
  if (!status.mesh_name.empty())
    ImGui::Text("%zu tets, %zu vertices", status.input_tets, status.input_vertices);
  ImGui::SetNextItemWidth(-70);
  const bool enter = ImGui::InputText("##path", panel->open_path, sizeof(panel->open_path),
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open") || enter) && panel->open_path[0] != '\0')
    commands->push_back({CommandKind::kOpen, panel->open_path});
  if (!panel->recent_files.empty() && ImGui::BeginCombo("Recent", "choose a recent file")) {
    for (const std::string& path : panel->recent_files) {
      if (ImGui::Selectable(path.c_str())) {
        copy_path(path, panel->open_path, sizeof(panel->open_path));
        commands->push_back({CommandKind::kOpen, path});
      }
    }
    ImGui::EndCombo();
  }
  ImGui::TextDisabled("(or drop a mesh file onto the window)");
  if (!status.load_error.empty()) {
    text_error_wrapped("Error", status.load_error);
  }
  // The last message in a box two lines high, there even when empty, so that a message
  // of another length does not move what is under it (a longer one scrolls, and shows
  // whole under the pointer).
  // (The lines of one wrapped text are a line height apart, without item spacing.)
  const float box_height = 2 * ImGui::GetTextLineHeight();
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::BeginChild("##message", ImVec2(0, box_height));
  ImGui::PopStyleVar();
  ImGui::TextWrapped("%s", status.message.c_str());
  const bool longer = ImGui::GetItemRectSize().y > box_height + 0.5f;
  ImGui::EndChild();
  if (longer && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40);
    ImGui::TextUnformatted(status.message.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  // The reader's notes on the loaded file, folded (they change only with the file).
  if (!status.load_notes.empty()) {
    char title[64];
    std::snprintf(title, sizeof(title), "%zu note%s on reading the file###notes",
                  status.load_notes.size(), status.load_notes.size() == 1 ? "" : "s");
    if (ImGui::TreeNode(title)) {
      for (const std::string& note : status.load_notes) {
        ImGui::Bullet();
        ImGui::SameLine();
        ImGui::TextWrapped("%s", note.c_str());
      }
      ImGui::TreePop();
    }
  }
}

// A box per surface group of the input, in its colour, flowing onto further lines: a
// group ticked is drawn over the surface in stripes of its colour.
void surface_group_boxes(const ViewerStatus& status, ViewSettings* view) {
  ImGui::Text("Surface groups drawn:");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "the input's surface groups (boundary conditions) on the level shown, in stripes;\n"
        "where the surface hides them they show through");
  const ImGuiStyle& style = ImGui::GetStyle();
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  const size_t listed = std::min(status.surface_groups.size(), kListedMaterials);
  for (uint32_t g = 0; g < listed; ++g) {
    const ViewerStatus::SurfaceGroupItem& item = status.surface_groups[g];
    auto& shown = view->shown_groups;
    const bool was = std::binary_search(shown.begin(), shown.end(), g);
    bool on = was;
    const render::Rgb c = render::surface_group_rgb(g);
    const std::string label =
        (item.label.size() > 16 ? item.label.substr(0, 16) + "..." : item.label) + "##group" +
        std::to_string(g);
    const float width = ImGui::GetFrameHeight() + style.ItemInnerSpacing.x +
                        ImGui::CalcTextSize(label.c_str(), nullptr, true).x;
    if (ImGui::GetItemRectMax().x + style.ItemSpacing.x + width <= right) ImGui::SameLine();
    ImGui::PushStyleColor(ImGuiCol_CheckMark, ImVec4(c[0], c[1], c[2], 1));
    ImGui::Checkbox(label.c_str(), &on);
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s: tag %d, %zu triangles in the input", item.label.c_str(), item.tag,
                        item.triangles);
    if (on != was) {
      if (on)
        shown.insert(std::lower_bound(shown.begin(), shown.end(), g), g);
      else
        shown.erase(std::find(shown.begin(), shown.end(), g));
    }
  }
  if (listed < status.surface_groups.size())
    text_disabled_wrapped("and %zu more groups (a script's 'groups' line draws any by name)",
                          status.surface_groups.size() - listed);
}

void view_section(const ViewerStatus& status, ViewSettings* view, std::vector<Command>* commands) {
  int mode = view->color_mode == render::ColorMode::kStretch    ? 0
             : view->color_mode == render::ColorMode::kMaterial ? 1
             : view->color_mode == render::ColorMode::kField    ? 2
                                                                : 3;
  // Two rows of two (four in one row do not fit the panel).
  ImGui::Text("Colour by");
  ImGui::SameLine();
  const float column = ImGui::GetCursorPosX();
  ImGui::RadioButton("stretch", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("material", &mode, 1);
  ImGui::SetCursorPosX(column);
  ImGui::RadioButton("size", &mode, 3);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("each tet's longest edge, over the drawn tets' range: how the sizing grades");
  ImGui::SameLine();
  ImGui::RadioButton("field |E|", &mode, 2);
  view->color_mode = mode == 0   ? render::ColorMode::kStretch
                     : mode == 1 ? render::ColorMode::kMaterial
                     : mode == 2 ? render::ColorMode::kField
                                 : render::ColorMode::kSize;
  if (view->color_mode != render::ColorMode::kMaterial) {
    int map = view->color_map == render::ColorMap::kViridis ? 0 : 1;
    ImGui::Combo("Colour map", &map, "viridis\0turbo\0");
    view->color_map = map == 0 ? render::ColorMap::kViridis : render::ColorMap::kTurbo;
  }
  const ViewerStatus::Analysis& analysis = status.analysis;
  const bool field_shown =
      view->color_mode == render::ColorMode::kField && analysis.has_solution && !analysis.stale;
  if (view->color_mode == render::ColorMode::kField && !field_shown) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    if (analysis.has_solution)
      ImGui::TextWrapped(
          "|E| is stale (the displayed level changed): showing stretch. Solve again in "
          "Analysis.");
    else if (!analysis.superseded.empty())
      ImGui::TextWrapped(
          "The last |E| is of an earlier mesh (%s since): showing stretch. Solve again in "
          "Analysis.",
          analysis.superseded.c_str());
    else
      ImGui::TextWrapped("No field yet: showing stretch. Solve in Analysis.");
    ImGui::PopStyleColor();
  }
  if (field_shown) {
    ImGui::SliderFloat("|E| top (%ile)", &view->field_percentile, 50.0f, 100.0f, "%.1f");
    ImGui::TextWrapped("|E| range [0, %.4g] (max %.4g)", analysis.field_range_max,
                       analysis.field_max);
  } else if (view->color_mode == render::ColorMode::kSize) {
    ImGui::TextWrapped("Range: the drawn tets' smallest and largest size");
  } else if (view->color_mode != render::ColorMode::kMaterial) {
    ImGui::DragFloatRange2("Range", &view->range_min, &view->range_max, 0.005f, 0.0f, 1.0f, "%.3f",
                           "%.3f", ImGuiSliderFlags_AlwaysClamp);
    keep_range_apart(&view->range_min, &view->range_max);
  }
  ImGui::Checkbox("Wireframe", &view->wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("Legend", &view->legend);

  ImGui::Checkbox("Cut", &view->cut);
  if (view->cut) {
    int axis = static_cast<int>(view->cut_axis);
    ImGui::SameLine();
    ImGui::RadioButton("x", &axis, 0);
    ImGui::SameLine();
    ImGui::RadioButton("y", &axis, 1);
    ImGui::SameLine();
    ImGui::RadioButton("z", &axis, 2);
    ImGui::SameLine();
    ImGui::Checkbox("flip", &view->cut_flip);
    view->cut_axis = static_cast<CutAxis>(axis);
    const int a = static_cast<int>(view->cut_axis);
    ImGui::SliderFloat("Offset", &view->cut_offset, status.bounds_min[a], status.bounds_max[a],
                       "%.4g");
  }
  ImGui::Checkbox("Highlight stretch below", &view->highlight);
  if (view->highlight) ImGui::SliderFloat("##below", &view->highlight_below, 0.0f, 1.0f, "%.3f");

  if (!status.materials.empty()) {
    ImGui::Text("Materials shown:");
    // The boxes flow onto further lines rather than past the panel's edge.
    const ImGuiStyle& style = ImGui::GetStyle();
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    for (const int32_t m : listed_materials(status)) {
      const bool was_hidden =
          std::binary_search(view->hidden_materials.begin(), view->hidden_materials.end(), m);
      bool shown = !was_hidden;
      const render::Rgb c = render::material_rgb(m);
      const std::string label = material_label(status, m, "", 16) + "##shown" + std::to_string(m);
      const float width = ImGui::GetFrameHeight() + style.ItemInnerSpacing.x +
                          ImGui::CalcTextSize(label.c_str(), nullptr, true).x;
      if (ImGui::GetItemRectMax().x + style.ItemSpacing.x + width <= right) ImGui::SameLine();
      ImGui::PushStyleColor(ImGuiCol_CheckMark, ImVec4(c[0], c[1], c[2], 1));
      ImGui::Checkbox(label.c_str(), &shown);
      ImGui::PopStyleColor();
      if (const std::string* name = material_name(status, m); name && ImGui::IsItemHovered())
        ImGui::SetTooltip("material %d: %s", m, name->c_str());
      if (shown == was_hidden) {
        auto& hidden = view->hidden_materials;
        if (shown)
          hidden.erase(std::find(hidden.begin(), hidden.end(), m));
        else
          hidden.insert(std::lower_bound(hidden.begin(), hidden.end(), m), m);
      }
    }
    unlisted_note(status);
  }
  if (!status.surface_groups.empty()) surface_group_boxes(status, view);
  ImGui::Text("Camera:");
  const char* names[] = {"Fit", "Iso", "X", "Y", "Z"};
  for (int i = 0; i < 5; ++i) {
    ImGui::SameLine();
    if (ImGui::Button(names[i])) {
      if (i == 0)
        commands->push_back({CommandKind::kFit});
      else
        commands->push_back({CommandKind::kAxisView, "", i - 1});
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(i == 0 ? "frame the shown materials from the current direction (key F)"
                               : "frame the shown materials from this direction (key %d)",
                        i - 1);
  }
  text_disabled_wrapped("drag: orbit, right/middle or shift-drag: pan, wheel: zoom");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Keys: F fit, 0 iso, 1/2/3 x/y/z views; the level of detail: left/right one step,\n"
        "page up/down a hundredth of the history, home/end the finest/coarsest level");
}

// The stretch and valence sliders' ranges (core/simplify.h check_params(): stretch in
// (0, 1), valence >= 4). The size and tolerance sliders follow the model:
// size_slider_range(), tolerance_slider_range().
constexpr double kStretchRange[2] = {0.01, 0.9};
constexpr int kValenceRange[2] = {4, 200};
// The crease angle's (check_params(): between 0 and 180 degrees).
constexpr double kCreaseRange[2] = {1, 179};

// The input's bounding-box diagonal, which the size and tolerance sliders follow.
double diagonal(const ViewerStatus& status) {
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = double(status.bounds_max[k]) - double(status.bounds_min[k]);
    sum += d * d;
  }
  return std::sqrt(sum);
}

// A logarithmic slider over a length in `range`, clamping typed values to it. Its
// format may have many digits (log_slider_format()); a value set by dragging is
// rounded to 4 significant ones (a pixel moves it by about 4 %), so that it reads as
// it did with "%.4g"; a typed one is kept as typed.
bool length_slider(const char* label, double* value, const SliderRange& range,
                   const std::string& prefix = "") {
  const bool changed =
      ImGui::SliderScalar(label, ImGuiDataType_Double, value, &range.min, &range.max,
                          log_slider_format(range, prefix).c_str(),
                          ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  if (changed && ImGui::IsMouseDown(ImGuiMouseButton_Left) && *value > 0) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.4g", *value);
    *value = std::clamp(std::strtod(text, nullptr), range.min, range.max);
  }
  return changed;
}

void thresholds_section(const ViewerStatus& status, ThresholdSettings* t,
                        std::vector<Command>* commands) {
  ImGui::TextDisabled("ctrl-click a slider to type a value");
  if (status.thresholds_from_history) {
    text_disabled_wrapped("On open: the thresholds the history was made with");
  } else {
    if (status.from_history && !status.history_thresholds.empty()) {
      // from_simplify_params() declined them; the text under Simplify gives them.
      text_disabled_wrapped(
          "The history's thresholds (a size map with region rules or material sizes) do not "
          "fit the panel: below are the mesh's defaults");
    }
    if (t->size_map) {
      text_disabled_wrapped(
          "On open: the size map given with the mesh, capped at its largest size; tolerance "
          "%.4g = 0.001 x diagonal",
          status.default_tolerance);
    } else if (status.default_size > 0) {
      text_disabled_wrapped(
          "On open: size %.4g %s, tolerance %.4g = 0.001 x diagonal (hover)", status.default_size,
          status.default_size_raised ? "(3 x median tet size, raised for a graded mesh)"
                                     : "= 3 x median tet size",
          status.default_tolerance);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Opening a mesh resets every threshold and the sizing: size = 3 x the median tet\n"
            "size (longest edge), so that subdivision, which splits every edge longer than\n"
            "half the size, leaves most edges whole; on a graded mesh (fine parts, coarse\n"
            "air) more, until subdivision would at most double the tets; tolerance = 0.001 x\n"
            "the bounding-box diagonal (as tetlod simplify); stretch %.3g, valence %d,\n"
            "crease angle %g, uniform sizing.",
            ThresholdSettings{}.stretch, ThresholdSettings{}.valence,
            ThresholdSettings{}.crease_angle);
    }
  }
  const double model_diagonal = diagonal(status);
  const SliderRange tolerance_range = tolerance_slider_range(model_diagonal, t->tolerance);
  length_slider("tolerance (TL)", &t->tolerance, tolerance_range);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%.4g to %.4g, from the model's diagonal (%.4g)", tolerance_range.min,
                      tolerance_range.max, model_diagonal);
  if (!uses_material_sizes(t->sizing_mode)) {  // else the cap is the table's "all" row
    const SliderRange size_range = size_slider_range(model_diagonal, t->size);
    length_slider(t->sizing_mode == SizingMode::kUniform ? "size (SZ)" : "size cap (SZ)", &t->size,
                  size_range);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%.4g to %.4g, from the model's diagonal (%.4g)", size_range.min,
                        size_range.max, model_diagonal);
  }
  // A typed value is clamped to the slider's range, within the valid one.
  ImGui::SliderScalar("stretch (ST)", ImGuiDataType_Double, &t->stretch, &kStretchRange[0],
                      &kStretchRange[1], "%.3f", ImGuiSliderFlags_AlwaysClamp);
  ImGui::SliderInt("valence (VL)", &t->valence, kValenceRange[0], kValenceRange[1], "%d",
                   ImGuiSliderFlags_AlwaysClamp);
  int mode = static_cast<int>(t->sizing_mode);
  // The size map is offered only where one was given (it belongs to the mesh opened).
  ImGui::Combo("Sizing", &mode,
               t->size_map ? "uniform\0region\0per material\0region and per material\0size map\0"
                           : "uniform\0region\0per material\0region and per material\0");
  t->sizing_mode = static_cast<SizingMode>(mode);
  if (t->sizing_mode == SizingMode::kMap && t->size_map) {
    text_disabled_wrapped(
        "sizes %.4g to %.4g at the input's vertices, linear in its tets (%s); the cap above "
        "limits them too",
        t->size_map->smallest(), t->size_map->largest(), t->size_map_name.c_str());
  }
  if (uses_region(t->sizing_mode)) {
    char buffer[512];
    copy_path(t->region_spec, buffer, sizeof(buffer));
    if (ImGui::InputText("rules", buffer, sizeof(buffer))) t->region_spec = buffer;
    text_disabled_wrapped(
        "radial:cx,cy,cz,s0,g; axis:cx,cy,cz,dx,dy,dz,s0,g; box:x0,y0,z0,x1,y1,z1,s "
        "(';' between rules)");
  }
  if (uses_material_sizes(t->sizing_mode)) {
    // A material without a size of its own has no per-material limit, as with
    // `--material-size` (only the sizes listed); tick it to give it one.
    text_disabled_wrapped(t->sizing_mode == SizingMode::kRegionAndMaterial
                              ? "size (SZ) per material; unticked: only the rules above"
                              : "size (SZ) per material; unticked: no size limit");
    // Each row named as in the material list ("3 shield"), in a wider column where the
    // materials have names (a long one cut, whole under the pointer).
    const std::vector<int32_t> listed = listed_materials(status);
    const bool named = std::any_of(listed.begin(), listed.end(),
                                   [&](int32_t m) { return material_name(status, m) != nullptr; });
    const float column = named ? 170 : 90;
    // The cap over every material, as --size given with --material-size.
    ImGui::Checkbox("all", &t->material_cap);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "A size cap for every material besides its own size\n"
          "(tetlod simplify --size S --material-size ...)");
    ImGui::SameLine(column);
    if (t->material_cap) {
      ImGui::SetNextItemWidth(-1);
      length_slider("##cap", &t->size, size_slider_range(model_diagonal, t->size), "cap ");
    } else {
      ImGui::TextDisabled("no size cap");
    }
    auto& sizes = t->material_sizes;
    for (const int32_t m : listed) {
      auto it =
          std::find_if(sizes.begin(), sizes.end(), [m](const auto& p) { return p.first == m; });
      ImGui::PushID(m);
      const std::string label = material_label(status, m, "mat ", 12);
      bool limited = it != sizes.end();
      const bool changed = ImGui::Checkbox(label.c_str(), &limited);
      if (const std::string* name = material_name(status, m); name && ImGui::IsItemHovered())
        ImGui::SetTooltip("material %d: %s", m, name->c_str());
      if (changed) {
        if (limited) {
          sizes.insert(std::lower_bound(sizes.begin(), sizes.end(), std::make_pair(m, 0.0)),
                       {m, t->size});
        } else {
          sizes.erase(it);
        }
        it = std::find_if(sizes.begin(), sizes.end(), [m](const auto& p) { return p.first == m; });
      }
      ImGui::SameLine(column);
      if (it != sizes.end()) {
        ImGui::SetNextItemWidth(-1);
        length_slider("##size", &it->second, size_slider_range(model_diagonal, it->second));
      } else {
        ImGui::TextDisabled("no size limit");
      }
      ImGui::PopID();
    }
    unlisted_note(status);
  }
  ImGui::Checkbox("Subdivide first", &t->subdivide);
  // The crease angle beside it, in that row (a row of its own pushed Simplify below a
  // 800-pixel window's edge).
  ImGui::SameLine();
  ImGui::SetNextItemWidth(std::max(60.0f, ImGui::GetContentRegionAvail().x -
                                              ImGui::CalcTextSize("crease").x -
                                              ImGui::GetStyle().ItemInnerSpacing.x));
  ImGui::SliderScalar("crease", ImGuiDataType_Double, &t->crease_angle, &kCreaseRange[0],
                      &kCreaseRange[1], "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "A boundary or interface edge whose two faces' normals differ by more than this\n"
        "is a feature curve, kept as one (tetlod simplify --crease-angle; default %g)",
        SimplifyParams{}.crease_angle_degrees);
  if (status.inside_group_triangles > 0) {
    ImGui::Checkbox("Keep groups inside materials", &t->keep_inside_groups);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "The input's surface groups inside a material (%zu triangles):\n"
          "kept as they are, so that Save can write them\n"
          "(tetlod simplify --surfaces). Off: coarsened like the rest\n"
          "of the material, and not written (tetlod simplify).",
          status.inside_group_triangles);
  }

  // Simplify stays where it is, greyed while a run goes, and Cancel comes beside it: a
  // second click on Simplify does nothing (not cancel, nor tick what slid under it).
  ImGui::BeginDisabled(status.running);
  if (ImGui::Button("Simplify") && !status.mesh_name.empty())
    commands->push_back({CommandKind::kSimplify});
  ImGui::EndDisabled();
  if (!status.running) {
    if (!status.simplify_error.empty()) {  // here, where the thresholds can be changed
      text_error_wrapped("Error", status.simplify_error);
    }
  } else {
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) commands->push_back({CommandKind::kCancel});
    ImGui::SameLine();
    ImGui::ProgressBar(static_cast<float>(status.phase_fraction), ImVec2(-1, 0),
                       section_progress_text(status).c_str());
    other_run_bar(status);
    ImGui::TextWrapped("%zu collapses, %.0f /s, %.1f s", status.collapses,
                       status.collapses_per_second, status.elapsed_seconds);
  }
  if (status.from_history && !status.history_thresholds.empty()) {
    ImGui::TextWrapped(
        "Levels from a saved collapse history (%zu steps), made with %s (Save's improve "
        "uses them). It keeps no run statistics; Simplify starts again from its finest level.",
        status.step_count, status.history_thresholds.c_str());
  } else if (status.from_history) {
    ImGui::TextWrapped(
        "Levels from a saved collapse history (%zu steps), saved without its thresholds "
        "(Save's improve uses the panel's) or run statistics; Simplify starts again from its "
        "finest level.",
        status.step_count);
  }
  if (status.has_result) {
    if (status.subdivided) {
      ImGui::TextWrapped("Last run: %.2f s (subdivide, classify, simplify), %zu splits%s",
                         status.simplify_seconds, status.splits,
                         status.result_cancelled ? " (cancelled)" : "");
    } else {
      ImGui::TextWrapped("Last run: %.2f s (classify, simplify), no subdivision%s",
                         status.simplify_seconds, status.result_cancelled ? " (cancelled)" : "");
    }
    if (!status.past_valence.empty())
      ImGui::TextWrapped("Past the valence: %s.", status.past_valence.c_str());
    if (status.kept_faces_stopped_past_valence)
      text_disabled_wrapped(
          "The surface groups inside a material are kept as they are, which can leave nodes "
          "next to them that nothing may bring back: unticking \"Keep groups inside materials\" "
          "may "
          "let that run be taken.");
    // What the tolerance did to the materials' volumes, where it is much (a thin conductor
    // thinned): in orange, as tetlod simplify's note.
    if (!status.volume_changes.empty()) {
      text_warning_wrapped(
          "Volumes changed by more than 1 %%: %s (the tolerance lets surfaces move that far; "
          "a smaller one keeps them).",
          status.volume_changes.c_str());
    }
    if (!status.area_changes.empty()) {
      text_warning_wrapped(
          "Surface groups' areas changed by more than 1 %%: %s (their borders move within "
          "the tolerance; a smaller one keeps them).",
          status.area_changes.c_str());
    }
    // Layers a few tolerances thick, whose volume may hardly change as both sides move.
    if (!status.thin_materials.empty()) {
      text_warning_wrapped(
          "Thin for the tolerance: %s (twice the volume over the surface's area); its "
          "surfaces may move by up to the tolerance: a tenth of the thickness keeps them.",
          status.thin_materials.c_str());
    }
    // The guarantee, and where it could not reach: what the final mesh still breaks.
    const ThresholdViolations& v = status.violations;
    if (status.result_thresholds_changed) {  // of other thresholds than the sliders': greyed
      text_disabled_wrapped("%s", final_mesh_text(status).c_str());
      if (!status.above_size_reason.empty())
        text_disabled_wrapped("Above the size: %s", status.above_size_reason.c_str());
    } else if (v.below_stretch + v.above_size + v.above_valence == 0) {
      ImGui::TextWrapped("%s", final_mesh_text(status).c_str());
    } else {
      text_warning_wrapped("%s", final_mesh_text(status).c_str());
      if (!status.above_size_reason.empty())
        ImGui::TextWrapped("Above the size: %s", status.above_size_reason.c_str());
    }
  }
}

// The statistics strip's height: its own, less in a window too short for it and the 3D
// view's least height above the level-of-detail strip (a 1920x300 window showed no view,
// a 2000x200 one the statistics over everything).
// 0 where it is off, or would be too short to show a row (then it is not drawn).
float stats_height(float display_height, bool shown) {
  const float h =
      std::min(display_height - kLodHeight - 3 * kMargin - kMinViewHeight, kStatsHeight);
  return shown && h >= 60 ? h : 0.0f;
}

// The level-of-detail strip: a bar across the bottom of the 3D view (above the statistics),
// always in sight, whose slider is as wide as the view, so that a history of thousands of
// steps can be scrubbed a few steps a pixel.
void lod_strip(const ViewerStatus& status, PanelState* panel, std::vector<Command>* commands) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  const float left = std::max(scene_left(*panel), kMargin);
  const float stats = stats_height(viewport->WorkSize.y, panel->show_stats);
  const float below = stats > 0 ? stats + kMargin : 0.0f;
  ImGui::SetNextWindowPos(
      ImVec2(viewport->WorkPos.x + left,
             viewport->WorkPos.y + viewport->WorkSize.y - below - kLodHeight - kMargin),
      ImGuiCond_Always);
  ImGui::SetNextWindowSize(
      ImVec2(std::max(200.0f, viewport->WorkSize.x - left - kMargin), kLodHeight),
      ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.9f);
  ImGui::Begin("Level of detail", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
  const bool wide = ImGui::GetContentRegionAvail().x >= 520;  // room for the label
  if (status.step_count == 0) {
    ImGui::PushTextWrapPos(0);  // over both rows if need be
    ImGui::TextDisabled("%s%s", wide ? "Level of detail: " : "", no_history_text(status).c_str());
    ImGui::PopTextWrapPos();
    ImGui::End();
    return;
  }
  if (wide) {
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted("Level of detail");
    ImGui::SameLine();
  }
  const long long last = static_cast<long long>(status.step_count);
  int step = static_cast<int>(panel->target_step);
  char format[64];
  std::snprintf(format, sizeof(format), "step %%d of %lld: %zu elements", last,
                status.elements_at_target);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderInt("##step", &step, 0, static_cast<int>(last), format,
                       ImGuiSliderFlags_AlwaysClamp))
    panel->target_step = step;
  const auto key_tip = [](const char* keys) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (over the view)", keys);
  };
  if (ImGui::ArrowButton("##back", ImGuiDir_Left)) panel->target_step -= 1;
  key_tip("one step finer: the left arrow key; page up: a hundredth of the history");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##forward", ImGuiDir_Right)) panel->target_step += 1;
  key_tip("one step coarser: the right arrow key; page down: a hundredth of the history");
  ImGui::SameLine();
  if (ImGui::Button("Finest")) panel->target_step = 0;
  key_tip("the finest level: the Home key");
  ImGui::SameLine();
  if (ImGui::Button("Coarsest")) panel->target_step = last;
  key_tip("the coarsest level: the End key");
  panel->target_step = std::clamp(panel->target_step, 0LL, last);
  ImGui::SameLine();
  // The number of elements to jump to (Enter or Jump), as wide as the strip allows.
  const float jump_width = ImGui::CalcTextSize("Jump").x + 2 * ImGui::GetStyle().FramePadding.x;
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  ImGui::SetNextItemWidth(
      std::clamp(ImGui::GetContentRegionAvail().x - jump_width - spacing, 60.0f, 100.0f));
  // The box follows the level the slider, keys or buttons go to, unless it is being
  // typed in (then the level a jump reaches shows what it holds).
  if (!panel->jump_editing && status.elements_at_target != panel->jump_synced) {
    panel->jump_elements = static_cast<int>(
        std::min<size_t>(status.elements_at_target, std::numeric_limits<int>::max()));
    panel->jump_synced = status.elements_at_target;
  }
  // The number is taken as it is typed (with EnterReturnsTrue it was only on Enter, so
  // a click on Jump jumped to the number before), and Enter, which ends the typing, jumps.
  ImGui::InputInt("##elements", &panel->jump_elements, 0, 0);
  bool jump = ImGui::IsItemDeactivated() && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter));
  panel->jump_editing = ImGui::IsItemActive();
  ImGui::SameLine();
  jump |= ImGui::Button("Jump");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("to the level nearest this number of elements (or Enter in the box)");
  if (jump) commands->push_back({CommandKind::kJumpElements, "", panel->jump_elements});
  // What is on screen (behind the slider while the mesh catches up), shorter if the strip
  // is narrow, left out if it is narrower still.
  char shown[128], shown_short[64];
  const char* drawing = status.drawing ? " (drawing...)" : "";
  std::snprintf(shown, sizeof(shown), "shown: step %zu, %zu elements (%zu at the end)%s",
                status.step, status.elements, status.elements_at_end, drawing);
  std::snprintf(shown_short, sizeof(shown_short), "shown: step %zu%s", status.step, drawing);
  ImGui::SameLine();
  const float room = ImGui::GetContentRegionAvail().x;
  if (ImGui::CalcTextSize(shown_short).x <= room) {
    ImGui::TextUnformatted(ImGui::CalcTextSize(shown).x <= room ? shown : shown_short);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", shown);
  }
  ImGui::End();
}

void output_section(const ViewerStatus& status, PanelState* panel, std::vector<Command>* commands) {
  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##save", panel->save_path, sizeof(panel->save_path));
  ImGui::SameLine();
  if (ImGui::Button("Save level")) {
    panel->output_used = true;
    commands->push_back({CommandKind::kSave, panel->save_path,
                         (panel->save_improved ? kSaveImproved : 0) |
                             (panel->save_surfaces ? kSaveSurfaces : 0) |
                             (panel->save_binary ? kSaveBinary : 0)});
  }
  text_disabled_wrapped(".mesh .meshb .msh .node .vtk .vtu .bdf .nas .inp; .tlh: the history");
  ImGui::Checkbox("improve shapes first", &panel->save_improved);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Before saving, edge removals, flips and vertex moves that raise the worst\n"
        "stretch, within the run's thresholds; boundaries and interfaces stay where they\n"
        "are. The levels on screen do not change.");
  ImGui::Checkbox("boundary groups", &panel->save_surfaces);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Also write the boundary and interface triangles for boundary conditions: the\n"
        "input file's own surface groups under their names and tags, the rest a group\n"
        "per material pair (boundary_<m>, interface_<a>_<b>). In .msh physical\n"
        "surfaces, .mesh triangle references, a TetGen .face file, .inp node sets and\n"
        "element-face surfaces, .vtk/.vtu triangle cells and Nastran CTRIA3s (by tag).");
  ImGui::SameLine();
  ImGui::Checkbox("binary", &panel->save_binary);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Write .msh, .vtk and .vtu in binary, as gmsh -bin and ParaView do: smaller, and\n"
        "much faster for them to read (.meshb is always binary; other formats are text).");
  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##shot", panel->screenshot_path, sizeof(panel->screenshot_path));
  ImGui::SameLine();
  if (ImGui::Button("Screenshot")) {
    panel->output_used = true;
    Command c{CommandKind::kScreenshot, panel->screenshot_path};
    c.width = panel->screenshot_size[0];  // checked with the path (viewer.cpp)
    c.height = panel->screenshot_size[1];
    c.with_ui = panel->screenshot_ui;
    commands->push_back(c);
  }
  ImGui::Checkbox("with UI (window size)", &panel->screenshot_ui);
  if (!panel->screenshot_ui) {
    ImGui::SetNextItemWidth(160);
    ImGui::InputInt2("size (0: view)", panel->screenshot_size);
  }
  // How the last Save or Screenshot went, here too: the File section, which says it, is
  // often scrolled out of sight when this one is used.
  if (panel->output_used && !status.load_error.empty()) {
    text_error_wrapped("Error", status.load_error);
  } else if (panel->output_used && !status.message.empty()) {
    ImGui::TextWrapped("%s", status.message.c_str());
  }
}

void analysis_section(const ViewerStatus& status, AnalysisSettings* settings,
                      std::vector<Command>* commands) {
  const ViewerStatus::Analysis& a = status.analysis;
  auto& materials = settings->materials;
  // The materials of the loaded mesh: a role kept for a material of another mesh would
  // make the solver fail on an id that is not there.
  const std::vector<int32_t> listed = listed_materials(status);
  materials.erase(std::remove_if(materials.begin(), materials.end(),
                                 [&](const MaterialAnalysis& x) {
                                   return !std::binary_search(listed.begin(), listed.end(),
                                                              x.material);
                                 }),
                  materials.end());
  for (const int32_t m : listed) {
    const auto it =
        std::lower_bound(materials.begin(), materials.end(), m,
                         [](const MaterialAnalysis& x, int32_t id) { return x.material < id; });
    if (it == materials.end() || it->material != m) materials.insert(it, MaterialAnalysis{m});
  }
  text_disabled_wrapped("-div(eps grad u) = 0, linear elements (tetlod solve)");
  settings->groups.resize(status.surface_groups.size());
  const size_t listed_groups = std::min(status.surface_groups.size(), kListedMaterials);
  if (ImGui::BeginTable("analysis_materials", 3, ImGuiTableFlags_SizingStretchProp)) {
    for (MaterialAnalysis& m : materials) {
      ImGui::PushID(m.material);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const render::Rgb c = render::material_rgb(m.material);
      ImGui::TextColored(ImVec4(c[0], c[1], c[2], 1), "%s",
                         material_label(status, m.material, "mat ").c_str());
      ImGui::TableNextColumn();
      int role = static_cast<int>(m.role);
      ImGui::SetNextItemWidth(-1);
      ImGui::Combo("##role", &role, "dielectric\0conductor\0ground\0");
      m.role = static_cast<MaterialRole>(role);
      ImGui::TableNextColumn();
      ImGui::SetNextItemWidth(-1);
      if (m.role == MaterialRole::kConductor) {
        ImGui::InputDouble("##v", &m.potential, 0, 0, "V = %.4g");
      } else if (m.role == MaterialRole::kDielectric) {
        ImGui::InputDouble("##eps", &m.permittivity, 0, 0, "eps = %.4g");
      } else {
        ImGui::TextDisabled("V = 0");
      }
      ImGui::PopID();
    }
    // The input's surface groups, whose nodes a conductor or ground may hold (a port),
    // in the same columns.
    for (uint32_t g = 0; g < listed_groups; ++g) {
      GroupAnalysis& group = settings->groups[g];
      ImGui::PushID(-1 - static_cast<int>(g));  // apart from the materials' ids
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const std::string& label = status.surface_groups[g].label;
      const render::Rgb c = render::surface_group_rgb(g);
      ImGui::TextColored(ImVec4(c[0], c[1], c[2], 1), "%s",
                         (label.size() > 24 ? label.substr(0, 24) + "..." : label).c_str());
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "surface group %s (tag %d): held as a conductor or ground, its nodes "
            "are; free, they are not",
            label.c_str(), status.surface_groups[g].tag);
      ImGui::TableNextColumn();
      int role = static_cast<int>(group.role);
      ImGui::SetNextItemWidth(-1);
      ImGui::Combo("##grouprole", &role, "free\0conductor\0ground\0");
      group.role = static_cast<MaterialRole>(role);
      ImGui::TableNextColumn();
      ImGui::SetNextItemWidth(-1);
      if (group.role == MaterialRole::kConductor)
        ImGui::InputDouble("##gv", &group.potential, 0, 0, "V = %.4g");
      else if (group.role == MaterialRole::kGround)
        ImGui::TextDisabled("V = 0");
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  if (status.materials.size() > kListedMaterials)
    text_disabled_wrapped("and %zu more materials, not listed: dielectrics of eps 1",
                          status.materials.size() - kListedMaterials);
  if (status.surface_groups.size() > listed_groups)
    text_disabled_wrapped("and %zu more surface groups, not listed: free",
                          status.surface_groups.size() - listed_groups);
  ImGui::Checkbox("Ground the outer boundary", &settings->ground_boundary);

  ImGui::BeginDisabled(a.solving);  // as Simplify: in place, greyed while it solves
  if (ImGui::Button("Solve displayed level") && !status.mesh_name.empty())
    commands->push_back({CommandKind::kSolve});
  ImGui::EndDisabled();
  if (a.solving) {
    ImGui::SameLine();
    if (ImGui::Button("Cancel##solve")) commands->push_back({CommandKind::kCancelSolve});
    char overlay[128];
    std::snprintf(overlay, sizeof(overlay), "%s: %s %.0f%% (it %d)", a.solving_what.c_str(),
                  a.phase.c_str(), 100 * a.fraction, a.iteration);
    ImGui::ProgressBar(static_cast<float>(a.fraction), ImVec2(-1, 0), overlay);
    ImGui::Text("%.1f s", a.elapsed_seconds);
  }
  if (!a.error.empty()) {
    text_error_wrapped("Solver", a.error);
  }
  if (!a.has_solution) {
    if (!a.superseded.empty())
      text_disabled_wrapped(
          "The last solve (C = %.10g, %zu tets) no longer applies: %s since. Solve again "
          "for this mesh.",
          a.earlier_capacitance, a.earlier_tets, a.superseded.c_str());
    return;
  }
  ImGui::TextWrapped("Solved: step %zu, %zu tets, %zu unknowns%s", a.solved_step, a.solved_tets,
                     a.unknowns, a.stale ? " (not the displayed level)" : "");
  if (a.setup_changed) text_disabled_wrapped("(the set-up above changed since: solve again)");
  ImGui::Text("C = %.10g", a.capacitance);
  ImGui::Text("W = %.10g (V = %.4g)", a.energy, a.voltage);
  if (a.direct)
    ImGui::TextWrapped("direct LDL^T, residual %.2g, %.3f s", a.residual, a.seconds);
  else
    ImGui::TextWrapped("CG: %d iterations, residual %.2g, %.3f s", a.iterations, a.residual,
                       a.seconds);
  if (a.finest_is_displayed) {
    ImGui::Text("This is the finest level.");
  } else if (a.has_finest) {
    const double diff = 100 * (a.capacitance - a.finest_capacitance) / a.finest_capacitance;
    ImGui::TextWrapped("Finest level (step 0: the input as subdivided): C = %.10g",
                       a.finest_capacitance);
    ImGui::Text("Difference from finest: %+.4f %%", diff);
  } else {
    ImGui::TextDisabled("Finest level: not solved yet");
  }
}

void row_cells(const PropertyRow& r) {
  ImGui::TableNextColumn();
  ImGui::Text("%zu", r.nodes);
  ImGui::TableNextColumn();
  ImGui::Text("%zu", r.edges);
  ImGui::TableNextColumn();
  ImGui::Text("%zu", r.elements);
  ImGui::TableNextColumn();
  ImGui::Text("%.3f", r.average_stretch);
  ImGui::TableNextColumn();
  ImGui::Text("%.3f", r.min_stretch);
  ImGui::TableNextColumn();
  ImGui::Text("%u", r.max_valence);
  ImGui::TableNextColumn();
  ImGui::Text("%.3g", r.max_size);
  ImGui::TableNextColumn();
  ImGui::Text("%.7g", r.volume);
}

void stats_window(const ViewerStatus& status, PanelState* panel) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  const float height = stats_height(viewport->WorkSize.y, panel->show_stats);
  if (height == 0) return;
  const float strip_left = std::max(scene_left(*panel), kMargin);
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + strip_left,
                                 viewport->WorkPos.y + viewport->WorkSize.y - height - kMargin),
                          ImGuiCond_Always);
  ImGui::SetNextWindowSize(
      ImVec2(std::max(200.0f, viewport->WorkSize.x - strip_left - kMargin), height),
      ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.9f);
  const ImGuiWindowFlags window_flags =
      ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
  if (!ImGui::Begin("Statistics of the displayed level", &panel->show_stats, window_flags)) {
    ImGui::End();
    return;
  }
  if (!status.has_stats) {
    ImGui::TextDisabled("computing...");
    ImGui::End();
    return;
  }
  // The chart narrows with the window (down to 120 px) before the table does (to 200 px,
  // then it scrolls): a chart cut at the window's edge looked like another distribution.
  const float room = ImGui::GetContentRegionAvail().x;
  const float chart_width = std::clamp(room - 208, 120.0f, 250.0f);
  const float table_width = std::max(200.0f, room - chart_width - 8);
  ImGui::BeginGroup();
  ImGui::Text("Table I at step %zu%s", status.stats_step,
              status.stats_step == status.step ? "" : " (updating...)");
  // A level before the last may break the run's thresholds (tets not yet collapsed):
  // what Save would write, as `tetlod lod` says it.
  if (!status.stats_breaks.empty()) {
    text_warning_wrapped("this level: %s", status.stats_breaks.c_str());
  }
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_ScrollX | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingFixedFit;
  if (ImGui::BeginTable("table1", 9, flags,
                        ImVec2(table_width, ImGui::GetContentRegionAvail().y - 24))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* h :
         {"", "nodes", "edges", "elements", "avg str", "min str", "max val", "max size", "volume"})
      ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("whole");
    row_cells(status.stats.whole);
    // Only the rows in sight are drawn: a mesh may have thousands of materials.
    const auto& rows = status.stats.per_material;
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(rows.size()));
    while (clipper.Step()) {
      for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
        const MaterialRow& m = rows[static_cast<size_t>(i)];
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(material_label(status, m.material, "mat ").c_str());
        row_cells(m.row);
      }
    }
    ImGui::EndTable();
  }
  ImGui::EndGroup();
  ImGui::SameLine();
  std::vector<float> bins(status.stats.stretch_histogram.begin(),
                          status.stats.stretch_histogram.end());
  float top = 0;
  for (const float b : bins) top = std::max(top, b);
  ImGui::BeginGroup();
  ImGui::Text("Stretch histogram (0 .. 1)");
  const float line = ImGui::GetTextLineHeightWithSpacing();
  ImGui::PlotHistogram("##hist", bins.data(), static_cast<int>(bins.size()), 0, nullptr, 0,
                       top * 1.1f,
                       ImVec2(chart_width, ImGui::GetContentRegionAvail().y - 24 - line));
  // Tick labels under stretch 0, 0.5 and 1: the bars span the plot's frame less its
  // padding (as PlotHistogram draws them), each label centred on its stretch and kept
  // inside the frame.
  const ImVec2 frame_min = ImGui::GetItemRectMin(), frame_max = ImGui::GetItemRectMax();
  const float x0 = frame_min.x + ImGui::GetStyle().FramePadding.x;
  const float x1 = frame_max.x - ImGui::GetStyle().FramePadding.x;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImU32 tick_color = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  for (const float stretch : {0.0f, 0.5f, 1.0f}) {
    char text[8];
    std::snprintf(text, sizeof(text), "%.1f", stretch);
    const float w = ImGui::CalcTextSize(text).x;
    const float at = x0 + stretch * (x1 - x0);
    const float left = std::clamp(at - 0.5f * w, frame_min.x, frame_max.x - w);
    draw->AddLine(ImVec2(at, frame_max.y), ImVec2(at, frame_max.y + 3), tick_color);
    draw->AddText(ImVec2(left, frame_max.y + 3), tick_color, text);
  }
  ImGui::Dummy(ImVec2(chart_width, line));
  ImGui::EndGroup();
  if (status.has_result) {
    const RejectionCounts& r = status.rejections;
    ImGui::TextWrapped("Rejections (last run): tolerance %" PRIu64 ", stretch %" PRIu64
                       ", size %" PRIu64 ", valence %" PRIu64 ", topology %" PRIu64
                       ", overlap %" PRIu64,
                       r.tolerance, r.stretch, r.size, r.valence, r.topology, r.overlap);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "Evaluated collapses refused, each by its first failed test: the geometric\n"
          "tolerance, a new tet flatter than the stretch or larger than the size, a node\n"
          "above the valence, the topology of the regions, interfaces, curves and\n"
          "corners; overlap: the outer boundary would cross itself, or cross or sweep\n"
          "past another body meshed apart, so that tets would overlap.");
  }
  ImGui::End();
}

// When nothing is drawn, a line in the middle of the 3D view says why: every material
// hidden, or the cut leaving none of the shown tets.
void empty_view_note(const ViewerStatus& status, const ViewSettings& view,
                     const PanelState& panel) {
  if (status.mesh_name.empty() || status.loading || status.visible_tets > 0) return;
  bool all_hidden = true;
  for (const int32_t m : status.materials)
    all_hidden = all_hidden &&
                 std::binary_search(view.hidden_materials.begin(), view.hidden_materials.end(), m);
  char text[256];
  if (all_hidden) {
    std::snprintf(text, sizeof(text),
                  "Nothing to show: every material is hidden (View, Materials shown).");
  } else if (view.cut) {
    const char axis = "xyz"[static_cast<int>(view.cut_axis)];
    std::snprintf(text, sizeof(text),
                  "Nothing to show: the cut keeps %c %s %.4g, where no tet of the shown materials "
                  "lies. Move its offset or flip it (View, Cut).",
                  axis, view.cut_flip ? ">=" : "<=", view.cut_offset);
  } else {
    std::snprintf(text, sizeof(text), "Nothing to show at this level.");
  }
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  const ViewRect r = scene_rect(viewport->WorkSize.x, viewport->WorkSize.y, panel);
  const float wrap = std::min(420.0f, r.width - 40);
  const ImVec2 size = ImGui::CalcTextSize(text, nullptr, false, wrap);
  const ImVec2 at(viewport->WorkPos.x + r.x + 0.5f * (r.width - size.x),
                  viewport->WorkPos.y + r.y + 0.5f * (r.height - size.y));
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, IM_COL32(60, 60, 70, 255), text,
                nullptr, wrap);
}

double usable_diagonal(double diagonal) {
  return std::isfinite(diagonal) && diagonal > 0 ? diagonal : 1.0;
}

// `range` widened to hold `current` (a negative or non-finite one is not a length: the
// panel shows it, and Simplify says what is wrong with it).
SliderRange holding(SliderRange range, double current) {
  if (std::isfinite(current) && current >= 0) {
    range.min = std::min(range.min, current);
    range.max = std::max(range.max, current);
  }
  return range;
}

}  // namespace

SliderRange size_slider_range(double diagonal, double current) {
  const double d = usable_diagonal(diagonal);
  return current > 0 ? holding({d * 1e-4, d}, current) : SliderRange{d * 1e-4, d};
}

SliderRange tolerance_slider_range(double diagonal, double current) {
  const double d = usable_diagonal(diagonal);
  return holding({d * 1e-7, d * 0.1}, current);
}

std::string log_slider_format(const SliderRange& range, const std::string& prefix) {
  // A range from 0 (a tolerance of 0) is as fine near 0 as one from max x 1e-7.
  const double low = range.min > 0 ? range.min : range.max * 1e-7;
  int digits = 4;
  if (std::isfinite(low) && low > 0)
    digits = std::clamp(static_cast<int>(std::ceil(-std::log10(low))) + 1, 4, 30);
  return prefix + "%." + std::to_string(digits) + "g";
}

bool to_simplify_params(const ThresholdSettings& settings, SimplifyParams* params,
                        std::string* error) {
  SimplifyParams p;
  p.tolerance = settings.tolerance;
  p.min_stretch = settings.stretch;
  p.max_valence = static_cast<uint32_t>(std::max(0, settings.valence));
  p.subdivide = settings.subdivide;
  p.crease_angle_degrees = settings.crease_angle;
  // Every bad value is named at once (a user who typed two should not learn of the
  // second only after fixing the first): each threshold is checked by check_params()
  // alone, the others set to valid values, so that the rules and words are core's.
  std::vector<std::string> errors;
  const auto check_alone = [&errors](auto set) {
    SimplifyParams q;
    q.sizing.uniform = 1;
    set(&q);
    if (const Status s = check_params(q); !s) errors.push_back(s.message());
  };
  check_alone([&p](SimplifyParams* q) { q->tolerance = p.tolerance; });
  check_alone([&p](SimplifyParams* q) { q->min_stretch = p.min_stretch; });
  check_alone([&p](SimplifyParams* q) { q->max_valence = p.max_valence; });
  check_alone([&p](SimplifyParams* q) { q->crease_angle_degrees = p.crease_angle_degrees; });
  // Uniform: the size everywhere; region, size map: the cap besides the rules or the
  // map; per material: the materials' sizes, and the cap if it is ticked.
  if (!uses_material_sizes(settings.sizing_mode) || settings.material_cap) {
    if (settings.size > 0)
      p.sizing.uniform = settings.size;
    else
      errors.push_back("size must be > 0");
  }
  if (settings.sizing_mode == SizingMode::kMap) {
    if (settings.size_map)
      p.sizing.map = settings.size_map;
    else
      errors.push_back("no size map (give one with the mesh: tetlod view FILE --size-map S.sol)");
  }
  if (uses_region(settings.sizing_mode)) {
    if (const Status s = parse_size_field(settings.region_spec, &p.sizing); !s)
      errors.push_back(s.message());
  }
  if (uses_material_sizes(settings.sizing_mode)) {
    for (const auto& [material, size] : settings.material_sizes) {
      if (size > 0)
        p.sizing.material_sizes.push_back({material, size});
      else
        errors.push_back("size of material " + std::to_string(material) + " must be > 0");
    }
    std::sort(p.sizing.material_sizes.begin(), p.sizing.material_sizes.end());
    // (check_params() would ask for the size, which this mode's panel does not show.)
    if (p.sizing.unlimited())
      errors.push_back("no size limit given: tick a material to give it a size, or \"all\"");
  }
  if (errors.empty()) {  // what only the whole set can break (no size limit at all, ...)
    if (const Status s = check_params(p); !s) errors.push_back(s.message());
  }
  if (!errors.empty()) {
    error->clear();
    for (const std::string& e : errors) *error += (error->empty() ? "" : "; ") + e;
    return false;
  }
  *params = std::move(p);
  return true;
}

bool same_thresholds(const ThresholdSettings& settings, const SimplifyParams& run) {
  SimplifyParams p;
  std::string error;
  if (!to_simplify_params(settings, &p, &error)) return false;
  const SizingField &a = p.sizing, &b = run.sizing;
  return p.tolerance == run.tolerance && p.min_stretch == run.min_stretch &&
         p.max_valence == run.max_valence && p.subdivide == run.subdivide &&
         p.crease_angle_degrees == run.crease_angle_degrees && a.uniform == b.uniform &&
         a.material_sizes == b.material_sizes && a.map == b.map && a.radial == b.radial &&
         a.boxes == b.boxes;
}

bool from_simplify_params(const SimplifyParams& params, ThresholdSettings* settings) {
  const SizingField& sizing = params.sizing;
  const bool region = !sizing.radial.empty() || !sizing.boxes.empty();
  const bool uniform = std::isfinite(sizing.uniform);
  if ((sizing.map && (region || !sizing.material_sizes.empty())) ||
      (!uniform && sizing.material_sizes.empty() && !sizing.map && !region))
    return false;
  ThresholdSettings t;
  t.tolerance = params.tolerance;
  t.stretch = params.min_stretch;
  t.valence = static_cast<int>(std::min<uint32_t>(params.max_valence, 1 << 30));
  t.subdivide = params.subdivide;
  t.crease_angle = params.crease_angle_degrees;
  if (uniform) t.size = sizing.uniform;
  if (sizing.map) {
    // Without a uniform size, a cap the map never reaches: the same limits.
    t.sizing_mode = SizingMode::kMap;
    t.size_map = sizing.map;
    t.size_map_name = "saved in the history";
    if (!uniform) t.size = sizing.map->largest();
  }
  if (region) {
    // Region rules with a size cap are the region mode; with per-material sizes, or
    // without a cap (`--size-field` alone), region and per material.
    t.sizing_mode = uniform && sizing.material_sizes.empty() ? SizingMode::kRegion
                                                             : SizingMode::kRegionAndMaterial;
    t.material_cap = uniform;
    // Each number in the shortest text that reads back to it ("0.2", not
    // "0.20000000000000001"), so that the rules parse back to the same values.
    const auto rule = [](const char* kind, std::initializer_list<double> numbers) {
      std::string text = kind;
      char buffer[32];
      for (const double x : numbers) {
        const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
        text += (text.back() == ':' ? "" : ",") + std::string(buffer, end);
      }
      return text;
    };
    for (const SizingField::Radial& r : sizing.radial) {
      const Vec3 &c = r.center, &a = r.axis;
      const std::string text =
          a == Vec3{} ? rule("radial:", {c.x, c.y, c.z, r.size0, r.growth})
                      : rule("axis:", {c.x, c.y, c.z, a.x, a.y, a.z, r.size0, r.growth});
      t.region_spec += (t.region_spec.empty() ? "" : ";") + text;
    }
    for (const SizingField::Box& b : sizing.boxes) {
      t.region_spec +=
          (t.region_spec.empty() ? "" : ";") +
          rule("box:", {b.low.x, b.low.y, b.low.z, b.high.x, b.high.y, b.high.z, b.size});
    }
  } else if (!sizing.material_sizes.empty()) {
    t.sizing_mode = SizingMode::kPerMaterial;
    t.material_cap = uniform;
  }
  for (const auto& [material, size] : sizing.material_sizes)
    t.material_sizes.push_back({material, size});
  *settings = std::move(t);
  return true;
}

ElectrostaticsProblem to_electrostatics_problem(const AnalysisSettings& settings) {
  ElectrostaticsProblem problem;
  problem.ground_boundary = settings.ground_boundary;
  for (const MaterialAnalysis& m : settings.materials) {
    if (m.role == MaterialRole::kConductor) {
      problem.conductors.push_back({m.material, m.potential});
    } else if (m.role == MaterialRole::kGround) {
      problem.ground_materials.push_back(m.material);
    } else if (m.permittivity != 1) {
      problem.permittivities.push_back({m.material, m.permittivity});
    }
  }
  return problem;
}

AnalysisSettings analysis_settings_from(const ElectrostaticsProblem& problem,
                                        const std::vector<int32_t>& materials) {
  AnalysisSettings settings;
  settings.ground_boundary = problem.ground_boundary;
  const auto entry = [&](int32_t id) -> MaterialAnalysis& {
    auto it = std::lower_bound(
        settings.materials.begin(), settings.materials.end(), id,
        [](const MaterialAnalysis& x, int32_t material) { return x.material < material; });
    if (it == settings.materials.end() || it->material != id)
      it = settings.materials.insert(it, MaterialAnalysis{id});
    return *it;
  };
  for (const int32_t m : materials) entry(m);
  for (const auto& [m, eps] : problem.permittivities) entry(m).permittivity = eps;
  for (const int32_t m : problem.ground_materials) entry(m).role = MaterialRole::kGround;
  for (const auto& [m, v] : problem.conductors) {
    entry(m).role = MaterialRole::kConductor;
    entry(m).potential = v;
  }
  return settings;
}

namespace {
std::string phase_percent(const char* prefix, const std::string& phase, double fraction) {
  char text[128];
  std::snprintf(text, sizeof(text), "%s%s %.0f%%", prefix, phase.c_str(), 100 * fraction);
  return text;
}
}  // namespace

std::string top_progress_text(const ViewerStatus& status) {
  // Short enough for the panel's width: the collapses only while they are made (a run
  // past the valence's are in the Thresholds section).
  if (status.past_valence_run)
    return phase_percent("past the valence: ", status.phase, status.phase_fraction);
  if (status.phase == "simplify") {
    char text[96];
    std::snprintf(text, sizeof(text), "simplify %.0f%%, %zu collapses", 100 * status.phase_fraction,
                  status.collapses);
    return text;
  }
  return phase_percent("simplifying: ", status.phase, status.phase_fraction);
}

std::string section_progress_text(const ViewerStatus& status) {
  return phase_percent(status.past_valence_run ? "past the valence: " : "", status.phase,
                       status.phase_fraction);
}

std::string final_mesh_text(const ViewerStatus& status) {
  const auto counts = [](size_t thin, size_t big, size_t crowded) {
    return std::to_string(thin) + (thin == 1 ? " tet" : " tets") + " below the stretch, " +
           std::to_string(big) + " above the size, " + std::to_string(crowded) +
           (crowded == 1 ? " node" : " nodes") + " above the valence";
  };
  const ThresholdViolations& v = status.violations;
  const ThresholdCounts& in = status.input_breaks;
  const std::string input =
      "the input: " + counts(in.below_stretch, in.above_size, in.above_valence) + ".";
  // Which thresholds: the run's, which the sliders may no longer show.
  std::string final_mesh = "Final mesh";
  if (!status.result_thresholds.empty())
    final_mesh += ", for the run's thresholds (" + status.result_thresholds + ")";
  if (status.result_thresholds_changed)
    final_mesh += status.result_thresholds.empty() ? ", for the run's thresholds, not the panel's"
                                                   : ", not the panel's, changed since";
  if (v.below_stretch + v.above_size + v.above_valence == 0)
    return final_mesh + ": every tet and node within the thresholds; " + input;
  return final_mesh + ": " + counts(v.below_stretch, v.above_size, v.above_valence) + "; " +
         (v.created == 0 ? "all input ones or pieces of input tets that already broke it"
                         : "some new ones: please report it") +
         "; " + input;
}

namespace {

// `message` with the command line's flags the simplifier's and the sizing's messages
// name replaced by `words[0]` (for --no-subdivide), `words[1]` (for "(set --size)")
// and `words[2]` (for --size-field, the region rules).
std::string reword_flags(const std::string& message, const char* const (&words)[3]) {
  static const char* const kFlags[] = {"--no-subdivide", "(set --size)", "--size-field"};
  std::string text = message;
  for (int k = 0; k < 3; ++k) {
    const size_t at = text.find(kFlags[k]);
    if (at != std::string::npos) text.replace(at, std::strlen(kFlags[k]), words[k]);
  }
  return text;
}

}  // namespace

void keep_range_apart(float* low, float* high) {
  constexpr float kGap = 0.01f;
  if (*high - *low >= kGap) return;
  if (*low + kGap <= 1.0f)
    *high = *low + kGap;
  else
    *low = *high - kGap;
}

std::string no_history_text(const ViewerStatus& status) {
  const std::string elements = "(" + std::to_string(status.elements) + " elements).";
  if (status.has_result || status.from_history)
    return "no collapse: the thresholds allowed none " + elements;
  return "Simplify to get a collapse history " + elements;
}

std::string still_running_text(bool simplification, bool solve) {
  if (simplification && solve) return "; the running simplification and solve go on";
  if (simplification) return "; the running simplification goes on";
  if (solve) return "; the running solve goes on";
  return "";
}

std::string simplify_error_text(const std::string& message) {
  return reword_flags(message,
                      {"untick \"Subdivide first\" above", "(set the size)", "the region rules"});
}

std::string script_error_text(const std::string& message) {
  return reword_flags(message, {"'thresholds subdivide=0'", "(set 'thresholds size=S')", "region"});
}

std::string other_run_progress_text(const ViewerStatus& status) {
  if (status.other_phase.empty()) return "";
  return phase_percent("past the valence: ", status.other_phase, status.other_fraction);
}

ViewRect scene_rect(float display_width, float display_height, const PanelState& panel) {
  ViewRect r;
  r.x = scene_left(panel);
  r.y = panel.panel_collapsed ? kFoldedPanelHeight : 0;  // below the folded panel's bar
  r.width = std::max(1.0f, display_width - r.x);
  const float stats = stats_height(display_height, panel.show_stats);
  r.height = std::max(
      1.0f, display_height - r.y - kLodHeight - 2 * kMargin - (stats > 0 ? stats + kMargin : 0.0f));
  return r;
}

namespace {

// The panel's first row, always there and always one row high, so that nothing under it
// moves when a run, a solve or a load starts or ends (the second click of a double click
// would land on whatever slid under the pointer): Cancel, and the progress of what runs
// (the simplification first; a solve's is also in the Analysis section).
void activity_row(const ViewerStatus& status, std::vector<Command>* commands) {
  const ViewerStatus::Analysis& a = status.analysis;
  ImGui::BeginDisabled(!status.running && !a.solving);
  if (ImGui::Button("Cancel##top"))
    commands->push_back({status.running ? CommandKind::kCancel : CommandKind::kCancelSolve});
  ImGui::EndDisabled();
  ImGui::SameLine();
  double fraction = 0;
  char text[160];
  if (status.running) {
    fraction = status.phase_fraction;
    std::snprintf(text, sizeof(text), "%s", top_progress_text(status).c_str());
  } else if (a.solving) {
    fraction = a.fraction;
    std::snprintf(text, sizeof(text), "solving the %s: %s %.0f%%", a.solving_what.c_str(),
                  a.phase.c_str(), 100 * a.fraction);
  } else if (status.loading) {
    // Shorter where the bar is too narrow for the line (it drew it from its left,
    // "g huge.mesh: ...", as it centres text wider than it): the file's name cut in the
    // middle, then left out (it is under the pointer), then "loading" too.
    std::string name = std::filesystem::path(status.loading_path).filename().string();
    const float room = ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemInnerSpacing.x;
    const auto fits = [&] { return ImGui::CalcTextSize(text).x <= room; };
    for (;;) {
      std::snprintf(text, sizeof(text), "loading %s: %s, %.1f s", name.c_str(),
                    status.phase.c_str(), status.elapsed_seconds);
      if (fits() || name.size() <= 12) break;
      const size_t keep = (name.size() - 4) / 2;  // each side of "..."
      name = name.substr(0, keep) + "..." + name.substr(name.size() - keep);
    }
    if (!fits())
      std::snprintf(text, sizeof(text), "loading: %s, %.1f s", status.phase.c_str(),
                    status.elapsed_seconds);
    if (!fits())
      std::snprintf(text, sizeof(text), "%s, %.1f s", status.phase.c_str(), status.elapsed_seconds);
  } else {
    std::snprintf(text, sizeof(text), "nothing running");
  }
  ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1, 0), text);
  if (status.loading && ImGui::IsItemHovered())
    ImGui::SetTooltip("%s", status.loading_path.c_str());
}

}  // namespace

void draw_viewer_panels(const ViewerStatus& status, ViewSettings* view,
                        ThresholdSettings* thresholds, AnalysisSettings* analysis,
                        PanelState* panel, std::vector<Command>* commands) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + kMargin, viewport->WorkPos.y + kMargin),
                          ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, viewport->WorkSize.y - 2 * kMargin),
                           ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.95f);
  panel->panel_collapsed =
      !ImGui::Begin("TetLOD", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  ImGui::Text("%.1f FPS, %.2f ms/frame", status.fps, status.frame_ms);
  if (status.scene_scale < 1) {
    ImGui::SameLine();
    ImGui::TextDisabled("(3D view at %.0f%%)", 100 * status.scene_scale);
  }
  ImGui::Text("%zu visible tets, %zu triangles", status.visible_tets, status.drawn_triangles);
  ImGui::Checkbox("Statistics window", &panel->show_stats);
  activity_row(status, commands);
  ImGui::SetNextItemOpen(true, ImGuiCond_FirstUseEver);
  if (ImGui::CollapsingHeader("File")) file_section(status, panel, commands);
  ImGui::SetNextItemOpen(true, ImGuiCond_FirstUseEver);
  if (ImGui::CollapsingHeader("View")) view_section(status, view, commands);
  ImGui::SetNextItemOpen(true, ImGuiCond_FirstUseEver);
  if (ImGui::CollapsingHeader("Thresholds")) thresholds_section(status, thresholds, commands);
  ImGui::SetNextItemOpen(true, ImGuiCond_FirstUseEver);
  if (ImGui::CollapsingHeader("Analysis")) analysis_section(status, analysis, commands);
  if (ImGui::CollapsingHeader("Output")) output_section(status, panel, commands);
  ImGui::End();
  lod_strip(status, panel, commands);
  stats_window(status, panel);
  empty_view_note(status, *view, *panel);
}

bool add_name_glyphs(const std::string& path) {
  ImFontAtlas* fonts = ImGui::GetIO().Fonts;
  fonts->AddFontDefault();
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return false;
  if (bytes.size() < 12 || bytes.size() > (64u << 20)) return false;  // not a font
  // The atlas frees the data it owns with ImGui's allocator.
  void* data = ImGui::MemAlloc(bytes.size());
  std::memcpy(data, bytes.data(), bytes.size());
  static const ImWchar kRanges[] = {0x0100, 0x024F, 0x0370, 0x03FF, 0x0400, 0x04FF, 0};
  ImFontConfig config;
  config.MergeMode = true;
  config.PixelSnapH = true;
  return fonts->AddFontFromMemoryTTF(data, int(bytes.size()), 13.0f, &config, kRanges) != nullptr;
}

}  // namespace tetlod::ui
