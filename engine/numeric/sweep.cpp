#include "engine/numeric/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include "engine/numeric/batch_workspace.hpp"
#include "engine/numeric/closed_form.hpp"
#include "engine/numeric/solver.hpp"
#include "engine/numeric/workspace.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

// Where a run of rows stands between calls of solve_rows: the last solution and what
// is known of the rows before the next one.
struct RunCursor {
  Eigen::VectorXd q;                ///< A solution at the last row solved (or the guess).
  bool have_previous = false;       ///< The last row is solved (status ok) on the user's branch.
  bool after_gap = false;           ///< The last row failed or was singular after solved rows.
  bool q_singular = false;          ///< q is a singular position (Newton from it has no direction).
  bool any_solved = false;
  int sign = 0;                     ///< det Phi_q's sign at the last row solved ok (0: not known).
  bool start_given = false;         ///< q was carried to the next row's value by the caller (a chunk's start).
  std::size_t next_batch_try = 0;   ///< Run row: after a refused SIMD block, one by one until here.
  std::size_t batch_rows = 0;       ///< Rows solved in SIMD blocks.
  // Joints and links (rows placed in closed form):
  std::vector<int> signs;           ///< The dyads' signs to place with (empty: the sketch's).
  // Every run: the last ok row, to keep its assembly or run on smoothly from it.
  bool have_last_ok = false;
  double last_ok_input = 0;
  Eigen::VectorXd last_ok_q, last_ok_qd, last_ok_qdd;

  /// After `row` of `table`, solved with status ok by other means than the scalar run
  /// (a SIMD block, the design lanes): where solve_rows stands after such a row.
  void ok_row(const MotionTable& table, std::size_t row) {
    q = table.q(row);
    any_solved = true;
    q_singular = false;
    after_gap = false;
    have_previous = true;
    have_last_ok = true;
    last_ok_input = table.input(row);
    last_ok_q = q;
    last_ok_qd = table.qd(row);
    last_ok_qdd = table.qdd(row);
  }
  /// Stores `row` of `table` as unassembled for `why`; the branch may differ after a gap,
  /// so the run resumes from the last good q.
  void failed_row(MotionTable& table, std::size_t row, const Failure& why) {
    MotionState failed;
    failed.input = table.input(row);
    failed.status = Status::unassembled;
    failed.failure = why;
    table.set(row, failed);
    after_gap = any_solved;
    have_previous = false;
  }
};

// Newton could not close equation group `group`, max |Phi| `residual` staying open.
Failure group_open(std::size_t group, double residual, bool from_guesses) {
  Failure why;
  why.kind = Failure::Kind::group_open;
  why.group = static_cast<std::uint32_t>(group);
  why.residual = residual;
  why.from_guesses = from_guesses;
  return why;
}

