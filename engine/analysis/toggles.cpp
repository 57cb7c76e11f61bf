#include "engine/analysis/toggles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/numeric/workspace.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

// det Phi_q with its columns scaled (the solvers' scaling) and divided by the length
// scale per row: of order 1 where the mechanism is well conditioned.
double scaled_determinant(const Eigen::MatrixXd& phi_q, const Kinematics& k) {
  Eigen::MatrixXd m = phi_q;
  for (Eigen::Index j = 0; j < m.cols(); ++j) m.col(j) *= k.column_scale()[std::size_t(j)] / k.length_scale();
  return m.determinant();
}

// In [0, 2 pi); within the solver's precision of a full turn, 0.
double wrapped(double angle) {
  const double turn = 2 * kPi;
  double a = std::fmod(angle, turn);
  if (a < 0) a += turn;
  return a < 1e-8 || turn - a < 1e-8 ? 0.0 : a;
}

}  // namespace

namespace {

// Solutions over a turn of Phi(q, theta) = 0 together with one more equation
// extra(Phi_q, Phi_theta) = 0, by Newton in (q, theta) from positions every 10 deg.
template <class Extra>
std::vector<Toggle> solve_with(const Model& model, Extra extra) {
  std::vector<Toggle> found;
  const ConstraintSystem& system = model.system;
  if (system.input.dimension != Dimension::angle || system.unknowns.empty()) return found;
  const auto n = Eigen::Index(system.unknowns.size());
  const Kinematics& k = model.kinematics;
  const double scale = k.length_scale();
  Workspace workspace(model);
  Eigen::VectorXd phi, phi_theta;
  Eigen::MatrixXd phi_q;
  const auto residual = [&](const Eigen::VectorXd& at, Eigen::VectorXd& f) {
    workspace.position_system(at[n], at.head(n), phi, phi_q, phi_theta);
    f.resize(n + 1);
    f.head(n) = phi / scale;
    f[n] = extra(phi_q, phi_theta);
  };
  const double first = system.input.values.empty() ? 0.0 : system.input.values.front();
  std::vector<double> starts;
  for (int i = 0; i < 36; ++i) starts.push_back(first + i * kPi / 18);
  const MotionTable solved = solve_motion(model, starts);
  for (std::size_t row = 0; row < solved.size(); ++row) {
    if (solved.status(row) == Status::unassembled) continue;
    Eigen::VectorXd z(n + 1), f;
    z.head(n) = solved.q(row);
    z[n] = solved.input(row);
    bool converged = false;
    for (int iteration = 0; iteration < 40 && !converged; ++iteration) {
      residual(z, f);
      if (!f.allFinite()) break;
      Eigen::MatrixXd jacobian(n + 1, n + 1);
      jacobian.topLeftCorner(n, n) = phi_q / scale;
      jacobian.topRightCorner(n, 1) = phi_theta / scale;
      // The extra equation's gradient by central differences.
      for (Eigen::Index j = 0; j <= n; ++j) {
        const double h = 1e-6 * (j < n && k.column_scale()[std::size_t(j)] != 1.0 ? scale : 1.0);
        Eigen::VectorXd plus = z, minus = z, fp, fm;
        plus[j] += h;
        minus[j] -= h;
        residual(plus, fp);
        residual(minus, fm);
        jacobian(n, j) = (fp[n] - fm[n]) / (2 * h);
      }
      Eigen::VectorXd step = jacobian.fullPivLu().solve(-f);
      if (!step.allFinite()) break;
      // Damped: at most 3 deg of any angle (or 5 % of the length scale) per step, so that
      // Newton stays on the assembly it starts from.
      double largest = 0;
      for (Eigen::Index j = 0; j <= n; ++j) {
        const bool length = j < n && k.column_scale()[std::size_t(j)] != 1.0;
        largest = std::max(largest, std::fabs(step[j]) / (length ? 0.05 * scale : 3 * kPi / 180));
      }
      if (largest > 1) step /= largest;
      z += step;
      converged = step.norm() < 1e-13 * (1 + z.norm()) && f.head(n).norm() < 1e-10;
    }
    if (!converged) continue;
    residual(z, f);  // on the loops and the extra equation both
    if (f.head(n).norm() > 1e-9 || std::fabs(f[n]) > 1e-9) continue;
    const double at = wrapped(z[n]);
    const bool known = std::any_of(found.begin(), found.end(), [&](const Toggle& t) {
      const double d = std::fabs(t.input - at);
      return std::min(d, 2 * kPi - d) < 1e-7;
    });
    if (!known) found.push_back({at, z.head(n)});
  }
  std::sort(found.begin(), found.end(), [](const Toggle& a, const Toggle& b) { return a.input < b.input; });
  return found;
}

}  // namespace

std::vector<Toggle> find_toggles(const Model& model) {
  const Kinematics& k = model.kinematics;
  return solve_with(model, [&](const Eigen::MatrixXd& phi_q, const Eigen::VectorXd&) { return scaled_determinant(phi_q, k); });
}

std::vector<Toggle> limit_positions_in_turn(const MotionTable& turn, std::size_t rows, const double* g,
                                            std::size_t unknown, Workspace& workspace, const KnownLimit& known) {
  std::vector<double> inputs(rows);
  for (std::size_t row = 0; row < rows; ++row) inputs[row] = turn.input(row);
  return limit_positions_in_turn(inputs.data(), [&](std::size_t row) { return Eigen::VectorXd(turn.q(row)); }, rows, g,
                                 unknown, workspace, known);
}

