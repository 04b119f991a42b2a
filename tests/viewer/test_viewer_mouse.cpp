// Mouse and key input through the X server (XTest), as from a hand on the mouse: a drag over
// the 3D view orbits the camera; the same drag started over the side panel does not
// move it, even when it ends over the view (ImGui wants the mouse for it); keys move
// the level of detail. Runs under
// xvfb-run with the other window tests; the viewer's window sits at the screen's
// origin (no window manager).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>

#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/simplify.h"
#include "viewer/background_viewer.h"

// Last, and their macros that clash with C++ names removed.
#include <X11/Xlib.h>
#include <X11/extensions/XTest.h>
#include <X11/keysym.h>
#undef Status
#undef None
#undef Bool

namespace tetlod {
namespace {

using namespace std::chrono_literals;

void drag(Display* display, int x0, int y0, int x1, int y1) {
  XTestFakeMotionEvent(display, -1, x0, y0, CurrentTime);
  XFlush(display);
  std::this_thread::sleep_for(100ms);
  XTestFakeButtonEvent(display, 1, True, CurrentTime);
  XFlush(display);
  std::this_thread::sleep_for(100ms);
  for (int k = 1; k <= 10; ++k) {
    XTestFakeMotionEvent(display, -1, x0 + (x1 - x0) * k / 10, y0 + (y1 - y0) * k / 10,
                         CurrentTime);
    XFlush(display);
    std::this_thread::sleep_for(40ms);
  }
  XTestFakeButtonEvent(display, 1, False, CurrentTime);
  XFlush(display);
}

// Runs the viewer on box2 in the background, drags once it has taken a.png, and
// returns how many pixels of b.png (taken after the drag) differ from a.png.
size_t pixels_moved_by_drag(const std::string& name, int x0, int y0, int x1, int y1) {
  test::BackgroundViewer viewer;
  EXPECT_TRUE(viewer.start(name, std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh",
                           "screenshot a.png width=200 height=200\n"
                           "wait seconds=3\n"
                           "screenshot b.png width=200 height=200\n"
                           "quit\n"));
  EXPECT_TRUE(viewer.wait_for("a.png"));
  std::this_thread::sleep_for(200ms);
  Display* display = XOpenDisplay(nullptr);
  EXPECT_NE(display, nullptr);
  if (display) {
    drag(display, x0, y0, x1, y1);
    XCloseDisplay(display);
  }
  EXPECT_EQ(viewer.finish(), 0);
  return viewer.differing_pixels("a.png", "b.png");
}

TEST(ViewerMouse, DragOverTheViewOrbits) {
  EXPECT_GT(pixels_moved_by_drag("viewer_mouse_view", 600, 170, 700, 200), 200u * 200u / 50u);
}

TEST(ViewerMouse, DragStartedOverThePanelLeavesTheCamera) {
  // From an empty spot of the side panel (right of the "visible tets" line) into the view.
  EXPECT_EQ(pixels_moved_by_drag("viewer_mouse_panel", 340, 58, 640, 200), 0u);
}

// The size slider follows the model: on the motor in metres (diagonal 0.18, default
// size 0.023) a short drag of its grab to the right gives a size a little above the
// default, rounded to 4 digits, which Simplify then uses (saved with the history). With
// the fixed range 0.1 to 100 it jumped past 0.1, above half the model's diagonal.
// The thresholds of the history a viewer saved as run.tlh, once it has quit with 0.
void read_saved_params(test::BackgroundViewer* viewer, SimplifyParams* params) {
  ASSERT_EQ(viewer->finish(std::chrono::seconds(120)), 0);
  TetMesh base;
  CollapseHistory history;
  std::optional<SimplifyParams> saved;
  ASSERT_TRUE(read_history((viewer->dir() / "run.tlh").string(), &base, &history, &saved).ok());
  ASSERT_TRUE(saved.has_value());
  *params = *saved;
}

TEST(ViewerMouse, SizeSliderFollowsAModelInMetres) {
  namespace fs = std::filesystem;
  const fs::path mesh_dir = fs::path(TETLOD_TEST_OUTPUT_DIR) / "vms";
  fs::create_directories(mesh_dir);
  TetMesh motor;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", &motor).ok());
  for (Vec3& p : motor.positions) p = p * 1e-3;
  ASSERT_TRUE(write_mesh((mesh_dir / "m.mesh").string(), motor).ok());
  test::BackgroundViewer viewer;
  // A short path keeps the panel's lines from wrapping: the slider stays at its place.
  ASSERT_TRUE(viewer.start("viewer_mouse_size_slider", "../vms/m.mesh",
                           "screenshot a.png ui=1\n"
                           "wait seconds=3\n"
                           "screenshot b.png ui=1\n"
                           "simplify\nsave run.tlh\nquit\n",
                           "1280x800"));
  ASSERT_TRUE(viewer.wait_for("a.png"));
  std::this_thread::sleep_for(200ms);
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  // The size slider's row (y 648) from its grab at the default (x 200) 15 pixels right.
  drag(display, 200, 648, 215, 648);
  XCloseDisplay(display);
  SimplifyParams params;
  read_saved_params(&viewer, &params);
  if (HasFatalFailure()) return;
  const double size = params.sizing.uniform;
  EXPECT_GT(size, 0.023 * 1.05) << "the drag did not move the size";
  EXPECT_LT(size, 0.023 * 2) << "the size jumped";
  char rounded[32];
  std::snprintf(rounded, sizeof rounded, "%.4g", size);
  EXPECT_EQ(std::strtod(rounded, nullptr), size);
}

// Folding the side panel (its title bar's arrow) gives its place to the 3D view: a
// screenshot of the view is then as wide as the window.
TEST(ViewerMouse, FoldingThePanelWidensTheView) {
  test::BackgroundViewer viewer;
  ASSERT_TRUE(viewer.start("viewer_fold_panel",
                           std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh",
                           "color material\nscreenshot a.png\nwait seconds=3\n"
                           "screenshot b.png\nscreenshot ui.png ui=1\nquit\n",
                           "800x600"));
  ASSERT_TRUE(viewer.wait_for("a.png"));
  std::this_thread::sleep_for(200ms);
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  drag(display, 17, 15, 17, 15);  // a click on the arrow of the panel's title bar
  XCloseDisplay(display);
  ASSERT_EQ(viewer.finish(), 0);
  const render::Image a = viewer.load("a.png"), b = viewer.load("b.png");
  EXPECT_EQ(a.width, 800 - 392);
  EXPECT_EQ(b.width, 800);
  EXPECT_EQ(b.height, a.height - 32);  // below the folded panel's title bar
}

// A double click on Simplify starts one run and changes nothing else: the second click
// used to land on "Subdivide first", which the run's progress row at the panel's top had
// pushed under the pointer, and the next run was made without subdividing.
TEST(ViewerMouse, ADoubleClickOnSimplifyTicksNothing) {
  namespace fs = std::filesystem;
  const fs::path mesh_dir = fs::path(TETLOD_TEST_OUTPUT_DIR) / "vdc";
  fs::create_directories(mesh_dir);
  fs::copy_file(std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", mesh_dir / "m.mesh",
                fs::copy_options::overwrite_existing);
  test::BackgroundViewer viewer;
  // A short path keeps the panel's lines from wrapping: Simplify stays at its place.
  ASSERT_TRUE(viewer.start("viewer_double_click", "../vdc/m.mesh",
                           "screenshot a.png ui=1\nwait seconds=3\nwait done\n"
                           "simplify\nsave run.tlh\nquit\n",
                           "1280x800"));
  ASSERT_TRUE(viewer.wait_for("a.png"));
  std::this_thread::sleep_for(200ms);
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  XTestFakeMotionEvent(display, -1, 45, 771, CurrentTime);  // on Simplify
  XFlush(display);
  std::this_thread::sleep_for(100ms);
  for (int click = 0; click < 2; ++click) {
    XTestFakeButtonEvent(display, 1, True, CurrentTime);
    XFlush(display);
    std::this_thread::sleep_for(40ms);
    XTestFakeButtonEvent(display, 1, False, CurrentTime);
    XFlush(display);
    std::this_thread::sleep_for(120ms);
  }
  XCloseDisplay(display);
  SimplifyParams params;
  read_saved_params(&viewer, &params);
  if (HasFatalFailure()) return;
  EXPECT_TRUE(params.subdivide);
  // Two runs: the clicks' and the script's.
  std::ifstream log(viewer.dir() / "log.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  size_t runs = 0;
  for (size_t at = text.find("simplified:"); at != std::string::npos;
       at = text.find("simplified:", at + 1))
    ++runs;
  EXPECT_EQ(runs, 2u) << text;
}

// A key pressed and released as by a hand (held 80 ms: shorter taps can fall between
// two frames of a loaded machine).
// (`hold`: how long, for taps shorter than that.)
void press(Display* display, KeySym key, std::chrono::milliseconds hold = 80ms) {
  const KeyCode code = XKeysymToKeycode(display, key);
  XTestFakeKeyEvent(display, code, True, CurrentTime);
  XFlush(display);
  std::this_thread::sleep_for(hold);
  XTestFakeKeyEvent(display, code, False, CurrentTime);
  XFlush(display);
  std::this_thread::sleep_for(150ms);
}

// The pointer over the 3D view (of a 1280x800 window), where the keys go to the viewer.
void hover_view(Display* display) {
  XTestFakeMotionEvent(display, -1, 800, 200, CurrentTime);
  XFlush(display);
  std::this_thread::sleep_for(100ms);
}

// The viewer on the spheres in the background at 1280x800: it simplifies, takes a.png,
// waits 4 s for the test's input, then saves the level shown and the history.
void start_simplified_spheres(test::BackgroundViewer* viewer, const std::string& name) {
  ASSERT_TRUE(viewer->start(name, std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh",
                            "simplify\nscreenshot a.png ui=1\nwait seconds=4\n"
                            "screenshot b.png ui=1\nsave level.mesh\nsave run.tlh\nquit\n",
                            "1280x800"));
  ASSERT_TRUE(viewer->wait_for("a.png", std::chrono::seconds(120)));
}

// What such a viewer saved, once it has quit.
struct SavedLevel {
  TetMesh base, level;
  CollapseHistory history;
};
void read_saved(test::BackgroundViewer* viewer, SavedLevel* saved) {
  ASSERT_EQ(viewer->finish(std::chrono::seconds(120)), 0);
  ASSERT_TRUE(
      read_history((viewer->dir() / "run.tlh").string(), &saved->base, &saved->history).ok());
  ASSERT_TRUE(read_mesh((viewer->dir() / "level.mesh").string(), &saved->level).ok());
}

// Home goes to the finest level, page down a hundredth of the history on, the right arrow
// one step: the level saved after Home, page down twice and right is that step's.
TEST(ViewerMouse, KeysMoveTheLevelOfDetail) {
  test::BackgroundViewer viewer;
  start_simplified_spheres(&viewer, "viewer_keys_lod");
  if (HasFatalFailure()) return;
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  hover_view(display);
  for (const KeySym key : {XK_Home, XK_Next, XK_Next, XK_Right}) press(display, key);
  XCloseDisplay(display);
  SavedLevel saved;
  read_saved(&viewer, &saved);
  if (HasFatalFailure()) return;
  ASSERT_GE(saved.history.step_count(), 200u);
  const Lod lod(saved.base, &saved.history);
  const size_t page = saved.history.step_count() / 100;
  EXPECT_EQ(saved.level.tet_count(), lod.tet_count_at(2 * page + 1));
  EXPECT_LT(saved.level.tet_count(), lod.tet_count_at(2 * page));
}

// Taps shorter than a frame count too (ImGui 1.86 reads the keys once a frame, and lost
// them): Home, then the right arrow tapped three times, 1 ms each, save step 3's level.
TEST(ViewerMouse, ShortKeyTapsAreNotLost) {
  test::BackgroundViewer viewer;
  start_simplified_spheres(&viewer, "viewer_short_taps");
  if (HasFatalFailure()) return;
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  hover_view(display);
  press(display, XK_Home);
  for (int tap = 0; tap < 3; ++tap) press(display, XK_Right, 1ms);
  XCloseDisplay(display);
  SavedLevel saved;
  read_saved(&viewer, &saved);
  if (HasFatalFailure()) return;
  const Lod lod(saved.base, &saved.history);
  EXPECT_EQ(saved.level.tet_count(), lod.tet_count_at(3));
}

// A click in the strip's box of elements, ctrl+A, 17000, then Enter or a click on Jump:
// the level saved is the one nearest 17000 elements (not the coarsest, 14222, shown
// then).
void type_17000_then_jump(const std::string& name, bool by_button) {
  test::BackgroundViewer viewer;
  start_simplified_spheres(&viewer, name);
  if (::testing::Test::HasFatalFailure()) return;
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  drag(display, 630, 534, 630, 534);  // a click in the box (left of Jump, on the strip)
  const KeyCode control = XKeysymToKeycode(display, XK_Control_L);
  XTestFakeKeyEvent(display, control, True, CurrentTime);
  press(display, XK_a);
  XTestFakeKeyEvent(display, control, False, CurrentTime);
  for (const KeySym key : {XK_1, XK_7, XK_0, XK_0, XK_0}) press(display, key);
  if (by_button)
    drag(display, 709, 534, 709, 534);  // Jump, right of the box
  else
    press(display, XK_Return);
  XCloseDisplay(display);
  SavedLevel saved;
  read_saved(&viewer, &saved);
  if (::testing::Test::HasFatalFailure()) return;
  const Lod lod(saved.base, &saved.history);
  EXPECT_EQ(saved.level.tet_count(), lod.tet_count_at(lod.step_for_elements(17000)));
  EXPECT_NE(saved.level.tet_count(), lod.tet_count_at(saved.history.step_count()));
}

TEST(ViewerMouse, EnterInTheElementsBoxJumps) {
  type_17000_then_jump("viewer_jump_enter", false);
}

// Jump takes the number typed in the box, not the one before (it was applied on Enter
// only, so Jump went to the number shown before the typing).
TEST(ViewerMouse, JumpTakesTheNumberTyped) {
  type_17000_then_jump("viewer_jump_button", true);
}

// What the viewer prints as it goes (each run's time) can be read while it runs, from
// the file its output goes to (it came out at the end, the output being buffered).
TEST(ViewerMouse, ItsOutputCanBeReadWhileItRuns) {
  test::BackgroundViewer viewer;
  ASSERT_TRUE(
      viewer.start("viewer_output_as_it_goes", std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh",
                   "simplify\nscreenshot a.png width=64 height=64\nwait seconds=4\nquit\n"));
  ASSERT_TRUE(viewer.wait_for("a.png", std::chrono::seconds(60)));
  std::this_thread::sleep_for(200ms);
  std::ifstream log(viewer.dir() / "log.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("tetlod view: simplified: "), std::string::npos) << text;
  EXPECT_FALSE(std::filesystem::exists(viewer.dir() / "rc.txt")) << "it had already ended";
  EXPECT_EQ(viewer.finish(std::chrono::seconds(60)), 0);
}

// The box of elements follows the level the keys go to: after Home and page down three
// times, Enter in it jumps to that level's count, so the level stays there (without
// following, the box held the count of the level shown when the run ended).
TEST(ViewerMouse, TheElementsBoxFollowsTheLevel) {
  test::BackgroundViewer viewer;
  start_simplified_spheres(&viewer, "viewer_box_follows");
  if (HasFatalFailure()) return;
  Display* display = XOpenDisplay(nullptr);
  ASSERT_NE(display, nullptr);
  hover_view(display);
  for (const KeySym key : {XK_Home, XK_Next, XK_Next, XK_Next}) press(display, key);
  std::this_thread::sleep_for(500ms);
  drag(display, 630, 534, 630, 534);  // a click in the box
  press(display, XK_Return);
  XCloseDisplay(display);
  SavedLevel saved;
  read_saved(&viewer, &saved);
  if (HasFatalFailure()) return;
  const Lod lod(saved.base, &saved.history);
  const size_t step = 3 * (saved.history.step_count() / 100);
  EXPECT_EQ(saved.level.tet_count(), lod.tet_count_at(step));
}

}  // namespace
}  // namespace tetlod
