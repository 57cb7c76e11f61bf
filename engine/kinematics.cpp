#include "engine/kinematics.hpp"

#include <cmath>
#include <sstream>
#include <algorithm>
#include <memory>
#include <thread>

namespace kinema {
namespace {

using GiNaC::ex;

// Reciprocal condition of the length-scaled Phi_q below which a position counts
// as singular: a Newton solution at a toggle is only sqrt(eps)-accurate, so
// exact toggles show up around 1e-6; rates there would be 1e5 times their
// usual size, which is no result to print.
constexpr double kSingularThreshold = 1e-5;

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

}  // namespace

const char* status_name(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::singular: return "singular";
    case Status::unassembled: return "unassembled";
  }
  return "?";
}

Kinematics::Kinematics(const Mechanism& mechanism, const Derivation& d)
    : mechanism_(mechanism),
      unknown_count_(d.closure.unknowns.size()),
      point_count_(d.closure.point_x.size()),
      parameter_count_(d.closure.parameters.size()),
      parameter_values_(d.closure.parameter_values) {
  double largest = 0;
  for (const Parameter& parameter : mechanism.parameters) {
    if (parameter.quantity && parameter.quantity->dimension == Dimension::length)
      largest = std::max(largest, std::fabs(parameter.quantity->si_value));
  }
  length_scale_ = largest > 0 ? largest : 1.0;

  std::vector<ex> inputs(d.closure.parameters.begin(), d.closure.parameters.end());
  inputs.push_back(d.closure.input);
  inputs.push_back(d.input_rate);
  inputs.push_back(d.input_second_rate);
  for (const auto& s : d.closure.unknowns) inputs.push_back(s);
  for (const auto& s : d.rates) inputs.push_back(s);
  for (const auto& s : d.second_rates) inputs.push_back(s);

  const std::size_t n = unknown_count_;
  std::vector<ex> position;
  for (std::size_t i = 0; i < n; ++i) position.push_back(d.closure.equations[i]);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) position.push_back(d.jacobian(i, j));
  for (std::size_t i = 0; i < n; ++i) position.push_back(d.input_jacobian(i, 0));
  std::vector<ex> points;
  for (std::size_t p = 0; p < point_count_; ++p) {
    points.push_back(d.closure.point_x[p]);
    points.push_back(d.closure.point_y[p]);
    points.push_back(d.point_velocity_x[p]);
    points.push_back(d.point_velocity_y[p]);
    points.push_back(d.point_acceleration_x[p]);
    points.push_back(d.point_acceleration_y[p]);
  }
  evaluator_ = CompiledExpressions(inputs, {position, d.acceleration_rhs, points});
}

Eigen::VectorXd Kinematics::guess() const {
  Eigen::VectorXd q(unknown_count_);
  for (std::size_t i = 0; i < unknown_count_; ++i) q[i] = mechanism_.unknowns[i].guess;
  return q;
}

std::string Kinematics::describe_input(double input) const {
  if (mechanism_.input.dimension == Dimension::angle) {
    return mechanism_.input.name + " = " + format_number(input * 180.0 / M_PI) + " deg";
  }
  return mechanism_.input.name + " = " + format_number(input / mechanism_.output.length_factor) +
         " " + mechanism_.output.length;
}

Workspace::Workspace(const Kinematics& k)
    : k_(k),
      registers_(k.evaluator_.make_workspace()),
      position_out_(k.evaluator_.stage_output_count(Kinematics::kPositionStage)),
      acceleration_out_(k.evaluator_.stage_output_count(Kinematics::kAccelerationStage)),
      point_out_(k.evaluator_.stage_output_count(Kinematics::kPointStage)),
      phi_(k.unknown_count_),
      phi_theta_(k.unknown_count_),
      step_(k.unknown_count_),
      trial_(k.unknown_count_),
      column_scale_(k.unknown_count_),
      rhs_(k.unknown_count_),
      phi_q_(k.unknown_count_, k.unknown_count_),
      lu_(k.unknown_count_, k.unknown_count_),
      pivots_(k.unknown_count_) {
  std::copy(k.parameter_values_.begin(), k.parameter_values_.end(), registers_.begin());
  // Columns of slider lengths are unitless, columns of angles are lengths:
  // scale them alike so the condition number does not depend on units.
  for (std::size_t j = 0; j < k.unknown_count_; ++j)
    column_scale_[j] = k.mechanism_.unknowns[j].dimension == Dimension::length ? k.length_scale_ : 1.0;
}


