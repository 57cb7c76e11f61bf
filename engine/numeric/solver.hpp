// The numeric rules of kinema, written once: the solver's constants, the LU
// factorisation with partial pivoting and its solve, and the second-order
// predictor. The scalar workspace uses them as they are; the lane-parallel
// workspace follows the same pivoting rule in lane form; the generated C++
// header carries the same constants, so both call the same positions singular.
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

/// min/max |pivot| of an lu_factor result; 0 when not finite.
inline double pivot_ratio(const double* a, std::size_t n) {
  double smallest = INFINITY, largest = 0;
  for (std::size_t c = 0; c < n; ++c) {
    const double pivot = std::fabs(a[c * n + c]);
    smallest = pivot < smallest ? pivot : smallest;
    largest = pivot > largest ? pivot : largest;
  }
  const double ratio = smallest / largest;
  return std::isfinite(ratio) ? ratio : 0.0;
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
