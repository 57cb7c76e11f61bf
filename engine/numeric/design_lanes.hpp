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
// lane too, and a value it leaves open is stored as the scalar run stores it. A lane a
// four-bar's loop closure places in closed form is solved without the tape (closed_value).
// Each lane's rows are what solve_sweep gives its design, to rounding, whichever designs
// share the lanes.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/lane_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/simd_math.hpp"

namespace kinema {

/// Where a loop of four terms closes that has two known at each input (a crank's, signed
/// length `crank` at the input's angle, and a fixed vector) and two of unknown angle
/// (lengths `first`, `second`): where |crank e^(i input) + fixed| lies between
/// |first - second| and first + second. A design study's four-bars have one: it tells,
/// without Newton, the values that cannot close.
class LoopReach {
 public:
  LoopReach() = default;  ///< None: every input may close.
  LoopReach(double crank, double fixed_x, double fixed_y, double first, double second);
  /// How far the known terms' sum lies outside the reach of the other two (<= 0 within
  /// it): the least |Phi| any position leaves at `input`.
  double distance(double input) const;
  /// Whether `input` (its cosine and sine) is out of reach by more than rounding could
  /// hide from Newton (which counts max |Phi| within solver::kRoundingTolerance of the
  /// lengths as closed). Squares compared: no root per value.
  bool clearly_open(double cos_input, double sin_input) const {
    const double x = crank_ * cos_input + fixed_x_, y = crank_ * sin_input + fixed_y_, square = x * x + y * y;
    return square > far_square_ || square < near_square_;
  }
  /// Whether any input is clearly open (else the test need not be made).
  bool ever_open() const { return ever_open_; }
  /// Where the loop stops closing between `from` (within reach) and `to` (out of it).
  double limit(double from, double to) const;

