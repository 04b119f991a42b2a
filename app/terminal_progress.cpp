#include "app/terminal_progress.h"

#include <unistd.h>

#include <cstdio>

namespace tetlod::app {

TerminalProgress::TerminalProgress(const std::string& command)
    : command_(command), terminal_(isatty(STDERR_FILENO) == 1) {}

ProgressCallback TerminalProgress::callback() {
  if (!terminal_) return {};
  return [this](const SimplifyProgress& p) { show(p); };
}

void TerminalProgress::show(const SimplifyProgress& p) {
  const std::string phase = std::string(p.past_valence ? "past the valence: " : "") + p.phase;
  const auto now = std::chrono::steady_clock::now();
  if (phase == phase_ && now - last_ < std::chrono::milliseconds(200)) return;
  phase_ = phase;
  last_ = now;
  // \r and "erase to the end of the line": the line is rewritten in place.
  if (std::string(p.phase) == "simplify")
    std::fprintf(stderr, "\r%s: %s %.0f%%, %zu collapses\033[K", command_.c_str(), phase.c_str(),
                 100 * p.fraction, p.collapses);
  else
    std::fprintf(stderr, "\r%s: %s %.0f%%\033[K", command_.c_str(), phase.c_str(),
                 100 * p.fraction);
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
