// A progress line on stderr while the simplifier works, for the commands that run it
// (`simplify`, `report`, `render --simplify`): only where stderr is a terminal, so
// scripts and logs that read the output see none of it.
#pragma once

#include <chrono>
#include <string>

#include "core/simplify.h"

namespace tetlod::app {

class TerminalProgress {
 public:
  explicit TerminalProgress(const std::string& command);  // "tetlod simplify", say
  ~TerminalProgress() { clear(); }
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  // The callback to give simplify(): rewrites the line at most five times a second
  // (always at a new phase). Empty where stderr is not a terminal.
  ProgressCallback callback();
  // Erases the line, before the command prints what it found.
  void clear();

 private:
  void show(const SimplifyProgress& p);

  std::string command_;
  bool terminal_ = false;
  bool shown_ = false;
  std::string phase_;  // the last shown, with the run it belongs to
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace tetlod::app
