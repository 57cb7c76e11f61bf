// Design figures of a four-bar (issue 13): Grashof class with its inequality, and the
// transmission angle over the crank's turn with its least and greatest values and where.
// A vector-loop file is a four-bar when it has one loop of four link vectors of constant
// length — the crank (its angle the input), two links whose angles are unknowns, and the
// ground (a constant vector) — written in the order the loop goes round (crank, coupler,
// rocker, ground, in any rotation), which tells the coupler (opposite the ground) from the
// rocker (next to it).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/model.hpp"

namespace kinema {

struct FourBarFigures {
  double ground = 0, crank = 0, coupler = 0, rocker = 0;  ///< Link lengths (SI).
  std::string grashof;     ///< "crank-rocker", "double-crank", "rocker-crank", "double-rocker", "change point", "non-Grashof triple rocker"
  std::string inequality;  ///< "s + l = 40 + 120 = 160 < p + q = 80 + 100 = 180 (mm)"
  /// The transmission angle (between coupler and rocker, at their joint, 0 to 180 deg) over
  /// a turn of the input in 1-degree steps: least and greatest, in deg, and the input
  /// angles (deg, in [0, 360)) where they are; NaN without an assembled value.
  double least_transmission = 0, least_at = 0, greatest_transmission = 0, greatest_at = 0;
  bool full_turn = false;  ///< Every value of the turn assembled.
  /// Toggle positions (engine/analysis/toggles: det Phi_q = 0, solved): the input angles,
  /// deg in [0, 360).
  std::vector<double> toggles;
};

/// A slider driven by a crank (an offset slider-crank, a shaper, a six-bar whose slider
/// turns back twice a turn): every limit position over a turn and the crank angles of the
/// strokes between them.
struct Strokes {
  std::string name;                  ///< The slider's coordinate.
  std::vector<double> limit_inputs;  ///< Crank angles of the limit positions, deg in [0, 360), increasing.
  std::vector<double> limit_values;  ///< The coordinate there (output units).
  std::vector<bool> maxima;          ///< Each limit a maximum of the coordinate (else a minimum).
  /// strokes[k]: the crank angle (deg) from limit k to the next limit the crank reaches as it
  /// turns the way its rate says (k + 1, or k - 1 turning clockwise; round the turn after the
  /// last); they add up to 360. Empty where part of the turn does not assemble (the crank
  /// does not pass from one limit to the next) or there is one limit only.
  std::vector<double> strokes;
  /// The longer stroke's crank angle over the shorter's (at a constant crank rate), for
  /// exactly two limit positions over a whole turn; NaN otherwise.
  double time_ratio = std::numeric_limits<double>::quiet_NaN();
  bool whole_turn = true;  ///< Every value of the turn assembles.
  bool two_limits() const { return limit_inputs.size() == 2 && strokes.size() == 2; }
};

/// The strokes and time ratio of s from its limit_inputs, for a crank turning the way
/// `rate` says (the file's input rate).
void set_strokes(Strokes& s, double rate);

/// Most unknowns of a mechanism whose sliders' strokes are searched: the search solves a
/// turn in 1-degree steps (a dense solve of all unknowns at each), so a larger system has no
/// strokes in eval's header, which would otherwise cost as much as a sweep of the turn.
constexpr std::size_t kMaxStrokeUnknowns = 128;

/// Every limit position over a turn (engine/analysis/toggles: dq/dtheta = 0, solved) of each
/// slider coordinate of a crank-driven mechanism that has one, and the strokes between them
/// where the whole turn assembles; none for a mechanism of more than kMaxStrokeUnknowns
/// unknowns.
std::vector<Strokes> slider_strokes(const Model& model);
std::string describe_strokes(const Strokes& strokes, const std::string& input_name, const std::string& unit);

/// The Grashof classes four_bar_figures tells apart (FourBarFigures::grashof in words:
/// grashof_name), none where there is no four-bar or nothing to classify.
enum class GrashofClass : std::uint8_t {
  none, crank_rocker, double_crank, rocker_crank, double_rocker, change_point, triple_rocker
};
const char* grashof_name(GrashofClass kind);  ///< "crank-rocker", ...; "n/a" for none.
/// The class of a four-bar of these side lengths (SI; signs ignored); none where a side is
/// zero or the sum is past the largest number in the output unit (SI metres per unit).
GrashofClass grashof_class(double ground, double crank, double coupler, double rocker, double length_unit);

/// A side of a vector-loop four-bar: its length as written (a formula of the parameters,
/// signed as the loop's term), its value at the system's parameter values, and for the
/// coupler and the rocker which unknown is its angle; for the ground its fixed angle as
/// written (0 where its term has no exp) and that angle's value (NaN where not real).
struct FourBarSide {
  GiNaC::ex length;
  double value = 0;
  std::size_t unknown = 0;
  GiNaC::ex angle = 0;
  double angle_value = 0;
};
/// A side's numbers alone: what work on several threads holds, as GiNaC expressions may
/// not be copied on two threads at once (their reference counts are not atomic).
struct FourBarSideValues {
  double value = 0;
  std::size_t unknown = 0;
  double angle_value = 0;
};
struct FourBarLoopValues {
  FourBarSideValues ground, crank, coupler, rocker;
};
struct FourBarLoop {
  FourBarSide ground, crank, coupler, rocker;
  FourBarLoopValues values() const;
};
/// The loop of a vector-loop four-bar driven by its crank, its sides told apart as
/// four_bar_figures tells them; nothing for other mechanisms.
std::optional<FourBarLoop> four_bar_loop(const ConstraintSystem& system);
/// A term of a point's position that turns with one variable: length e^(i (variable +
/// offset)), the variable the input (-1) or an unknown (its index), length and offset
/// free of both (formulas of the parameters, real at the file's values).
struct MovingPointTerm {
  std::size_t point = 0;
  int variable = -1;
  GiNaC::ex length, offset;
};
/// Every point of a planar system written as a sum of such terms and of terms that do not
/// move (left out: they add nothing to its velocity or acceleration), the terms in the
/// points' order; nullopt where a point has a term that is neither (a sliding length, an
/// angle of two variables). What a design study's lanes give the points' motion from.
std::optional<std::vector<MovingPointTerm>> moving_point_terms(const ConstraintSystem& system);

/// The transmission angle (deg, 0 to 180) where the coupler's and the rocker's angles are
/// solved: between them at their joint, the sides' signs those of the loop's values.
double transmission_angle(const FourBarLoopValues& loop, double coupler_angle, double rocker_angle);

/// The figures of a four-bar driven by its crank; nothing for other mechanisms.
std::optional<FourBarFigures> four_bar_figures(const Model& model);

/// One line for people: "Grashof crank-rocker (s + l = ... < p + q = ...); transmission
/// angle from 33.6 deg (theta2 = 0 deg) to 123 deg (theta2 = 180 deg)".
std::string describe_four_bar(const FourBarFigures& figures, const std::string& input_name);

}  // namespace kinema
