#include "engine/analysis/design_study.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "engine/analysis/toggles.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/threads.hpp"
#include "engine/base/units.hpp"
#include "engine/constraints/output_columns.hpp"
#include "engine/numeric/design_lanes.hpp"
#include "engine/numeric/sweep.hpp"
#include "engine/numeric/tape.hpp"
#include "engine/numeric/workspace.hpp"

namespace kinema {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The parameter each varied name sets (its index in the system), the designs checked.
std::vector<std::size_t> varied_parameters(const ConstraintSystem& system, const Designs& designs) {
  if (designs.names.size() != designs.values.size())
    throw InputError("a design study: " + std::to_string(designs.names.size()) + " parameter names for " +
                     std::to_string(designs.values.size()) + " lists of values");
  std::vector<std::size_t> indices;
  for (std::size_t k = 0; k < designs.names.size(); ++k) {
    const std::string& name = designs.names[k];
    const std::size_t index = written_parameter_index(system, name);  // names the file's parameters when not one
    if (std::find(indices.begin(), indices.end(), index) != indices.end())
      throw InputError("a design study: parameter \"" + name + "\" is given twice");
    if (designs.values[k].size() != designs.size())
      throw InputError("a design study: " + std::to_string(designs.values[k].size()) + " values of \"" + name + "\" but " +
                       std::to_string(designs.size()) + " of \"" + designs.names.front() + "\" (one value of each a design)");
    for (std::size_t i = 0; i < designs.values[k].size(); ++i) {
      if (!std::isfinite(designs.values[k][i]))
        throw InputError(system.source_file + ": parameter \"" + name + "\" = " + format_significant(designs.values[k][i]) +
                         " in design " + std::to_string(i) + " is not a finite number");
    }
    indices.push_back(index);
  }
  return indices;
}

// What every design shares, set up once: the parameter values of the model, the varied
// ones' places, and one small tape (compiled once for the study) giving from the
// parameter values the formula parameters that follow them and a four-bar's side lengths.
struct StudySetup {
  const Model* base = nullptr;  // the model as with_parameters has it (a joints file solved by Newton)
  std::vector<std::size_t> varied;
  std::vector<double> values;                // SI, every parameter, the model's
  std::vector<std::size_t> following;        // formula parameters that follow the varied ones
  std::optional<FourBarLoop> loop;           // a four-bar's sides (lengths from the tape's outputs)
  CompiledExpressions tape;                  // outputs: the following parameters, then the four sides
  bool has_tape = false;
  double length_unit = 1;                    // SI metres per output length unit (Grashof's check)
  std::vector<std::size_t> stroke_unknowns;  // candidates for the time ratio, in order
  std::size_t turn_rows = 0;                 // rows of the run's first full turn (0: none)
  // A four-bar's points as terms that turn with one variable (DesignLanes' rates in closed
  // form), each one's length and angle offset among the tape's outputs from point_outputs
  // on; empty (closed_points false) where a point is not such a sum.
  std::vector<ClosedPointTerm> point_terms;
  std::size_t point_outputs = 0;
  bool closed_points = false;
};

StudySetup set_up(const Model& base, const Designs& designs, const std::vector<double>& inputs,
                  const StudyOptions& options) {
  const ConstraintSystem& system = base.system;
  StudySetup setup;
  setup.base = &base;
  setup.varied = varied_parameters(system, designs);
  for (const SystemParameter& p : system.parameters) setup.values.push_back(p.value);
  // Formula parameters in terms of the free ones (each earlier formula substituted).
  GiNaC::exmap resolved;
  std::vector<GiNaC::ex> symbols, outputs;
  for (std::size_t i = 0; i < system.parameters.size(); ++i) {
    const SystemParameter& p = system.parameters[i];
    symbols.push_back(p.symbol);
    const bool varied = std::find(setup.varied.begin(), setup.varied.end(), i) != setup.varied.end();
    if (!p.formula || varied) continue;
    resolved[p.symbol] = p.formula->subs(resolved);
    setup.following.push_back(i);
    outputs.push_back(resolved[p.symbol]);
  }
  // A four-bar's sides: its figures, and its loop's reach (the values that cannot close
  // told without Newton in the lanes).
  setup.loop = four_bar_loop(system);
  if (setup.loop) {
    for (const FourBarSide* side : {&setup.loop->ground, &setup.loop->crank, &setup.loop->coupler, &setup.loop->rocker})
      outputs.push_back(side->length.subs(resolved));
    outputs.push_back(setup.loop->ground.angle.subs(resolved));
    setup.point_outputs = outputs.size();
    const std::optional<std::vector<MovingPointTerm>> moving = moving_point_terms(system);
    setup.closed_points = moving && !designs.names.empty();
    for (std::size_t t = 0; setup.closed_points && t < moving->size(); ++t) {
      const MovingPointTerm& term = (*moving)[t];
      setup.point_terms.push_back({term.point, term.variable});
      outputs.push_back(term.length.subs(resolved));
      outputs.push_back(term.offset.subs(resolved));
    }
  }
  if (!outputs.empty() && !designs.names.empty()) {
    setup.tape = CompiledExpressions(symbols, outputs);
    setup.has_tape = true;
  }
  setup.length_unit = OutputScale(system).length;
  // The time ratio as slider_strokes and a rocker's limits have it: over a crank's turn.
  const double turn = 2 * kPi;
  if (options.wants(StudyFigure::time_ratio) && system.input.dimension == Dimension::angle && system.frames.empty() &&
      system.unknowns.size() <= kMaxStrokeUnknowns && system.input.rate_value != 0 && !inputs.empty() &&
      std::fabs(inputs.back() - inputs.front()) >= turn * (1 - 1e-12)) {
    if (setup.loop) {
      setup.stroke_unknowns.push_back(setup.loop->rocker.unknown);
    } else {
      for (std::size_t j = 0; j < system.unknowns.size(); ++j)
        if (system.unknowns[j].dimension == Dimension::length) setup.stroke_unknowns.push_back(j);
    }
    while (setup.turn_rows < inputs.size() &&
           std::fabs(inputs[setup.turn_rows] - inputs.front()) <= turn * (1 + 1e-12))
      ++setup.turn_rows;
  }
  return setup;
}

// The largest |value| of a column over the rows whose status is ok; NaN with none.
double largest_magnitude(const MotionTable& table, const double* column) {
  double largest = kNaN;
  for (std::size_t row = 0; row < table.size(); ++row)
    if (table.status(row) == Status::ok && !(std::fabs(column[row]) <= largest)) largest = std::fabs(column[row]);
  return largest;
}

// The largest length of a point's velocity or acceleration (components `first` on) over
// the rows whose status is ok.
double largest_vector(const MotionTable& table, std::size_t p, std::size_t dimension, std::size_t first) {
  double largest = kNaN;
  const double* x = table.point_column(p, first);
  const double* y = table.point_column(p, first + 1);
  const double* z = dimension == 3 ? table.point_column(p, first + 2) : nullptr;
  for (std::size_t row = 0; row < table.size(); ++row) {
    if (table.status(row) != Status::ok) continue;
    const double length = vector_length(x[row], y[row], z ? z[row] : 0.0);
    if (!(length <= largest)) largest = length;
  }
  return largest;
}

// The crank angles (rad, in (-pi, 2 pi)) where a four-bar's rocker stops: its crank and
// coupler in line, stretched out or folded (their terms' sum L e^(i input), L = crank
// +- coupler), where |L e^(i input) + ground| is the rocker's length; on either assembly,
// up to four. The count.
int rocker_stops(const FourBarLoopValues& loop, double stops[4]) {
  const double gx = loop.ground.value * std::cos(loop.ground.angle_value);
  const double gy = loop.ground.value * std::sin(loop.ground.angle_value);
  const double g = std::hypot(gx, gy), towards = std::atan2(gy, gx), rocker = loop.rocker.value;
  int count = 0;
  for (const double in_line : {loop.crank.value + loop.coupler.value, loop.crank.value - loop.coupler.value}) {
    // L^2 + 2 L g cos(input - towards) + g^2 = rocker^2.
    const double cosine = (rocker * rocker - in_line * in_line - g * g) / (2 * in_line * g);
    if (!(std::fabs(cosine) <= 1)) continue;
    const double off = std::acos(cosine);
    stops[count++] = towards + off;
    stops[count++] = towards - off;
  }
  return count;
}

// The one rocker stop between two rows' inputs (on the assembly run: it has one there,
// its rate changing sign), NaN where there is not exactly one.
double rocker_stop_between(const double* stops, int count, double from, double to) {
  const double low = std::min(from, to), high = std::max(from, to), turn = 2 * kPi;
  double found = kNaN;
  int inside = 0;
  for (int k = 0; k < count; ++k) {
    const double at = stops[k] + turn * std::ceil((low - stops[k]) / turn);  // the first at or after low
    if (at <= high) found = at, ++inside;
  }
  return inside == 1 ? found : kNaN;
}

// One thread's designs: its own kinematics (sharing the tape), sweep, workspaces and
// buffers, made once and reused design after design.
class DesignRunner {
 public:
  DesignRunner(const StudySetup& setup, const std::vector<double>& inputs, const StudyOptions& options)
      : setup_(setup),
        options_(options),
        kinematics_(setup.base->kinematics),
        values_(setup.values),
        tape_outputs_(setup.has_tape ? setup.tape.output_count() : 0),
        tape_registers_(setup.has_tape ? setup.tape.make_workspace() : std::vector<double>{}),
        rates_(inputs.size()),
        inputs_(inputs) {
    SweepSettings settings;
    settings.rate = setup.base->system.input.rate_value;
    settings.second_rate = setup.base->system.input.second_rate_value;
    sweep_ = std::make_unique<RepeatedSweep>(kinematics_, inputs, settings);
    if (!setup.stroke_unknowns.empty()) limits_ = std::make_unique<Workspace>(kinematics_);
    if (setup.loop) loop_ = setup.loop->values();
    if (options.across_designs && solves() && settings.rate != 0 && !inputs.empty()) {
      lanes_ = std::make_unique<DesignLanes>(kinematics_, inputs, settings.rate, settings.second_rate);
      lanes_->set_positions_and_rates_only(true);  // summarise reads no more of a lane's rows
      if (setup.closed_points) lanes_->set_point_terms(setup.point_terms);
      lane_designs_.resize(DesignLanes::kLanes);
    }
  }

