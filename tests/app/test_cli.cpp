// The real `tetlod` binary: exit codes, messages, and the simplify -> lod flow.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "app/cli_runner.h"
#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/metrics.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

namespace fs = std::filesystem;

using test::CommandResult;

CommandResult run(const std::string& arguments, const std::string& environment = "") {
  return test::run_tetlod(arguments, environment);
}

std::string out_dir() {
  return test::cli_output_dir("cli");
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string write_grid(const std::string& name) {
  const TetMesh mesh = test::make_grid_mesh(
      4, 2, 2, [](int i, int, int) { return i < 2 ? 1 : 2; }, 0.5);
  const std::string path = out_dir() + "/" + name;
  const Status s = write_mesh(path, mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return path;
}

TEST(Cli, UsageAndExitCodes) {
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("--help").code, 0);
  const CommandResult version = run("--version");
  EXPECT_EQ(version.code, 0);
  EXPECT_EQ(version.output.rfind(std::string("tetlod ") + TETLOD_VERSION + "\n", 0), 0u)
      << version.output;
  const CommandResult unknown = run("frobnicate");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.output.find("unknown command"), std::string::npos);
  for (const char* command : {"stats", "convert", "generate", "simplify", "lod"}) {
    const CommandResult help = run(std::string(command) + " --help");
    EXPECT_EQ(help.code, 0) << command;
    EXPECT_NE(help.output.find("usage: tetlod"), std::string::npos) << command;
  }
  EXPECT_EQ(run("stats").code, 2);
  EXPECT_EQ(run("stats a.mesh --bogus").code, 2);
}

// generate: options that would be ignored or read loosely are usage errors, checked
// before TetGen runs.
// A name two materials share names neither (Nastran comments can give it twice): an
// option that takes it is a usage error naming both; each id still works.
TEST(Cli, ANameTwoMaterialsShareIsAnError) {
  const std::string dir = test::cli_output_dir("shared_name");
  const TetMesh grid = test::make_grid_mesh(
      3, 1, 1, [](int i, int, int) { return i + 1; }, 0.5);
  const std::vector<MaterialName> names = {{1, "copper"}, {2, "copper"}, {3, "air"}};
  WriteOptions options;
  options.material_names = &names;
  const std::string path = dir + "/shared.bdf";
  ASSERT_TRUE(write_mesh(path, grid, options).ok());
  CommandResult r = run("simplify " + path + " -o " + dir + "/s.mesh --material-size copper=1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("the mesh names materials 1 and 2 'copper': give the number"),
            std::string::npos)
      << r.output;
  r = run("simplify " + path + " -o " + dir + "/s.mesh --material-size 2=1,air=1");
  EXPECT_EQ(r.code, 0) << r.output;
}

// A region rule that sets no tet's size is said (a box in metres for a model in
// millimetres): a box that holds no tet's centroid, a radial rule nowhere below --size.
// Rules that reach the mesh are not.
TEST(Cli, RegionRulesThatSetNoSizeAreSaid) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const test::CommandResult unused = test::run_tetlod(
      "stats '" + motor +
      "' --size 20 --size-field 'radial:0,0,0,30,0.1;box:0.001,0.001,0.001,0.002,0.002,0.002,1'");
  ASSERT_EQ(unused.code, 0) << unused.output;
  EXPECT_NE(unused.output.find("note: --size-field box (0.001, 0.001, 0.001) to (0.002, 0.002, "
                               "0.002) holds no tet's centroid (the mesh spans (-60, -60, -30) "
                               "to (60, 60, 30)): it sets no size"),
            std::string::npos)
      << unused.output;
  EXPECT_NE(unused.output.find("note: --size-field radial rule around (0, 0, 0) gives no size "
                               "below --size 20 on the mesh (at least 30 there"),
            std::string::npos)
      << unused.output;
  // An axis rule nowhere below --size (the line far off, or its least size above it), and
  // a box whose size is not below it (a re-check tester's cases).
  const test::CommandResult more = test::run_tetlod(
      "stats '" + motor +
      "' --size 20 --size-field "
      "'axis:1000,0,0,0,0,1,1,0.1;axis:0,0,0,0,0,1,25,0.1;box:-10,-10,-10,10,10,10,30'");
  ASSERT_EQ(more.code, 0) << more.output;
  EXPECT_NE(more.output.find("note: --size-field axis rule along the line through (1000, 0, 0) "
                             "gives no size below --size 20"),
            std::string::npos)
      << more.output;
  EXPECT_NE(more.output.find("note: --size-field axis rule along the line through (0, 0, 0) "
                             "gives no size below --size 20 on the mesh (at least 25 there"),
            std::string::npos)
      << more.output;
  EXPECT_NE(more.output.find("note: --size-field box (-10, -10, -10) to (10, 10, 10) gives size "
                             "30, not below --size 20: it sets no size"),
            std::string::npos)
      << more.output;
  const test::CommandResult used =
      test::run_tetlod("stats '" + motor +
                       "' --size 20 --size-field 'radial:0,0,0,3,0.1;box:-10,-10,-10,10,10,10,5'");
  ASSERT_EQ(used.code, 0) << used.output;
  EXPECT_EQ(used.output.find("--size-field"), std::string::npos) << used.output;
}

// Surface groups kept inside a material (--surfaces or --history) can keep the run past
// the valence from being taken: nodes on the sheets went past it and no edge removal
// or collapse may bring them back (tests/data/gmsh/sheet.msh at size 0.2: 2,203 tets
// stay above the size; not keeping the sheets, none). The output says so.
TEST(Cli, SimplifySaysKeptSheetsCanStopTheRunPastTheValence) {
  const std::string dir = test::cli_output_dir("kept_sheets");
  const std::string sheet = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/sheet.msh";
  const test::CommandResult kept =
      test::run_tetlod("simplify '" + sheet + "' -o " + dir + "/k.msh --size 0.2 --surfaces");
  ASSERT_EQ(kept.code, 0) << kept.output;
  EXPECT_NE(kept.output.find("was given up"), std::string::npos) << kept.output;
  EXPECT_NE(kept.output.find("(the input's surface groups inside a material are kept as they "
                             "are (76 faces), which can leave nodes next to them"),
            std::string::npos)
      << kept.output;
  const test::CommandResult dropped =
      test::run_tetlod("simplify '" + sheet + "' -o " + dir + "/d.msh --size 0.2");
  ASSERT_EQ(dropped.code, 0) << dropped.output;
  EXPECT_NE(dropped.output.find("final mesh, breaking a threshold: 0 tets below the stretch, 0 "
                                "above the size"),
            std::string::npos)
      << dropped.output;
  EXPECT_EQ(dropped.output.find("inside a material are kept"), std::string::npos) << dropped.output;
}

// A tolerance that shrinks a surface group is said too, with its change: the round port
// on the block's top (tests/data/gmsh/port.msh) at tolerance 0.2 loses a quarter of its
// area, as the border's vertices move along the face (its volume does not change); at
// 0.001 it keeps it within 1 %.
TEST(Cli, SimplifySaysWhichSurfaceGroupsChangedArea) {
  const std::string dir = test::cli_output_dir("area_note");
  const std::string port = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/port.msh";
  const test::CommandResult coarse =
      test::run_tetlod("simplify '" + port + "' -o " + dir + "/p.msh --size 2 --tolerance 0.2");
  ASSERT_EQ(coarse.code, 0) << coarse.output;
  EXPECT_NE(coarse.output.find("note: surface groups' areas changed by more than 1 %: 'port' -26.9 "
                               "%; the tolerance (0.2)"),
            std::string::npos)
      << coarse.output;
  EXPECT_EQ(coarse.output.find("volumes changed"), std::string::npos) << coarse.output;
  const test::CommandResult fine =
      test::run_tetlod("simplify '" + port + "' -o " + dir + "/p.msh --size 2 --tolerance 0.001");
  ASSERT_EQ(fine.code, 0) << fine.output;
  EXPECT_EQ(fine.output.find("areas changed"), std::string::npos) << fine.output;
}

// A tolerance that thins a part is said, with each material's change: the motor at
// tolerance 3 changes its shaft (material 3) by -15.9 %; at the default (0.18) none by 1 %.
// And before the run, which parts are thin for the tolerance.
TEST(Cli, SimplifySaysWhichMaterialsChangedVolume) {
  const std::string dir = test::cli_output_dir("volume_note");
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const test::CommandResult coarse =
      test::run_tetlod("simplify '" + motor + "' -o " + dir + "/t3.mesh --size 30 --tolerance 3");
  ASSERT_EQ(coarse.code, 0) << coarse.output;
  EXPECT_NE(coarse.output.find("note: volumes changed by more than 1 %: material 2 +9.6 %, "
                               "material 3 -15.9 %"),
            std::string::npos)
      << coarse.output;
  EXPECT_NE(coarse.output.find("a smaller --tolerance keeps it"), std::string::npos);
  // Before the run: the parts a few tolerances thick (the shaft, 2 x volume / area
  // 5.13, is one; the air, 12.8, is not).
  EXPECT_NE(coarse.output.find("note: thin for the tolerance (3): material 2 about 1.62 thick, "
                               "material 3 about 5.13 thick"),
            std::string::npos)
      << coarse.output;
  EXPECT_EQ(coarse.output.find("material 1 about"), std::string::npos) << coarse.output;
  const test::CommandResult fine =
      test::run_tetlod("simplify '" + motor + "' -o " + dir + "/t.mesh --size 30");
  ASSERT_EQ(fine.code, 0) << fine.output;
  EXPECT_EQ(fine.output.find("volumes changed"), std::string::npos) << fine.output;
  EXPECT_EQ(fine.output.find("thin for the tolerance"), std::string::npos) << fine.output;
}

