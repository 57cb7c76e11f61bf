#include "engine/numeric/workspace.hpp"

#include <algorithm>
#include <cmath>

#include "engine/numeric/solver.hpp"

namespace kinema {

Workspace::Workspace(const Kinematics& k)
    : k_(k),
      layout_(k.layout()),
      n_(k.unknown_count()),
      registers_(k.evaluator().make_workspace()),
      position_out_(k.evaluator().stage_output_count(TapeLayout::kPositionStage)),
      acceleration_out_(k.evaluator().stage_output_count(TapeLayout::kAccelerationStage)),
      point_out_(k.evaluator().stage_output_count(TapeLayout::kPointStage)),
      lu_(n_ * n_),
      inverse_pivots_(n_),
      pivots_(n_),
      rhs_(n_),
      least_squares_matrix_(n_ * n_),
      least_squares_scratch_(n_ * n_),
      step_(n_),
      trial_(n_),
      predicted_(n_),
      corrected_(n_) {
  reload_parameters();
}

void Workspace::reload_parameters() {
  std::copy(k_.parameter_values().begin(), k_.parameter_values().end(), registers_.begin());
  k_.evaluator().prepare(registers_);
  evaluated_ = false;
}

void Workspace::evaluate_position(double input, const double* q) {
  // Only q changed (a Newton iterate): what depends on the input alone still holds.
  const int level = evaluated_ && evaluated_input_ == input ? TapeLayout::kCoordinateLevel : TapeLayout::kInputLevel;
  registers_[layout_.input()] = input;
  for (std::size_t i = 0; i < n_; ++i) registers_[layout_.q(i)] = q[i];
  k_.evaluator().evaluate_stage_from(TapeLayout::kPositionStage, level, registers_, position_out_.data());
  evaluated_ = true;
  jacobian_ready_ = false;
  evaluated_input_ = input;
}

void Workspace::position_system(double input, const Eigen::VectorXd& q, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q,
                                Eigen::VectorXd& phi_theta) {
  evaluate_position(input, q.data());
  const auto n = Eigen::Index(n_);
  phi.resize(n);
  phi_q.resize(n, n);
  phi_theta.resize(n);
  for (std::size_t i = 0; i < n_; ++i) {
    phi[Eigen::Index(i)] = this->phi(i);
    phi_theta[Eigen::Index(i)] = this->phi_theta(i);
    for (std::size_t j = 0; j < n_; ++j) phi_q(Eigen::Index(i), Eigen::Index(j)) = this->phi_q(i, j);
  }
}

bool Workspace::evaluated_at(double input, const Eigen::VectorXd& q) const {
  if (!evaluated_ || evaluated_input_ != input) return false;
  for (std::size_t i = 0; i < n_; ++i)
    if (registers_[layout_.q(i)] != q[i]) return false;
  return true;
}

double Workspace::residual_norm() const { return solver::max_magnitude(position_out_.data(), n_); }

solver::Factorisation Workspace::factorisation() { return {lu_.data(), pivots_.data(), inverse_pivots_.data()}; }

void Workspace::factorise() {
  solver::factorise(position_out_.data(), k_.column_scale().data(), factorisation(), n_);
  jacobian_ready_ = false;
}

double Workspace::reciprocal_condition() const {
  // The rule is solver::reciprocal_condition's (the generated header runs the
  // same code). It reads the scaled Phi_q only near a toggle, so the copy (which
  // allocates) is made only then: row-major, as factorise() wrote it before the LU.
  std::vector<double> scaled;
  return solver::reciprocal_condition(lu_.data(), n_, k_.length_scale(), [&] {
    scaled.resize(n_ * n_);
    solver::scaled_phi_q(position_out_.data(), k_.column_scale().data(), scaled.data(), n_);
    return scaled.data();
  });
}

void Workspace::solve_rhs(double* x) {
  for (std::size_t i = 0; i < n_; ++i) x[i] = rhs_[i];
  solver::solve(factorisation(), k_.column_scale().data(), x, n_);
}

bool Workspace::solve_position(double input, Eigen::VectorXd& q, std::size_t* worst_group,
                               double* residual) {
  if (!evaluated_at(input, q)) evaluate_position(input, q.data());
  // solver::newton over the tape's position stage: a trial is evaluated into the stage's
  // own outputs, so a trial taken is already q's evaluation.
  struct Stage {
    Workspace& w;
    double input;
    double residual() const { return w.residual_norm(); }
    void step(double* step) const {
      solver::newton_step(w.position_out_.data(), w.k_.column_scale().data(), w.k_.length_scale(), w.factorisation(),
                          w.least_squares_matrix_.data(), w.least_squares_scratch_.data(), w.rhs_.data(), step, w.n_);
      w.jacobian_ready_ = false;
    }
    double try_at(const double* trial) const {
      w.evaluate_position(input, trial);
      return w.residual_norm();
    }
    void accept() const {}
  } stage{*this, input};
  const bool converged = solver::newton(stage, q.data(), step_.data(), trial_.data(), n_, k_.length_scale());
  if (!evaluated_at(input, q)) evaluate_position(input, q.data());
  if (worst_group) {
    std::size_t row = 0;
    for (std::size_t i = 1; i < n_; ++i)
      if (std::fabs(phi(i)) > std::fabs(phi(row))) row = i;
    *worst_group = k_.equation_group(row);
  }
  if (residual) *residual = residual_norm();
  return converged;
}

bool Workspace::sensitivity(double input, const Eigen::VectorXd& q, Eigen::VectorXd& dq) {
  if (!evaluated_at(input, q)) evaluate_position(input, q.data());
  factorise();
  if (reciprocal_condition() < solver::kSingularThreshold) return false;
  for (std::size_t i = 0; i < n_; ++i) rhs_[i] = -phi_theta(i);
  dq.resize(static_cast<Eigen::Index>(n_));
  solve_rhs(dq.data());
  return dq.allFinite();
}

bool Workspace::solve_jacobian(double input, const Eigen::VectorXd& q, const double* rhs, double* x) {
  if (!evaluated_at(input, q)) evaluate_position(input, q.data());
  if (!jacobian_ready_) {
    factorise();
    jacobian_regular_ = reciprocal_condition() >= solver::kSingularThreshold;
    jacobian_ready_ = true;
  }
  if (!jacobian_regular_) return false;
  std::copy(rhs, rhs + n_, rhs_.begin());
  solve_rhs(x);
  return true;
}

int Workspace::jacobian_sign(double input, const Eigen::VectorXd& q) {
  if (!evaluated_at(input, q)) evaluate_position(input, q.data());
  factorise();
  return solver::lu_determinant_sign(lu_.data(), pivots_.data(), n_);
}

bool Workspace::predict_and_correct(double from, double to, const Eigen::VectorXd& predicted, Eigen::VectorXd& q,
                                    int from_sign) {
  corrected_ = predicted;
  if (!solve_position(to, corrected_)) return false;
  double correction = 0, step = solver::kLeastStep * std::fabs(to - from) / max_continuation_step();
  for (std::size_t i = 0; i < n_; ++i) {
    const double scale = k_.column_scale()[i];
    const double off = std::fabs(corrected_[i] - predicted[i]) / scale;
    if (!(off <= solver::kBranchTolerance)) return false;
    correction = std::max(correction, off);
    step = std::max(step, std::fabs(predicted[i] - q[i]) / scale);
  }
  const int to_sign = jacobian_sign(to, corrected_);
  // Landed on a singular position (the motion's own toggle or change point at `to`): a
  // branch ending there is a square root, its correction as large as the step, and the
  // sign says nothing; the step goes no further than it.
  if (reciprocal_condition() < solver::kSingularThreshold) {
    q = corrected_;
    return true;
  }
  if (!(correction <= solver::kStepCorrection * step)) return false;
  if (to_sign != from_sign) {
    if (!change_point_between(from, q, from_sign, to, corrected_, to_sign)) return false;
    ++change_points_passed_;
  }
  q = corrected_;
  return true;
}

bool Workspace::change_point_between(double from, const Eigen::VectorXd& from_q, int from_sign, double to,
                                     const Eigen::VectorXd& to_q, int to_sign) {
  if (from_sign == 0 || to_sign == 0) return false;
  double lo = from, hi = to;
  Eigen::VectorXd lo_q = from_q, hi_q = to_q, mid_q;
  const double width = solver::kCrossingWidth * max_continuation_step();
  const double closes_between = solver::kCrossingResidual * k_.length_scale();
  while (std::fabs(hi - lo) > width) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    mid_q = 0.5 * (lo_q + hi_q);
    double residual = 0;
    // A value in between that does not close is a gap. Closing at Newton's stall level
    // (kRoundingTolerance) is not enough: inside a gap of 1e-4 turn or less the loop misses
    // by less than that.
    if (!solve_position(mid, mid_q, nullptr, &residual) || !(residual <= closes_between)) return false;
    const int sign = jacobian_sign(mid, mid_q);
    if (sign == from_sign) {
      lo = mid;
      lo_q = mid_q;
    } else {
      hi = mid;
      hi_q = mid_q;
    }
  }
  const double largest_jump = solver::kCrossingJump * std::fabs(hi - lo) / max_continuation_step();
  for (std::size_t i = 0; i < n_; ++i)
    if (!(std::fabs(hi_q[Eigen::Index(i)] - lo_q[Eigen::Index(i)]) / k_.column_scale()[i] <= largest_jump))
      return false;  // two assemblies side by side: a toggle
  return true;
}

