// Subcommands of the `tetlod` command-line tool. Each takes the arguments after
// its own name and returns the process exit code.
#pragma once

#include <string>
#include <vector>

namespace tetlod::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;  // a file or value that cannot be used
inline constexpr int kExitUsage = 2;     // a malformed command line
inline constexpr int kExitBreaks = 3;    // stats, compare --check: the check failed

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