TEST(Cli, GenerateRefusesWhatItWouldIgnore) {
  const std::string out = out_dir() + "/generated.mesh";
  fs::remove(out);
  const struct {
    const char* arguments;
    const char* message;
  } cases[] = {
      {"box2 --sphere-level 3 -o ", "--sphere-level applies to the spheres model only"},
      {"box2 --tets 1e3 -o ", "--tets must be a whole number"},
      {"box2 -o x.stl", "-o x.stl: unknown mesh file extension '.stl'"},
  };
  for (const auto& c : cases) {
    const std::string arguments = c.arguments;
    const CommandResult r =
        run("generate " + arguments + (arguments.back() == ' ' ? out : std::string()));
    EXPECT_EQ(r.code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
  // A bad value is named, without the whole usage; a line of the wrong shape gets it.
  CommandResult r = run("generate box2 --tets -5 -o " + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("(see 'tetlod generate --help')"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("usage: tetlod generate"), std::string::npos) << r.output;
  r = run("generate box2 --bogus -o " + out);
  EXPECT_NE(r.output.find("usage: tetlod generate"), std::string::npos) << r.output;
}

TEST(Cli, StatsPrintsTableOneAndJson) {
  const std::string path = write_grid("grid.mesh");
  const CommandResult text = run("stats " + path);
  ASSERT_EQ(text.code, 0) << text.output;
  EXPECT_NE(text.output.find("whole mesh"), std::string::npos);
  EXPECT_NE(text.output.find("material 2"), std::string::npos);
  EXPECT_NE(text.output.find("stretch histogram"), std::string::npos);
  const CommandResult json = run("stats --json " + path);
  ASSERT_EQ(json.code, 0) << json.output;
  EXPECT_NE(json.output.find("\"elements\": 96"), std::string::npos) << json.output;
  EXPECT_NE(json.output.find("\"nodes\": 45"), std::string::npos);
  EXPECT_NE(json.output.find("\"1|2\": 8"), std::string::npos);
  EXPECT_NE(json.output.find("\"surface_groups\": []"), std::string::npos) << json.output;
  // A name that is not UTF-8 (Latin-1 "caf\xe9", from a Nastran comment): the JSON must
  // be UTF-8 (the byte went out as it was).
  const TetMesh grid = test::make_grid_mesh(
      2, 1, 1, [](int i, int, int) { return i + 1; }, 0.5);
  const std::vector<MaterialName> names = {{1, "caf\xe9"}};
  WriteOptions options;
  options.material_names = &names;
  const std::string latin = out_dir() + "/latin1.bdf";
  ASSERT_TRUE(write_mesh(latin, grid, options).ok());
  const CommandResult named = run("stats --json " + latin);
  ASSERT_EQ(named.code, 0) << named.output;
  // (The reader makes every name UTF-8: the byte is '?', as in the other formats.)
  EXPECT_NE(named.output.find("\"caf?\""), std::string::npos) << named.output;
  EXPECT_EQ(named.output.find("caf\xe9"), std::string::npos) << named.output;
}

// Runs `command` through the shell: its exit status (-1 if it did not exit), and what
// it wrote to the shell's standard output in `output`.
int shell(const std::string& command, std::string* output) {
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output->append(buffer, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Standard output that cannot be written (a full disk, a closed descriptor) is an
// error, not a success with nothing written (found by a hostile-input test).
TEST(Cli, AStandardOutputThatCannotBeWrittenIsAnError) {
  const std::string path = write_grid("grid_full.mesh");
  struct Case {
    std::string arguments, to, says;
  };
  const Case cases[] = {{"stats --json " + path, "> /dev/full", "tetlod stats: cannot write"},
                        {"stats --json " + path, ">&-", "tetlod stats: cannot write"},
                        // The help too (it exited 0).
                        {"--help", "> /dev/full", "tetlod --help: cannot write"}};
  for (const Case& c : cases) {
    // stderr to the pipe, stdout where asked.
    const std::string command = std::string(TETLOD_BINARY) + " " + c.arguments + " 2>&1 " + c.to;
    std::string output;
    EXPECT_EQ(shell(command, &output), 1) << command << "\n" << output;
    EXPECT_NE(output.find(c.says + " to standard output"), std::string::npos) << command << "\n"
                                                                              << output;
  }
}

// The thresholds line shows a stretch as given where %g would show another number
// (0.9999999 read "stretch 1", which --stretch refuses; a hostile-input test).
TEST(Cli, TheThresholdsLineShowsTheStretchGiven) {
  const std::string box2 = std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh";
  const std::string out = out_dir() + "/stretch.mesh";
  const CommandResult near_one =
      run("simplify " + box2 + " -o " + out + " --size 1 --stretch 0.9999999");
  ASSERT_EQ(near_one.code, 0) << near_one.output;
  EXPECT_NE(near_one.output.find("thresholds: size 1, stretch 0.9999999, valence 25"),
            std::string::npos)
      << near_one.output;
  const CommandResult usual = run("simplify " + box2 + " -o " + out + " --size 1 --stretch 0.15");
  EXPECT_NE(usual.output.find("thresholds: size 1, stretch 0.15, valence 25"), std::string::npos)
      << usual.output;
}

// A pipe closed early (tetlod stats | head) is such an error too, exit 1 with the
// message, not a SIGPIPE that killed the process silently (exit 141; found by a
// hostile-input test): a mesh of 1,728 materials, whose table outgrows the pipe's buffer.
TEST(Cli, APipeClosedEarlyIsAnError) {
  const TetMesh mesh = test::make_grid_mesh(
      12, 12, 12, [](int i, int j, int k) { return 1 + i + 12 * j + 144 * k; }, 1.0);
  const std::string path = out_dir() + "/many_materials.mesh";
  ASSERT_TRUE(write_mesh(path, mesh).ok());
  const std::string command = "bash -c '{ " + std::string(TETLOD_BINARY) + " stats " + path +
                              " | head -c 10 > /dev/null; exit ${PIPESTATUS[0]}; } 2>&1'";
  std::string output;
  EXPECT_EQ(shell(command, &output), 1) << command << "\n" << output;
  EXPECT_NE(output.find("tetlod stats: cannot write to standard output: Broken pipe"),
            std::string::npos)
      << output;
}

// Running out of memory is an error that says so, with no output file, not an abort
// (std::bad_alloc ended the process; found by a hostile-input test): box2 at a size
// that subdivides it into millions of tets, in 200 MB of address space.
TEST(Cli, OutOfMemoryIsAnErrorThatSaysSo) {
  const std::string out = out_dir() + "/oom.mesh";
  std::filesystem::remove(out);
  for (const char* threads : {" --one-thread", ""}) {
    const CommandResult r = run("simplify " + std::string(TETLOD_SOURCE_DIR) +
                                    "/assets/box2.mesh -o " + out + " --size 0.023" + threads,
                                "ulimit -v 200000;");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("tetlod simplify: out of memory"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

// The file's own surface groups as --surfaces writes them (a partitioned Gmsh file's),
// and a note for a group that is not on the surface.
TEST(Cli, StatsListsTheFilesSurfaceGroups) {
  const std::string coax = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax_part3.msh";
  CommandResult r = run("stats " + coax);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("the file's surface groups (tag name: triangles on the surface): 20 "
                          "ends: 246, 21 jacket: 180\n"),
            std::string::npos)
      << r.output;
  r = run("stats --json " + coax);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(
      r.output.find(
          "{\"tag\": 21, \"name\": \"jacket\", \"written_as\": \"jacket\", \"triangles\": 180, "
          "\"in_a_smaller_group\": 0, \"inside_a_material\": 0, \"not_faces\": 0}"),
      std::string::npos)
      << r.output;
  // A Medit triangle inside the grid that is no face of it is noted; its group has
  // none on the surface.
  const std::string path = write_grid("inner_triangle.mesh");
  std::string text = read_file(path);
  const size_t end = text.rfind("End");
  ASSERT_NE(end, std::string::npos);
  text.insert(end, "Triangles\n1\n22 23 27 9\n");  // 22: an inner vertex
  std::ofstream(path) << text;
  r = run("stats " + path);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("tetlod stats: note: no triangle of surface group with tag 9 (unnamed) "
                          "is a face of the mesh: not written\n"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the file's surface groups (tag name: triangles on the surface): 9 "
                          "(unnamed): 0\n"),
            std::string::npos)
      << r.output;
}

// Surface groups inside one material (tests/data/gmsh/sheet.msh: 'sheet' inside the
// block, 'top_and_sheet' its top face and another sheet): stats counts them; convert
// and simplify (with --improve too) write them (the file read back has them, inside
// again); subdivision says which long edges it left for them.
TEST(Cli, GroupsInsideAMaterialAreKept) {
  const std::string sheet = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/sheet.msh";
  CommandResult r = run("stats " + sheet);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("the file's surface groups (tag name: triangles on the surface): 100 "
                          "sheet: 0 (+38 inside a material), 200 bottom: 112, 300 top_and_sheet: "
                          "112 (+38 inside a material)\n"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("note: every triangle of surface group 'sheet'"), std::string::npos)
      << r.output;
  r = run("stats --json " + sheet);
  EXPECT_NE(
      r.output.find("{\"tag\": 300, \"name\": \"top_and_sheet\", \"written_as\": "
                    "\"top_and_sheet\", \"triangles\": 112, "
                    "\"in_a_smaller_group\": 0, \"inside_a_material\": 38, \"not_faces\": 0}"),
      std::string::npos)
      << r.output;

  const std::string converted = out_dir() + "/sheet_converted.msh";
  r = run("convert " + sheet + " " + converted + " --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("surface groups (tag name: triangles): 2 boundary_1: 358, 200 bottom: "
                          "112, 300 top_and_sheet: 150, 100 sheet: 38\n"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("inside one material"), std::string::npos) << r.output;
  r = run("stats " + converted);
  EXPECT_NE(r.output.find("100 sheet: 0 (+38 inside a material), 200 bottom: 112, 300 "
                          "top_and_sheet: 112 (+38 inside a material)\n"),
            std::string::npos)
      << r.output;

  const std::string simplified = out_dir() + "/sheet_simplified.msh";
  r = run("simplify " + sheet + " -o " + simplified + " --size 0.5 --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("inside one material"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(", 100 sheet: 38\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tetlod simplify: note: the surface groups inside a material ('sheet', "
                          "'top_and_sheet'; 76 triangles) are kept as they are: the mesh is not "
                          "coarsened on them (without --surfaces and --history it is)\n"),
            std::string::npos)
      << r.output;
  // Without --surfaces (and --history) nothing keeps them: the mesh coarsens there too.
  TetMesh kept, free;
  ASSERT_TRUE(read_mesh(simplified, &kept).ok());
  const std::string plain = out_dir() + "/sheet_simplified_plain.msh";
  r = run("simplify " + sheet + " -o " + plain + " --size 0.5");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("kept as they are"), std::string::npos) << r.output;
  ASSERT_TRUE(read_mesh(plain, &free).ok());
  EXPECT_LT(free.tet_count(), kept.tet_count());
  r = run("stats " + simplified);
  EXPECT_NE(r.output.find(", 100 sheet: 0 (+38 inside a material), "), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" top_and_sheet: "), std::string::npos) << r.output;

  // At a size whose half is below the sheets' edges, subdivision says it left those.
  r = run("simplify " + sheet + " -o " + simplified + " --size 0.3 --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(" edges of surface groups inside a material, which are kept as they "
                          "are), "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(", 100 sheet: 38\n"), std::string::npos) << r.output;

  // --improve keeps them too.
  const std::string improved = out_dir() + "/sheet_improved.msh";
  r = run("simplify " + sheet + " -o " + improved + " --size 0.5 --surfaces --improve");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("inside one material"), std::string::npos) << r.output;
  r = run("stats " + improved);
  EXPECT_NE(r.output.find(", 100 sheet: 0 (+38 inside a material), "), std::string::npos)
      << r.output;
}

TEST(Cli, BadInputNamesTheFileAndExitsOne) {
  const CommandResult missing = run("stats " + out_dir() + "/does-not-exist.mesh");
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.output.find("does-not-exist.mesh"), std::string::npos);
  const std::string bad = out_dir() + "/bad.mesh";
  std::ofstream(bad) << "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n1 nan 0 0\n";
  const CommandResult r = run("stats " + bad);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("bad.mesh:"), std::string::npos) << r.output;
}

// What a reader notes (here: no cell array of a .vtu read as the material) is printed
// with the file's name, and the command goes on.
TEST(Cli, ReadNotesArePrinted) {
  const std::string path = out_dir() + "/no_material.vtu";
  std::ofstream(path)
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\"><UnstructuredGrid>\n"
         "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\"><Points>\n"
         "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
         "0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points><Cells>\n"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>\n"
         "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4</DataArray>\n"
         "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray>\n"
         "</Cells><CellData><DataArray type=\"Int32\" Name=\"zone\" format=\"ascii\">3"
         "</DataArray></CellData></Piece></UnstructuredGrid></VTKFile>\n";
  const CommandResult r = run("stats " + path);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("tetlod: " + path +
                          ": note: no cell array is read as the material, so every tet is "
                          "material 0 (the file's cell arrays: 'zone';"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("material 0"), std::string::npos) << r.output;
}

TEST(Cli, ConvertKeepsCountsAcrossFormats) {
  const std::string path = write_grid("conv.mesh");
  for (const char* ext : {"msh", "vtu", "vtk", "node", "mesh", "meshb", "bdf", "nas", "inp"}) {
    const std::string target = out_dir() + "/conv_out." + ext;
    const CommandResult c = run("convert " + path + " " + target);
    ASSERT_EQ(c.code, 0) << c.output;
    const CommandResult s = run("stats --json " + target);
    ASSERT_EQ(s.code, 0) << s.output;
    EXPECT_NE(s.output.find("\"elements\": 96"), std::string::npos) << ext;
  }
  // A binary flag for another format is an error, not ignored (found by a user test).
  const std::string none = out_dir() + "/conv_none.mesh";
  const CommandResult msh = run("convert " + path + " " + none + " --msh-binary");
  EXPECT_EQ(msh.code, 2) << msh.output;
  EXPECT_NE(msh.output.find("--msh-binary: " + none + " is not a .msh file"), std::string::npos)
      << msh.output;
  EXPECT_EQ(run("convert " + path + " " + none + " --vtk-binary").code, 2);
  EXPECT_FALSE(fs::exists(none));
}

// The materials' names of a Gmsh input (its physical volumes) are in what convert and
// simplify write; convert also takes its output as -o OUT, once.
TEST(Cli, ConvertAndSimplifyKeepMaterialNames) {
  const std::string input = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax_order2.msh";
  const std::string names =
      "$PhysicalNames\n4\n3 1 \"inner_conductor\"\n3 2 \"dielectric_inner\"\n"
      "3 3 \"dielectric_outer\"\n3 4 \"shield\"\n$EndPhysicalNames\n";
  const std::string converted = out_dir() + "/named.msh";
  CommandResult r = run("convert " + input + " -o " + converted);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(read_file(converted).find(names), std::string::npos);
  const std::string deck = out_dir() + "/named.inp";
  r = run("convert " + converted + " " + deck);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(read_file(deck).find("*ELEMENT, TYPE=C3D4, ELSET=shield_4\n"), std::string::npos);
  const std::string simplified = out_dir() + "/named_simplified.msh";
  const std::string history = out_dir() + "/named.tlh";
  r = run("simplify " + input + " -o " + simplified + " --size 2 --tolerance 0.01 --history " +
          history);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(read_file(simplified).find(names), std::string::npos);
  EXPECT_NE(r.output.find("volume  name\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("46.9738  shield\n"), std::string::npos) << r.output;  // the input
  // The history keeps them for lod.
  const std::string level = out_dir() + "/named_level.msh";
  r = run("lod " + history + " --elements 1000 -o " + level);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(read_file(level).find(names), std::string::npos);
  // --elements from 1, as simplify and render take it (0 was taken as the last level).
  EXPECT_EQ(run("lod " + history + " --elements 0 -o " + level).code, 2);
  // stats names them too, in its table and its JSON.
  r = run("stats " + input);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("11.3237  inner_conductor\n"), std::string::npos) << r.output;
  r = run("stats --json " + input);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("{\"material\": 4, \"name\": \"shield\", \"row\": "), std::string::npos)
      << r.output;
  r = run("convert " + input + " " + converted + " -o " + deck);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("give the output once"), std::string::npos) << r.output;
  r = run("convert " + input + " -o " + converted + " -o " + deck);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("-o given twice"), std::string::npos) << r.output;
  r = run("convert " + input + " -o");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("-o needs a file"), std::string::npos) << r.output;
}

// simplify --elements writes a level before the last: what that level breaks is said
// apart from what the final mesh breaks (the same counts stats gives for the file), as
// the final mesh's line described the history's last step.
TEST(Cli, SimplifyElementsSaysWhatTheLevelWrittenBreaks) {
  const std::string input = std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh";
  const std::string level = out_dir() + "/spheres_level.mesh";
  const std::string thresholds = " --size 1.6 --stretch 0.25 --valence 25";
  CommandResult r =
      run("simplify " + input + " -o " + level + thresholds + " --tolerance 0.05 --elements 30000");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("final mesh (the history's last step), breaking a threshold: "),
            std::string::npos)
      << r.output;
  const std::string said = "the level written (step 0), breaking a threshold: ";
  const size_t at = r.output.find(said);
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string counts =
      r.output.substr(at + said.size(), r.output.find('\n', at) - at - said.size());
  const CommandResult stats = run("stats " + level + thresholds);
  ASSERT_EQ(stats.code, 0) << stats.output;
  EXPECT_NE(stats.output.find("breaking them: " + counts + "\n"), std::string::npos)
      << counts << "\n"
      << stats.output;
  // Its counts are not the final mesh's (the level is the subdivided input).
  EXPECT_EQ(r.output.find("final mesh (the history's last step), breaking a threshold: " + counts),
            std::string::npos);
}

// A Gmsh input's surface groups go through simplification: a round port on a flat
// face, and a coax's ends (four materials' boundaries) and jacket (part of the
// shield's), each written under its name and tag.
TEST(Cli, SimplifyKeepsTheInputsSurfaceGroups) {
  const std::string data = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/";
  const std::string port = out_dir() + "/port_simplified.msh";
  const std::string history = out_dir() + "/port.tlh";
  CommandResult r = run("simplify " + data + "port.msh -o " + port +
                        " --size 0.5 --tolerance 0.01 --surfaces --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("surface groups (tag name: triangles): 2 boundary_1: "),
            std::string::npos)
      << r.output;
  const size_t at = r.output.find(", 20 port: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string port_line = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_NE(read_file(port).find("2 20 \"port\"\n"), std::string::npos);
  // The history keeps the groups: lod writes the same level with the same groups.
  const std::string level = out_dir() + "/port_level.msh";
  r = run("lod " + history + " --step 1000000000 --surfaces -o " + level);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(port_line), std::string::npos) << port_line << "\n" << r.output;
  EXPECT_EQ(read_file(level), read_file(port));
  const std::string coax = out_dir() + "/coax_simplified.msh";
  r = run("simplify " + data + "coax_order2.msh -o " + coax +
          " --size 2 --tolerance 0.01 --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* group : {" ends: ", " jacket: "})
    EXPECT_NE(r.output.find(group), std::string::npos) << group << "\n" << r.output;
  EXPECT_EQ(r.output.find("note: surface group"), std::string::npos) << r.output;
}

// A Gmsh file's surface elements are read as its surface groups only: a note says so
// (and how many are in no group: the partitions' boundaries), except where the command
// writes the groups again (--surfaces).
TEST(Cli, SurfaceElementsNoteOnlyWhereTheGroupsAreNotWritten) {
  const std::string coax = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax_part3.msh";
  const std::string note =
      "coax_part3.msh: note: 552 surface elements are not kept as elements, only as the "
      "surface groups 'ends', 'jacket' (126 of them in no group, not kept at all): TetLOD keeps "
      "the tetrahedra";
  const std::string out = out_dir() + "/coax_note.msh";
  for (const std::string& command : {"stats " + coax, "convert " + coax + " " + out,
                                     "simplify " + coax + " -o " + out + " --size 2"}) {
    const CommandResult r = run(command);
    EXPECT_EQ(r.code, 0) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(note), std::string::npos) << command << "\n" << r.output;
  }
  for (const std::string& command : {"convert " + coax + " " + out + " --surfaces",
                                     "simplify " + coax + " -o " + out + " --size 2 --surfaces"}) {
    const CommandResult r = run(command);
    EXPECT_EQ(r.code, 0) << command << "\n" << r.output;
    EXPECT_EQ(r.output.find("surface elements are not kept"), std::string::npos) << command << "\n"
                                                                                 << r.output;
    EXPECT_NE(r.output.find("surface groups (tag name: triangles): "), std::string::npos)
        << command << "\n"
        << r.output;
  }
  // Gmsh's VTK export of the same model: its triangles are the groups by number.
  const std::string vtk = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax.vtk";
  CommandResult r = run("convert " + vtk + " " + out);
  EXPECT_NE(r.output.find("coax.vtk: note: 426 surface elements are not kept as elements, only "
                          "as the surface groups 20, 21: TetLOD keeps the tetrahedra and their "
                          "volume groups; --surfaces, or the viewer's boundary groups, writes the "
                          "boundary and interface triangles again, these groups under their tags"),
            std::string::npos)
      << r.output;
  r = run("convert " + vtk + " " + out + " --surfaces");
  EXPECT_NE(r.output.find("surface groups (tag name: triangles): 20 surface_20: 246, 21 "
                          "surface_21: 180, "),
            std::string::npos)
      << r.output;
}

