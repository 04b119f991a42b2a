#include "app/terminal_progress.h"

#include <sys/ioctl.h>
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
    char other[64] = "";  // where the run past the valence on the second thread is
    if (p.other_phase)
      std::snprintf(other, sizeof(other), "; past the valence: %s %.0f%%", p.other_phase,
                    100 * p.other_fraction);
    show(phase, p.fraction, collapsing ? std::to_string(p.collapses) + " collapses" : "", other);
  };
}

SolveProgressCallback TerminalProgress::solve_callback() {
  if (!terminal_) return {};
  return [this](const SolveProgress& p) {
    const bool iterating = std::string(p.phase) == "solve";
    show(p.phase, p.fraction, iterating ? "iteration " + std::to_string(p.iteration) : "");
  };
}

void TerminalProgress::show(const std::string& phase, double fraction, const std::string& detail,
                            const std::string& suffix) {
  const auto now = std::chrono::steady_clock::now();
  if (phase == phase_ && now - last_ < std::chrono::milliseconds(200)) return;
  phase_ = phase;
  last_ = now;
  char percent[16];
  std::snprintf(percent, sizeof(percent), " %.0f%%", 100 * fraction);
  std::string line =
      command_ + ": " + phase + percent + (detail.empty() ? "" : ", ") + detail + suffix;
  // A line longer than the terminal would wrap, and \r would then rewrite only its last
  // row: cut it one column short of the width (its text is ASCII).
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 && line.size() >= size.ws_col)
    line.resize(size.ws_col - 1);
  // \r and "erase to the end of the line": the line is rewritten in place.
  std::fprintf(stderr, "\r%s\033[K", line.c_str());
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
