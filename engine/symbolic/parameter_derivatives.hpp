// Exact sensitivities: how the solved values change with a parameter, by implicit
// differentiation of the equations the solver solves (the derivation keeps the lengths
// as symbols). With D the total derivative in the parameter p at fixed q, qd, qdd and
// the input (through every formula parameter that follows p, EF = "CE" for p = CE):
//   position:      Phi_q dq/dp   = -D Phi
//   velocity:      Phi_q dqd/dp  = -(V_q dq/dp + D V),                 V = Phi_q qd + Phi_theta thetad
//   acceleration:  Phi_q dqdd/dp = -(A_q dq/dp + A_qd dqd/dp + D A),   A = Phi_q qdd - gamma
//   an observable O(q, qd, qdd, p) (a point's position, velocity, acceleration; a
//   frame's angular velocity and acceleration):
//                  dO/dp = O_q dq/dp + O_qd dqd/dp + O_qdd dqdd/dp + D O
// The products with dq/dp, dqd/dp, dqdd/dp are formed here with symbols that stand for
// them (directional derivatives: no n x n matrix of second derivatives is built), so the
// stages below compile into one tape (engine/numeric/sensitivity) whose stage k reads the
// derivatives solved after stage k - 1.
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/symbolic/derivation.hpp"

namespace kinema {

struct ParameterDerivatives {
  /// The tape's inputs: the model's tape inputs (parameters, theta, thetad, thetadd, q,
  /// qd, qdd; TapeLayout's order), then dq/dp, dqd/dp, dqdd/dp (n each).
  std::vector<GiNaC::ex> inputs;
  static constexpr std::size_t kPositionStage = 0;      ///< D Phi (n): Phi_q dq/dp = -this.
  static constexpr std::size_t kVelocityStage = 1;      ///< V_q dq/dp + D V (n).
  static constexpr std::size_t kAccelerationStage = 2;  ///< A_q dq/dp + A_qd dqd/dp + D A (n).
  /// dO/dp of each output of the model's point stage, in its order (TapeLayout: each
  /// point's position, velocity, acceleration; each frame's angular velocity, angular acceleration).
  static constexpr std::size_t kObservableStage = 3;
  std::vector<std::vector<GiNaC::ex>> stages;
};

/// The derivatives of the solved values in system.parameters[parameter], that parameter
/// taken as given (its own formula, if any, not followed) and every later formula
/// parameter following it by the chain rule.
ParameterDerivatives parameter_derivatives(const ConstraintSystem& system, const Derivation& derivation,
                                           std::size_t parameter);

}  // namespace kinema