// Material ids at the top of the tag range leave no room to number the surface
// groups: simplify --surfaces says so before simplifying, and writes nothing.
TEST(Cli, SimplifyRefusesSurfaceGroupsWithNoTagsLeftUpFront) {
  TetMesh mesh = test::make_grid_mesh(
      2, 1, 1, [](int i, int, int) { return i == 0 ? 1 : 2147483647; }, 0.5);
  const std::string path = out_dir() + "/top_tags.mesh";
  ASSERT_TRUE(write_mesh(path, mesh).ok());
  const std::string out = out_dir() + "/top_tags_out.msh";
  fs::remove(out);
  const CommandResult r = run("simplify " + path + " -o " + out + " --size 1 --surfaces");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("leave no room to number the surface groups"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("thresholds:"), std::string::npos) << r.output;  // before the run
  EXPECT_FALSE(fs::exists(out));
}

// --surfaces and --msh-version on every command that writes a mesh: the groups are
// printed and written, in every format (Nastran too).
TEST(Cli, SurfaceGroupsAreWrittenByConvertSimplifyAndLod) {
  const std::string path = write_grid("surf.mesh");  // materials 1 (x < 1) and 2
  const std::string groups_line =
      "surface groups (tag name: triangles): 3 boundary_1: 40, 4 boundary_2: 40, "
      "5 interface_1_2: 8\n";
  const std::string converted = out_dir() + "/surf_out.msh";
  CommandResult r = run("convert " + path + " " + converted + " --msh-version 2.2 --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  std::string text = read_file(converted);
  EXPECT_EQ(text.rfind("$MeshFormat\n2.2 0 8\n", 0), 0u);
  EXPECT_NE(text.find("$PhysicalNames\n5\n2 3 \"boundary_1\"\n"), std::string::npos);

  // Nastran: a CTRIA3 per triangle, the group's tag as its PID, as Gmsh writes them.
  const std::string bdf = out_dir() + "/surf_out.bdf";
  r = run("convert " + path + " " + bdf + " --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_NE(read_file(bdf).find(" 88 CTRIA3;"), std::string::npos);
  r = run("convert " + bdf + " " + out_dir() + "/surf_bdf_again.msh --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  // Read back, each group is a whole pair's: written again under the same tag and name.
  const std::string again = out_dir() + "/surf_again.msh";
  r = run("convert " + converted + " " + again + " --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("tetlod convert: note"), std::string::npos) << r.output;
  // A TetGen pair with its .face; written again without, the old .face is replaced by
  // the faces of the mesh written, without markers, so the pair reads back without
  // groups, as written.
  const std::string node = out_dir() + "/surf_pair.node";
  fs::remove(out_dir() + "/surf_pair.face");
  r = run("convert " + path + " " + node + " --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(read_file(out_dir() + "/surf_pair.face").rfind("88 1\n", 0), 0u);
  r = run("convert " + path + " " + node);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("note: " + out_dir() +
                          "/surf_pair.face, which was beside the pair written, now lists this "
                          "mesh's faces without group markers"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_file(out_dir() + "/surf_pair.face").rfind("88 0\n1 ", 0), 0u);
  {
    TetMesh pair;
    ReadInfo info;
    ASSERT_TRUE(read_mesh(node, &pair, &info).ok());
    EXPECT_TRUE(info.surface_groups.empty());
  }
  r = run("convert " + path + " " + converted + " --msh-version 3");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("--msh-version must be 2.2 or 4.1, not '3'"), std::string::npos);

  // simplify at a size that keeps the grid as it is (no collapse can pass the
  // tolerance), so the groups are the input's.
  const std::string simplified = out_dir() + "/surf_simp.msh";
  const std::string history = out_dir() + "/surf.tlh";
  r = run("simplify " + path + " -o " + simplified + " --size 0.9 --tolerance 1e-12 " +
          "--no-subdivide --surfaces --msh-version 2.2 --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_EQ(read_file(simplified).rfind("$MeshFormat\n2.2 0 8\n", 0), 0u);
  r = run("simplify " + path + " -o " + bdf + " --size 0.9 --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(read_file(bdf).find("\nCTRIA3  "), std::string::npos);

  // --msh-binary on simplify and lod: binary files of the same mesh and groups.
  const std::string binary = out_dir() + "/surf_simp_binary.msh";
  r = run("simplify " + path + " -o " + binary + " --size 0.9 --tolerance 1e-12 " +
          "--no-subdivide --surfaces --msh-binary");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_EQ(read_file(binary).rfind(std::string("$MeshFormat\n4.1 1 8\n\1\0\0\0\n", 25), 0), 0u);
  fs::remove(binary);
  r = run("lod " + history + " --step 0 -o " + binary +
          " --surfaces --msh-binary --msh-version 2.2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_EQ(read_file(binary).rfind(std::string("$MeshFormat\n2.2 1 8\n\1\0\0\0\n", 25), 0), 0u);
  r = run("stats " + binary);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(Gmsh 2.2 .msh)"), std::string::npos) << r.output;

  // --vtk-binary on simplify and lod: a .vtu with raw appended data, a BINARY .vtk.
  const std::string vtu = out_dir() + "/surf_simp_binary.vtu";
  const std::string vtk = out_dir() + "/surf_level_binary.vtk";
  r = run("simplify " + path + " -o " + vtu + " --size 0.9 --tolerance 1e-12 " +
          "--no-subdivide --surfaces --vtk-binary");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_NE(read_file(vtu).find("<AppendedData encoding=\"raw\">"), std::string::npos);
  r = run("lod " + history + " --step 0 -o " + vtk + " --surfaces --vtk-binary");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_EQ(
      read_file(vtk).rfind("# vtk DataFile Version 3.0\nTetLOD tetrahedral mesh\nBINARY\n", 0), 0u);
  for (const std::string& file : {vtu, vtk}) {
    TetMesh written;
    ReadInfo info;
    ASSERT_TRUE(read_mesh(file, &written, &info).ok()) << file;
    EXPECT_EQ(written.tet_count(), 96u) << file;
    size_t triangles = 0;
    for (const InputSurfaceGroup& group : info.surface_groups) triangles += group.triangles.size();
    EXPECT_EQ(triangles, 88u) << file;
  }

  const std::string level = out_dir() + "/surf_level.mesh";
  r = run("lod " + history + " --step 0 -o " + level + " --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  text = read_file(level);
  EXPECT_NE(text.find("\nTriangles\n88\n"), std::string::npos);
  fs::remove(bdf);
  r = run("lod " + history + " --step 0 -o " + bdf + " --surfaces");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(groups_line), std::string::npos) << r.output;
  EXPECT_NE(read_file(bdf).find(" 88 CTRIA3;"), std::string::npos);
}

// An empty item in a list (a trailing comma, two in a row) is named as such, in every
// option that takes a list (render said only "is not a comma-separated list", solve
// "'' is neither 'boundary' nor ...").
TEST(Cli, AnEmptyListItemIsNamed) {
  const std::string spheres = std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh";
  const std::string out = out_dir() + "/empty_item";
  for (const std::string& command :
       {"render " + spheres + " -o " + out + ".png --materials 1,2,",
        "render " + spheres + " -o " + out + ".png --hide 1,,2",
        "solve " + spheres + " --conductor 1=1 --ground 4,",
        "solve " + spheres + " --conductor 1=1, --ground 4",
        "simplify " + spheres + " -o " + out + ".mesh --size 3 --material-size 1=2,",
        // Inside or at the start of an M=V list: not a name ",3" (commas inside names
        // are written as they are there).
        "solve " + spheres + " --conductor 1=1,,4=0",
        "solve " + spheres + " --conductor 1=1 --ground 4 --eps ,2=2",
        "simplify " + spheres + " -o " + out + ".mesh --size 3 --material-size 1=2,,2=3"}) {
    const CommandResult r = run(command);
    EXPECT_EQ(r.code, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("an empty item (a comma at either end, or two in a row)"),
              std::string::npos)
        << command << "\n"
        << r.output;
  }
  const CommandResult id = run("render " + spheres + " -o " + out + ".png --hide 1,-1");
  EXPECT_NE(id.output.find("--hide '1,-1': '-1' is not a material id >= 0"), std::string::npos)
      << id.output;
}

TEST(Cli, SimplifyRejectsAbsurdThresholds) {
  const std::string path = write_grid("thr.mesh");
  const std::string out = out_dir() + "/thr_out.mesh";
  for (const char* flags :
       {"--size -1", "--size nan", "--size 1 --stretch 1", "--size 1 --stretch 0",
        "--size 1 --stretch 1e-06", "--size 1 --valence 3", "--size 1 --valence 256",
        "--size 1 --tolerance -2", "--stretch 0.2", "--size 1 --material-size 1=0",
        "--size 1 --size-field box:0,0,0,1,1", "--material-size ''", "--material-size ,",
        "--size 1e-05"}) {
    const CommandResult r = run("simplify " + path + " -o " + out + " " + flags);
    EXPECT_EQ(r.code, 2) << flags << "\n" << r.output;
  }
  // Past 255 the work of a collapse at a node of hundreds of neighbours took minutes.
  EXPECT_NE(run("simplify " + path + " -o " + out + " --size 1 --valence 100000")
                .output.find("--valence '100000' is not a valence, a whole number of neighbours "
                             "in [4, 255]"),
            std::string::npos);
  // A size that would subdivide the mesh past the tet limit is a value refused too.
  EXPECT_NE(run("simplify " + path + " -o " + out + " --size 1e-05")
                .output.find("size 1e-05 would subdivide the mesh into more than 10^15 tets"),
            std::string::npos);
  // stats only counts the tets below a stretch: any in (0, 1) will do there.
  EXPECT_EQ(run("stats " + path + " --size 1 --stretch 1e-05").code, 0);
  // Below the least stretch, tets too flat to read back would pass.
  EXPECT_NE(run("simplify " + path + " -o " + out + " --size 1 --stretch 1e-06")
                .output.find("--stretch '1e-06' is not a stretch from 0.00012 to below 1"),
            std::string::npos);
  // A bad size is worded alike wherever it is given (--size said "is not a size > 0",
  // and so did a named material's).
  for (const char* flags : {"--size abc", "--material-size 1=abc", "--material-size copper=abc"}) {
    const CommandResult bad = run("simplify " + path + " -o " + out + " " + flags);
    EXPECT_EQ(bad.code, 2) << flags;
    EXPECT_NE(bad.output.find("abc"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("a finite number > 0"), std::string::npos) << bad.output;
  }
  // An empty --material-size is refused as such (it once gave "no size limit given").
  EXPECT_NE(run("simplify " + path + " -o " + out + " --material-size ''")
                .output.find("--material-size: empty specification"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

// How options are written: "--size=2" as "--size 2"; an option given twice is refused
// (a second --size replaced the first silently), but for those that add up; a second
// input names both and where the output goes (-o forgotten); a flag given a value is
// refused; a valence that is not a whole number says so.
TEST(Cli, OptionsAreGivenOnceWithOrWithoutEquals) {
  const std::string path = write_grid("opt.mesh");
  const std::string out = out_dir() + "/opt_out.mesh";
  CommandResult r = run("simplify " + path + " -o " + out + " --size=2 --tolerance=0.1");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out));
  fs::remove(out);
  r = run("simplify " + path + " -o " + out + " --size 1 --size 2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("tetlod simplify: --size given twice: give it once"), std::string::npos)
      << r.output;
  r = run("simplify " + path + " -o " + out + " --output " + out + " --size 2");
  EXPECT_NE(r.output.find("-o given twice"), std::string::npos) << r.output;
  r = run("simplify " + path + " -o " + out + " --size=1 --size=2");
  EXPECT_NE(r.output.find("--size given twice"), std::string::npos) << r.output;
  // A flag with a value (its "1" was taken as a second input file).
  r = run("stats " + path + " --json=1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("tetlod stats: --json takes no value (got '--json=1')"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  // Rules add up.
  r = run("simplify " + path + " -o " + out +
          " --size 2 --size-field box:0,0,0,1,1,1,0.5 --size-field=box:1,1,1,2,2,2,0.6");
  EXPECT_EQ(r.code, 0) << r.output;
  fs::remove(out);
  r = run("simplify " + path + " " + out + " --size 2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("two inputs given, '" + path + "' and '" + out +
                          "' (the output file goes after -o: -o " + out + ")"),
            std::string::npos)
      << r.output;
  // With -o given, the second is a second input: no advice to write over it.
  r = run("simplify " + path + " " + path + " -o " + out + " --size 2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("' (it takes one)"), std::string::npos) << r.output;
  r = run("simplify " + path + " -o=" + out + " --size 2");  // -o=OUT as --output=OUT
  EXPECT_EQ(r.code, 0) << r.output;
  fs::remove(out);
  r = run("simplify " + path + " -o " + out + " --size 2 --valence 25.0");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("a whole number"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Writes a Medit .sol file of the sizes, one per vertex.
std::string write_sol(const std::string& name, const std::vector<double>& sizes) {
  const std::string path = out_dir() + "/" + name;
  std::ofstream out(path);
  out << "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n" << sizes.size() << "\n1 1\n";
  for (double s : sizes) out << s << "\n";
  out << "End\n";
  return path;
}

// A size map on a mesh that covers only part of the input (the motor without its air):
// outside it the map's value jumps where the tet it is read from changes, and the final
// count read it at centroids summed in another order than the collapses' checks, so
// that 10 tets came out "new" above the size. Now none (an outside tester's case).
TEST(Cli, ASizeMapCoveringPartOfTheInputBreaksNothing) {
  TetMesh motor;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh", &motor).ok());
  TetMesh cylinder;  // the tets of materials 2-7, their vertices renumbered
  std::vector<uint32_t> id(motor.vertex_count(), kInvalidIndex);
  for (size_t t = 0; t < motor.tet_count(); ++t) {
    if (motor.materials[t] == 1) continue;
    Tet q = motor.tets[t];
    for (uint32_t& v : q) {
      if (id[v] == kInvalidIndex) {
        id[v] = static_cast<uint32_t>(cylinder.positions.size());
        cylinder.positions.push_back(motor.positions[v]);
      }
      v = id[v];
    }
    cylinder.tets.push_back(q);
    cylinder.materials.push_back(motor.materials[t]);
  }
  const std::string background = out_dir() + "/partial_map.mesh";
  ASSERT_TRUE(write_mesh(background, cylinder).ok());
  std::vector<double> sizes;
  for (const Vec3& p : cylinder.positions)
    sizes.push_back(2 + 0.2 * std::fabs(p.x) + 0.3 * std::fabs(p.z));
  const CommandResult r =
      run("simplify " + std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh -o " + out_dir() +
          "/partial_map_out.mesh --size-map " + write_sol("partial_map.sol", sizes) +
          " --size-map-mesh " + background + " --size 20 --within-valence");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(of these tets and nodes, 0 new"), std::string::npos) << r.output;
}

// --size-map: sizes at the input's vertices (a Medit .sol, as MMG3D takes them); the
// output is finer where they are small; a history keeps the map for lod --improve;
// a file that does not fit the input is an error that names it.
TEST(Cli, SimplifyKeepsToASizeMap) {
  const TetMesh grid = test::make_grid_mesh(
      6, 3, 3, [](int i, int, int) { return i < 3 ? 1 : 2; }, 1.0 / 3);
  const std::string in = out_dir() + "/map_grid.mesh";
  ASSERT_TRUE(write_mesh(in, grid).ok());
  std::vector<double> sizes;
  for (const Vec3& p : grid.positions) sizes.push_back(p.x < 1 ? 0.3 : 1.2);
  const std::string sol = write_sol("map_grid.sol", sizes);
  const std::string out = out_dir() + "/map_out.mesh";
  const std::string history = out_dir() + "/map_out.tlh";
  const CommandResult r = run("simplify " + in + " -o " + out + " --size-map " + sol +
                              " --tolerance 1e-9 --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("thresholds: size from the local sizing (a size map, 0.3 to 1.2), "
                          "stretch 0.15"),
            std::string::npos)
      << r.output;
  // With material sizes and region rules too, each is said (material sizes listed up to
  // six): a history's reader has no other way to learn them.
  const CommandResult all =
      run("simplify " + in + " -o " + out_dir() + "/map_all.mesh --size-map " + sol +
          " --material-size 1=0.5,2=0.75 --size-field 'box:0,0,0,1,1,1,0.4;radial:0,0,0,1,2'" +
          " --tolerance 1e-9");
  ASSERT_EQ(all.code, 0) << all.output;
  EXPECT_NE(all.output.find("thresholds: size from the local sizing (material sizes 1=0.5, "
                            "2=0.75; 2 region rules; a size map, 0.3 to 1.2), stretch 0.15"),
            std::string::npos)
      << all.output;
  EXPECT_NE(r.output.find("0 new: the others"), std::string::npos) << r.output;
  TetMesh output;
  ASSERT_TRUE(read_mesh(out, &output).ok());
  size_t fine = 0, coarse = 0;
  for (const Tet& t : output.tets) {
    const Vec3 c = (output.positions[t[0]] + output.positions[t[1]] + output.positions[t[2]] +
                    output.positions[t[3]]) *
                   0.25;
    double right = 0;
    for (uint32_t v : t) right = std::max(right, output.positions[v].x);
    // Where every input tet has sizes 0.3 at its corners (x <= 2/3; the map then grows
    // to 1.2 at x = 1), the size is 0.3.
    if (right <= 2.0 / 3 + 1e-12) {
      EXPECT_LE(tet_shape(output, t).size, 0.3 * (1 + 1e-12));
    }
    fine += c.x < 0.5;
    coarse += c.x > 1.5;
  }
  EXPECT_GT(fine, 4 * coarse) << fine << " tets where the sizes are 0.3, " << coarse
                              << " where they are 1.2";
  // The history keeps the map: lod --improve keeps to it without being given it.
  const std::string level = out_dir() + "/map_level.mesh";
  const CommandResult l = run("lod " + history + " --elements 1 -o " + level + " --improve");
  ASSERT_EQ(l.code, 0) << l.output;
  EXPECT_NE(l.output.find("improving within size from the local sizing (a size map, 0.3 to 1.2)"),
            std::string::npos)
      << l.output;
  const CommandResult given =
      run("lod " + history + " --step 0 -o " + level + " --improve --size-map " + sol);
  EXPECT_EQ(given.code, 2) << given.output;
  EXPECT_NE(given.output.find("--size-map: --improve keeps to the size map saved in the history"),
            std::string::npos)
      << given.output;

  const std::vector<double> fewer_sizes(sizes.begin(), sizes.end() - 1);
  // The sizes may be given at the vertices of another mesh over the same domain (the
  // level an analysis was solved on): a field linear in x, at the input's vertices or at
  // those of a coarse grid, gives the same function, so (to rounding) the same mesh.
  {
    const TetMesh background = test::make_grid_mesh(2, 1, 1, [](int, int, int) { return 1; });
    const std::string coarse_path = out_dir() + "/map_coarse.mesh";
    ASSERT_TRUE(write_mesh(coarse_path, background).ok());
    std::vector<double> on_coarse, on_input;
    for (const Vec3& p : background.positions) on_coarse.push_back(0.3 + 0.45 * p.x);
    for (const Vec3& p : grid.positions) on_input.push_back(0.3 + 0.45 * p.x);
    const std::string a = out_dir() + "/map_linear_input.mesh";
    const std::string b = out_dir() + "/map_linear_coarse.mesh";
    const CommandResult ra = run("simplify " + in + " -o " + a + " --size-map " +
                                 write_sol("map_linear_input.sol", on_input) + " --tolerance 1e-9");
    const CommandResult rb = run("simplify " + in + " -o " + b + " --size-map " +
                                 write_sol("map_linear_coarse.sol", on_coarse) +
                                 " --size-map-mesh " + coarse_path + " --tolerance 1e-9");
    ASSERT_EQ(ra.code, 0) << ra.output;
    ASSERT_EQ(rb.code, 0) << rb.output;
    EXPECT_NE(rb.output.find("(a size map, 0.3 to 1.2)"), std::string::npos) << rb.output;
    EXPECT_NE(rb.output.find("0 new: the others"), std::string::npos) << rb.output;
    EXPECT_EQ(rb.output.find("lie outside"), std::string::npos) << rb.output;  // one domain
    // A background over another box (here moved by 10): a note says so.
    TetMesh moved = background;
    for (Vec3& p : moved.positions) p.x += 10;
    const std::string moved_path = out_dir() + "/map_moved.mesh";
    ASSERT_TRUE(write_mesh(moved_path, moved).ok());
    const CommandResult rm =
        run("stats " + in + " --size-map " + write_sol("map_linear_coarse.sol", on_coarse) +
            " --size-map-mesh " + moved_path);
    EXPECT_NE(rm.output.find("note: 112 of the input's 112 vertices lie outside "
                             "--size-map-mesh " +
                             moved_path + "'s box"),
              std::string::npos)
        << rm.output;
    TetMesh ma, mb;
    ASSERT_TRUE(read_mesh(a, &ma).ok());
    ASSERT_TRUE(read_mesh(b, &mb).ok());
    EXPECT_NEAR(double(mb.tet_count()), double(ma.tet_count()), 0.02 * double(ma.tet_count()));
    // Sizes at the coarse mesh's vertices, given without it: a count that does not fit.
    const CommandResult wrong = run("simplify " + in + " -o " + b + " --size-map " +
                                    write_sol("map_linear_coarse.sol", on_coarse));
    EXPECT_EQ(wrong.code, 1) << wrong.output;
    EXPECT_NE(wrong.output.find("12 sizes, but the input has 112 vertices"), std::string::npos)
        << wrong.output;
    const CommandResult fewer =
        run("simplify " + in + " -o " + b + " --size-map " +
            write_sol("map_fewer.sol", fewer_sizes) + " --size-map-mesh " + coarse_path);
    EXPECT_NE(fewer.output.find("but --size-map-mesh " + coarse_path + " has 12 vertices"),
              std::string::npos)
        << fewer.output;
    const CommandResult alone =
        run("simplify " + in + " -o " + b + " --size 1 --size-map-mesh " + coarse_path);
    EXPECT_EQ(alone.code, 2) << alone.output;
    EXPECT_NE(alone.output.find("give the sizes too (--size-map)"), std::string::npos)
        << alone.output;
  }

  // stats checks a mesh against sizes at its own vertices: the grid's tets are 0.58
  // long, above 0.3 in the cubes with x <= 2/3 (108) and in part of the next (18).
  const CommandResult st = run("stats " + in + " --size-map " + sol + " --check");
  EXPECT_EQ(st.code, 3) << st.output;
  EXPECT_NE(st.output.find("breaking them: 0 tets below the stretch, 126 above the size"),
            std::string::npos)
      << st.output;

  // A binary .solb as FreeFEM writes it, with its cube (tests/data/other_tools): every
  // tet of the cube (0.58 long) is above the sizes, 0.1 to 0.35.
  const std::string ff = std::string(TETLOD_SOURCE_DIR) + "/tests/data/other_tools/";
  const CommandResult fs = run("stats " + ff + "meshb_freefem_cube.meshb --size-map " + ff +
                               "solb_freefem_cube.solb --check");
  EXPECT_EQ(fs.code, 3) << fs.output;
  EXPECT_NE(fs.output.find("(a size map, 0.1 to 0.35)"), std::string::npos) << fs.output;
  EXPECT_NE(fs.output.find("breaking them: 0 tets below the stretch, 162 above the size"),
            std::string::npos)
      << fs.output;

  // Errors: what does not fit names the file, as bad input (exit 1); nothing is
  // written.
  const std::string none = out_dir() + "/map_none.mesh";
  auto error = [&](const std::string& map_path) {
    const CommandResult e = run("simplify " + in + " -o " + none + " --size-map " + map_path);
    EXPECT_EQ(e.code, 1) << e.output;
    return e.output;
  };
  std::vector<double> fewer(sizes.begin(), sizes.end() - 1);
  EXPECT_NE(error(write_sol("map_fewer.sol", fewer))
                .find("--size-map " + out_dir() +
                      "/map_fewer.sol:4: 111 sizes, but the input has "
                      "112 vertices"),
            std::string::npos)
      << error(write_sol("map_fewer.sol", fewer));
  std::vector<double> negative = sizes;
  negative[4] = -1;
  EXPECT_NE(error(write_sol("map_negative.sol", negative))
                .find(out_dir() + "/map_negative.sol:10: size 5 is -1: sizes must be > 0"),
            std::string::npos)
      << error(write_sol("map_negative.sol", negative));
  EXPECT_NE(error(out_dir() + "/no_such.sol").find("no_such.sol: cannot"), std::string::npos);
  // A mesh given as the map (for --size-map-mesh): a usage error that says which is which.
  const CommandResult mesh_as_map = run("simplify " + in + " -o " + none + " --size-map " + in);
  EXPECT_EQ(mesh_as_map.code, 2) << mesh_as_map.output;
  EXPECT_NE(mesh_as_map.output.find("is not a size map: a Medit .sol or .solb file (the mesh its "
                                    "sizes are at goes in --size-map-mesh)"),
            std::string::npos)
      << mesh_as_map.output;
  EXPECT_FALSE(fs::exists(none));

  // A vertex no tet uses is dropped on reading, and its size with it: the sizes stay
  // with their vertices (here the dropped one's is tiny: shifted, it would refine).
  TetMesh spare = grid;
  spare.positions.insert(spare.positions.begin(), Vec3{9, 9, 9});
  for (Tet& t : spare.tets)
    for (uint32_t& v : t) ++v;
  const std::string spare_in = out_dir() + "/map_spare.mesh";
  ASSERT_TRUE(write_mesh(spare_in, spare).ok());
  std::vector<double> spare_sizes = sizes;
  spare_sizes.insert(spare_sizes.begin(), 1e-4);
  const std::string spare_out = out_dir() + "/map_spare_out.mesh";
  const CommandResult d = run("simplify " + spare_in + " -o " + spare_out + " --size-map " +
                              write_sol("map_spare.sol", spare_sizes) + " --tolerance 1e-9");
  ASSERT_EQ(d.code, 0) << d.output;
  EXPECT_NE(d.output.find("(a size map, 0.3 to 1.2)"), std::string::npos) << d.output;
  EXPECT_EQ(read_file(spare_out), read_file(out));
}

// A --material-size for a material the mesh does not have (a mistyped id) is an
// error naming it and the materials there are, not a size silently ignored.
TEST(Cli, MaterialSizeOfAnAbsentMaterialIsAnError) {
  const std::string path = write_grid("absent.mesh");
  const std::string out = out_dir() + "/absent_out.mesh";
  fs::remove(out);  // from an earlier run
  const CommandResult r =
      run("simplify " + path + " -o " + out + " --size 2 --material-size 2=0.5,3=0.5");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(
      r.output.find("--material-size 3=0.5: the mesh has no material 3 (its materials: 1, 2)"),
      std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  const CommandResult render =
      run("render " + path + " -o " + out_dir() + "/absent.png --simplify --material-size 9=1");
  EXPECT_EQ(render.code, 2) << render.output;  // a usage error, as in simplify
  EXPECT_NE(render.output.find("tetlod render: --material-size 9=1: the mesh has no material 9"),
            std::string::npos)
      << render.output;
  const std::string history = out_dir() + "/absent.tlh";
  const CommandResult ok =
      run("simplify " + path + " -o " + out + " --material-size 2=0.5 --history " + history);
  EXPECT_EQ(ok.code, 0) << ok.output;
  const CommandResult lod = run("lod " + history + " --step 1 -o " + out_dir() +
                                "/absent_lod.mesh --improve --material-size 4=1");
  EXPECT_EQ(lod.code, 2) << lod.output;
  EXPECT_NE(lod.output.find("tetlod lod: --material-size 4=1: the mesh has no material 4"),
            std::string::npos)
      << lod.output;
}

// A tolerance above the width of a thin gap (tests/data/gmsh/gap.geo): collapses that
// would push one wall through the other are refused and counted, so the output reads
// back (the reader refuses tets that overlap).
TEST(Cli, SimplifyNeverPushesTheBoundaryThroughItself) {
  const std::string gap = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/gap.msh";
  const std::string out = out_dir() + "/gap_out.msh";
  const CommandResult r = run("simplify " + gap + " -o " + out + " --size 6 --tolerance 2");
  ASSERT_EQ(r.code, 0) << r.output;
  const size_t at = r.output.find(", overlap ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_GT(std::stoul(r.output.substr(at + 10)), 0u) << r.output;
  const CommandResult back = run("stats " + out);
  EXPECT_EQ(back.code, 0) << back.output;
  EXPECT_EQ(back.output.find("overlaps"), std::string::npos) << back.output;
}

TEST(Cli, SimplifyThenLodWritesLevels) {
  const std::string path = write_grid("simp.mesh");
  const std::string out = out_dir() + "/simp_out.mesh";
  const std::string history = out_dir() + "/simp.tlh";
  const CommandResult r = run("simplify " + path + " -o " + out +
                              " --size 2 --stretch 0.05 --valence 40 "
                              "--tolerance 1e-9 --history " +
                              history);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("rejected evaluations"), std::string::npos);
  EXPECT_NE(r.output.find("evaluations: "), std::string::npos);
  EXPECT_NE(r.output.find("0 new: the others are input tets or nodes"), std::string::npos)
      << r.output;
  const std::string level = out_dir() + "/simp_level.vtu";
  const CommandResult l = run("lod " + history + " --step 0 -o " + level);
  ASSERT_EQ(l.code, 0) << l.output;
  EXPECT_NE(l.output.find("step 0 of"), std::string::npos);
  std::ofstream(out_dir() + "/junk.tlh") << "not a history";
  const CommandResult junk = run("lod " + out_dir() + "/junk.tlh --step 0 -o " + level);
  EXPECT_EQ(junk.code, 1);
  EXPECT_NE(junk.output.find("junk.tlh"), std::string::npos);
}

// A command's outputs are written together or not at all, and never over a file the
// user did not name as an output: a history that cannot be written leaves the mesh
// output as it was; a history path that is not .tlh (the input, say), an unknown
// output extension, or --step with --elements are usage errors before any work.
TEST(Cli, OutputsAreWrittenTogetherOrNotAtAll) {
  const std::string path = write_grid("together.mesh");
  const std::string input_bytes = [&] {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  const std::string out = out_dir() + "/together_out.mesh";
  std::ofstream(out) << "old";
  const std::string thresholds = " --size 2 --tolerance 1e-9";
  CommandResult r = run("simplify " + path + " -o " + out + thresholds + " --history " + out_dir() +
                        "/no_such_dir/h.tlh");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("no_such_dir/h.tlh: cannot write"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("whole mesh"), std::string::npos) << "found before any work\n"
                                                            << r.output;
  std::ifstream kept(out);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "old");

  for (const std::string& history : {path, out, out_dir() + "/h.mesh"}) {
    r = run("simplify " + path + " -o " + out + thresholds + " --history " + history);
    EXPECT_EQ(r.code, 2) << history << "\n" << r.output;
    EXPECT_NE(r.output.find("a collapse history file ends in .tlh"), std::string::npos) << r.output;
  }
  std::ifstream input(path, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(input), {}), input_bytes);

  r = run("simplify " + path + " -o " + out_dir() + "/out.tlh" + thresholds);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("unknown mesh file extension '.tlh'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--history FILE.tlh"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("thresholds:"), std::string::npos) << "checked before the run";
  r = run("convert " + path + " " + out_dir() + "/x.stl");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(
      r.output.find("tetlod convert: " + out_dir() + "/x.stl: unknown mesh file extension '.stl'"),
      std::string::npos)
      << r.output;  // no "-o": convert's OUT is not an option

  const std::string history = out_dir() + "/together.TLH";  // any case
  r = run("simplify " + path + " -o " + out + thresholds + " --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("lod " + history + " --step 0 --elements 5 -o " + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("give --elements or --step, not both"), std::string::npos) << r.output;
  r = run("lod " + history + " --step 99999999 -o " + out);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(the last: --step is past it)"), std::string::npos) << r.output;
  r = run("lod " + history + " --elements 1 -o " + out);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(the last: no level has fewer elements than this one)"),
            std::string::npos)
      << r.output;
  r = run("lod " + history + " --elements 100000000 -o " + out);
  EXPECT_NE(r.output.find("step 0 of "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(the first: no level has more elements than this one)"),
            std::string::npos)
      << r.output;
}

// A forged history whose mesh has positive tets that overlap (three on one face):
// the reader's replay checks pass, but lod checks the level as a mesh file would be
// checked, and writes nothing.
TEST(Cli, LodRefusesAHistoryWhoseLevelIsNotAMesh) {
  TetMesh base;
  base.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1, 0.1, 1}, {0.2, 0.1, 0.9}};
  base.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}};
  base.materials = {1, 1, 1};
  const std::string history = out_dir() + "/overlap.tlh";
  ASSERT_TRUE(write_history(history, base, CollapseHistory()).ok());
  const std::string out = out_dir() + "/overlap.mesh";
  fs::remove(out);
  const CommandResult r = run("lod " + history + " --step 0 -o " + out);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("corrupt history: " + history + " (level at step 0)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// --improve reshapes the level written (flips, vertex moves) within the thresholds and
// says what it did; the file holds the improved mesh.
TEST(Cli, SimplifyImproveWritesTheImprovedLevel) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string out = out_dir() + "/improved.mesh";
  for (const char* level : {"", " --elements 20000"}) {
    const CommandResult r =
        run("simplify " + motor + " -o " + out + " --size 12 --tolerance 0.05 --improve" + level);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("final mesh (before --improve), breaking a threshold"),
              std::string::npos)
        << r.output;
    const size_t at = r.output.find("improve (the level written): ");
    ASSERT_NE(at, std::string::npos) << r.output;
    const size_t mean_at = r.output.find("stretch mean ", at);
    ASSERT_NE(mean_at, std::string::npos) << r.output;
    double before = 0, after = 0;
    ASSERT_EQ(std::sscanf(r.output.c_str() + mean_at, "stretch mean %lf -> %lf", &before, &after),
              2)
        << r.output;
    EXPECT_GT(after, before + 0.005) << level;
    const CommandResult s = run("stats --json " + out);
    ASSERT_EQ(s.code, 0) << s.output;
    const size_t key = s.output.find("\"average_stretch\": ");
    ASSERT_NE(key, std::string::npos);
    EXPECT_NEAR(std::atof(s.output.c_str() + key + 19), after, 1e-4) << level;
  }
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// `lod --improve` with the thresholds the history was made with writes what
// `simplify --elements N --improve` writes; thresholds without --improve, or --improve
// without a size, are usage errors.
TEST(Cli, LodImproveWritesWhatSimplifyImproveWrites) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string history = out_dir() + "/improve.tlh";
  const std::string direct = out_dir() + "/improve_direct.mesh";
  const std::string later = out_dir() + "/improve_later.mesh";
  const CommandResult r =
      run("simplify " + motor + " -o " + direct +
          " --size 12 --tolerance 0.05 --elements 20000 --improve --history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  const CommandResult l =
      run("lod " + history + " --elements 20000 -o " + later + " --improve --size 12");
  ASSERT_EQ(l.code, 0) << l.output;
  EXPECT_NE(l.output.find("improve (the level written): "), std::string::npos) << l.output;
  EXPECT_EQ(file_bytes(later), file_bytes(direct));
  const std::string plain = out_dir() + "/improve_plain.mesh";
  ASSERT_EQ(run("lod " + history + " --elements 20000 -o " + plain).code, 0);
  EXPECT_NE(file_bytes(plain), file_bytes(direct));
  for (const char* flags : {" --size 12", " --improve --size 12 --stretch 1",
                            " --improve --size 12 --tolerance 0.05"}) {
    const CommandResult bad = run("lod " + history + " --step 0 -o " + plain + flags);
    EXPECT_EQ(bad.code, 2) << flags << "\n" << bad.output;
  }
  // The history keeps its thresholds: --improve alone uses them.
  const std::string saved = out_dir() + "/improve_saved.mesh";
  const CommandResult a = run("lod " + history + " --elements 20000 -o " + saved + " --improve");
  ASSERT_EQ(a.code, 0) << a.output;
  EXPECT_NE(a.output.find("improving within size 12, stretch 0.15, valence 25 (saved in the "
                          "history)"),
            std::string::npos)
      << a.output;
  EXPECT_EQ(file_bytes(saved), file_bytes(direct));
  // A threshold given here replaces only its own saved value.
  const CommandResult m =
      run("lod " + history + " --elements 20000 -o " + saved + " --improve --valence 30");
  ASSERT_EQ(m.code, 0) << m.output;
  EXPECT_NE(m.output.find("improving within size 12, stretch 0.15, valence 30 (saved in the "
                          "history, but --valence given here)"),
            std::string::npos)
      << m.output;
  // One saved without them (as before 2026-11-24: the file up to the thresholds, with
  // the first version's magic and no end block) needs them given.
  std::string bytes = file_bytes(history);
  const size_t at = bytes.find("TLPARAM1");
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.substr(0, 8), "TETLODH3");
  bytes[7] = '1';
  const std::string legacy = out_dir() + "/improve_legacy.tlh";
  std::ofstream(legacy, std::ios::binary) << bytes.substr(0, at);
  const CommandResult b = run("lod " + legacy + " --elements 20000 -o " + saved + " --improve");
  EXPECT_EQ(b.code, 2) << b.output;
  EXPECT_NE(b.output.find("improve_legacy.tlh was saved without its thresholds"), std::string::npos)
      << b.output;
  const CommandResult c =
      run("lod " + legacy + " --elements 20000 -o " + saved + " --improve --size 12");
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_EQ(file_bytes(saved), file_bytes(direct));
  EXPECT_NE(c.output.find("is a history of format 1 (written before 2026-11-29), without a "
                          "checksum"),
            std::string::npos)
      << c.output;
  // A history may have any name: a level written over it would replace it.
  const std::string named = out_dir() + "/history_named.mesh";
  fs::copy_file(history, named, fs::copy_options::overwrite_existing);
  const CommandResult over = run("lod " + named + " --step 2 -o " + named);
  EXPECT_EQ(over.code, 2) << over.output;
  EXPECT_NE(over.output.find("the history being read"), std::string::npos) << over.output;
  EXPECT_EQ(file_bytes(named), file_bytes(history));
  // Nor over a file of a .node/.ele output's set.
  const std::string node = out_dir() + "/history_named.node";
  fs::copy_file(history, node, fs::copy_options::overwrite_existing);
  const CommandResult pair =
      run("lod " + node + " --step 2 -o " + out_dir() + "/history_named.ele");
  EXPECT_EQ(pair.code, 2) << pair.output;
  EXPECT_NE(pair.output.find("would write " + node + ", the history being read"), std::string::npos)
      << pair.output;
  EXPECT_EQ(file_bytes(node), file_bytes(history));
}

// Subdivision may take nodes past the valence threshold; the output says how many, and
// whether edge removals and collapses brought them all back or the run was given up
// and made again within the threshold.
TEST(Cli, SimplifySaysWhatSubdivisionPastTheValenceDid) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string out = out_dir() + "/past_valence.mesh";
  CommandResult r = run("simplify " + motor + " -o " + out + " --size 18 --tolerance 0.05");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("past the valence: subdivision within the valence threshold left "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("collapses (the history's first) and left 0, so it is the result"),
            std::string::npos)
      << r.output;
  // And how to make the first run only (a user's 2.2M-tet mesh took twice the time for
  // 8 tets above the size).
  EXPECT_NE(r.output.find("(--within-valence makes the first run only, which left "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" in the links of nodes subdivision took past the valence"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" tets below the stretch, 0 above the size, "), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("a run whose subdivision split "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" edges in 1 red level (Bey's 1:8 refinement) and took "),
            std::string::npos)
      << r.output;
  // --within-valence: one run, and its tets above the size.
  r = run("simplify " + motor + " -o " + out + " --size 18 --tolerance 0.05 --within-valence");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("past the valence"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(" 0 above the size, "), std::string::npos) << r.output;
  r = run("simplify " + motor + " -o " + out + " --size 18 --valence 18 --tolerance 0.05");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("was given up: "), std::string::npos) << r.output;
}

// --past-valence-factor bounds the run past the valence (at size 12 the bundled motor's
// needs 2.2 times the first run's tets): at 1 it stops, the first run stands, and the
// output says so and names the flag; at 3 it is the result. Bad values are usage errors.
TEST(Cli, PastValenceFactorBoundsTheRunPastTheValence) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string out = out_dir() + "/factor.mesh";
  const std::string base = "simplify " + motor + " -o " + out + " --size 12 --tolerance 0.05";
  CommandResult r = run(base + " --past-valence-factor 1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("stopped before its end: its subdivision passed "), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" tets, as many as the first run's\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(--past-valence-factor raises that bound: it was 1)"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find(" 0 above the size, "), std::string::npos) << r.output;
  r = run(base + " --past-valence-factor 3");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("so it is the result"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" 0 above the size, "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("--past-valence-factor raises"), std::string::npos) << r.output;
  for (const char* bad : {"0", "1001", "2.5", "x"}) {
    r = run(base + " --past-valence-factor " + bad);
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.output.find("--past-valence-factor '" + std::string(bad) +
                            "' is not a whole number in [1, 1000]"),
              std::string::npos)
        << r.output;
  }
}

// By default the run past the valence starts on a second thread while the first
// collapses, and the time line says so; --one-thread makes it after the first. The
// mesh and the history are the same, byte for byte.
TEST(Cli, OneThreadGivesTheSameOutput) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  std::string mesh[2], history[2];
  for (int one = 0; one < 2; ++one) {
    const std::string name = out_dir() + (one ? "/one_thread" : "/alongside");
    const CommandResult r = run("simplify " + motor + " -o " + name + ".mesh --history " + name +
                                ".tlh --size 16 --tolerance 0.05" + (one ? " --one-thread" : ""));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("so it is the result"), std::string::npos) << r.output;
    const bool alongside =
        r.output.find(
            " for the run that is not the result, made at the same time on a second "
            "thread\n") != std::string::npos;
    EXPECT_EQ(alongside, !one && std::thread::hardware_concurrency() >= 2) << r.output;
    mesh[one] = read_file(name + ".mesh");
    history[one] = read_file(name + ".tlh");
  }
  EXPECT_FALSE(mesh[0].empty());
  EXPECT_EQ(mesh[0], mesh[1]);
  EXPECT_EQ(history[0], history[1]);
}

// Where stderr is a terminal, `simplify` (and `solve`) show progress on one line, rewritten in
// place (the run past the valence's phases named as such) and erased before the
// results; where it is not (a pipe, as for scripts), nothing of it. The terminal is
// util-linux's `script` (Debian's bsdutils, an essential package); skipped where it
// cannot make one.
TEST(Cli, ProgressLineOnlyOnATerminal) {
  if (std::system("script -qec true /dev/null > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no script(1), or no pseudo-terminal for it";
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string simplify = std::string(TETLOD_BINARY) + " simplify " + motor + " -o " +
                               out_dir() + "/progress.mesh --size 16 --tolerance 0.05";
  // What the command writes to a terminal (its stdout thrown away).
  const auto on_terminal = [](const std::string& command) {
    std::string terminal;
    std::FILE* pipe = popen(("script -qec '" + command + " > /dev/null' /dev/null").c_str(), "r");
    EXPECT_NE(pipe, nullptr);
    if (!pipe) return terminal;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) terminal.append(buffer, n);
    EXPECT_EQ(pclose(pipe), 0) << terminal;
    return terminal;
  };
  const std::string terminal = on_terminal(simplify);
  EXPECT_EQ(terminal.rfind("\rtetlod simplify: subdivide ", 0), 0u) << terminal;
  EXPECT_NE(terminal.find("\rtetlod simplify: simplify "), std::string::npos) << terminal;
  // Every edge's first evaluation is shown before the collapses.
  const size_t evaluate = terminal.find("\rtetlod simplify: evaluate edges 0%");
  EXPECT_NE(evaluate, std::string::npos) << terminal;
  EXPECT_LT(evaluate, terminal.find("\rtetlod simplify: simplify ")) << terminal;
  // The run past the valence starts on a second thread when the first run's
  // subdivision ends (with a second processor): the first's collapses are shown with
  // where it is, then its own.
  const bool alongside = std::thread::hardware_concurrency() >= 2;
  EXPECT_EQ(terminal.find("\rtetlod simplify: simplify 0%, 0 collapses; past the valence: ") !=
                std::string::npos,
            alongside)
      << terminal;
  EXPECT_NE(terminal.find("\033[K\rtetlod simplify: past the valence: simplify "),
            std::string::npos)
      << terminal;
  ASSERT_GE(terminal.size(), 4u);
  EXPECT_EQ(terminal.substr(terminal.size() - 4), "\r\033[K") << terminal;  // erased
  // On a narrow terminal each line is cut short of its width, so that it never wraps
  // (\r would then rewrite only its last row).
  const std::string narrow = on_terminal("stty cols 50; " + simplify);
  EXPECT_NE(narrow.find("\rtetlod simplify: simplify "), std::string::npos) << narrow;
  for (size_t at = 0; (at = narrow.find('\r', at)) != std::string::npos; ++at) {
    const size_t end = narrow.find("\033[K", at);
    ASSERT_NE(end, std::string::npos) << narrow;
    EXPECT_LE(end - at - 1, 49u) << narrow.substr(at + 1, end - at - 1);
  }
  const CommandResult piped = run(simplify.substr(std::string(TETLOD_BINARY).size() + 1));
  ASSERT_EQ(piped.code, 0) << piped.output;
  EXPECT_EQ(piped.output.find('\r'), std::string::npos) << piped.output;
  // `solve` likewise: its setup, assembly, factorisation (and iterations, on larger
  // meshes than this).
  const std::string solve = std::string(TETLOD_BINARY) + " solve " + TETLOD_SOURCE_DIR +
                            "/assets/spheres.mesh --conductor 1=1 --ground 4";
  const std::string solving = on_terminal(solve);
  EXPECT_EQ(solving.rfind("\rtetlod solve: setup ", 0), 0u) << solving;
  EXPECT_NE(solving.find("\rtetlod solve: assemble "), std::string::npos) << solving;
  ASSERT_GE(solving.size(), 4u);
  EXPECT_EQ(solving.substr(solving.size() - 4), "\r\033[K") << solving;
  const CommandResult solved = run(solve.substr(std::string(TETLOD_BINARY).size() + 1));
  ASSERT_EQ(solved.code, 0) << solved.output;
  EXPECT_EQ(solved.output.find('\r'), std::string::npos) << solved.output;
}

// What the Gmsh patch antenna breaks of size 3, stretch 0.2, valence 22, counted here
// from the file: flat tets in its thin layers, tets larger than 3 in the air, nodes of
// many neighbours round the feed pin ("N tets below the stretch, M above the size, K
// nodes above the valence").
std::string antenna_breaks() {
  TetMesh mesh;
  ReadInfo info;
  EXPECT_TRUE(
      read_mesh(std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/antenna.msh", &mesh, &info));
  size_t flat = 0, big = 0, crowded = 0;
  for (const Tet& t : mesh.tets) {
    const TetShape shape = tet_shape(mesh, t);
    flat += shape.stretch < 0.2;
    big += shape.size > 3;
  }
  for (uint32_t n : test::valences(mesh)) crowded += n > 22;
  EXPECT_GT(flat, 0u);
  EXPECT_GT(big, 0u);
  EXPECT_GT(crowded, 0u);
  return std::to_string(flat) + (flat == 1 ? " tet" : " tets") + " below the stretch, " +
         std::to_string(big) + " above the size, " + std::to_string(crowded) +
         (crowded == 1 ? " node" : " nodes") + " above the valence";
}

// `tetlod simplify` says what its input breaks of the thresholds before it starts.
TEST(Cli, SimplifySaysWhatTheInputBreaks) {
  const std::string antenna = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/antenna.msh";
  const CommandResult r = run("simplify " + antenna + " -o " + out_dir() +
                              "/input_breaks.mesh --size 3 --stretch 0.2 --valence 22 "
                              "--tolerance 0.05");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string line = "input, breaking them: " + antenna_breaks() + "\n";
  EXPECT_NE(r.output.find("thresholds: size 3, stretch 0.2, valence 22, tolerance 0.05\n" + line),
            std::string::npos)
      << line << r.output;
}

// `tetlod stats` with thresholds counts what a mesh breaks of them, and with --check
// exits with status 3 if anything does (0 if nothing does; 2 for a bad threshold).
TEST(Cli, StatsChecksAMeshAgainstThresholds) {
  const std::string antenna = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/antenna.msh";
  const std::string breaks = antenna_breaks();
  const CommandResult counted = run("stats " + antenna + " --size 3 --stretch 0.2 --valence 22");
  ASSERT_EQ(counted.code, 0) << counted.output;
  EXPECT_NE(counted.output.find(
                "thresholds: size 3, stretch 0.2, valence 22\nbreaking them: " + breaks + "\n"),
            std::string::npos)
      << counted.output;
  const CommandResult checked =
      run("stats " + antenna + " --size 3 --stretch 0.2 --valence 22 --check --json");
  EXPECT_EQ(checked.code, 3) << checked.output;
  EXPECT_NE(checked.output.find("\"breaking\": {\"below_stretch\": "), std::string::npos)
      << checked.output;
  // The bundled motor within loose thresholds: nothing breaks them.
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const CommandResult within =
      run("stats " + motor + " --size 30 --stretch 0.05 --valence 40 --check");
  EXPECT_EQ(within.code, 0) << within.output;
  EXPECT_NE(within.output.find("breaking them: 0 tets below the stretch, 0 above the size, 0 "
                               "nodes above the valence\n"),
            std::string::npos)
      << within.output;
  // Without thresholds, no such lines; a bad one is a usage error.
  const CommandResult plain = run("stats " + motor);
  EXPECT_EQ(plain.code, 0);
  EXPECT_EQ(plain.output.find("breaking them"), std::string::npos);
  EXPECT_EQ(run("stats " + motor + " --stretch 1.5").code, 2);
  EXPECT_EQ(run("stats " + motor + " --material-size 99=3").code, 2);
}

// The number after `label` in `text` (e.g. "largest: " -> 0.0356639).
double number_after(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  EXPECT_NE(at, std::string::npos) << label << " in " << text;
  return at == std::string::npos ? NAN : std::atof(text.c_str() + at + label.size());
}

// `tetlod compare`: each material's volume and how far each surface moved. Exact on box2
// moved by 0.25 along z (every surface moves by 0.25: the top and bottom faces along
// their normal, the sides' ends past the old top and bottom), nothing on a mesh against
// itself; within the tolerance after `simplify`; --check fails (status 3) past a
// tolerance or where a material or surface is lost.
TEST(Cli, CompareSaysHowFarEachSurfaceMoved) {
  const std::string box2 = std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh";
  TetMesh moved;
  ASSERT_TRUE(read_mesh(box2, &moved));
  for (Vec3& p : moved.positions) p.z += 0.25;
  const std::string moved_path = out_dir() + "/box2_moved.mesh";
  ASSERT_TRUE(write_mesh(moved_path, moved));
  const CommandResult shifted = run("compare " + box2 + " " + moved_path);
  ASSERT_EQ(shifted.code, 0) << shifted.output;
  EXPECT_NEAR(number_after(shifted.output, "largest: "), 0.25, 1e-9) << shifted.output;
  EXPECT_NE(shifted.output.find("surfaces lost 0, new 0; materials lost 0, new 0"),
            std::string::npos)
      << shifted.output;
  EXPECT_EQ(run("compare " + box2 + " " + moved_path + " --check --tolerance 0.24").code, 3);
  EXPECT_EQ(run("compare " + box2 + " " + moved_path + " --check --tolerance 0.26").code, 0);

  const std::string antenna = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/antenna.msh";
  const CommandResult same = run("compare " + antenna + " " + antenna + " --check --tolerance 0");
  EXPECT_EQ(same.code, 0) << same.output;
  EXPECT_NE(same.output.find("largest: 0 (-)"), std::string::npos) << same.output;
  EXPECT_NE(same.output.find("3 patch | 4 feed"), std::string::npos) << same.output;

  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string simplified = out_dir() + "/compare_motor.mesh";
  ASSERT_EQ(run("simplify " + motor + " -o " + simplified + " --size 12 --tolerance 0.05").code, 0);
  const CommandResult kept =
      run("compare " + motor + " " + simplified + " --check --tolerance 0.05");
  EXPECT_EQ(kept.code, 0) << kept.output;
  const double largest = number_after(kept.output, "largest: ");
  EXPECT_GT(largest, 0);
  EXPECT_LE(largest, 0.05);
  EXPECT_EQ(run("compare " + motor + " " + simplified + " --check --tolerance " +
                std::to_string(largest / 2))
                .code,
            3);

  EXPECT_NE(kept.output.find("topology: every material in as many pieces, every surface with "
                             "its Euler characteristic"),
            std::string::npos)
      << kept.output;

  // A tet of one material away from the other (no face on the interface) given to the
  // other: a piece more, a topology change --check fails on, whatever the tolerance.
  TetMesh split;
  ASSERT_TRUE(read_mesh(box2, &split));
  const CommandResult not_split = run("compare " + box2 + " " + box2 + " --check");
  EXPECT_EQ(not_split.code, 0) << not_split.output;
  std::vector<uint32_t> neighbors;
  build_face_neighbors(split, &neighbors);
  size_t island = split.tet_count();
  for (size_t t = 0; t < split.tet_count() && island == split.tet_count(); ++t) {
    bool inside = true;
    for (int f = 0; f < 4; ++f) {
      const uint32_t o = neighbors[4 * t + size_t(f)];
      inside &= o == kInvalidIndex || split.materials[o] == split.materials[t];
    }
    if (inside) island = t;
  }
  ASSERT_LT(island, split.tet_count());
  split.materials[island] = split.materials[island] == 1 ? 2 : 1;
  const std::string split_path = out_dir() + "/box2_split.mesh";
  ASSERT_TRUE(write_mesh(split_path, split));
  const CommandResult changed = run("compare " + box2 + " " + split_path + " --check --json");
  EXPECT_EQ(changed.code, 3) << changed.output;
  EXPECT_NE(changed.output.find("a material's number of pieces or a surface's Euler "
                                "characteristic changed"),
            std::string::npos)
      << changed.output;
  EXPECT_NE(changed.output.find("\"euler_before\": "), std::string::npos) << changed.output;
  EXPECT_NE(changed.output.find("\"pieces_before\": 1, \"pieces_after\": 2"), std::string::npos)
      << changed.output;
  EXPECT_EQ(changed.output.find("\"topology_changes\": 0"), std::string::npos) << changed.output;

  const CommandResult other = run("compare " + motor + " " + box2 + " --check");
  EXPECT_EQ(other.code, 3) << other.output;
  EXPECT_NE(other.output.find("lost"), std::string::npos) << other.output;
  EXPECT_EQ(run("compare " + motor).code, 2);
  EXPECT_EQ(run("compare " + motor + " " + box2 + " --tolerance -1").code, 2);
  EXPECT_EQ(run("compare " + motor + " " + out_dir() + "/no_such.mesh").code, 1);
}

// Another tool's numbering: the same named materials under other ids are matched by
// name (nothing lost or new), and by id with --by-id (both lost and new).
TEST(Cli, CompareMatchesNamedMaterialsByName) {
  const std::string apart = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/apart.msh";
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(apart, &mesh, &info));
  ASSERT_EQ(info.material_names.size(), 2u);  // shell = 1, core = 2
  for (int32_t& m : mesh.materials) m = m == 1 ? 20 : 10;
  std::vector<MaterialName> names = {{10, "core"}, {20, "shell"}};
  WriteOptions options;
  options.material_names = &names;
  const std::string renumbered = out_dir() + "/apart_renumbered.msh";
  ASSERT_TRUE(write_mesh(renumbered, mesh, options));

  const CommandResult r = run("compare " + apart + " " + renumbered + " --check");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("materials matched by name: AFTER's 10 is 2, 20 is 1"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("materials lost 0, new 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("largest: 0 "), std::string::npos) << r.output;

  const CommandResult ids = run("compare " + apart + " " + renumbered + " --check --by-id");
  EXPECT_EQ(ids.code, 3) << ids.output;
  EXPECT_NE(ids.output.find("materials matched by id\n"), std::string::npos) << ids.output;
  EXPECT_NE(ids.output.find("materials lost 2, new 2"), std::string::npos) << ids.output;
  EXPECT_NE(ids.output.find("10 core"), std::string::npos) << ids.output;  // AFTER's names

  // The same in JSON: valid (Debian's Python reads it), the matching and each surface.
  const CommandResult json = run("compare " + apart + " " + renumbered + " --json");
  ASSERT_EQ(json.code, 0) << json.output;
  EXPECT_NE(json.output.find("\"materials_matched\": \"by name: AFTER's 10 is 2, 20 is 1\""),
            std::string::npos)
      << json.output;
  EXPECT_NE(json.output.find("{\"inner\": 2, \"outer\": \"outside\", \"moved\": 0, "
                             "\"euler_before\": 2, \"euler_after\": 2}"),
            std::string::npos)
      << json.output;
  const std::string json_path = out_dir() + "/compare.json";
  std::ofstream(json_path) << json.output.substr(json.output.find('{'));
  if (std::filesystem::exists("/usr/bin/python3")) {
    const std::string check =
        "/usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' ";
    EXPECT_EQ(std::system((check + json_path).c_str()), 0) << json.output;
  }

  // A file without names: by id, and the output says why.
  const std::string unnamed = out_dir() + "/apart_unnamed.mesh";
  ASSERT_TRUE(write_mesh(unnamed, mesh));
  const CommandResult plain = run("compare " + apart + " " + unnamed);
  EXPECT_NE(plain.output.find("materials matched by id (AFTER does not name them)"),
            std::string::npos)
      << plain.output;

  // Names BEFORE does not have: by id, and said (it said "by name" with none matched).
  ASSERT_TRUE(read_mesh(apart, &mesh));
  const std::string renamed = out_dir() + "/apart_renamed.msh";
  const std::pair<std::vector<MaterialName>, const char*> cases[] = {
      {{{1, "Shell2"}, {2, "core"}},
       "materials matched by name; by id, names BEFORE does not have: 1 'Shell2'\n"},
      {{{1, "Shell2"}, {2, "Core2"}},
       "materials matched by id (no name of AFTER's is one of BEFORE's); names BEFORE does not "
       "have: 1 'Shell2', 2 'Core2'\n"}};
  for (const auto& [after_names, expected] : cases) {
    names = after_names;
    ASSERT_TRUE(write_mesh(renamed, mesh, options));
    const CommandResult r2 = run("compare " + apart + " " + renamed);
    EXPECT_NE(r2.output.find(expected), std::string::npos) << r2.output;
  }
}

// `tetlod lod` says what the level it writes breaks of the thresholds saved in the
// history: at the last level, what `simplify` said of its final mesh; at the first,
// more (after a run past the valence, nodes subdivision took past it among them).
TEST(Cli, LodSaysWhatTheLevelBreaks) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string history = out_dir() + "/breaks.tlh", level = out_dir() + "/breaks.mesh";
  const CommandResult r = run("simplify " + motor + " -o " + level +
                              " --size 18 --tolerance 0.05 " + "--history " + history);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string head = "final mesh, breaking a threshold: ";
  const size_t at = r.output.find(head);
  ASSERT_NE(at, std::string::npos) << r.output;
  const size_t end = r.output.find(" (", at);
  const std::string breaks = r.output.substr(at + head.size(), end - at - head.size());
  ASSERT_NE(breaks.find(" above the valence"), std::string::npos) << breaks;
  const std::string line = "this level, breaking the thresholds saved in the history: ";
  const CommandResult last = run("lod " + history + " --step 1000000 -o " + level);
  ASSERT_EQ(last.code, 0) << last.output;
  EXPECT_NE(last.output.find(line + breaks + "\n"), std::string::npos) << breaks << "\n"
                                                                       << last.output;
  const CommandResult first = run("lod " + history + " --step 0 -o " + level);
  ASSERT_EQ(first.code, 0) << first.output;
  ASSERT_NE(first.output.find(line), std::string::npos) << first.output;
  auto nodes_above = [](const std::string& text) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(text, m, std::regex("([0-9]+) nodes? above the valence")))
        << text;
    return m.empty() ? 0ul : std::stoul(m[1]);
  };
  EXPECT_GT(nodes_above(first.output), nodes_above(breaks));
}

// --check: simplify and lod exit with status 3 where the mesh written breaks a
// threshold (the motor's input has tets below the default stretch 0.15), and write it
// all the same; 0 where nothing is broken (stretch 0.05). lod checks the level written
// against the history's thresholds (its first level breaks the valence).
TEST(Cli, SimplifyAndLodCheckWhatTheyWrite) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const std::string out = out_dir() + "/check.mesh", history = out_dir() + "/check.tlh";
  fs::remove(out);
  CommandResult r = run("simplify " + motor + " -o " + out + " --size 12 --tolerance 0.05 --check");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_NE(r.output.find("tetlod simplify: --check: " + out + " breaks a threshold: "),
            std::string::npos)
      << r.output;
  r = run("simplify " + motor + " -o " + out + " --size 12 --tolerance 0.05 --stretch 0.05" +
          " --history " + history + " --check");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("--check"), std::string::npos) << r.output;
  EXPECT_EQ(run("lod " + history + " --step 1000000 -o " + out + " --check").code, 0);
  r = run("lod " + history + " --step 0 -o " + out + " --check");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("tetlod lod: --check: " + out + " breaks a threshold: "),
            std::string::npos)
      << r.output;
  // The same for the level nearest a number of elements, written by simplify itself
  // (past the count: the first level).
  r = run("simplify " + motor + " -o " + out + " --size 12 --tolerance 0.05 --stretch 0.05" +
          " --elements 100000000 --check");
  EXPECT_EQ(r.code, 3) << r.output;
}

// The simplifier's candidate kernels run on AVX2 where the processor has it, else on
// the baseline instruction set (forced by TETLOD_NO_AVX2): the two must agree bit for
// bit (same output mesh, same history), with a uniform size (where a run past the
// valence is the result) and with a size field (within it).
TEST(Cli, SimplifyKernelsAgreeBitForBit) {
  const std::string motor = std::string(TETLOD_SOURCE_DIR) + "/assets/motor.mesh";
  const char* settings[] = {
      "--size 12 --tolerance 0.05",
      "--size 12 --tolerance 0.05 --size-field axis:0,0,0,0,0,1,3,0.3 --within-valence"};
  int n = 0;
  for (const char* flags : settings) {
    std::string out[2], history[2];
    for (int forced = 0; forced < 2; ++forced) {
      const std::string name =
          out_dir() + "/kernels_" + std::to_string(n) + "_" + std::to_string(forced);
      out[forced] = name + ".mesh";
      history[forced] = name + ".tlh";
      const CommandResult r = run("simplify " + motor + " -o " + out[forced] + " --history " +
                                      history[forced] + " " + flags,
                                  forced ? "TETLOD_NO_AVX2=1" : "");
      ASSERT_EQ(r.code, 0) << r.output;
      if (forced) {
        EXPECT_NE(r.output.find("(baseline kernels)"), std::string::npos) << r.output;
      }
      // The threshold line says whether a size field lowers the uniform size, and how
      // many rules it has.
      const std::string size_line =
          n == 0 ? "thresholds: size 12, stretch"
                 : "thresholds: size 12, less where the local sizing asks (1 region rule), stretch";
      EXPECT_NE(r.output.find(size_line), std::string::npos) << r.output;
      if (n == 0) {
        EXPECT_NE(r.output.find(", so it is the result"), std::string::npos) << r.output;
      } else {
        // The bundled motor is coarse: within the valence, some of its long edges cannot
        // be split, and the output says so, with both reasons.
        EXPECT_NE(r.output.find("why: these tets hold edges longer than half the size that "
                                "subdivision left unsplit"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("would have raised a node's valence"), std::string::npos);
      }
    }
    const std::string mesh = file_bytes(out[0]);
    EXPECT_GT(mesh.size(), 1000u);
    EXPECT_TRUE(mesh == file_bytes(out[1])) << flags;
    EXPECT_TRUE(file_bytes(history[0]) == file_bytes(history[1])) << flags;
    ++n;
  }
}

// A stale queue entry or a sweep skips an evaluation already made on the mesh as it
// is (its result is known). Making every one of them again (TETLOD_REPEAT_EVALUATIONS)
// must give the same mesh and history, byte for byte: here with a uniform size, a size
// field and material sizes, on the motor and the spheres.
TEST(Cli, SkippedRepeatEvaluationsChangeNothing) {
  const std::string assets = std::string(TETLOD_SOURCE_DIR) + "/assets/";
  const char* settings[] = {
      "motor.mesh --size 8 --tolerance 0.05",
      "motor.mesh --size 14 --tolerance 0.05 --size-field axis:0,0,0,0,0,1,3,0.3",
      "motor.mesh --size 20 --tolerance 0.05 --material-size 1=20,2=4,3=10,4=10,5=6,6=10,7=10",
      "spheres.mesh --size 30 --tolerance 0.05 --size-field radial:0,0,0,2,0.3"};
  int n = 0;
  for (const char* flags : settings) {
    std::string out[2], history[2];
    for (int repeat = 0; repeat < 2; ++repeat) {
      const std::string name =
          out_dir() + "/repeats_" + std::to_string(n) + "_" + std::to_string(repeat);
      out[repeat] = name + ".mesh";
      history[repeat] = name + ".tlh";
      const CommandResult r =
          run("simplify " + assets + flags + " -o " + out[repeat] + " --history " + history[repeat],
              repeat ? "TETLOD_REPEAT_EVALUATIONS=1" : "");
      ASSERT_EQ(r.code, 0) << r.output;
      const size_t at = r.output.find(" more not made again");
      ASSERT_NE(at, std::string::npos) << r.output;
      const size_t from = r.output.rfind(' ', at - 1) + 1;
      const long long skipped = std::stoll(r.output.substr(from, at - from));
      if (repeat) {
        EXPECT_EQ(skipped, 0) << flags;
      } else {
        EXPECT_GT(skipped, 0) << flags;
      }
    }
    EXPECT_GT(file_bytes(out[0]).size(), 1000u);
    EXPECT_TRUE(file_bytes(out[0]) == file_bytes(out[1])) << flags;
    EXPECT_TRUE(file_bytes(history[0]) == file_bytes(history[1])) << flags;
    ++n;
  }
}

TEST(Cli, SolveSpheresPrintsCapacitanceAndWritesTheField) {
  const std::string spheres = std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh";
  const std::string field = out_dir() + "/spheres_field.vtu";
  fs::remove(field);
  const CommandResult help = run("solve --help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.output.find("usage: tetlod solve"), std::string::npos);
  const CommandResult r =
      run("solve " + spheres + " --conductor 1=1 --ground 4 --eps 2=2,3=5 -o " + field);
  ASSERT_EQ(r.code, 0) << r.output;
  // --vtk-binary: the same field in raw appended data.
  const std::string binary_field = out_dir() + "/spheres_field_binary.vtu";
  const CommandResult b =
      run("solve " + spheres + " --conductor 1=1 --ground 4 -o " + binary_field + " --vtk-binary");
  ASSERT_EQ(b.code, 0) << b.output;
  EXPECT_NE(read_file(binary_field).find("Name=\"potential\" format=\"appended\""),
            std::string::npos);
  // The committed asset's value (direct solver); the exact sphere value is 44.36.
  EXPECT_NE(r.output.find("capacitance  C = 46.9104"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("energy       W = 23.4552"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("time "), std::string::npos);
  // Two conductors at two potentials need no ground: the outer sphere at 0 V is the
  // same problem.
  const CommandResult two = run("solve " + spheres + " --conductor 1=1,4=0 --eps 2=2,3=5");
  ASSERT_EQ(two.code, 0) << two.output;
  EXPECT_NE(two.output.find("capacitance  C = 46.9104"), std::string::npos) << two.output;
  const CommandResult one = run("solve " + spheres + " --conductor 1=1 --eps 2=2,3=5");
  EXPECT_EQ(one.code, 2) << one.output;
  EXPECT_NE(one.output.find("--ground (or conductors at two potentials)"), std::string::npos)
      << one.output;
  // cg's options where auto takes the direct solver (886 unknowns) are said to be unused;
  // with --solver direct, or --vtk-binary with no field file, they are usage errors.
  const CommandResult unused =
      run("solve " + spheres + " --conductor 1=1 --ground 4 --preconditioner ic");
  ASSERT_EQ(unused.code, 0) << unused.output;
  EXPECT_NE(unused.output.find("(auto chose it for this size: --preconditioner and --tolerance "
                               "are for cg, --solver cg to use them)"),
            std::string::npos)
      << unused.output;
  for (const char* flags : {"--solver direct --tolerance 1e-8", "--vtk-binary"}) {
    const CommandResult bad = run("solve " + spheres + " --conductor 1=1 --ground 4 " + flags);
    EXPECT_EQ(bad.code, 2) << flags << "\n" << bad.output;
  }
  std::ifstream file(field);
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("<PointData Scalars=\"potential\">"), std::string::npos);
  EXPECT_NE(text.find("Name=\"field magnitude\""), std::string::npos);
  // The field file reads back as a mesh (our reader skips the extra arrays).
  const CommandResult stats = run("stats --json " + field);
  EXPECT_EQ(stats.code, 0) << stats.output;
  EXPECT_NE(stats.output.find("\"elements\": 16088"), std::string::npos);
  // The iterative solver agrees to many digits.
  const CommandResult cg =
      run("solve " + spheres + " --conductor 1=1 --ground 4 --eps 2=2,3=5 --solver cg");
  ASSERT_EQ(cg.code, 0) << cg.output;
  EXPECT_NE(cg.output.find("capacitance  C = 46.9104"), std::string::npos) << cg.output;
  EXPECT_NE(cg.output.find("iterations"), std::string::npos) << cg.output;
}

// A conductor or ground given by the name of one of the input's surface groups holds
// that surface's nodes: the spheres with the inner sphere's surface at 1 and the outer
// one's at 0 is the problem with materials 1 and 4 held, the same capacitance to the
// last printed digit. A name that is neither a material's nor a surface group's lists
// the groups; a surface given twice, or held at two potentials, is an error.
TEST(Cli, SolveHoldsSurfaceGroups) {
  const std::string spheres = std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh";
  const std::string msh = out_dir() + "/spheres_groups.msh";
  ASSERT_EQ(run("convert " + spheres + " -o " + msh + " --surfaces").code, 0);
  const auto capacitance = [](const std::string& output) {
    const size_t at = output.find("capacitance  C = ");
    return at == std::string::npos ? std::string()
                                   : output.substr(at, output.find(' ', at + 17) - at);
  };
  const CommandResult materials =
      run("solve " + msh + " --conductor 1=1 --ground 4 --eps 2=2,3=5 --solver direct");
  ASSERT_EQ(materials.code, 0) << materials.output;
  const CommandResult surfaces = run("solve " + msh +
                                     " --conductor interface_1_2=1 --ground interface_3_4"
                                     " --eps 2=2,3=5 --solver direct");
  ASSERT_EQ(surfaces.code, 0) << surfaces.output;
  ASSERT_FALSE(capacitance(materials.output).empty()) << materials.output;
  EXPECT_EQ(capacitance(surfaces.output), capacitance(materials.output)) << surfaces.output;
  // Fewer nodes held: material 1's and 4's inner nodes are unknowns now.
  EXPECT_NE(surfaces.output.find("unknowns     1680 (1389 nodes held)"), std::string::npos)
      << surfaces.output;
  const CommandResult unknown = run("solve " + msh + " --conductor nope=1 --ground 4");
  EXPECT_EQ(unknown.code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("nor is it a surface group (the input's: boundary_4, "
                                "interface_1_2, interface_2_3, interface_3_4)"),
            std::string::npos)
      << unknown.output;
  const CommandResult twice =
      run("solve " + msh + " --conductor interface_1_2=1 --ground interface_1_2");
  EXPECT_EQ(twice.code, 2) << twice.output;
  EXPECT_NE(twice.output.find("surface 'interface_1_2' is given more than once"), std::string::npos)
      << twice.output;
  const CommandResult touching = run("solve " + msh + " --conductor interface_1_2=1 --ground 2");
  EXPECT_EQ(touching.code, 1) << touching.output;
  EXPECT_NE(touching.output.find("conductor surface 'interface_1_2' (held at 1) touches "
                                 "material 2 (held at 0)"),
            std::string::npos)
      << touching.output;
}

// --solver direct on a mesh of more than 20000 nodes says, before it starts, that its
// time grows as the square of the unknowns (a user forced it on 280,000 and waited ten
// minutes); below that, and with auto, nothing. (The conductors here touch the ground,
// an error found before any factoring: the note is about the choice, made first.)
TEST(Cli, DirectSolverOnALargeMeshIsNoted) {
  const auto write = [](int cells, const std::string& name) {
    const TetMesh mesh = test::make_grid_mesh(
        cells, cells, cells, [cells](int i, int, int) { return i < cells / 2 ? 1 : 2; }, 0.5);
    const std::string path = out_dir() + "/" + name;
    EXPECT_TRUE(write_mesh(path, mesh).ok());
    return path;
  };
  const std::string large = write(27, "direct_large.mesh");  // 28^3 = 21952 nodes
  const std::string small = write(26, "direct_small.mesh");  // 27^3 = 19683
  const std::string note =
      "note: --solver direct on 21952 nodes: its time grows about as the "
      "square of the unknowns";
  const CommandResult forced =
      run("solve " + large + " --conductor 1=1 --ground 2 --solver direct");
  EXPECT_NE(forced.output.find(note), std::string::npos) << forced.output;
  EXPECT_NE(forced.output.find("touches material 2"), std::string::npos) << forced.output;
  for (const std::string& command :
       {"solve " + large + " --conductor 1=1 --ground 2",
        "solve " + small + " --conductor 1=1 --ground 2 --solver direct"}) {
    const CommandResult quiet = run(command);
    EXPECT_EQ(quiet.output.find("--solver direct on"), std::string::npos) << quiet.output;
    EXPECT_NE(quiet.output.find("touches material 2"), std::string::npos) << quiet.output;
  }
}

TEST(Cli, SolveBadValuesNameTheFlagAndValue) {
  const std::string path = write_grid("solve.mesh");  // materials 1 (x < 1) and 2
  const std::string field = out_dir() + "/solve_bad.vtu";
  fs::remove(field);
  struct Case {
    const char* flags;
    int code;
    const char* message;
  };
  const Case cases[] = {
      {"--conductor 1=abc --ground boundary", 2, "--conductor '1=abc'"},
      {"--conductor 1 --ground boundary", 2, "'1' is not MATERIAL=NUMBER"},
      {"--conductor -3=1 --ground boundary", 2, "'-3=1'"},
      // Not a whole number: a name ("2 pole magnet" is one), which the mesh lacks.
      {"--conductor 1=1 --ground 1.5", 2, "--ground: the mesh has no material named '1.5'"},
      {"--conductor 1=1 --ground -2", 2, "--ground '-2'"},
      // A name is looked up in the mesh, which names no material.
      {"--conductor 1=1 --ground somewhere", 2,
       "--ground: the mesh has no material named 'somewhere' (its materials have no names"},
      {"--conductor 1=1 --ground boundary --eps 2=nan", 2, "--eps '2=nan'"},
      {"--conductor 1=1 --ground boundary --solver magic", 2, "--solver 'magic'"},
      {"--conductor 1=1 --ground boundary --tolerance 2", 2, "--tolerance '2'"},
      // CG cannot reach it in double precision: it would break down, not converge.
      {"--conductor 1=1 --ground boundary --solver cg --tolerance 1e-300", 2,
       "--tolerance '1e-300' is not a number in [1e-14, 1)"},
      {"--conductor 1=1", 2, "need MESH, --conductor and --ground"},
      {"--conductor 1=1 --ground boundary -o field.txt", 2, "written as .vtu only"},
      // Values out of range, or of materials the mesh lacks: bad usage too (they were
      // 1, as for a bad mesh; found by a hostile-input test).
      {"--conductor 7=1 --ground boundary", 2, "conductor material 7 does not exist"},
      {"--conductor 1=1 --ground 2 --eps 2=0", 2, "permittivity of material 2 is 0"},
      // Beyond these the energy overflowed ("a non-finite solution", naming nothing).
      {"--conductor 1=1e308 --ground boundary", 2,
       "potential 1e+308 is not a number in [-1e30, 1e30]"},
      {"--conductor 1=1e-170 --ground boundary", 2,
       "potential 9.9999999999999998e-171 is too small: give 0, or a magnitude of at least 1e-30"},
      {"--conductor 1=1 --ground boundary --eps 2=1e300", 2,
       "permittivity of material 2 is 1.0000000000000001e+300, not a number in [1e-30, 1e30]"},
      // The problem on this mesh: a conductor touching the ground.
      {"--conductor 1=1 --ground 2", 1, "conductor material 1 (held at 1) touches material 2"},
      {"--conductor 1=1 --ground boundary", 1, "touches the grounded outer boundary"},
  };
  for (const Case& c : cases) {
    const bool has_output = std::string(c.flags).find("-o ") != std::string::npos;
    const CommandResult r =
        run("solve " + path + " " + c.flags + (has_output ? "" : " -o " + field));
    EXPECT_EQ(r.code, c.code) << c.flags << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.flags << "\n" << r.output;
    EXPECT_FALSE(fs::exists(field)) << c.flags;
  }
}

// An output given twice, or an option where a file should be, is a usage error that
// says so (it used to take the last file, or read "--size" as the output's name).
TEST(Cli, OutputsAreGivenOnce) {
  const std::string in = write_grid("once.mesh");
  const std::string a = out_dir() + "/once_a.mesh", b = out_dir() + "/once_b.mesh";
  for (const std::string& args :
       {"simplify " + in + " -o " + a + " -o " + b + " --size 2",
        "simplify " + in + " -o " + a + " --size 2 --history " + out_dir() + "/h1.tlh --history " +
            out_dir() + "/h2.tlh",
        "generate box2 -o " + a + " -o " + b,
        "render " + in + " -o " + out_dir() + "/a.png -o " + out_dir() + "/b.png",
        "solve " + in + " --conductor 1=1 --ground boundary -o " + out_dir() + "/a.vtu -o " +
            out_dir() + "/b.vtu"}) {
    const CommandResult r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(" once ("), std::string::npos) << r.output;
  }
  CommandResult r = run("simplify " + in + " -o --size 2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("-o needs a value, not the option '--size'"), std::string::npos)
      << r.output;
  r = run("simplify " + in + " --history -o " + a + " --size 2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--history needs a value, not the option '-o'"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(a));
  EXPECT_FALSE(fs::exists(b));
}

// The line of `text` from the first `what` on ("" if none).
std::string line_with(const std::string& text, const std::string& what) {
  const size_t at = text.find(what);
  return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
}

// The capacitance line of `tetlod solve MESH FLAGS` (which must succeed).
std::string capacitance_of(const std::string& mesh, const std::string& flags) {
  const CommandResult r = run("solve " + mesh + " " + flags);
  EXPECT_EQ(r.code, 0) << r.output;
  return line_with(r.output, "capacitance");
}

// The coax's conductors, ground and dielectric by id (tests/data/gmsh/coax_part3.msh).
constexpr const char* kCoaxById = "--conductor 1=1 --ground 4 --eps 2=3";

// Where an option takes a material, the input's name for it does as well as its
// id: the same capacitance, the same simplified mesh, the same picture.
TEST(Cli, MaterialsByName) {
  const std::string coax = std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax_part3.msh";
  const std::string by_id = capacitance_of(coax, kCoaxById);
  EXPECT_NE(by_id, "");
  EXPECT_EQ(capacitance_of(
                coax, "--conductor inner_conductor=1 --ground SHIELD --eps dielectric_inner=3"),
            by_id);

  const std::string a = out_dir() + "/by_id.mesh", b = out_dir() + "/by_name.mesh";
  ASSERT_EQ(run("simplify " + coax + " -o " + a + " --size 2 --material-size 4=0.5,1=0.4").code, 0);
  ASSERT_EQ(
      run("simplify " + coax + " -o " + b + " --size 2 --material-size shield=0.5,1=0.4").code, 0);
  EXPECT_EQ(read_file(a), read_file(b));
  // Blanks around the items, as typed after a comma, are not part of the names.
  ASSERT_EQ(
      run("simplify " + coax + " -o " + b + " --size 2 --material-size 'shield=0.5, 1=0.4'").code,
      0);
  EXPECT_EQ(read_file(a), read_file(b));
  EXPECT_EQ(capacitance_of(coax,
                           "--conductor ' inner_conductor=1' --ground ' SHIELD' "
                           "--eps 'dielectric_inner=3 '"),
            by_id);

  // Unknown names list the names there are; a name and an id of one material clash.
  CommandResult r = run("solve " + coax + " --conductor copper=1 --ground 4");
  EXPECT_EQ(r.code, 2) << r.output;  // as simplify's --material-size
  EXPECT_NE(r.output.find("--conductor: the mesh has no material named 'copper' (its names: 1 "
                          "inner_conductor, 2 dielectric_inner, 3 dielectric_outer, 4 shield)"),
            std::string::npos)
      << r.output;
  r = run("simplify " + coax + " -o " + a + " --size 2 --material-size shield=0.5,4=0.4");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("material 4 (shield) is given twice"), std::string::npos) << r.output;
  r = run("simplify " + write_grid("unnamed.mesh") + " -o " + a +
          " --size 2 --material-size air=1");
  EXPECT_NE(r.output.find("its materials have no names: give their numbers"), std::string::npos)
      << r.output;
}

// A material name may hold commas (and '='): in a MATERIAL=VALUE list a piece without
// '=' joins the next, so the name needs no escape; in a list of names, "\\," is a comma.
TEST(Cli, MaterialNamesWithCommas) {
  std::string text = read_file(std::string(TETLOD_SOURCE_DIR) + "/tests/data/gmsh/coax_part3.msh");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"\"inner_conductor\"", "\"inner, Cu=OFHC\""},
        {"\"shield\"", "\"shield, braided (Cu)\""}}) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const std::string coax = out_dir() + "/commas.msh";
  std::ofstream(coax) << text;
  const std::string by_id = capacitance_of(coax, kCoaxById);
  EXPECT_NE(by_id, "");
  EXPECT_EQ(capacitance_of(coax,
                           "--conductor 'inner, Cu=OFHC=1' --ground 'shield\\, braided (Cu)' "
                           "--eps 2=3"),
            by_id);

  const std::string a = out_dir() + "/commas_id.mesh", b = out_dir() + "/commas_name.mesh";
  ASSERT_EQ(run("simplify " + coax + " -o " + a + " --size 2 --material-size 4=0.5,1=0.4").code, 0);
  const CommandResult named = run("simplify " + coax + " -o " + b +
                                  " --size 2 --material-size 'shield, braided (Cu)=0.5, inner, "
                                  "Cu=OFHC=0.4'");
  ASSERT_EQ(named.code, 0) << named.output;
  EXPECT_EQ(read_file(a), read_file(b));
  // Without the escape, a list of names splits the name: the error says how to write it.
  const CommandResult split =
      run("solve " + coax + " --conductor 1=1 --ground 'shield, braided (Cu)' --eps 2=3");
  EXPECT_EQ(split.code, 2) << split.output;
  EXPECT_NE(split.output.find("in a list of names, a comma in a name is written \\,"),
            std::string::npos)
      << split.output;
  // A last item without '=' is still an error that names it.
  const CommandResult bad = run("simplify " + coax + " -o " + b +
                                " --size 2 --material-size 'shield, braided (Cu)=0.5,1'");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("'1' is not of the form MATERIAL=SIZE"), std::string::npos)
      << bad.output;
}

// A tolerance finer than the rounding of coordinates far from the origin cannot hold:
// a note says so (an outside tester's mesh 2e6 from the origin moved 1.3e-10 at
// --tolerance 1e-12); near the origin, none.
TEST(Cli, ATolerancePastTheCoordinatesRoundingIsNoted) {
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh).ok());
  const std::string near = out_dir() + "/near.mesh", far = out_dir() + "/far.mesh";
  ASSERT_TRUE(write_mesh(near, mesh).ok());
  for (Vec3& p : mesh.positions) p = p + Vec3{1e6, -2e6, 3e5};
  ASSERT_TRUE(write_mesh(far, mesh).ok());
  const std::string flags = " -o " + out_dir() + "/tol_out.mesh --size 0.5 --tolerance 1e-12";
  const CommandResult f = run("simplify " + far + flags);
  ASSERT_EQ(f.code, 0) << f.output;
  EXPECT_NE(f.output.find("note: --tolerance 1e-12 is finer than the rounding of the mesh's "
                          "coordinates (about 1.8e-09, 2e+06 from the origin)"),
            std::string::npos)
      << f.output;
  const CommandResult n = run("simplify " + near + flags);
  ASSERT_EQ(n.code, 0) << n.output;
  EXPECT_EQ(n.output.find("finer than the rounding"), std::string::npos) << n.output;
}