void Workspace::evaluate_position(double input, const Eigen::VectorXd& q) {
  const std::size_t base = k_.parameter_count_, n = k_.unknown_count_;
  registers_[base] = input;
  for (std::size_t i = 0; i < n; ++i) registers_[base + 3 + i] = q[i];
  k_.evaluator_.evaluate_stage(Kinematics::kPositionStage, registers_, position_out_.data());
  phi_ = Eigen::Map<const Eigen::VectorXd>(position_out_.data(), n);
  phi_q_ = Eigen::Map<const Eigen::MatrixXd>(position_out_.data() + n, n, n);
  phi_theta_ = Eigen::Map<const Eigen::VectorXd>(position_out_.data() + n + n * n, n);
  evaluated_ = true;
  evaluated_input_ = input;
}

bool Workspace::evaluated_at(double input, const Eigen::VectorXd& q) const {
  if (!evaluated_ || evaluated_input_ != input) return false;
  const std::size_t base = k_.parameter_count_;
  for (std::size_t i = 0; i < k_.unknown_count_; ++i)
    if (registers_[base + 3 + i] != q[i]) return false;
  return true;
}

namespace {

// LU with partial pivoting, in place, for the small Phi_q of a mechanism
// (hand-written so that nothing is allocated per input value).
void lu_factor(Eigen::MatrixXd& lu, std::vector<Eigen::Index>& pivots) {
  const Eigen::Index n = lu.rows();
  for (Eigen::Index c = 0; c < n; ++c) {
    Eigen::Index best = c;
    for (Eigen::Index r = c + 1; r < n; ++r)
      if (std::fabs(lu(r, c)) > std::fabs(lu(best, c))) best = r;
    pivots[c] = best;
    if (best != c) lu.row(c).swap(lu.row(best));
    if (lu(c, c) == 0.0) continue;  // singular: the pivot ratio reports it
    for (Eigen::Index r = c + 1; r < n; ++r) {
      lu(r, c) /= lu(c, c);
      for (Eigen::Index j = c + 1; j < n; ++j) lu(r, j) -= lu(r, c) * lu(c, j);
    }
  }
}

// Solves with lu_factor's result; x holds the right-hand side on entry.
void lu_solve(const Eigen::MatrixXd& lu, const std::vector<Eigen::Index>& pivots, Eigen::VectorXd& x) {
  const Eigen::Index n = lu.rows();
  // Row swaps first: the rows of L are stored in their final order.
  for (Eigen::Index c = 0; c < n; ++c)
    if (pivots[c] != c) std::swap(x[c], x[pivots[c]]);
  for (Eigen::Index c = 0; c < n; ++c)
    for (Eigen::Index r = c + 1; r < n; ++r) x[r] -= lu(r, c) * x[c];
  for (Eigen::Index c = n - 1; c >= 0; --c) {
    x[c] /= lu(c, c);
    for (Eigen::Index r = 0; r < c; ++r) x[r] -= lu(r, c) * x[c];
  }
}

double pivot_ratio(const Eigen::MatrixXd& lu) {
  const auto pivots = lu.diagonal().cwiseAbs();
  const double ratio = pivots.minCoeff() / pivots.maxCoeff();
  return std::isfinite(ratio) ? ratio : 0.0;
}

}  // namespace

void Workspace::factorise() {
  lu_.noalias() = phi_q_ * column_scale_.asDiagonal();
  lu_factor(lu_, pivots_);
}

double Workspace::reciprocal_condition() const {
  const double ratio = pivot_ratio(lu_);
  if (ratio == 0.0) return 0.0;
  // Well away from singular the pivots say so; the singular values (which
  // allocate) are only needed near a toggle, where they decide.
  if (ratio >= 1e-2) return ratio;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(phi_q_ * column_scale_.asDiagonal());
  const auto& s = svd.singularValues();
  return s[0] > 0 && std::isfinite(s[0]) ? s[s.size() - 1] / s[0] : 0.0;
}

void Workspace::solve_rhs(Eigen::VectorXd& x) const {
  x = rhs_;
  lu_solve(lu_, pivots_, x);
  x.array() *= column_scale_.array();
}


