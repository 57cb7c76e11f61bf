#include "engine/run/results_stream.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "engine/numeric/sweep.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/run/view.hpp"

namespace kinema {

namespace {

// Whether `ready` holds within `budget`, asked again and again: waking a thread that
// sleeps costs about 70 us on a virtual machine (as long as formatting a block), and the
// waits of a run whose threads each have a core are shorter than that.
template <class Ready>
bool spin_until(Ready ready, std::chrono::microseconds budget) {
  if (budget.count() <= 0) return ready();
  const auto deadline = std::chrono::steady_clock::now() + budget;
  for (;;) {
    for (int spin = 0; spin < 64; ++spin) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    if (std::chrono::steady_clock::now() > deadline) return ready();
  }
}

// The blocks of a run on several threads, each taking the next block from the solver
// (one at a time, so the run is the serial one), formatting it, and writing it once the
// blocks before it are written. At most one block a thread is in flight.
class OrderedRun {
 public:
  OrderedRun(SweepSolver& solver, const ResultsPrinter& printer, const PrintJob& job, const StreamSettings& settings,
             std::size_t block_rows, const std::function<void(const SweepBlock&)>& account)
      : solver_(solver), printer_(printer), job_(job), settings_(settings), block_rows_(block_rows), rows_(block_rows),
        account_(account) {}

