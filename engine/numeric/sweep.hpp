// The sweep driver: solves input values in order, each continued from the
// last so that the assembly branch is kept, sweeps in SIMD blocks where the
// motion is regular, long runs on several threads. Failures become rows with
// a status and a structured Failure; nothing is thrown for them.
#pragma once

#include <vector>

#include <kinema/engine/numeric/kinematics.hpp>
#include <kinema/engine/numeric/motion_table.hpp>

namespace kinema {

struct SweepSettings {
  double rate = 0.0;         ///< Input rate (SI) at every value.
  double second_rate = 0.0;  ///< Input second rate (SI).
  /// A long run is split into this many chunks whose starting positions are found by
  /// continuation first, so the branch is the serial run's.
  unsigned threads = 1;
  /// Consecutive values solved kLanes at a time on the batch (SIMD) tape, predicted
  /// from the rows before and checked to stay on their branch (else one by one).
  bool simd = true;
};

MotionTable solve_sweep(const Kinematics& kinematics, const std::vector<double>& inputs, const SweepSettings& settings);

}  // namespace kinema
