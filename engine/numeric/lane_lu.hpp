// The small dense LU of kLanes matrices at once, lane-parallel (lane l of element (i, j)
// at (i n + j) kLanes + l): what the batch workspaces (consecutive values of one design,
// or one value of kLanes designs) factorise Phi_q with. Same operations, in the same
// order, as solver::lu_factor; the pivot row of each lane is chosen and swapped in by
// selects, so every loop is a fixed-length loop over lanes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "engine/numeric/simd_math.hpp"
#include "engine/numeric/tape.hpp"

namespace kinema {

constexpr std::size_t kLuLanes = CompiledExpressions::kBatchLanes;

// Inlined into each caller, so that each of a caller's KINEMA_LANE_LOOPS clones gets its
// own (a clone's symbols are local to its file: no call across files reaches them).
#if defined(__GNUC__)
#define KINEMA_INLINE_LANES inline __attribute__((always_inline))
#else
#define KINEMA_INLINE_LANES inline
#endif

/// LU with partial pivoting of each lane's n x n matrix in `a`, in place; pivots[c kLanes + l]
/// is the row lane l swapped into row c (as a double).
KINEMA_INLINE_LANES void lu_factor_lanes(double* a, double* pivots, std::size_t n) {
  auto at = [&](std::size_t i, std::size_t j) { return a + (i * n + j) * kLuLanes; };
  for (std::size_t c = 0; c < n; ++c) {
    double best[kLuLanes], best_magnitude[kLuLanes];
    const double* diagonal = at(c, c);
    for (std::size_t l = 0; l < kLuLanes; ++l) {
      best[l] = static_cast<double>(c);
      best_magnitude[l] = std::fabs(diagonal[l]);
    }
    for (std::size_t r = c + 1; r < n; ++r) {
      const double* candidate = at(r, c);
      for (std::size_t l = 0; l < kLuLanes; ++l) {
        const double magnitude = std::fabs(candidate[l]);
        const bool larger = magnitude > best_magnitude[l];
        best[l] = larger ? static_cast<double>(r) : best[l];
        best_magnitude[l] = larger ? magnitude : best_magnitude[l];
      }
    }
    std::copy(best, best + kLuLanes, pivots + c * kLuLanes);
    for (std::size_t r = c + 1; r < n; ++r) {
      for (std::size_t j = 0; j < n; ++j) {
        double* __restrict top = at(c, j);
        double* __restrict other = at(r, j);
        for (std::size_t l = 0; l < kLuLanes; ++l) {
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
      for (std::size_t l = 0; l < kLuLanes; ++l) factor[l] /= pivot[l];
      for (std::size_t j = c + 1; j < n; ++j) {
        double* __restrict target = at(r, j);
        const double* __restrict source = at(c, j);
        for (std::size_t l = 0; l < kLuLanes; ++l) target[l] -= factor[l] * source[l];
      }
    }
  }
}

/// Solves with lu_factor_lanes's result; x (n rows of kLanes) holds the right-hand sides.
KINEMA_INLINE_LANES void lu_solve_lanes(const double* a, const double* pivots, double* x, std::size_t n) {
  auto at = [&](std::size_t i, std::size_t j) { return a + (i * n + j) * kLuLanes; };
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t r = c + 1; r < n; ++r) {
      double* __restrict top = x + c * kLuLanes;
      double* __restrict other = x + r * kLuLanes;
      const double* __restrict pivot = pivots + c * kLuLanes;
      for (std::size_t l = 0; l < kLuLanes; ++l) {
        const bool swap = pivot[l] == static_cast<double>(r);
        const double t = top[l];
        top[l] = swap ? other[l] : t;
        other[l] = swap ? t : other[l];
      }
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t r = c + 1; r < n; ++r) {
      double* __restrict target = x + r * kLuLanes;
      const double* __restrict source = x + c * kLuLanes;
      const double* __restrict factor = at(r, c);
      for (std::size_t l = 0; l < kLuLanes; ++l) target[l] -= factor[l] * source[l];
    }
  }
  for (std::size_t c = n; c-- > 0;) {
    double* __restrict value = x + c * kLuLanes;
    const double* __restrict pivot = at(c, c);
    for (std::size_t l = 0; l < kLuLanes; ++l) value[l] /= pivot[l];
    for (std::size_t r = 0; r < c; ++r) {
      double* __restrict target = x + r * kLuLanes;
      const double* __restrict factor = at(r, c);
      for (std::size_t l = 0; l < kLuLanes; ++l) target[l] -= factor[l] * value[l];
    }
  }
}

}  // namespace kinema
