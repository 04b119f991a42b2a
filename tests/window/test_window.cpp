// The window backend (GLFW) draws the same pixels as the offscreen one: the motor
// golden image, rendered in a hidden GLFW window, must match. Needs a display; the
// test suite runs it under xvfb-run (see tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <string>

#include "core/io/mesh_io.h"
#include "render/gl_context.h"
#include "render/renderer.h"
#include "render/snapshot.h"

namespace tetlod::render {
namespace {

TEST(Window, RendersTheSamePixelsAsOffscreen) {
  std::string error;
  auto window = WindowContext::create(256, 256, "tetlod test", /*visible=*/false, &error);
  ASSERT_TRUE(window) << error;
  std::printf("%s\n", window->description().c_str());
  Renderer renderer(window->gl());
  ASSERT_TRUE(renderer.init(&error)) << error;

  TetMesh mesh;
  ReadInfo info;
  const std::string source = TETLOD_SOURCE_DIR;
  ASSERT_TRUE(read_mesh(source + "/assets/motor.mesh", &mesh, &info).ok());
  const PreparedMesh prepared = prepare_mesh(std::move(mesh));
  SnapshotSettings settings;  // as the golden test's motor_stretch
  settings.width = settings.height = 256;
  settings.filter.hidden_materials = {1};
  const Image actual = render_snapshot(&renderer, prepared, settings);

  // Shows the frame in the window too (the viewer's path).
  int width = 0, height = 0;
  window->framebuffer_size(&width, &height);
  renderer.present(width, height);
  window->swap_buffers();
  window->poll_events();
  EXPECT_EQ(window->gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));

  Image golden;
  ASSERT_TRUE(read_png(source + "/tests/golden/motor_stretch.png", &golden).ok());
  const ImageDifference d = compare_images(golden, actual, 8, nullptr);
  EXPECT_TRUE(d.same_size);
  EXPECT_LE(d.differing_pixels, 256u * 256u / 200u)
      << "largest difference " << d.max_channel_difference;
}

TEST(Window, NoDisplayIsAnErrorNotACrash) {
  // Only meaningful without a display; under xvfb-run DISPLAY is set, so this
  // checks the message path by pointing at a display that does not exist.
  const char* saved = std::getenv("DISPLAY");
  const std::string display = saved ? saved : "";
  setenv("DISPLAY", ":4711", 1);
  std::string error;
  auto window = WindowContext::create(64, 64, "tetlod test", false, &error);
  EXPECT_FALSE(window);
  EXPECT_NE(error.find("no window"), std::string::npos) << error;
  setenv("DISPLAY", display.c_str(), 1);
}

}  // namespace
}  // namespace tetlod::render
