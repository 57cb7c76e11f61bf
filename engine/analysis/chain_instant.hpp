// A spatial chain worked out at the instant as seed 000 does it — each frame's angular
// velocity as the sum of its relative turnings and its angular acceleration, each point's
// velocity and acceleration term by term — as formulas (the joint variables put in) and
// numbers, in the observer's basis or any frame's. The text and LaTeX printers show the
// same ChainAtInstant.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <string>
#include <vector>

#include "engine/constraint_system.hpp"

namespace kinema {

/// What a vector of the worked chain is.
enum class ChainTerm {
  angular_velocity, angular_acceleration,
  rate_change, carried,  ///< of a term of w: d(rate)/dt axis, w_frame x (rate axis)
  position,  ///< r, from the point's frame's origin
  frame_velocity, transport, relative_velocity, velocity,  ///< v = v_F + w x r + v_rel
  frame_acceleration, tangential, centripetal, coriolis, relative_acceleration, acceleration,
};

struct ChainVector {
  ChainTerm term;
  std::vector<GiNaC::ex> formula;  ///< 3 components in the basis, the instant's joint values put in.
  std::array<double, 3> value{};   ///< SI.
};

struct ChainFrameAtInstant {
  std::string name, parent;
  std::vector<AngularVelocityTerm> terms;  ///< As summed into w (observer basis).
  ChainVector angular_velocity, angular_acceleration;
  /// The parts of alpha, per term of w: its rate_change and carried parts (in the basis).
  std::vector<std::pair<ChainVector, ChainVector>> acceleration_parts;
};

struct ChainPointAtInstant {
  std::string name, frame;
  std::vector<ChainVector> velocity;      ///< position, frame_velocity, transport, relative_velocity, velocity
  std::vector<ChainVector> acceleration;  ///< frame_acceleration ... relative_acceleration, acceleration
};

struct ChainAtInstant {
  std::string observer;
  std::string basis;  ///< The frame whose axes the components are along (the observer by default).
  /// Each joint variable at the instant: its coordinate and SI value (the input first, if
  /// a variable is the input).
  std::vector<std::pair<Coordinate, double>> values;
  std::vector<ChainFrameAtInstant> frames;
  std::vector<ChainPointAtInstant> points;
};

/// A spatial chain whose joint variables are all driven (no closures): it is worked out
/// at the instant; a closed chain is printed as its loops.
bool is_driven_chain(const ConstraintSystem& system);

/// A rate written with a minus sign (-omega4): a sum of terms shows it as "- omega4".
bool is_negative_term(const GiNaC::ex& e);

/// The observer of a spatial chain (the parent that is not a frame).
std::string chain_observer(const ConstraintSystem& system);

/// InputError (naming the frames) unless `basis` is empty, the observer or a frame of the
/// chain: what chain_at_instant checks first, without working the chain out.
void check_chain_basis(const ConstraintSystem& system, const std::string& basis);

/// Works a driven chain out at the instant, in the basis of frame `basis` (empty: the
/// observer's). InputError for a basis that is not a frame of the chain (the names in
/// the message).
ChainAtInstant chain_at_instant(const ConstraintSystem& system, const std::string& basis = "");

}  // namespace kinema
