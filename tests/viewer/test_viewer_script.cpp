// The viewer's script parser (no display needed) and the `tetlod view` command
// line: every bad script line is an error naming the script and the line, before
// any window opens.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/viewer_script.h"

namespace tetlod::app {
namespace {

using Kind = ScriptAction::Kind;

std::vector<ScriptAction> parse_ok(const std::string& text) {
  std::vector<ScriptAction> actions;
  const Status s = parse_script_text(text, "t.script", &actions);
  EXPECT_TRUE(s.ok()) << s.message();
  return actions;
}

std::string parse_error(const std::string& text) {
  std::vector<ScriptAction> actions;
  const Status s = parse_script_text(text, "t.script", &actions);
  EXPECT_FALSE(s.ok()) << text;
  return s.message();
}

// hide and show take a material by id or by name (looked up when the line runs).
TEST(ViewerScript, HideAndShowTakeIdsOrNames) {
  const auto a = parse_ok("hide shield\nshow 3\nhide Dielectric_Outer\n");
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[0].kind, Kind::kHide);
  EXPECT_EQ(a[0].word, "shield");
  EXPECT_EQ(a[1].kind, Kind::kShow);
  EXPECT_EQ(a[1].word, "");
  EXPECT_EQ(a[1].count, 3);
  EXPECT_EQ(a[2].word, "Dielectric_Outer");
  // A name is the rest of the line (Gmsh names hold blanks); a number is one word.
  const auto spaced = parse_ok("hide rotor iron\nshow  air   gap \n");
  ASSERT_EQ(spaced.size(), 2u);
  EXPECT_EQ(spaced[0].word, "rotor iron");
  EXPECT_EQ(spaced[1].word, "air gap");
  // Anything but a whole number is a name: one that starts with a digit too.
  const auto digit = parse_ok("hide 2 pole magnet\nshow 1.5\n");
  EXPECT_EQ(digit[0].word, "2 pole magnet");
  EXPECT_EQ(digit[1].word, "1.5");
  EXPECT_EQ(parse_error("hide -2\n"), "t.script:1: '-2' is not a material id (>= 0)");
}

// 'groups' takes the rest of the line (names may hold blanks), looked up when it runs.
TEST(ViewerScript, GroupsTakeTheRestOfTheLine) {
  const auto a = parse_ok("groups all\ngroups none\ngroups port, outer wall,3\n");
  ASSERT_EQ(a.size(), 3u);
  for (const auto& action : a) EXPECT_EQ(action.kind, Kind::kGroups);
  EXPECT_EQ(a[0].word, "all");
  EXPECT_EQ(a[1].word, "none");
  EXPECT_EQ(a[2].word, "port, outer wall,3");
  EXPECT_EQ(parse_error("groups\n"), "t.script:1: 'groups' takes 1 argument(s), got 0");
}

TEST(ViewerScript, ParsesEveryCommand) {
  const auto a = parse_ok(
      "# comment\n"
      "\n"
      "open m.mesh\n"
      "thresholds size=12 stretch=0.15 valence=25 tolerance=0.05 subdivide=0 keep-inside=off "
      "crease-angle=30\n"
      "simplify  # trailing comment\n"
      "scrub elements=5000\n"
      "scrub step=100\n"
      "scrub end\n"
      "cut z=-1.5 flip\n"
      "cut off\n"
      "hide 1\n"
      "show 1\n"
      "color material\n"
      "range 0.1 0.9\n"
      "colormap turbo\n"
      "wireframe on\n"
      "highlight 0.2\n"
      "highlight off\n"
      "view x\n"
      "screenshot a.png ui=1\n"
      "screenshot b.png width=640 height=480\n"
      "save out.vtu\n"
      "wait frames=3\n"
      "bench-scrub frames=50 out=b.csv\n"
      "save better.mesh improve\n"
      "save groups.msh binary surfaces improve\n"
      "quit\n");
  ASSERT_EQ(a.size(), 25u);
  EXPECT_EQ(a[0].kind, Kind::kOpen);
  EXPECT_EQ(a[0].line, 3);
  EXPECT_EQ(a[0].path, "m.mesh");
  EXPECT_EQ(a[1].kind, Kind::kThresholds);
  EXPECT_EQ(*a[1].size, 12);
  EXPECT_EQ(*a[1].stretch, 0.15);
  EXPECT_EQ(*a[1].valence, 25);
  EXPECT_EQ(*a[1].tolerance, 0.05);
  EXPECT_FALSE(*a[1].subdivide);
  EXPECT_FALSE(*a[1].keep_inside);
  EXPECT_EQ(*a[1].crease_angle, 30);
  EXPECT_EQ(a[2].kind, Kind::kSimplify);
  EXPECT_EQ(a[3].kind, Kind::kScrubElements);
  EXPECT_EQ(a[3].count, 5000);
  EXPECT_EQ(a[4].kind, Kind::kScrubStep);
  EXPECT_EQ(a[4].count, 100);
  EXPECT_EQ(a[5].kind, Kind::kScrubEnd);
  EXPECT_EQ(a[6].kind, Kind::kCut);
  EXPECT_EQ(a[6].axis, 2);
  EXPECT_EQ(a[6].value, -1.5);
  EXPECT_TRUE(a[6].flag);
  EXPECT_EQ(a[7].kind, Kind::kCutOff);
  EXPECT_EQ(a[8].kind, Kind::kHide);
  EXPECT_EQ(a[8].count, 1);
  EXPECT_EQ(a[9].kind, Kind::kShow);
  EXPECT_EQ(a[10].word, "material");
  EXPECT_EQ(a[11].value, 0.1);
  EXPECT_EQ(a[11].value2, 0.9);
  EXPECT_EQ(a[12].word, "turbo");
  EXPECT_TRUE(a[13].flag);
  EXPECT_EQ(a[14].value, 0.2);
  EXPECT_EQ(a[15].kind, Kind::kHighlightOff);
  EXPECT_EQ(a[16].word, "x");
  EXPECT_TRUE(a[17].flag);
  EXPECT_EQ(a[17].width, 0);
  EXPECT_FALSE(a[18].flag);
  EXPECT_EQ(a[18].width, 640);
  EXPECT_EQ(a[18].height, 480);
  EXPECT_EQ(a[19].path, "out.vtu");
  EXPECT_EQ(a[20].count, 3);
  EXPECT_EQ(a[21].count, 50);
  EXPECT_EQ(a[21].path, "b.csv");
  EXPECT_EQ(a[19].kind, Kind::kSave);
  EXPECT_FALSE(a[19].flag);
  EXPECT_EQ(a[22].kind, Kind::kSave);
  EXPECT_EQ(a[22].path, "better.mesh");
  EXPECT_TRUE(a[22].flag);
  EXPECT_FALSE(a[22].surfaces);
  EXPECT_FALSE(a[22].binary);
  EXPECT_FALSE(a[19].surfaces);
  EXPECT_EQ(a[23].kind, Kind::kSave);
  EXPECT_TRUE(a[23].flag);
  EXPECT_TRUE(a[23].surfaces);
  EXPECT_TRUE(a[23].binary);
  EXPECT_EQ(a[24].kind, Kind::kQuit);
}

TEST(ViewerScript, CameraMoves) {
  const auto a = parse_ok("orbit 40 -10\npan 5 6\nzoom -2.5\nmouse 100 20.5\n");
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0].kind, Kind::kOrbit);
  EXPECT_EQ(a[0].value, 40);
  EXPECT_EQ(a[0].value2, -10);
  EXPECT_EQ(a[1].kind, Kind::kPan);
  EXPECT_EQ(a[2].kind, Kind::kZoom);
  EXPECT_EQ(a[2].value, -2.5);
  EXPECT_EQ(parse_error("orbit 1\n"), "t.script:1: 'orbit' takes 2 argument(s), got 1");
  EXPECT_EQ(parse_error("save a.msh surfaces surfaces\n"),
            "t.script:1: 'save' takes PATH [improve] [surfaces] [binary]");
  EXPECT_EQ(parse_error("save a.msh boundary\n"),
            "t.script:1: 'save' takes PATH [improve] [surfaces] [binary]");
  EXPECT_EQ(parse_error("save a.msh binary improve surfaces binary\n"),
            "t.script:1: 'save' takes 1 to 4 argument(s), got 5");
  EXPECT_EQ(parse_error("zoom in\n"), "t.script:1: 'clicks' needs a number, got 'in'");
  // The pointer held where a tooltip should show.
  EXPECT_EQ(a[3].kind, Kind::kMouse);
  EXPECT_EQ(a[3].value, 100);
  EXPECT_EQ(a[3].value2, 20.5);
  EXPECT_EQ(parse_error("mouse -1 5\n"),
            "t.script:1: 'mouse' takes pixel coordinates in [0, 16384]");
  EXPECT_EQ(parse_error("mouse 5\n"), "t.script:1: 'mouse' takes 2 argument(s), got 1");
}