  /// Design `design` solved alone.
  void run(const Designs& designs, std::size_t design, StudyResults& results) {
    const GrashofClass kind = load_design(designs, design, results);
    kinematics_.set_parameter_values(values_.data());
    if (!solves()) return;
    summarise(sweep_->solve(), kind, design, results);
  }

  /// Whether designs go kLanes at a time to run_lanes: a run predicted by the input's rate.
  bool uses_lanes() const { return lanes_ != nullptr; }

  /// Designs [first, first + count), count <= kLanes, solved together, one to a lane.
  void run_lanes(const Designs& designs, std::size_t first, std::size_t count, StudyResults& results) {
    for (std::size_t l = 0; l < count; ++l) {
      lane_designs_[l].kind = load_design(designs, first + l, results);
      lane_designs_[l].values = values_;
      lane_designs_[l].loop = loop_;
      lanes_->set_design(l, values_.data());
      lanes_->set_reach(l, loop_reach());
      if (vector_loop()) lanes_->set_closure(l, loop_closure());
      lanes_->set_angle_measure(l, loop_.coupler.unknown, loop_.rocker.unknown,
                                lane_designs_[l].kind != GrashofClass::none ? transmission_offset() : kNaN);
      if (vector_loop() && setup_.closed_points) lanes_->set_point_term_values(l, point_factors_.data());
    }
    lanes_->solve(count);
    lane_values_ += lanes_->lane_values();
    for (std::size_t l = 0; l < count; ++l) {
      const LaneDesign& lane = lane_designs_[l];
      kinematics_.set_parameter_values(lane.values.data());  // for the time ratio's refinement
      loop_ = lane.loop;
      summarise(lanes_->table(l), lane.kind, first + l, results, l);
    }
  }

