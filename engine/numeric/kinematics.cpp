#include <kinema/engine/numeric/kinematics.hpp>

#include <cfloat>
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
  // Levels: parameters fixed; input and its rates per value; then q (per Newton
  // iterate), qd, qdd. Work that depends only on the input (sin/cos of a crank angle)
  // is not redone per iterate, and work on parameters alone is done once.
  std::vector<int> levels(inputs.size(), 0);
  const std::size_t first_input = d.closure.parameters.size();
  for (std::size_t i = first_input; i < inputs.size(); ++i) {
    const std::size_t k = i - first_input;
    levels[i] = k < 3 ? kInputLevel : k < 3 + n ? kCoordinateLevel : k < 3 + 2 * n ? kCoordinateLevel + 1 : kCoordinateLevel + 2;
  }
  evaluator_ = CompiledExpressions(inputs, levels, {position, d.acceleration_rhs, points});
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
      n_(k.unknown_count_),
      registers_(k.evaluator_.make_workspace()),
      position_out_(k.evaluator_.stage_output_count(Kinematics::kPositionStage)),
      acceleration_out_(k.evaluator_.stage_output_count(Kinematics::kAccelerationStage)),
      point_out_(k.evaluator_.stage_output_count(Kinematics::kPointStage)),
      lu_(n_ * n_),
      inverse_pivots_(n_),
      pivots_(n_),
      column_scale_(n_),
      rhs_(n_),
      step_(n_),
      trial_(n_),
      predicted_(n_) {
  std::copy(k.parameter_values_.begin(), k.parameter_values_.end(), registers_.begin());
  k.evaluator_.prepare(registers_);
  // Columns of slider lengths are unitless, columns of angles are lengths:
  // scale them alike so the condition number does not depend on units.
  for (std::size_t j = 0; j < n_; ++j)
    column_scale_[j] = k.mechanism_.unknowns[j].dimension == Dimension::length ? k.length_scale_ : 1.0;
}

void Workspace::evaluate_position(double input, const Eigen::VectorXd& q) {
  const std::size_t base = k_.parameter_count_;
  // Only q changed (a Newton iterate): what depends on the input alone still holds.
  const int level = evaluated_ && evaluated_input_ == input ? Kinematics::kCoordinateLevel : Kinematics::kInputLevel;
  registers_[base] = input;
  for (std::size_t i = 0; i < n_; ++i) registers_[base + 3 + i] = q[i];
  k_.evaluator_.evaluate_stage_from(Kinematics::kPositionStage, level, registers_, position_out_.data());
  evaluated_ = true;
  evaluated_input_ = input;
}

bool Workspace::evaluated_at(double input, const Eigen::VectorXd& q) const {
  if (!evaluated_ || evaluated_input_ != input) return false;
  const std::size_t base = k_.parameter_count_;
  for (std::size_t i = 0; i < n_; ++i)
    if (registers_[base + 3 + i] != q[i]) return false;
  return true;
}

double Workspace::residual_norm() const {
  double norm = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    const double magnitude = std::fabs(phi()[i]);
    if (std::isnan(magnitude)) return magnitude;
    norm = std::max(norm, magnitude);
  }
  return norm;
}

namespace {

// LU with partial pivoting, in place, row-major, for the small Phi_q of a mechanism
// (plain loops: nothing allocated, nothing sized at run time by a library).
void lu_factor(double* a, std::size_t* pivots, std::size_t n) {
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t best = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::fabs(a[r * n + c]) > std::fabs(a[best * n + c])) best = r;
    pivots[c] = best;
    if (best != c) std::swap_ranges(a + c * n, a + c * n + n, a + best * n);
    const double pivot = a[c * n + c];
    if (pivot == 0.0) continue;  // singular: the pivot ratio reports it
    for (std::size_t r = c + 1; r < n; ++r) {
      const double factor = a[r * n + c] /= pivot;
      for (std::size_t j = c + 1; j < n; ++j) a[r * n + j] -= factor * a[c * n + j];
    }
  }
}

