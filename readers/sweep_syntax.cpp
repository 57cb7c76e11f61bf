#include "readers/sweep_syntax.hpp"

#include <cmath>
#include <sstream>

#include "engine/base/errors.hpp"

namespace kinema {

InputValues parse_sweep(const std::string& text, double unit_factor, std::size_t max_values) {
  double start = 0, stop = 0, step = 0;
  char colon1 = 0, colon2 = 0;
  std::istringstream in(text);
  if (!(in >> start >> colon1 >> stop >> colon2 >> step) || colon1 != ':' || colon2 != ':' ||
      !(in >> std::ws).eof()) {
    throw InputError("sweep \"" + text + "\" is not start:stop:step (e.g. 0:360:1)");
  }
  return sweep_between(start, stop, step, unit_factor, max_values, "sweep \"" + text + "\"");
}

InputValues sweep_between(double start, double stop, double step, double unit_factor, std::size_t max_values,
                          const std::string& written) {
  if (!std::isfinite(start) || !std::isfinite(stop) || !std::isfinite(step) || step == 0 ||
      (stop - start) / step < 0) {
    throw InputError(written + " never reaches its stop: the step must be non-zero "
                     "and point from start to stop");
  }
  const double count = std::floor((stop - start) / step + 1e-9);
  if (count >= static_cast<double>(max_values)) {
    throw InputError(written + " has more than " + std::to_string(max_values) +
                     " values; use a larger step or split the range");
  }
  return InputValues::sweep(start, step, static_cast<std::size_t>(count) + 1, unit_factor);
}

}  // namespace kinema
