#include "engine/analysis/slider_ranges.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <thread>

#include "engine/analysis/resolving.hpp"
#include "engine/base/threads.hpp"
#include "engine/base/units.hpp"
#include "engine/numeric/sweep.hpp"

namespace kinema {

namespace {

// The grid the search walks out on from the file's value: a length's value times or over
// this ratio a step (the caps, 1/20 to 5 times, are 8 and 4 steps away), an angle's or a
// zero length's value this fraction of the caps' width a step.
constexpr double kLengthRatio = 1.5;
constexpr double kLinearStep = 1.0 / 16;

// What a run (or its values from `first` on) showed before it stopped: whether a value
// assembles (the first one, and the last of those after it that all do), whether one does not.
struct Assembly {
  bool any = false, all = true;
  std::size_t first_ok = 0, last_ok = 0;
};

// The rows searched over: every row, or where the run has more than kMaxSliderRangeRows, every
// k-th and the last (each probe solves the run again, tens of times a parameter).
std::vector<std::size_t> searched_rows(std::size_t count) {
  const std::size_t every = count > kMaxSliderRangeRows ? (count + kMaxSliderRangeRows - 1) / kMaxSliderRangeRows : 1;
  std::vector<std::size_t> rows;
  for (std::size_t row = 0; row < count; row += every) rows.push_back(row);
  if (count > 0 && rows.back() != count - 1) rows.push_back(count - 1);
  return rows;
}

// The assembly of the searched rows (indices among them).
Assembly assembly_of(const MotionTable& table, const std::vector<std::size_t>& searched) {
  Assembly a;
  for (std::size_t row = 0; row < searched.size(); ++row) {
    const bool ok = table.status(searched[row]) != Status::unassembled;
    if (ok && !a.any) a.first_ok = a.last_ok = row, a.any = true;
    if (ok && a.last_ok + 1 == row) a.last_ok = row;
    if (!ok) a.all = false;
  }
  return a;
}

// When a probe may stop: once the run has a value that assembles and one that does not
// (somewhere and everywhere both answered), at its first value that does not, at the first
// that does not after one that does (the values that assemble first, all known).
enum class Stop { answered, at_failure, after_success };

// The page's run solved again with one parameter at another value, the others at the
// file's (formula parameters following, by the resolving's formula tape), on a copy of the
// model's kinematics sharing its tape, value by value as the serial run solves them
// (RowSolver), so that a probe stops as soon as it has its answer.
class RunProbe {
 public:
  RunProbe(const Model& model, const Resolving& r, const std::vector<double>& inputs)
      : kinematics_(model.kinematics), resolving_(r), registers_(r.formulas.make_workspace()),
        followers_(r.formulas.output_count()), rows_(kinematics_),
        table_(inputs, kinematics_.unknown_count(), kinematics_.layout().point_dimensions,
               model.system.input.rate_value, model.system.input.second_rate_value, kinematics_.frame_count()) {
    for (const Resolving::Parameter& p : r.parameters) file_values_.push_back(p.value);
  }

  /// Parameter p at x, the run's values [first, last] (a run from the guesses there, as
  /// the serial run goes on after values that do not assemble) until `stop` says.
  Assembly solve(std::size_t p, double x, std::size_t first, std::size_t last, Stop stop) {
    std::vector<double> values = file_values_;
    values[p] = x;
    if (!followers_.empty()) {
      resolving_.formulas.evaluate(values.data(), followers_.data(), registers_);
      for (std::size_t k = 0; k < followers_.size(); ++k) values[resolving_.formula_targets[k]] = followers_[k];
    }
    kinematics_.set_parameter_values(values.data());
    rows_.start();
    Assembly a;
    for (std::size_t row = first; row <= last; ++row) {
      rows_.solve(table_, row);
      const bool ok = table_.status(row) != Status::unassembled;
      if (ok && !a.any) a.first_ok = a.last_ok = row, a.any = true;
      if (ok) a.last_ok = row;
      // A gap between two values (however narrow) stops the motion as one that holds a
      // value: the mechanism no longer runs through the whole run.
      if (!ok || table_.failure(row).kind == Failure::Kind::resumed_after_gap) a.all = false;
      if (stop == Stop::at_failure && !ok) break;
      if (stop == Stop::after_success && !ok && a.any) break;
      if (stop == Stop::answered && a.any && !a.all) break;
    }
    return a;
  }

