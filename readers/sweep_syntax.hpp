// The sweep syntax, "start:stop:step", of a file's [input] sweep and of --sweep: its
// values computed when asked, and the bounds on how many.
#pragma once

#include <cstddef>
#include <string>

#include "engine/base/input_values.hpp"

namespace kinema {

/// Most input values a file lists or sweeps: they are held in memory (8 bytes each), and
/// a library run of them (solve_motion) holds every row.
constexpr std::size_t kMaxValuesPerRun = 10'000'000;

/// Most values of a command-line sweep: streamed (computed, solved and written a block
/// at a time), so memory stays constant; the bound only keeps a typo from asking for
/// an output of petabytes.
constexpr std::size_t kMaxSweepValues = 1'000'000'000;

/// Parses a sweep "start:stop:step" (numbers in `unit_factor` units) into its SI values
/// (computed when asked); more than max_values of them are refused.
InputValues parse_sweep(const std::string& text, double unit_factor, std::size_t max_values = kMaxValuesPerRun);

/// The values from start to stop by step (numbers in `unit_factor` units), the last
/// within a billionth of a step of stop; `written` names the run in messages.
InputValues sweep_between(double start, double stop, double step, double unit_factor, std::size_t max_values,
                          const std::string& written);

}  // namespace kinema
