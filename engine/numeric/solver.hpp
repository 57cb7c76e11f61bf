// The numeric rules of kinema, written once: the solver's constants, the LU
// factorisation with partial pivoting and its solve, the damped Newton-Raphson
// on the position system, the singular values and the reciprocal condition that
// decides singular positions, and the second-order predictor. The scalar
// workspace and the generated header use them as they are; the
// lane-parallel workspace follows the same pivoting rule in lane form.
//
// The generated C++ header (`kinema codegen`, printers/code/cpp_header.cpp)
// carries this code itself, not a restatement: at build time this file's text
// becomes a string (CMakeLists.txt: solver_source.inc), and the printer pastes
// everything between the line `namespace kinema::solver {` and the line
// `}  // namespace kinema::solver` into the header's own `namespace solver`,
// after this file's #include lines. So, in the part between those lines: no
// Eigen, GiNaC or kinema names, only what the includes below provide; and
// nothing a -Wall -Wextra -Werror compile of the header would reject.
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>

namespace kinema::solver {

/// Newton stops when max |Phi| <= this times the mechanism's length scale: rounding
/// level (near a toggle the position error is the square root of the residual).
constexpr double kNewtonTolerance = 1e-14;
/// A Newton run that stalls with max |Phi| below this (times the length scale)
/// has converged to rounding all the same.
constexpr double kRoundingTolerance = 1e-9;
constexpr int kNewtonIterations = 60;
constexpr int kStepHalvings = 30;
/// Pivot ratio below which Newton takes a least-squares step instead of an LU step.
constexpr double kLeastSquaresPivotRatio = 1e-14;
/// Continuation takes at most this many steps from one value to the next (a step is
/// at most 2 deg or 1 % of the length scale: about 555 turns); farther is refused.
constexpr double kMaxContinuationSteps = 1e5;
/// A corrected solution farther than this (scaled) from its prediction is another branch.
constexpr double kBranchTolerance = 0.05;
/// Pivot ratio above which Phi_q is clearly regular (below it, singular values decide).
constexpr double kClearlyRegularPivotRatio = 1e-2;
/// Reciprocal condition of the length-scaled Phi_q below which a position is singular:
/// a Newton solution at a toggle is only sqrt(eps)-accurate, so exact toggles show up
/// around 1e-6; rates there would be 1e5 times their usual size, no result to print.
constexpr double kSingularThreshold = 1e-5;

/// LU with partial pivoting, in place, row-major n x n; pivots[c] is the row swapped
/// into row c. A zero pivot is left in place (the pivot ratio reports it).
inline void lu_factor(double* a, std::size_t* pivots, std::size_t n) {
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t best = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::fabs(a[r * n + c]) > std::fabs(a[best * n + c])) best = r;
    pivots[c] = best;
    if (best != c)
      for (std::size_t j = 0; j < n; ++j) std::swap(a[c * n + j], a[best * n + j]);
    const double pivot = a[c * n + c];
    if (pivot == 0.0) continue;
    for (std::size_t r = c + 1; r < n; ++r) {
      const double factor = a[r * n + c] /= pivot;
      for (std::size_t j = c + 1; j < n; ++j) a[r * n + j] -= factor * a[c * n + j];
    }
  }
}