 private:
  Kinematics kinematics_;
  const Resolving& resolving_;
  std::vector<double> file_values_, registers_, followers_;
  RowSolver rows_;
  MotionTable table_;
};

// The caps of a parameter's range (SliderRange's).
void set_caps(const Resolving::Parameter& p, double length_scale, SliderRange& range) {
  const double v = p.value;
  if (p.dimension == Dimension::angle) {
    range.cap_min = v - kPi, range.cap_max = v + kPi;
  } else if (v == 0) {
    range.cap_min = -length_scale, range.cap_max = length_scale;
  } else {
    range.cap_min = std::min(v / 20, 5 * v), range.cap_max = std::max(v / 20, 5 * v);
  }
}

// Step k of the grid from the file's value toward the upper (up) or lower cap, at most the cap.
double grid_value(const Resolving::Parameter& p, const SliderRange& range, bool up, int k) {
  const double v = p.value, cap = up ? range.cap_max : range.cap_min;
  double x;
  if (p.dimension == Dimension::angle || v == 0) {
    x = v + (up ? 1 : -1) * k * kLinearStep * (range.cap_max - range.cap_min);
  } else {
    const bool grows = up == (v > 0);  // away from zero
    x = grows ? v * std::pow(kLengthRatio, k) : v / std::pow(kLengthRatio, k);
  }
  return up ? std::min(x, cap) : std::max(x, cap);
}

// One side of a parameter's range: out from the file's value over the grid to the first
// value where the run assembles nowhere (or the cap), then the last values where it
// assembles somewhere and everywhere bisected to the tolerance. Where every value no
// longer assembles, fewer and fewer do toward the end: the search for one looks from the
// first that assembled at the last value that had one (the values before it do not
// assemble), and the bisection only at the values that assemble first there (the serial
// run solves them as it would after values that do not assemble, from the guesses). A run
// whose last values to close were others than those would end its range a little early:
// within where the mechanism assembles, as a slider's range must be.
void find_side(RunProbe& probe, std::size_t index, const Resolving::Parameter& p, const Assembly& at_file,
               std::size_t last_row, bool up, SliderRange& range) {
  const double cap = up ? range.cap_max : range.cap_min;
  double good_any = p.value, bad_any = cap, good_all = p.value, bad_all = cap;
  bool any_ends = false, all_ends = !at_file.all;
  Assembly window = at_file;
  for (int k = 1; !any_ends; ++k) {
    const double x = grid_value(p, range, up, k);
    const Assembly a = all_ends ? probe.solve(index, x, window.first_ok, last_row, Stop::after_success)
                                : probe.solve(index, x, 0, last_row, Stop::answered);
    if (!all_ends && a.all) good_all = x;
    if (!all_ends && !a.all) bad_all = x, all_ends = true;
    if (a.any) good_any = x, window = a;
    else bad_any = x, any_ends = true;
    if (x == cap) break;
  }
  const double tolerance = kSliderRangeTolerance * (range.cap_max - range.cap_min);
  if (at_file.all && good_all != cap) {
    while (std::fabs(bad_all - good_all) > tolerance) {
      const double x = 0.5 * (good_all + bad_all);
      (probe.solve(index, x, 0, last_row, Stop::at_failure).all ? good_all : bad_all) = x;
    }
  }
  if (any_ends) {
    // The values that assemble first at the last value found assembling, every one.
    window = probe.solve(index, good_any, window.first_ok, last_row, Stop::after_success);
    while (std::fabs(bad_any - good_any) > tolerance) {
      const double x = 0.5 * (good_any + bad_any);
      const Assembly a = probe.solve(index, x, window.first_ok, window.last_ok, Stop::after_success);
      if (a.any) good_any = x, window = a;
      else bad_any = x;
    }
  }
  (up ? range.max : range.min) = good_any;
  if (at_file.all) (up ? range.whole_max : range.whole_min) = good_all;
}

}  // namespace

std::vector<SliderRange> slider_ranges(const Model& model, const Resolving& resolving, const MotionTable& rows) {
  std::vector<SliderRange> ranges(resolving.parameters.size());
  std::vector<std::size_t> sliders;
  for (std::size_t p = 0; p < resolving.parameters.size(); ++p) {
    if (!resolving.parameters[p].slider) continue;
    set_caps(resolving.parameters[p], model.kinematics.length_scale(), ranges[p]);
    sliders.push_back(p);
  }
  const std::vector<std::size_t> searched = searched_rows(rows.size());
  const Assembly at_file = assembly_of(rows, searched);
  std::vector<double> inputs;
  for (std::size_t row : searched) inputs.push_back(rows.input(row));
  if (sliders.empty()) return ranges;
  if (!at_file.any) {  // nothing to search from: the caps
    for (std::size_t p : sliders) ranges[p].min = ranges[p].cap_min, ranges[p].max = ranges[p].cap_max;
    return ranges;
  }
  // The parameters' sides shared out among the cores, each thread with its own probe.
  std::atomic<std::size_t> next{0};
  const auto work = [&]() {
    RunProbe probe(model, resolving, inputs);
    for (std::size_t k = next++; k < 2 * sliders.size(); k = next++) {
      const std::size_t p = sliders[k / 2];
      find_side(probe, p, resolving.parameters[p], at_file, inputs.size() - 1, k % 2 == 1, ranges[p]);
    }
  };
  run_on_threads(std::max(1u, std::min(std::thread::hardware_concurrency(), 2u)), work);
  return ranges;
}

}  // namespace kinema