  std::uint64_t lane_values() const { return lane_values_; }

 private:
  // The design's parameter values into values_ (formula ones following), its four-bar
  // sides into loop_; its class (into the results when asked for).
  GrashofClass load_design(const Designs& designs, std::size_t design, StudyResults& results) {
    for (std::size_t k = 0; k < setup_.varied.size(); ++k) values_[setup_.varied[k]] = designs.values[k][design];
    if (setup_.has_tape) {
      setup_.tape.evaluate(values_.data(), tape_outputs_.data(), tape_registers_);
      for (std::size_t f = 0; f < setup_.following.size(); ++f) values_[setup_.following[f]] = tape_outputs_[f];
    }
    GrashofClass kind = GrashofClass::none;
    if (setup_.loop) {
      const double* sides = tape_outputs_.data() + setup_.following.size();
      if (setup_.has_tape) {
        loop_.ground.value = sides[0], loop_.crank.value = sides[1], loop_.coupler.value = sides[2], loop_.rocker.value = sides[3];
        loop_.ground.angle_value = sides[4];
      }
      kind = grashof_class(loop_.ground.value, loop_.crank.value, loop_.coupler.value, loop_.rocker.value,
                           setup_.length_unit);
      // Each moving point term's factor, length e^(i offset).
      point_factors_.resize(2 * setup_.point_terms.size());
      for (std::size_t t = 0; t < setup_.point_terms.size(); ++t) {
        const double length = tape_outputs_[setup_.point_outputs + 2 * t];
        const double offset = tape_outputs_[setup_.point_outputs + 2 * t + 1];
        point_factors_[2 * t] = length * std::cos(offset);
        point_factors_[2 * t + 1] = length * std::sin(offset);
      }
    }
    if (options_.wants(StudyFigure::grashof)) results.grashof[design] = kind;
    return kind;
  }