std::vector<Toggle> limit_positions_in_turn(const double* inputs, const RowPosition& position, std::size_t rows,
                                            const double* g, std::size_t unknown, Workspace& workspace,
                                            const KnownLimit& known) {
  const auto j = Eigen::Index(unknown);
  std::vector<Toggle> found;
  // `maximum`: the unknown's rate goes from positive to negative there as the input grows.
  const auto keep = [&](double input, const Eigen::VectorXd& q, bool maximum) {
    const double at = wrapped(input);
    const bool known = std::any_of(found.begin(), found.end(), [&](const Toggle& t) {
      const double d = std::fabs(t.input - at);
      return std::min(d, 2 * kPi - d) < 1e-7;
    });
    if (!known) found.push_back({at, q, maximum});
  };
  for (std::size_t row = 0; row + 1 < rows; ++row) {
    if (std::isnan(g[row]) || std::isnan(g[row + 1])) continue;
    double ga = g[row], gb = g[row + 1];
    if (ga == 0) {
      // On a row: a maximum where the rate was positive before it, or is negative after.
      const bool before = row > 0 && !std::isnan(g[row - 1]) && g[row - 1] != 0;
      keep(inputs[row], position(row), before ? g[row - 1] > 0 : gb < 0);
      continue;
    }
    if (!(ga * gb < 0)) continue;
    const bool maximum = ga > 0;
    if (known) {
      const double at = known(inputs[row], inputs[row + 1]);
      if (!std::isnan(at)) {
        keep(at, position(std::fabs(at - inputs[row]) <= std::fabs(at - inputs[row + 1]) ? row : row + 1), maximum);
        continue;
      }
    }
    // Regula falsi, Illinois variant: q solved from the nearer end of the bracket (1 deg
    // apart at most, so on the same assembly).
    double ta = inputs[row], tb = inputs[row + 1];
    Eigen::VectorXd qa = position(row), qb = position(row + 1), q, dq;
    double t = ta, last = std::numeric_limits<double>::quiet_NaN();
    bool solved = false;
    for (int iteration = 0; iteration < 200; ++iteration) {
      t = (ta * gb - tb * ga) / (gb - ga);
      if (!(t > std::min(ta, tb) && t < std::max(ta, tb))) {
        if (std::isfinite(t)) {  // rounded onto an end: the root is there to round-off
          const bool at_a = std::fabs(ga) < std::fabs(gb);
          t = at_a ? ta : tb;
          q = at_a ? qa : qb;
          solved = true;
          break;
        }
        t = 0.5 * (ta + tb);
      }
      q = std::fabs(t - ta) < std::fabs(t - tb) ? qa : qb;
      if (!workspace.solve_position(t, q) || !workspace.sensitivity(t, q, dq)) break;
      const double value = dq[j];
      // Converged when the bracket or the step from the last trial is at round-off.
      const double tolerance = 1e-14 * (1 + std::fabs(t));
      if (value == 0 || std::fabs(tb - ta) < tolerance || std::fabs(t - last) < tolerance) {
        solved = true;
        break;
      }
      last = t;
      // (ta, ga) the end kept, (tb, gb) the latest trial: halve the kept end's value when
      // it is kept twice in a row (Illinois), so that it does not stall.
      if ((value < 0) != (gb < 0)) {
        ta = tb, ga = gb, qa = qb;
      } else {
        ga *= 0.5;
      }
      tb = t, gb = value, qb = q;
    }
    if (solved) keep(t, q, maximum);
  }
  std::sort(found.begin(), found.end(), [](const Toggle& a, const Toggle& b) { return a.input < b.input; });
  return found;
}

std::vector<std::vector<Toggle>> find_limit_positions(const Model& model, const std::vector<std::size_t>& unknowns,
                                                      bool* whole_turn) {
  // One sweep of the turn in 1-deg steps, shared by every unknown asked for: dq/dtheta of all
  // unknowns from one LU per row, then each sign change of dq_j/dtheta refined alone (a
  // root of one function of theta, q solved at each trial). Newton in (q, theta) per unknown,
  // with its gradient by differences, cost O(n^4) a step for every unknown: 32 sliders of 16
  // loops took 15-23 s in eval's header (issue 33); this is one sweep and a few solves a limit.
  std::vector<std::vector<Toggle>> limits(unknowns.size());
  const ConstraintSystem& system = model.system;
  if (whole_turn) *whole_turn = false;
  if (system.input.dimension != Dimension::angle || system.unknowns.empty() || unknowns.empty()) return limits;
  const double first = system.input.values.empty() ? 0.0 : system.input.values.front();
  std::vector<double> inputs;
  for (int k = 0; k <= 360; ++k) inputs.push_back(first + k * kPi / 180);
  // The mechanism's own assembly, by continuation from its file value.
  const MotionTable turn = solve_motion(model, inputs);
  Workspace workspace(model);
  std::vector<Eigen::VectorXd> rates(turn.size());  // dq/dtheta; empty where not assembled or singular
  if (whole_turn) *whole_turn = true;
  for (std::size_t row = 0; row < turn.size(); ++row) {
    if (turn.status(row) == Status::unassembled) {
      if (whole_turn) *whole_turn = false;
      continue;
    }
    Eigen::VectorXd dq;
    if (workspace.sensitivity(turn.input(row), turn.q(row), dq)) rates[row] = dq;
  }
  std::vector<double> g(turn.size());
  for (std::size_t w = 0; w < unknowns.size(); ++w) {
    for (std::size_t row = 0; row < turn.size(); ++row)
      g[row] = rates[row].size() == 0 ? std::numeric_limits<double>::quiet_NaN() : rates[row][Eigen::Index(unknowns[w])];
    limits[w] = limit_positions_in_turn(turn, turn.size(), g.data(), unknowns[w], workspace);
  }
  return limits;
}

std::vector<Toggle> find_limit_positions(const Model& model, std::size_t j) {
  return find_limit_positions(model, std::vector<std::size_t>{j}).front();
}

}  // namespace kinema
