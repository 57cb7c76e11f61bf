#include "engine/base/units.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>

#include "engine/base/errors.hpp"

namespace kinema {
namespace {

struct BaseUnit {
  double factor;
  Dimension dimension;
};

// Base units; "/s" and "/s^2" are applied on top of these.
const std::map<std::string, BaseUnit>& base_units() {
  static const std::map<std::string, BaseUnit> units = {
      {"m", {1.0, Dimension::length}},       {"mm", {1e-3, Dimension::length}},
      {"cm", {1e-2, Dimension::length}},     {"in", {0.0254, Dimension::length}},
      {"ft", {0.3048, Dimension::length}},   {"rad", {1.0, Dimension::angle}},
      {"deg", {kRadiansPerDegree, Dimension::angle}}, {"s", {1.0, Dimension::time}},
      {"ms", {1e-3, Dimension::time}},
  };
  return units;
}

std::string trim(const std::string& text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  return text.substr(begin, end - begin);
}

Dimension per_second(Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return Dimension::velocity;
    case Dimension::angle: return Dimension::angular_velocity;
    case Dimension::velocity: return Dimension::acceleration;
    case Dimension::angular_velocity: return Dimension::angular_acceleration;
    default: return Dimension::number;  // not a unit kinema knows
  }
}

}  // namespace

const char* dimension_name(Dimension dimension) {
  switch (dimension) {
    case Dimension::number: return "plain number";
    case Dimension::length: return "length";
    case Dimension::angle: return "angle";
    case Dimension::angular_velocity: return "angular velocity";
    case Dimension::angular_acceleration: return "angular acceleration";
    case Dimension::velocity: return "velocity";
    case Dimension::acceleration: return "acceleration";
    case Dimension::time: return "time";
  }
  return "?";
}

std::string with_article(const std::string& word) {
  const bool vowel = !word.empty() && std::string("aeiou").find(word[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + word;
}

Dimension rate_dimension(Dimension dimension) { return per_second(dimension); }

const char* understood_units() {
  return "m, mm, cm, in, ft, rad, deg, rpm, s, ms, and any of the lengths and angles followed by /s or /s^2 "
         "(e.g. rad/s, in/s, m/s^2)";
}

namespace {

// The length of the decimal number that `text` starts with ("40", "-1.5e3", ".5"), 0 if
// none: strtod alone would also read hexadecimal ("0x10"), "inf" and "nan", which
// --sweep's numbers and a reader of the file do not take for numbers.
std::size_t decimal_number_length(const char* text) {
  const auto digit = [](const char* c) { return std::isdigit(static_cast<unsigned char>(*c)) != 0; };
  const char* p = text;
  if (*p == '+' || *p == '-') ++p;
  const char* whole = p;
  while (digit(p)) ++p;
  bool any = p != whole;
  if (*p == '.') {
    const char* fraction = ++p;
    while (digit(p)) ++p;
    any = any || p != fraction;
  }
  if (!any) return 0;
  if (*p == 'e' || *p == 'E') {
    const char* exponent = p + 1;
    if (*exponent == '+' || *exponent == '-') ++exponent;
    if (digit(exponent)) {
      while (digit(exponent)) ++exponent;
      p = exponent;
    }
  }
  return static_cast<std::size_t>(p - text);
}

}  // namespace

bool looks_like_quantity(const std::string& text) {
  const std::string trimmed = trim(text);
  if (trimmed.empty()) return false;
  const char* begin = trimmed.c_str();
  const char* end = begin + decimal_number_length(begin);
  if (end == begin) return false;
  // "2*a" or "0.5 + a" are formulas, "2 in" is a quantity.
  std::string rest = trim(std::string(end));
  if (rest.empty()) return true;
  return std::isalpha(static_cast<unsigned char>(rest[0])) != 0;
}

namespace {

// A nonzero number below the smallest normal double (about 2.2e-308) is subnormal: CLN
// refuses to take it in ("floating point underflow") and the solvers lose its digits.
Quantity normal_or_refused(const Quantity& q, const std::string& text) {
  if (q.si_value != 0 && std::fabs(q.si_value) < std::numeric_limits<double>::min()) {
    throw UnitError("\"" + text + "\" is smaller than the smallest number kinema computes with (about 2.2e-308 in SI "
                    "units: m, rad, s); write 0 if you mean zero");
  }
  return q;
}

Quantity parse_quantity_as_written(const std::string& text);

}  // namespace

Quantity parse_quantity(const std::string& text) { return normal_or_refused(parse_quantity_as_written(text), text); }

namespace {

Quantity parse_quantity_as_written(const std::string& text) {
  const std::string trimmed = trim(text);
  const char* begin = trimmed.c_str();
  const char* end = begin + decimal_number_length(begin);
  const double number = std::strtod(std::string(begin, end).c_str(), nullptr);
  if ((*end == 'x' || *end == 'X') && number == 0 && end - begin <= 2) {
    throw UnitError("\"" + text + "\" is written in hexadecimal; write the number in decimal digits (16, not 0x10)");
  }
  if (end == begin) {
    throw UnitError("\"" + text + "\" is not a number with a unit (write e.g. \"150 mm\")");
  }
  if (!std::isfinite(number)) {
    throw UnitError("\"" + text + "\" is not a finite number");
  }
  std::string unit = trim(std::string(end));
  if (unit.empty()) return {number, Dimension::number};
  if (unit == "rpm" || unit == "rev/min") {
    return {number * 2.0 * kPi / 60.0, Dimension::angular_velocity};
  }
  if (unit == "°") unit = "deg";

  int time_power = 0;
  std::string base = unit;
  for (const char* suffix : {"/s^2", "/s2", "/s²"}) {
    const std::string s(suffix);
    if (base.size() > s.size() && base.compare(base.size() - s.size(), s.size(), s) == 0) {
      base = base.substr(0, base.size() - s.size());
      time_power = 2;
      break;
    }
  }
  if (time_power == 0 && base.size() > 2 && base.compare(base.size() - 2, 2, "/s") == 0) {
    base = base.substr(0, base.size() - 2);
    time_power = 1;
  }
  const auto found = base_units().find(base);
  if (found == base_units().end()) {
    throw UnitError("unit \"" + unit + "\" in \"" + text + "\" is not understood; kinema reads " +
                    understood_units());
  }
  Dimension dimension = found->second.dimension;
  for (int i = 0; i < time_power; ++i) dimension = per_second(dimension);
  return {number * found->second.factor, dimension};
}

}  // namespace

double quantity_of_dimension(const std::string& text, Dimension dimension, const std::string& context) {
  Quantity q;
  try {
    q = parse_quantity(text);
  } catch (const UnitError& error) {
    throw UnitError(context + ": " + error.what());
  }
  if (q.dimension != dimension && q.dimension != Dimension::number) {
    throw UnitError(context + " = \"" + text + "\" is " + with_article(dimension_name(q.dimension)) + ", but " +
                    with_article(dimension_name(dimension)) + " is needed here");
  }
  return q.si_value;
}

double length_unit_factor(const std::string& unit) {
  const auto found = base_units().find(unit);
  if (found == base_units().end() || found->second.dimension != Dimension::length) {
    throw UnitError("output length unit \"" + unit + "\" is not one of m, mm, cm, in, ft");
  }
  return found->second.factor;
}

}  // namespace kinema