/// Solves with lu_factor's result and the reciprocals of its pivots (a multiply is
/// quicker than a divide on the dependent chain); x holds the right-hand side.
inline void lu_solve(const double* a, const double* inverse_pivots, const std::size_t* pivots, double* x,
                     std::size_t n) {
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

/// min/max |pivot| of an lu_factor result; 0 when not finite. The column-scaled Phi_q's
/// rows are lengths; a 1 x 1 one (one closure, one unknown) has no other pivot to be
/// compared with, so its pivot is compared with `length_scale` (at most 1): it still
/// falls to 0 at a limit position.
inline double pivot_ratio(const double* a, std::size_t n, double length_scale) {
  double smallest = INFINITY, largest = n == 1 ? length_scale : 0;
  for (std::size_t c = 0; c < n; ++c) {
    const double pivot = std::fabs(a[c * n + c]);
    smallest = pivot < smallest ? pivot : smallest;
    largest = pivot > largest ? pivot : largest;
  }
  const double ratio = smallest / largest;
  return std::isfinite(ratio) ? ratio : 0.0;
}

/// The sign of the determinant of an lu_factor result: +1 or -1, 0 where a pivot is 0 or
/// not finite. Along one branch of the motion it changes only where Phi_q is singular (a
/// toggle, where two assemblies meet, or a change point), so it certifies a step: a step
/// whose two ends have other signs has passed such a point, or jumped a gap.
inline int lu_determinant_sign(const double* a, const std::size_t* pivots, std::size_t n) {
  int sign = 1;
  for (std::size_t c = 0; c < n; ++c) {
    const double pivot = a[c * n + c];
    if (!(std::fabs(pivot) > 0.0) || !std::isfinite(pivot)) return 0;
    if (pivot < 0) sign = -sign;
    if (pivots[c] != c) sign = -sign;
  }
  return sign;
}

/// How far a corrected position may lie from its prediction, beside the step predicted,
/// for the step to have stayed on its branch: a step over a gap lands on a position the
/// prediction did not point to.
constexpr double kStepCorrection = 0.25;
/// The least step counted (scaled), per largest continuation step of the input: where the
/// position barely moves (a dwell) the correction is compared with this.
constexpr double kLeastStep = 0.02;
/// Where det Phi_q's sign changes within a step, the step is bisected in the input down to
/// this fraction of the largest continuation step: a value in between that does not close
/// is a gap stepped over (two toggles, however close); else the sign changes at one input,
/// a change point (two branches crossing) if the position does not jump there.
constexpr double kCrossingWidth = 1e-10;
/// A value bisected there closes where max |Phi| <= this times the length scale (Newton's
/// own tolerance with room for rounding): the least miss inside a gap of 1e-6 turn is
/// about 1e-12 of the lengths.
constexpr double kCrossingResidual = 1e-13;
/// The largest scaled jump of the position across that width at a change point, per
/// largest continuation step of the input the width spans: a branch through a change
/// point moves in proportion to the input; two assemblies beside a toggle g away are
/// sqrt(g * width) apart, far more.
constexpr double kCrossingJump = 1.0;
/// A value with no solved value before it is carried from the guesses' own input value in
/// steps of the largest continuation step, at most this many; farther (a time far on), it
/// is solved from the guesses as it stands.
constexpr double kMostEntrySteps = 2000;
/// Guesses that do not close at their own input value (a copy with other lengths), or close
/// on a singular position there, stand for the nearest value, in largest continuation
/// steps up to this many each way, at which they close on a regular one.
constexpr int kHomeSearchSteps = 90;

/// Sweeps of one-sided Jacobi before it gives up (it converges in a handful).
constexpr int kJacobiSweeps = 60;
/// Two columns count as orthogonal when |cosine of their angle| is at most this.
constexpr double kJacobiTolerance = 1e-15;
/// Machine epsilon of double, 2^-52.
constexpr double kEpsilon = 2.220446049250313e-16;

/// One-sided Jacobi (Hestenes): rotates the columns of a (row-major n x n, in
/// place) pairwise until they are orthogonal; their lengths are then the singular
/// values of the original a. With v (row-major n x n), also accumulates the
/// rotations: original a times v = final a.
inline void jacobi_orthogonalise(double* a, double* v, std::size_t n) {
  if (v)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) v[i * n + j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < kJacobiSweeps; ++sweep) {
    bool rotated = false;
    for (std::size_t p = 0; p + 1 < n; ++p) {
      for (std::size_t q = p + 1; q < n; ++q) {
        double alpha = 0, beta = 0, gamma = 0;
        for (std::size_t i = 0; i < n; ++i) {
          alpha += a[i * n + p] * a[i * n + p];
          beta += a[i * n + q] * a[i * n + q];
          gamma += a[i * n + p] * a[i * n + q];
        }
        // Orthogonal to rounding (or a zero column): nothing to rotate.
        if (!(std::fabs(gamma) > kJacobiTolerance * std::sqrt(alpha) * std::sqrt(beta))) continue;
        rotated = true;
        const double zeta = (beta - alpha) / (2 * gamma);
        const double t = (zeta >= 0 ? 1.0 : -1.0) / (std::fabs(zeta) + std::hypot(1.0, zeta));
        const double c = 1 / std::sqrt(1 + t * t), s = c * t;
        for (std::size_t i = 0; i < n; ++i) {
          const double ap = a[i * n + p], aq = a[i * n + q];
          a[i * n + p] = c * ap - s * aq;
          a[i * n + q] = s * ap + c * aq;
        }
        if (v)
          for (std::size_t i = 0; i < n; ++i) {
            const double vp = v[i * n + p], vq = v[i * n + q];
            v[i * n + p] = c * vp - s * vq;
            v[i * n + q] = s * vp + c * vq;
          }
      }
    }
    if (!rotated) break;
  }
}