// The dyads' signs at `input` marched from a position at `from` (q, with rates qd and qdd
// at the run's input rates where `rates`) in small steps, `total` on (the short way round
// for an angle), each step placed on the signs nearest the position extrapolated from the
// steps before. A dyad's sign may change on the way without a jump — through a change
// point, where two assemblies meet (the parallelogram at 180 deg). False where the march
// cannot pass (a gap).
bool march_signs(const Kinematics& kinematics, const SolvingPlan& frames, double from, const Eigen::VectorXd& q0,
                 const Eigen::VectorXd* qd, const Eigen::VectorXd* qdd, double rate, double second_rate, double total,
                 std::vector<int>& signs) {
  const double scale = kinematics.length_scale();
  signs = signs_nearest(frames, from, q0.data(), scale);
  const int steps = static_cast<int>(std::ceil(std::fabs(total) / (0.5 * kinematics.max_continuation_step())));
  if (steps > 100000) return false;
  const double h = total / std::max(steps, 1);
  std::vector<Eigen::VectorXd> q{q0};  // the last three positions marched
  std::vector<BodyPose> poses;
  std::vector<int> marched = signs;
  for (int k = 1; k <= steps; ++k) {
    const double x = from + k * h;
    Eigen::VectorXd predicted(q.back().size());
    for (Eigen::Index i = 0; i < predicted.size(); ++i) {
      const std::size_t m = q.size();
      predicted[i] = m >= 3                    ? 3 * q[m - 1][i] - 3 * q[m - 2][i] + q[m - 3][i]
                     : qd && rate != 0 ? solver::predict_second_order(q0[i], (*qd)[i], (*qdd)[i], rate, second_rate, k * h)
                     : m == 2                  ? 2 * q[1][i] - q[0][i]
                                               : q.back()[i];
    }
    marched = signs_nearest(frames, x, predicted.data(), scale);
    if (place_dyads(frames, x, poses, &marched) < frames.dyads.size()) return false;
    Eigen::VectorXd placed = predicted;
    unknowns_from_poses(frames, poses, placed.data());
    for (const SolvingPlan::Body& body : frames.bodies)
      if (body.unknown >= 0)
        placed[body.unknown] += 2 * kPi * std::round((predicted[body.unknown] - placed[body.unknown]) / (2 * kPi));
    q.push_back(placed);
    if (q.size() > 3) q.erase(q.begin());
  }
  signs = marched;
  return true;
}

// The dyads' signs for a row placed in closed form: the assembly the motion runs on from
// the last ok row, marched there (the short way round for an angle); where there is no ok
// row before it or the march cannot pass (a gap), the file's assembly: marched from the
// sketch, the short way round or else the long way; where that cannot pass either, the
// sketch's signs.
void choose_signs(const Kinematics& kinematics, const SolvingPlan& frames, double input, double rate,
                  double second_rate, bool angle_input, RunCursor& at) {
  auto ahead = [&](double from) {
    const double total = input - from;
    return angle_input ? std::remainder(total, 2 * kPi) : total;  // the same position, the short way
  };
  if (at.have_last_ok && march_signs(kinematics, frames, at.last_ok_input, at.last_ok_q, &at.last_ok_qd,
                                     &at.last_ok_qdd, rate, second_rate, ahead(at.last_ok_input), at.signs))
    return;
  std::vector<BodyPose> poses;
  Eigen::VectorXd home = kinematics.guess();
  if (place_dyads(frames, frames.sketch_input, poses) == frames.dyads.size()) {  // the sketch's signs
    unknowns_from_poses(frames, poses, home.data());
    const double short_way = ahead(frames.sketch_input);
    if (march_signs(kinematics, frames, frames.sketch_input, home, nullptr, nullptr, 0, 0, short_way, at.signs)) return;
    if (angle_input && short_way != 0 &&
        march_signs(kinematics, frames, frames.sketch_input, home, nullptr, nullptr, 0, 0,
                    short_way - std::copysign(2 * kPi, short_way), at.signs))
      return;
  }
  at.signs.clear();
}

// The position h on from one whose rates are qd and qdd at the run's input rates.
template <class Q, class Rate, class SecondRate>
void predict_position(const Q& q, const Rate& qd, const SecondRate& qdd, double rate, double second_rate, double h,
                      Eigen::VectorXd& out) {
  for (Eigen::Index i = 0; i < out.size(); ++i) out[i] = solver::predict_second_order(q[i], qd[i], qdd[i], rate, second_rate, h);
}

