#include <cmath>

#include <kinema/engine/printers/printers.hpp>

namespace kinema {

OutputScale::OutputScale(const Mechanism& mechanism)
    : length(mechanism.output.length_factor),
      length_unit(mechanism.output.length),
      input_is_angle(mechanism.input.dimension == Dimension::angle) {}

double OutputScale::coordinate(Dimension dimension, double si) const {
  if (dimension == Dimension::angle) {
    double degrees = std::remainder(si * 180.0 / M_PI, 360.0);
    if (degrees <= -180.0) degrees += 360.0;
    return degrees;
  }
  return si / length;
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
