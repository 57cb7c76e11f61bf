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

std::vector<Toggle> find_toggles(const Model& model) {
  std::vector<Toggle> toggles;
  const ConstraintSystem& system = model.system;
  if (system.input.dimension != Dimension::angle || system.unknowns.empty()) return toggles;
  const Kinematics& k = model.kinematics;
  const auto n = Eigen::Index(system.unknowns.size());
  const double scale = k.length_scale();
  Workspace workspace(model);
  Eigen::VectorXd phi, phi_theta;
  Eigen::MatrixXd phi_q;
  // Starting positions: the mechanism solved every 10 deg of a turn from its file value.
  const double first = system.input.values.empty() ? 0.0 : system.input.values.front();
  std::vector<double> starts;
  for (int i = 0; i < 36; ++i) starts.push_back(first + i * M_PI / 18);
  const MotionTable solved = analyse(model, starts);
  for (std::size_t row = 0; row < solved.size(); ++row) {
    if (solved.status(row) == Status::unassembled) continue;
    Eigen::VectorXd z(n + 1);
    z.head(n) = solved.q(row);
    z[n] = solved.input(row);
    bool converged = false;
    for (int iteration = 0; iteration < 40 && !converged; ++iteration) {
      const auto residual = [&](const Eigen::VectorXd& at, Eigen::VectorXd& f) {
        workspace.position_system(at[n], at.head(n), phi, phi_q, phi_theta);
        f.resize(n + 1);
        f.head(n) = phi / scale;
        f[n] = scaled_determinant(phi_q, k);
      };
      Eigen::VectorXd f;
      residual(z, f);
      if (!f.allFinite()) break;
      Eigen::MatrixXd jacobian(n + 1, n + 1);
      jacobian.topLeftCorner(n, n) = phi_q / scale;
      jacobian.topRightCorner(n, 1) = phi_theta / scale;
      // The determinant's gradient by central differences (a few evaluations per step).
      for (Eigen::Index j = 0; j <= n; ++j) {
        const double h = 1e-6 * (j < n && k.column_scale()[std::size_t(j)] != 1.0 ? scale : 1.0);
        Eigen::VectorXd plus = z, minus = z, fp, fm;
        plus[j] += h;
        minus[j] -= h;
        residual(plus, fp);
        residual(minus, fm);
        jacobian(n, j) = (fp[n] - fm[n]) / (2 * h);
      }
      const Eigen::VectorXd step = jacobian.fullPivLu().solve(-f);
      if (!step.allFinite()) break;
      z += step;
      converged = step.norm() < 1e-13 * (1 + z.norm()) && f.head(n).norm() < 1e-10;
    }
    if (!converged) continue;
    // A solution of both: on the loops and folded.
    Eigen::VectorXd f;
    workspace.position_system(z[n], z.head(n), phi, phi_q, phi_theta);
    if (phi.norm() > 1e-9 * scale || std::fabs(scaled_determinant(phi_q, k)) > 1e-9) continue;
    const double at = wrapped(z[n]);
    const bool known = std::any_of(toggles.begin(), toggles.end(), [&](const Toggle& t) {
      const double d = std::fabs(t.input - at);
      return std::min(d, 2 * M_PI - d) < 1e-7;
    });
    if (!known) toggles.push_back({at, z.head(n)});
  }
  std::sort(toggles.begin(), toggles.end(), [](const Toggle& a, const Toggle& b) { return a.input < b.input; });
  return toggles;
}

}  // namespace kinema