// The file's assembly: the position the guesses give at the input value they stand for
// (home), carried along the input each way as far as its branch goes, in steps of the
// largest continuation step from home (so that the positions on the way are the same
// whichever value asked for them first). A value with no solved value before it (the
// first of a run, one after a gap, one a list's step cannot reach) lands there: the short
// way round for a periodic angle, else the long way; so a value's assembly is the same
// however it is asked.
class FileAssembly {
 public:
  explicit FileAssembly(const Kinematics& kinematics) : k_(kinematics) {}
  /// The parameters changed (a design study's next design): home is found again.
  void reset() {
    started_ = false;
    for (Way& way : ways_) way = Way{};
  }
  /// Whether the guesses close at their own input value (else values are solved from the
  /// guesses, as they stand).
  bool has_home(Workspace& workspace) { return start(workspace); }
  int home_sign() const { return home_sign_; }
  double home_input() const { return home_; }
  /// The position at `input` on the file's assembly into q; false where its branch does not
  /// reach the value either way (then *stopped_at: where it stops on the shorter way). A
  /// periodic angle goes the short way round, unless only the long way reaches the value
  /// without passing a change point: there the branch through it does not come back to the
  /// same assembly a turn on (a four-bar with s + l = p + q), and a run from home that
  /// meets no change point (a sweep over the turn) gives the long way's.
  bool reach(Workspace& workspace, double input, Eigen::VectorXd& q, double* stopped_at, bool* too_far = nullptr) {
    reached_ = false;
    if (!start(workspace)) return false;
    const double home = home_;
    double ahead = input - home;
    if (k_.periodic_input()) ahead = std::remainder(ahead, 2 * kPi);
    double ways[2] = {ahead, ahead - std::copysign(2 * kPi, ahead)};
    const int count = k_.periodic_input() && ahead != 0 ? 2 : 1;
    bool have_crossed = false;
    for (int w = 0; w < count; ++w) {
      const double target = home + ways[w];
      Way& way = ways_[ways[w] < 0 ? 1 : 0];
      if (!(std::fabs(ways[w]) <= solver::kMostEntrySteps * k_.max_continuation_step())) {
        if (w == 0 && too_far) *too_far = true;
        continue;
      }
      // The way carried past the target where it goes so far; where it stops before, it
      // may still reach the target (a limit between the target and the next step's end).
      extend(workspace, way, ways[w]);
      // The last position on the way not past the target, then on to it.
      std::size_t k = 0;
      while (k + 1 < way.inputs.size() && std::fabs(way.inputs[k + 1] - home) <= std::fabs(ways[w])) ++k;
      Eigen::VectorXd p = way.q[k];
      double stuck = way.inputs[k];
      const std::size_t passed = workspace.change_points_passed();
      if (!workspace.continue_to(way.inputs[k], target, p, &stuck)) {
        if (w == 0 && stopped_at) *stopped_at = stuck;
        continue;
      }
      if (target != input && !workspace.solve_position(input, p)) continue;
      const bool crossed = way.crossed_at <= k || workspace.change_points_passed() != passed;
      if (!crossed || have_crossed) {
        if (crossed) continue;  // the short way's, kept below
        q = p;
        return reached_ = true;
      }
      q = p;  // through a change point: kept unless the long way reaches without one
      have_crossed = true;
    }
    return reached_ = have_crossed;
  }
  /// The last reach() landed.
  bool reached() const { return reached_; }

