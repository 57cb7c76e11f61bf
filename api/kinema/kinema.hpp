// kinema as a library: the one header a program includes (and the only one installed,
// with error.hpp). It names nothing of GiNaC or Eigen and no header of the engine, so
// that a program builds in about a second and depends only on what is declared here;
// the engine behind it (engine/model.hpp) is kinema's own and may change.
//
//   const kinema::MechanismModel four_bar("samples/four_bar.toml");
//   const kinema::Solution at_30 = four_bar.solve("30 deg");
//   double omega3 = at_30.rate("omega3");                  // rad/s
//   std::array<double, 3> v = at_30.point("P").velocity;   // m/s
//
// Input values are quantities with units ("30 deg", "120 mm", "2 s"; or a number in SI,
// kinema::degrees(30) for one in degrees); results are in SI (m, rad, s), read by the
// names the mechanism file gives (or as arrays in the order of MechanismModel::names()).
// Everything kinema throws is a kinema::Error whose message says what and where.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <kinema/error.hpp>

namespace kinema {

/// Radians in `value` degrees: solve(kinema::degrees(30)) is solve("30 deg").
constexpr double degrees(double value) { return value * (3.14159265358979323846 / 180.0); }
/// Metres in `value` millimetres (a slider's input given in SI).
constexpr double millimetres(double value) { return value * 1e-3; }

/// The names of a mechanism's variables as its file gives them (file order).
struct Names {
  std::string input, input_rate, input_second_rate;        ///< "theta2", "omega2", "alpha2"
  std::string input_unit;                                   ///< Its SI unit: "rad", "m" or "s".
  std::vector<std::string> unknowns, rates, second_rates;   ///< "theta3", "omega3", "alpha3", ...
  std::vector<std::string> points, frames;                  ///< Points (and joints); a spatial chain's frames.
};

/// Position, velocity and acceleration of a point (SI; z is 0 for a planar point).
struct PointResult {
  std::size_t dimension = 2;  ///< 2 (planar) or 3 (spatial chain).
  std::array<double, 3> position{}, velocity{}, acceleration{};
};

/// Angular velocity and acceleration of a spatial chain's frame, in the observer's basis.
struct FrameResult {
  std::array<double, 3> angular_velocity{}, angular_acceleration{};
};

enum class SolutionStatus {
  ok,           ///< Positions, rates and second rates known.
  singular,     ///< Positions known; at a toggle or dead centre, so no rates.
  unassembled,  ///< The mechanism does not close at this input (on its branch).
};

class MechanismModel;

/// The mechanism at one input value, as plain numbers read by name. A value that does
/// not assemble is a Solution whose status says so and whose message says why (in
/// kinema's words); asking it for what it does not have throws that message, never
/// gives NaN.
class Solution {
 public:
  double input() const { return input_; }  ///< SI (rad, m or s).
  double input_rate() const { return input_rate_; }
  double input_second_rate() const { return input_second_rate_; }
  SolutionStatus status() const { return status_; }
  bool ok() const { return status_ == SolutionStatus::ok; }
  /// Why the status is not ok ("four_bar.toml: loop ... does not close at ..."); empty when ok.
  const std::string& message() const { return message_; }

  /// An unknown's value ("theta3", rad or m), or the input's ("theta2"). Error for a name
  /// the mechanism does not have, or when unassembled.
  double value(const std::string& name) const;
  /// A rate ("omega3", rad/s or m/s; the input's too). Error unless ok.
  double rate(const std::string& name) const;
  /// A second rate ("alpha3", rad/s^2 or m/s^2; the input's too). Error unless ok.
  double second_rate(const std::string& name) const;
  /// A point's motion ("P", or a joint's name). Error unless ok.
  const PointResult& point(const std::string& name) const;
  /// A spatial chain frame's angular motion. Error unless ok.
  const FrameResult& frame(const std::string& name) const;

  /// The same as arrays in the order of MechanismModel::names() (empty where the status
  /// leaves them unknown).
  const std::vector<double>& values() const { return values_; }
  const std::vector<double>& rates() const { return rates_; }
  const std::vector<double>& second_rates() const { return second_rates_; }
  const std::vector<PointResult>& points() const { return points_; }
  const std::vector<FrameResult>& frames() const { return frames_; }