// 'wait done' waits for the runs started with wait=0; 'wait frames=N' does not.
TEST(ViewerScript, WaitDone) {
  const auto a = parse_ok("simplify wait=0\nwait done\nwait frames=2\n");
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[1].kind, ScriptAction::Kind::kWait);
  EXPECT_TRUE(a[1].flag);
  EXPECT_EQ(a[2].kind, ScriptAction::Kind::kWait);
  EXPECT_FALSE(a[2].flag);
  EXPECT_EQ(a[2].count, 2);
}

// Waits and frame benchmarks are bounded, and screenshots are PNGs by name too (a
// script waited without end, or wrote PNG data under a .jpg name; found by a
// hostile-input test).
TEST(ViewerScript, WaitsAreBoundedAndScreenshotsArePngs) {
  EXPECT_EQ(parse_ok("wait frames=100000\nbench-frames frames=100000\n").size(), 2u);
  EXPECT_EQ(parse_error("wait frames=99999999999\n"), "t.script:1: frames must be in [0, 100000]");
  EXPECT_EQ(parse_error("bench-frames frames=100001\n"),
            "t.script:1: frames must be in [1, 100000]");
  EXPECT_EQ(parse_error("bench-scrub frames=0\n"), "t.script:1: frames must be in [1, 100000]");
  EXPECT_EQ(parse_error("screenshot out/a.jpg\n"),
            "t.script:1: a screenshot is written as PNG: give a .png name, got 'out/a.jpg'");
  EXPECT_EQ(parse_ok("screenshot A.PNG\n").size(), 1u);
  // The panel's Screenshot is checked alike (it clamped 100000 to 8192, wrote 'noext').
  EXPECT_EQ(screenshot_problem("a.png", 0, 0), "");
  EXPECT_EQ(screenshot_problem("a.png", 16, 8192), "");
  EXPECT_EQ(screenshot_problem("out/noext", 0, 0),
            "a screenshot is written as PNG: give a .png name, got 'out/noext'");
  EXPECT_EQ(screenshot_problem("a.png", 100000, 5),
            "a screenshot's size is 16 to 8192 pixels a side, or 0 x 0 for the view's, not "
            "100000 x 5");
  EXPECT_NE(screenshot_problem("a.png", 0, 500), "");
}

