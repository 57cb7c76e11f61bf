// One run of input values solved for kLanes designs of a mechanism at once (a design
// study, issue 36): lane l of the batch tape holds design l's parameter values (the work
// on them alone rerun per lane), every lane at the same input value, each lane's Newton
// started from its own last row predicted by its rates (as the scalar run predicts), a
// few iterations with each lane's own convergence test, the LU of Phi_q vectorised
// across lanes; then rates, second rates and points. A lane that does not converge
// cleanly at a value (more iterations, a step that does not lower the residual, a pivot
// not clearly regular, another branch, numbers not finite) is solved at that value by
// the scalar run (RowSolver), and goes on in the lanes from the next value after one it
// solves ok. After a value that does not assemble, the scalar run's Newton alone from the
// last position (its steps halved where they do not lower the residual) runs lane by
// lane too, and a value it leaves open is stored as the scalar run stores it. Each lane's
// table is what solve_sweep gives its design, to rounding.
#pragma once

#include <memory>
#include <vector>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/lane_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/simd_math.hpp"

namespace kinema {

class DesignLanes : LaneSystem {
 public:
  using LaneSystem::kLanes;
  /// Lanes on `kinematics`' tape (their parameter values set by set_design), the run
  /// `inputs` at the input's rates `rate` (not 0) and `second_rate`.
  DesignLanes(const Kinematics& kinematics, const std::vector<double>& inputs, double rate, double second_rate);
  ~DesignLanes();
  DesignLanes(const DesignLanes&) = delete;
  DesignLanes& operator=(const DesignLanes&) = delete;

  /// Lane l's design: the value of every parameter (SI, formula parameters following).
  void set_design(std::size_t lane, const double* values);
  /// Solves the run for lanes [0, count).
  void solve(std::size_t count);
  /// Lane l's rows of the last solve(). The points' columns hold only the values the
  /// scalar run solved: of the others each point's largest speed and acceleration are
  /// kept (largest_speed, largest_acceleration), not written value by value.
  const MotionTable& table(std::size_t lane) const;
  /// Point p's largest speed (acceleration magnitude) over lane l's values whose status is
  /// ok in the last solve(), as MotionTable::point(row, p).speed() gives each; NaN with none.
  double largest_speed(std::size_t lane, std::size_t p) const;
  double largest_acceleration(std::size_t lane, std::size_t p) const;
  /// Values the last solve() solved in the lanes (the others by the scalar run).
  std::size_t lane_values() const { return lane_values_; }

 private:
  struct Lane;
  std::vector<double> inputs_;
  double rate_, second_rate_;
  std::vector<std::unique_ptr<Lane>> lanes_;
  std::vector<double> start_;  ///< Each lane's start: unknown i of lane l at i kLanes + l.
  std::vector<double> step_, phi_;  ///< restart_values: each lane's step and Phi at its position.
  std::size_t worst_row_[kLanes];
  std::vector<double> previous_;  ///< Each lane's last ok row: q_i, qd_i, qdd_i at (3 i + 0, 1, 2) kLanes + l.
  /// Point p of lane l at p * kLanes + l: the largest length from the scalar run's rows
  /// and from squares vector_length takes apart (NaN: none), and the largest square of
  /// the others (0: none; its root is the largest length, the root being monotonic).
  std::vector<double> largest_speed_, largest_acceleration_, largest_speed_square_, largest_acceleration_square_;
  double tolerance_[kLanes], residual_[kLanes];
  std::size_t lane_values_ = 0;

  /// Each lane's start at `row` into start_: take[l] 1 for a lane whose value is predicted
  /// (or the first, from the guesses), restart[l] 1 for one that starts Newton alone after
  /// a value that did not assemble (RowSolver::restart_position). Whether any is.
  bool choose_lanes(std::size_t row, std::size_t count, double* take, double* restart);
  /// start_ of the lanes predicted (predicted[l] 1) h on from their last row, as the
  /// scalar run predicts (solver::predict_second_order).
  KINEMA_LANE_LOOPS void predict(double h, const double* predicted);
  /// The rows just solved in the lanes (ok[l] 1) as each lane's last row.
  KINEMA_LANE_LOOPS void keep_previous(const double* ok);
  /// Newton, rates and points at `input` for the lanes taken from start_; ok[l] 1 where
  /// a lane's values are the scalar run's (check_branch: within the branch tolerance of
  /// the start, as a predicted value must be).
  KINEMA_LANE_LOOPS void solve_value(double input, bool check_branch, const double* take, double* ok);
  /// Workspace::solve_position's damped Newton (halved steps) from start_ for the lanes
  /// restarted; open[l] 1 where it stops open as the scalar solver would (max |Phi| in
  /// residual_, its row in worst_row_), 0 where the scalar run is to solve the value
  /// (it closes, or needs a least-squares step).
  KINEMA_LANE_LOOPS void restart_values(double input, const double* restart, double* open);
  void store(std::size_t lane, std::size_t row);
  /// The lanes' point speeds and accelerations (ok[l] 1 where lane l's value is ok) into
  /// their largest.
  KINEMA_LANE_LOOPS void keep_largest(const double* ok);
  /// The same for a row of lane l's table the scalar run solved.
  void keep_largest(std::size_t lane, std::size_t row);
};

}  // namespace kinema