 private:
  friend class MechanismModel;
  Solution() = default;
  std::shared_ptr<const Names> names_;
  std::string source_;  ///< The file, for messages.
  double input_ = 0, input_rate_ = 0, input_second_rate_ = 0;
  SolutionStatus status_ = SolutionStatus::unassembled;
  std::string message_;
  std::vector<double> values_, rates_, second_rates_;
  std::vector<PointResult> points_;
  std::vector<FrameResult> frames_;
};

/// A mechanism file read, derived and compiled once (immutable; copies share it, and it
/// may be solved from several threads). Its rates are the file's.
class MechanismModel {
 public:
  /// Reads a mechanism file (any of the three forms). Error with file:line for a bad file.
  explicit MechanismModel(const std::string& path);
  /// The same from TOML text; `name` stands for the file in messages.
  static MechanismModel from_toml(const std::string& text, const std::string& name = "mechanism.toml");

  const std::string& title() const;
  const Names& names() const { return *names_; }

  /// At one input value: "30 deg", "0.5 rad", "120 mm", "2 s"; a bare number ("30") in
  /// the file's output unit of its kind, as `kinema eval --at` reads it (degrees for an
  /// angle). Error for a unit of another kind than the input's.
  Solution solve(const std::string& value) const;
  /// At one input value in SI (rad, m or s): solve(kinema::degrees(30)).
  Solution solve(double value) const;
  /// At each value in order, each solution continued from the one before, so that the
  /// branch the file's guesses pick is kept (as `kinema eval` solves a list).
  std::vector<Solution> solve(const std::vector<std::string>& values) const;
  std::vector<Solution> solve(const std::vector<double>& values) const;
  /// solve({"10 deg", "20 deg"}) and solve({0.1, 0.2}) (a braced pair of strings would
  /// otherwise also be a std::string made from two pointers).
  std::vector<Solution> solve(std::initializer_list<std::string> values) const {
    return solve(std::vector<std::string>(values));
  }
  std::vector<Solution> solve(std::initializer_list<double> values) const { return solve(std::vector<double>(values)); }

  /// The same mechanism with other parameter values, as quantities with units
  /// ({{"b", "0.31 m"}, {"delta", "25 deg"}}; a bare number for a parameter of no unit),
  /// gives the numbers the file edited to them would give, in microseconds: nothing is
  /// derived or compiled again (the copy shares this model's formulas and compiled code).
  /// Parameters written as formulas of others follow them (EF = "CE" follows CE). A
  /// joints-and-links copy solves by Newton from the file's sketch guesses rather than
  /// dyad by dyad (the same numbers); one whose sketch gave lengths the file does not
  /// state is refused. Error naming the parameter for a name the file does not write or
  /// a value of another kind than the parameter's (a length given in degrees).
  MechanismModel with_parameters(const std::vector<std::pair<std::string, std::string>>& values) const;

  /// The exact derivative of an output column ("omega3", "theta3", "P_vx", "P_speed": the
  /// names of `kinema eval`'s columns) in a parameter ("b") at each input value (SI), each
  /// continued from the one before as solve(values) does: SI (rad/s per m of b), NaN where a
  /// value is not ok. Derived symbolically and solved with the model's Jacobian (the
  /// parameter's derivatives compiled on each call). Error naming an unknown column or
  /// parameter, with the names there are.
  std::vector<double> sensitivity(const std::string& column, const std::string& parameter,
                                  const std::vector<double>& values) const;

  struct Engine;  ///< The engine's model (api/kinema.cpp).

 private:
  friend struct EngineAccess;  ///< kinema's own views beside this one (api/engine_access.hpp).
  explicit MechanismModel(std::shared_ptr<const Engine> engine);
  MechanismModel(std::shared_ptr<const Engine> engine, std::shared_ptr<const Names> names);
  std::shared_ptr<const Engine> engine_;
  std::shared_ptr<const Names> names_;
};

}  // namespace kinema
