// `tetlod render` through the real binary: a PNG is written, bad values are usage
// errors, and failures (unreadable input, no GL, unwritable output) leave no file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/cli_runner.h"
#include "core/io/mesh_io.h"
#include "core/test_meshes.h"
#include "render/image.h"

namespace tetlod {
namespace {

namespace fs = std::filesystem;

using test::CommandResult;

CommandResult run(const std::string& arguments, const std::string& environment = "") {
  return test::run_tetlod(arguments, environment);
}

std::string out_dir() {
  return test::cli_output_dir("cli_render");
}

std::string asset(const char* name) {
  return std::string(TETLOD_SOURCE_DIR) + "/assets/" + name;
}

// Width and height from a PNG's IHDR chunk, or {0, 0} if it is not a PNG.
std::pair<int, int> png_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(signature, signature + 8, header)) return {0, 0};
  auto be32 = [&](int at) {
    return (header[at] << 24) | (header[at + 1] << 16) | (header[at + 2] << 8) | header[at + 3];
  };
  return {be32(16), be32(20)};
}

TEST(CliRender, WritesAPngOfTheRequestedSize) {
  const std::string out = out_dir() + "/motor.png";
  fs::remove(out);
  const CommandResult r = run("render " + asset("motor.mesh") +
                              " --hide 1 --cut y=0 --wireframe --highlight-below 0.2 --width 320 "
                              "--height 200 -o " +
                              out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("faces drawn"), std::string::npos) << r.output;
  EXPECT_EQ(png_size(out), std::make_pair(320, 200));
}

