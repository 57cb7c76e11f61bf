// The design figures a problem's `find` may name (issue 37): figures of the whole
// mechanism (engine/analysis/design_figures), asked once per variant, not at an input
// value. Their names are those Model.study uses (engine/analysis/design_study).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/model.hpp"

namespace kinema {

/// A figure's value: a number in `unit` (its SI value in `si`), or a class in words
/// (`text`, the Grashof class; value and si NaN then).
struct DesignAnswer {
  std::string name;
  double si = 0.0;
  double value = 0.0;
  std::string unit;  ///< "deg", the output length unit, or "" for a ratio.
  std::string text;
};

/// Every figure name `find` knows, whether or not a given mechanism has it.
bool is_design_figure_name(const std::string& name);

/// The figures `model` has: grashof, min_transmission_angle, max_transmission_angle for a
/// four-bar driven by its crank; stroke_S and time_ratio_S of each slider S with two limit
/// positions over a whole turn of the crank, and stroke and time_ratio of the first slider
/// with limit positions when it has two (none where it has four: it turns back on its way).
std::vector<DesignAnswer> design_answers(const Model& model);

/// Why a mechanism has not figure `name` (a name is_design_figure_name knows), as the
/// redraw report of a problem set counts it: "no stroke (not two limit positions over a whole turn)".
std::string missing_figure_reason(const std::string& name);

/// The figure `name` of `answers`, nothing when the mechanism has none of that name.
std::optional<DesignAnswer> design_answer(const std::vector<DesignAnswer>& answers, const std::string& name);

}  // namespace kinema