// Solves with lu_factor's result and the reciprocals of its pivots (a multiply is
// much quicker than a divide on the dependent chain); x holds the right-hand side.
void lu_solve(const double* a, const double* inverse_pivots, const std::size_t* pivots, double* x, std::size_t n) {
  // Row swaps first: the rows of L are stored in their final order.
  for (std::size_t c = 0; c < n; ++c)
    if (pivots[c] != c) std::swap(x[c], x[pivots[c]]);
  for (std::size_t c = 0; c < n; ++c)
    for (std::size_t r = c + 1; r < n; ++r) x[r] -= a[r * n + c] * x[c];
  for (std::size_t c = n; c-- > 0;) {
    x[c] *= inverse_pivots[c];
    for (std::size_t r = 0; r < c; ++r) x[r] -= a[r * n + c] * x[c];
  }
}

}  // namespace

void Workspace::factorise() {
  const double* phi_q = this->phi_q();
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t j = 0; j < n_; ++j) lu_[i * n_ + j] = phi_q[j * n_ + i] * column_scale_[j];
  lu_factor(lu_.data(), pivots_.data(), n_);
  for (std::size_t c = 0; c < n_; ++c) inverse_pivots_[c] = 1.0 / lu_[c * n_ + c];
}

double Workspace::pivot_ratio() const {
  double smallest = INFINITY, largest = 0;
  for (std::size_t c = 0; c < n_; ++c) {
    const double pivot = std::fabs(lu_[c * n_ + c]);
    smallest = std::min(smallest, pivot);
    largest = std::max(largest, pivot);
  }
  const double ratio = smallest / largest;
  return std::isfinite(ratio) ? ratio : 0.0;
}

Eigen::MatrixXd Workspace::scaled_phi_q() const {
  const Eigen::Index n = static_cast<Eigen::Index>(n_);
  return Eigen::Map<const Eigen::MatrixXd>(phi_q(), n, n) *
         Eigen::Map<const Eigen::VectorXd>(column_scale_.data(), n).asDiagonal();
}

double Workspace::reciprocal_condition() const {
  const double ratio = pivot_ratio();
  if (ratio == 0.0) return 0.0;
  // Well away from singular the pivots say so; the singular values (which
  // allocate) are only needed near a toggle, where they decide.
  if (ratio >= 1e-2) return ratio;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled_phi_q());
  const auto& s = svd.singularValues();
  return s[0] > 0 && std::isfinite(s[0]) ? s[s.size() - 1] / s[0] : 0.0;
}

void Workspace::solve_rhs(double* x) const {
  for (std::size_t i = 0; i < n_; ++i) x[i] = rhs_[i];
  lu_solve(lu_.data(), inverse_pivots_.data(), pivots_.data(), x, n_);
  for (std::size_t i = 0; i < n_; ++i) x[i] *= column_scale_[i];
}

bool Workspace::solve_position(double input, Eigen::VectorXd& q, std::size_t* worst_loop,
                               double* residual) {
  // Down to rounding: near a toggle the position error is the square root of the residual.
  const double tolerance = 1e-14 * k_.length_scale_;
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  double norm = residual_norm();
  bool converged = false;
  for (int iteration = 0; iteration < 60 && std::isfinite(norm); ++iteration) {
    if (norm <= tolerance) {
      converged = true;
      break;
    }
    factorise();
    if (pivot_ratio() > 1e-14) {
      for (std::size_t i = 0; i < n_; ++i) rhs_[i] = -phi()[i];
      solve_rhs(step_.data());
    } else {
      // Least-squares step: stays defined where Phi_q is (nearly) singular.
      const Eigen::Index n = static_cast<Eigen::Index>(n_);
      step_ = Eigen::Map<const Eigen::MatrixXd>(phi_q(), n, n).completeOrthogonalDecomposition().solve(
          -Eigen::Map<const Eigen::VectorXd>(phi(), n));
    }
    if (!step_.allFinite()) break;
    double lambda = 1.0;
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving, lambda *= 0.5) {
      for (std::size_t i = 0; i < n_; ++i) trial_[i] = q[i] + lambda * step_[i];
      evaluate_position(input, trial_);
      const double trial_norm = residual_norm();
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
    std::size_t row = 0;
    for (std::size_t i = 1; i < n_; ++i)
      if (std::fabs(phi()[i]) > std::fabs(phi()[row])) row = i;
    *worst_loop = row / 2;
  }
  if (residual) *residual = residual_norm();
  return converged && q.allFinite();
}

