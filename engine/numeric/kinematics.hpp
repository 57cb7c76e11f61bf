// Numeric kinematics of one mechanism: the derivation compiled to register
// tapes (built once), Newton-Raphson for the position, one LU of Phi_q for
// velocity and acceleration, and continuation along lists and sweeps that
// keeps the assembly branch and says so when it cannot.
#pragma once

#include <Eigen/Dense>

#include <iterator>
#include <string>
#include <vector>

#include <kinema/engine/numeric/tape.hpp>
#include <kinema/engine/symbolic/derivation.hpp>
#include <kinema/engine/numeric/simd_math.hpp>
#include <kinema/loops/mechanism.hpp>

namespace kinema {

/// Immutable compiled model; Workspace holds the buffers of one caller.
class Kinematics {
 public:
  Kinematics(const Mechanism& mechanism, const Derivation& derivation);

  const Mechanism& mechanism() const { return mechanism_; }
  std::size_t unknown_count() const { return unknown_count_; }
  std::size_t point_count() const { return point_count_; }
  /// Typical length (largest length parameter), for tolerances and scaling.
  double length_scale() const { return length_scale_; }
  /// Largest input step continuation takes at once (2 deg, or 1 % of the length scale).
  double max_continuation_step() const;
  /// Starting guesses from the file, SI.
  Eigen::VectorXd guess() const;
  /// "theta2 = 30 deg" / "r = 12.5 mm" in the output units.
  std::string describe_input(double input) const;

  /// The compiled evaluator, for exporters (codegen). Inputs:
  /// [parameters, theta, thetad, thetadd, q, qd, qdd]; stages: kPositionStage
  /// (Phi, Phi_q column-major, Phi_theta), kAccelerationStage (gamma), kPointStage
  /// (x, y, vx, vy, ax, ay per point).
  const CompiledExpressions& evaluator() const { return evaluator_; }
  static constexpr std::size_t kPositionStage = 0, kAccelerationStage = 1, kPointStage = 2;
  /// Input levels of the evaluator: parameters 0 (prepared once), input and rates,
  /// then coordinates (qd, qdd above them).
  static constexpr int kInputLevel = 1, kCoordinateLevel = 2;
  const std::vector<double>& parameter_values() const { return parameter_values_; }

 private:
  friend class Workspace;
  friend class BatchWorkspace;
  Mechanism mechanism_;
  std::size_t unknown_count_ = 0, point_count_ = 0, parameter_count_ = 0;
  double length_scale_ = 1.0;
  std::vector<double> parameter_values_;
  /// One tape for position, acceleration and points: sin/cos and every other
  /// subexpression computed once per input value, whatever stage needs it.
  CompiledExpressions evaluator_;
};

enum class Status {
  ok,           ///< Position, rates and second rates are valid.
  singular,     ///< Position valid; Phi_q rank-deficient, rates undefined.
  unassembled,  ///< The loops cannot be closed (on this branch) at this input.
};

const char* status_name(Status status);

struct PointMotion {
  double x = 0, y = 0, vx = 0, vy = 0, ax = 0, ay = 0;  ///< SI.
};

/// Everything known at one input value (SI).
struct MotionState {
  double input = 0, input_rate = 0, input_second_rate = 0;
  Status status = Status::unassembled;
  std::string message;  ///< Why, when status is not ok.
  Eigen::VectorXd q, qd, qdd;  ///< q empty when unassembled; qd, qdd empty unless ok.
  std::vector<PointMotion> points;  ///< Empty unless ok.
  double loop_residual = 0;      ///< max |Phi| at the solution (m).
  double reciprocal_condition = 0;  ///< of the length-scaled Phi_q; ~0 at a toggle.
};

/// The results of analyse(): one row per input value, kept in flat arrays so that
/// a long sweep costs no allocation per value (a 10^6-value six-bar sweep is a
/// few hundred MB in one piece, not millions of small blocks). Rows read back as
/// MotionState (a copy), by index or by iterating.
class MotionTable {
 public:
  MotionTable() = default;
  /// Rows for `inputs`, all unassembled until set.
  MotionTable(const std::vector<double>& inputs, std::size_t unknowns, std::size_t points, double rate,
              double second_rate);

  std::size_t size() const { return input_.size(); }
  bool empty() const { return input_.empty(); }
  std::size_t unknown_count() const { return n_; }
  std::size_t point_count() const { return points_per_row_; }
  double input_rate() const { return rate_; }
  double input_second_rate() const { return second_rate_; }
  /// How many rows analyse() solved in SIMD blocks (the rest one by one): a diagnostic.
  std::size_t batch_rows() const { return batch_rows_; }
  /// Heap bytes held by the table (for the benchmark's memory figure).
  std::size_t bytes() const;

