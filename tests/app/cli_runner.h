// Runs the real `tetlod` binary for the command-line tests.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace tetlod::test {

struct CommandResult {
  int code = -1;
  std::string output;  // stdout and stderr
};

// Runs `environment tetlod arguments` through the shell; `environment` may set
// variables (e.g. "TETLOD_GL_BACKEND=none").
inline CommandResult run_tetlod(const std::string& arguments, const std::string& environment = "") {
  CommandResult r;
  const std::string command =
      environment + " " + std::string(TETLOD_BINARY) + " " + arguments + " 2>&1";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A fresh-or-existing directory for one test file's outputs.
inline std::string cli_output_dir(const std::string& name) {
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/" + name;
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace tetlod::test