bool Workspace::sensitivity(double input, const Eigen::VectorXd& q, Eigen::VectorXd& dq) {
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  factorise();
  if (reciprocal_condition() < kSingularThreshold) return false;
  for (std::size_t i = 0; i < n_; ++i) rhs_[i] = -phi_theta()[i];
  dq.resize(static_cast<Eigen::Index>(n_));
  solve_rhs(dq.data());
  return dq.allFinite();
}

double Kinematics::max_continuation_step() const {
  return mechanism_.input.dimension == Dimension::angle ? 2.0 * M_PI / 180.0 : 0.01 * length_scale_;
}

bool Workspace::predict_and_correct(double to, const Eigen::VectorXd& predicted, Eigen::VectorXd& q) {
  // A corrected solution this far (scaled) from the prediction is another branch.
  constexpr double branch_tolerance = 0.05;
  trial_q_ = predicted;
  if (!solve_position(to, trial_q_)) return false;
  for (std::size_t i = 0; i < n_; ++i) {
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
    bool accepted = sensitivity(t, q, slope_);
    if (accepted) {
      predicted_ = q + slope_ * h;
      accepted = predict_and_correct(t + h, predicted_, q);
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
    const double w = state.input_rate, alpha = state.input_second_rate;
    for (std::size_t i = 0; i < n_; ++i) {
      const double slope = state.qd[i] / w;
      const double curvature = (state.qdd[i] - slope * alpha) / (w * w);
      predicted_[i] = state.q[i] + h * (slope + 0.5 * h * curvature);
    }
    solved = predict_and_correct(input, predicted_, trial_q_);
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
  const std::size_t base = k_.parameter_count_;
  state.input = input;
  state.input_rate = rate;
  state.input_second_rate = second_rate;
  state.q = q;
  state.message.clear();
  if (!evaluated_at(input, q)) evaluate_position(input, q);
  state.loop_residual = residual_norm();
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
  state.qd.resize(static_cast<Eigen::Index>(n));
  state.qdd.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) rhs_[i] = -phi_theta()[i] * rate;
  solve_rhs(state.qd.data());

  // Later stages reuse the registers of the position stage just evaluated at (input, q).
  registers_[base + 1] = rate;
  registers_[base + 2] = second_rate;
  for (std::size_t i = 0; i < n; ++i) registers_[base + 3 + n + i] = state.qd[i];
  k_.evaluator_.evaluate_stage_from(Kinematics::kAccelerationStage, Kinematics::kInputLevel, registers_, rhs_.data());
  solve_rhs(state.qdd.data());
  for (std::size_t i = 0; i < n; ++i) registers_[base + 3 + 2 * n + i] = state.qdd[i];
  k_.evaluator_.evaluate_stage_from(Kinematics::kPointStage, Kinematics::kInputLevel, registers_, point_out_.data());
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

MotionTable::MotionTable(const std::vector<double>& inputs, std::size_t unknowns, std::size_t points, double rate,
                         double second_rate)
    : n_(unknowns),
      points_per_row_(points),
      rate_(rate),
      second_rate_(second_rate),
      input_(inputs),
      q_(inputs.size() * unknowns),
      qd_(inputs.size() * unknowns),
      qdd_(inputs.size() * unknowns),
      loop_residual_(inputs.size()),
      reciprocal_condition_(inputs.size()),
      status_(inputs.size(), Status::unassembled),
      message_(inputs.size()),
      points_(inputs.size() * points * 6) {}

std::size_t MotionTable::bytes() const {
  std::size_t total = sizeof(double) * (input_.capacity() + q_.capacity() + qd_.capacity() + qdd_.capacity() +
                                        loop_residual_.capacity() + reciprocal_condition_.capacity() +
                                        points_.capacity());
  total += sizeof(Status) * status_.capacity() + sizeof(std::string) * message_.capacity();
  for (const std::string& message : message_)
    if (message.capacity() > 15) total += message.capacity() + 1;  // beyond the small-string buffer
  return total;
}

MotionState MotionTable::operator[](std::size_t row) const {
  MotionState s;
  s.input = input_[row];
  s.input_rate = rate_;
  s.input_second_rate = second_rate_;
  s.status = status_[row];
  s.message = message_[row];
  s.loop_residual = loop_residual_[row];
  s.reciprocal_condition = reciprocal_condition_[row];
  if (s.status != Status::unassembled) s.q = q(row);
  if (s.status == Status::ok) {
    s.qd = qd(row);
    s.qdd = qdd(row);
    s.points.resize(points_per_row_);
    for (std::size_t p = 0; p < points_per_row_; ++p) s.points[p] = point(row, p);
  }
  return s;
}

void MotionTable::set(std::size_t row, const MotionState& s) {
  input_[row] = s.input;
  status_[row] = s.status;
  message_[row] = s.message;
  loop_residual_[row] = s.loop_residual;
  reciprocal_condition_[row] = s.reciprocal_condition;
  const std::size_t rows = size();
  auto copy = [&](const Eigen::VectorXd& from, std::vector<double>& to) {
    if (static_cast<std::size_t>(from.size()) != n_) return;
    for (std::size_t i = 0; i < n_; ++i) to[i * rows + row] = from[i];
  };
  copy(s.q, q_);
  copy(s.qd, qd_);
  copy(s.qdd, qdd_);
  if (s.points.size() == points_per_row_) {
    double* v = points_.data() + row;
    for (const PointMotion& m : s.points) {
      for (double value : {m.x, m.y, m.vx, m.vy, m.ax, m.ay}) {
        *v = value;
        v += rows;
      }
    }
  }
}

namespace {

constexpr std::size_t kLanes = BatchWorkspace::kLanes;

// LU with partial pivoting of kLanes small matrices at once, lane-parallel: the
// pivot row of each lane is chosen and swapped in by selects, so every loop is a
// fixed-length loop over lanes. Same operations, in the same order, as lu_factor.
KINEMA_LANE_LOOPS void lu_factor_lanes(double* a, double* pivots, std::size_t n) {
  auto at = [&](std::size_t i, std::size_t j) { return a + (i * n + j) * kLanes; };
  for (std::size_t c = 0; c < n; ++c) {
    double best[kLanes], best_magnitude[kLanes];
    const double* diagonal = at(c, c);
    for (std::size_t l = 0; l < kLanes; ++l) {
      best[l] = static_cast<double>(c);
      best_magnitude[l] = std::fabs(diagonal[l]);
    }
    for (std::size_t r = c + 1; r < n; ++r) {
      const double* candidate = at(r, c);
      for (std::size_t l = 0; l < kLanes; ++l) {
        const double magnitude = std::fabs(candidate[l]);
        const bool larger = magnitude > best_magnitude[l];
        best[l] = larger ? static_cast<double>(r) : best[l];
        best_magnitude[l] = larger ? magnitude : best_magnitude[l];
      }
    }
    std::copy(best, best + kLanes, pivots + c * kLanes);
    for (std::size_t r = c + 1; r < n; ++r) {
      for (std::size_t j = 0; j < n; ++j) {
        double* __restrict top = at(c, j);
        double* __restrict other = at(r, j);
        for (std::size_t l = 0; l < kLanes; ++l) {
          const bool swap = best[l] == static_cast<double>(r);
          const double t = top[l];
          top[l] = swap ? other[l] : t;
          other[l] = swap ? t : other[l];
        }
      }
    }
    for (std::size_t r = c + 1; r < n; ++r) {
      double* __restrict factor = at(r, c);
      const double* __restrict pivot = at(c, c);
      for (std::size_t l = 0; l < kLanes; ++l) factor[l] /= pivot[l];
      for (std::size_t j = c + 1; j < n; ++j) {
        double* __restrict target = at(r, j);
        const double* __restrict source = at(c, j);
        for (std::size_t l = 0; l < kLanes; ++l) target[l] -= factor[l] * source[l];
      }
    }
  }
}

// Solves with lu_factor_lanes's result; x (n rows of kLanes) holds the right-hand sides.
KINEMA_LANE_LOOPS void lu_solve_lanes(const double* a, const double* pivots, double* x, std::size_t n) {
  auto at = [&](std::size_t i, std::size_t j) { return a + (i * n + j) * kLanes; };
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t r = c + 1; r < n; ++r) {
      double* __restrict top = x + c * kLanes;
      double* __restrict other = x + r * kLanes;
      const double* __restrict pivot = pivots + c * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) {
        const bool swap = pivot[l] == static_cast<double>(r);
        const double t = top[l];
        top[l] = swap ? other[l] : t;
        other[l] = swap ? t : other[l];
      }
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t r = c + 1; r < n; ++r) {
      double* __restrict target = x + r * kLanes;
      const double* __restrict source = x + c * kLanes;
      const double* __restrict factor = at(r, c);
      for (std::size_t l = 0; l < kLanes; ++l) target[l] -= factor[l] * source[l];
    }
  }
  for (std::size_t c = n; c-- > 0;) {
    double* __restrict value = x + c * kLanes;
    const double* __restrict pivot = at(c, c);
    for (std::size_t l = 0; l < kLanes; ++l) value[l] /= pivot[l];
    for (std::size_t r = 0; r < c; ++r) {
      double* __restrict target = x + r * kLanes;
      const double* __restrict factor = at(r, c);
      for (std::size_t l = 0; l < kLanes; ++l) target[l] -= factor[l] * value[l];
    }
  }
}

}  // namespace