TEST(CliRender, RendersASimplifiedLevel) {
  const std::string out = out_dir() + "/box2_level.png";
  fs::remove(out);
  const CommandResult r = run("render " + asset("box2.mesh") +
                              " --simplify --size 10 --no-subdivide --elements 60 --color material "
                              "--width 64 --height 64 -o " +
                              out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(png_size(out), std::make_pair(64, 64));
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// `render --simplify --improve` draws what `simplify --improve` writes, and that is not
// what `render --simplify` draws.
TEST(CliRender, RendersTheImprovedLevelThatSimplifyWrites) {
  const std::string level = out_dir() + "/improved_level.mesh";
  const std::string flags = " --size 12 --tolerance 0.05 --improve";
  CommandResult r = run("simplify " + asset("motor.mesh") + " -o " + level + flags);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string view = " --hide 1 --cut y=0 --highlight-below 0.2 --width 96 --height 96 -o ";
  const std::string direct = out_dir() + "/improved_direct.png";
  const std::string later = out_dir() + "/improved_later.png";
  const std::string plain = out_dir() + "/not_improved.png";
  r = run("render " + asset("motor.mesh") + " --simplify" + flags + view + direct);
  ASSERT_EQ(r.code, 0) << r.output;
  const CommandResult from_file = run("render " + level + view + later);
  ASSERT_EQ(from_file.code, 0) << from_file.output;
  // "PATH: WxH, N tets, ..." from each.
  auto tets = [](const std::string& output) {
    const size_t at = output.find("x96, ");
    return at == std::string::npos ? -1L : std::atol(output.c_str() + at + 5);
  };
  EXPECT_GT(tets(r.output), 0) << r.output;
  EXPECT_EQ(tets(r.output), tets(from_file.output)) << from_file.output;
  EXPECT_EQ(file_bytes(direct), file_bytes(later));
  r = run("render " + asset("motor.mesh") + " --simplify --size 12 --tolerance 0.05" + view +
          plain);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(file_bytes(plain), file_bytes(direct));
}

// A saved history renders any of its levels without simplifying again: the level
// nearest --elements (the last by default) is drawn as `lod` writes it; simplifier
// flags other than --elements are usage errors for a history.
TEST(CliRender, RendersALevelOfASavedHistory) {
  const std::string history = out_dir() + "/render_history.tlh";
  CommandResult r = run("simplify " + asset("motor.mesh") + " -o " + out_dir() +
                        "/render_history_end.mesh --size 12 --tolerance 0.05 --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string view = " --hide 1 --cut y=0 --width 96 --height 96 -o ";
  for (const char* elements : {"40000", ""}) {
    const std::string level = out_dir() + "/render_history_level.mesh";
    const std::string select = *elements ? std::string(" --elements ") + elements : "";
    r = run("lod " + history + (*elements ? select : " --step 999999") + " -o " + level);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string from_history = out_dir() + "/render_history_direct.png";
    const std::string from_level = out_dir() + "/render_history_level.png";
    r = run("render " + history + select + view + from_history);
    ASSERT_EQ(r.code, 0) << r.output;
    r = run("render " + level + view + from_level);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(file_bytes(from_history), file_bytes(from_level)) << "--elements " << elements;
  }
  // Commands that take a mesh say what to do with a history instead.
  r = run("stats " + history);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("is a collapse history, not a mesh: write one of its levels with "
                          "'tetlod lod"),
            std::string::npos)
      << r.output;
  for (const char* flags : {" --simplify", " --size 3", " --elements 10 --improve --size 3"}) {
    r = run("render " + history + flags + view + out_dir() + "/render_history_bad.png");
    EXPECT_EQ(r.code, 2) << flags << "\n" << r.output;
    EXPECT_NE(r.output.find("is a collapse history"), std::string::npos) << r.output;
  }
  // --improve improves the level within the history's saved thresholds, as `lod
  // --improve` does; a history saved without them says so.
  const std::string improved = out_dir() + "/render_history_improved.mesh";
  ASSERT_EQ(run("lod " + history + " --elements 40000 --improve -o " + improved).code, 0);
  const std::string from_history = out_dir() + "/render_history_improved_direct.png";
  const std::string from_level = out_dir() + "/render_history_improved_level.png";
  r = run("render " + history + " --elements 40000 --improve" + view + from_history);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_EQ(run("render " + improved + view + from_level).code, 0);
  EXPECT_EQ(file_bytes(from_history), file_bytes(from_level));
  r = run("render " + history + " --elements 40000" + view + from_level);
  EXPECT_NE(file_bytes(from_history), file_bytes(from_level)) << "--improve changed nothing";
  std::string bytes = file_bytes(history);
  bytes[7] = '1';  // a history of the first version, saved without its thresholds
  const std::string legacy = out_dir() + "/render_history_legacy.tlh";
  std::ofstream(legacy, std::ios::binary) << bytes.substr(0, bytes.find("TLPARAM1"));
  r = run("render " + legacy + " --improve" + view + from_level);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("render_history_legacy.tlh was saved without its thresholds"),
            std::string::npos)
      << r.output;
}

TEST(CliRender, BadValuesAreUsageErrors) {
  const std::string in = asset("box2.mesh");
  const std::string out = out_dir() + "/never.png";
  fs::remove(out);
  for (const char* flags : {"--width 0",
                            "--width 5000",
                            "--width abc",
                            "--color hue",
                            "--colormap jet",
                            "--cut w=1",
                            "--cut x",
                            "--cut-plane 0,0,0,1",
                            "--cut-plane 1,2",
                            "--view top",
                            "--camera 1,2,3,1,2,3",
                            "--highlight-below 2",
                            "--range 1,0",
                            "--materials 1,-2",
                            "--bogus",
                            "--simplify",
                            "--color material --range 0,1",
                            "--size -1",
                            "--view x --camera 5,5,5,1,0.5,0.5",
                            "--cut x=0.5 --cut-plane 1,0,0,0.5",
                            "--materials 1 --hide 2"}) {
    const CommandResult r = run("render " + in + " -o " + out + " " + flags);
    EXPECT_EQ(r.code, 2) << flags << "\n" << r.output;
    EXPECT_NE(r.output.find("tetlod"), std::string::npos) << flags;
  }
  // Alternatives given together: one would be dropped without a word.
  EXPECT_NE(run("render " + in + " -o " + out + " --camera 5,5,5,1,0.5,0.5 --view=x")
                .output.find("tetlod render: give --view or --camera, not both"),
            std::string::npos);
  const CommandResult elements = run("render " + in + " -o " + out + " --elements 5");
  EXPECT_EQ(elements.code, 2) << elements.output;
  EXPECT_NE(elements.output.find("--elements picks a level of a simplification"), std::string::npos)
      << elements.output;
  EXPECT_EQ(run("render " + in).code, 2);  // no -o
  // PNG only: an output named like the input mesh (or anything else) is refused.
  const std::string copy = out_dir() + "/box2_copy.mesh";
  fs::copy_file(in, copy, fs::copy_options::overwrite_existing);
  for (const std::string& name : {copy, out_dir() + "/shot.jpg", out_dir() + "/shot"}) {
    const CommandResult r = run("render " + copy + " -o " + name);
    EXPECT_EQ(r.code, 2) << name << "\n" << r.output;
    EXPECT_NE(r.output.find("give a .png name"), std::string::npos) << r.output;
  }
  TetMesh kept;
  EXPECT_TRUE(read_mesh(copy, &kept).ok());
  EXPECT_EQ(run("render --help").code, 0);
  EXPECT_FALSE(fs::exists(out));
}

// The count in render's "N faces drawn", or "" if the output has none.
std::string faces_drawn(const std::string& output) {
  const size_t at = output.find(" faces drawn");
  if (at == std::string::npos || at == 0) return "";
  const size_t start = output.rfind(' ', at - 1) + 1;
  return output.substr(start, at - start);
}

// A cut plane's normal of any magnitude is that normal: the same faces are drawn for
// 1,1,0,D, 1e300,1e300,0,1e300*D and 1e-200,1e-200,0,1e-200*D.
TEST(CliRender, CutPlaneNormalsOfAnyMagnitude) {
  const std::string out = out_dir() + "/plane.png";
  std::string first;
  for (const char* plane : {"1,1,0,0.5", "1e300,1e300,0,5e299", "1e-200,1e-200,0,5e-201"}) {
    const CommandResult r = run("render " + asset("box2.mesh") +
                                " --width 64 --height 64 --cut-plane " + plane + " -o " + out);
    ASSERT_EQ(r.code, 0) << plane << "\n" << r.output;
    const std::string faces = faces_drawn(r.output);
    ASSERT_NE(faces, "") << r.output;
    if (first.empty()) first = faces;
    EXPECT_EQ(faces, first) << plane;
  }
  const CommandResult far =
      run("render " + asset("box2.mesh") + " --cut-plane 1e-300,0,0,1e300 -o " + out);
  EXPECT_EQ(far.code, 2) << far.output;
}

// The picture does not depend on the model's unit: box2 in units a 1e25th or 1e25
// times as large draws as box2 does (in float, lighting squared view positions: at
// 1e-9 or 1e20 the faces came out black, at 1e-15 nothing was drawn). Beyond what
// float positions hold, a clear error.
TEST(CliRender, AnyModelSizeDrawsTheSamePicture) {
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(asset("box2.mesh"), &mesh).ok());
  render::Image first;
  for (const double scale : {1.0, 1e-25, 1e25}) {
    SCOPED_TRACE(scale);
    TetMesh scaled = mesh;
    for (Vec3& p : scaled.positions) p = p * scale;
    const std::string in = out_dir() + "/scaled.mesh", out = out_dir() + "/scaled.png";
    ASSERT_TRUE(write_mesh(in, scaled).ok());
    const CommandResult r = run("render " + in + " --width 96 --height 96 -o " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    render::Image image;
    ASSERT_TRUE(render::read_png(out, &image).ok());
    if (scale == 1.0) {
      first = image;
      continue;
    }
    const render::ImageDifference d = render::compare_images(first, image, 8, nullptr);
    EXPECT_LE(d.differing_pixels, 20u) << "max difference " << d.max_channel_difference;
  }
  for (const double scale : {1e-40, 1e40, 1e-9}) {
    TetMesh scaled = mesh;
    // 1e-9: a nanometre part 1000 units from the origin.
    for (Vec3& p : scaled.positions) p = p * scale + Vec3{scale == 1e-9 ? 1000.0 : 0.0, 0, 0};
    const std::string in = out_dir() + "/out_of_range.mesh";
    ASSERT_TRUE(write_mesh(in, scaled).ok());
    const CommandResult r = run("render " + in + " -o " + out_dir() + "/out_of_range.png");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("pictures hold coordinates within 1e30, meshes at least 1e-30 "
                            "across, and at least 1e-5 of their distance from the origin"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out_dir() + "/out_of_range.png"));
  }
}