  // The loop closure and reach of the design loaded: a vector-loop four-bar's (not one
  // placed in closed form, whose failures the scalar run tells otherwise); no reach for
  // other mechanisms.
  bool vector_loop() const { return setup_.loop && kinematics_.closed_form() == nullptr; }
  LoopClosure loop_closure() const {
    const double ground_angle = loop_.ground.angle_value;
    return LoopClosure{loop_.crank.value,   loop_.ground.value * std::cos(ground_angle),
                       loop_.ground.value * std::sin(ground_angle),
                       loop_.coupler.value, loop_.rocker.value,
                       loop_.coupler.unknown, loop_.rocker.unknown};
  }
  LoopReach loop_reach() const {
    if (!vector_loop()) return {};
    const LoopClosure c = loop_closure();
    return LoopReach(c.crank, c.fixed_x, c.fixed_y, c.first, c.second);
  }

  // |rocker - coupler + this| wrapped to [-pi, pi] (angle_magnitude) is what
  // transmission_angle gives (in degrees): the direction from the rocker's edge to the
  // coupler's back, pi (2 pi where one of their lengths is written negative).
  double transmission_offset() const { return (loop_.coupler.value < 0) == (loop_.rocker.value < 0) ? kPi : 0; }

  bool solves() const {
    for (StudyFigure f : {StudyFigure::min_transmission_angle, StudyFigure::time_ratio, StudyFigure::assembles,
                          StudyFigure::max_rates, StudyFigure::max_second_rates, StudyFigure::max_speeds,
                          StudyFigure::max_accelerations})
      if (options_.wants(f)) return true;
    return false;
  }

