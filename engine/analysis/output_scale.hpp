// Numbers for people: a solved table's values in the order and units of its output
// columns (engine/constraints/output_columns.hpp names them and holds the units), the
// same for every format.
#pragma once

#include <cstddef>
#include <functional>

#include "engine/constraints/output_columns.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

/// Row `row` of a table in the order and units of result_columns, written to values
/// (result_columns(...).size() of them); NaN where the row's status leaves a value
/// undefined (no position when unassembled, no rates or points unless ok). A circuit's
/// table (MotionTable::is_circuit) gives the columns of result_columns(..., true).
void result_values(const ConstraintSystem& system, const OutputScale& scale, const MotionTable& table,
                   std::size_t row, double* values);

/// Rows [first, last) as result_values writes them, one after the other (row r's values
/// from values + (r - first) * result_column_count(system, table.is_circuit())); worked
/// out column by column, as the table holds them.
void result_rows(const ConstraintSystem& system, const OutputScale& scale, const MotionTable& table,
                 std::size_t first, std::size_t last, double* values);

/// The joints-and-links values of an ok state (blocks, sliders, guide points, relative turnings), from result_columns'
/// linkage_columns_begin on.
void linkage_values(const ConstraintSystem& system, const OutputScale& scale, const MotionState& state, double* values);

/// The derivatives in a parameter of an ok row's joints-and-links values, in linkage_values'
/// order but SI (block angles in rad): from the derivatives of the row's unknowns, their
/// rates and second rates, and of its points' motions (d_point(p)). A block's offset and a
/// slider's direction on its guide are the file's constants.
void linkage_derivatives(const ConstraintSystem& system, const MotionTable& table, std::size_t row,
                         const Eigen::VectorXd& dq, const Eigen::VectorXd& dqd, const Eigen::VectorXd& dqdd,
                         const std::function<PointMotion(std::size_t)>& d_point, double* values);

}  // namespace kinema
