// The real `tetlod` binary: exit codes, messages, and the simplify -> lod flow.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/io/mesh_io.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int code = -1;
  std::string output;  // stdout and stderr
};

CommandResult run(const std::string& arguments) {
  CommandResult r;
  const std::string command = std::string(TETLOD_BINARY) + " " + arguments + " 2>&1";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string out_dir() {
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/cli";
  fs::create_directories(dir);
  return dir;
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

TEST(Cli, ConvertKeepsCountsAcrossFormats) {
  const std::string path = write_grid("conv.mesh");
  for (const char* ext : {"msh", "vtu", "vtk", "node", "mesh"}) {
    const std::string target = out_dir() + "/conv_out." + ext;
    const CommandResult c = run("convert " + path + " " + target);
    ASSERT_EQ(c.code, 0) << c.output;
    const CommandResult s = run("stats --json " + target);
    ASSERT_EQ(s.code, 0) << s.output;
    EXPECT_NE(s.output.find("\"elements\": 96"), std::string::npos) << ext;
  }
}

TEST(Cli, SimplifyRejectsAbsurdThresholds) {
  const std::string path = write_grid("thr.mesh");
  const std::string out = out_dir() + "/thr_out.mesh";
  for (const char* flags :
       {"--size -1", "--size nan", "--size 1 --stretch 1", "--size 1 --stretch 0",
        "--size 1 --valence 3", "--size 1 --tolerance -2", "--stretch 0.2",
        "--size 1 --material-size 1=0", "--size 1 --size-field box:0,0,0,1,1"}) {
    const CommandResult r = run("simplify " + path + " -o " + out + " " + flags);
    EXPECT_EQ(r.code, 2) << flags << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
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
  EXPECT_NE(r.output.find("0 of them made by TetLOD"), std::string::npos) << r.output;
  const std::string level = out_dir() + "/simp_level.vtu";
  const CommandResult l = run("lod " + history + " --step 0 -o " + level);
  ASSERT_EQ(l.code, 0) << l.output;
  EXPECT_NE(l.output.find("step 0 of"), std::string::npos);
  std::ofstream(out_dir() + "/junk.tlh") << "not a history";
  const CommandResult junk = run("lod " + out_dir() + "/junk.tlh --step 0 -o " + level);
  EXPECT_EQ(junk.code, 1);
  EXPECT_NE(junk.output.find("junk.tlh"), std::string::npos);
}

}  // namespace
}  // namespace tetlod