  // The figures of a design from its table; a lane's (`lane` < kLanes) largest rates and
  // points' from the lanes, which keep them as values are solved (no scan of the table).
  void summarise(const MotionTable& table, GrashofClass kind, std::size_t design, StudyResults& results,
                 std::size_t lane = DesignLanes::kLanes) {
    const bool from_lanes = lane < DesignLanes::kLanes;
    if (options_.wants(StudyFigure::assembles)) {
      std::uint32_t failed = 0;
      for (std::size_t row = 0; row < table.size(); ++row) failed += table.status(row) == Status::unassembled;
      results.failed_values[design] = failed;
      results.assembles[design] = failed == 0;
    }
    if (options_.wants(StudyFigure::min_transmission_angle)) {
      double least = kNaN;
      if (kind != GrashofClass::none) {  // as four_bar_figures: no figures where there is nothing to classify
        // The row where the angle is least by a measure without trigonometry, its angle
        // as transmission_angle gives it (the least of every row's, to rounding); the
        // lanes keep it as they solve.
        double coupler_angle = kNaN, rocker_angle = kNaN;
        if (from_lanes) {
          lanes_->least_measure_angles(lane, coupler_angle, rocker_angle);
        } else {
          const double* coupler = table.q_column(loop_.coupler.unknown);
          const double* rocker = table.q_column(loop_.rocker.unknown);
          double least_measure = kNaN;
          for (std::size_t row = 0; row < table.size(); ++row) {
            if (table.status(row) == Status::unassembled) continue;
            const double measure = angle_magnitude(rocker[row] - coupler[row] + transmission_offset());
            if (!(measure >= least_measure)) least_measure = measure, coupler_angle = coupler[row], rocker_angle = rocker[row];
          }
        }
        if (!std::isnan(coupler_angle)) least = transmission_angle(loop_, coupler_angle, rocker_angle);
      }
      results.min_transmission_angle[design] = least * kPi / 180;
    }
    const std::size_t n = table.unknown_count();
    for (std::size_t i = 0; i < n; ++i) {
      if (options_.wants(StudyFigure::max_rates))
        results.max_rate[i][design] = from_lanes ? lanes_->largest_rate(lane, i) : largest_magnitude(table, table.qd_column(i));
      if (options_.wants(StudyFigure::max_second_rates))
        results.max_second_rate[i][design] =
            from_lanes ? lanes_->largest_second_rate(lane, i) : largest_magnitude(table, table.qdd_column(i));
    }
    const std::vector<std::size_t>& dimensions = kinematics_.layout().point_dimensions;
    for (std::size_t p = 0; p < dimensions.size(); ++p) {
      if (options_.wants(StudyFigure::max_speeds))
        results.max_speed[p][design] = from_lanes ? lanes_->largest_speed(lane, p)
                                                  : largest_vector(table, p, dimensions[p], dimensions[p]);
      if (options_.wants(StudyFigure::max_accelerations))
        results.max_acceleration[p][design] = from_lanes ? lanes_->largest_acceleration(lane, p)
                                                         : largest_vector(table, p, dimensions[p], 2 * dimensions[p]);
    }
    if (options_.wants(StudyFigure::time_ratio)) results.time_ratio[design] = time_ratio(table, lane);
  }

  // The time ratio of the first candidate unknown with exactly two limit positions over
  // the run's first turn (find_limit_positions' refinement, set_strokes' ratio); a lane's
  // (`lane` < kLanes) rows from the lanes.
  double time_ratio(const MotionTable& table, std::size_t lane) {
    if (setup_.stroke_unknowns.empty()) return kNaN;
    const bool from_lanes = lane < DesignLanes::kLanes;
    const double rate = table.input_rate();
    const std::size_t rows = setup_.turn_rows;
    bool reloaded = false;
    for (std::size_t j : setup_.stroke_unknowns) {
      if (from_lanes) {
        lanes_->rates_at_ok_rows(lane, j, rows, rates_.data());
      } else {
        for (std::size_t row = 0; row < rows; ++row)
          rates_[row] = table.status(row) == Status::ok ? table.qd_column(j)[row] : kNaN;
      }
      std::size_t changes = 0;
      for (std::size_t row = 0; row < rows; ++row) {
        rates_[row] /= rate;
        if (row > 0 && (rates_[row - 1] == 0 || rates_[row - 1] * rates_[row] < 0)) ++changes;
      }
      if (changes < 2 || changes > 3) continue;  // two limits (one more where one lies on a row twice round)
      if (!reloaded) limits_->reload_parameters();
      reloaded = true;
      // A four-bar's rocker stops in closed form; others (and a bracket with none or two
      // of them) refined by the scalar solver.
      double stops[4];
      const int stop_count = setup_.loop ? rocker_stops(loop_, stops) : 0;
      const KnownLimit known = [&](double from, double to) { return rocker_stop_between(stops, stop_count, from, to); };
      const RowPosition position = [&](std::size_t row) {
        return from_lanes ? lanes_->position(lane, row) : Eigen::VectorXd(table.q(row));
      };
      const std::vector<Toggle> limits = limit_positions_in_turn(inputs_.data(), position, rows, rates_.data(), j,
                                                                 *limits_, setup_.loop ? known : KnownLimit{});
      if (limits.size() != 2) continue;
      Strokes strokes;
      for (const Toggle& limit : limits) strokes.limit_inputs.push_back(limit.input * 180 / kPi);
      set_strokes(strokes, setup_.base->system.input.rate_value);
      return strokes.time_ratio;
    }
    return kNaN;
  }