BatchWorkspace::BatchWorkspace(const Kinematics& k)
    : k_(k),
      n_(k.unknown_count_),
      registers_(k.evaluator_.make_batch_workspace()),
      lu_(n_ * n_ * kLanes),
      pivots_(n_ * kLanes),
      x_(n_ * kLanes),
      predicted_(n_ * kLanes),
      column_scale_(n_) {
  for (std::size_t p = 0; p < k.parameter_count_; ++p) std::fill_n(lanes(p), kLanes, k.parameter_values_[p]);
  k.evaluator_.prepare_batch(registers_.data());
  for (std::size_t j = 0; j < n_; ++j)
    column_scale_[j] = k.mechanism_.unknowns[j].dimension == Dimension::length ? k.length_scale_ : 1.0;
}

bool BatchWorkspace::factorise() {
  const auto& e = k_.evaluator_;
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t j = 0; j < n_; ++j) {
      const double* phi_q = lanes(e.output_register(Kinematics::kPositionStage, n_ + j * n_ + i));
      double* target = lu_.data() + (i * n_ + j) * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) target[l] = phi_q[l] * column_scale_[j];
    }
  lu_factor_lanes(lu_.data(), pivots_.data(), n_);
  // Clearly regular pivots only; anything near a toggle goes to the scalar path,
  // which decides singularity with the singular values.
  pivot_ratios(pivot_ratio_);
  int irregular = 0;
  for (std::size_t l = 0; l < kLanes; ++l) irregular += !(pivot_ratio_[l] >= 1e-2);
  return irregular == 0;
}