 private:
  double crank_ = 0, fixed_x_ = 0, fixed_y_ = 0, first_ = 0, second_ = 0;
  // The squared lengths of the known sum past which (or short of which) it is clearly out
  // of reach; never where there is no reach.
  double far_square_ = INFINITY, near_square_ = -INFINITY;
  bool ever_open_ = false;
};

/// The same loop with its two terms of unknown angle told apart: their signed lengths
/// (the loop is crank e^(i input) + fixed + first e^(i q[first_unknown]) + second
/// e^(i q[second_unknown]) = 0) and unknowns. Its positions are where two circles meet:
/// DesignLanes starts Newton there instead of at the prediction (one evaluation closes
/// it where the prediction takes three or four).
struct LoopClosure {
  double crank = 0, fixed_x = 0, fixed_y = 0, first = 0, second = 0;
  std::size_t first_unknown = 0, second_unknown = 1;
};

/// A term of a point's position that turns with one variable of a loop closure's
/// mechanism: a factor fixed per design (x + i y: the term's length times e^(i offset))
/// times e^(i variable), the variable the input (-1) or an unknown (its index). A point's
/// position is the sum of its terms and of terms that do not move (those need no entry:
/// they add nothing to its velocity or acceleration).
struct ClosedPointTerm {
  std::size_t point = 0;
  int variable = -1;
};

/// |x wrapped to [-pi, pi]|, rounding by adding and taking away 1.5 * 2^52 (no libm
/// call; |x| < 2^51 turns): in a loop across lanes too.
inline double angle_magnitude(double x) {
  constexpr double kTurn = 2 * 3.14159265358979323846, kRound = 0x1.8p52;
  const double turns = (x / kTurn + kRound) - kRound;
  return std::fabs(x - turns * kTurn);
}

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
  /// Lane l's loop reach (none: every value to Newton): a value clearly out of it is
  /// stored as not assembling without Newton or continuation (RowSolver::unassembled_elsewhere).
  void set_reach(std::size_t lane, const LoopReach& reach);
  /// Lane l's angle measure (offset NaN: none; the unknowns the same in every lane): over
  /// the values that assemble, the least |q[second] - q[first] + offset| wrapped to
  /// [-pi, pi] (angle_magnitude) is kept, with the two angles where it is least (the first
  /// such value): a four-bar's transmission measure.
  void set_angle_measure(std::size_t lane, std::size_t first, std::size_t second, double offset) {
    measure_unknowns_[0] = first, measure_unknowns_[1] = second, measure_offset_[lane] = offset;
  }
  /// The two angles where lane l's measure was least in the last solve(); false where no
  /// value assembled (or no measure was set).
  bool least_measure_angles(std::size_t lane, double& first, double& second) const;
  /// Lane l's position at `row` of the last solve() (the lanes' kept, else the table's).
  Eigen::VectorXd position(std::size_t lane, std::size_t row) const;
  /// Unknown i's rate in lane l at rows [0, rows) of the last solve(): where the status is
  /// ok, the lanes' kept or the table's; NaN elsewhere.
  void rates_at_ok_rows(std::size_t lane, std::size_t i, std::size_t rows, double* rates) const;
  /// Lane l's loop closure (the same unknowns in every lane): each value predicted is
  /// started from the closed form on the predicted branch, the prediction kept for the
  /// branch test; near a toggle (the two branches within 1e-3 of the lengths) or where
  /// the prediction is not clearly on one branch, from the prediction as before.
  void set_closure(std::size_t lane, const LoopClosure& closure);
  /// Whether the values solved in the lanes are kept lane by lane with their positions and
  /// rates only (position(), rates_at_ok_rows(); their second rates, residuals, conditions
  /// and points not: what a design study, which keeps the largest figures in the lanes,
  /// does not read), not written to the tables; or written to the tables in full (the
  /// default; the points' velocities and accelerations, not their positions, and for a
  /// value closed_value solved, max |Phi| of the closed form's own terms). A row the
  /// scalar run goes on from is written to the table in full either way.
  void set_positions_and_rates_only(bool only) { positions_and_rates_ = only; }
  /// The points' moving terms (the same in every lane; every point planar and the sum of
  /// these and fixed terms): with a closure in every lane and positions and rates only,
  /// a value whose every lane the closed form starts is solved without the tape: its
  /// rates and second rates from the loop's velocity and acceleration equations (the 2x2
  /// system in the two angles at the closed-form position, Cramer's rule), its points'
  /// velocities and accelerations from these terms (see closed_value).
  void set_point_terms(const std::vector<ClosedPointTerm>& terms);
  /// Lane l's factors of those terms: x, y of term t at 2 t, 2 t + 1.
  void set_point_term_values(std::size_t lane, const double* factors);
  /// Solves the run for lanes [0, count).
  void solve(std::size_t count);
  /// Lane l's rows of the last solve(). The points' columns hold the values the scalar run
  /// solved (and, written in full, the lanes' velocities and accelerations): of the others
  /// each point's largest speed and acceleration are kept (largest_speed,
  /// largest_acceleration).
  const MotionTable& table(std::size_t lane) const;
  /// Point p's largest speed (acceleration magnitude) over lane l's values whose status is
  /// ok in the last solve(), as MotionTable::point(row, p).speed() gives each; NaN with none.
  double largest_speed(std::size_t lane, std::size_t p) const;
  double largest_acceleration(std::size_t lane, std::size_t p) const;
  /// Unknown i's largest |rate| (|second rate|) over lane l's values whose status is ok in
  /// the last solve(), kept as they are solved (the table's columns need no scan); NaN
  /// with none.
  double largest_rate(std::size_t lane, std::size_t i) const { return largest_rate_[i * kLanes + lane]; }
  double largest_second_rate(std::size_t lane, std::size_t i) const { return largest_second_rate_[i * kLanes + lane]; }
  /// Values the last solve() solved in the lanes (the others by the scalar run).
  std::size_t lane_values() const { return lane_values_; }
  /// Values of the last solve() started from the loop's closed form.
  std::size_t closed_form_values() const { return closed_form_values_; }
  /// Values of the last solve() whose rates, second rates and points the closed form gave
  /// (no tape, no LU), ok or not.
  std::size_t closed_rate_values() const { return closed_rate_values_; }

 private:
  struct Lane;
  std::vector<double> inputs_, cos_inputs_, sin_inputs_;  // the cosines and sines for LoopReach
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
  std::vector<double> largest_rate_, largest_second_rate_;  ///< Unknown i of lane l at i * kLanes + l (NaN: none).
  double tolerance_[kLanes], residual_[kLanes];
  std::size_t lane_values_ = 0, closed_form_values_ = 0, closed_rate_values_ = 0;
  bool positions_and_rates_ = false;
  LoopReach reach_[kLanes];
  // Each lane's loop closure (closes_[l] 1 where set), in lanes for the loops across them.
  double closes_[kLanes] = {}, closure_crank_[kLanes] = {}, closure_fixed_x_[kLanes] = {},
         closure_fixed_y_[kLanes] = {}, closure_first_[kLanes] = {}, closure_second_[kLanes] = {};
  // 1 / first, 1 / second, 1 / the longer's square: products in the loop, not quotients.
  double closure_over_first_[kLanes] = {}, closure_over_second_[kLanes] = {}, closure_over_length_square_[kLanes] = {};
  std::size_t closure_unknowns_[2] = {0, 1};
  // Of the last close_loops: closed_[l] 1 where lane l was moved onto the closed form, and
  // there the loop's two terms of unknown angle (first e^(i alpha), second e^(i beta)).
  std::size_t closed_lanes_ = 0;  // the lanes with closed_ 1
  double closed_[kLanes] = {}, first_x_[kLanes] = {}, first_y_[kLanes] = {}, second_x_[kLanes] = {},
         second_y_[kLanes] = {};
  // set_point_terms': factor x, y of term t of lane l at (2 t + 0, 1) kLanes + l.
  std::vector<ClosedPointTerm> point_terms_;
  std::vector<double> point_term_factors_;
  bool closed_rates_ = false;
  /// closed_value's points: point stage outputs' layout (only velocities and accelerations set).
  std::vector<double> closed_points_;
  /// Positions and rates only: row r's q_i of lane l at (2 n r + i) kLanes + l, qd_i at
  /// (2 n r + n + i) kLanes + l; kept_ok_ 1 at r kLanes + l where the lanes solved it.
  std::vector<double> kept_, kept_ok_;
  // set_angle_measure's offsets (NaN: none); the least measure so far (NaN: none) and the
  // two angles there.
  double measure_offset_[kLanes], least_measure_[kLanes], least_first_[kLanes], least_second_[kLanes];
  std::size_t measure_unknowns_[2] = {0, 1};
  std::vector<double> predicted_;  ///< Each lane's predicted start (start_'s layout): the branch test's.

