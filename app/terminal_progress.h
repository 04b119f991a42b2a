// A progress line on stderr while a long computation works, for the commands that
// run the simplifier (`simplify`, `report`, `render --simplify`) or the solver
// (`solve`): only where stderr is a terminal, so scripts and logs that read the
// output see none of it.
#pragma once

#include <chrono>
#include <string>

#include "core/electrostatics.h"
#include "core/simplify.h"

namespace tetlod::app {

class TerminalProgress {
 public:
  explicit TerminalProgress(const std::string& command);  // "tetlod simplify", say
  ~TerminalProgress() { clear(); }
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  // The callbacks to give simplify() and solve_electrostatics(): each rewrites the
  // line at most five times a second (always at a new phase). Empty where stderr is
  // not a terminal.
  ProgressCallback simplify_callback();
  SolveProgressCallback solve_callback();
  // Erases the line, before the command prints what it found.
  void clear();

 private:
  // "PHASE N%", ", DETAIL" if not empty, then SUFFIX; cut to the terminal's width, so
  // that it stays on one line, which the next rewrites.
  void show(const std::string& phase, double fraction, const std::string& detail,
            const std::string& suffix = "");

  std::string command_;
  bool terminal_ = false;
  bool shown_ = false;
  std::string phase_;  // the last shown
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace tetlod::app