void BatchWorkspace::pivot_ratios(double* ratio) const {
  double smallest[kLanes], largest[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) {
    smallest[l] = INFINITY;
    largest[l] = 0;
  }
  for (std::size_t c = 0; c < n_; ++c) {
    const double* pivot = lu_.data() + (c * n_ + c) * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double magnitude = std::fabs(pivot[l]);
      smallest[l] = magnitude < smallest[l] ? magnitude : smallest[l];
      largest[l] = magnitude > largest[l] ? magnitude : largest[l];
    }
  }
  // NaN (a zero pivot divided through) compares false: not regular.
  for (std::size_t l = 0; l < kLanes; ++l) ratio[l] = smallest[l] / largest[l];
}

bool BatchWorkspace::predict(const MotionTable& table, std::size_t first, std::size_t history_begin) {
  const double rate = table.input_rate(), second_rate = table.input_second_rate();
  const std::size_t last = first - 1;
  const double t1 = table.input(last);
  const double reach = 4 * k_.max_continuation_step();
  for (std::size_t l = 0; l < kLanes; ++l)
    if (!(std::fabs(table.input(first + l) - t1) <= reach)) return false;
  // Quintic Hermite through the last row and the one a block earlier (values, first
  // and second derivatives in the input) when both are on the same stretch of
  // solved rows; else Taylor to second order from the last row.
  bool hermite = last >= history_begin + kLanes;
  const std::size_t earlier = hermite ? last - kLanes : last;
  for (std::size_t row = earlier; hermite && row <= last; ++row)
    hermite = table.status(row) == Status::ok && (row == earlier || table.message(row).empty());
  const double t0 = table.input(earlier), span = t1 - t0;
  hermite = hermite && span != 0 && std::fabs(span) <= reach;
  for (std::size_t i = 0; i < n_; ++i) {
    auto derivatives = [&](std::size_t row, double& value, double& slope, double& curvature) {
      value = table.q(row)[i];
      slope = table.qd(row)[i] / rate;
      curvature = (table.qdd(row)[i] - slope * second_rate) / (rate * rate);
    };
    double y1, d1, c1;
    derivatives(last, y1, d1, c1);
    double* out = predicted_.data() + i * kLanes;
    if (!hermite) {
      for (std::size_t l = 0; l < kLanes; ++l) {
        const double h = table.input(first + l) - t1;
        out[l] = y1 + h * (d1 + 0.5 * c1 * h);
      }
      continue;
    }
    double y0, d0, c0;
    derivatives(earlier, y0, d0, c0);
    // Newton form on the nodes t0, t0, t0, t1, t1, t1 (confluent divided differences).
    const double f01 = (y1 - y0) / span;
    const double f001 = (f01 - d0) / span, f011 = (d1 - f01) / span;
    const double f0001 = (f001 - 0.5 * c0) / span, f0011 = (f011 - f001) / span, f0111 = (0.5 * c1 - f011) / span;
    const double f00011 = (f0011 - f0001) / span, f00111 = (f0111 - f0011) / span;
    const double f000111 = (f00111 - f00011) / span;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double u = table.input(first + l) - t0, v = table.input(first + l) - t1;
      out[l] = y0 + u * (d0 + u * (0.5 * c0 + u * (f0001 + v * (f00011 + v * f000111))));
    }
  }
  return true;
}