TEST(ViewerScript, MaterialSizesAndRegions) {
  const auto a = parse_ok("thresholds material-sizes=1=40,2=10 region=radial:0,0,0,1,0.5\n");
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(*a[0].material_sizes, "1=40,2=10");
  EXPECT_EQ(*a[0].region, "radial:0,0,0,1,0.5");

  // Names (looked up when the line runs), in quotes where they hold blanks; items
  // may have blanks around them, as typed after a comma.
  const auto named = parse_ok(
      "thresholds \"material-sizes=phase A=12, 3=4,core=1 FR4=2\" size=20\n"
      "hide \"rotor iron\"\n"
      "analysis \"conductor=phase A:1\" ground=boundary # a \"comment\"\n");
  ASSERT_EQ(named.size(), 3u);
  EXPECT_EQ(*named[0].material_sizes, "phase A=12, 3=4,core=1 FR4=2");
  EXPECT_EQ(named[1].word, "rotor iron");
  ASSERT_EQ(named[2].named.size(), 1u);
  EXPECT_EQ(named[2].named[0].name, "phase A");
  EXPECT_EQ(parse_error("hide \"rotor iron\n"), "t.script:1: a '\"' is left open");
  EXPECT_EQ(parse_error("thresholds material-sizes=copper=0\n"),
            "t.script:1: material-sizes: 'copper=0' is not MATERIAL=SIZE (a material id >= 0 "
            "or name, and a size > 0)");

  // Resolved against the mesh's names: the last '=' ends a name; a name the mesh
  // lacks, or a material given twice, is an error naming it.
  const std::vector<MaterialName> names = {{1, "phase A"}, {2, "core=1 FR4"}};
  std::vector<std::pair<int32_t, double>> sizes;
  ASSERT_TRUE(resolve_material_sizes("phase A=12, 3=4,core=1 FR4=2", &names, &sizes).ok());
  EXPECT_EQ(sizes, (std::vector<std::pair<int32_t, double>>{{1, 12}, {2, 2}, {3, 4}}));
  EXPECT_EQ(resolve_material_sizes("phase B=1", &names, &sizes).message(),
            "material-sizes: the mesh has no material named 'phase B' (its names: 1 phase A, 2 "
            "core=1 FR4)");
  EXPECT_EQ(resolve_material_sizes("1=2,phase A=3", &names, &sizes).message(),
            "material-sizes: material 1 is given twice");
}