// --color size: a face takes its tet's longest edge, the colour map spanning the drawn
// tets' sizes (or --range): two cubes, the right one stretched 2.5x along x (tets
// 2.87 long against 1.73), seen from +z, come out in the map's two ends (viridis: dark
// purple, yellow); with --range 0,100 both are at its low end.
TEST(CliRender, ColorsBySize) {
  TetMesh mesh = test::make_grid_mesh(2, 1, 1, [](int, int, int) { return 1; });
  for (Vec3& p : mesh.positions)
    if (p.x > 1.5) p.x = 3.5;
  const std::string in = out_dir() + "/two_sizes.mesh", out = out_dir() + "/two_sizes.png";
  ASSERT_TRUE(write_mesh(in, mesh).ok());
  auto picture = [&](const std::string& flags) {
    fs::remove(out);
    const CommandResult r = run("render " + in + " --view z --no-legend --width 200 --height 200 " +
                                flags + " -o " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    render::Image image;
    EXPECT_TRUE(render::read_png(out, &image).ok());
    return image;
  };
  // Green at a fraction of the way across the drawn box, along the middle row: viridis'
  // low end has almost none (1 of 255), its high end most (231).
  auto green = [](const render::Image& image, double x) {
    const int y = image.height / 2;
    int left = image.width, right = -1;
    for (int i = 0; i < image.width; ++i) {
      const uint8_t* p = image.pixel(i, y);
      if (p[0] != 255 || p[1] != 255 || p[2] != 255) left = std::min(left, i), right = i;
    }
    EXPECT_GT(right - left, image.width / 3) << "the box is drawn across the picture";
    return int(image.pixel(left + int(x * (right - left)), y)[1]);
  };
  const render::Image by_size = picture("--color size");
  ASSERT_EQ(by_size.width, 200);
  EXPECT_LT(green(by_size, 0.1), 40) << "the small tets' end";
  EXPECT_GT(green(by_size, 0.8), 150) << "the large tets' end";
  const render::Image ranged = picture("--color size --range 0,100");
  EXPECT_LT(green(ranged, 0.1), 40);
  EXPECT_LT(green(ranged, 0.8), 40);
  const render::Image by_stretch = picture("--color stretch");
  EXPECT_GT(std::abs(green(by_stretch, 0.8) - green(by_size, 0.8)), 50);
}

// --materials and --hide take the input's names as well as ids.
TEST(CliRender, MaterialsByName) {
  const std::string coax = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax_part3.msh";
  const std::string out = out_dir() + "/by_name.png";
  std::string first;
  for (const char* flags :
       {"--hide 4,3", "--hide shield,dielectric_outer", "--materials 1,dielectric_inner"}) {
    const CommandResult r =
        run("render " + coax + " --width 64 --height 64 " + flags + " -o " + out);
    ASSERT_EQ(r.code, 0) << flags << "\n" << r.output;
    const std::string faces = faces_drawn(r.output);
    ASSERT_NE(faces, "") << r.output;
    if (first.empty()) first = faces;
    EXPECT_EQ(faces, first) << flags;
  }
  const CommandResult r = run("render " + coax + " --hide air -o " + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--hide: the mesh has no material named 'air'"), std::string::npos)
      << r.output;
}

// --groups draws the input's surface groups over the faces, in stripes of their
// colours (the top of tests/data/gmsh/sheet.msh, seen from +z, is "top_and_sheet",
// the third group: blue), and names the groups the input has when one is not there.
TEST(CliRender, DrawsTheInputsSurfaceGroups) {
  const std::string sheet = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/sheet.msh";
  const std::string plain = out_dir() + "/groups_plain.png", drawn = out_dir() + "/groups.png";
  const std::string flags = " --view z --color material --no-legend --width 96 --height 96 -o ";
  ASSERT_EQ(run("render " + sheet + flags + plain).code, 0);
  const CommandResult r = run("render " + sheet + " --groups top_and_sheet" + flags + drawn);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto blue_and_white = [](const std::string& path) {
    render::Image image;
    EXPECT_TRUE(render::read_png(path, &image).ok()) << path;
    size_t blue = 0, white = 0;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
      const int red = image.rgba[i], green = image.rgba[i + 1], b = image.rgba[i + 2];
      blue += b > red + 80 && b > green + 50;
      white += red > 150 && green > 150 && b > 150 && std::abs(red - b) < 30;
    }
    return std::make_pair(blue, white);
  };
  const auto [plain_blue, plain_white] = blue_and_white(plain);
  const auto [blue, white] = blue_and_white(drawn);
  EXPECT_EQ(plain_blue, 0u);
  EXPECT_GT(blue, 1000u);               // of 96 x 96, the block filling half
  EXPECT_GT(white, plain_white + 500);  // the stripes
  const CommandResult missing = run("render " + sheet + " --groups sheet,nope -o " + drawn);
  EXPECT_EQ(missing.code, 2) << missing.output;
  EXPECT_NE(missing.output.find("--groups 'sheet,nope': the input has no surface group 'nope' "
                                "(it has 100 'sheet', 200 'bottom', 300 'top_and_sheet')"),
            std::string::npos)
      << missing.output;
  const CommandResult none = run("render " + asset("box2.mesh") + " --groups all -o " + drawn);
  EXPECT_EQ(none.code, 2) << none.output;
  EXPECT_NE(none.output.find("the input has no surface groups"), std::string::npos) << none.output;
  // An unnamed group (a Medit reference) by its tag, or as the key calls it; solve
  // takes it as surface_<tag> too (a re-check tester could name it by tag only).
  const std::string p2 = std::string(TETLOD_SOURCE_DIR) + "/tests/data/medit_p2.mesh";
  for (const char* name : {"5", "surface_5", "'surface 5'"}) {
    const CommandResult unnamed = run("render " + p2 + " --groups " + name + " -o " + drawn);
    EXPECT_EQ(unnamed.code, 0) << name << "\n" << unnamed.output;
  }
  const CommandResult solve = run("solve " + p2 + " --conductor nope=1 --ground boundary");
  EXPECT_NE(solve.output.find("nor is it a surface group (the input's: surface_5)"),
            std::string::npos)
      << solve.output;
  const CommandResult hidden = run("render " + sheet + " --groups 200 --cut z=0.8 -o " + drawn);
  EXPECT_EQ(hidden.code, 0) << hidden.output;
  EXPECT_EQ(hidden.output.find("note: surface group"), std::string::npos) << hidden.output;
  const CommandResult cut = run("render " + sheet + " --groups 200 --cut z=-1 -o " + drawn);
  EXPECT_NE(cut.output.find("note: surface group 'bottom' is not drawn: its"), std::string::npos)
      << cut.output;
}

// A picture with nothing in it is still written, with a note that says why.
TEST(CliRender, AnEmptyPictureSaysWhy) {
  const std::string out = out_dir() + "/empty.png";
  for (const char* flags : {"--hide 1,2", "--cut x=-5"}) {
    const CommandResult r =
        run("render " + asset("box2.mesh") + " --width 32 --height 32 " + flags + " -o " + out);
    EXPECT_EQ(r.code, 0) << flags << "\n" << r.output;
    EXPECT_NE(r.output.find("0 faces drawn"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("note: the picture is empty"), std::string::npos) << r.output;
  }
  const CommandResult drawn =
      run("render " + asset("box2.mesh") + " --width 32 --height 32 -o " + out);
  EXPECT_EQ(drawn.output.find("note: the picture is empty"), std::string::npos) << drawn.output;
}

// A picture too small for its legend is drawn without it, and says so.
TEST(CliRender, ALegendThatDoesNotFitIsLeftOutWithANote) {
  const std::string out = out_dir() + "/tiny.png";
  const CommandResult tiny =
      run("render " + asset("motor.mesh") + " --width 48 --height 48 -o " + out);
  EXPECT_EQ(tiny.code, 0) << tiny.output;
  EXPECT_NE(tiny.output.find("note: the colour bar does not fit a 48x48 picture"),
            std::string::npos)
      << tiny.output;
  const CommandResult key =
      run("render " + asset("motor.mesh") + " --color material --width 60 --height 60 -o " + out);
  EXPECT_NE(key.output.find("note: the material key does not fit a 60x60 picture"),
            std::string::npos)
      << key.output;
  for (const char* flags : {"", "--color material", "--no-legend --width 48 --height 48"}) {
    const CommandResult fits = run("render " + asset("motor.mesh") + " " + flags + " -o " + out);
    EXPECT_EQ(fits.output.find("does not fit"), std::string::npos) << flags << fits.output;
  }
}

TEST(CliRender, FailuresNameTheProblemAndWriteNothing) {
  const std::string out = out_dir() + "/failed.png";
  fs::remove(out);
  CommandResult r = run("render " + out_dir() + "/missing.mesh -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("missing.mesh"), std::string::npos) << r.output;

  // A material the mesh lacks is bad usage (exit 2), as in simplify and solve.
  r = run("render " + asset("box2.mesh") + " --materials 9 -o " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("material 9 is not in the mesh"), std::string::npos) << r.output;

  // No GL available: a clear message, not a crash.
  r = run("render " + asset("box2.mesh") + " -o " + out,
          "TETLOD_GL_BACKEND=osmesa TETLOD_OSMESA=/nonexistent/libOSMesa.so");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("no offscreen OpenGL context"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("libOSMesa"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  r = run("render " + asset("box2.mesh") + " -o " + out, "TETLOD_GL_BACKEND=vulkan");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("is not osmesa or egl"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));

  // An unwritable output leaves neither the file nor a temporary behind.
  const std::string blocked = out_dir() + "/no_such_dir/shot.png";
  r = run("render " + asset("box2.mesh") + " --width 32 --height 32 -o " + blocked);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("cannot write"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("faces drawn"), std::string::npos) << "found before drawing\n"
                                                             << r.output;
  EXPECT_FALSE(fs::exists(out_dir() + "/no_such_dir"));
}

}  // namespace
}  // namespace tetlod

namespace tetlod {
namespace {

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(CliReport, WritesASelfContainedPageWithEveryLevel) {
  const std::string dir = out_dir() + "/report";
  fs::remove_all(dir);
  const CommandResult r = run("report " + asset("box2.mesh") +
                              " --simplify --size 10 --no-subdivide --levels 100,60 --width 96 "
                              "--height 96 -o " +
                              dir);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("#elements"), std::string::npos);
  EXPECT_NE(html.find("level ~100"), std::string::npos);
  EXPECT_NE(html.find("level ~60"), std::string::npos);
  EXPECT_NE(html.find("simplified (step"), std::string::npos);
  // What the run did and what the final mesh still breaks, as simplify prints it.
  EXPECT_NE(html.find("<br>Run: 0 splits, "), std::string::npos);
  EXPECT_NE(html.find(" collapses; rejected evaluations: tolerance "), std::string::npos);
  EXPECT_NE(html.find("Final mesh: 0 tets below the stretch, "), std::string::npos);
  // input, two levels, the final mesh: a picture and a histogram each.
  EXPECT_EQ(count_of(html, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 8u);
  EXPECT_EQ(png_size(dir + "/level0.png"), std::make_pair(96, 96));
  EXPECT_EQ(png_size(dir + "/level3_histogram.png"), std::make_pair(480, 260));
  EXPECT_EQ(html.rfind("</html>"), html.size() - 8);
}

// A level that is the last step (or another level) is not shown twice: its count is named
// in that level's heading.
TEST(CliReport, ALevelThatIsTheLastIsShownOnce) {
  const std::string dir = out_dir() + "/report_same_level";
  fs::remove_all(dir);
  const CommandResult r = run("report " + asset("box2.mesh") +
                              " --simplify --size 10 --no-subdivide --levels 100,1,2 --width 32 "
                              "--height 32 -o " +
                              dir);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // input, the level ~100, the final mesh (also ~2 and ~1): a picture and a histogram each.
  EXPECT_EQ(count_of(html, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 6u);
  EXPECT_NE(html.find("; also level ~2 (step "), std::string::npos) << html;
  EXPECT_NE(html.find("; also level ~1 (step "), std::string::npos) << html;
  EXPECT_FALSE(fs::exists(dir + "/level3.png"));
}

// A shorter report into the directory of a longer one removes the longer one's
// extra pictures (they would read as levels of this report) and nothing else.
TEST(CliReport, RemovesThePicturesOfALongerEarlierReport) {
  const std::string dir = out_dir() + "/report_shorter";
  fs::remove_all(dir);
  CommandResult r = run("report " + asset("box2.mesh") +
                        " --simplify --size 10 --no-subdivide --levels 100,60 --width 32 "
                        "--height 32 -o " +
                        dir);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(fs::exists(dir + "/level3_histogram.png"));
  for (const char* keep : {"level12.txt", "level4.png.bak", "levelx.png", "notes.png"})
    std::ofstream(dir + "/" + keep) << "user's file\n";
  r = run("report " + asset("box2.mesh") + " --width 32 --height 32 -o " + dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("removed 6 picture(s) of an earlier report with more levels"),
            std::string::npos)
      << r.output;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"level0.png", "level0_histogram.png", "level12.txt",
                                      "level4.png.bak", "levelx.png", "notes.png", "report.html"}));
  // Written again: the same report leaves every file in place and says nothing.
  r = run("report " + asset("box2.mesh") + " --width 32 --height 32 -o " + dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("removed"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/level0_histogram.png"));
}

// A report's files are written together or not at all: here report.html cannot
// be (a directory is in its place), so no picture is written either.
TEST(CliReport, WritesEveryFileOrNone) {
  const std::string dir = out_dir() + "/report_none";
  fs::remove_all(dir);
  fs::create_directories(dir + "/report.html");
  CommandResult r = run("report " + asset("box2.mesh") + " --width 32 --height 32 -o " + dir);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("report.html: cannot write: it is a directory"), std::string::npos)
      << r.output;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"report.html"});
}

// A Gmsh input's material names label the per-material rows of every level.
TEST(CliReport, NamesTheMaterialsAsTheInputDoes) {
  const std::string dir = out_dir() + "/report_names";
  fs::remove_all(dir);
  const CommandResult r = run("report " + std::string(TETLOD_SOURCE_DIR) +
                              "/tests/data/gmsh/coax_order2.msh --simplify --size 2 --tolerance "
                              "0.01 --width 64 --height 64 -o " +
                              dir);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string html = file_bytes(dir + "/report.html");
  EXPECT_EQ(count_of(html, "<tr><th>material 4 shield</th>"), 2u);  // input and result
  EXPECT_EQ(count_of(html, "<tr><th>material 1 inner_conductor</th>"), 2u);
}

// A level no run reaches (fewer tets than the last, more than the first) is the last
// or first level, and the heading and a note say so, for a run and for a saved history.
TEST(CliReport, LevelsBeyondTheRunAreNamed) {
  const std::string history = out_dir() + "/report_beyond.tlh";
  CommandResult r = run("simplify " + asset("box2.mesh") + " -o " + out_dir() +
                        "/report_beyond.mesh --size 10 --no-subdivide --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string view = " --levels 1,100000 --width 64 --height 64 -o ";
  for (const std::string& source :
       {asset("box2.mesh") + " --simplify --size 10 --no-subdivide", history}) {
    SCOPED_TRACE(source);
    const std::string dir = out_dir() + "/report_beyond";
    fs::remove_all(dir);
    r = run("report " + source + view + dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("note: level ~1: no level has fewer than "), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("note: level ~100000: no level has more than 136 tets; the first "
                            "level is reported"),
              std::string::npos)
        << r.output;
    const std::string html = file_bytes(dir + "/report.html");
    EXPECT_NE(html.find("level ~1 (step "), std::string::npos);
    EXPECT_NE(html.find(", the last: no level has fewer than "), std::string::npos);
    EXPECT_NE(html.find("level ~100000 (step 0, the first: no level has more than 136 tets)"),
              std::string::npos);
  }
}

// With --improve every level of the report is the improved one: its Table I row is the
// one `simplify --elements N --improve` writes.
// Sizes from --material-size alone: the page says so (it used to print "size inf").
TEST(CliReport, ThresholdsSayWhereTheSizeComesFrom) {
  const std::string dir = out_dir() + "/report_material_size";
  fs::remove_all(dir);
  const CommandResult r = run("report " + asset("box2.mesh") +
                              " --simplify --material-size 1=10,2=10 --no-subdivide --levels 100 "
                              "--width 32 --height 32 -o " +
                              dir);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("size from the local sizing (material sizes 1=10, 2=10), stretch"),
            std::string::npos);
  EXPECT_EQ(html.find("size inf"), std::string::npos);
}

TEST(CliReport, ImproveReportsTheImprovedLevels) {
  const std::string dir = out_dir() + "/report_improved";
  fs::remove_all(dir);
  const std::string flags = " --size 12 --tolerance 0.05 --improve";
  const CommandResult r = run("report " + asset("motor.mesh") + " --hide 1 --simplify" + flags +
                              " --levels 40000 --width 64 --height 64 -o " + dir);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("level ~40000 (step"), std::string::npos);
  EXPECT_EQ(count_of(html, ", improved</th>"), 2u);  // the level and the final mesh
  EXPECT_NE(html.find("levels improved (--improve)"), std::string::npos);
  const std::string level = out_dir() + "/report_level.mesh";
  const CommandResult s =
      run("simplify " + asset("motor.mesh") + " -o " + level + flags + " --elements 40000");
  ASSERT_EQ(s.code, 0) << s.output;
  const CommandResult stats = run("stats --json " + level);
  ASSERT_EQ(stats.code, 0) << stats.output;
  const size_t key = stats.output.find("\"elements\": ");
  ASSERT_NE(key, std::string::npos) << stats.output;
  const std::string elements = std::to_string(std::atol(stats.output.c_str() + key + 12));
  const size_t row = html.find("<tr><th>level ~40000");
  ASSERT_NE(row, std::string::npos);
  const std::string cells = html.substr(row, html.find("</tr>", row) - row);
  EXPECT_NE(cells.find("<td>" + elements + "</td>"), std::string::npos) << elements << cells;
}

