// Results at input values: MotionState for one value, MotionTable for many,
// kept in flat column-major arrays so that a long sweep costs no allocation
// per value (a 10^6-value six-bar sweep is a few hundred MB in one piece).
#pragma once

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <vector>

#include "engine/numeric/failure.hpp"
#include "engine/base/input_values.hpp"

namespace kinema {

/// The length of (x, y, z): the square root of the sum of squares where that sum is a
/// normal number (fast), std::hypot where the squares overflow or underflow (|v| of
/// components of 1e160 is 1e160, not inf).
inline double vector_length(double x, double y, double z = 0) {
  const double squares = x * x + y * y + z * z;
  if (squares > 1e-300 && squares < 1e300) return std::sqrt(squares);
  return std::hypot(x, y, z);
}

/// Position, velocity and acceleration of a point (SI); `dimension` components
/// are meaningful (2 for planar points, 3 for spatial ones).
struct PointMotion {
  std::size_t dimension = 2;
  std::array<double, 3> position{}, velocity{}, acceleration{};
  double speed() const { return vector_length(velocity[0], velocity[1], velocity[2]); }
  double acceleration_magnitude() const { return vector_length(acceleration[0], acceleration[1], acceleration[2]); }
};

/// Angular velocity and angular acceleration of a frame of a spatial chain relative to
/// the observer, in the observer's basis (rad/s, rad/s^2).
struct FrameMotion {
  std::array<double, 3> angular_velocity{}, angular_acceleration{};
};

/// Everything known at one input value (SI).
struct MotionState {
  double input = 0, input_rate = 0, input_second_rate = 0;
  Status status = Status::unassembled;
  Failure failure;             ///< Why, when status is not ok (or a note when it is).
  Eigen::VectorXd q, qd, qdd;  ///< q empty when unassembled; qd, qdd empty unless ok.
  std::vector<PointMotion> points;  ///< Empty unless ok.
  std::vector<FrameMotion> frames;  ///< Empty unless ok.
  double loop_residual = 0;         ///< max |Phi| at the solution (m).
  double reciprocal_condition = 0;  ///< of the length-scaled Phi_q; ~0 at a toggle.
};

class MotionTable {
 public:
  MotionTable() = default;
  /// Rows for `inputs`, all unassembled until set; points of the given dimensions, and
  /// `frames` frames (spatial chains).
  MotionTable(const std::vector<double>& inputs, std::size_t unknowns, const std::vector<std::size_t>& point_dimensions,
              double rate, double second_rate, std::size_t frames = 0);

  /// Makes the table rows for values [first, first + count) of `inputs`, all unassembled
  /// until set (what a streamed run reuses block after block; keeps its capacity).
  void assign_inputs(const InputValues& inputs, std::size_t first, std::size_t count);

  std::size_t size() const { return input_.size(); }
  bool empty() const { return input_.empty(); }
  std::size_t unknown_count() const { return n_; }
  std::size_t point_count() const { return point_dimensions_.size(); }
  std::size_t frame_count() const { return frame_count_; }
  double input_rate() const { return rate_; }
  double input_second_rate() const { return second_rate_; }
  /// A row's input rate and second rate: the run's, times the row's direction along a circuit.
  double input_rate(std::size_t row) const { return direction_.empty() ? rate_ : rate_ * direction_[row]; }
  double input_second_rate(std::size_t row) const {
    return direction_.empty() ? second_rate_ : second_rate_ * direction_[row];
  }

  /// Rows along a circuit (engine/numeric/circuit.hpp) carry the direction the input
  /// moves in (+1, or -1 after a toggle) and each dyad's assembly sign (bit k set: dyad
  /// k on its -1 solution).
  void make_circuit() {
    direction_.assign(size(), 1);
    assembly_.assign(size(), 0);
  }
  bool is_circuit() const { return !direction_.empty(); }
  int direction(std::size_t row) const { return direction_.empty() ? 1 : direction_[row]; }
  int assembly_sign(std::size_t row, std::size_t dyad) const {
    return assembly_.empty() || ((assembly_[row] >> dyad) & 1u) == 0 ? 1 : -1;
  }
  void set_circuit_row(std::size_t row, int direction, std::uint64_t assembly) {
    direction_[row] = static_cast<signed char>(direction);
    assembly_[row] = assembly;
  }
  /// How many rows were solved in SIMD blocks (the rest one by one): a diagnostic.
  std::size_t batch_rows() const { return batch_rows_; }
  void add_batch_rows(std::size_t rows) { batch_rows_ += rows; }
  /// Heap bytes held by the table (for the benchmark's memory figure).
  std::size_t bytes() const;

