// An input value as a user writes it ("30 deg", "120 mm", or "30" in the file's output
// unit) turned into SI, and the range every input value is held to: the command line's
// --at and --sweep and the library facade (api/) read values the same way.
#pragma once

#include <string>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/base/input_values.hpp"

namespace kinema {

/// "30 deg", "0.5 rad", "120 mm", "2 s" in SI; a bare number is in the output unit of the
/// input's kind (degrees for an angle, the file's length unit for a slider, seconds for
/// time). UnitError for a unit of another kind than the input's.
double parse_input_value(const ConstraintSystem& system, const std::string& text);

/// A value for the parameter the file writes as `name`, in SI: "0.31 m", "120 mm", "30 deg";
/// a bare number for a parameter of no known unit. InputError for a name the file does
/// not write, UnitError naming the parameter for a value of another kind than its own.
double parse_parameter_value(const ConstraintSystem& system, const std::string& name, const std::string& text);

/// The values of a parameter the file writes over a range "first:last:step" (a design
/// study's --vary), in SI: each of the three with a unit ("0.25 m:0.35 m:1 mm") or bare in
/// the file's unit of the parameter's kind (its output length unit, degrees; a number of no
/// unit as it is), computed in their unit when the three share one (else in SI), as a
/// sweep is. InputError naming the parameter for a range with no values (a step of zero or
/// pointing away from last), not three parts, or a name the file does not write (naming
/// its parameters); UnitError for a value of another kind than the parameter.
std::vector<double> parameter_range(const ConstraintSystem& system, const std::string& name, const std::string& range);

/// An input value as written: a number and its unit (SI per unit; 1 for a value given in SI).
struct WrittenValue {
  double number = 0.0;
  double unit = 1.0;
};

/// "30 deg" as {30, radians per degree}, a bare "30" in the output unit of the input's
/// kind (as parse_input_value reads it).
WrittenValue written_input_value(const ConstraintSystem& system, const std::string& text);

/// The values from first to last by step (kMaxValuesPerRun at most): counted and computed
/// in their unit when the three share one, as `kinema eval --sweep` does in the output
/// unit (so the same values to the last bit), else in SI.
InputValues input_sweep(const ConstraintSystem& system, WrittenValue first, WrittenValue last, WrittenValue step);

/// InputError unless every value (SI) is within kMaxAngleDegrees where it is an angle, and
/// every angle that follows the input (a spatial chain's driven variables) is too; the
/// values of a sweep are checked at its ends and where a follower turns back.
void check_input_range(const ConstraintSystem& system, const InputValues& values);

}  // namespace kinema
