// Input values as users write them, and the range they are held to (input_value.hpp).
#include "engine/input_value.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/units.hpp"
#include "readers/sweep_syntax.hpp"

namespace kinema {

double parse_input_value(const ConstraintSystem& m, const std::string& text) {
  const Quantity q = parse_quantity(text);
  if (q.dimension == Dimension::number) {
    if (m.input.dimension == Dimension::time) return q.si_value;  // seconds
    return m.input.dimension == Dimension::angle ? from_degrees(q.si_value) : q.si_value * m.output.length_factor;
  }
  if (q.dimension != m.input.dimension) {
    throw UnitError("input value \"" + text + "\" is " + with_article(dimension_name(q.dimension)) + ", but " +
                    m.input.name + " is " + with_article(dimension_name(m.input.dimension)));
  }
  return q.si_value;
}

double parse_parameter_value(const ConstraintSystem& m, const std::string& name, const std::string& text) {
  const SystemParameter& p = m.parameters[written_parameter_index(m, name)];
  const Quantity q = parse_quantity(text);
  if (q.dimension != p.dimension) {
    // A bare number is refused for a length or an angle: its unit would be a guess.
    throw UnitError(m.source_file + ": parameter \"" + name + "\" is " + with_article(dimension_name(p.dimension)) +
                    ", but \"" + text + "\" is " + with_article(dimension_name(q.dimension)) +
                    (q.dimension == Dimension::number ? " (give its unit)" : ""));
  }
  return q.si_value;
}

std::vector<double> parameter_range(const ConstraintSystem& m, const std::string& name, const std::string& range) {
  const SystemParameter& p = m.parameters[written_parameter_index(m, name)];
  const std::string written = "the range of " + name + " \"" + range + "\"";
  std::vector<std::string> parts(1);
  for (char c : range) {
    if (c == ':') parts.emplace_back();
    else parts.back() += c;
  }
  if (parts.size() != 3) throw InputError(written + " is not first:last:step (e.g. 0.25:0.35:0.001 or 25 cm:35 cm:1 mm)");
  // Each part as {number, SI per its unit}; a bare number in the file's unit of its kind.
  const double file_unit = p.dimension == Dimension::length  ? m.output.length_factor
                           : p.dimension == Dimension::angle ? kRadiansPerDegree
                                                             : 1.0;
  WrittenValue values[3];
  for (std::size_t k = 0; k < 3; ++k) {
    const Quantity q = parse_quantity(parts[k]);
    if (q.dimension == Dimension::number) {
      values[k] = {q.si_value, file_unit};
      continue;
    }
    if (q.dimension != p.dimension) {
      throw UnitError(m.source_file + ": parameter \"" + name + "\" is " + with_article(dimension_name(p.dimension)) +
                      ", but \"" + parts[k] + "\" in " + written + " is " + with_article(dimension_name(q.dimension)));
    }
    char* end = nullptr;
    const double number = std::strtod(parts[k].c_str(), &end);
    const double unit = parse_quantity("1" + std::string(end)).si_value;
    values[k] = number * unit == q.si_value ? WrittenValue{number, unit} : WrittenValue{q.si_value, 1.0};
  }
  if (values[0].unit != values[1].unit || values[1].unit != values[2].unit)
    for (WrittenValue& v : values) v = {v.number * v.unit, 1.0};
  return sweep_between(values[0].number, values[1].number, values[2].number, values[0].unit, kMaxValuesPerRun, written)
      .to_vector();
}

WrittenValue written_input_value(const ConstraintSystem& m, const std::string& text) {
  const double si = parse_input_value(m, text);
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(number)) return {si, 1.0};
  const double unit = parse_input_value(m, "1" + std::string(end));
  // A form this split does not read as number times unit: the value in SI.
  if (number * unit != si) return {si, 1.0};
  return {number, unit};
}

InputValues input_sweep(const ConstraintSystem& m, WrittenValue first, WrittenValue last, WrittenValue step) {
  if (first.unit != last.unit || last.unit != step.unit) {
    first = {first.number * first.unit, 1.0};
    last = {last.number * last.unit, 1.0};
    step = {step.number * step.unit, 1.0};
  }
  return sweep_between(first.number, last.number, step.number, first.unit, kMaxValuesPerRun,
                      "the sweep of " + m.input.name + " from " + format_significant(first.number, 12) + " to " +
                          format_significant(last.number, 12) + " by " + format_significant(step.number, 12));
}

// An angle input is turned into radians and reduced by its sine and cosine: no further
// than kMaxAngleDegrees. An angle that follows the input is held to the same limit at
// every value: at a sweep's ends, and where it turns back in between.
void check_input_range(const ConstraintSystem& m, const InputValues& values) {
  const auto check = [&](double si) {
    if (m.input.dimension == Dimension::angle) {
      const double degrees = si / kRadiansPerDegree;
      if (!(std::fabs(degrees) <= kMaxAngleDegrees * (1 + 1e-12))) {  // 1e9 deg read back through radians
        throw InputError(m.source_file + ": " + m.input.name + " = " + format_significant(degrees, 12) +
                         " deg: an angle past 1e9 deg (2.8 million turns) loses digits in its sine and cosine; "
                         "give it within a few turns");
      }
    }
    const double tau = (si - m.input.follower_origin) / m.input.follower_scale;
    for (const FollowingAngle& f : m.input.followers) {
      const double degrees = (f.value + f.rate * tau + f.second_rate * tau * tau / 2) / kRadiansPerDegree;
      if (std::fabs(degrees) <= kMaxAngleDegrees * (1 + 1e-12)) continue;
      const OutputScale scale(m);
      throw InputError(m.source_file + ": at " + m.input.name + " = " + format_significant(scale.input(si), 12) + " " +
                       scale.coordinate_unit(m.input.dimension) + ", " + f.name + " would be " +
                       format_significant(degrees, 6) +
                       " deg: an angle past 1e9 deg (2.8 million turns) loses digits in its sine and cosine; "
                       "give " + m.input.name + " where the driven variables are within a few turns");
    }
  };
  // The sweep's values beside where a follower turns back (its largest size in between).
  const auto turning_point = [&]() {
    const std::size_t n = values.size();
    const double first = values[0], last = values[n - 1];
    for (const FollowingAngle& f : m.input.followers) {
      if (f.second_rate == 0 || n < 3) continue;
      const double at = m.input.follower_origin - f.rate / f.second_rate * m.input.follower_scale;
      if (!(at > std::min(first, last) && at < std::max(first, last))) continue;
      const double k = std::floor((at - first) / (last - first) * double(n - 1));
      for (double j : {k, k + 1})
        if (j >= 0 && j < double(n)) check(values[std::size_t(j)]);
    }
  };
  if (values.is_sweep() && !values.empty()) {
    check(values[0]);
    check(values[values.size() - 1]);
    turning_point();
  } else {
    for (std::size_t i = 0; i < values.size(); ++i) check(values[i]);
  }
}

}  // namespace kinema