 private:
  struct Way {
    std::vector<double> inputs;
    std::vector<Eigen::VectorXd> q;
    bool stopped = false;
    double stopped_at = 0;
    /// The first position kept past a change point (past the end: none).
    std::size_t crossed_at = std::numeric_limits<std::size_t>::max();
  };
  bool start(Workspace& workspace) {
    if (started_) return home_ok_;
    started_ = true;
    // Where the guesses do not close at their own value (a copy with other lengths), or
    // close on a singular position (a toggle: two assemblies meet, neither is the file's),
    // at the nearest value in steps of the largest continuation step where they close on a
    // regular one.
    Eigen::VectorXd q, slope;
    const double step = k_.max_continuation_step();
    auto regular_at = [&](double input) {
      q = k_.guess();
      return workspace.solve_position(input, q) && workspace.sensitivity(input, q, slope);
    };
    home_ = k_.guess_input();
    home_ok_ = regular_at(home_);
    for (int k = 1; !home_ok_ && k <= solver::kHomeSearchSteps; ++k)
      for (const double side : {1.0, -1.0}) {
        if (regular_at(k_.guess_input() + side * k * step)) {
          home_ = k_.guess_input() + side * k * step;
          home_ok_ = true;
          break;
        }
      }
    const double home = home_;
    home_sign_ = home_ok_ ? workspace.jacobian_sign(home, q) : 0;
    for (Way& way : ways_) {
      way = Way{};
      way.inputs.push_back(home);
      way.q.push_back(q);
    }
    return home_ok_;
  }
  // The way towards home + `ahead` carried past it (true), or as far as it goes (false).
  bool extend(Workspace& workspace, Way& way, double ahead) {
    const double home = home_, step = k_.max_continuation_step();
    while (std::fabs(way.inputs.back() - home) < std::fabs(ahead)) {
      if (way.stopped) return false;
      const double from = way.inputs.back();
      const double to = home + std::copysign(double(way.inputs.size()) * step, ahead);
      Eigen::VectorXd q = way.q.back();
      double stuck = from;
      const std::size_t passed = workspace.change_points_passed();
      bool on = workspace.continue_to(from, to, q, &stuck);
      if (!on && way.q.size() >= 2) {
        // The last position kept is singular (a change point on a step's end): from the
        // one before, over it.
        q = way.q[way.q.size() - 2];
        on = workspace.continue_to(way.inputs[way.inputs.size() - 2], to, q, &stuck);
      }
      if (!on) {
        way.stopped = true;
        way.stopped_at = stuck;
        return false;
      }
      if (workspace.change_points_passed() != passed) way.crossed_at = std::min(way.crossed_at, way.inputs.size());
      way.inputs.push_back(to);
      way.q.push_back(q);
    }
    return true;
  }
  const Kinematics& k_;
  double home_ = 0;
  bool started_ = false, home_ok_ = false, reached_ = false;
  int home_sign_ = 0;
  Way ways_[2];  ///< Onwards from home, and back.
};

struct Solvers {
  explicit Solvers(const Kinematics& kinematics, bool batch, double rate) : scalar(kinematics), assembly(kinematics) {
    if (batch && rate != 0) simd = std::make_unique<BatchWorkspace>(kinematics);
  }
  Workspace scalar;
  std::unique_ptr<BatchWorkspace> simd;
  FileAssembly assembly;
};

// Every value solve_rows solved in this process (values_solved_in_process()).
std::atomic<std::uint64_t> values_solved{0};

