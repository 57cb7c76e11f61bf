#include "engine/analysis/sensitivities.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/analysis/output_scale.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/model.hpp"
#include "engine/numeric/sensitivity.hpp"

namespace kinema {

namespace {

// What a result column's derivative is made of: a derivative the engine solves, or a
// vector's length (speed, acceleration magnitude): d|v| = v . dv / |v|.
struct ColumnSource {
  enum class Kind { none, q, qd, qdd, observable, magnitude, linkage } kind = Kind::none;
  std::size_t index = 0;      ///< Unknown, point-stage output (the first component of a magnitude), or linkage value.
  std::size_t point = 0, component = 0, dimension = 0;  ///< A magnitude: its vector among the point's values.
  double factor = 1;          ///< Output units of the column per SI unit.
};

// Each result column's source in the order of result_columns, up to a circuit's assembly
// signs (which have none).
std::vector<ColumnSource> column_sources(const ConstraintSystem& system) {
  using Kind = ColumnSource::Kind;
  const OutputScale scale(system);
  std::vector<ColumnSource> sources(kInputColumns);  // the input and its rates are given
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    const Dimension kind = system.unknowns[i].dimension;
    sources.push_back({Kind::q, i, 0, 0, 0, scale.unwrapped(kind, 1.0)});
    sources.push_back({Kind::qd, i, 0, 0, 0, scale.rate(kind, 1.0)});
    sources.push_back({Kind::qdd, i, 0, 0, 0, scale.rate(kind, 1.0)});
  }
  const double length = 1 / scale.length;
  std::size_t output = 0;  // of the point stage
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    const std::size_t d = system.points[p].components.size();
    for (std::size_t part = 0; part < 3; ++part) {
      for (std::size_t c = 0; c < d; ++c) sources.push_back({Kind::observable, output + part * d + c, 0, 0, 0, length});
      if (part > 0) sources.push_back({Kind::magnitude, output + part * d, p, part * d, d, length});
    }
    output += 3 * d;
  }
  for (std::size_t f = 0; f < system.frames.size(); ++f)
    for (std::size_t c = 0; c < 6; ++c) sources.push_back({Kind::observable, output++, 0, 0, 0, 1.0});
  if (!system.plan) return sources;
  // Joints and links (linkage_derivatives' order, SI): each block's angle (deg) and rates,
  // each slider's three vectors, each guide point's two, each relative turning's rates.
  std::size_t linkage = 0;
  const auto add = [&](std::size_t count, double factor) {
    for (std::size_t k = 0; k < count; ++k) sources.push_back({Kind::linkage, linkage++, 0, 0, 0, factor});
  };
  for (const SolvingPlan::Body& body : system.plan->bodies) {
    if (body.guide < 0) continue;
    add(1, scale.unwrapped(Dimension::angle, 1.0));
    add(2, 1.0);
  }
  add(6 * system.plan->sliders.size() + 4 * guide_points(system).size(), length);
  add(2 * relative_turnings(system).size(), 1.0);
  return sources;
}

// Whether any of the columns is a joints-and-links value (worked out per row only then).
bool asks_linkage(const std::vector<SensitivityColumn>& columns, const std::vector<ColumnSource>& sources) {
  for (const SensitivityColumn& column : columns)
    if (sources[column.column].kind == ColumnSource::Kind::linkage) return true;
  return false;
}

double derivative(const ColumnSource& source, const StateDerivatives& d, const std::vector<double>& linkage,
                  const MotionTable& table, std::size_t row) {
  switch (source.kind) {
    case ColumnSource::Kind::linkage: return linkage[source.index];
    case ColumnSource::Kind::q: return d.q[Eigen::Index(source.index)];
    case ColumnSource::Kind::qd: return d.qd[Eigen::Index(source.index)];
    case ColumnSource::Kind::qdd: return d.qdd[Eigen::Index(source.index)];
    case ColumnSource::Kind::observable: return d.observables[source.index];
    case ColumnSource::Kind::magnitude: {
      double dot = 0, v[3] = {0, 0, 0};
      for (std::size_t c = 0; c < source.dimension; ++c) {
        v[c] = table.point_column(source.point, source.component + c)[row];
        dot += v[c] * d.observables[source.index + c];
      }
      return dot / vector_length(v[0], v[1], v[2]);  // NaN where the vector is zero: no derivative
    }
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

// The joints-and-links values' derivatives at an ok row (linkage_derivatives), the points'
// from the point stage's derivatives (each point's position, velocity, acceleration).
void linkage_of(const ConstraintSystem& system, const MotionTable& table, std::size_t row, const StateDerivatives& d,
                double* values) {
  std::vector<std::size_t> first_output(system.points.size());
  for (std::size_t p = 0, output = 0; p < system.points.size(); output += 3 * system.points[p].components.size(), ++p)
    first_output[p] = output;
  const auto d_point = [&](std::size_t p) {
    PointMotion motion;
    motion.dimension = system.points[p].components.size();
    for (std::size_t c = 0; c < motion.dimension; ++c) {
      motion.position[c] = d.observables[first_output[p] + c];
      motion.velocity[c] = d.observables[first_output[p] + motion.dimension + c];
      motion.acceleration[c] = d.observables[first_output[p] + 2 * motion.dimension + c];
    }
    return motion;
  };
  linkage_derivatives(system, table, row, d.q, d.qd, d.qdd, d_point, values);
}

// A parameter's output unit ("" for a plain number) and SI units per output unit.
std::pair<std::string, double> parameter_unit(const SystemParameter& p, const OutputScale& scale) {
  if (p.dimension == Dimension::length) return {scale.length_unit, scale.length};
  if (p.dimension == Dimension::angle) return {"deg", kRadiansPerDegree};
  return {"", 1.0};
}

std::string joined(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

}  // namespace

std::vector<std::string> differentiable_columns(const ConstraintSystem& system) {
  const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system));
  const std::vector<ColumnSource> sources = column_sources(system);
  std::vector<std::string> names;
  for (std::size_t c = 0; c < sources.size(); ++c)
    if (sources[c].kind != ColumnSource::Kind::none) names.push_back(columns[c].name);
  return names;
}

