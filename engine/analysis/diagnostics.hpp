// Failures made into sentences for people: what happened, at which input
// value (in output units), in which loop, and what to do.
#pragma once

#include <string>

#include "engine/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

/// "theta2 = 30 deg" / "r = 12.5 mm" in the output units.
std::string describe_input(const ConstraintSystem& system, double input);

/// The sentence for a row's failure at `input` ("" when there is nothing to say).
std::string describe_failure(const ConstraintSystem& system, double input, const Failure& failure);

/// The same for a state.
inline std::string describe_failure(const ConstraintSystem& system, const MotionState& state) {
  return describe_failure(system, state.input, state.failure);
}

}  // namespace kinema