// Solves table rows from `first` on, in order, until a row at or past `stop`. A SIMD
// block may run on past stop, up to `limit`; rows before first back to history_begin
// are solved rows it may predict from (rows before history_begin belong to another
// thread and are not read). Table row 0 is row `offset` of the run. Returns the row
// after the last one solved.
std::size_t solve_rows(const Kinematics& kinematics, Solvers& solvers, MotionTable& table, std::size_t first,
                       std::size_t stop, std::size_t limit, std::size_t history_begin, std::size_t offset,
                       RunCursor& at) {
  const double rate = table.input_rate(), second_rate = table.input_second_rate();
  const SolvingPlan* closed_form = kinematics.closed_form();
  const bool angle_input = closed_form != nullptr && closed_form->driver_slider < 0;
  MotionState state;
  Eigen::VectorXd trial, predicted(at.q.size());
  std::size_t row = first;
  for (; row < stop; ++row) {
    const double input = table.input(row);
    const bool start_given = at.start_given;  // this row only
    at.start_given = false;
    if (solvers.simd && at.have_previous && offset + row >= at.next_batch_try && row + BatchWorkspace::kLanes <= limit &&
        table.failure(row - 1).kind == Failure::Kind::none) {
      if (at.sign == 0) at.sign = solvers.scalar.jacobian_sign(table.input(row - 1), at.q);
      if (solvers.simd->solve(table, row, history_begin, at.sign)) {
        at.batch_rows += BatchWorkspace::kLanes;
        row += BatchWorkspace::kLanes - 1;
        at.ok_row(table, row);  // the flags as they were: a block follows an ok row
        continue;
      }
      at.next_batch_try = offset + row + BatchWorkspace::kLanes;
    }
    bool solved = false;
    Failure why;
    trial = at.q;
    if (at.have_previous) {
      // Fast path for sweeps: predict from the rates just computed (dq/dtheta =
      // qd/thetad) and correct; the general continuation only when that fails.
      const double previous_input = table.input(row - 1);
      const double h = input - previous_input;
      if (rate != 0 && std::fabs(h) <= kinematics.max_continuation_step()) {
        predict_position(at.q, table.qd(row - 1), table.qdd(row - 1), rate, second_rate, h, predicted);
        if (at.sign == 0) at.sign = solvers.scalar.jacobian_sign(previous_input, at.q);
        solved = solvers.scalar.predict_and_correct(previous_input, input, predicted, trial, at.sign);
      }
      double stuck_at = previous_input;
      bool too_far = false;
      if (!solved && closed_form != nullptr && std::fabs(h) > kinematics.max_continuation_step()) {
        // A value far from the last (a list, a periodic angle): no path to follow, the
        // dyads' signs say the branch.
        std::uint32_t dyad = 0;
        choose_signs(kinematics, *closed_form, input, rate, second_rate, angle_input, at);
        if (closed_form_position(*closed_form, input, at.signs, trial, dyad)) {
          std::size_t worst_group = 0;
          double residual = 0;
          solved = solvers.scalar.solve_position(input, trial, &worst_group, &residual);
          if (!solved) why = group_open(worst_group, residual, false);
        } else {
          why.kind = Failure::Kind::dyad_open;
          why.group = dyad;
        }
      } else if (!solved) {
        // A periodic angle goes the short way round (300 deg after 0 is -60 deg).
        const double target =
            kinematics.periodic_input() ? previous_input + std::remainder(h, 2 * kPi) : input;
        solved = solvers.scalar.continue_to(previous_input, target, trial, &stuck_at, &too_far) &&
                 (target == input || solvers.scalar.solve_position(input, trial));
        if (!solved) {
          why.kind = too_far ? Failure::Kind::too_far : Failure::Kind::branch_stops;
          why.from = previous_input;
          why.stopped_at = stuck_at;
          // Past a gap the value is the file's assembly's where its branch reaches it (the
          // other way round, or another stretch), as the value asked alone would be.
          if (closed_form == nullptr && solvers.assembly.reach(solvers.scalar, input, trial, nullptr)) {
            solved = true;
            at.after_gap = true;
          }
        }
      }
    } else {
      std::size_t worst_group = 0;
      double residual = 0;
      std::uint32_t dyad = 0;
      double stopped_at = 0;
      bool too_far = false;
      // Not a joints file placed dyad by dyad: the file's assembly, carried from its
      // guesses to the value; unless the guesses do not close at their own value, or the
      // value is too far from it to carry them (then Newton from where the run stands).
      const bool from_home = closed_form == nullptr && !start_given && solvers.assembly.has_home(solvers.scalar) &&
                             (solvers.assembly.reach(solvers.scalar, input, trial, &stopped_at, &too_far) || !too_far);
      if (closed_form != nullptr) choose_signs(kinematics, *closed_form, input, rate, second_rate, angle_input, at);
      if (closed_form != nullptr && !closed_form_position(*closed_form, input, at.signs, trial, dyad)) {
        why.kind = Failure::Kind::dyad_open;
        why.group = dyad;
      } else if (from_home) {
        solved = solvers.assembly.reached();
        if (!solved) {
          // Its branch does not reach the value: where it stops, or, where nothing closes
          // there at all, the loop that stays open.
          trial = kinematics.guess();
          if (solvers.scalar.solve_position(input, trial, &worst_group, &residual)) {
            why.kind = Failure::Kind::branch_stops;
            why.from = solvers.assembly.home_input();
            why.stopped_at = stopped_at;
          } else {
            why = group_open(worst_group, residual, !at.after_gap);
          }
        }
      } else {
        solved = solvers.scalar.solve_position(input, trial, &worst_group, &residual);
        if (!solved && at.q_singular && at.have_last_ok && rate != 0) {
          // Newton from a singular position (a change point: the parallelogram folded)
          // has no direction to go; from the last ok row's motion carried on past it, it has.
          predict_position(at.last_ok_q, at.last_ok_qd, at.last_ok_qdd, rate, second_rate, input - at.last_ok_input,
                           trial);
          solved = solvers.scalar.solve_position(input, trial, &worst_group, &residual);
        }
        if (!solved) why = group_open(worst_group, residual, !at.after_gap);
      }
    }
    if (!solved) {
      at.failed_row(table, row, why);
      continue;
    }
    at.q = trial;
    at.any_solved = true;
    solvers.scalar.motion_into(input, rate, second_rate, at.q, state);
    at.sign = solvers.scalar.factorised_sign();
    at.q_singular = state.status == Status::singular;
    if (at.after_gap && state.status == Status::ok) state.failure.kind = Failure::Kind::resumed_after_gap;
    // Past a singular position the branch may change: treat it like a gap.
    at.after_gap = state.status != Status::ok;
    at.have_previous = state.status == Status::ok;
    if (state.status == Status::ok) {
      at.have_last_ok = true;
      at.last_ok_input = input;
      at.last_ok_q = state.q;
      at.last_ok_qd = state.qd;
      at.last_ok_qdd = state.qdd;
    }
    table.set(row, state);
  }
  values_solved.fetch_add(row - first, std::memory_order_relaxed);
  return row;
}

}  // namespace

