// Instant centres of a planar mechanism at one solved position, found as a course does:
// the primary ones at the joints (a pin's centre; a slider's at infinity, across its line),
// every other by the Aronhold-Kennedy theorem (the three centres of three bodies lie on one
// line), on two such lines. Where each stands is read from the model's drawing stage (the
// formulas a page's sliders run for other dimensions); the construction from the bodies'
// poses is kept to test them against. The angular-velocity ratios they give are set beside
// the analytic ones.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "engine/analysis/geometry.hpp"
#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

struct InstantCentre {
  std::size_t a = 0, b = 0;  ///< Bodies (0 = ground), a < b.
  bool at_infinity = false;
  std::complex<double> at;   ///< SI position, or the unit direction it lies in when at infinity.
  /// "pin B", "slider B2", or the two Kennedy lines it is on: "I02 I23, I04 I34".
  std::string found_by;
  /// Found by Kennedy: the bodies of the two other centres on each of its two lines.
  std::vector<std::pair<std::size_t, std::size_t>> kennedy;
  /// At infinity: a point of a line it lies on, where a drawing starts its arrow (a
  /// slider's joint, or a centre on the Kennedy line that fixed its direction).
  std::optional<std::complex<double>> seen_from;
  /// A vector-loop file's centre at infinity: the bodies whose points (the tape's) it is
  /// seen from, their mean (one body, or both).
  std::vector<std::size_t> seen_bodies;
  /// At a pin joining the two bodies: their centre whatever their rates (where they turn
  /// alike, or one is at rest at a limit position, the velocities give none or a poor one).
  bool pin = false;
};

/// omega_j / omega_driver from the centres (I_0d, I_dj, I_0j on one line:
/// omega_j / omega_d = (I_dj - I_0d) / (I_dj - I_0j)) and from the solution.
struct VelocityRatio {
  std::size_t body = 0;
  double from_centres = 0, analytic = 0;
};

struct InstantCentres {
  std::vector<std::string> bodies;  ///< Names: ground first ("0" or "ground"), then the links.
  std::vector<double> angular_velocities;  ///< rad/s, per body.
  /// The rate each body turns with (omega3), 0 for ground and for slider blocks.
  std::vector<GiNaC::ex> rates;
  /// Every pair that was found. A vector-loop file's centres that are not at a joint (a
  /// named point or the origin) carry the two Kennedy lines through them that cross most
  /// squarely, as the joints-and-links ones do.
  std::vector<InstantCentre> centres;
  std::vector<std::pair<std::size_t, std::size_t>> not_found;  ///< Pairs no two Kennedy lines fix.
  /// Of those, the pairs at rest relative to each other for the instant (the same angular
  /// velocity, no relative velocity: every point is their centre).
  std::vector<std::pair<std::size_t, std::size_t>> moving_as_one;
  std::size_t driver = 0;
  std::vector<VelocityRatio> ratios;
  /// The centre of bodies a and b, if found.
  const InstantCentre* find(std::size_t a, std::size_t b) const;
  /// Per body, the body of the model's drawing stage its angular velocity, point and
  /// centres are read from (TapeLayout::centre_bodies, ground 0); empty where the centres
  /// were constructed instead.
  std::vector<std::size_t> tape_bodies;
};

/// The difference of two bodies' angular velocities, relative to the fastest-turning body's,
/// below which they turn alike: a link that only translates has a rounding omega (1e-17
/// rad/s, the parallelogram's coupler), which no other body's is to be measured against.
constexpr double kCentreParallelTolerance = 1e-12;

/// The instant centres at a state that is ok of the mechanism whose model `geometry` reads:
/// a joints-and-links mechanism placed in closed form, or a vector-loop file with a named
/// point on a link (its links and their angular velocities as the model derived and
/// compiled them); nullopt for other systems (spatial chains) and states.
/// The centres are read from the model's drawing stage (centre_formulas.hpp): each N / (i D),
/// or at infinity across N where |D| <= kCentreParallelTolerance max_k |omega_k|, none
/// where N is 0 too. A joints-and-links file's are found by its pins and sliders and
/// the Kennedy lines its construction would choose (constructed only where the tape holds
/// none of its bodies' centres).
std::optional<InstantCentres> instant_centres(const MechanismGeometry& geometry, const MotionState& state);

/// The centres constructed, not read from the tape: what instant_centres' must equal
/// (tested). A vector-loop file's from the numbers its bodies were found by (a point on
/// each and that point's velocity: v_a(I) = v_b(I) with v(P) = v_A + i omega (P - A)); a
/// joints-and-links file's as a course does, from the bodies' poses (pins, sliders, Kennedy).
std::optional<InstantCentres> constructed_instant_centres(const MechanismGeometry& geometry, const MotionState& state);

}  // namespace kinema