bool Workspace::solve_position(double input, Eigen::VectorXd& q, std::size_t* worst_loop,
                               double* residual) {
  // Down to rounding: near a toggle the position error is the square root of the residual.
  const double tolerance = 1e-14 * k_.length_scale_;
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  double norm = phi_.lpNorm<Eigen::Infinity>();
  bool converged = false;
  for (int iteration = 0; iteration < 60 && std::isfinite(norm); ++iteration) {
    if (norm <= tolerance) {
      converged = true;
      break;
    }
    factorise();
    const auto pivots = lu_.diagonal().cwiseAbs();
    if (pivots.minCoeff() > 1e-14 * pivots.maxCoeff()) {
      rhs_ = -phi_;
      solve_rhs(step_);
    } else {
      // Least-squares step: stays defined where Phi_q is (nearly) singular.
      step_ = phi_q_.completeOrthogonalDecomposition().solve(-phi_);
    }
    if (!step_.allFinite()) break;
    double lambda = 1.0;
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving, lambda *= 0.5) {
      trial_ = q + lambda * step_;
      evaluate_position(input, trial_);
      const double trial_norm = phi_.lpNorm<Eigen::Infinity>();
      if (std::isfinite(trial_norm) && trial_norm < norm) {
        improved = true;
        norm = trial_norm;
        q = trial_;
        break;
      }
    }
    if (!improved) break;
  }
  // Converged to rounding level even if just above the tolerance.
  if (!converged && norm <= 1e-9 * k_.length_scale_) converged = true;
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  if (worst_loop) {
    Eigen::Index row = 0;
    phi_.cwiseAbs().maxCoeff(&row);
    *worst_loop = static_cast<std::size_t>(row) / 2;
  }
  if (residual) *residual = phi_.lpNorm<Eigen::Infinity>();
  return converged && q.allFinite();
}

bool Workspace::sensitivity(double input, const Eigen::VectorXd& q, Eigen::VectorXd& dq) {
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  factorise();
  if (reciprocal_condition() < kSingularThreshold) return false;
  rhs_ = -phi_theta_;
  solve_rhs(dq);
  return dq.allFinite();
}

double Workspace::max_continuation_step() const {
  return k_.mechanism_.input.dimension == Dimension::angle ? 2.0 * M_PI / 180.0 : 0.01 * k_.length_scale_;
}

bool Workspace::predict_and_correct(double to, const Eigen::VectorXd& predicted, Eigen::VectorXd& q) {
  // A corrected solution this far (scaled) from the prediction is another branch.
  constexpr double branch_tolerance = 0.05;
  trial_q_ = predicted;
  if (!solve_position(to, trial_q_)) return false;
  for (std::size_t i = 0; i < k_.unknown_count_; ++i) {
    if (std::fabs(trial_q_[i] - predicted[i]) / column_scale_[i] > branch_tolerance) return false;
  }
  q = trial_q_;
  return true;
}