// What the reader repaired, in words that agree with the count.
TEST(Cli, RepairNotesCountInWords) {
  const std::string path = out_dir() + "/repaired.mesh";
  // `stats` of a Medit file with these vertex and tetrahedron sections.
  const auto stats = [&](const std::string& vertices, const std::string& tets) {
    std::ofstream(path) << "MeshVersionFormatted 2\nDimension 3\nVertices\n"
                        << vertices << "Tetrahedra\n"
                        << tets << "End\n";
    return run("stats " + path);
  };
  const auto expect_notes = [](const CommandResult& r, std::initializer_list<const char*> notes) {
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* note : notes) EXPECT_NE(r.output.find(note), std::string::npos) << r.output;
  };
  // One tet, negatively oriented, and a vertex no tet uses.
  expect_notes(stats("5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n9 9 9 0\n", "1\n1 3 2 4 1\n"),
               {"note: 1 negatively oriented tetrahedron was reoriented",
                "note: 1 vertex used by no tetrahedron was dropped"});
  expect_notes(stats("7\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 0\n8 8 8 0\n9 9 9 0\n",
                     "2\n1 3 2 4 1\n2 4 3 5 1\n"),
               {"note: 2 negatively oriented tetrahedra were reoriented",
                "note: 2 vertices used by no tetrahedron were dropped"});
  // Two tets meshed apart that touch at a face: its three vertices are there twice.
  expect_notes(stats("8\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                     "1 1 1 0\n",
                     "2\n1 2 3 4 1\n5 7 6 8 2\n"),
               {"note: 3 vertices are at the position of another (the first at (",
                "the mesh is not conforming there"});
}

