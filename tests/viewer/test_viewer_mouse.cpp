// Mouse input through the X server (XTest), as from a hand on the mouse: a drag over
// the 3D view orbits the camera; the same drag started over the side panel does not
// move it, even when it ends over the view (ImGui wants the mouse for it). Runs under
// xvfb-run with the other window tests; the viewer's window sits at the screen's
// origin (no window manager).
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "viewer/background_viewer.h"

// Last, and their macros that clash with C++ names removed.
#include <X11/Xlib.h>
#include <X11/extensions/XTest.h>
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

}  // namespace
}  // namespace tetlod