MotionTable solve_sweep(const Kinematics& kinematics, const std::vector<double>& inputs, const SweepSettings& settings) {
  const std::size_t n = inputs.size();
  MotionTable table(inputs, kinematics.unknown_count(), kinematics.layout().point_dimensions, settings.rate,
                    settings.second_rate, kinematics.frame_count());
  unsigned threads = settings.threads;
  if (n == 0) return table;
  // Short runs are not worth a thread. A joints-and-links run stays serial: its
  // assembly is carried along the run (through change points, where a dyad's sign
  // changes without a jump), which chunk starts reached by Newton continuation may miss.
  threads = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(n / 256)));
  if (kinematics.closed_form() != nullptr) threads = 1;
  std::vector<std::size_t> begin(threads + 1);
  for (unsigned t = 0; t <= threads; ++t) begin[t] = n * t / threads;
  std::vector<Eigen::VectorXd> start(threads, kinematics.guess());
  if (threads > 1) {
    // Each chunk starts from a solution reached by continuation along the inputs
    // (coarse steps), so every chunk is on the branch the serial run would be on.
    // Where that is impossible (a gap or a toggle), the run stays serial.
    Workspace workspace(kinematics);
    FileAssembly assembly(kinematics);
    Eigen::VectorXd q = start[0];
    bool ok = assembly.has_home(workspace) ? assembly.reach(workspace, inputs[0], q, nullptr)
                                           : workspace.solve_position(inputs[0], q);
    start[0] = q;
    for (unsigned t = 1; t < threads && ok; ++t) {
      ok = workspace.continue_to(inputs[begin[t - 1]], inputs[begin[t]], q, nullptr);
      start[t] = q;
    }
    if (!ok) {
      threads = 1;
      begin = {0, n};
    }
  }
  std::vector<RunCursor> cursors(threads);
  auto solve_chunk = [&](unsigned t) {
    Solvers solvers(kinematics, settings.simd, settings.rate);
    cursors[t].q = start[t];
    cursors[t].start_given = threads > 1;  // carried there along the inputs from the first value's assembly
    solve_rows(kinematics, solvers, table, begin[t], begin[t + 1], begin[t + 1], begin[t], 0, cursors[t]);
  };
  if (threads == 1) {
    solve_chunk(0);
  } else {
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < threads; ++t) workers.emplace_back(solve_chunk, t);
    for (auto& worker : workers) worker.join();
  }
  for (const RunCursor& cursor : cursors) table.add_batch_rows(cursor.batch_rows);
  return table;
}