bool Workspace::continue_to(double from, double to, Eigen::VectorXd& q, double* stuck_at, bool* too_far) {
  const double max_step = max_continuation_step();
  const double min_step = max_step * 1e-7;
  auto refuse = [&](double at) {
    if (stuck_at) *stuck_at = at;
    if (too_far) *too_far = true;
    return false;
  };
  // NaN compares false: refused too.
  if (!(std::fabs(to - from) <= solver::kMaxContinuationSteps * max_step)) return refuse(from);
  double t = from;
  double h = std::copysign(std::min(max_step, std::fabs(to - from)), to - from);
  bool have_regular = false;
  while (t != to) {
    if (std::fabs(to - t) <= std::fabs(h) * (1 + 1e-12)) h = to - t;
    if (t + h == t) return refuse(t);  // the input is too large for a step to change it
    bool accepted = sensitivity(t, q, slope_);
    if (accepted) {
      const int sign = solver::lu_determinant_sign(lu_.data(), pivots_.data(), n_);
      regular_input_ = t;
      regular_q_ = q;
      regular_slope_ = slope_;
      regular_sign_ = sign;
      have_regular = true;
      predicted_ = q + slope_ * h;
      accepted = predict_and_correct(t, t + h, predicted_, q, sign);
    } else if (have_regular) {
      // A step landed on a singular position (a change point, where the branch goes on):
      // the step is taken from the last regular position, over it.
      predicted_ = regular_q_ + regular_slope_ * (t + h - regular_input_);
      restart_q_ = regular_q_;
      accepted = predict_and_correct(regular_input_, t + h, predicted_, restart_q_, regular_sign_);
      if (accepted) q = restart_q_;
    }
    if (accepted) {
      t = (h == to - t) ? to : t + h;
      h = std::copysign(std::min(max_step, 2 * std::fabs(h)), to - from);
    } else {
      h /= 2;
      if (std::fabs(h) < min_step) {
        if (stuck_at) *stuck_at = t;
        return false;
      }
    }
  }
  return true;
}

