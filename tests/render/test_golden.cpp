// Golden images: the bundled models rendered offscreen (OSMesa, no display) at a
// fixed camera and size, compared per channel with a tolerance and a cap on the
// number of differing pixels. On a mismatch the actual and a diff image are written
// to <build>/tests/out/golden/. TETLOD_UPDATE_GOLDENS=1 rewrites the goldens in
// tests/golden/ on purpose (look at them before committing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "core/io/mesh_io.h"
#include "render/gl_context.h"
#include "render/renderer.h"
#include "render/snapshot.h"

namespace tetlod::render {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 256;
// llvmpipe is deterministic on one machine; the tolerance absorbs rounding
// differences between Mesa builds, the cap a few edge pixels of multisampling.
constexpr int kChannelTolerance = 8;
constexpr size_t kMaxDifferingPixels = kSize * kSize / 200;  // 0.5%

class Offscreen {
 public:
  static Offscreen& get() {
    static Offscreen instance;
    return instance;
  }
  Renderer* renderer() {
    if (context_) context_->make_current();
    return renderer_.get();
  }
  const std::string& error() const { return error_; }

  const PreparedMesh& mesh(const std::string& asset) {
    auto it = meshes_.find(asset);
    if (it == meshes_.end()) {
      TetMesh mesh;
      ReadInfo info;
      const Status s = read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/" + asset, &mesh, &info);
      EXPECT_TRUE(s.ok()) << s.message();
      it = meshes_.emplace(asset, prepare_mesh(std::move(mesh))).first;
    }
    return it->second;
  }