  double input(std::size_t row) const { return input_[row]; }
  Status status(std::size_t row) const { return status_[row]; }
  const std::string& message(std::size_t row) const { return message_[row]; }
  /// Coordinates, rates and second rates of a row (meaningful as MotionState says).
  using Column = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>;
  Column q(std::size_t row) const { return column_view(q_, row); }
  Column qd(std::size_t row) const { return column_view(qd_, row); }
  Column qdd(std::size_t row) const { return column_view(qdd_, row); }
  PointMotion point(std::size_t row, std::size_t p) const {
    const double* v = points_.data() + p * 6 * size() + row;
    const std::size_t rows = size();
    return {v[0], v[rows], v[2 * rows], v[3 * rows], v[4 * rows], v[5 * rows]};
  }
  double loop_residual(std::size_t row) const { return loop_residual_[row]; }
  double reciprocal_condition(std::size_t row) const { return reciprocal_condition_[row]; }

  /// Row `row` as a MotionState (a copy).
  MotionState operator[](std::size_t row) const;
  /// Stores a state (its input, status, message and whatever its status makes valid).
  void set(std::size_t row, const MotionState& state);

  class const_iterator {
   public:
    using value_type = MotionState;
    using difference_type = std::ptrdiff_t;
    using reference = MotionState;
    using pointer = void;
    using iterator_category = std::input_iterator_tag;
    const_iterator(const MotionTable* table, std::size_t row) : table_(table), row_(row) {}
    MotionState operator*() const { return (*table_)[row_]; }
    const_iterator& operator++() { ++row_; return *this; }
    bool operator==(const const_iterator& other) const { return row_ == other.row_; }
    bool operator!=(const const_iterator& other) const { return row_ != other.row_; }
   private:
    const MotionTable* table_;
    std::size_t row_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size()}; }

 private:
  friend class BatchWorkspace;
  friend MotionTable analyse(const Kinematics&, const std::vector<double>&, double, double, unsigned, bool);
  std::size_t n_ = 0, points_per_row_ = 0, batch_rows_ = 0;
  double rate_ = 0, second_rate_ = 0;
  std::vector<double> input_, q_, qd_, qdd_, loop_residual_, reciprocal_condition_;
  std::vector<Status> status_;
  std::vector<std::string> message_;
  /// Column-major: value i of row r at i * size() + r, so a block of rows is a
  /// contiguous copy per quantity. Points: x, y, vx, vy, ax, ay of each point.
  std::vector<double> points_;
  Column column_view(const std::vector<double>& values, std::size_t row) const {
    return Column(values.data() + row, Eigen::Index(n_), Eigen::InnerStride<>(Eigen::Index(size())));
  }
};

/// Buffers for one thread of evaluation.
class Workspace {
 public:
  explicit Workspace(const Kinematics& kinematics);

  /// Newton-Raphson from q (updated in place). False when it does not converge;
  /// then worst_loop names the loop that stays open.
  bool solve_position(double input, Eigen::VectorXd& q, std::size_t* worst_loop = nullptr,
                      double* residual = nullptr);

  /// Rates, second rates and points at a solved position.
  MotionState motion(double input, double rate, double second_rate, const Eigen::VectorXd& q);
  /// The same into an existing state, reusing its storage (no allocation on the hot path).
  void motion_into(double input, double rate, double second_rate, const Eigen::VectorXd& q,
                   MotionState& state);

  /// dq/dtheta at a solved position (false when Phi_q is singular).
  bool sensitivity(double input, const Eigen::VectorXd& q, Eigen::VectorXd& dq);

  /// Continues the solution from (from, q) to `to` in small steps so that the
  /// branch is kept; false when that is impossible (limit or branch point).
  bool continue_to(double from, double to, Eigen::VectorXd& q, double* stuck_at);

  /// Newton from `predicted` at `to`; accepts (into q) only a solution close to the
  /// prediction, i.e. on the same branch.
  bool predict_and_correct(double to, const Eigen::VectorXd& predicted, Eigen::VectorXd& q);
  /// Largest input step continuation takes at once (2 deg, or 1 % of the length scale).
  double max_continuation_step() const { return k_.max_continuation_step(); }