std::vector<SensitivityColumn> sensitivity_columns(const ConstraintSystem& system, const std::vector<std::string>& asked) {
  const OutputScale scale(system);
  const std::vector<ResultColumn> columns = result_columns(system, scale);
  const std::vector<ColumnSource> sources = column_sources(system);
  std::vector<SensitivityColumn> result;
  const auto add = [&](std::size_t column, std::size_t parameter) {
    const std::string name = "d_" + columns[column].name + "_d_" + system.parameters[parameter].symbol.get_name();
    for (const SensitivityColumn& s : result)
      if (s.named.name == name) return;  // asked twice: one column
    for (const ResultColumn& other : columns)
      if (other.name == name)
        throw InputError(system.source_file + ": the sensitivity column \"" + name + "\" has the name of an output column; rename one");
    const auto [unit, per] = parameter_unit(system.parameters[parameter], scale);
    result.push_back({{name, unit.empty() ? columns[column].unit : columns[column].unit + "/" + unit}, column, parameter,
                      sources[column].factor * per});
  };
  for (const std::string& request : asked) {
    const std::size_t colon = request.find(':');
    const bool one = colon != std::string::npos;  // "omega3:b"; "b" asks for every column
    const std::string column = colon == std::string::npos ? "" : request.substr(0, colon),
                      parameter_name = colon == std::string::npos ? request : request.substr(colon + 1);
    std::vector<std::string> written;
    for (const SystemParameter& p : system.parameters)
      if (p.written) written.push_back(p.symbol.get_name());
    if (std::find(written.begin(), written.end(), parameter_name) == written.end()) {
      throw InputError(system.source_file + ": sensitivity \"" + request + "\": no parameter named \"" + parameter_name +
                       "\" (there are: " + (written.empty() ? "none" : joined(written)) + ")");
    }
    const std::size_t parameter = written_parameter_index(system, parameter_name);
    std::size_t found = 0;
    for (std::size_t c = 0; c < sources.size(); ++c) {
      if (sources[c].kind == ColumnSource::Kind::none || (one && columns[c].name != column)) continue;
      add(c, parameter);
      ++found;
    }
    if (found == 0 && one) {
      const std::vector<std::string> names = differentiable_columns(system);
      throw InputError(system.source_file + ": sensitivity \"" + request + "\": no output column named \"" + column +
                       "\" that has a derivative (there are: " + (names.empty() ? "none" : joined(names)) + ")");
    }
  }
  return result;
}

Sensitivities::Sensitivities(const Model& model, std::vector<SensitivityColumn> columns)
    : model_(model), columns_(std::move(columns)) {
  std::vector<std::size_t> compiled;  // parameter of each of parameters_
  for (const SensitivityColumn& column : columns_) {
    std::size_t k = 0;
    while (k < compiled.size() && compiled[k] != column.parameter) ++k;
    if (k == compiled.size()) {
      compiled.push_back(column.parameter);
      parameters_.push_back(std::make_unique<ParameterSensitivity>(
          model.system, model.derivation, model.kinematics, model.system.parameters[column.parameter].symbol.get_name()));
    }
    column_parameter_.push_back(k);
  }
}

Sensitivities::~Sensitivities() = default;

void Sensitivities::fill(MotionTable& table, std::size_t first, std::size_t last) const {
  const std::size_t width = columns_.size();
  std::vector<double> values((last - first) * width);
  rows(table, first, last, values.data());
  table.set_derived_count(width);
  for (std::size_t k = 0; k < width; ++k) {
    double* column = table.derived_column(k);
    for (std::size_t row = first; row < last; ++row) column[row] = values[(row - first) * width + k];
  }
}

void Sensitivities::rows(const MotionTable& table, std::size_t first, std::size_t last, double* values,
                         bool si) const {
  const std::vector<ColumnSource> sources = column_sources(model_.system);
  std::vector<SensitivityWorkspace> workspaces;
  workspaces.reserve(parameters_.size());
  for (const auto& parameter : parameters_) workspaces.emplace_back(*parameter);
  std::vector<StateDerivatives> derivatives(parameters_.size());
  std::vector<char> known(parameters_.size());
  const bool linkage = asks_linkage(columns_, sources);
  std::vector<std::vector<double>> linkage_values(parameters_.size());
  if (linkage)
    for (auto& list : linkage_values) list.resize(sources.size() - linkage_columns_begin(model_.system));
  for (std::size_t row = first; row < last; ++row) {
    for (std::size_t k = 0; k < workspaces.size(); ++k) {
      known[k] = workspaces[k].at(table, row, derivatives[k]);
      if (known[k] && linkage) linkage_of(model_.system, table, row, derivatives[k], linkage_values[k].data());
    }
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      const SensitivityColumn& column = columns_[c];
      const std::size_t k = column_parameter_[c];
      *values++ = known[k] ? derivative(sources[column.column], derivatives[k], linkage_values[k], table, row) *
                                 (si ? 1.0 : column.output_factor)
                           : std::numeric_limits<double>::quiet_NaN();
    }
  }
}

}  // namespace kinema
