#include "cli/progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace kinema_cli {

ProgressLine::ProgressLine(bool wanted)
    : enabled_(wanted && ::isatty(STDERR_FILENO) == 1), start_(Clock::now()), last_shown_(start_) {}

void ProgressLine::update(std::size_t done, std::size_t total) {
  if (!enabled_ || done == 0 || done >= total) return;
  const Clock::time_point now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // A quarter of a second tells how fast the run goes; redraw ten times a second.
  if (elapsed < 0.25 || (shown_ && std::chrono::duration<double>(now - last_shown_).count() < 0.1)) return;
  const double rate = static_cast<double>(done) / elapsed;
  const double left = static_cast<double>(total - done) / rate;
  if (!shown_ && elapsed + left < 1.0) return;
  std::fprintf(stderr, "\rkinema: %zu of %zu values, %.0f values/s, %.0f s left\033[K", done, total, rate, left + 0.5);
  std::fflush(stderr);
  shown_ = true;
  last_shown_ = now;
}

void ProgressLine::finish() {
  if (!shown_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace kinema_cli