  /// The next value along a path: from `state` (solved at a nearby input, status ok,
  /// on the wanted branch) predicted to second order by its rates, corrected by Newton
  /// and checked to stay on the branch (else continued in small steps); then rates and
  /// points at `input` into `state`. False, with state unchanged, when the branch
  /// cannot reach `input` (a limit or toggle position in between).
  bool advance(double input, double rate, double second_rate, MotionState& state);

 private:
  const Kinematics& k_;
  std::size_t n_;
  std::vector<double> registers_;  ///< Tape registers; the first ones are its inputs.
  /// Position stage outputs: Phi, Phi_q (column-major), Phi_theta.
  std::vector<double> position_out_, acceleration_out_, point_out_;
  /// LU (partial pivoting, in place, row-major) of Phi_q with columns scaled by
  /// column_scale_; plain loops for small n, so the hot path allocates nothing.
  std::vector<double> lu_, inverse_pivots_;
  std::vector<std::size_t> pivots_;
  std::vector<double> column_scale_, rhs_;
  Eigen::VectorXd step_, trial_, predicted_, slope_, trial_q_;
  bool evaluated_ = false;  ///< The position stage's registers hold (evaluated_input_, q).
  double evaluated_input_ = 0;

  const double* phi() const { return position_out_.data(); }
  const double* phi_q() const { return position_out_.data() + n_; }
  const double* phi_theta() const { return position_out_.data() + n_ + n_ * n_; }
  void evaluate_position(double input, const Eigen::VectorXd& q);
  bool evaluated_at(double input, const Eigen::VectorXd& q) const;
  /// max |Phi| at the evaluated position (NaN if any is).
  double residual_norm() const;
  /// LU of Phi_q with its columns scaled by column_scale_.
  void factorise();
  /// min/max |pivot| of the factorisation (0 when not finite).
  double pivot_ratio() const;
  Eigen::MatrixXd scaled_phi_q() const;
  /// Reciprocal condition of the scaled Phi_q from the factorisation: the pivot
  /// ratio where that is clearly fine, else from the singular values.
  double reciprocal_condition() const;
  /// Solves Phi_q x = rhs_ with the factorisation (undoing the column scaling).
  void solve_rhs(double* x) const;
};

/// Solves at each input value in order, warm-starting from the previous one.
/// Failures become rows with status != ok; nothing is thrown for them.
/// With threads > 1 a long run is split into chunks whose starting positions are
/// found by continuation first, so the branch is the serial run's.
/// With batch, consecutive values of a sweep are solved kLanes at a time on the
/// batch (SIMD) tape, predicted from the rows before and checked to stay on their
/// branch (else that block is solved one value at a time).
MotionTable analyse(const Kinematics& kinematics, const std::vector<double>& inputs, double rate,
                    double second_rate, unsigned threads = 1, bool batch = true);

/// Solves blocks of kLanes consecutive input values at once, everything lane-parallel:
/// the tape, the LU of Phi_q (partial pivoting by selects), Newton, rates, points.
class BatchWorkspace {
 public:
  static constexpr std::size_t kLanes = CompiledExpressions::kBatchLanes;
  explicit BatchWorkspace(const Kinematics& kinematics);

  /// Solves rows [first, first + kLanes) of `table` (inputs already stored), predicted
  /// from the solved rows [history_begin, first) (at least row first - 1, status ok).
  /// Writes the rows only when every value converged on its predicted branch,
  /// clearly regular; returns false otherwise (the caller solves them one by one).
  KINEMA_LANE_LOOPS bool solve(MotionTable& table, std::size_t first, std::size_t history_begin);

 private:
  const Kinematics& k_;
  std::size_t n_;
  std::vector<double> registers_;  ///< Register r of lane l at r * kLanes + l.
  std::vector<double> lu_;         ///< Element (i, j) of lane l at (i n + j) kLanes + l.
  std::vector<double> pivots_;     ///< Row chosen at column c for lane l at c kLanes + l.
  std::vector<double> x_, predicted_, column_scale_;

  double* lanes(std::size_t reg) { return registers_.data() + reg * kLanes; }
  KINEMA_LANE_LOOPS bool predict(const MotionTable& table, std::size_t first, std::size_t history_begin);
  /// Column-scaled Phi_q from the registers, factorised; false unless every lane's
  /// pivots are clearly regular (ratio >= 1e-2).
  KINEMA_LANE_LOOPS bool factorise();
  /// min/max |pivot| of each lane's factorisation.
  KINEMA_LANE_LOOPS void pivot_ratios(double* ratio) const;
  double pivot_ratio_[kLanes];
};

}  // namespace kinema
