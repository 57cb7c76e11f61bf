// Physical units at the edge of kinema: quantities are read as "150 mm",
// "60 rpm", "15 rad/s^2" and stored in SI (m, rad, s); printers convert back.
#pragma once

#include <string>

namespace kinema {

/// What a quantity measures; SI inside (m, rad, s).
enum class Dimension {
  number,                // a plain number with no unit
  length,                // m
  angle,                 // rad
  angular_velocity,      // rad/s
  angular_acceleration,  // rad/s^2
  velocity,              // m/s
  acceleration,          // m/s^2
  time,                  // s (the input of a spatial chain)
};

/// Degrees and radians, converted here and nowhere else.
/// pi, written once for the engine (the installed facade, which includes no engine header,
/// writes it in kinema::degrees).
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadiansPerDegree = kPi / 180.0;
inline double from_degrees(double degrees) { return degrees * kRadiansPerDegree; }
inline double to_degrees(double radians) { return radians * 180.0 / kPi; }

/// The largest angle kinema takes (the input's values, a slider's direction): past it a
/// double's rounding moves the angle by more than the printed digits (1e15 deg was
/// solved at 279.95 deg, not 280).
constexpr double kMaxAngleDegrees = 1e9;

/// "length", "angle", ... for messages.
const char* dimension_name(Dimension dimension);

/// The word with its indefinite article, for messages: "a length", "an angle".
std::string with_article(const std::string& word);

/// The time derivative's dimension: angle -> angular_velocity -> angular_acceleration.
Dimension rate_dimension(Dimension dimension);

/// The unit results are printed in (lengths, and velocities per second, ...).
struct OutputUnits {
  std::string length = "m";  ///< Lengths in this unit, velocities in unit/s, ...
  double length_factor = 1.0;  ///< SI metres per output unit.
};

struct Quantity {
  double si_value = 0.0;  ///< Value converted to SI.
  Dimension dimension = Dimension::number;
};

/// Parses "<number> [unit]"; throws UnitError (with the text and what is understood)
/// when the unit is unknown or the number does not parse.
Quantity parse_quantity(const std::string& text);

/// A quantity that must measure `dimension` (a bare number is taken as SI of it), in SI;
/// UnitError naming `context` ("file:line: what") and, for a mismatch, both dimensions.
double quantity_of_dimension(const std::string& text, Dimension dimension, const std::string& context);

/// True when text starts like a number (so it is a quantity, not a formula).
bool looks_like_quantity(const std::string& text);

/// Factor from one SI unit of length to the named length unit (m, mm, cm, in, ft).
/// Throws UnitError for other names.
double length_unit_factor(const std::string& unit);

/// The list of understood units, for error messages.
const char* understood_units();

}  // namespace kinema
