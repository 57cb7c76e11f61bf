// Solving blocks of kLanes consecutive input values at once, everything
// lane-parallel: the tape, the LU of Phi_q (the scalar solver's pivoting rule,
// done by selects), Newton, rates, points. Used by solve_motion() for sweeps.
#pragma once

#include <vector>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/lane_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/simd_math.hpp"

namespace kinema {

class BatchWorkspace : LaneSystem {
 public:
  using LaneSystem::kLanes;
  explicit BatchWorkspace(const Kinematics& kinematics);

  /// The kinematics' parameter values again (after Kinematics::set_parameter_values).
  void reload_parameters();

  /// Solves rows [first, first + kLanes) of `table` (inputs already stored), predicted
  /// from the solved rows [history_begin, first) (at least row first - 1, status ok).
  /// Writes the rows only when every value converged on its predicted branch,
  /// clearly regular, det Phi_q of the sign `sign` of row first - 1 (no toggle between
  /// them); returns false otherwise (the caller solves them one by one).
  bool solve(MotionTable& table, std::size_t first, std::size_t history_begin, int sign);

 private:
  std::vector<double> predicted_;

  /// solve(), compiled for AVX2 and for baseline x86-64 (the clones and their
  /// resolver stay in batch_workspace.cpp).
  KINEMA_LANE_LOOPS bool solve_lanes(MotionTable& table, std::size_t first, std::size_t history_begin, int sign);
  KINEMA_LANE_LOOPS bool predict(const MotionTable& table, std::size_t first, std::size_t history_begin);
  /// Whether every lane's pivots are clearly regular (after factorise()).
  bool clearly_regular() const;
};

}  // namespace kinema
