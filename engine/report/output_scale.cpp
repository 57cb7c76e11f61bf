#include <kinema/engine/report/output_scale.hpp>

#include <algorithm>
#include <limits>

#include <cmath>

namespace kinema {

OutputScale::OutputScale(const ConstraintSystem& system)
    : length(system.output.length_factor),
      length_unit(system.output.length),
      input_dimension(system.input.dimension) {}

double OutputScale::coordinate(Dimension dimension, double si) const {
  if (dimension == Dimension::angle) {
    double degrees = to_degrees(si);
    if (degrees > -180.0 && degrees <= 180.0) return degrees;  // the common case, and exact
    degrees = std::remainder(degrees, 360.0);
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

void result_values(const ConstraintSystem& system, const OutputScale& scale, const MotionTable& table,
                   std::size_t row, double* values) {
  constexpr double undefined = std::numeric_limits<double>::quiet_NaN();
  const Status status = table.status(row);
  const Dimension input_kind = system.input.dimension;
  *values++ = scale.input(table.input(row));
  *values++ = scale.rate(input_kind, table.input_rate());
  *values++ = scale.rate(input_kind, table.input_second_rate());
  const auto q = table.q(row), qd = table.qd(row), qdd = table.qdd(row);
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    const Dimension kind = system.unknowns[i].dimension;
    *values++ = status != Status::unassembled ? scale.coordinate(kind, q[Eigen::Index(i)]) : undefined;
    *values++ = status == Status::ok ? scale.rate(kind, qd[Eigen::Index(i)]) : undefined;
    *values++ = status == Status::ok ? scale.rate(kind, qdd[Eigen::Index(i)]) : undefined;
  }
  const double f = scale.length;
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    const std::size_t dimension = system.points[p].components.size();
    if (status != Status::ok) {
      values = std::fill_n(values, 3 * dimension + 2, undefined);
      continue;
    }
    const PointMotion m = table.point(row, p);
    for (std::size_t c = 0; c < dimension; ++c) *values++ = m.position[c] / f;
    for (std::size_t c = 0; c < dimension; ++c) *values++ = m.velocity[c] / f;
    *values++ = m.speed() / f;
    for (std::size_t c = 0; c < dimension; ++c) *values++ = m.acceleration[c] / f;
    *values++ = m.acceleration_magnitude() / f;
  }
}

}  // namespace kinema