  /// Each lane's start at `row` into start_: take[l] 1 for a lane whose value is predicted
  /// (or the first, from the guesses), restart[l] 1 for one that starts Newton alone after
  /// a value that did not assemble (RowSolver::restart_position), out_of_reach[l] 1 (and
  /// neither) for one whose LoopReach says the value cannot close. Whether any restarts.
  bool choose_lanes(std::size_t row, std::size_t count, double* take, double* restart, double* out_of_reach);
  /// start_ of the lanes predicted (predicted[l] 1) h on from their last row, as the
  /// scalar run predicts (solver::predict_second_order).
  KINEMA_LANE_LOOPS void predict(double h, const double* predicted);
  /// start_ of the lanes predicted with a closure moved onto the closed form (see
  /// set_closure), at the input of `row`; the count moved.
  KINEMA_LANE_LOOPS std::size_t close_loops(std::size_t row, const double* predicted);
  /// The rows just solved in the lanes (ok[l] 1) as each lane's last row.
  KINEMA_LANE_LOOPS void keep_previous(const double* ok);
  /// Newton, rates and points at `input` for the lanes taken from start_; ok[l] 1 where
  /// a lane's values are the scalar run's (check_branch: within the branch tolerance of
  /// the start, as a predicted value must be).
  KINEMA_LANE_LOOPS void solve_value(double input, bool check_branch, const double* take, double* ok);
  /// solve_value's results for the lanes whose start the closed form placed (closed_),
  /// from the loop: the positions as placed; the rates and second rates from the loop's
  /// velocity and acceleration equations, linear in them (a 2x2 system: the columns are
  /// the two terms' derivatives in their angles, i first e^(i alpha) and i second
  /// e^(i beta)), by Cramer's rule; the points from their terms. ok as solve_value's: the
  /// branch test, Phi_q's column-scaled pivots clearly regular (their ratio as
  /// factorise() has it), the numbers finite. The other lanes keep what solve_value gave
  /// them (`merge`: it ran, their points copied beside the closed form's).
  KINEMA_LANE_LOOPS void closed_value(std::size_t row, bool check_branch, bool merge, double* ok);
  /// Workspace::solve_position's damped Newton (halved steps) from start_ for the lanes
  /// restarted; open[l] 1 where it stops open as the scalar solver would (max |Phi| in
  /// residual_, its row in worst_row_), 0 where the scalar run is to solve the value
  /// (it closes, or needs a least-squares step).
  KINEMA_LANE_LOOPS void restart_values(double input, const double* restart, double* open);
  /// The lanes' value at `row` kept (positions and rates only; ok[l] 1 where lane l's is
  /// ok), and the measure.
  KINEMA_LANE_LOOPS void keep_row(std::size_t row, const double* ok);
  /// Lane l's measure at a row the scalar run solved (that assembles).
  void keep_measure(std::size_t lane, const MotionTable& table, std::size_t row);
  /// Lane l's value at `row` into its table in full (`closed`: closed_value's).
  void store(std::size_t lane, std::size_t row, bool closed);
  /// Lane l goes to the scalar run at `row`: the row before, where it was last in the
  /// lanes, written in full and told to the scalar run.
  void hand_over(std::size_t lane, std::size_t row);
  /// The lanes' rates, second rates, point speeds and accelerations (ok[l] 1 where lane
  /// l's value is ok) into their largest.
  /// `closed`: the points from closed_value (beside the others'), else from the tape's point stage.
  KINEMA_LANE_LOOPS void keep_largest(const double* ok, bool closed);
  /// Component c of point p's velocity (kind 1) or acceleration (2), lane by lane.
  const double* point_vector(bool closed, std::size_t p, std::size_t kind, std::size_t c);
  /// The same for a row of lane l's table the scalar run solved.
  void keep_largest(std::size_t lane, std::size_t row);
};

}  // namespace kinema