  /// Runs on this thread and `threads - 1` more; rethrows the first error of any.
  void run(unsigned threads) {
    // More threads than cores: a spinning thread would take the core of one that works.
    if (threads > 1 && threads <= std::max(1u, std::thread::hardware_concurrency())) spin_ = std::chrono::microseconds(200);
    std::vector<std::thread> others;
    for (unsigned t = 1; t < threads; ++t) {
      try {
        others.emplace_back([this] { work(); });
      } catch (const std::system_error&) {
        break;  // no more threads to be had: the run goes on with those there are
      }
    }
    work();
    for (auto& thread : others) thread.join();
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void work() {
    SweepBlock block;
    std::string text;
    try {
      for (;;) {
        std::size_t turn;
        {
          if (!spin_until([&] { return solve_mutex_.try_lock(); }, spin_)) solve_mutex_.lock();
          std::lock_guard<std::mutex> lock(solve_mutex_, std::adopt_lock);
          if (failed_ || solver_.done()) return;
          turn = next_turn_++;
          const auto started = std::chrono::steady_clock::now();
          solver_.solve_next(block, rows_);
          if (settings_.block_time.count() > 0)
            rows_ = resized_block_rows(rows_, block_rows_, std::chrono::steady_clock::now() - started, settings_.block_time);
          account_(block);
        }
        if (settings_.sensitivities) settings_.sensitivities->fill(block.table, block.first, block.last);
        text.clear();
        printer_.rows(text, job_, block.table, block.first, block.last, block.run_row);
        if (!spin_until([&] { return write_turn_ == turn || failed_; }, spin_)) {
          std::unique_lock<std::mutex> lock(turn_mutex_);
          turn_passed_.wait(lock, [&] { return write_turn_ == turn || failed_; });
        }
        if (failed_) return;
        settings_.write(text);
        done_ += block.size();
        if (settings_.progress) settings_.progress(done_, solver_.size());
        pass_turn(turn + 1);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(turn_mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
      turn_passed_.notify_all();
    }
  }
  void pass_turn(std::size_t next) {
    {
      std::lock_guard<std::mutex> lock(turn_mutex_);
      write_turn_ = next;
    }
    turn_passed_.notify_all();  // no system call when no thread sleeps on it
  }

  SweepSolver& solver_;
  const ResultsPrinter& printer_;
  const PrintJob& job_;
  const StreamSettings& settings_;
  const std::size_t block_rows_;
  std::size_t rows_;  // the next block's (block_rows_ unless StreamSettings::block_time)
  const std::function<void(const SweepBlock&)>& account_;
  std::mutex solve_mutex_;  // the solver, next_turn_ and rows_
  std::size_t next_turn_ = 0;
  std::mutex turn_mutex_;   // sleeping on write_turn_, and error_
  std::condition_variable turn_passed_;
  std::atomic<std::size_t> write_turn_{0};
  std::atomic<bool> failed_{false};
  std::chrono::microseconds spin_{0};
  std::size_t done_ = 0;  // written by the thread whose turn it is
  std::exception_ptr error_;
};

// Each block costs some tens of microseconds whatever its size (a write, hand-offs
// between threads), and each thread's buffers are first touched once, page by page
// (microseconds a page on a virtual machine): a short run gains from smaller blocks, a
// long one from larger. Measured: 36,001 rows 38 -> 34 ms at 256 rows, 360,001 rows
// best at 1024; the same with a block a thread in flight.
std::size_t automatic_block_rows(std::size_t total) { return std::clamp<std::size_t>(total / 128, 256, 1024); }

}  // namespace

std::size_t resized_block_rows(std::size_t rows, std::size_t most, std::chrono::steady_clock::duration took,
                               std::chrono::microseconds target) {
  const std::chrono::steady_clock::duration aim = target;
  if (took > aim) {  // at once to the rows that take about the target (a slow stretch starts at any row)
    const double share = double(aim.count()) / double(took.count());
    return std::max(std::min(kMinBlockRows, most), static_cast<std::size_t>(double(rows) * share));
  }
  if (took * 4 < aim) return std::min(most, rows * 2);  // back up by halves: a slow stretch may go on
  return rows;
}

RunSummary stream_results(const Model& model, const InputValues& inputs, const MotionOptions& options,
                          const StreamSettings& settings) {
  SweepSettings sweep;
  sweep.rate = options.rate.value_or(model.system.input.rate_value);
  sweep.second_rate = options.second_rate.value_or(model.system.input.second_rate_value);
  sweep.simd = options.simd;
  SweepSolver solver(model.kinematics, inputs, sweep);
  PrintJob job{model};
  job.precision = settings.precision;
  if (settings.sensitivities) job.sensitivities = &settings.sensitivities->columns();
  const std::size_t total = inputs.size(), block_rows = settings.block_rows > 0 ? settings.block_rows
                                                                                 : automatic_block_rows(total);
  RunSummary summary;
  summary.values = total;
  const auto account = [&](const SweepBlock& block) {
    for (std::size_t row = block.first; row < block.last; ++row) {
      const Status status = block.table.status(row);
      if (status == Status::ok) continue;
      ++summary.failures;
      const double input = block.table.input(row);
      if (!summary.first_failure) summary.first_failure = RunSummary::FirstFailure{input, status, block.table.failure(row)};
      if (settings.on_failure) settings.on_failure(input, status, block.table.failure(row));
    }
  };
  const ResultsPrinter* printer = settings.printer;
  if (!printer) {  // solve only
    SweepBlock block;
    const OutputScale scale(model.system);
    const std::size_t columns = result_column_count(model.system);  // a run of values: no circuit
    std::vector<double> values;
    while (!solver.done()) {
      solver.solve_next(block, block_rows);
      account(block);
      // The rows' values as a printer takes them: one past the largest number in the
      // output unit throws here, before anything of the run is printed.
      values.resize(block.size() * columns);
      result_rows(model.system, scale, block.table, block.first, block.last, values.data());
      if (settings.progress) settings.progress(solver.solved(), total);
    }
    return summary;
  }
  const Analysis analysis = analyse_for_printer(*printer, job);  // what the head shows, once
  job.analysis = &analysis;
  std::string text;
  printer->head(text, job, total);
  settings.write(text);
  OrderedRun(solver, *printer, job, settings, block_rows, account).run(std::max(1u, settings.threads));
  text.clear();
  printer->tail(text, job, total);
  settings.write(text);
  return summary;
}

}  // namespace kinema