  const StudySetup& setup_;
  const StudyOptions& options_;
  Kinematics kinematics_;  // this thread's, its parameter values the design's
  std::vector<double> values_, tape_outputs_, tape_registers_, rates_, point_factors_;
  const std::vector<double>& inputs_;
  std::unique_ptr<RepeatedSweep> sweep_;
  std::unique_ptr<Workspace> limits_;
  FourBarLoopValues loop_;
  // Designs across lanes: what each lane's design needs summed up after the run.
  struct LaneDesign {
    GrashofClass kind = GrashofClass::none;
    std::vector<double> values;
    FourBarLoopValues loop;
  };
  std::unique_ptr<DesignLanes> lanes_;
  std::vector<LaneDesign> lane_designs_;
  std::uint64_t lane_values_ = 0;
};

// Room for one value of each figure asked for per design.
StudyResults sized_results(const Model& model, std::size_t designs, const StudyOptions& options) {
  StudyResults r;
  const std::size_t n = model.kinematics.unknown_count(), points = model.kinematics.point_count();
  if (options.wants(StudyFigure::grashof)) r.grashof.assign(designs, GrashofClass::none);
  if (options.wants(StudyFigure::min_transmission_angle)) r.min_transmission_angle.assign(designs, kNaN);
  if (options.wants(StudyFigure::time_ratio)) r.time_ratio.assign(designs, kNaN);
  if (options.wants(StudyFigure::assembles)) {
    r.assembles.assign(designs, 0);
    r.failed_values.assign(designs, 0);
  }
  if (options.wants(StudyFigure::max_rates)) r.max_rate.assign(n, std::vector<double>(designs, kNaN));
  if (options.wants(StudyFigure::max_second_rates)) r.max_second_rate.assign(n, std::vector<double>(designs, kNaN));
  if (options.wants(StudyFigure::max_speeds)) r.max_speed.assign(points, std::vector<double>(designs, kNaN));
  if (options.wants(StudyFigure::max_accelerations)) r.max_acceleration.assign(points, std::vector<double>(designs, kNaN));
  return r;
}

}  // namespace

void check_study_size(std::size_t designs, std::size_t values, const std::string& asked) {
  if (designs > kMaxStudyDesigns)
    throw InputError(asked + ": " + std::to_string(designs) + " designs, more than the " + std::to_string(kMaxStudyDesigns) +
                     " a study may have; vary fewer parameters or give larger steps");
  if (values != 0 && designs > kMaxStudyValues / values)
    throw InputError(asked + ": " + std::to_string(designs) + " designs of " + std::to_string(values) + " values each, " +
                     "more than the " + std::to_string(kMaxStudyValues) + " values a study may solve; give fewer designs "
                     "or a larger step of the run");
}