TEST(ViewerScript, AnalysisSolveAndReport) {
  const auto a = parse_ok(
      "analysis conductor=1:1 ground=4 eps=2:2,3:5\n"
      "analysis conductor=1:1.5,2:-0.5 ground=boundary,3\n"
      "solve\n"
      "color field\n"
      "report-analysis c.txt\n");
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(a[0].kind, Kind::kAnalysis);
  const ElectrostaticsProblem& p = a[0].problem;
  ASSERT_EQ(p.conductors.size(), 1u);
  EXPECT_EQ(p.conductors[0], (std::pair<int32_t, double>{1, 1.0}));
  EXPECT_EQ(p.ground_materials, std::vector<int32_t>{4});
  EXPECT_FALSE(p.ground_boundary);
  ASSERT_EQ(p.permittivities.size(), 2u);
  EXPECT_EQ(p.permittivities[0], (std::pair<int32_t, double>{2, 2.0}));
  EXPECT_EQ(p.permittivities[1], (std::pair<int32_t, double>{3, 5.0}));
  const ElectrostaticsProblem& q = a[1].problem;
  ASSERT_EQ(q.conductors.size(), 2u);
  EXPECT_EQ(q.conductors[1], (std::pair<int32_t, double>{2, -0.5}));
  EXPECT_TRUE(q.ground_boundary);
  EXPECT_EQ(q.ground_materials, std::vector<int32_t>{3});
  EXPECT_TRUE(q.permittivities.empty());
  EXPECT_EQ(a[2].kind, Kind::kSolve);
  EXPECT_EQ(a[3].kind, Kind::kColor);
  EXPECT_EQ(a[3].word, "field");
  EXPECT_EQ(a[4].kind, Kind::kReportAnalysis);
  EXPECT_EQ(a[4].path, "c.txt");

  // Only the syntax is the parser's: a physically bad set-up (eps <= 0, a conductor
  // that is also ground) parses, and fails at 'solve' with the solver's message.
  const auto bad = parse_ok("analysis conductor=1:1 ground=1 eps=2:-3\n");
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_EQ(bad[0].problem.permittivities[0].second, -3.0);

  EXPECT_EQ(parse_error("quit\nanalysis ground=4\n"), "t.script:2: 'analysis' needs conductor=M:V");
  EXPECT_EQ(parse_error("analysis conductor=1:1\n"),
            "t.script:1: 'analysis' needs ground=boundary|M[,...] (or conductors at two "
            "potentials)");
  EXPECT_EQ(parse_error("analysis conductor=1:1,2:1\n"),
            "t.script:1: 'analysis' needs ground=boundary|M[,...] (or conductors at two "
            "potentials)");
  EXPECT_EQ(parse_error("analysis conductor=1=1 ground=4\n"),
            "t.script:1: 'conductor': '1=1' is not MATERIAL:NUMBER (a material id >= 0 or name, "
            "and a finite number)");
  EXPECT_EQ(parse_error("analysis conductor=1:1 ground=4 eps=2:nan\n"),
            "t.script:1: 'eps': '2:nan' is not MATERIAL:NUMBER (a material id >= 0 or name, and a "
            "finite number)");
  EXPECT_EQ(parse_error("analysis conductor=-1:1 ground=4\n"),
            "t.script:1: 'conductor': '-1:1' is not MATERIAL:NUMBER (a material id >= 0 or name, "
            "and a finite number)");
  EXPECT_EQ(parse_error("analysis conductor=1:1 ground=-4\n"),
            "t.script:1: 'ground': '-4' is neither 'boundary' nor a material id or name");
  // Materials by name (resolved when the line runs), as the CLI takes them; no ground
  // where the conductors hold two potentials, as `tetlod solve`.
  const auto named = parse_ok(
      "analysis conductor=inner:1,2:0 eps=dielectric:2.5\n"
      "analysis conductor=1:1 ground=shield,boundary\n");
  ASSERT_EQ(named.size(), 2u);
  ASSERT_EQ(named[0].problem.conductors.size(), 1u);
  EXPECT_EQ(named[0].problem.conductors[0], (std::pair<int32_t, double>{2, 0.0}));
  ASSERT_EQ(named[0].named.size(), 2u);
  EXPECT_EQ(named[0].named[0].key, "conductor");
  EXPECT_EQ(named[0].named[0].name, "inner");
  EXPECT_EQ(named[0].named[0].value, 1.0);
  EXPECT_EQ(named[0].named[1].key, "eps");
  EXPECT_EQ(named[0].named[1].name, "dielectric");
  EXPECT_EQ(named[0].named[1].value, 2.5);
  ASSERT_EQ(named[1].named.size(), 1u);
  EXPECT_EQ(named[1].named[0].key, "ground");
  EXPECT_EQ(named[1].named[0].name, "shield");
  EXPECT_TRUE(named[1].problem.ground_boundary);
  // An empty item (a trailing comma) is named as such.
  EXPECT_EQ(parse_error("analysis conductor=1:1 ground=4,\n"),
            "t.script:1: 'ground=4,': an empty item (a comma at either end, or two in a row)");
  EXPECT_EQ(parse_error("analysis conductor=1:1, ground=4\n"),
            "t.script:1: 'conductor=1:1,': an empty item (a comma at either end, or two in a "
            "row)");
  EXPECT_EQ(parse_error("analysis conductor=1:1 ground=4 mu=2:1\n"),
            "t.script:1: unknown analysis key 'mu' (conductor, ground, eps)");
  EXPECT_EQ(parse_error("solve now\n"),
            "t.script:1: 'solve' takes may-fail and wait=0|1, got 'now'");
  EXPECT_EQ(parse_error("solve wait=maybe\n"),
            "t.script:1: 'wait' needs on/off (or 1/0), got 'maybe'");
  EXPECT_EQ(parse_error("solve may-fail wait=0 x\n"),
            "t.script:1: 'solve' takes 0 to 2 argument(s), got 3");
  const auto options = parse_ok("solve may-fail\nsolve wait=0\n");
  ASSERT_EQ(options.size(), 2u);
  EXPECT_TRUE(options[0].flag);
  EXPECT_EQ(options[0].count, 1);
  EXPECT_FALSE(options[1].flag);
  EXPECT_EQ(options[1].count, 0);
  EXPECT_FALSE(a[2].flag);
  EXPECT_EQ(a[2].count, 1);
  EXPECT_EQ(parse_error("report-analysis\n"),
            "t.script:1: 'report-analysis' takes 1 argument(s), got 0");
  const auto range = parse_ok("field-range max\nfield-range 99.5\n");
  ASSERT_EQ(range.size(), 2u);
  EXPECT_EQ(range[0].kind, Kind::kFieldRange);
  EXPECT_EQ(range[0].value, 100);
  EXPECT_EQ(range[1].value, 99.5);
  EXPECT_EQ(parse_error("field-range 0\n"),
            "t.script:1: the percentile must be in (0, 100], got '0'");
  EXPECT_EQ(parse_error("field-range 101\n"),
            "t.script:1: the percentile must be in (0, 100], got '101'");
  EXPECT_EQ(parse_error("field-range\n"), "t.script:1: 'field-range' takes 1 argument(s), got 0");
  EXPECT_EQ(parse_error("color e\n"),
            "t.script:1: 'color' takes stretch, material, field or size, got 'e'");
}