// The serial run, block by block: each block's table holds the last rows of the one
// before (the SIMD prediction reads back kLanes + 1 rows), then the block's values and
// kLanes - 1 more, so that a SIMD block starting inside the block is taken or refused
// exactly as in one table.
struct SweepSolver::State {
  State(const Kinematics& k, InputValues values, const SweepSettings& s)
      : kinematics(k),
        inputs(std::move(values)),
        settings(s),
        solvers(k, s.simd, s.rate),
        history(std::vector<double>{}, k.unknown_count(), k.layout().point_dimensions, s.rate, s.second_rate,
                k.frame_count()) {
    at.q = k.guess();
  }
  static constexpr std::size_t kHistory = BatchWorkspace::kLanes + 1;
  const Kinematics& kinematics;
  InputValues inputs;
  SweepSettings settings;
  Solvers solvers;
  RunCursor at;
  MotionTable history;  ///< The last rows solved (up to kHistory), ending at row next - 1.
  std::size_t next = 0;
};

SweepSolver::SweepSolver(const Kinematics& kinematics, InputValues inputs, const SweepSettings& settings)
    : state_(std::make_unique<State>(kinematics, std::move(inputs), settings)) {}
SweepSolver::~SweepSolver() = default;

std::size_t SweepSolver::size() const { return state_->inputs.size(); }
std::size_t SweepSolver::solved() const { return state_->next; }

void SweepSolver::solve_next(SweepBlock& block, std::size_t rows) {
  State& s = *state_;
  const std::size_t start = s.next, n = s.inputs.size();
  const std::size_t history = s.history.size();
  const std::size_t count = std::min(std::max<std::size_t>(rows, 1), n - start);
  const std::size_t ahead = std::min(count + BatchWorkspace::kLanes - 1, n - start);
  if (block.table.unknown_count() != s.kinematics.unknown_count() || block.table.input_rate() != s.settings.rate ||
      block.table.input_second_rate() != s.settings.second_rate) {
    block.table = MotionTable(std::vector<double>{}, s.kinematics.unknown_count(),
                              s.kinematics.layout().point_dimensions, s.settings.rate, s.settings.second_rate,
                              s.kinematics.frame_count());
  }
  MotionTable& table = block.table;
  table.assign_inputs(s.inputs, start - history, history + ahead);
  for (std::size_t row = 0; row < history; ++row) table.set(row, s.history, row);
  const std::size_t before = s.at.batch_rows;
  const std::size_t reached =
      solve_rows(s.kinematics, s.solvers, table, history, history + count, table.size(), 0, start - history, s.at);
  table.add_batch_rows(s.at.batch_rows - before);
  block.first = history;
  block.last = reached;
  block.run_row = start;
  s.next = start + (reached - history);
  const std::size_t keep = std::min(State::kHistory, reached);
  s.history.assign_inputs(s.inputs, s.next - keep, keep);
  for (std::size_t row = 0; row < keep; ++row) s.history.set(row, table, reached - keep + row);
}

struct RepeatedSweep::State {
  State(const Kinematics& k, const std::vector<double>& inputs, const SweepSettings& s)
      : kinematics(k),
        solvers(k, s.simd, s.rate),
        table(inputs, k.unknown_count(), k.layout().point_dimensions, s.rate, s.second_rate, k.frame_count()) {}
  const Kinematics& kinematics;
  Solvers solvers;
  MotionTable table;
};

