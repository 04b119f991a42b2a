// tetlod: the command-line tool.
#include <signal.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "app/cli_util.h"
#include "app/commands.h"
#include "core/io/output_files.h"

namespace {

constexpr const char* kUsage =
    "usage: tetlod COMMAND [ARGS...]\n"
    "\n"
    "commands:\n"
    "  stats FILE [--json]              mesh properties (the paper's Table I row) and a\n"
    "                                   stretch histogram, whole mesh and per material\n"
    "  compare BEFORE AFTER [--check]   each material's volume and pieces, how far each\n"
    "                                   interface moved and its Euler characteristic,\n"
    "                                   between two meshes (any tools')\n"
    "  convert IN OUT [--msh-version V] convert between .mesh .meshb .msh .node/.ele .vtk\n"
    "                                   .vtu .bdf/.nas .inp (--surfaces: with boundary groups)\n"
    "  generate MODEL -o FILE           make a bundled model (motor, spheres, box2) with TetGen\n"
    "  simplify IN -o OUT --size S ...  subdivide and simplify under the four thresholds\n"
    "                                   (--size, or a local sizing in its place)\n"
    "  lod HISTORY --elements N -o OUT  write a level of a saved collapse history\n"
    "  solve MESH --conductor M=V ...   electrostatic finite-element solve: capacitance, field\n"
    "  render FILE -o SHOT.png ...      draw a mesh offscreen to a PNG (stretch, cut, ...)\n"
    "  report IN -o DIR [...]           HTML report: Table I rows, pictures, histograms\n"
    "  view [FILE] [--script S]         the interactive viewer (a window; needs a display)\n"
    "\n"
    "Run 'tetlod COMMAND --help' for the options of a command, 'tetlod --version' for the\n"
    "version.\n"
    "Exit codes: 0 ok, 1 bad input, 2 bad usage, 3 a --check failed (stats, compare,\n"
    "simplify, lod).\n";

// Ctrl-C, `timeout`, a closed terminal: remove the temporaries of the files being
// written, then end as the signal would have ended the process.
// (During the renames of a commit, it is raised again once they are all made.)
extern "C" void remove_temporaries_and_reraise(int signal_number) {
  if (!tetlod::remove_output_temporaries(signal_number)) return;
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

int run_command(const std::string& command, const tetlod::app::Args& args) {
  using namespace tetlod::app;
  if (command == "stats") return cmd_stats(args);
  if (command == "compare") return cmd_compare(args);
  if (command == "convert") return cmd_convert(args);
  if (command == "generate") return cmd_generate(args);
  if (command == "simplify") return cmd_simplify(args);
  if (command == "lod") return cmd_lod(args);
  if (command == "solve") return cmd_solve(args);
  if (command == "render") return cmd_render(args);
  if (command == "report") return cmd_report(args);
  if (command == "view") return cmd_view(args);
  std::fprintf(stderr, "tetlod: unknown command '%s'\n\n%s", command.c_str(), kUsage);
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tetlod::app;
  // Signals the caller chose to ignore (nohup, a shell's background job) stay ignored.
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
    struct sigaction old_action;
    if (sigaction(signal_number, nullptr, &old_action) != 0 || old_action.sa_handler == SIG_IGN)
      continue;
    struct sigaction action = {};
    action.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&action.sa_mask);
    sigaction(signal_number, &action, nullptr);
  }
  // A closed pipe (tetlod stats big.mesh | head) is a write error, said and exit 1 as a
  // full disk is, not a SIGPIPE that kills the process silently (exit 141).
  std::signal(SIGPIPE, SIG_IGN);
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return kExitUsage;
  }
  const std::string command = argv[1];
  // What went to standard output must have got there (a full disk, a closed pipe).
  const auto written = [&command](int code) {
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      // (The command's own files are complete: each is written whole or not at all.)
      std::fprintf(
          stderr, "tetlod %s: cannot write to standard output: %s%s\n", command.c_str(),
          std::strerror(errno),
          code == kExitOk ? " (the command itself succeeded; any file it wrote is complete)" : "");
      return kExitBadInput;
    }
    return code;
  };
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kUsage, stdout);
    return written(kExitOk);
  }
  if (command == "--version" || command == "version") {
    std::printf(
        "tetlod %s\n"
        "It links TetGen 1.5 (for 'tetlod generate'), so it is covered by the GNU AGPLv3;\n"
        "see the README's Licensing.\n",
        TETLOD_VERSION);
    return written(kExitOk);
  }
  Args args(argv + 2, argv + argc);
  if (!normalize_args(command, &args)) return kExitUsage;
  int code = kExitUsage;
  try {
    code = run_command(command, args);
  } catch (const std::bad_alloc&) {
    // Outputs are staged (core/io/output_files.h): none is half written.
    std::fflush(stdout);
    std::fprintf(stderr,
                 "tetlod %s: out of memory (ask for less: a larger size, fewer elements, or a "
                 "smaller mesh)\n",
                 command.c_str());
    return kExitBadInput;
  }
  return written(code);
}