 private:
  Offscreen() {
    // The goldens are OSMesa's pictures; the EGL backend is compared with them below.
    context_ = create_offscreen_context(&error_, OffscreenBackend::kOsMesa);
    if (!context_) return;
    renderer_ = std::make_unique<Renderer>(context_->gl());
    if (!renderer_->init(&error_)) renderer_.reset();
  }
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Renderer> renderer_;
  std::string error_;
  std::map<std::string, PreparedMesh> meshes_;
};

struct GoldenCase {
  const char* name;
  const char* asset;
  SnapshotSettings settings;
};

SnapshotSettings base_settings() {
  SnapshotSettings s;
  s.width = s.height = kSize;
  return s;
}

// The motor with the air (material 1) hidden, coloured by stretch (viridis).
SnapshotSettings motor_stretch() {
  SnapshotSettings s = base_settings();
  s.filter.hidden_materials = {1};
  return s;
}

// The motor by material, cut at y = 0, worst tets highlighted.
SnapshotSettings motor_cut() {
  SnapshotSettings s = base_settings();
  s.filter.hidden_materials = {1};
  s.filter.cut = true;
  s.filter.cut_plane = {{0, 1, 0}, 0};
  s.filter.highlight = true;
  s.filter.highlight_below = 0.2;
  s.draw.color_mode = ColorMode::kMaterial;
  return s;
}

// The concentric spheres cut in half at x = 0, by stretch (turbo).
SnapshotSettings spheres_cut() {
  SnapshotSettings s = base_settings();
  s.filter.cut = true;
  s.filter.cut_plane = {{1, 0, 0}, 0};
  s.draw.color_map = ColorMap::kTurbo;
  return s;
}

// The two-material box by material with the wireframe.
SnapshotSettings box2_wireframe() {
  SnapshotSettings s = base_settings();
  s.draw.color_mode = ColorMode::kMaterial;
  s.draw.wireframe = true;
  return s;
}

std::string golden_path(const std::string& name) {
  return std::string(TETLOD_SOURCE_DIR) + "/tests/golden/" + name + ".png";
}

std::string output_path(const std::string& name, const char* suffix) {
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/golden";
  fs::create_directories(dir);
  return dir + "/" + name + suffix;
}

Image render_case(const char* asset, const SnapshotSettings& settings) {
  Offscreen& offscreen = Offscreen::get();
  if (!offscreen.renderer()) {
    ADD_FAILURE() << "no offscreen renderer: " << offscreen.error();
    return {};
  }
  return render_snapshot(offscreen.renderer(), offscreen.mesh(asset), settings);
}

bool updating_goldens() {
  const char* update = std::getenv("TETLOD_UPDATE_GOLDENS");
  return update && std::string(update) == "1";
}

// Renders and compares with the golden `golden`; true if it matches.
ImageDifference difference_from_golden(const std::string& golden, const Image& actual) {
  Image expected;
  const Status s = read_png(golden_path(golden), &expected);
  EXPECT_TRUE(s.ok()) << s.message() << " (run with TETLOD_UPDATE_GOLDENS=1 to create it)";
  if (!s.ok()) return {0, 0, false};
  return compare_images(expected, actual, kChannelTolerance, nullptr);
}

bool matches(const ImageDifference& d) {
  return d.same_size && d.differing_pixels <= kMaxDifferingPixels;
}

void check_golden(const std::string& name, const char* asset, const SnapshotSettings& settings) {
  const Image actual = render_case(asset, settings);
  ASSERT_EQ(actual.width, kSize);
  // Pictures are opaque: blending (the highlight's see-through pass) must not leave
  // alpha below 1, or viewers would show the page through the PNG.
  size_t translucent = 0;
  for (size_t i = 3; i < actual.rgba.size(); i += 4) translucent += actual.rgba[i] != 255;
  EXPECT_EQ(translucent, 0u) << name;
  if (updating_goldens()) {
    const Status s = write_png(golden_path(name), actual);
    ASSERT_TRUE(s.ok()) << s.message();
    std::printf("updated %s\n", golden_path(name).c_str());
    return;
  }
  Image expected;
  const Status s = read_png(golden_path(name), &expected);
  ASSERT_TRUE(s.ok()) << s.message() << " (run with TETLOD_UPDATE_GOLDENS=1 to create it)";
  Image diff;
  const ImageDifference d = compare_images(expected, actual, kChannelTolerance, &diff);
  if (!matches(d)) {
    const std::string actual_path = output_path(name, ".actual.png");
    const std::string diff_path = output_path(name, ".diff.png");
    EXPECT_TRUE(write_png(actual_path, actual).ok());
    if (d.same_size) {
      EXPECT_TRUE(write_png(diff_path, diff).ok());
    }
    ADD_FAILURE() << name << ": " << d.differing_pixels << " pixels differ by more than "
                  << kChannelTolerance << " (cap " << kMaxDifferingPixels
                  << "), largest channel difference " << d.max_channel_difference
                  << "\n  actual: " << actual_path << "\n  diff:   " << diff_path;
  }
}

TEST(Golden, MotorStretchAirHidden) {
  check_golden("motor_stretch", "motor.mesh", motor_stretch());
}
TEST(Golden, MotorCutByMaterialWithHighlight) {
  check_golden("motor_cut", "motor.mesh", motor_cut());
}
TEST(Golden, SpheresCutInHalf) {
  check_golden("spheres_cut", "spheres.mesh", spheres_cut());
}
TEST(Golden, Box2MaterialWireframe) {
  check_golden("box2_wireframe", "box2.mesh", box2_wireframe());
}

// The comparison must be able to fail: each change below must NOT match its golden.
void expect_mismatch(const std::string& golden, const char* asset,
                     const SnapshotSettings& changed) {
  if (updating_goldens()) {
    GTEST_SKIP() << "updating goldens";
  }
  const ImageDifference d = difference_from_golden(golden, render_case(asset, changed));
  EXPECT_FALSE(matches(d)) << "a changed picture matched " << golden << " (" << d.differing_pixels
                           << " pixels differ)";
  EXPECT_GT(d.differing_pixels, 4 * kMaxDifferingPixels);
}

TEST(GoldenSensitivity, ColourMapChangeIsCaught) {
  SnapshotSettings s = motor_stretch();
  s.draw.color_map = ColorMap::kTurbo;
  expect_mismatch("motor_stretch", "motor.mesh", s);
}

TEST(GoldenSensitivity, ColourModeChangeIsCaught) {
  SnapshotSettings s = box2_wireframe();
  s.draw.color_mode = ColorMode::kStretch;
  expect_mismatch("box2_wireframe", "box2.mesh", s);
}

TEST(GoldenSensitivity, CutChangeIsCaught) {
  SnapshotSettings s = spheres_cut();
  s.filter.cut_plane.offset = 1.0;
  expect_mismatch("spheres_cut", "spheres.mesh", s);
  s = spheres_cut();
  s.filter.cut_plane = {{0, 1, 0}, 0};
  expect_mismatch("spheres_cut", "spheres.mesh", s);
}

TEST(GoldenSensitivity, CameraChangeIsCaught) {
  SnapshotSettings s = motor_stretch();
  s.view.direction = ViewDirection::kX;
  expect_mismatch("motor_stretch", "motor.mesh", s);
  s = motor_cut();
  s.view.custom = true;
  s.view.eye = {200, 150, 180};
  s.view.target = {5, 0, 0};
  expect_mismatch("motor_cut", "motor.mesh", s);
}

TEST(GoldenSensitivity, HiddenMaterialChangeIsCaught) {
  SnapshotSettings s = motor_stretch();
  s.filter.hidden_materials = {1, 6};
  expect_mismatch("motor_stretch", "motor.mesh", s);
}

TEST(GoldenSensitivity, HighlightChangeIsCaught) {
  SnapshotSettings s = motor_cut();
  s.filter.highlight = false;
  const ImageDifference d = difference_from_golden("motor_cut", render_case("motor.mesh", s));
  EXPECT_FALSE(matches(d)) << d.differing_pixels << " pixels differ";
}

// Names given to the materials replace "material <m>" in the key at the top left, and
// nothing else in the picture changes; an unnamed material keeps its number.
TEST(GoldenSensitivity, MaterialNamesAreInTheKeyOnly) {
  const Image plain = render_case("box2.mesh", box2_wireframe());
  Offscreen::get().renderer()->set_material_names({MaterialName{2, "air gap"}});
  const Image named = render_case("box2.mesh", box2_wireframe());
  Offscreen::get().renderer()->set_material_names({});  // the renderer is shared
  ASSERT_EQ(plain.width, kSize);
  ASSERT_EQ(named.width, kSize);
  // The key's second line (material 2) is 8 x 2 pixels high at the top left; the
  // first line, for material 1, stays.
  int x_max = 0, y_min = kSize, y_max = 0;
  size_t changed = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if (std::memcmp(plain.pixel(x, y), named.pixel(x, y), 3) == 0) continue;
      ++changed;
      x_max = std::max(x_max, x);
      y_min = std::min(y_min, y);
      y_max = std::max(y_max, y);
    }
  }
  EXPECT_GT(changed, 40u);      // the new text
  EXPECT_LT(x_max, kSize / 2);  // within the key
  EXPECT_GT(y_min, 16);         // below its first line
  EXPECT_LT(y_max, 48);         // within its second line
  const Image again = render_case("box2.mesh", box2_wireframe());
  EXPECT_EQ(again.rgba, plain.rgba);
}

