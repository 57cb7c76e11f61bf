// The web page's dimension sliders' ranges (issue 35): for each parameter a slider moves,
// where the mechanism assembles over the page's run of input values, the other parameters
// at the file's values (formula parameters following). Found by solving the run again
// with the parameter moved, as the sweep solves it (engine/numeric/sweep RepeatedSweep: the
// serial run from the file's guesses), computed once by the analysis.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "engine/model.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

struct Resolving;

/// One parameter's range (SI). [min, max]: the values around the file's where the run
/// assembles at one input value at least (each end refined by bisection where it is not a
/// cap); [whole_min, whole_max] within it: where every input value assembles (NaN where the
/// file's own dimensions leave a value unassembled). The caps: a length keeps the file's
/// sign and goes from 1/20 to 5 times the file's value (a length written 0: plus or minus the
/// length scale); an angle goes half a turn either way of the file's value.
struct SliderRange {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double min = kNaN, max = kNaN;
  double whole_min = kNaN, whole_max = kNaN;
  double cap_min = kNaN, cap_max = kNaN;  ///< The caps the range was searched within.
};

/// Relative width (of the caps' interval) to which each end found is bisected.
constexpr double kSliderRangeTolerance = 1e-7;

/// Most values of the run the ranges are searched over: a longer run (a page holds 20,000)
/// is searched over every k-th value and its last, at most this many (a turn at 1 deg) (a probe solves the run
/// again, and a parameter takes tens of probes), so a page of any length is written in
/// seconds. Where the run is thinned so, the bands are the thinned run's.
constexpr std::size_t kMaxSliderRangeRows = 360;

/// The range of every parameter `resolving` gives a slider (default ranges, NaN, for the
/// others), over the run of `rows` (the page's table at the file's dimensions; thinned to
/// kMaxSliderRangeRows values).
std::vector<SliderRange> slider_ranges(const Model& model, const Resolving& resolving, const MotionTable& rows);

}  // namespace kinema
