// Printing a run while it is solved: block by block, so that memory does not grow
// with the number of values; the blocks formatted on several threads and written
// in order. The bytes are those ResultsPrinter::print gives for the whole run solved
// in one table by solve_motion() on one thread.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>

#include "engine/model.hpp"
#include "engine/analysis/sensitivities.hpp"
#include "engine/base/input_values.hpp"
#include "engine/printers/printer.hpp"

namespace kinema {

/// The fewest rows StreamSettings::block_time makes a block.
constexpr std::size_t kMinBlockRows = 16;

/// The rows of the next block after one of `rows` rows that took `took` to solve, for blocks
/// of about `target` and at most `most` rows (StreamSettings::block_time's rule).
std::size_t resized_block_rows(std::size_t rows, std::size_t most, std::chrono::steady_clock::duration took,
                               std::chrono::microseconds target);

struct StreamSettings {
  /// nullptr: solve only, to check a run before printing it (its values taken out as a
  /// printer takes them: one that overflows the output unit throws InputError).
  const ResultsPrinter* printer = nullptr;
  int precision = 0;                        ///< As PrintJob::precision.
  /// Derivative columns worked out for each block after its solve (on the thread that
  /// formats it) and printed after the result columns (kinema eval --sensitivity).
  const Sensitivities* sensitivities = nullptr;
  /// Threads (this one and count - 1 more), each taking the next block from the solver,
  /// formatting it and writing it after the blocks before it. The solve itself stays
  /// serial, one block at a time, so the numbers are the serial run's whatever the count
  /// (MotionOptions::threads is not used here).
  unsigned threads = 1;
  /// Rows a block; 0: from the run's length (a 128th of it, 256 to 1024 rows).
  std::size_t block_rows = 0;
  /// Nonzero (a run with a printer): a block that takes longer than this to solve makes
  /// the next ones smaller (in proportion, down to kMinBlockRows rows), and blocks solved
  /// in under a quarter of it larger again (doubling, up to block_rows), so that each
  /// thread comes back to `write` and `progress` within about this time even where values
  /// are slow (one that does not assemble is sought from the last that did: half a
  /// millisecond), and a `progress` that throws to stop the run (Python's Ctrl-C) is heard
  /// within about it. The same bytes whatever the blocks.
  std::chrono::microseconds block_time{0};
  std::function<void(std::string_view)> write;  ///< Takes the text in order; throws to stop the run.
  /// After each block written: values done of the run's total.
  std::function<void(std::size_t done, std::size_t total)> progress;
  /// Every row that is not ok, in order.
  std::function<void(double input, Status status, const Failure& failure)> on_failure;
};

struct RunSummary {
  std::size_t values = 0;
  std::size_t failures = 0;  ///< Rows with status singular or unassembled.
  struct FirstFailure {
    double input;
    Status status;
    Failure failure;
  };
  std::optional<FirstFailure> first_failure;
};

RunSummary stream_results(const Model& model, const InputValues& inputs, const MotionOptions& options,
                          const StreamSettings& settings);

}  // namespace kinema