// The EGL surfaceless backend (OSMesa's successor) draws the same pictures.
TEST(GoldenBackends, EglSurfacelessMatchesTheGoldens) {
  if (updating_goldens()) {
    GTEST_SKIP() << "updating goldens";
  }
  // Load the meshes (and make the OSMesa context) before the EGL context is made
  // current, so that nothing switches contexts under the EGL renderer.
  const PreparedMesh& motor_mesh = Offscreen::get().mesh("motor.mesh");
  const PreparedMesh& spheres_mesh = Offscreen::get().mesh("spheres.mesh");
  std::string error;
  auto egl = create_offscreen_context(&error, OffscreenBackend::kEgl);
  ASSERT_TRUE(egl) << error;
  ASSERT_TRUE(egl->make_current());
  std::printf("%s\n", egl->description().c_str());
  {
    Renderer renderer(egl->gl());
    ASSERT_TRUE(renderer.init(&error)) << error;
    const Image motor = render_snapshot(&renderer, motor_mesh, motor_stretch());
    EXPECT_TRUE(matches(difference_from_golden("motor_stretch", motor)));
    const Image spheres = render_snapshot(&renderer, spheres_mesh, spheres_cut());
    EXPECT_TRUE(matches(difference_from_golden("spheres_cut", spheres)));
  }
}

// A framebuffer GL cannot make is an error, and the renderer still works after it.
TEST(GoldenBackends, ImpossibleFramebufferIsAnErrorNotGarbage) {
  Renderer* renderer = Offscreen::get().renderer();
  ASSERT_TRUE(renderer) << Offscreen::get().error();
  SnapshotSettings s = box2_wireframe();
  s.width = 100000;  // beyond GL_MAX_RENDERBUFFER_SIZE
  s.height = 16;
  const Image failed = render_snapshot(renderer, Offscreen::get().mesh("box2.mesh"), s);
  EXPECT_EQ(failed.width, 0);
  EXPECT_NE(renderer->last_error().find("cannot make a 100000x16 framebuffer"), std::string::npos)
      << renderer->last_error();
  if (updating_goldens()) return;
  const ImageDifference d =
      difference_from_golden("box2_wireframe", render_case("box2.mesh", box2_wireframe()));
  EXPECT_TRUE(matches(d));
}

