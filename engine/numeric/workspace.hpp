// Solving one input value at a time: Newton-Raphson for the position, one LU
// of Phi_q for velocity and acceleration, continuation that keeps the
// assembly branch. The buffers of one caller (one thread); nothing is
// allocated per input value on the hot path.
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/solver.hpp"

namespace kinema {

struct Model;

class Workspace {
 public:
  explicit Workspace(const Kinematics& kinematics);
  /// The workspace of a loaded model (engine/model.hpp).
  explicit Workspace(const Model& model);

  /// The kinematics' parameter values again (after Kinematics::set_parameter_values):
  /// the work on them alone (the tape's level 0) rerun, nothing allocated.
  void reload_parameters();

  /// Newton-Raphson from q (updated in place). False when it does not converge;
  /// then worst_group names the equation group that stays open.
  bool solve_position(double input, Eigen::VectorXd& q, std::size_t* worst_group = nullptr,
                      double* residual = nullptr);

  /// Rates, second rates and points at a solved position.
  MotionState motion(double input, double rate, double second_rate, const Eigen::VectorXd& q);
  /// The same into an existing state, reusing its storage (no allocation on the hot path).
  void motion_into(double input, double rate, double second_rate, const Eigen::VectorXd& q,
                   MotionState& state);

  /// Phi, Phi_q and Phi_theta at (input, q), any q (for solvers of other systems built on
  /// the loop equations, such as the toggle positions).
  void position_system(double input, const Eigen::VectorXd& q, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q,
                       Eigen::VectorXd& phi_theta);

  /// dq/dtheta at a solved position (false when Phi_q is singular).
  bool sensitivity(double input, const Eigen::VectorXd& q, Eigen::VectorXd& dq);

  /// Solves Phi_q x = rhs (n values each) at a position (input, q) with the solver's LU
  /// of Phi_q, factorised once for any number of right-hand sides there (the
  /// sensitivities in a parameter solve three); false where Phi_q is singular.
  bool solve_jacobian(double input, const Eigen::VectorXd& q, const double* rhs, double* x);

  /// Continues the solution from (from, q) to `to` in small steps so that the
  /// branch is kept; false when that is impossible (limit or branch point), or, with
  /// *too_far set, when `to` is more than solver::kMaxContinuationSteps steps away or
  /// the input is too large for a step to change it.
  bool continue_to(double from, double to, Eigen::VectorXd& q, double* stuck_at, bool* too_far = nullptr);

  /// Newton from `predicted` at `to`; accepts (into q) only a solution close to the
  /// prediction, i.e. on the same branch. q holds the position the step starts from, whose
  /// input is `from` and whose determinant sign is `from_sign` (jacobian_sign there): a step is refused where it did
  /// not stay on its branch (its correction large beside the step, solver::kStepCorrection;
  /// det Phi_q of another sign without a change point between), so no toggle is stepped over.
  bool predict_and_correct(double from, double to, const Eigen::VectorXd& predicted, Eigen::VectorXd& q,
                           int from_sign);
  /// The sign of det Phi_q at (input, q) (solver::lu_determinant_sign): the same along a
  /// branch between singular positions.
  int jacobian_sign(double input, const Eigen::VectorXd& q);
  /// det Phi_q's sign differs at two positions of a step (from_sign at from_q, to_sign at
  /// to_q): true where the branch passes a change point between them (the sign changes at
  /// one input and the position does not jump there), false where a toggle or a gap lies
  /// between (a value in between that does not close, or two assemblies side by side).
  bool change_point_between(double from, const Eigen::VectorXd& from_q, int from_sign, double to,
                            const Eigen::VectorXd& to_q, int to_sign);
  /// Steps accepted through a change point so far (predict_and_correct).
  std::size_t change_points_passed() const { return change_points_passed_; }
  /// The same at the position motion_into() last solved rates at.
  int factorised_sign() const { return solver::lu_determinant_sign(lu_.data(), pivots_.data(), n_); }
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
  const TapeLayout& layout_;
  std::size_t n_;
  std::vector<double> registers_;  ///< Tape registers; the first ones are its inputs.
  std::vector<double> position_out_, acceleration_out_, point_out_;
  /// LU (partial pivoting, in place, row-major) of Phi_q with columns scaled by
  /// the column scale; plain loops for small n, so the hot path allocates nothing.
  std::vector<double> lu_, inverse_pivots_;
  std::vector<std::size_t> pivots_;
  std::vector<double> rhs_;
  std::vector<double> least_squares_matrix_, least_squares_scratch_;  ///< Near-singular Newton steps.
  Eigen::VectorXd step_, trial_, predicted_, slope_, trial_q_, corrected_;
  /// continue_to's last regular position (input, q, dq/dinput, det sign), and a copy to
  /// step from it again.
  Eigen::VectorXd regular_q_, regular_slope_, restart_q_;
  double regular_input_ = 0;
  std::size_t change_points_passed_ = 0;
  int regular_sign_ = 0;
  bool evaluated_ = false;  ///< The position stage's registers hold (evaluated_input_, q).
  /// solve_jacobian's LU is that of the evaluated position (reset by evaluate_position and
  /// factorise), and whether Phi_q is regular there.
  bool jacobian_ready_ = false, jacobian_regular_ = false;
  double evaluated_input_ = 0;

  double phi(std::size_t i) const { return position_out_[layout_.phi(i)]; }
  double phi_q(std::size_t i, std::size_t j) const { return position_out_[layout_.phi_q(i, j)]; }
  double phi_theta(std::size_t i) const { return position_out_[layout_.phi_theta(i)]; }
  void evaluate_position(double input, const double* q);
  bool evaluated_at(double input, const Eigen::VectorXd& q) const;
  /// max |Phi| at the evaluated position (NaN if any is).
  double residual_norm() const;
  /// LU of Phi_q with its columns scaled by the column scale.
  void factorise();
  solver::Factorisation factorisation();
  /// Reciprocal condition of the scaled Phi_q from the factorisation: the pivot
  /// ratio where that is clearly fine, else from the singular values
  /// (solver::reciprocal_condition).
  double reciprocal_condition() const;
  /// Solves Phi_q x = rhs_ with the factorisation (undoing the column scaling).
  void solve_rhs(double* x);
};

}  // namespace kinema
