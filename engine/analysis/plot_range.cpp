#include "engine/analysis/plot_range.hpp"

#include <cmath>

namespace kinema {

std::vector<double> plot_range(const ConstraintSystem& system, double first) {
  std::vector<double> range;
  if (system.input.dimension == Dimension::angle) {
    for (int i = 0; i <= 180; ++i) range.push_back(first + from_degrees(2.0 * i));
  } else if (system.input.dimension == Dimension::time) {  // two seconds from the instant
    for (int i = 0; i <= 200; ++i) range.push_back(first + 0.01 * i);
  } else {
    const double span = system.length_scale;
    for (int i = 0; i <= 200; ++i) range.push_back(first - span / 2 + span * i / 200.0);
  }
  return range;
}

std::vector<double> unwrap_degrees(std::vector<double> degrees, std::size_t reference) {
  double last = NAN;
  for (double& d : degrees) {
    if (!std::isfinite(d)) continue;
    if (std::isfinite(last)) d -= 360.0 * std::round((d - last) / 360.0);
    last = d;
  }
  if (reference < degrees.size() && std::isfinite(degrees[reference])) {
    double turns = std::round(degrees[reference] / 360.0);
    if (degrees[reference] - 360.0 * turns <= -180.0) turns -= 1;
    for (double& d : degrees) d -= 360.0 * turns;
  }
  return degrees;
}

}  // namespace kinema
