// Symbolic derivation, done once per constraint system: the equations
// Phi(q, theta) = 0 differentiated in time by the chain rule into
//   velocity:      Phi_q * qd  = -Phi_theta * thetad
//   acceleration:  Phi_q * qdd = gamma(q, qd, theta, thetad, thetadd)
// the rates solved block by block in solving order (as a textbook does), the
// points' velocities and accelerations, and the relative-motion terms
// (relative and Coriolis accelerations) that worked solutions name.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/symbolic/link_vectors.hpp"
#include "engine/symbolic/solving_order.hpp"

namespace kinema {

/// A link vector length*exp(I*angle) whose length and angle both change: a point
/// sliding along a turning link. Its acceleration has the textbook's named parts.
struct SlidingLinkTerms {
  std::size_t group = 0;  ///< The loop it belongs to.
  GiNaC::ex length, angle;
  GiNaC::ex relative;    ///< d2(length)/dt2, along the link.
  GiNaC::ex coriolis;    ///< d(length)/dt * d(angle)/dt (the Coriolis term is twice this, across the link).
  GiNaC::ex tangential;  ///< length * d2(angle)/dt2, across the link.
  GiNaC::ex normal;      ///< length * (d(angle)/dt)^2, towards the link's start.
};

/// Velocity and acceleration of a point, one expression per component.
struct PointMotionFormulas {
  std::vector<GiNaC::ex> velocity, acceleration;
  std::vector<GiNaC::ex> acceleration_combined;  ///< The same, products of sin/cos combined (for reading).
};

/// What a derivation is made for: the evaluator needs the Jacobians, gamma and the
/// points' rates; the printers of formulas also need the rates solved in closed form and
/// the combined forms, which take most of the time (`kinema eval` does without them).
enum class DerivationScope { full, evaluation };

struct Derivation {
  /// evaluation: solved_rates, solved_second_rates, acceleration_rhs_combined,
  /// points[].acceleration_combined and sliding_links are left empty.
  DerivationScope scope = DerivationScope::full;

  GiNaC::matrix jacobian;        ///< Phi_q (n x n), rows as ConstraintSystem::equations.
  GiNaC::matrix input_jacobian;  ///< Phi_theta (n x 1).
  std::vector<GiNaC::ex> velocity_equations;      ///< dPhi/dt (= 0), linear in qd.
  std::vector<GiNaC::ex> acceleration_equations;  ///< d2Phi/dt2 (= 0), linear in qdd.
  std::vector<GiNaC::ex> acceleration_rhs;        ///< gamma: Phi_q qdd = gamma.
  std::vector<GiNaC::ex> acceleration_rhs_combined;  ///< gamma with products of sin/cos combined (for reading).

  std::vector<SolvingBlock> blocks;  ///< Solving order.
  /// qd_i solved, in terms of q, theta, thetad and the rates of earlier blocks.
  std::vector<GiNaC::ex> solved_rates;
  /// qdd_i solved, in terms of q, qd, theta, thetad, thetadd and earlier blocks' second rates.
  std::vector<GiNaC::ex> solved_second_rates;

  std::vector<PointMotionFormulas> points;  ///< As ConstraintSystem::points.
  std::vector<SlidingLinkTerms> sliding_links;
  /// Every link vector of a planar system with its motion (either scope: the drawings and
  /// polygons of any view read them, evaluated by the compiled model).
  PlanarLinkVectors link_vectors;
};

/// d/dt by the chain rule through q, qd, theta, thetad.
GiNaC::ex time_derivative(const ConstraintSystem& system, const GiNaC::ex& e);

/// Builds the derivation of a system. Either scope checks the same: a block whose
/// unknowns are not independent, more than kMaxUnknowns unknowns, and a formula whose
/// velocity or acceleration would be too large to build are refused (InputError).
Derivation derive(const ConstraintSystem& system, DerivationScope scope = DerivationScope::full);

/// The derivation a printer of formulas reads; throws std::logic_error for one made for
/// evaluation only (a programming error: load the model with DerivationScope::full).
const Derivation& full_derivation(const Derivation& derivation);

}  // namespace kinema
