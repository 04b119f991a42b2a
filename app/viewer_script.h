// Scripted viewer runs (`tetlod view FILE --script SCRIPT`): a line-based list of
// actions done in the real window, one after the other, each waiting until the
// previous one has finished (a simplification, a scrub, a statistics update).
//
//   # comment                        blank lines and comments are skipped (a NUL byte
//                                    is an error; a byte-order mark at the start is skipped)
//   "a b"                            double quotes keep blanks in a word (names:
//                                    material-sizes="phase A=12", hide "rotor iron")
//   open PATH [may-fail]             load a mesh, or a collapse history (.tlh) with its
//                                    levels (waits); with may-fail a bad file is not a
//                                    script error: it shows in the UI as for a user
//   thresholds size=S stretch=D valence=V tolerance=T subdivide=0|1 keep-inside=0|1
//              crease-angle=DEG material-sizes=M=S,M=S region=RULES
//              (any subset; see core/sizing.h;
//              M is a material's id or name, looked up when the line runs; a
//              material material-sizes leaves out has no size limit, as in the CLI;
//              size= on the same line as material-sizes= also caps every material, as
//              --size with --material-size; region= and material-sizes= on one line
//              combine, as --size-field with --material-size (the panel's "region and
//              per material"); sizing=map the size map given with the mesh, with size=
//              its cap; sizing=uniform back to one size)
//   simplify [wait=0]                run the simplifier with the thresholds (waits,
//                                    unless wait=0: then the next actions run meanwhile)
//   cancel                           cancel a running simplification and/or solve (waits
//                                    until the workers have stopped; the previous result
//                                    stays); with none running, an error, unless one was
//                                    started with wait=0 (it has ended: a note)
//   scrub step=K | elements=N | end  move the LOD to a step / nearest level (waits)
//   cut x|y|z=VALUE [flip] | cut off
//   hide M | show M                  material visibility, by id or by the mesh's name for
//                                    it (looked up when the line runs; the rest of the
//                                    line: hide rotor iron)
//   groups all|none|G[,G...]         the input's surface groups drawn over the surface
//                                    (the View section's "Surface groups drawn"), by
//                                    name or tag (looked up when the line runs; the rest
//                                    of the line, a comma inside a name written \,);
//                                    waits until they are drawn
//   color stretch|material|field|size  range MIN MAX        colormap viridis|turbo
//                                    (field: |E| of the last solve while it matches the
//                                    displayed level; stretch otherwise. size: each tet's
//                                    longest edge, over the drawn tets' range)
//   field-range max | P              |E| colour map over [0, max] or [0, percentile P of
//                                    the solved tets' |E|], 0 < P <= 100
//   wireframe on|off                 highlight D | highlight off
//   legend on|off                    the colour bar or material key (as the panel's
//                                    Legend; framing keeps the model above the bar)
//   view iso|x|y|z|fit
//   orbit DX DY | pan DX DY          camera moves as by a mouse drag of DX, DY pixels
//   zoom CLICKS                      as by the mouse wheel (positive: closer)
//   mouse X Y                        hold the mouse pointer at window pixel (X, Y), from
//                                    the top left, for the rest of the script (to show a
//                                    tooltip in a 'screenshot ui=1'; the tet's tooltip
//                                    shows once the pointer has rested 0.3 s: 'wait
//                                    seconds=0.5' first, not frames); the real pointer is
//                                    not read meanwhile
//   screenshot PATH [ui=0|1] [width=W height=H]   PNG of the view (ui=1: the window)
//   save PATH [improve] [surfaces] [binary]   the displayed level, format from the
//                                    extension; improve: its shapes improved first
//                                    (improve.h); surfaces: with boundary groups;
//                                    binary: .msh, .vtk, .vtu in binary (WriteOptions);
//                                    PATH.tlh: the whole collapse history instead
//   wait frames=N | seconds=S        keep drawing (and taking input) meanwhile
//   wait done                        until the simplification and the solve started with
//                                    wait=0 have ended (nothing to wait for: no wait)
//   bench-scrub [frames=N] [out=CSV] drag the scrubber end to end and back over N
//                                    frames each way; prints frame times
//   bench-frames [frames=N] [out=CSV] times the next N frames as they are (e.g. while
//                                    a 'simplify wait=0' runs)
//   analysis conductor=M:V[,M:V...] [ground=boundary|M[,...]] [eps=M:E[,M:E...]]
//                                    set up the Analysis panel (replaces the previous
//                                    set-up; unlisted materials: dielectric, eps 1);
//                                    ground= is needed unless the conductors hold two
//                                    potentials; M is a material's id or its name (one
//                                    without ','; in quotes if it has blanks:
//                                    "conductor=phase A:1"), or for a conductor or ground
//                                    the name of one of the input's surface groups (its
//                                    nodes held); a material given twice is an
//                                    error. The syntax is checked here, the materials
//                                    when it runs; a bad set-up (a conductor touching
//                                    the ground, eps <= 0, ...) fails at 'solve'
//   solve [may-fail] [wait=0]        solve the displayed level (and the finest level,
//                                    once, for the difference) and wait (wait=0: go on
//                                    meanwhile); the solver's error fails the script at
//                                    this line (with may-fail it only shows in the
//                                    Analysis panel, as for a user)
//   report-analysis PATH             write the last solve's figures as 'key value' lines
//   report-tet PATH                  write what the tooltip says of the tet under the
//                                    pointer ('mouse X Y' first) as 'key value' lines
//                                    (tet: its id in the level of detail, not in a saved
//                                    file; material, stretch, size, volume, valence (the
//                                    most neighbours of its nodes); the run's min_stretch,
//                                    max_size there and max_valence; field; name), or
//                                    'tet none'
//   quit
//
// Relative paths are relative to the working directory.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/electrostatics.h"
#include "core/status.h"

