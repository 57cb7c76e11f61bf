#include <kinema/engine/numeric/sweep.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <thread>

#include <kinema/engine/numeric/batch_workspace.hpp>
#include <kinema/engine/numeric/solver.hpp>
#include <kinema/engine/numeric/workspace.hpp>

namespace kinema {

namespace {

// Solves rows [begin, end) of the table in order from q (a solution at inputs[begin]
// or a guess); rows before begin belong to another thread and are not read. Adds the
// rows solved in SIMD blocks to batch_rows.
void analyse_range(const Kinematics& kinematics, std::size_t begin, std::size_t end, Eigen::VectorXd q,
                   MotionTable& table, bool batch, std::size_t& batch_rows) {
  const double rate = table.input_rate(), second_rate = table.input_second_rate();
  Workspace workspace(kinematics);
  std::unique_ptr<BatchWorkspace> batch_workspace;
  if (batch && rate != 0) batch_workspace = std::make_unique<BatchWorkspace>(kinematics);
  MotionState state;
  Eigen::VectorXd trial, predicted(q.size());
  std::size_t next_batch_try = begin;  // after a refused block, go on one by one for a while
  bool have_previous = false;  // row - 1 is solved (status ok) on the user's branch
  bool after_gap = false;
  bool any_solved = false;
  for (std::size_t row = begin; row < end; ++row) {
    const double input = table.input(row);
    if (batch_workspace && have_previous && row >= next_batch_try && row + BatchWorkspace::kLanes <= end &&
        table.failure(row - 1).kind == Failure::Kind::none) {
      if (batch_workspace->solve(table, row, begin)) {
        batch_rows += BatchWorkspace::kLanes;
        row += BatchWorkspace::kLanes - 1;
        q = table.q(row);
        continue;
      }
      next_batch_try = row + BatchWorkspace::kLanes;
    }
    bool solved = false;
    Failure why;
    trial = q;
    if (have_previous) {
      // Fast path for sweeps: predict from the rates just computed (dq/dtheta =
      // qd/thetad) and correct; the general continuation only when that fails.
      const double previous_input = table.input(row - 1);
      const double h = input - previous_input;
      if (rate != 0 && std::fabs(h) <= kinematics.max_continuation_step()) {
        for (Eigen::Index i = 0; i < q.size(); ++i) {
          predicted[i] = solver::predict_second_order(q[i], table.qd(row - 1)[i], table.qdd(row - 1)[i], rate,
                                                      second_rate, h);
        }
        solved = workspace.predict_and_correct(input, predicted, trial);
      }
      double stuck_at = previous_input;
      bool too_far = false;
      if (!solved) solved = workspace.continue_to(previous_input, input, trial, &stuck_at, &too_far);
      if (!solved) {
        why.kind = too_far ? Failure::Kind::too_far : Failure::Kind::branch_stops;
        why.from = previous_input;
        why.stopped_at = stuck_at;
      }
    } else {
      std::size_t worst_group = 0;
      double residual = 0;
      solved = workspace.solve_position(input, trial, &worst_group, &residual);
      if (!solved) {
        why.kind = Failure::Kind::group_open;
        why.group = static_cast<std::uint32_t>(worst_group);
        why.residual = residual;
        why.from_guesses = !after_gap;
      }
    }
    if (!solved) {
      MotionState failed;
      failed.input = input;
      failed.status = Status::unassembled;
      failed.failure = why;
      table.set(row, failed);
      after_gap = any_solved;
      have_previous = false;  // resume from the last good q; the branch may differ after a gap
      continue;
    }
    q = trial;
    any_solved = true;
    workspace.motion_into(input, rate, second_rate, q, state);
    if (after_gap && state.status == Status::ok) state.failure.kind = Failure::Kind::resumed_after_gap;
    // Past a singular position the branch may change: treat it like a gap.
    after_gap = state.status != Status::ok;
    have_previous = state.status == Status::ok;
    table.set(row, state);
  }
}

}  // namespace

MotionTable solve_sweep(const Kinematics& kinematics, const std::vector<double>& inputs, const SweepSettings& settings) {
  const std::size_t n = inputs.size();
  MotionTable table(inputs, kinematics.unknown_count(), kinematics.layout().point_dimensions, settings.rate,
                    settings.second_rate);
  const bool batch = settings.simd;
  unsigned threads = settings.threads;
  if (n == 0) return table;
  // Short runs are not worth a thread.
  threads = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(n / 256)));
  std::vector<std::size_t> begin(threads + 1);
  for (unsigned t = 0; t <= threads; ++t) begin[t] = n * t / threads;
  std::vector<Eigen::VectorXd> start(threads, kinematics.guess());
  if (threads > 1) {
    // Each chunk starts from a solution reached by continuation along the inputs
    // (coarse steps), so every chunk is on the branch the serial run would be on.
    // Where that is impossible (a gap or a toggle), the run stays serial.
    Workspace workspace(kinematics);
    Eigen::VectorXd q = start[0];
    bool ok = workspace.solve_position(inputs[0], q);
    for (unsigned t = 1; t < threads && ok; ++t) {
      ok = workspace.continue_to(inputs[begin[t - 1]], inputs[begin[t]], q, nullptr);
      start[t] = q;
    }
    if (!ok) {
      threads = 1;
      begin = {0, n};
    }
  }
  if (threads == 1) {
    std::size_t batch_rows = 0;
    analyse_range(kinematics, 0, n, start[0], table, batch, batch_rows);
    table.add_batch_rows(batch_rows);
    return table;
  }
  std::vector<std::thread> workers;
  std::vector<std::size_t> batch_rows(threads, 0);
  for (unsigned t = 0; t < threads; ++t) {
    workers.emplace_back(analyse_range, std::cref(kinematics), begin[t], begin[t + 1], start[t], std::ref(table),
                         batch, std::ref(batch_rows[t]));
  }
  for (auto& worker : workers) worker.join();
  for (std::size_t rows : batch_rows) table.add_batch_rows(rows);
  return table;
}

}  // namespace kinema
