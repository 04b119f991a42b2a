// Subcommands of the `tetlod` command-line tool. Each takes the arguments after
// its own name and returns the process exit code.
#pragma once

#include <string>
#include <vector>

namespace tetlod::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;  // a file that cannot be used; out of memory
inline constexpr int kExitUsage = 2;     // a malformed command line or a bad option value
inline constexpr int kExitBreaks = 3;    // stats, compare --check: the check failed

// The exit code of a failed simplify(): a value refused (a threshold; a size that
// would subdivide the mesh past the limit) is a usage error, anything else bad input.
inline int exit_code_of_failed_run(bool bad_value) {
  return bad_value ? kExitUsage : kExitBadInput;
}

using Args = std::vector<std::string>;

int cmd_stats(const Args& args);
int cmd_compare(const Args& args);
int cmd_convert(const Args& args);
int cmd_generate(const Args& args);
int cmd_simplify(const Args& args);
int cmd_lod(const Args& args);
int cmd_solve(const Args& args);
int cmd_render(const Args& args);
int cmd_report(const Args& args);
int cmd_view(const Args& args);  // the interactive viewer (app/viewer.h)

}  // namespace tetlod::app