// A report of a saved history has the rows and pictures of the report that made the
// same run, level for level, without simplifying again.
TEST(CliReport, ReportsTheLevelsOfASavedHistory) {
  const std::string history = out_dir() + "/report_history.tlh";
  CommandResult r = run("simplify " + asset("box2.mesh") + " -o " + out_dir() +
                        "/report_history.mesh --size 10 --no-subdivide --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string view = " --levels 100,60 --width 96 --height 96 -o ";
  const std::string direct = out_dir() + "/report_direct", saved = out_dir() + "/report_saved";
  fs::remove_all(direct);
  fs::remove_all(saved);
  r = run("report " + asset("box2.mesh") + " --simplify --size 10 --no-subdivide" + view + direct);
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("report " + history + view + saved);
  ASSERT_EQ(r.code, 0) << r.output;
  auto html = [](const std::string& dir) { return file_bytes(dir + "/report.html"); };
  const std::string from_history = html(saved);
  EXPECT_NE(from_history.find("levels of a saved collapse history"), std::string::npos);
  // The thresholds it keeps, as the direct report prints its own.
  const size_t start = html(direct).find("Thresholds: ");
  ASSERT_NE(start, std::string::npos);
  const std::string thresholds =
      html(direct).substr(start, html(direct).find("<br>", start) - start);
  EXPECT_NE(thresholds.find("size 10, stretch 0.15, valence 25, tolerance "), std::string::npos)
      << thresholds;
  EXPECT_NE(from_history.find(thresholds + " (saved in the history)"), std::string::npos)
      << thresholds;
  // Level by level: the same Table I row (after the label) and the same picture.
  auto row = [](const std::string& page, const std::string& label) {
    const size_t at = page.find("<tr><th>" + label);
    if (at == std::string::npos) return std::string("missing ") + label;
    const size_t cells = page.find("<td>", at);
    return page.substr(cells, page.find("</tr>", at) - cells);
  };
  for (const char* label : {"level ~100", "level ~60"})
    EXPECT_EQ(row(from_history, label), row(html(direct), label)) << label;
  EXPECT_EQ(row(from_history, "last step"), row(html(direct), "simplified (step"));
  for (const char* picture : {"/level1.png", "/level2.png", "/level3.png"})
    EXPECT_EQ(file_bytes(saved + picture), file_bytes(direct + picture)) << picture;
  r = run("report " + history + " --size 3 -o " + saved);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("is a collapse history"), std::string::npos) << r.output;
  // --improve: the levels improved within the saved thresholds, as a direct run's.
  fs::remove_all(direct);
  fs::remove_all(saved);
  r = run("report " + asset("box2.mesh") + " --simplify --size 10 --no-subdivide --improve" + view +
          direct);
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("report " + history + " --improve" + view + saved);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* label : {"level ~100", "level ~60"}) {
    EXPECT_NE(row(html(saved), label).find("<td>"), std::string::npos) << label;
    EXPECT_EQ(row(html(saved), label), row(html(direct), label)) << label;
  }
  EXPECT_NE(html(saved).find(", improved</th>"), std::string::npos);
  EXPECT_NE(html(saved).find("; levels improved (--improve)"), std::string::npos);
}

