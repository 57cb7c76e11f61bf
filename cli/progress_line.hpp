// A one-line progress indicator on stderr for long runs: values done, values per
// second, time left. Only on a terminal, and only when the run looks like taking
// over a second; the line is cleared at the end.
#pragma once

#include <chrono>
#include <cstddef>

namespace kinema_cli {

class ProgressLine {
 public:
  /// Shows nothing unless `wanted` (not --quiet) and stderr is a terminal.
  explicit ProgressLine(bool wanted);
  ~ProgressLine() { finish(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  void update(std::size_t done, std::size_t total);
  /// Clears the line (before a message, or at the end).
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_, shown_ = false;
  Clock::time_point start_, last_shown_;
};

}  // namespace kinema_cli