// Rendering twice gives the same pixels (the goldens can be trusted run to run).
TEST(GoldenSensitivity, RenderingIsDeterministic) {
  const Image a = render_case("spheres.mesh", spheres_cut());
  const Image b = render_case("spheres.mesh", spheres_cut());
  const ImageDifference d = compare_images(a, b, 0, nullptr);
  EXPECT_EQ(d.differing_pixels, 0u);
}

// The rows the colour bar covers at the bottom and the box of the material key at the
// top left, drawn without the legend from the camera the snapshot takes (framed clear
// of it): background only, so the legend hides nothing. Framed as before (no legend
// space), box2's nearest corner reaches into the bar's rows, and the motor (a box) into
// the key.
size_t model_pixels_under_legend(const char* asset, int width, int height, ColorMode mode,
                                 bool keep_clear) {
  Renderer* renderer = Offscreen::get().renderer();
  if (!renderer) {
    ADD_FAILURE() << Offscreen::get().error();
    return 0;
  }
  const PreparedMesh& mesh = Offscreen::get().mesh(asset);
  SurfaceBuffers buffers;
  build_surface(mesh.surface_input(), SurfaceFilter{}, &buffers);
  renderer->upload(buffers);
  DrawSettings draw;
  draw.color_mode = mode;
  const LegendSpace legend = renderer->legend_space(draw, width, height);
  if (mode == ColorMode::kMaterial) {
    EXPECT_GT(legend.key_width, 0.05);
    EXPECT_GT(legend.key_height, 0.05);
  } else {
    EXPECT_GT(legend.bottom, 0.05);
  }
  const PictureFraming framing = snapshot_framing(mesh, buffers, ViewSpec{}, width, height,
                                                  keep_clear ? legend : LegendSpace{});
  draw.legend = false;
  EXPECT_TRUE(renderer->draw(draw, framing.camera, width, height, &framing.scene))
      << renderer->last_error();
  const Image image = renderer->read_pixels();
  const auto model = [&image](int x0, int y0, int x1, int y1) {
    size_t count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        count += image.pixel(x, y)[0] != 255 || image.pixel(x, y)[1] != 255;
    return count;
  };
  const int bar_rows = static_cast<int>(std::floor(legend.bottom * height));
  const int key_w = static_cast<int>(std::floor(legend.key_width * width));
  const int key_h = static_cast<int>(std::floor(legend.key_height * height));
  return model(0, height - bar_rows, width, height) + model(0, 0, key_w, key_h);
}

TEST(Legend, TheModelStandsClearOfTheLegend) {
  for (const char* asset : {"box2.mesh", "motor.mesh", "spheres.mesh"}) {
    for (const ColorMode mode : {ColorMode::kStretch, ColorMode::kMaterial}) {
      for (const auto& [width, height] :
           {std::pair{800, 800}, std::pair{640, 400}, std::pair{300, 500}, std::pair{256, 256}}) {
        EXPECT_EQ(model_pixels_under_legend(asset, width, height, mode, true), 0u)
            << asset << " " << width << "x" << height << " mode " << int(mode);
      }
    }
  }
  EXPECT_GT(model_pixels_under_legend("box2.mesh", 800, 800, ColorMode::kStretch, false), 100u);
  EXPECT_GT(model_pixels_under_legend("motor.mesh", 800, 800, ColorMode::kMaterial, false), 100u);
}