namespace tetlod::app {

struct ScriptAction {
  enum class Kind {
    kOpen,
    kThresholds,
    kSimplify,
    kCancel,
    kScrubStep,
    kScrubElements,
    kScrubEnd,
    kCut,
    kCutOff,
    kHide,
    kShow,
    kGroups,
    kColor,
    kRange,
    kColormap,
    kWireframe,
    kLegend,
    kHighlight,
    kHighlightOff,
    kView,
    kOrbit,
    kPan,
    kZoom,
    kMouse,
    kScreenshot,
    kSave,
    kWait,
    kBenchScrub,
    kBenchFrames,
    kFieldRange,
    kAnalysis,
    kSolve,
    kReportAnalysis,
    kReportTet,
    kQuit,
  };
  Kind kind = Kind::kQuit;
  int line = 0;
  std::string path;     // open, screenshot, save, bench-scrub out, report-analysis, -tet
  std::string word;     // color, colormap, view; hide, show: a material's name; groups
  long long count = 0;  // step, elements, material, frames, solve: wait (1) or not (0)
  double value = 0;     // cut offset, highlight, range min, field-range percentile
  double value2 = 0;    // range max
  int axis = 0;         // cut: 0 x, 1 y, 2 z
  bool flag = false;    // cut flip, wireframe on, legend on, screenshot ui, save improve, wait done
  bool surfaces = false;  // save surfaces
  bool binary = false;    // save binary
  int width = 0, height = 0;
  // thresholds
  std::optional<double> size, stretch, tolerance, crease_angle;
  std::optional<long long> valence;
  std::optional<bool> subdivide;
  std::optional<bool> keep_inside;
  std::optional<std::string> material_sizes, region;
  std::optional<bool> size_map;  // sizing=map (true) or sizing=uniform (false)
  // analysis: the materials given by id in `problem`, those given by name in `named`
  // (resolved when the line runs)
  ElectrostaticsProblem problem;
  struct NamedMaterial {
    std::string key;  // conductor, eps or ground
    std::string name;
    double value = 0;  // the potential or the permittivity
  };
  std::vector<NamedMaterial> named;
};

// "M=S,M=S" of material-sizes=: each M an id or (with `names`) a name the mesh has;
// sizes > 0. Without `names`, any name is taken and `out` gets only the ids (the
// script's check before it runs). Errors name the item.
Status resolve_material_sizes(const std::string& spec, const std::vector<MaterialName>* names,
                              std::vector<std::pair<int32_t, double>>* out);

// What is wrong with a screenshot's file and size as a script line or the panel gives
// them, or "": a .png name; width and height both 0 (the 3D view's size) or both in
// [16, 8192].
std::string screenshot_problem(const std::string& path, int width, int height);

// Reads and checks the whole script before anything runs. Errors read
// "SCRIPT:LINE: what is wrong".
Status parse_script(const std::string& path, std::vector<ScriptAction>* actions);
Status parse_script_text(const std::string& text, const std::string& name,
                         std::vector<ScriptAction>* actions);

}  // namespace tetlod::app
