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

std::vector<ResultColumn> result_columns(const ConstraintSystem& system, const OutputScale& scale) {
  const Driver& input = system.input;
  std::vector<ResultColumn> columns = {{input.name, scale.coordinate_unit(input.dimension)},
                                       {input.rate.get_name(), scale.rate_unit(input.dimension)},
                                       {input.second_rate.get_name(), scale.second_rate_unit(input.dimension)}};
  for (const Coordinate& q : system.unknowns) {
    columns.push_back({q.name, scale.coordinate_unit(q.dimension)});
    columns.push_back({q.rate.get_name(), scale.rate_unit(q.dimension)});
    columns.push_back({q.second_rate.get_name(), scale.second_rate_unit(q.dimension)});
  }
  const std::string& l = scale.length_unit;
  for (const PointObservable& p : system.points) {
    for (const auto& c : p.components) columns.push_back({p.name + "_" + c, l});
    for (const auto& c : p.components) columns.push_back({p.name + "_v" + c, l + "/s"});
    columns.push_back({p.name + "_speed", l + "/s"});
    for (const auto& c : p.components) columns.push_back({p.name + "_a" + c, l + "/s^2"});
    columns.push_back({p.name + "_acceleration", l + "/s^2"});
  }
  return columns;
}

}  // namespace kinema