/// Length of column j of a row-major n x n matrix.
inline double column_length(const double* a, std::size_t j, std::size_t n) {
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += a[i * n + j] * a[i * n + j];
  return std::sqrt(sum);
}

/// Smallest over largest singular value of a (row-major n x n; overwritten);
/// 0 when not finite.
inline double singular_value_ratio(double* a, std::size_t n) {
  jacobi_orthogonalise(a, nullptr, n);
  double smallest = INFINITY, largest = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double length = column_length(a, j, n);
    smallest = length < smallest ? length : smallest;
    largest = length > largest ? length : largest;
  }
  const double ratio = smallest / largest;
  return std::isfinite(ratio) ? ratio : 0.0;
}

/// The reciprocal condition that decides singular positions (compared with
/// kSingularThreshold), of a matrix (the column-scaled Phi_q) from its lu_factor
/// result `lu`: the pivot ratio where that says the matrix is clearly regular
/// (>= kClearlyRegularPivotRatio), else the ratio of its singular values; 0 when
/// not finite. `matrix()` gives a row-major copy of the factorised matrix, which is
/// overwritten; it is called only when the singular values are needed (near a
/// toggle), so a caller may build the copy only then. A 1 x 1 matrix: its pivot
/// against the length scale (pivot_ratio).
template <class MatrixCopy>
inline double reciprocal_condition(const double* lu, std::size_t n, double length_scale, MatrixCopy&& matrix) {
  const double ratio = pivot_ratio(lu, n, length_scale);
  if (ratio == 0.0) return 0.0;
  if (ratio >= kClearlyRegularPivotRatio || n == 1) return ratio;
  return singular_value_ratio(matrix(), n);
}

/// The same with the copy at hand (row-major n x n; overwritten when read).
inline double reciprocal_condition(const double* lu, double* matrix, std::size_t n, double length_scale) {
  return reciprocal_condition(lu, n, length_scale, [matrix] { return matrix; });
}

/// Minimum-norm least-squares solution of a x = b (a row-major n x n, overwritten;
/// v: n x n scratch), from the singular values: those at or below n * epsilon times
/// the largest count as zero. The generated header's Newton step where the pivot
/// ratio is at or below kLeastSquaresPivotRatio, in Workspace::solve_position and in
/// the generated header alike (tested against Eigen's complete orthogonal
/// decomposition in tests/codegen_test.cpp).
inline void least_squares_solve(double* a, double* v, const double* b, double* x, std::size_t n) {
  jacobi_orthogonalise(a, v, n);
  // a v = u sigma: column j of a is u_j sigma_j, so x = sum_j v_j (a_j . b) / sigma_j^2.
  double largest = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double length = column_length(a, j, n);
    largest = length > largest ? length : largest;
  }
  const double cutoff = static_cast<double>(n) * kEpsilon * largest;
  for (std::size_t i = 0; i < n; ++i) x[i] = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double sigma = column_length(a, j, n);
    if (!(sigma > cutoff)) continue;
    double projection = 0;
    for (std::size_t i = 0; i < n; ++i) projection += a[i * n + j] * b[i];
    const double coefficient = projection / (sigma * sigma);
    for (std::size_t i = 0; i < n; ++i) x[i] += v[i * n + j] * coefficient;
  }
}

// ---- Newton-Raphson on the position system ------------------------------------------
// The position system of n unknowns as the tape's position stage writes it (TapeLayout):
// Phi (n values), then Phi_q column by column (n x n), then Phi_theta (n).

/// max |v[i]| of n values; NaN where one is NaN: Newton's residual norm.
inline double max_magnitude(const double* v, std::size_t n) {
  double norm = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double magnitude = std::fabs(v[i]);
    if (std::isnan(magnitude)) return magnitude;
    norm = magnitude > norm ? magnitude : norm;
  }
  return norm;
}

