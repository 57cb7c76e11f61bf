#include <kinema/engine/report/plot_range.hpp>

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

}  // namespace kinema