bool Workspace::continue_to(double from, double to, Eigen::VectorXd& q, double* stuck_at) {
  const double max_step = max_continuation_step();
  const double min_step = max_step * 1e-7;
  double t = from;
  double h = std::copysign(std::min(max_step, std::fabs(to - from)), to - from);
  while (t != to) {
    if (std::fabs(to - t) <= std::fabs(h) * (1 + 1e-12)) h = to - t;
    const bool accepted = sensitivity(t, q, slope_) && predict_and_correct(t + h, q + slope_ * h, q);
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

MotionState Workspace::motion(double input, double rate, double second_rate,
                              const Eigen::VectorXd& q) {
  MotionState state;
  motion_into(input, rate, second_rate, q, state);
  return state;
}

void Workspace::motion_into(double input, double rate, double second_rate, const Eigen::VectorXd& q,
                            MotionState& state) {
  const std::size_t n = k_.unknown_count_;
  const std::size_t base = k_.parameter_count_;
  state.input = input;
  state.input_rate = rate;
  state.input_second_rate = second_rate;
  state.q = q;
  state.message.clear();
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  state.loop_residual = phi_.lpNorm<Eigen::Infinity>();
  // One factorisation of Phi_q: the singularity test, then velocity and acceleration.
  factorise();
  state.reciprocal_condition = reciprocal_condition();
  if (state.reciprocal_condition < kSingularThreshold) {
    state.status = Status::singular;
    state.message = "singular position at " + k_.describe_input(input) +
                    ": the Jacobian Phi_q is rank-deficient (toggle or dead-centre position), so "
                    "velocities and accelerations are not defined there; choose a nearby value";
    return;
  }
  state.qd.resize(n);
  state.qdd.resize(n);
  rhs_ = -phi_theta_ * rate;
  solve_rhs(state.qd);

  // Later stages reuse the registers of the position stage just evaluated at (input, q).
  registers_[base + 1] = rate;
  registers_[base + 2] = second_rate;
  for (std::size_t i = 0; i < n; ++i) registers_[base + 3 + n + i] = state.qd[i];
  k_.evaluator_.evaluate_stage(Kinematics::kAccelerationStage, registers_, acceleration_out_.data());
  rhs_ = Eigen::Map<const Eigen::VectorXd>(acceleration_out_.data(), n);
  solve_rhs(state.qdd);
  for (std::size_t i = 0; i < n; ++i) registers_[base + 3 + 2 * n + i] = state.qdd[i];
  k_.evaluator_.evaluate_stage(Kinematics::kPointStage, registers_, point_out_.data());
  state.points.resize(k_.point_count_);
  bool finite = state.qd.allFinite() && state.qdd.allFinite();
  for (std::size_t p = 0; p < k_.point_count_; ++p) {
    const double* v = point_out_.data() + 6 * p;
    state.points[p] = {v[0], v[1], v[2], v[3], v[4], v[5]};
    for (int i = 0; i < 6; ++i) finite = finite && std::isfinite(v[i]);
  }
  if (!finite) {
    state.status = Status::singular;
    state.message = "non-finite rates at " + k_.describe_input(input) +
                    " (a formula divides by zero there); choose a nearby value";
    return;
  }
  state.status = Status::ok;
}

BatchWorkspace::BatchWorkspace(const Kinematics& k)
    : k_(k),
      registers_(k.evaluator_.make_batch_workspace(kLanes)),
      lu_(kLanes, Eigen::MatrixXd(k.unknown_count_, k.unknown_count_)),
      pivots_(kLanes, std::vector<Eigen::Index>(k.unknown_count_)),
      x_(k.unknown_count_),
      column_scale_(k.unknown_count_),
      q_(kLanes, Eigen::VectorXd(k.unknown_count_)),
      qd_(kLanes, Eigen::VectorXd(k.unknown_count_)) {
  for (std::size_t p = 0; p < k.parameter_count_; ++p)
    for (std::size_t l = 0; l < kLanes; ++l) lane(p, l) = k.parameter_values_[p];
  for (std::size_t j = 0; j < k.unknown_count_; ++j)
    column_scale_[j] = k.mechanism_.unknowns[j].dimension == Dimension::length ? k.length_scale_ : 1.0;
}

void BatchWorkspace::factorise_lane(std::size_t l) {
  const std::size_t n = k_.unknown_count_;
  const auto& e = k_.evaluator_;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
      lu_[l](i, j) = lane(e.output_register(Kinematics::kPositionStage, n + j * n + i), l) * column_scale_[j];
  lu_factor(lu_[l], pivots_[l]);
}

bool BatchWorkspace::solve(const double* inputs, std::size_t count,
                           const std::vector<Eigen::VectorXd>& predicted, double rate, double second_rate,
                           std::vector<MotionState>& states) {
  const std::size_t n = k_.unknown_count_, base = k_.parameter_count_;
  const auto& e = k_.evaluator_;
  const double tolerance = 1e-14 * k_.length_scale_;
  // Unused lanes repeat the last value so the whole block stays finite.
  for (std::size_t l = 0; l < kLanes; ++l) {
    const std::size_t from = std::min(l, count - 1);
    lane(base, l) = inputs[from];
    lane(base + 1, l) = rate;
    lane(base + 2, l) = second_rate;
    q_[l] = predicted[from];
  }
  // Chord Newton: each lane's Phi_q is factorised once, at the prediction; the
  // prediction is close, so the iteration converges in a few cheap steps. A lane
  // that does not converge sends the block to the scalar path.
  std::vector<bool> converged(kLanes, false);
  std::size_t remaining = kLanes;
  for (int iteration = 0; iteration < 12 && remaining > 0; ++iteration) {
    for (std::size_t l = 0; l < kLanes; ++l)
      for (std::size_t i = 0; i < n; ++i) lane(base + 3 + i, l) = q_[l][i];
    e.evaluate_stage_batch(Kinematics::kPositionStage, registers_, kLanes);
    for (std::size_t l = 0; l < kLanes; ++l) {
      double residual = 0;
      for (std::size_t i = 0; i < n; ++i)
        residual = std::max(residual, std::fabs(lane(e.output_register(Kinematics::kPositionStage, i), l)));
      if (!std::isfinite(residual)) return false;
      converged[l] = residual <= tolerance;
      if (converged[l]) continue;
      if (iteration == 0) {
        factorise_lane(l);
        if (pivot_ratio(lu_[l]) < 1e-12) return false;
      }
      for (std::size_t i = 0; i < n; ++i) x_[i] = -lane(e.output_register(Kinematics::kPositionStage, i), l);
      lu_solve(lu_[l], pivots_[l], x_);
      q_[l].array() += x_.array() * column_scale_.array();
    }
    remaining = static_cast<std::size_t>(std::count(converged.begin(), converged.end(), false));
  }
  if (remaining > 0) return false;
  // Same branch as predicted (as Workspace::predict_and_correct checks).
  for (std::size_t l = 0; l < count; ++l)
    for (std::size_t i = 0; i < n; ++i)
      if (std::fabs(q_[l][i] - predicted[l][i]) / column_scale_[i] > 0.05) return false;

  // Rates: one factorisation per lane at the solution, for both qd and qdd; the
  // registers hold every lane at its q.
  for (std::size_t l = 0; l < kLanes; ++l) {
    factorise_lane(l);
    // Clearly regular pivots only; anything near a toggle goes to the scalar path,
    // which decides singularity with the singular values.
    if (pivot_ratio(lu_[l]) < 1e-2) return false;
    for (std::size_t i = 0; i < n; ++i)
      x_[i] = -lane(e.output_register(Kinematics::kPositionStage, n + n * n + i), l) * rate;
    lu_solve(lu_[l], pivots_[l], x_);
    qd_[l] = x_.cwiseProduct(column_scale_);
    for (std::size_t i = 0; i < n; ++i) lane(base + 3 + n + i, l) = qd_[l][i];
  }
  e.evaluate_stage_batch(Kinematics::kAccelerationStage, registers_, kLanes);
  states.resize(count);
  for (std::size_t l = 0; l < kLanes; ++l) {
    for (std::size_t i = 0; i < n; ++i) x_[i] = lane(e.output_register(Kinematics::kAccelerationStage, i), l);
    lu_solve(lu_[l], pivots_[l], x_);
    x_.array() *= column_scale_.array();
    for (std::size_t i = 0; i < n; ++i) lane(base + 3 + 2 * n + i, l) = x_[i];
    if (l < count) {
      MotionState& state = states[l];
      state.input = inputs[l];
      state.input_rate = rate;
      state.input_second_rate = second_rate;
      state.status = Status::ok;
      state.message.clear();
      state.q = q_[l];
      state.qd = qd_[l];
      state.qdd = x_;
      state.reciprocal_condition = pivot_ratio(lu_[l]);
      double residual = 0;
      for (std::size_t i = 0; i < n; ++i)
        residual = std::max(residual, std::fabs(lane(e.output_register(Kinematics::kPositionStage, i), l)));
      state.loop_residual = residual;
    }
  }
  e.evaluate_stage_batch(Kinematics::kPointStage, registers_, kLanes);
  for (std::size_t l = 0; l < count; ++l) {
    MotionState& state = states[l];
    state.points.resize(k_.point_count_);
    for (std::size_t p = 0; p < k_.point_count_; ++p) {
      double v[6];
      for (int c = 0; c < 6; ++c) v[c] = lane(e.output_register(Kinematics::kPointStage, 6 * p + c), l);
      state.points[p] = {v[0], v[1], v[2], v[3], v[4], v[5]};
      for (double value : v)
        if (!std::isfinite(value)) return false;
    }
    if (!state.qd.allFinite() || !state.qdd.allFinite()) return false;
  }
  return true;
}

namespace {

// Solves inputs[begin, end) in order from q (a solution at inputs[begin] or a guess),
// writing states[begin, end).
void analyse_range(const Kinematics& kinematics, const std::vector<double>& all_inputs, std::size_t begin,
                   std::size_t end, double rate, double second_rate, Eigen::VectorXd q,
                   std::vector<MotionState>& all_states, bool batch) {
  Workspace workspace(kinematics);
  std::unique_ptr<BatchWorkspace> batch_workspace;
  if (batch) batch_workspace = std::make_unique<BatchWorkspace>(kinematics);
  std::vector<MotionState> states;
  states.reserve(end - begin);
  const std::vector<double> inputs(all_inputs.begin() + begin, all_inputs.begin() + end);
  std::vector<Eigen::VectorXd> predicted(BatchWorkspace::kLanes);
  std::vector<MotionState> block;
  std::size_t next_batch_try = 0;  // after a refused block, go on one by one for a while
  bool have_previous = false;  // q is a solution at previous_input on the user's branch
  double previous_input = 0;
  bool after_gap = false;
  bool any_solved = false;
  for (std::size_t index = 0; index < inputs.size(); ++index) {
    const double input = inputs[index];
    if (batch && rate != 0 && index >= next_batch_try && !states.empty() && states.back().status == Status::ok &&
        states.back().message.empty()) {
      // A block of the following values, predicted to second order from the last state.
      const MotionState& last = states.back();
      const Eigen::VectorXd slope = last.qd / rate;
      const Eigen::VectorXd curvature = (last.qdd - slope * second_rate) / (rate * rate);
      const double reach = 4 * workspace.max_continuation_step();
      std::size_t count = 0;
      for (; count < BatchWorkspace::kLanes && index + count < inputs.size(); ++count) {
        const double h = inputs[index + count] - last.input;
        if (std::fabs(h) > reach) break;
        predicted[count] = last.q + slope * h + 0.5 * curvature * h * h;
      }
      if (count == BatchWorkspace::kLanes &&
          batch_workspace->solve(inputs.data() + index, count, predicted, rate, second_rate, block)) {
        for (auto& state : block) states.push_back(std::move(state));
        q = states.back().q;
        previous_input = states.back().input;
        index += count - 1;
        continue;
      }
      next_batch_try = index + BatchWorkspace::kLanes;
    }
    bool solved = false;
    std::string why;
    Eigen::VectorXd trial = q;
    if (have_previous) {
      // Fast path for sweeps: predict from the rates just computed (dq/dtheta =
      // qd/thetad) and correct; the general continuation only when that fails.
      const double h = input - previous_input;
      if (rate != 0 && std::fabs(h) <= workspace.max_continuation_step()) {
        solved = workspace.predict_and_correct(input, q + states.back().qd * (h / rate), trial);
      }
      double stuck_at = previous_input;
      if (!solved) solved = workspace.continue_to(previous_input, input, trial, &stuck_at);
      if (!solved) {
        why = kinematics.describe_input(input) + " cannot be reached from " +
              kinematics.describe_input(previous_input) +
              " on the same assembly branch: the motion stops near " +
              kinematics.describe_input(stuck_at) + " (a limit or toggle position)";
      }
    } else {
      std::size_t worst_loop = 0;
      double residual = 0;
      solved = workspace.solve_position(input, trial, &worst_loop, &residual);
      if (!solved) {
        const Loop& loop = kinematics.mechanism().loops.at(worst_loop);
        why = "loop \"" + loop.name + "\" (" + loop.where.str() + ") cannot be closed at " +
              kinematics.describe_input(input) + ": the links do not reach (loop gap " +
              format_number(residual / kinematics.mechanism().output.length_factor) + " " +
              kinematics.mechanism().output.length + " after Newton-Raphson from the " +
              (after_gap ? "last assembled position" : "guesses") +
              "); choose another input value, or check the lengths and the guesses";
      }
    }
    if (!solved) {
      MotionState state;
      state.input = input;
      state.input_rate = rate;
      state.input_second_rate = second_rate;
      state.status = Status::unassembled;
      state.message = why;
      states.push_back(state);
      after_gap = any_solved;
      have_previous = false;  // resume from the last good q; the branch may differ after a gap
      continue;
    }
    q = trial;
    any_solved = true;
    MotionState state = workspace.motion(input, rate, second_rate, q);
    if (after_gap && state.status == Status::ok) {
      state.message = "resumed after positions that could not be assembled; the branch across "
                      "the gap is not guaranteed";
    }
    // Past a singular position the branch may change: treat it like a gap.
    after_gap = state.status != Status::ok;
    have_previous = state.status == Status::ok;
    previous_input = input;
    states.push_back(state);
  }
  std::move(states.begin(), states.end(), all_states.begin() + begin);
}

}  // namespace

std::vector<MotionState> analyse(const Kinematics& kinematics, const std::vector<double>& inputs,
                                 double rate, double second_rate, unsigned threads, bool batch) {
  std::vector<MotionState> states(inputs.size());
  const std::size_t n = inputs.size();
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
    analyse_range(kinematics, inputs, 0, n, rate, second_rate, start[0], states, batch);
    return states;
  }
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < threads; ++t) {
    workers.emplace_back(analyse_range, std::cref(kinematics), std::cref(inputs), begin[t], begin[t + 1], rate,
                         second_rate, start[t], std::ref(states), batch);
  }
  for (auto& worker : workers) worker.join();
  return states;
}

}  // namespace kinema
