// Symbolic derivation, done once per mechanism: the loop-closure equations
// Phi(q, theta) = 0 differentiated in time by the chain rule into
//   velocity:      Phi_q * qd  = -Phi_theta * thetad
//   acceleration:  Phi_q * qdd = gamma(q, qd, theta, thetad, thetadd)
// and the rates solved block by block (loops that can be closed one after
// the other are solved in that order, as a textbook does).
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include <kinema/loops/planar_loops.hpp>
#include <kinema/loops/mechanism.hpp>

namespace kinema {

/// Unknowns solved together from a group of loops, in solving order.
struct RateBlock {
  std::vector<std::size_t> loops;      ///< Loop indices.
  std::vector<std::size_t> equations;  ///< Rows of Phi.
  std::vector<std::size_t> unknowns;   ///< Columns of Phi_q.
};

struct Derivation {
  LoopClosure closure;
  std::vector<std::string> unknown_names;  ///< As in the file.

  GiNaC::realsymbol input_rate;         ///< thetad (e.g. omega2).
  GiNaC::realsymbol input_second_rate;  ///< thetadd (e.g. alpha2).
  std::vector<GiNaC::realsymbol> rates;         ///< qd, one per unknown.
  std::vector<GiNaC::realsymbol> second_rates;  ///< qdd.

  GiNaC::matrix jacobian;        ///< Phi_q (n x n).
  GiNaC::matrix input_jacobian;  ///< Phi_theta (n x 1).
  std::vector<GiNaC::ex> velocity_equations;      ///< dPhi/dt (= 0), linear in qd.
  std::vector<GiNaC::ex> acceleration_equations;  ///< d2Phi/dt2 (= 0), linear in qdd.
  std::vector<GiNaC::ex> acceleration_rhs;        ///< gamma: Phi_q qdd = gamma.

  std::vector<RateBlock> blocks;
  /// qd_i solved, in terms of q, theta, thetad and the rates of earlier blocks.
  std::vector<GiNaC::ex> solved_rates;
  /// qdd_i solved, in terms of q, qd, theta, thetad, thetadd and earlier blocks' second rates.
  std::vector<GiNaC::ex> solved_second_rates;

  std::vector<GiNaC::ex> point_velocity_x, point_velocity_y;
  std::vector<GiNaC::ex> point_acceleration_x, point_acceleration_y;

  /// d/dt by the chain rule through q, qd, theta, thetad.
  GiNaC::ex time_derivative(const GiNaC::ex& e) const;
};

/// Builds the derivation; mechanism supplies the names of rates.
Derivation derive(const Mechanism& mechanism, const LoopClosure& closure);

/// Conventional name of a coordinate's rate: theta3 -> omega3, r1 -> r1_dot.
std::string default_rate_name(const std::string& coordinate, int order);

}  // namespace kinema