inline bool all_finite(const double* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

/// Phi_q of a position system, row-major into a, with column j scaled by column_scale[j]
/// (the unknowns' own scales: what is factorised and tested for singularity).
inline void scaled_phi_q(const double* system, const double* column_scale, double* a, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) a[i * n + j] = system[n + j * n + i] * column_scale[j];
}

/// The LU of a position system's scaled Phi_q (n x n, row-major), its pivots and the
/// reciprocals of its diagonal: one factorisation, for any number of right-hand sides.
struct Factorisation {
  double* lu;
  std::size_t* pivots;
  double* inverse_pivots;
};

inline void factorise(const double* system, const double* column_scale, const Factorisation& f, std::size_t n) {
  scaled_phi_q(system, column_scale, f.lu, n);
  lu_factor(f.lu, f.pivots, n);
  for (std::size_t c = 0; c < n; ++c) f.inverse_pivots[c] = 1.0 / f.lu[c * n + c];
}

/// Solves Phi_q x = b with the factorisation (x holds b), undoing the column scaling.
inline void solve(const Factorisation& f, const double* column_scale, double* x, std::size_t n) {
  lu_solve(f.lu, f.inverse_pivots, f.pivots, x, n);
  for (std::size_t i = 0; i < n; ++i) x[i] *= column_scale[i];
}

/// The Newton step -Phi_q^-1 Phi at a position system: by the LU of the scaled Phi_q, or,
/// where its pivots say Phi_q is (nearly) singular, by least squares on the unscaled Phi_q
/// (the step stays defined there). `a` and `v` are n x n scratch.
inline void newton_step(const double* system, const double* column_scale, double length_scale, const Factorisation& f,
                        double* a, double* v, double* b, double* step, std::size_t n) {
  factorise(system, column_scale, f, n);
  if (pivot_ratio(f.lu, n, length_scale) > kLeastSquaresPivotRatio) {
    for (std::size_t i = 0; i < n; ++i) step[i] = -system[i];
    solve(f, column_scale, step, n);
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      b[i] = -system[i];
      for (std::size_t j = 0; j < n; ++j) a[i * n + j] = system[n + j * n + i];
    }
    least_squares_solve(a, v, b, step, n);
  }
}

/// Damped Newton-Raphson from q (n values, updated in place), the step halved until max
/// |Phi| decreases; true when max |Phi| reaches kNewtonTolerance times the length scale, or
/// stalls below kRoundingTolerance times it (converged to rounding all the same). `system`
/// is what evaluates: on entry it holds the position system at q; system.step(step) writes
/// the Newton step there (newton_step); system.try_at(trial) evaluates at a trial position
/// and returns its max |Phi|; system.accept() makes that evaluation q's (the trial is
/// taken). `step` and `trial` are n values of scratch.
template <class System>
inline bool newton(System& system, double* q, double* step, double* trial, std::size_t n, double length_scale) {
  const double tolerance = kNewtonTolerance * length_scale;
  double norm = system.residual();
  bool converged = false;
  for (int iteration = 0; iteration < kNewtonIterations && std::isfinite(norm); ++iteration) {
    if (norm <= tolerance) {
      converged = true;
      break;
    }
    system.step(step);
    if (!all_finite(step, n)) break;
    double lambda = 1.0;
    bool improved = false;
    for (int halving = 0; halving < kStepHalvings; ++halving, lambda *= 0.5) {
      for (std::size_t i = 0; i < n; ++i) trial[i] = q[i] + lambda * step[i];
      const double trial_norm = system.try_at(trial);
      if (std::isfinite(trial_norm) && trial_norm < norm) {
        improved = true;
        norm = trial_norm;
        for (std::size_t i = 0; i < n; ++i) q[i] = trial[i];
        system.accept();
        break;
      }
    }
    if (!improved) break;
  }
  if (!converged && norm <= kRoundingTolerance * length_scale) converged = true;
  return converged && all_finite(q, n);
}

/// Second-order prediction of a coordinate at input + h from its value, rate and
/// second rate at input (the input moving at `rate` with `second_rate`): the
/// rates give dq/dtheta and d2q/dtheta2.
inline double predict_second_order(double value, double value_rate, double value_second_rate, double rate,
                                   double second_rate, double h) {
  const double slope = value_rate / rate;
  const double curvature = (value_second_rate - slope * second_rate) / (rate * rate);
  return value + h * (slope + 0.5 * h * curvature);
}

}  // namespace kinema::solver