// Writes `mesh` as Medit text: tet t (0-based) on line 71 + t when it has 64 vertices.
void write_medit_text(const std::string& path, const TetMesh& mesh) {
  std::ofstream out(path);
  out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << mesh.positions.size() << "\n";
  for (const Vec3& p : mesh.positions) out << p.x << " " << p.y << " " << p.z << " 0\n";
  out << "Tetrahedra\n" << mesh.tets.size() << "\n";
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const Tet& q = mesh.tets[t];
    out << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << " "
        << mesh.materials[t] << "\n";
  }
  out << "End\n";
}

// A tet whose vertex number is wrong reaches across the mesh, through other tets: the
// file is refused with that tet's line, and `convert` writes nothing.
TEST(Cli, OverlappingTetsAreRefusedWithTheirLine) {
  TetMesh grid = test::make_grid_mesh(3, 3, 3, [](int, int, int) { return 1; });
  ASSERT_EQ(grid.positions.size(), 64u);
  grid.tets[0][3] = 63;  // (1, 1, 1) -> (3, 3, 3)
  const std::string path = out_dir() + "/reaching.mesh", out = out_dir() + "/reaching.vtu";
  write_medit_text(path, grid);
  fs::remove(out);
  const CommandResult r = run("convert " + path + " -o " + out);
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_FALSE(fs::exists(out));
  const size_t at = r.output.find(path + ":");
  ASSERT_NE(at, std::string::npos) << r.output;
  unsigned line = 0, n = 0, m = 0;
  ASSERT_EQ(std::sscanf(r.output.c_str() + at + path.size(),
                        ":%u: tetrahedron %u overlaps tetrahedron %u", &line, &n, &m),
            3)
      << r.output;
  EXPECT_EQ(line, 70 + n);
  EXPECT_TRUE(n == 1 || m == 1) << r.output;  // the tet that reaches across is one of them
}

