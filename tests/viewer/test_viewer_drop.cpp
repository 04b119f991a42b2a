// Drag-and-drop of a file onto the viewer's window, done the way a file manager does
// it: a minimal XDND source (Enter, Position, Drop, then the text/uri-list data on
// request) talking to the GLFW window under Xvfb. The dropped mesh must replace the
// one on screen.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <string>
#include <thread>

#include "core/io/mesh_io.h"
#include "viewer/background_viewer.h"

// Last, and their macros that clash with C++ names removed.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#undef Status
#undef None
#undef Bool

namespace tetlod {
namespace {

using namespace std::chrono_literals;

constexpr ::Window kNoWindow = 0;

::Window find_window(Display* display, ::Window window, const char* title) {
  char* name = nullptr;
  if (XFetchName(display, window, &name) && name) {
    const bool match = std::strcmp(name, title) == 0;
    XFree(name);
    if (match) return window;
  }
  ::Window root = 0, parent = 0, *children = nullptr;
  unsigned count = 0;
  ::Window found = kNoWindow;
  if (XQueryTree(display, window, &root, &parent, &children, &count)) {
    for (unsigned i = 0; i < count && found == kNoWindow; ++i)
      found = find_window(display, children[i], title);
    if (children) XFree(children);
  }
  return found;
}

void send_client_message(Display* display, ::Window target, Atom type, const long data[5]) {
  XEvent event{};
  event.xclient.type = ClientMessage;
  event.xclient.display = display;
  event.xclient.window = target;
  event.xclient.message_type = type;
  event.xclient.format = 32;
  for (int i = 0; i < 5; ++i) event.xclient.data.l[i] = data[i];
  XSendEvent(display, target, False, NoEventMask, &event);
  XFlush(display);
}

// Drops `uri_list` onto the window titled `title`. False if the window does not
// ask for the data within a few seconds.
bool drop_files(const std::string& title, const std::string& uri_list) {
  Display* display = XOpenDisplay(nullptr);
  if (!display) return false;
  const ::Window root = DefaultRootWindow(display);
  const ::Window target = find_window(display, root, title.c_str());
  if (target == kNoWindow) {
    XCloseDisplay(display);
    return false;
  }
  const ::Window source = XCreateSimpleWindow(display, root, 0, 0, 1, 1, 0, 0, 0);
  const Atom enter = XInternAtom(display, "XdndEnter", False);
  const Atom position = XInternAtom(display, "XdndPosition", False);
  const Atom drop = XInternAtom(display, "XdndDrop", False);
  const Atom finished = XInternAtom(display, "XdndFinished", False);
  const Atom selection = XInternAtom(display, "XdndSelection", False);
  const Atom action_copy = XInternAtom(display, "XdndActionCopy", False);
  const Atom uri_type = XInternAtom(display, "text/uri-list", False);
  XSetSelectionOwner(display, selection, source, CurrentTime);

  const long enter_data[5] = {static_cast<long>(source), 5L << 24, static_cast<long>(uri_type), 0,
                              0};
  send_client_message(display, target, enter, enter_data);
  const long position_data[5] = {static_cast<long>(source), 0, (600L << 16) | 200L, CurrentTime,
                                 static_cast<long>(action_copy)};
  send_client_message(display, target, position, position_data);
  std::this_thread::sleep_for(200ms);
  const long drop_data[5] = {static_cast<long>(source), 0, CurrentTime, 0, 0};
  send_client_message(display, target, drop, drop_data);

  bool served = false, done = false;
  const auto end = std::chrono::steady_clock::now() + 10s;
  while (!done && std::chrono::steady_clock::now() < end) {
    if (!XPending(display)) {
      std::this_thread::sleep_for(20ms);
      continue;
    }
    XEvent event;
    XNextEvent(display, &event);
    if (event.type == SelectionRequest) {
      const XSelectionRequestEvent& request = event.xselectionrequest;
      XChangeProperty(display, request.requestor, request.property, request.target, 8,
                      PropModeReplace, reinterpret_cast<const unsigned char*>(uri_list.data()),
                      static_cast<int>(uri_list.size()));
      XEvent reply{};
      reply.xselection.type = SelectionNotify;
      reply.xselection.display = display;
      reply.xselection.requestor = request.requestor;
      reply.xselection.selection = request.selection;
      reply.xselection.target = request.target;
      reply.xselection.property = request.property;
      reply.xselection.time = request.time;
      XSendEvent(display, request.requestor, False, NoEventMask, &reply);
      XFlush(display);
      served = true;
    } else if (event.type == ClientMessage && event.xclient.message_type == finished) {
      done = true;
    }
  }
  XDestroyWindow(display, source);
  XCloseDisplay(display);
  return served;
}

TEST(ViewerDrop, DroppedFileReplacesTheMesh) {
  const std::string source = TETLOD_SOURCE_DIR;
  test::BackgroundViewer viewer;
  ASSERT_TRUE(viewer.start("viewer_drop", source + "/assets/box2.mesh",
                           "screenshot a.png width=200 height=200\n"
                           "wait seconds=3\n"
                           "screenshot b.png width=200 height=200\n"
                           "save b.mesh\n"
                           "quit\n"));
  ASSERT_TRUE(viewer.wait_for("a.png"));
  EXPECT_TRUE(drop_files("TetLOD", "file://" + source + "/assets/spheres.mesh\r\n"));
  EXPECT_EQ(viewer.finish(), 0);
  EXPECT_GT(viewer.differing_pixels("a.png", "b.png"), 200u * 200u / 50u);
  // The saved level is the dropped mesh (no simplification yet: the input itself).
  TetMesh saved, spheres;
  ASSERT_TRUE(read_mesh((viewer.dir() / "b.mesh").string(), &saved).ok());
  ASSERT_TRUE(read_mesh(source + "/assets/spheres.mesh", &spheres).ok());
  EXPECT_EQ(saved.tet_count(), spheres.tet_count());
  EXPECT_EQ(saved.materials, spheres.materials);
}

}  // namespace
}  // namespace tetlod
