// The sweep driver: solves input values in order, each continued from the
// last so that the assembly branch is kept, sweeps in SIMD blocks where the
// motion is regular, long runs on several threads. Failures become rows with
// a status and a structured Failure; nothing is thrown for them.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "engine/base/input_values.hpp"
#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

struct SweepSettings {
  double rate = 0.0;         ///< Input rate (SI) at every value.
  double second_rate = 0.0;  ///< Input second rate (SI).
  /// A long run is split into this many chunks whose starting positions are found by
  /// continuation first, so the branch is the serial run's.
  unsigned threads = 1;
  /// Consecutive values solved kLanes at a time on the batch (SIMD) tape, predicted
  /// from the rows before and checked to stay on their branch (else one by one).
  bool simd = true;
};

/// Input values solved by solve_sweep and SweepSolver in this process so far (each
/// counted once, however it was solved): lets a test see that a run solves a value once.
std::uint64_t values_solved_in_process();

MotionTable solve_sweep(const Kinematics& kinematics, const std::vector<double>& inputs, const SweepSettings& settings);

/// Rows of a run solved by SweepSolver: rows [first, last) of `table` are values
/// [run_row, run_row + last - first) of the run (rows before first are the history
/// the solver predicted from, rows from last on are not solved).
struct SweepBlock {
  MotionTable table;
  std::size_t first = 0, last = 0, run_row = 0;
  std::size_t size() const { return last - first; }
};

/// The serial run of solve_sweep, a block of rows at a time: the same rows, the same
/// numbers, in memory that does not grow with the number of values (it keeps only the
/// rows the next prediction reads).
class SweepSolver {
 public:
  SweepSolver(const Kinematics& kinematics, InputValues inputs, const SweepSettings& settings);
  ~SweepSolver();
  SweepSolver(const SweepSolver&) = delete;
  SweepSolver& operator=(const SweepSolver&) = delete;

  std::size_t size() const;       ///< Values in the run.
  std::size_t solved() const;     ///< Values solved so far (the next block starts there).
  bool done() const { return solved() == size(); }
  /// Solves the next `rows` values (a few more when a SIMD block runs past them) into block.
  void solve_next(SweepBlock& block, std::size_t rows);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// One run of input values solved again and again as the parameter values of the
/// kinematics change (Kinematics::set_parameter_values between runs: a design study):
/// each run is solve_sweep's serial run (threads = 1), the same rows and numbers as
/// solve_sweep on kinematics built with those values, in a table and solvers kept from
/// run to run (no derivation, compilation or table per run).
class RepeatedSweep {
 public:
  RepeatedSweep(const Kinematics& kinematics, const std::vector<double>& inputs, const SweepSettings& settings);
  ~RepeatedSweep();
  RepeatedSweep(const RepeatedSweep&) = delete;
  RepeatedSweep& operator=(const RepeatedSweep&) = delete;

  /// Solves the run at the kinematics' current parameter values; the table is this
  /// object's, valid until the next call.
  const MotionTable& solve();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// One run's rows solved one at a time into a table the caller keeps, each as
/// solve_sweep's serial run solves it when it goes one by one (no SIMD blocks): for a
/// caller that solves the rows it can itself and hands the others here (a design study's
/// lanes across designs, engine/numeric/design_lanes).
class RowSolver {
 public:
  explicit RowSolver(const Kinematics& kinematics);
  ~RowSolver();
  RowSolver(const RowSolver&) = delete;
  RowSolver& operator=(const RowSolver&) = delete;

  /// A new run at the kinematics' current parameter values, from its guesses.
  void start();
  /// Solves `row` of `table` (its input stored; every row before it in this run solved).
  void solve(MotionTable& table, std::size_t row);
  /// Row `row` (status ok, nothing to report) was solved elsewhere as solve() would
  /// have solved it: the run goes on from it.
  void solved_elsewhere(const MotionTable& table, std::size_t row);
  /// The last row solved is ok: solve() predicts the next from its rates.
  bool on_branch() const;
  /// Where solve() starts Newton alone (Workspace::solve_position) for the next row: after
  /// a row that did not assemble, from the last position solved (or the guesses), where the
  /// guesses do not close at their own input value; nullptr where it does anything else
  /// (predicts, carries the file's assembly to the value, restarts past a singular
  /// position, places dyads in closed form).
  const Eigen::VectorXd* restart_position();
  /// The next row, `row`, did not assemble: Newton from restart_position() stopped open
  /// with max |Phi| = residual, largest in equation group `group`, found elsewhere as
  /// solve() would have found it. Stored as solve() stores it.
  void failed_elsewhere(MotionTable& table, std::size_t row, std::size_t group, double residual);
  /// The next row, `row`, cannot close: a test outside Newton (a design study's LoopReach)
  /// found no position there, so solve()'s Newton or continuation would stop open. Stored
  /// with the status and the kind of failure solve() would store (a branch that stops
  /// after an ok row, else a group left open), the details the test's: continuation
  /// stopped at `limit` (where the loop stops closing), Newton left `distance` open in
  /// `group` (the least |Phi| any position leaves).
  void unassembled_elsewhere(MotionTable& table, std::size_t row, double limit, std::size_t group, double distance);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Counts values solved outside solve_sweep and the solvers above (a design study's
/// lanes) in values_solved_in_process().
void count_values_solved(std::uint64_t values);

}  // namespace kinema
