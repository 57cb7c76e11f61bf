#include <kinema/engine/numeric/toggles.hpp>

#include <algorithm>
#include <cmath>

#include <kinema/engine/numeric/workspace.hpp>

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
  const double turn = 2 * M_PI;
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
  for (int i = 0; i < 36; ++i) starts.push_back(first + i * M_PI / 18);
  const MotionTable solved = analyse(model, starts);
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
        largest = std::max(largest, std::fabs(step[j]) / (length ? 0.05 * scale : 3 * M_PI / 180));
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
      return std::min(d, 2 * M_PI - d) < 1e-7;
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

std::vector<Toggle> find_limit_positions(const Model& model, std::size_t j) {
  const Kinematics& k = model.kinematics;
  // dq_j/dtheta = 0, by Cramer: the determinant with column j replaced by -Phi_theta
  // (scaled like det Phi_q, so that it is of order 1; no division near a toggle).
  const std::vector<Toggle> candidates = solve_with(model, [&, j](const Eigen::MatrixXd& phi_q, const Eigen::VectorXd& phi_theta) {
    Eigen::MatrixXd m = phi_q;
    m.col(Eigen::Index(j)) = -phi_theta;
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      m.col(c) *= (c == Eigen::Index(j) ? 1.0 : k.column_scale()[std::size_t(c)]) / k.length_scale();
    return m.determinant();
  });
  // Newton in (q, theta) may land on another assembly of the loops: keep the limits of the
  // mechanism's own, as reached by continuation from its file value.
  std::vector<Toggle> limits;
  const double first = model.system.input.values.empty() ? 0.0 : model.system.input.values.front();
  for (const Toggle& t : candidates) {
    const MotionTable path = analyse(model, {first, first + std::remainder(t.input - first, 2 * M_PI)});
    if (path.status(1) == Status::unassembled) continue;
    const double scale = k.length_scale();
    bool same = true;
    for (Eigen::Index i = 0; i < t.q.size(); ++i) {
      const double unit = k.column_scale()[std::size_t(i)] != 1.0 ? scale : 1.0;
      double d = path.q(1)[i] - t.q[i];
      if (unit == 1.0) d = std::remainder(d, 2 * M_PI);  // angles a turn apart are the same
      same = same && std::fabs(d) < 1e-6 * unit;
    }
    if (same) limits.push_back(t);
  }
  return limits;
}

}  // namespace kinema
