// The interactive viewer (`tetlod view`): a GLFW window with Dear ImGui panels over
// the renderer, the simplifier in a worker thread and the LOD scrubber. See
// app/viewer.cpp for the frame loop and ui/viewer_ui.h for the panels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/viewer_script.h"

namespace tetlod::app {

struct ViewerOptions {
  std::string mesh_path;  // opened at start ("" opens nothing)
  int width = 1280, height = 800;
  std::vector<ScriptAction> script;  // run in the window, then stay open unless it quits
  std::string script_name;           // for messages
  bool has_script = false;
  double interactive_scale = 0.5;         // resolution of the 3D view while it changes (1: full)
  bool remember_recent = true;            // keep the recent-files list in ~/.config/tetlod
  std::vector<int32_t> hidden_materials;  // hidden at start
  // Hidden at start by the name the first mesh opened gives them (looked up once it is read).
  std::vector<std::string> hidden_names;
  // --size-map: a Medit .sol of sizes at the vertices of the first mesh opened, read with
  // it (the panel's "size map" sizing; a history keeps its own), or at the vertices of
  // --size-map-mesh (a background mesh over the same domain), as the CLI takes them.
  std::string size_map_path, size_map_mesh_path;
};

// Runs the window until it is closed (or the script quits). Returns the exit code:
// 0, or kExitBadInput when there is no display or a scripted action failed.
int run_viewer(const ViewerOptions& options);

}  // namespace tetlod::app