RepeatedSweep::RepeatedSweep(const Kinematics& kinematics, const std::vector<double>& inputs,
                             const SweepSettings& settings)
    : state_(std::make_unique<State>(kinematics, inputs, settings)) {}
RepeatedSweep::~RepeatedSweep() = default;

const MotionTable& RepeatedSweep::solve() {
  State& s = *state_;
  s.solvers.scalar.reload_parameters();
  s.solvers.assembly.reset();
  if (s.solvers.simd) s.solvers.simd->reload_parameters();
  // solve_sweep's one chunk: from the guesses, every row set again.
  RunCursor cursor;
  cursor.q = s.kinematics.guess();
  const std::size_t n = s.table.size();
  if (n > 0) solve_rows(s.kinematics, s.solvers, s.table, 0, n, n, 0, 0, cursor);
  return s.table;
}

struct RowSolver::State {
  explicit State(const Kinematics& k) : kinematics(k), solvers(k, false, 0) {}
  const Kinematics& kinematics;
  Solvers solvers;
  RunCursor at;
};

RowSolver::RowSolver(const Kinematics& kinematics) : state_(std::make_unique<State>(kinematics)) {}
RowSolver::~RowSolver() = default;

void RowSolver::start() {
  State& s = *state_;
  s.solvers.scalar.reload_parameters();
  s.solvers.assembly.reset();
  s.at = RunCursor{};
  s.at.q = s.kinematics.guess();
}

void RowSolver::solve(MotionTable& table, std::size_t row) {
  State& s = *state_;
  solve_rows(s.kinematics, s.solvers, table, row, row + 1, row + 1, row, 0, s.at);
}

void RowSolver::solved_elsewhere(const MotionTable& table, std::size_t row) {
  state_->at.ok_row(table, row);
}

bool RowSolver::on_branch() const { return state_->at.have_previous; }

const Eigen::VectorXd* RowSolver::restart_position() {
  State& s = *state_;
  // Where the file's assembly has a home, a value without one before it is carried from there.
  const bool newton_alone = !s.at.have_previous && !s.at.q_singular && s.kinematics.closed_form() == nullptr &&
                            !s.solvers.assembly.has_home(s.solvers.scalar);
  return newton_alone ? &s.at.q : nullptr;
}

void RowSolver::failed_elsewhere(MotionTable& table, std::size_t row, std::size_t group, double residual) {
  // As solve_rows stores a row Newton alone could not close.
  RunCursor& at = state_->at;
  at.failed_row(table, row, group_open(group, residual, !at.after_gap));
}

void RowSolver::unassembled_elsewhere(MotionTable& table, std::size_t row, double limit, std::size_t group,
                                      double distance) {
  RunCursor& at = state_->at;
  if (!at.have_previous) {
    failed_elsewhere(table, row, group, distance);
    return;
  }
  // After an ok row solve_rows continues from it (Workspace::continue_to), which refuses
  // a step of more than kMaxContinuationSteps of the largest.
  MotionState failed;
  failed.input = table.input(row);
  failed.status = Status::unassembled;
  const double from = table.input(row - 1);
  const bool too_far =
      !(std::fabs(failed.input - from) <= solver::kMaxContinuationSteps * state_->kinematics.max_continuation_step());
  failed.failure.kind = too_far ? Failure::Kind::too_far : Failure::Kind::branch_stops;
  failed.failure.from = from;
  failed.failure.stopped_at = too_far ? from : limit;
  table.set(row, failed);
  at.after_gap = at.any_solved;
  at.have_previous = false;
}

void count_values_solved(std::uint64_t values) { values_solved.fetch_add(values, std::memory_order_relaxed); }

std::uint64_t values_solved_in_process() { return values_solved.load(std::memory_order_relaxed); }

}  // namespace kinema
