// The problem's own size of each kind of quantity: what a view of numbers for people
// shows a value against (zero_at_scale, engine/base/number_format), together with the
// values shown beside it.
#pragma once

#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/output_columns.hpp"

namespace kinema {

/// The mechanism's size in the output units (OutputScale: lengths in its unit, angles in
/// degrees, angular rates in rad/s): lengths the longest length parameter (1 m without
/// one); angles 1 rad; rates the driver's rate times those, second rates its rate
/// squared plus its second rate (a length driver's over the size is its angular rate).
class ProblemScale {
 public:
  explicit ProblemScale(const ConstraintSystem& system);
  /// A quantity of `dimension` (length or angle; anything else 0: no size of its own)
  /// differentiated `order` times (0, 1, 2).
  double of(Dimension dimension, int order) const;
  double of(const ResultColumn& column) const { return of(column.dimension, column.order); }

 private:
  double length_ = 1;       ///< The mechanism's size, in the output length unit.
  double rate_ = 1;         ///< Its typical angular rate (rad/s).
  double second_rate_ = 1;  ///< Its typical angular second rate (rad/s^2).
};

/// The scale each value of a result row (result_values' order and output units) is shown
/// at by the views that lay rows out for people (the text table, the worked solution): the
/// larger of the problem's size for its column's kind and the largest magnitude shown
/// with it, its table column, which holds its vector's components: the unknowns' values,
/// rates or second rates; one of the points' columns (x, v_x, |v|, ...) over the points of
/// its dimension, its vector (position, velocity and speed, acceleration and magnitude)
/// over them all; a frame's angular velocity or acceleration over the frames; a block's
/// angle, rate or second rate over the blocks; a slider's relative velocity, relative
/// acceleration or Coriolis term over the sliders; a guide point's velocity or acceleration
/// over the guide points; a relative turning's rate or second rate over the turnings. The
/// input's values and a circuit's signs stand alone. NaN (undefined) counts for nothing.
class RowScales {
 public:
  RowScales(const ConstraintSystem& system, const std::vector<ResultColumn>& columns);
  /// The scales of `row`'s values (as many as the columns).
  std::vector<double> operator()(const double* row) const;

 private:
  // Values [begin, begin + count * sum(groups)) of a row as `count` entries, each cut into
  // vectors of the sizes in `groups`; `entries` lists where each entry begins.
  struct Section {
    std::vector<std::size_t> entries;
    std::vector<std::size_t> groups;
  };
  std::vector<Section> sections_;
  std::vector<double> sizes_;  ///< The problem's size for each column's kind.
};

}  // namespace kinema
