// The hand-off between what the user wrote and the engine: every front end
// (vector loops, joints and links, spatial chains) produces a ConstraintSystem, and
// derivation, compilation, analyses and printers read only this. Equations carry labels (loop ABCD, component x), so nothing
// downstream counts rows; points have as many components as their space.
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/source_location.hpp"
#include "engine/base/units.hpp"
#include "engine/constraints/solving_plan.hpp"

namespace kinema {

/// A named constant of the system, with its SI value.
struct SystemParameter {
  GiNaC::realsymbol symbol;     ///< Carries its LaTeX name.
  double value = 0.0;           ///< SI.
  Dimension dimension = Dimension::number;  ///< length, angle, or number (unknown unit).
  std::string text;             ///< As written ("150 mm", "b/2").
  std::optional<GiNaC::ex> formula;  ///< For a parameter written as a formula of earlier ones.
  SourceLocation where;
  /// In the file as the user wrote it; false for one kinema made (a joints file's sketch
  /// numbers, a spatial chain's starting motion), which with_parameters does not set.
  bool written = true;
  /// Not written: the written parameters its value was worked out from (a joints file's
  /// sketch placed with them); empty where it is a constant of the file whatever they are.
  std::vector<std::string> follows;
  /// Counted in ConstraintSystem::length_scale (each front end chooses which).
  bool sets_length_scale = false;
};

/// A coordinate and its two time derivatives (the symbols carry their LaTeX names).
struct Coordinate {
  std::string name;
  Dimension dimension = Dimension::angle;  ///< angle or length
  GiNaC::realsymbol symbol, rate, second_rate;
  double guess = 0.0;  ///< SI starting value (unknowns): picks the assembly branch.
  SourceLocation where;
};

/// An angle that moves with the input as a given function of it (a spatial chain's driven
/// variable): value + rate tau + second_rate tau^2 / 2 at tau = (input - origin) / scale
/// (Driver's follower_origin and follower_scale). An input value is refused where one of
/// them would pass kMaxAngleDegrees (its sine and cosine lose their digits).
struct FollowingAngle {
  std::string name;
  double value = 0.0, rate = 0.0, second_rate = 0.0;  ///< SI, per unit of tau.
};

/// The driver: its coordinate and the motion the file gives it.
struct Driver : Coordinate {
  std::vector<double> values;  ///< SI values from the file (may be empty).
  double rate_value = 0.0;     ///< SI; negative = clockwise / retracting.
  double second_rate_value = 0.0;
  /// The rate and second rate as the file wrote them ("60 rpm", "90 deg/s"): a document
  /// states what was written beside its SI value. Empty where no file gave them (a
  /// spatial chain's time, a system built in code).
  std::string rate_text, second_rate_text;
  std::vector<FollowingAngle> followers;
  double follower_origin = 0.0, follower_scale = 1.0;
};

/// Equations that belong together as the user wrote them: a vector loop
/// (later a dyad, a frame).
struct EquationGroup {
  std::string kind;  ///< "loop"
  std::string name;  ///< "ABCD"
  SourceLocation where;
  std::vector<std::size_t> equations;  ///< Indices into ConstraintSystem::equations.
  /// A planar loop as a complex sum (= 0) and its terms in the order written
  /// (link vectors length*exp(I*angle)); empty for groups of other kinds.
  std::optional<GiNaC::ex> vector;
  std::vector<GiNaC::ex> terms;
  /// A spatial chain's distance closure: its two points (names in ConstraintSystem::points),
  /// the coupler the drawings join; empty for groups of other kinds.
  std::vector<std::string> between;
};

/// One scalar equation Phi_i(q, theta) = 0 and where it comes from.
struct Equation {
  GiNaC::ex expression;
  std::size_t group = 0;  ///< Index into ConstraintSystem::groups.
  std::string component;  ///< "x", "y" (later "axis 2", ...).
};

/// A point of a spatial chain in its frame F: the terms of its velocity and
/// acceleration as the seed writes them (observer basis), derived once by the front end:
/// v = v_F + w x r + v_rel, a = a_F + alpha x r + w x (w x r) + 2 w x v_rel + a_rel.
struct RelativeMotionTerms {
  std::string frame;
  std::vector<GiNaC::ex> relative_position;  ///< r, from the frame's origin.
  std::vector<GiNaC::ex> frame_velocity, transport, relative_velocity;
  std::vector<GiNaC::ex> frame_acceleration, tangential, centripetal, coriolis, relative_acceleration;
};

/// A named point whose position the system determines (2-D or 3-D).
struct PointObservable {
  std::string name;
  SourceLocation where;
  std::vector<std::string> components;  ///< "x", "y" (and "z").
  std::vector<GiNaC::ex> position;      ///< One expression per component.
  std::optional<GiNaC::ex> written;     ///< Planar: x + I*y as written.
  std::vector<GiNaC::ex> written_terms;  ///< Planar: its terms in the order written (sum = written).
  std::optional<RelativeMotionTerms> terms;  ///< Spatial chains.
  bool is_joint = false;                     ///< A joint of a joints-and-links file (its messages say "joint").
};

/// One relative turning summed into a frame's angular velocity: a rate times the unit
/// axis it turns about ("omega5 y_E2": axis y of frame E2, as turned so far).
struct AngularVelocityTerm {
  GiNaC::ex rate;
  std::string axis;             ///< "x", "y" or "z"
  std::string frame;            ///< Whose axis it is.
  std::vector<GiNaC::ex> vector;  ///< rate times the axis, observer basis.
  /// Its time derivative in the observer, in two parts (their sums over the terms are the
  /// frame's angular acceleration): d(rate)/dt times the axis, and w_frame x (rate axis),
  /// the axis carried round by the frame it belongs to.
  std::vector<GiNaC::ex> rate_change, carried;
};

/// A frame of a spatial chain: where it is and how it turns relative to the observer
/// (observer basis): its origin, its rotation, its angular velocity with each relative
/// term along the chain, and its angular acceleration.
struct FrameObservable {
  std::string name, parent;
  std::string joint;  ///< The letter of the joint at its origin, for drawings ("A"); may be empty.
  SourceLocation where;
  std::vector<GiNaC::ex> origin;    ///< 3 components.
  std::vector<GiNaC::ex> rotation;  ///< 3 x 3 row-major; its columns are the frame's axes.
  std::vector<GiNaC::ex> angular_velocity;
  std::vector<AngularVelocityTerm> angular_velocity_terms;
  std::vector<GiNaC::ex> angular_acceleration;
};

struct ConstraintSystem {
  std::string title;
  std::string description;
  std::string source_file;  ///< Path as given (for messages).
  std::vector<SystemParameter> parameters;  ///< In file order.
  Driver input;
  std::vector<Coordinate> unknowns;  ///< q, in file order.
  std::vector<Equation> equations;   ///< As many as unknowns.
  std::vector<EquationGroup> groups;
  std::vector<PointObservable> points;
  std::vector<FrameObservable> frames;
  OutputUnits output;
  /// How a mechanism of joints and links is solved: its dyads, joints and links (set by
  /// the front end that found them).
  std::optional<SolvingPlan> plan;
  /// Joints and links: each ground joint's position (x + I*y) by name, a formula of the
  /// parameters (the drawing stage draws the pivots where the sliders put them).
  std::vector<std::pair<std::string, GiNaC::ex>> ground_joints;
  /// Typical length (largest length parameter, else 1 m): tolerances and scaling.
  double length_scale = 1.0;

