// Sensitivity columns: the derivative of an output column in a parameter, named
// d_<column>_d_<parameter> and given in the column's unit per the parameter's output
// unit ("d_omega3_d_b [rad/s/mm]"; a parameter of no unit adds none). Every column that
// is a function of the solved state has one: each unknown, its rate and second rate; each
// point's position, velocity, speed, acceleration and its magnitude; each frame's angular
// velocity and acceleration; a joints file's blocks, sliders' relative velocities, relative
// and Coriolis accelerations, guide points and relative turnings. The values are the engine's exact derivatives
// (engine/numeric/sensitivity), NaN where the row is not ok.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "engine/constraints/output_columns.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

struct Model;
class ParameterSensitivity;

struct SensitivityColumn {
  ResultColumn named;         ///< "d_omega3_d_b", "rad/s/mm".
  std::size_t column = 0;     ///< Of result_columns: whose derivative.
  std::size_t parameter = 0;  ///< Of the system's parameters.
  double output_factor = 1;   ///< Output units per SI unit (the column's over the parameter's).
};

/// The names of the result columns that have a derivative, in their order.
std::vector<std::string> differentiable_columns(const ConstraintSystem& system);

/// The columns asked as the command line writes them, in that order, each once: "b"
/// (every column that has a derivative in parameter b) or "omega3:b" (one). InputError
/// naming an unknown parameter or column, with the list of those there are.
std::vector<SensitivityColumn> sensitivity_columns(const ConstraintSystem& system, const std::vector<std::string>& asked);

/// Sensitivity columns of a model, each parameter's derivatives compiled once (holds the
/// model by reference). Thread-safe: each call has its own buffers.
class Sensitivities {
 public:
  Sensitivities(const Model& model, std::vector<SensitivityColumn> columns);
  ~Sensitivities();
  const std::vector<SensitivityColumn>& columns() const { return columns_; }
  /// Rows [first, last) of a table of the model, one row after the other
  /// (columns().size() values a row): in output units, or SI (`si`); NaN unless ok.
  void rows(const MotionTable& table, std::size_t first, std::size_t last, double* values, bool si = false) const;
  /// The same in output units into the table's derived columns (MotionTable::derived_column),
  /// where a printer reads them (PrintJob::sensitivities names them).
  void fill(MotionTable& table, std::size_t first, std::size_t last) const;
  void fill(MotionTable& table) const { fill(table, 0, table.size()); }

 private:
  const Model& model_;
  std::vector<SensitivityColumn> columns_;
  std::vector<std::unique_ptr<ParameterSensitivity>> parameters_;  ///< One per parameter asked.
  std::vector<std::size_t> column_parameter_;  ///< Index into parameters_ of each column.
};

}  // namespace kinema