// A valid mesh on which the check for overlapping tets stops early says so.
TEST(Cli, AnOverlapCheckCutShortIsNoted) {
  const std::string path = out_dir() + "/star.mesh";
  write_medit_text(path, test::make_needle_star(1500, 3));
  const CommandResult r = run("stats " + path);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find(path + ": note: the check for tetrahedra that overlap with no face "
                                 "between them stopped early"),
            std::string::npos)
      << r.output;
}

// A signal between the renames that put a command's files in place ends the process
// only once they are all in place: strace delivers SIGINT at the second rename of a
// .node/.ele/.face triple, which held the new .node beside the old .ele and .face.
TEST(Cli, ASignalBetweenTheRenamesWaitsForTheLast) {
  if (!test::on_path("strace") ||
      std::system("strace -o /dev/null -e trace=none true >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no strace, or it may not trace here (ptrace)";
  const std::string dir = out_dir() + "/signal_renames";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string box2 = std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh";
  const std::string spheres = std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh";
  ASSERT_EQ(run("convert " + box2 + " " + dir + "/out.node --surfaces").code, 0);
  const CommandResult r =
      run("convert " + spheres + " " + dir + "/out.node --surfaces",
          "strace -f -o /dev/null -e trace=rename -e inject=rename:signal=SIGINT:when=2");
  EXPECT_NE(r.code, 0) << r.output;  // ended by the signal, after the renames
  TetMesh expected, written;
  ReadInfo expected_info, written_info;
  ASSERT_TRUE(read_mesh(spheres, &expected, &expected_info).ok());
  const Status s = read_mesh(dir + "/out.node", &written, &written_info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(written.tet_count(), expected.tet_count());
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(expected, &groups).ok());
  EXPECT_EQ(written_info.surface_groups.size(), groups.groups.size());
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
}

// Ctrl-C, `timeout` or a closed terminal while an output is being written: the
// process ends as the signal ends it, and its temporary file goes with it.
TEST(Cli, ASignalDuringAWriteLeavesNoTemporary) {
  const std::string dir = out_dir() + "/signal";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // 384,000 tets: making their ASCII .vtk takes a good part of a second, then the text
  // goes to a temporary, which is renamed.
  const std::string in = dir + "/in.mesh", out = dir + "/out.vtk";
  ASSERT_TRUE(
      write_mesh(in, test::make_grid_mesh(40, 40, 40, [](int, int, int) { return 1; })).ok());
  const auto temporaries = [&] {
    size_t n = 0;
    for (const auto& entry : fs::directory_iterator(dir))
      n += entry.path().filename().string().find(".tmp") != std::string::npos;
    return n;
  };
  // What the write makes when nothing stops it. The temporary is written from text
  // already made, in a few milliseconds: on a loaded machine the signal may come after
  // the file is complete (then it must be the whole file), so each signal is tried up
  // to five times until one comes during the write.
  const std::string reference = dir + "/reference.vtk";
  ASSERT_EQ(run("convert " + in + " " + reference).code, 0);
  const std::string expected = read_file(reference);
  ASSERT_FALSE(expected.empty());
  for (const int signal_number : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(signal_number);
    bool during_the_write = false;
    for (int attempt = 0; attempt < 5 && !during_the_write; ++attempt) {
      SCOPED_TRACE(attempt);
      const pid_t pid = fork();
      ASSERT_GE(pid, 0);
      if (pid == 0) {
        execl(TETLOD_BINARY, "tetlod", "convert", in.c_str(), out.c_str(), nullptr);
        _exit(127);
      }
      // Wait for the temporary to appear, then stop the process.
      const auto start = std::chrono::steady_clock::now();
      int status = 0;
      bool ended = false;
      while (temporaries() == 0 &&
             std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
        if ((ended = waitpid(pid, &status, WNOHANG) == pid)) break;
      if (ended) {
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
      } else {
        kill(pid, signal_number);
        ASSERT_EQ(waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << status;
        EXPECT_EQ(WTERMSIG(status), signal_number);
      }
      EXPECT_EQ(temporaries(), 0u);
      if (fs::exists(out)) {  // the write ended first: the whole file, or nothing
        EXPECT_EQ(read_file(out), expected);
        fs::remove(out);
        continue;
      }
      during_the_write = !ended;
    }
    EXPECT_TRUE(during_the_write) << "no signal came during the write in five runs";
  }
  fs::remove(reference);
  // A signal the caller ignores (nohup) stays ignored: the run goes on and writes.
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    signal(SIGHUP, SIG_IGN);
    execl(TETLOD_BINARY, "tetlod", "convert", in.c_str(), out.c_str(), nullptr);
    _exit(127);
  }
  int status = 0;
  bool ended = false;
  const auto start = std::chrono::steady_clock::now();
  while (temporaries() == 0 && std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    if ((ended = waitpid(pid, &status, WNOHANG) == pid)) break;
  if (!ended) {
    kill(pid, SIGHUP);
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
  }
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_EQ(temporaries(), 0u);
}

}  // namespace
}  // namespace tetlod
