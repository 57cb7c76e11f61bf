// The spatial-chain front end: a chain of rotating frames (seed 000's robot arm) as
// symbolic kinematics, written the way the seed works it out. Conventions, once:
//  - vectors are given in the observer frame's basis (E0, the Ê of seed 000) unless
//    named otherwise; R_F's columns are frame F's axes in that basis;
//  - w_F is F's angular velocity relative to the observer, the sum of each frame's
//    turning relative to its parent along the chain (w_F = w_parent + d(angle)/dt axis);
//  - a point P fixed (or moving) in frame F at r_local: p_P = p_F + R_F r_local,
//    v_P = v_F + w_F x r + v_rel, a_P = a_F + alpha_F x r + w_F x (w_F x r) + 2 w_F x v_rel
//    + a_rel, with r = R_F r_local, v_rel = R_F d(r_local)/dt, a_rel = R_F d2(r_local)/dt2.
// Joint variables are symbols with rate and second-rate symbols (theta1, omega1, alpha1);
// time derivatives are total derivatives along them (the second rates constant).
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/differentiate.hpp"
#include "readers/mechanism.hpp"

namespace kinema {

using Vector3 = std::array<GiNaC::ex, 3>;

struct ChainFrameMotion {
  std::string name, parent;
  GiNaC::matrix rotation{3, 3};  ///< Columns: the frame's axes in the observer basis.
  Vector3 origin;                ///< Position of the frame's origin.
  /// The relative angular velocities summed into w: each turn of each frame along the chain
  /// from the observer ("omega5 y_E2").
  std::vector<AngularVelocityTerm> angular_velocity_terms;
  Vector3 angular_velocity, angular_acceleration;
};

struct ChainPointMotion {
  std::string name, frame;
  Vector3 position, velocity, acceleration;
  /// v = frame_velocity + transport + relative;
  Vector3 frame_velocity, transport, relative_velocity;
  /// a = frame_acceleration + tangential (alpha x r) + centripetal (w x (w x r)) + coriolis + relative.
  Vector3 frame_acceleration, tangential, centripetal, coriolis, relative_acceleration;
};

struct SpatialKinematics {
  std::vector<SystemParameter> parameters;
  std::vector<Coordinate> variables;  ///< Joint variables with rate and second-rate symbols.
  std::vector<bool> unknown;          ///< Of each variable: found by the closures (its value a guess).
  std::vector<double> values, rates, second_rates;  ///< Of each variable at t = 0 (SI).
  std::string observer;
  /// Time, for formulas written in it (a point moving in its frame as 0.1*sin(2*t)): "t"
  /// unless the file names a parameter or variable so.
  GiNaC::realsymbol time{"t", "t"};
  std::vector<ChainFrameMotion> frames;  ///< In file order, parents first.
  std::vector<ChainPointMotion> points;
  /// Closed loops: each closure's residual (|p_from - p_to|^2 - length^2) / (2 length) (= 0).
  std::vector<std::pair<std::string, GiNaC::ex>> closures;

  /// Every symbol (parameters, variables, rates, second rates, time) at t = 0.
  GiNaC::exmap instant() const;
  /// What d/dt goes through: the variables (theta -> omega -> alpha -> 0) and time itself.
  std::vector<SymbolMotion> motions() const;
};

/// Builds the chain's kinematics; InputError with file:line for a parent that is not a
/// frame or a cycle of parents, an axis that is not one of x, y, z (or -x, ...), a point in
/// a frame that does not exist, a formula with an unknown symbol.
SpatialKinematics build_spatial_chain(const Mechanism& mechanism);

/// The chain as a constraint system the engine solves and prints: the input is time t
/// (rate 1), each joint variable an unknown whose "motion" equation is
/// theta - (theta_0 + omega_0 t + alpha_0 t^2 / 2) = 0 (its value, rate and second rate
/// at t = 0 as the parameters <name>_0, <rate>_0, <second rate>_0), and the points in 3-D.
/// The values are t = 0 (the instant).
ConstraintSystem build_spatial_system(const Mechanism& mechanism);

}  // namespace kinema