TEST(ViewerScript, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(parse_error("quit\nfrobnicate\n"), "t.script:2: unknown command 'frobnicate'");
  EXPECT_EQ(parse_error("\n\nthresholds size=abc\n"),
            "t.script:3: 'size' needs a number, got 'abc'");
  // A list as --hide takes: one a line here (it said 'material' needs a whole number).
  EXPECT_EQ(parse_error("hide 1,2\n"), "t.script:1: 'hide' takes one material a line, got '1,2'");
  EXPECT_EQ(parse_error("thresholds size=1 stretch=0.2 size=2\n"),
            "t.script:1: 'size' is given twice");
  // A NUL would cut a path where it is opened ("a.mesh\0.vtk" saved .vtk text as a.mesh).
  EXPECT_EQ(parse_error(std::string("quit\nsave a.mesh\0.vtk\n", 22)), "t.script:2: a NUL byte");
  EXPECT_EQ(parse_error("thresholds region=sphere:1\n"),
            "t.script:1: region: unknown rule 'sphere:1' (expected radial:..., axis:... or "
            "box:...)");
  // A byte-order mark before the first command is no part of it.
  EXPECT_EQ(parse_ok("\xef\xbb\xbfquit\n").size(), 1u);
}

// An endless file is refused after 16 MiB; /dev/null is an empty script.
TEST(ViewerScript, AnEndlessFileIsNotAScript) {
  std::vector<ScriptAction> actions;
  const Status s = parse_script("/dev/zero", &actions);
  EXPECT_EQ(s.message(), "/dev/zero: more than 16 MiB: not a script");
  EXPECT_TRUE(parse_script("/dev/null", &actions).ok());
  EXPECT_EQ(parse_script("/nonexistent/s.script", &actions).message(),
            "/nonexistent/s.script: cannot open the script");
}

