#include <kinema/engine/report/output_scale.hpp>

#include <cmath>

namespace kinema {

OutputScale::OutputScale(const ConstraintSystem& system)
    : length(system.output.length_factor),
      length_unit(system.output.length),
      input_dimension(system.input.dimension) {}

double OutputScale::coordinate(Dimension dimension, double si) const {
  if (dimension == Dimension::angle) {
    double degrees = std::remainder(to_degrees(si), 360.0);
    if (degrees <= -180.0) degrees += 360.0;
    return degrees;
  }
  return si / length;
}

double OutputScale::unwrapped(Dimension dimension, double si) const {
  return dimension == Dimension::angle ? to_degrees(si) : si / length;
}

double OutputScale::rate(Dimension dimension, double si) const {
  return dimension == Dimension::angle ? si : si / length;
}

std::string OutputScale::coordinate_unit(Dimension dimension) const {
  return dimension == Dimension::angle ? "deg" : length_unit;
}

std::string OutputScale::rate_unit(Dimension dimension) const {
  return dimension == Dimension::angle ? "rad/s" : length_unit + "/s";
}

std::string OutputScale::second_rate_unit(Dimension dimension) const {
  return dimension == Dimension::angle ? "rad/s^2" : length_unit + "/s^2";
}

}  // namespace kinema