  /// "loop ABCD (four_bar.toml:12)" for messages.
  std::string describe_group(std::size_t group) const {
    const EquationGroup& g = groups.at(group);
    return g.kind + " \"" + g.name + "\" (" + g.where.str() + ")";
  }
};

/// The largest |value| of the parameters that set the length scale, else 1 (m): what
/// every front end stores as ConstraintSystem::length_scale.
double length_scale_of(const std::vector<SystemParameter>& parameters);

/// Where the parameter the file writes as `name` is in system.parameters; InputError
/// naming it (and listing the file's parameters) for a name the file does not write.
std::size_t written_parameter_index(const ConstraintSystem& system, const std::string& name);

/// Most unknowns in one system: the numeric solver factorises the dense Jacobian at
/// each position, so its time grows as the cube of the count (2,000 took minutes).
constexpr std::size_t kMaxUnknowns = 256;

/// Throws InputError at the first unknown past the limit (where, name).
[[noreturn]] void refuse_unknown_count(std::size_t count, const SourceLocation& first_past, const std::string& name);

/// Refuses more than kMaxUnknowns unknowns (each with .where and .name); a front end asks
/// before its own work grows with the count.
template <class Unknowns>
void check_unknown_count(const Unknowns& unknowns) {
  if (unknowns.size() > kMaxUnknowns)
    refuse_unknown_count(unknowns.size(), unknowns[kMaxUnknowns].where, unknowns[kMaxUnknowns].name);
}

}  // namespace kinema
