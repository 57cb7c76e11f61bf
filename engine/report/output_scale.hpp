// Numbers for people: SI values converted to the output units the file asks
// for (lengths in its unit, angles in degrees), the same for every format.
#pragma once

#include <string>

#include <kinema/engine/constraint_system.hpp>

namespace kinema {

struct OutputScale {
  explicit OutputScale(const ConstraintSystem& system);
  double length;  ///< SI metres per output length unit.
  std::string length_unit;
  Dimension input_dimension;
  /// Coordinate value in output units (angles in deg, wrapped to (-180, 180]).
  double coordinate(Dimension dimension, double si) const;
  /// Coordinate value in output units, angles not wrapped (continuous curves, inputs).
  double unwrapped(Dimension dimension, double si) const;
  double input(double si) const { return unwrapped(input_dimension, si); }
  double rate(Dimension dimension, double si) const;  ///< rad/s or length/s (also for second rates)
  std::string coordinate_unit(Dimension dimension) const;
  std::string rate_unit(Dimension dimension) const;
  std::string second_rate_unit(Dimension dimension) const;
};

}  // namespace kinema