  /// Columns worked out from the solved rows after the solve, for a printer to show
  /// (kinema eval --sensitivity: engine/analysis/sensitivities fills them): `columns` of
  /// them, each over every row (their values until set: NaN).
  void set_derived_count(std::size_t columns) {
    if (derived_count_ == columns && derived_.size() == columns * size()) return;  // kept
    derived_count_ = columns;
    derived_.assign(columns * size(), NAN);
  }
  std::size_t derived_count() const { return derived_count_; }
  const double* derived_column(std::size_t k) const { return derived_.data() + k * size(); }
  double* derived_column(std::size_t k) { return derived_.data() + k * size(); }

  double input(std::size_t row) const { return input_[row]; }
  Status status(std::size_t row) const { return status_[row]; }
  const Failure& failure(std::size_t row) const { return failure_[row]; }
  /// Coordinates, rates and second rates of a row (meaningful as MotionState says).
  using Column = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>;
  Column q(std::size_t row) const { return column_view(q_, row); }
  Column qd(std::size_t row) const { return column_view(qd_, row); }
  Column qdd(std::size_t row) const { return column_view(qdd_, row); }
  PointMotion point(std::size_t row, std::size_t p) const;
  /// Value k (of 3 * dimension: position, velocity, acceleration components) of point p,
  /// every row: [row]. What walks a block column by column reads.
  const double* point_column(std::size_t p, std::size_t k) const { return points_.data() + (point_offset_[p] + k) * size(); }
  /// Value k (of 6: angular velocity, angular acceleration) of frame f, every row.
  const double* frame_column(std::size_t f, std::size_t k) const { return points_.data() + (frame_offset_ + 6 * f + k) * size(); }
  /// Coordinate i (its rate, second rate), every row.
  const double* q_column(std::size_t i) const { return q_.data() + i * size(); }
  const double* qd_column(std::size_t i) const { return qd_.data() + i * size(); }
  const double* qdd_column(std::size_t i) const { return qdd_.data() + i * size(); }
  FrameMotion frame(std::size_t row, std::size_t f) const;
  double loop_residual(std::size_t row) const { return loop_residual_[row]; }
  double reciprocal_condition(std::size_t row) const { return reciprocal_condition_[row]; }

  /// Row `row` as a MotionState (a copy).
  MotionState operator[](std::size_t row) const;
  /// Stores a state (its input, status, failure and whatever its status makes valid).
  void set(std::size_t row, const MotionState& state);
  /// set(row, from[from_row]) for a table of the same shape, without the MotionState
  /// between (no vectors allocated a row: a streamed run copies its history every block).
  void set(std::size_t row, const MotionTable& from, std::size_t from_row);

  /// Column storage for solvers that fill blocks of rows: value i of row r at
  /// [i * size() + r]; points: the 3 * dimension values of each point in turn, then the
  /// 6 of each frame (angular velocity, angular acceleration): the point stage's outputs.
  double* q_values() { return q_.data(); }
  double* qd_values() { return qd_.data(); }
  double* qdd_values() { return qdd_.data(); }
  double* point_values() { return points_.data(); }
  double* loop_residuals() { return loop_residual_.data(); }
  double* reciprocal_conditions() { return reciprocal_condition_.data(); }
  /// Marks rows [first, first + count) ok with nothing to report.
  void set_ok(std::size_t first, std::size_t count);

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
  std::size_t n_ = 0, batch_rows_ = 0, frame_count_ = 0;
  std::vector<std::size_t> point_dimensions_;
  double rate_ = 0, second_rate_ = 0;
  std::vector<double> input_, q_, qd_, qdd_, loop_residual_, reciprocal_condition_;
  std::vector<Status> status_;
  std::vector<Failure> failure_;
  std::vector<double> points_;
  std::size_t derived_count_ = 0;
  std::vector<double> derived_;  ///< Column-major, as points_.
  std::vector<std::size_t> point_offset_;  ///< First column of each point in points_.
  std::size_t frame_offset_ = 0;            ///< First column of the frames in points_.
  std::vector<signed char> direction_;      ///< Along a circuit only.
  std::vector<std::uint64_t> assembly_;     ///< Along a circuit only.
  Column column_view(const std::vector<double>& values, std::size_t row) const {
    return Column(values.data() + row, Eigen::Index(n_), Eigen::InnerStride<>(Eigen::Index(size())));
  }
};

}  // namespace kinema