TEST(ViewerScript, RejectsBadValues) {
  // Below the least stretch, tets too flat to read back would pass (core/simplify.h).
  EXPECT_EQ(parse_error("thresholds stretch=0.0001\n"),
            "t.script:1: stretch=0.0001 must be in [0.00012, 1) (below, tets too flat to read "
            "back would pass)");
  parse_ok("thresholds stretch=0.00012\n");
  for (const char* bad : {
           "thresholds\n",
           "thresholds size=0\n",
           "thresholds size=-1\n",
           "thresholds stretch=1\n",
           "thresholds stretch=0\n",
           "thresholds valence=3\n",
           "thresholds valence=2.5\n",
           "thresholds tolerance=-1\n",
           "thresholds tolerance=nan\n",
           "thresholds subdivide=maybe\n",
           "thresholds keep-inside=2\n",
           "thresholds crease-angle=0\n",
           "thresholds crease-angle=180\n",
           "thresholds colour=1\n",
           "thresholds size\n",
           "thresholds material-sizes=1=0\n",
           "thresholds region=sphere:1\n",
           "simplify now\n",
           "scrub\n",
           "scrub elements=-3\n",
           "scrub elements=0\n",  // (as --elements 0)
           "scrub elements=many\n",
           "scrub frame=3\n",
           "cut w=0\n",
           "cut z=abc\n",
           "cut z=0 flop\n",
           "cut off now\n",
           "hide\n",
           "color blue\n",
           "colormap jet\n",
           "range 1 0\n",
           "range 0\n",
           "wireframe maybe\n",
           "highlight lots\n",
           "highlight 2\n",  // (as --highlight-below 2)
           "highlight 0\n",
           "view top\n",
           "screenshot\n",
           "screenshot a.png ui=2\n",
           "screenshot a.png width=100\n",
           "screenshot a.png width=10 height=10\n",
           "screenshot a.png ui=1 width=100 height=100\n",
           "screenshot a.png dpi=3\n",
           "save\n",
           "save a b\n",
           "save a improve now\n",
           "wait\n",
           "wait frames=-1\n",
           "wait seconds=-1\n",
           "wait minutes=1\n",
           "wait done now\n",
           "wait until=done\n",
           "bench-scrub frames=0\n",
           "bench-scrub speed=2\n",
           "quit now\n",
       }) {
    const std::string message = parse_error(bad);
    EXPECT_EQ(message.rfind("t.script:1: ", 0), 0u) << bad << " -> " << message;
  }
}