std::size_t design_grid_size(const std::vector<std::size_t>& sizes) {
  std::size_t count = sizes.empty() ? 0 : 1;
  for (const std::size_t size : sizes) {  // counted without overflow
    if (size != 0 && count > kMaxStudyDesigns / size) {
      std::string shown;
      for (const std::size_t s : sizes) shown += (shown.empty() ? "" : " x ") + std::to_string(s);
      throw InputError("a design study of " + shown + " designs: more than the " + std::to_string(kMaxStudyDesigns) +
                       " a study may have; vary fewer parameters or give larger steps");
    }
    count *= size;
  }
  return count;
}

Designs design_grid(const std::vector<std::string>& names, const std::vector<std::vector<double>>& axes) {
  Designs grid;
  grid.names = names;
  std::vector<std::size_t> sizes;
  for (const std::vector<double>& axis : axes) sizes.push_back(axis.size());
  const std::size_t count = design_grid_size(sizes);  // refused before any is held
  grid.values.assign(axes.size(), std::vector<double>(count));
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t rest = i;
    for (std::size_t k = axes.size(); k-- > 0;) {  // the last name varies fastest
      grid.values[k][i] = axes[k][rest % axes[k].size()];
      rest /= axes[k].size();
    }
  }
  return grid;
}

std::vector<std::pair<std::string, StudyFigure>> study_figure_fields(const ConstraintSystem& system) {
  std::vector<std::pair<std::string, StudyFigure>> fields{{"grashof", StudyFigure::grashof},
                                                          {"min_transmission_angle", StudyFigure::min_transmission_angle},
                                                          {"time_ratio", StudyFigure::time_ratio},
                                                          {"assembles", StudyFigure::assembles},
                                                          {"failed_values", StudyFigure::assembles}};
  const std::vector<ResultColumn> table = result_columns(system, OutputScale(system));
  for (std::size_t j = 0; j < system.unknowns.size(); ++j) {
    fields.emplace_back("max_abs_" + table[kInputColumns + 3 * j + 1].name, StudyFigure::max_rates);
    fields.emplace_back("max_abs_" + table[kInputColumns + 3 * j + 2].name, StudyFigure::max_second_rates);
  }
  for (const PointObservable& point : system.points) {
    fields.emplace_back("max_" + point.name + "_speed", StudyFigure::max_speeds);
    fields.emplace_back("max_" + point.name + "_acceleration", StudyFigure::max_accelerations);
  }
  return fields;
}

