#include "app/terminal_progress.h"

#include <unistd.h>

#include <cstdio>

namespace tetlod::app {

TerminalProgress::TerminalProgress(const std::string& command)
    : command_(command), terminal_(isatty(STDERR_FILENO) == 1) {}

ProgressCallback TerminalProgress::simplify_callback() {
  if (!terminal_) return {};
  return [this](const SimplifyProgress& p) {
    const std::string phase = std::string(p.past_valence ? "past the valence: " : "") + p.phase;
    const bool collapsing = std::string(p.phase) == "simplify";
    show(phase, p.fraction, collapsing ? std::to_string(p.collapses) + " collapses" : "");
  };
}

SolveProgressCallback TerminalProgress::solve_callback() {
  if (!terminal_) return {};
  return [this](const SolveProgress& p) {
    const bool iterating = std::string(p.phase) == "solve";
    show(p.phase, p.fraction, iterating ? "iteration " + std::to_string(p.iteration) : "");
  };
}

void TerminalProgress::show(const std::string& phase, double fraction, const std::string& detail) {
  const auto now = std::chrono::steady_clock::now();
  if (phase == phase_ && now - last_ < std::chrono::milliseconds(200)) return;
  phase_ = phase;
  last_ = now;
  // \r and "erase to the end of the line": the line is rewritten in place.
  std::fprintf(stderr, "\r%s: %s %.0f%%%s%s\033[K", command_.c_str(), phase.c_str(), 100 * fraction,
               detail.empty() ? "" : ", ", detail.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void TerminalProgress::clear() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace tetlod::app