bool BatchWorkspace::solve(MotionTable& table, std::size_t first, std::size_t history_begin) {
  const std::size_t n = n_, base = k_.parameter_count_, point_count = k_.point_count_;
  const auto& e = k_.evaluator_;
  const double rate = table.input_rate(), second_rate = table.input_second_rate();
  const double tolerance = 1e-14 * k_.length_scale_;
  if (!predict(table, first, history_begin)) return false;
  for (std::size_t l = 0; l < kLanes; ++l) {
    lanes(base)[l] = table.input(first + l);
    lanes(base + 1)[l] = rate;
    lanes(base + 2)[l] = second_rate;
  }
  for (std::size_t i = 0; i < n; ++i) std::copy_n(predicted_.data() + i * kLanes, kLanes, lanes(base + 3 + i));

  // Newton on every lane at once; Phi_q is factorised at each iterate, so the last
  // factorisation (at the solution) also gives the rates. A lane that has converged
  // stays where it is, as the scalar solver stops there.
  double residual[kLanes];
  double done[kLanes];  // 1 for a lane that has converged
  for (int iteration = 0;; ++iteration) {
    e.evaluate_stage_batch_from(Kinematics::kPositionStage,
                                iteration == 0 ? Kinematics::kInputLevel : Kinematics::kCoordinateLevel,
                                registers_.data());
    bool all_done = true;
    for (std::size_t l = 0; l < kLanes; ++l) residual[l] = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double* phi = lanes(e.output_register(Kinematics::kPositionStage, i));
      for (std::size_t l = 0; l < kLanes; ++l) {
        // NaN stays: the comparison is false for it.
        const double magnitude = std::fabs(phi[l]);
        residual[l] = (magnitude > residual[l] || magnitude != magnitude) ? magnitude : residual[l];
      }
    }
    int nonfinite = 0, open = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      nonfinite += !(residual[l] <= DBL_MAX);
      done[l] = residual[l] <= tolerance ? 1.0 : 0.0;
      open += !(residual[l] <= tolerance);
    }
    if (nonfinite) return false;
    all_done = open == 0;
    if (!factorise()) return false;
    if (all_done) break;
    if (iteration == 6) return false;
    for (std::size_t i = 0; i < n; ++i) {
      const double* phi = lanes(e.output_register(Kinematics::kPositionStage, i));
      for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi[l];
    }
    lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
      double* q = lanes(base + 3 + i);
      for (std::size_t l = 0; l < kLanes; ++l) q[l] += (1.0 - done[l]) * x_[i * kLanes + l] * column_scale_[i];
    }
  }
  // Same branch as predicted (as Workspace::predict_and_correct checks).
  int jumped = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double* q = lanes(base + 3 + i);
    const double* predicted = predicted_.data() + i * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) jumped += !(std::fabs(q[l] - predicted[l]) <= 0.05 * column_scale_[i]);
  }
  if (jumped) return false;

  // Velocity, then acceleration, with the factorisation at the solution.
  for (std::size_t i = 0; i < n; ++i) {
    const double* phi_theta = lanes(e.output_register(Kinematics::kPositionStage, n + n * n + i));
    for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi_theta[l] * rate;
  }
  lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    double* qd = lanes(base + 3 + n + i);
    for (std::size_t l = 0; l < kLanes; ++l) qd[l] = x_[i * kLanes + l] * column_scale_[i];
  }
  e.evaluate_stage_batch_from(Kinematics::kAccelerationStage, Kinematics::kInputLevel, registers_.data());
  for (std::size_t i = 0; i < n; ++i)
    std::copy_n(lanes(e.output_register(Kinematics::kAccelerationStage, i)), kLanes, x_.data() + i * kLanes);
  lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    double* qdd = lanes(base + 3 + 2 * n + i);
    for (std::size_t l = 0; l < kLanes; ++l) qdd[l] = x_[i * kLanes + l] * column_scale_[i];
  }
  e.evaluate_stage_batch_from(Kinematics::kPointStage, Kinematics::kInputLevel, registers_.data());
  // x * 0 is 0 for finite x and NaN otherwise: one sum per lane says whether all are finite.
  double nonfinite[kLanes] = {};
  auto accumulate = [&](const double* v) {
    for (std::size_t l = 0; l < kLanes; ++l) nonfinite[l] += v[l] * 0.0;
  };
  for (std::size_t k = 0; k < 6 * point_count; ++k) accumulate(lanes(e.output_register(Kinematics::kPointStage, k)));
  for (std::size_t i = 0; i < 2 * n; ++i) accumulate(lanes(base + 3 + n + i));
  int bad = 0;
  for (std::size_t l = 0; l < kLanes; ++l) bad += nonfinite[l] != 0.0;
  if (bad) return false;

  // Lanes to rows: the table is column-major, so each quantity is one contiguous copy.
  for (std::size_t l = 0; l < kLanes; ++l) {
    table.status_[first + l] = Status::ok;
    table.message_[first + l].clear();
  }
  const std::size_t rows = table.size();
  std::copy_n(residual, kLanes, table.loop_residual_.data() + first);
  std::copy_n(pivot_ratio_, kLanes, table.reciprocal_condition_.data() + first);
  for (std::size_t i = 0; i < n; ++i) {
    std::copy_n(lanes(base + 3 + i), kLanes, table.q_.data() + i * rows + first);
    std::copy_n(lanes(base + 3 + n + i), kLanes, table.qd_.data() + i * rows + first);
    std::copy_n(lanes(base + 3 + 2 * n + i), kLanes, table.qdd_.data() + i * rows + first);
  }
  for (std::size_t k = 0; k < 6 * point_count; ++k)
    std::copy_n(lanes(e.output_register(Kinematics::kPointStage, k)), kLanes, table.points_.data() + k * rows + first);
  return true;
}

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
  Eigen::VectorXd trial, predicted;
  std::size_t next_batch_try = begin;  // after a refused block, go on one by one for a while
  bool have_previous = false;  // row - 1 is solved (status ok) on the user's branch
  bool after_gap = false;
  bool any_solved = false;
  for (std::size_t row = begin; row < end; ++row) {
    const double input = table.input(row);
    if (batch_workspace && have_previous && row >= next_batch_try && row + BatchWorkspace::kLanes <= end &&
        table.message(row - 1).empty()) {
      if (batch_workspace->solve(table, row, begin)) {
        batch_rows += BatchWorkspace::kLanes;
        row += BatchWorkspace::kLanes - 1;
        q = table.q(row);
        continue;
      }
      next_batch_try = row + BatchWorkspace::kLanes;
    }
    bool solved = false;
    std::string why;
    trial = q;
    if (have_previous) {
      // Fast path for sweeps: predict from the rates just computed (dq/dtheta =
      // qd/thetad) and correct; the general continuation only when that fails.
      const double previous_input = table.input(row - 1);
      const double h = input - previous_input;
      if (rate != 0 && std::fabs(h) <= kinematics.max_continuation_step()) {
        // Second order: the rates of row - 1 give dq/dtheta and d2q/dtheta2.
        const auto slope = table.qd(row - 1) / rate;
        predicted = q + h * slope + (0.5 * h * h / (rate * rate)) * (table.qdd(row - 1) - slope * second_rate);
        solved = workspace.predict_and_correct(input, predicted, trial);
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
      MotionState failed;
      failed.input = input;
      failed.status = Status::unassembled;
      failed.message = why;
      table.set(row, failed);
      after_gap = any_solved;
      have_previous = false;  // resume from the last good q; the branch may differ after a gap
      continue;
    }
    q = trial;
    any_solved = true;
    workspace.motion_into(input, rate, second_rate, q, state);
    if (after_gap && state.status == Status::ok) {
      state.message = "resumed after positions that could not be assembled; the branch across "
                      "the gap is not guaranteed";
    }
    // Past a singular position the branch may change: treat it like a gap.
    after_gap = state.status != Status::ok;
    have_previous = state.status == Status::ok;
    table.set(row, state);
  }
}

}  // namespace

MotionTable analyse(const Kinematics& kinematics, const std::vector<double>& inputs, double rate,
                    double second_rate, unsigned threads, bool batch) {
  const std::size_t n = inputs.size();
  MotionTable table(inputs, kinematics.unknown_count(), kinematics.point_count(), rate, second_rate);
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
    analyse_range(kinematics, 0, n, start[0], table, batch, table.batch_rows_);
    return table;
  }
  std::vector<std::thread> workers;
  std::vector<std::size_t> batch_rows(threads, 0);
  for (unsigned t = 0; t < threads; ++t) {
    workers.emplace_back(analyse_range, std::cref(kinematics), begin[t], begin[t + 1], start[t], std::ref(table),
                         batch, std::ref(batch_rows[t]));
  }
  for (auto& worker : workers) worker.join();
  for (std::size_t rows : batch_rows) table.batch_rows_ += rows;
  return table;
}

}  // namespace kinema