std::vector<StudyColumn> study_columns(const ConstraintSystem& system, const Designs& designs,
                                       const StudyResults& results, StudyUnits units) {
  const OutputScale scale(system);
  const bool si = units == StudyUnits::si;
  // The unit and factor (SI per shown unit) of a quantity of a dimension, and of its rates.
  const auto length_unit = [&] { return si ? std::string("m") : scale.length_unit; };
  const auto shown = [&](std::vector<double> values, double factor) {
    if (factor != 1)
      for (double& v : values) v /= factor;
    return values;
  };
  std::vector<StudyColumn> columns;
  const auto add = [&](StudyColumn::Kind kind, std::string name, std::string unit, std::vector<double> values) {
    columns.push_back({kind, std::move(name), std::move(unit), std::move(values)});
  };
  for (std::size_t k = 0; k < designs.names.size(); ++k) {
    const SystemParameter& p = system.parameters[written_parameter_index(system, designs.names[k])];
    const bool length = p.dimension == Dimension::length, angle = p.dimension == Dimension::angle;
    const double factor = si ? 1 : length ? scale.length : angle ? kRadiansPerDegree : 1;
    add(StudyColumn::Kind::real, designs.names[k], length ? length_unit() : angle ? (si ? "rad" : "deg") : "",
        shown(designs.values[k], factor));
  }
  // The figures' fields in study_figure_fields' order: each unknown's rate and second rate,
  // then each point's speed and acceleration, counted as they come.
  std::size_t rate = 0, second_rate = 0, speed = 0, acceleration = 0;
  const double length_factor = si ? 1 : scale.length;
  const auto unknown_rate = [&](std::size_t j, const std::vector<std::vector<double>>& values, bool second,
                                std::string name) {
    const Dimension dimension = system.unknowns[j].dimension;
    const bool length = dimension == Dimension::length;
    const std::string unit = si ? (length ? "m" : "rad") + std::string(second ? "/s^2" : "/s")
                                : second ? scale.second_rate_unit(dimension) : scale.rate_unit(dimension);
    if (!values.empty()) add(StudyColumn::Kind::real, std::move(name), unit, shown(values[j], length ? length_factor : 1));
  };
  for (auto& [name, figure] : study_figure_fields(system)) {
    switch (figure) {
      case StudyFigure::grashof:
        if (!results.grashof.empty())
        {
          std::vector<double> codes;
          for (GrashofClass kind : results.grashof) codes.push_back(static_cast<double>(kind));
          add(StudyColumn::Kind::grashof, name, "", std::move(codes));
        }
        break;
      case StudyFigure::min_transmission_angle:
        if (!results.min_transmission_angle.empty())
          add(StudyColumn::Kind::real, name, si ? "rad" : "deg",
              shown(results.min_transmission_angle, si ? 1 : kRadiansPerDegree));
        break;
      case StudyFigure::time_ratio:
        if (!results.time_ratio.empty()) add(StudyColumn::Kind::real, name, "", results.time_ratio);
        break;
      case StudyFigure::assembles:
        if (results.assembles.empty()) break;
        if (name == "assembles")
          add(StudyColumn::Kind::flag, name, "", std::vector<double>(results.assembles.begin(), results.assembles.end()));
        else
          add(StudyColumn::Kind::count, name, "", std::vector<double>(results.failed_values.begin(), results.failed_values.end()));
        break;
      case StudyFigure::max_rates: unknown_rate(rate++, results.max_rate, false, name); break;
      case StudyFigure::max_second_rates: unknown_rate(second_rate++, results.max_second_rate, true, name); break;
      case StudyFigure::max_speeds:
        if (!results.max_speed.empty())
          add(StudyColumn::Kind::real, name, length_unit() + "/s", shown(results.max_speed[speed], length_factor));
        ++speed;
        break;
      case StudyFigure::max_accelerations:
        if (!results.max_acceleration.empty())
          add(StudyColumn::Kind::real, name, length_unit() + "/s^2",
              shown(results.max_acceleration[acceleration], length_factor));
        ++acceleration;
        break;
      case StudyFigure::kCount: break;
    }
  }
  return columns;
}

StudyResults run_design_study(const Model& model, const Designs& designs, const std::vector<double>& inputs,
                              const StudyOptions& options) {
  varied_parameters(model.system, designs);  // refused before anything else
  check_study_size(designs.size(), inputs.size(), "a design study");
  const Model base = with_parameters(model, {});
  const StudySetup setup = set_up(base, designs, inputs, options);
  const std::size_t count = designs.size();
  StudyResults results = sized_results(model, count, options);
  if (count == 0) return results;
  // Designs handed out a few at a time (their cost varies: a design that does not
  // assemble solves its values one by one), a lane's worth where they go in lanes.
  constexpr std::size_t kDesignsATurn = 8;
  std::atomic<std::size_t> next{0};
  std::atomic<std::uint64_t> lane_values{0};
  const auto work = [&]() {
    DesignRunner runner(setup, inputs, options);
    const std::size_t turn = runner.uses_lanes() ? DesignLanes::kLanes : kDesignsATurn;
    for (std::size_t first = next.fetch_add(turn); first < count; first = next.fetch_add(turn)) {
      if (options.cancelled && options.cancelled()) throw Cancelled("a design study: cancelled by its caller");
      const std::size_t last = std::min(count, first + turn);
      if (runner.uses_lanes()) {
        runner.run_lanes(designs, first, last - first, results);
        continue;
      }
      for (std::size_t design = first; design < last; ++design) runner.run(designs, design, results);
    }
    lane_values += runner.lane_values();
  };
  const unsigned threads = static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(options.threads, count)));
  run_on_threads(threads, work, [&] { next = count; });
  results.lane_values = lane_values;
  return results;
}

}  // namespace kinema