// Pictures with nothing in them are said to be empty, as render says it (a report
// with every material hidden was silent; found by a user test).
TEST(CliReport, EmptyPicturesAreNoted) {
  const CommandResult r =
      run("report " + asset("box2.mesh") + " --hide 1,2 -o " + out_dir() + "/report_empty");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("tetlod report: note: the pictures are empty"), std::string::npos)
      << r.output;
  const CommandResult shown =
      run("report " + asset("box2.mesh") + " -o " + out_dir() + "/report_shown");
  EXPECT_EQ(shown.output.find("pictures are empty"), std::string::npos) << shown.output;
}

// Coloured by size, every level of a report is on one colour scale (each its own made
// the coarser level look finer), which the page gives; hidden materials are said to
// count in the tables.
TEST(CliReport, SizeColoursShareOneScale) {
  const std::string dir = out_dir() + "/report_size";
  const CommandResult r = run("report " + asset("motor.mesh") + " -o " + dir +
                              " --hide 1 --color size --simplify --size 20 --levels 12000");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string scale = "on one scale for every level, ";
  const size_t at = html.find(scale);
  ASSERT_NE(at, std::string::npos);
  double lo = 0, hi = 0;
  ASSERT_EQ(std::sscanf(html.c_str() + at + scale.size(), "%lf to %lf", &lo, &hi), 2);
  // The input's shortest shown tet and the coarsest level's longest (at most the size).
  EXPECT_GT(lo, 0);
  EXPECT_LT(lo, 7);
  EXPECT_GT(hi, 15);
  EXPECT_LE(hi, 20 + 1e-9);
  EXPECT_NE(html.find("the tables and the stretch histograms count every tet"), std::string::npos);
}

TEST(CliReport, ErrorsAreClear) {
  EXPECT_EQ(run("report --help").code, 0);
  EXPECT_EQ(run("report " + asset("box2.mesh")).code, 2);                        // no -o
  EXPECT_EQ(run("report " + asset("box2.mesh") + " --levels 10 -o x").code, 2);  // no size
  EXPECT_EQ(run("report " + asset("box2.mesh") + " --levels 0 -o x").code, 2);   // bad level
  // The output directory cannot be made under a regular file: found before any work.
  const std::string file = out_dir() + "/plain_file";
  std::ofstream(file) << "x";
  const CommandResult r = run("report " + asset("box2.mesh") + " -o " + file + "/dir");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("plain_file/dir: cannot write: " + file + "/ is not a directory"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace tetlod
