// Solving blocks of kLanes consecutive input values at once, everything
// lane-parallel: the tape, the LU of Phi_q (the scalar solver's pivoting rule,
// done by selects), Newton, rates, points. Used by analyse() for sweeps.
#pragma once

#include <vector>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/simd_math.hpp"

namespace kinema {

class BatchWorkspace {
 public:
  static constexpr std::size_t kLanes = CompiledExpressions::kBatchLanes;
  explicit BatchWorkspace(const Kinematics& kinematics);

  /// The kinematics' parameter values again (after Kinematics::set_parameter_values).
  void reload_parameters();

  /// Solves rows [first, first + kLanes) of `table` (inputs already stored), predicted
  /// from the solved rows [history_begin, first) (at least row first - 1, status ok).
  /// Writes the rows only when every value converged on its predicted branch,
  /// clearly regular; returns false otherwise (the caller solves them one by one).
  bool solve(MotionTable& table, std::size_t first, std::size_t history_begin);

 private:
  const Kinematics& k_;
  const TapeLayout& layout_;
  std::size_t n_;
  std::vector<double> registers_;  ///< Register r of lane l at r * kLanes + l.
  std::vector<double> lu_;         ///< Element (i, j) of lane l at (i n + j) kLanes + l.
  std::vector<double> pivots_;     ///< Row chosen at column c for lane l at c kLanes + l.
  std::vector<double> x_, predicted_;

  /// solve(), compiled for AVX2 and for baseline x86-64 (the clones and their
  /// resolver stay in batch_workspace.cpp).
  KINEMA_LANE_LOOPS bool solve_lanes(MotionTable& table, std::size_t first, std::size_t history_begin);
  double* lanes(std::size_t reg) { return registers_.data() + reg * kLanes; }
  const double* output(std::size_t stage, std::size_t k) {
    return lanes(k_.evaluator().output_register(stage, k));
  }
  KINEMA_LANE_LOOPS bool predict(const MotionTable& table, std::size_t first, std::size_t history_begin);
  /// Column-scaled Phi_q from the registers, factorised; false unless every lane's
  /// pivots are clearly regular.
  KINEMA_LANE_LOOPS bool factorise();
  /// min/max |pivot| of each lane's factorisation.
  KINEMA_LANE_LOOPS void pivot_ratios(double* ratio) const;
  double pivot_ratio_[kLanes];
};

}  // namespace kinema