// The command line: a bad script is reported before any window opens, so this
// needs no display.
int run(const std::string& arguments, std::string* output, const std::string& prefix = "") {
  const std::filesystem::path dir = std::filesystem::path(TETLOD_TEST_OUTPUT_DIR) / "viewer_cli";
  std::filesystem::create_directories(dir);
  // One log per test: ctest runs the tests of this file in parallel processes.
  const std::string log =
      (dir / (std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + ".txt"))
          .string();
  const int status =
      std::system((prefix + TETLOD_BINARY + " " + arguments + " >" + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  *output = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ViewerCli, BadScriptIsAnErrorNamingTheLine) {
  const std::filesystem::path dir = std::filesystem::path(TETLOD_TEST_OUTPUT_DIR) / "viewer_cli";
  std::filesystem::create_directories(dir);
  const std::string script = (dir / "bad.script").string();
  std::ofstream(script) << "thresholds size=10\nscrub elements=lots\nquit\n";
  std::string output;
  EXPECT_EQ(run("view --script " + script, &output), 1);
  EXPECT_NE(output.find(script + ":2: 'elements' needs a whole number"), std::string::npos)
      << output;
  EXPECT_EQ(run("view --script /nonexistent/x.script", &output), 1);
  EXPECT_NE(output.find("cannot open the script"), std::string::npos) << output;
}

TEST(ViewerCli, BadOptionsAreUsageErrors) {
  std::string output;
  EXPECT_EQ(run("view --size 12", &output), 2);
  EXPECT_EQ(run("view --frobnicate", &output), 2);
  EXPECT_EQ(run("view a.mesh b.mesh", &output), 2);
  EXPECT_EQ(run("view --interactive-scale 2", &output), 2);
  EXPECT_EQ(run("view --help", &output), 0);
  EXPECT_NE(output.find("--script"), std::string::npos);
}

TEST(ViewerCli, NoDisplayIsAMessage) {
  std::string output;
  EXPECT_EQ(run("view " + std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh --script /dev/null",
                &output, "env -u DISPLAY -u WAYLAND_DISPLAY "),
            1);
  EXPECT_NE(output.find("the viewer needs a display"), std::string::npos) << output;
}

}  // namespace
}  // namespace tetlod::app