// A picture of its own frames what is drawn, not its box: the motor without its air (a
// cylinder, whose box's corners stand well clear of it in the iso view) spans 94 % of the
// picture's width or height, with a margin on every side (framed by the box's corners,
// it spanned 68-73 %).
TEST(Framing, ARoundModelFillsItsPicture) {
  Renderer* renderer = Offscreen::get().renderer();
  ASSERT_TRUE(renderer) << Offscreen::get().error();
  const PreparedMesh& mesh = Offscreen::get().mesh("motor.mesh");
  for (const auto& [width, height] : {std::pair{400, 400}, std::pair{480, 300}}) {
    SurfaceFilter filter;
    filter.hidden_materials = {1};
    SurfaceBuffers buffers;
    build_surface(mesh.surface_input(), filter, &buffers);
    renderer->upload(buffers);
    DrawSettings draw;
    draw.legend = false;
    const PictureFraming framing = snapshot_framing(mesh, buffers, ViewSpec{}, width, height);
    ASSERT_TRUE(renderer->draw(draw, framing.camera, width, height, &framing.scene))
        << renderer->last_error();
    const Image image = renderer->read_pixels();
    int x0 = width, x1 = -1, y0 = height, y1 = -1;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        if (image.pixel(x, y)[0] != 255 || image.pixel(x, y)[1] != 255) {
          x0 = std::min(x0, x), x1 = std::max(x1, x);
          y0 = std::min(y0, y), y1 = std::max(y1, y);
        }
    ASSERT_GE(x1, 0) << width << "x" << height << ": nothing drawn";
    const double span = std::max(double(x1 - x0 + 1) / width, double(y1 - y0 + 1) / height);
    EXPECT_GT(span, 0.92) << width << "x" << height;
    EXPECT_LT(span, 0.96) << width << "x" << height;
    EXPECT_GT(x0, 0);
    EXPECT_GT(y0, 0);
    EXPECT_LT(x1, width - 1);
    EXPECT_LT(y1, height - 1);
  }
}

// A picture too small for the legend leaves it out (its numbers would overprint):
// nothing of it is drawn or kept clear of.
TEST(Legend, APictureTooSmallForTheLegendHasNone) {
  Renderer* renderer = Offscreen::get().renderer();
  ASSERT_TRUE(renderer) << Offscreen::get().error();
  SurfaceBuffers buffers;
  build_surface(Offscreen::get().mesh("motor.mesh").surface_input(), SurfaceFilter{}, &buffers);
  renderer->upload(buffers);
  DrawSettings draw;
  EXPECT_EQ(renderer->legend_space(draw, 48, 48).bottom, 0);
  EXPECT_GT(renderer->legend_space(draw, 320, 320).bottom, 0);
  draw.color_mode = ColorMode::kMaterial;
  EXPECT_EQ(renderer->legend_space(draw, 60, 60).key_width, 0);
  EXPECT_GT(renderer->legend_space(draw, 320, 320).key_width, 0);
  draw.legend = false;
  EXPECT_EQ(renderer->legend_space(draw, 320, 320).key_width, 0);
}

// Many surface groups drawn keep a key: those that fit, then "and N more surface groups",
// the materials' key giving way a line at a time too (past 16 groups the key vanished,
// the materials' with it). A key of groups is as tall as one of the same number of
// materials.
TEST(Legend, ManySurfaceGroupsKeepAKey) {
  Renderer* renderer = Offscreen::get().renderer();
  ASSERT_TRUE(renderer) << Offscreen::get().error();
  SurfaceBuffers buffers;
  build_surface(Offscreen::get().mesh("motor.mesh").surface_input(), SurfaceFilter{}, &buffers);
  renderer->upload(buffers);
  GroupOverlay overlay;
  for (uint32_t g = 0; g < 40; ++g)
    overlay.groups.push_back({g, 0, 0, 0, surface_group_rgb(g), "group " + std::to_string(g)});
  DrawSettings draw;
  const LegendSpace none = renderer->legend_space(draw, 640, 480);
  EXPECT_EQ(none.key_height, 0);
  renderer->set_groups(overlay);
  const LegendSpace groups = renderer->legend_space(draw, 640, 480);
  EXPECT_GT(groups.key_height, 0.3);  // (60 % of the picture at most)
  EXPECT_LE(groups.key_height, 0.62);
  draw.color_mode = ColorMode::kMaterial;  // the motor's 7 materials and 40 groups
  const LegendSpace both = renderer->legend_space(draw, 640, 480);
  EXPECT_GT(both.key_height, 0.3);
  EXPECT_LE(both.key_height, 0.62);
  renderer->set_groups({});
  EXPECT_LT(renderer->legend_space(draw, 640, 480).key_height, both.key_height);
}

}  // namespace
}  // namespace tetlod::render