bool Workspace::advance(double input, double rate, double second_rate, MotionState& state) {
  if (state.status != Status::ok) return false;
  const double h = input - state.input;
  bool solved = false;
  trial_q_ = state.q;
  if (std::fabs(h) <= max_continuation_step() && state.input_rate != 0) {
    // Second order in the input: the previous rates give dq/dtheta and d2q/dtheta2.
    for (std::size_t i = 0; i < n_; ++i) {
      predicted_[i] = solver::predict_second_order(state.q[i], state.qd[i], state.qdd[i], state.input_rate,
                                                   state.input_second_rate, h);
    }
    solved = predict_and_correct(state.input, input, predicted_, trial_q_, jacobian_sign(state.input, state.q));
  }
  if (!solved) {
    trial_q_ = state.q;
    solved = continue_to(state.input, input, trial_q_, nullptr);
  }
  if (!solved) return false;
  motion_into(input, rate, second_rate, trial_q_, state);
  return true;
}

MotionState Workspace::motion(double input, double rate, double second_rate,
                              const Eigen::VectorXd& q) {
  MotionState state;
  motion_into(input, rate, second_rate, q, state);
  return state;
}

void Workspace::motion_into(double input, double rate, double second_rate, const Eigen::VectorXd& q,
                            MotionState& state) {
  const std::size_t n = n_;
  state.input = input;
  state.input_rate = rate;
  state.input_second_rate = second_rate;
  state.q = q;
  state.failure = Failure{};
  if (!evaluated_at(input, q)) evaluate_position(input, q.data());
  state.loop_residual = residual_norm();
  // One factorisation of Phi_q: the singularity test, then velocity and acceleration.
  factorise();
  state.reciprocal_condition = reciprocal_condition();
  if (state.reciprocal_condition < solver::kSingularThreshold) {
    state.status = Status::singular;
    state.failure.kind = Failure::Kind::singular_jacobian;
    return;
  }
  state.qd.resize(static_cast<Eigen::Index>(n));
  state.qdd.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) rhs_[i] = -phi_theta(i) * rate;
  solve_rhs(state.qd.data());

  // Later stages reuse the registers of the position stage just evaluated at (input, q).
  registers_[layout_.rate()] = rate;
  registers_[layout_.second_rate()] = second_rate;
  for (std::size_t i = 0; i < n; ++i) registers_[layout_.qd(i)] = state.qd[i];
  k_.evaluator().evaluate_stage_from(TapeLayout::kAccelerationStage, TapeLayout::kInputLevel, registers_, rhs_.data());
  solve_rhs(state.qdd.data());
  for (std::size_t i = 0; i < n; ++i) registers_[layout_.qdd(i)] = state.qdd[i];
  k_.evaluator().evaluate_stage_from(TapeLayout::kPointStage, TapeLayout::kInputLevel, registers_, point_out_.data());
  state.points.resize(k_.point_count());
  bool finite = state.qd.allFinite() && state.qdd.allFinite();
  const bool rates_finite = finite;
  int undefined_point = -1;  // the first point without a number while the rates have them
  for (std::size_t p = 0; p < k_.point_count(); ++p) {
    const std::size_t d = layout_.point_dimensions[p];
    const double* v = point_out_.data() + layout_.point_output(p);
    PointMotion& motion = state.points[p];
    motion.dimension = d;
    for (std::size_t c = 0; c < d; ++c) {
      motion.position[c] = v[c];
      motion.velocity[c] = v[d + c];
      motion.acceleration[c] = v[2 * d + c];
    }
    for (std::size_t c = 0; c < 3 * d; ++c) finite = finite && std::isfinite(v[c]);
    if (rates_finite && !finite && undefined_point < 0) undefined_point = int(p);
  }
  state.frames.resize(k_.frame_count());
  for (std::size_t f = 0; f < k_.frame_count(); ++f) {
    const double* v = point_out_.data() + layout_.frame_output(f);
    for (std::size_t c = 0; c < 3; ++c) {
      state.frames[f].angular_velocity[c] = v[c];
      state.frames[f].angular_acceleration[c] = v[3 + c];
    }
    for (std::size_t c = 0; c < 6; ++c) finite = finite && std::isfinite(v[c]);
  }
  if (!finite) {
    state.status = Status::singular;
    state.failure.kind = undefined_point >= 0 ? Failure::Kind::point_undefined : Failure::Kind::nonfinite_rates;
    state.failure.group = undefined_point >= 0 ? std::uint32_t(undefined_point) : 0;
    return;
  }
  state.status = Status::ok;
}

}  // namespace kinema
