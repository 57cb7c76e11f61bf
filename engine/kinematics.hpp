// Numeric kinematics of one mechanism: the derivation compiled to register
// tapes (built once), Newton-Raphson for the position, one LU of Phi_q for
// velocity and acceleration, and continuation along lists and sweeps that
// keeps the assembly branch and says so when it cannot.
#pragma once

#include <Eigen/Dense>

#include <string>
#include <vector>

#include "engine/compiled_expressions.hpp"
#include "engine/derivation.hpp"
#include "loops/mechanism.hpp"

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
  Eigen::VectorXd q, qd, qdd;
  std::vector<PointMotion> points;
  double loop_residual = 0;      ///< max |Phi| at the solution (m).
  double reciprocal_condition = 0;  ///< of the length-scaled Phi_q; ~0 at a toggle.
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
  double max_continuation_step() const;

 private:
  const Kinematics& k_;
  std::vector<double> registers_;  ///< Tape registers; the first ones are its inputs.
  std::vector<double> position_out_, acceleration_out_, point_out_;
  Eigen::VectorXd phi_, phi_theta_, step_, trial_, column_scale_, rhs_, slope_, trial_q_;
  Eigen::MatrixXd phi_q_;
  /// LU (partial pivoting, in place) of Phi_q with columns scaled by column_scale_;
  /// hand-written for small n so the hot path allocates nothing.
  Eigen::MatrixXd lu_;
  std::vector<Eigen::Index> pivots_;
  bool evaluated_ = false;  ///< The position stage's registers hold (evaluated_input_, q).
  double evaluated_input_ = 0;

  void evaluate_position(double input, const Eigen::VectorXd& q);
  bool evaluated_at(double input, const Eigen::VectorXd& q) const;
  /// LU of Phi_q with its columns scaled by column_scale_.
  void factorise();
  /// Reciprocal condition of the scaled Phi_q from the factorisation: the pivot
  /// ratio where that is clearly fine, else Eigen's 1-norm estimate.
  double reciprocal_condition() const;
  /// Solves Phi_q x = rhs_ with the factorisation (undoing the column scaling).
  void solve_rhs(Eigen::VectorXd& x) const;
};

/// Solves at each input value in order, warm-starting from the previous one.
/// Failures become states with status != ok; nothing is thrown for them.
/// With threads > 1 a long run is split into chunks whose starting positions are
/// found by continuation first, so the branch is the serial run's.
/// With batch, consecutive values of a sweep are solved kLanes at a time on the
/// batch (SIMD) tape, each block predicted from the last solution and checked to
/// stay on its branch (else that block is solved one value at a time).
std::vector<MotionState> analyse(const Kinematics& kinematics, const std::vector<double>& inputs,
                                 double rate, double second_rate, unsigned threads = 1,
                                 bool batch = true);

/// Solves blocks of input values at once on the batch tape.
class BatchWorkspace {
 public:
  static constexpr std::size_t kLanes = 16;
  explicit BatchWorkspace(const Kinematics& kinematics);

  /// Solves inputs[0, count) (count <= kLanes) from the predicted positions; fills
  /// states (resized) only when every value converged on its predicted branch and
  /// none is singular. Returns false otherwise (the caller solves them one by one).
  bool solve(const double* inputs, std::size_t count, const std::vector<Eigen::VectorXd>& predicted,
             double rate, double second_rate, std::vector<MotionState>& states);

 private:
  const Kinematics& k_;
  std::vector<double> registers_;
  std::vector<Eigen::MatrixXd> lu_;                ///< Per lane.
  std::vector<std::vector<Eigen::Index>> pivots_;  ///< Per lane.
  Eigen::VectorXd x_, column_scale_;
  std::vector<Eigen::VectorXd> q_, qd_;

  double& lane(std::size_t reg, std::size_t l) { return registers_[reg * kLanes + l]; }
  /// Column-scaled Phi_q of lane l from the registers, factorised into lu_[l].
  void factorise_lane(std::size_t l);
};

}  // namespace kinema
