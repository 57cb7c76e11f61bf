#include "engine/problems/problem_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/problem_scale.hpp"
#include "engine/analysis/toggles.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/constraints/output_columns.hpp"
#include "engine/input_value.hpp"
#include "engine/problems/design_answers.hpp"

namespace kinema {

std::uint64_t ProblemDraws::below_or_equal(std::uint64_t n) {
  if (n == std::numeric_limits<std::uint64_t>::max()) return engine_();
  // Rejection from the largest multiple of n + 1: every integer equally likely, and the
  // mapping ours (the same on every machine), not the standard library's.
  const std::uint64_t span = n + 1;
  const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % span;
  std::uint64_t x = engine_();
  while (x >= limit) x = engine_();
  return x % span;
}

double ProblemTolerance::absolute(double value) const {
  if (sig_figs <= 0) return std::fabs(value) * relative;
  if (value == 0) return 0;
  // Half a unit of the last significant figure.
  return 0.5 * std::pow(10.0, std::floor(std::log10(std::fabs(value))) - sig_figs + 1);
}

namespace {

// The unit a quantity is written in ("0.150 m" -> "m"); empty for a bare number or a formula.
std::string written_unit(const std::string& text) {
  if (!looks_like_quantity(text)) return "";
  const auto space = text.find_first_of(" \t");
  if (space == std::string::npos) return "";
  const auto start = text.find_first_not_of(" \t", space);
  return start == std::string::npos ? "" : text.substr(start);
}

// SI per one `unit` (1 for none).
double unit_factor(const std::string& unit) { return unit.empty() ? 1.0 : parse_quantity("1 " + unit).si_value; }

// A column's index by a find name: an output column, or vP / aP of a point P.
std::optional<std::size_t> column_of(const ConstraintSystem& system, const std::vector<ResultColumn>& columns,
                                     const std::string& name) {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k].name == name) return k;
  for (const PointObservable& p : system.points) {
    const std::string column = name == "v" + p.name ? p.name + "_speed" : name == "a" + p.name ? p.name + "_acceleration" : "";
    if (column.empty()) continue;
    for (std::size_t k = 0; k < columns.size(); ++k)
      if (columns[k].name == column) return k;
  }
  return std::nullopt;
}

// What a vary entry sets.
enum class VaryKind { parameter, driver_value, driver_rate };

struct VaryTarget {
  const ProblemVary* vary = nullptr;
  VaryKind kind = VaryKind::parameter;
  std::string unit;  ///< The unit the given value is shown in (the file's).
  std::uint64_t steps = 0;  ///< Grid values low + k step, k in [0, steps].
};

VaryTarget vary_target(const ConstraintSystem& system, const ProblemVary& vary) {
  VaryTarget target{&vary, VaryKind::parameter, vary.unit,
                    static_cast<std::uint64_t>(std::floor((vary.high - vary.low) / vary.step * (1 + 1e-12)))};
  const std::string at = vary.where.str() + ": [problem] vary." + vary.name + ": ";
  Dimension expected = Dimension::number;
  if (vary.name == system.input.name) {
    target.kind = VaryKind::driver_value;
    expected = system.input.dimension;
  } else if (vary.name == system.input.rate.get_name()) {
    target.kind = VaryKind::driver_rate;
    expected = rate_dimension(system.input.dimension);
    if (!written_unit(system.input.rate_text).empty()) target.unit = written_unit(system.input.rate_text);
  } else {
    std::size_t index = 0;
    try {
      index = written_parameter_index(system, vary.name);
    } catch (const InputError& error) {
      throw InputError(at + error.what() + "; or vary the driver's value (" + system.input.name + ") or rate (" +
                       system.input.rate.get_name() + ")");
    }
    const SystemParameter& parameter = system.parameters[index];
    expected = parameter.dimension;
    if (!written_unit(parameter.text).empty()) target.unit = written_unit(parameter.text);
  }
  if (expected != Dimension::number && vary.dimension != expected)
    throw InputError(at + "the range is " + with_article(dimension_name(vary.dimension)) + ", but \"" + vary.name +
                     "\" is " + with_article(dimension_name(expected)));
  if (!target.unit.empty() && parse_quantity("1 " + target.unit).dimension != vary.dimension) target.unit = vary.unit;
  return target;
}

// The asked values (SI) and their texts: [problem] at, else the file's input values.
void asked_values(const ConstraintSystem& system, const Problem& problem, std::vector<double>& at,
                  std::vector<std::string>& texts) {
  for (const ProblemAt& value : problem.at) {
    try {
      at.push_back(parse_input_value(system, value.text));
      check_input_range(system, std::vector<double>{at.back()});
    } catch (const std::exception& error) {
      throw InputError(value.where.str() + ": [problem] at = \"" + value.text + "\": " + error.what());
    }
    texts.push_back(value.text);
  }
  if (!problem.at.empty()) return;
  const OutputScale scale(system);
  for (double si : system.input.values) {
    at.push_back(si);
    texts.push_back(format_significant(scale.input(si), 12) + " " + scale.coordinate_unit(system.input.dimension));
  }
  if (at.empty())
    throw InputError(problem.where.str() + ": [problem] needs at = [...], the input values the answers are asked at "
                     "(the file gives none), e.g. at = [\"30 deg\"]");
  if (at.size() > kMaxProblemAt)
    throw InputError(problem.where.str() + ": [problem] is asked at the file's " + std::to_string(at.size()) +
                     " input values; a problem has at most " + std::to_string(kMaxProblemAt) +
                     ": give at = [...] with the values the answers are asked at");
}

// Refuses conditions the mechanism has no figure for, before any draw.
void check_conditions_apply(const Model& model, const Problem& problem) {
  const ProblemConditions& c = problem.conditions;
  if ((!c.grashof.empty() || c.min_transmission_angle) && !four_bar_figures(model)) {
    const SourceLocation& at = c.grashof.empty() ? c.transmission_where : c.grashof_where;
    throw InputError(at.str() + ": [problem.conditions] " + (c.grashof.empty() ? "min_transmission_angle" : "grashof") +
                     " is for a four-bar driven by its crank (one loop of four links); this mechanism is not one");
  }
  if (c.toggle_margin && model.system.input.dimension != Dimension::angle)
    throw InputError(c.toggle_where.str() + ": [problem.conditions] toggle_margin is for a crank-driven mechanism "
                     "(its toggles over a turn); this one's input is not an angle");
  if (problem.find.empty()) throw InputError(problem.where.str() + ": [problem] find lists no quantity");
}

// Every find name known (a design figure one the mechanism has), else InputError at its
// line listing the names.
void check_find_names(const Model& model, const Problem& problem) {
  const ConstraintSystem& system = model.system;
  const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system));
  std::optional<std::vector<DesignAnswer>> figures;  // a turn's solve: only when a figure is asked
  for (const ProblemFind& find : problem.find) {
    if (column_of(system, columns, find.name)) continue;
    if (is_design_figure_name(find.name)) {
      if (!figures) figures = design_answers(model);
      if (design_answer(*figures, find.name)) continue;
    }
    std::string names;
    for (const std::string& name : find_names(system)) names += (names.empty() ? "" : ", ") + name;
    if (!figures) figures = design_answers(model);
    for (const DesignAnswer& figure : *figures) names += ", " + figure.name;
    throw InputError(find.where.str() + ": [problem] find: no quantity \"" + find.name +
                     "\" in this mechanism; the names are: " + names);
  }
}

// The order the redraw report names conditions in: assembling, then the figures asked that
// a variant lacks, then [problem.conditions].
std::vector<std::string> condition_names(const Problem& problem) {
  std::vector<std::string> names = {"assembles"};
  for (const ProblemFind& f : problem.find) {
    const std::string reason = missing_figure_reason(f.name);
    if (is_design_figure_name(f.name) && std::find(names.begin(), names.end(), reason) == names.end()) names.push_back(reason);
  }
  for (const char* name : {"grashof", "min_transmission_angle", "toggle_margin", "min_answer"}) names.push_back(name);
  return names;
}

// The digits after the point that write every value of a range's grid in `factor`'s unit
// alike: those of its step and of its low end (a 5 mm step in m: 3, so 0.380 beside 0.385).
int grid_decimals(const ProblemVary& vary, double factor) {
  int decimals = 0;
  for (const double v : {vary.step / factor, vary.low / factor})
    for (int d = decimals; d <= 9; ++d) {
      const double scaled = std::fabs(v) * std::pow(10.0, d);
      if (std::fabs(scaled - std::round(scaled)) <= 1e-6 * std::max(1.0, scaled)) {
        decimals = d;
        break;
      }
    }
  return decimals;
}

// A draw of every varied value on its grid, set into a copy of the model.
struct Draw {
  std::vector<GivenValue> given;
  std::vector<std::pair<std::string, double>> parameters;
  std::optional<std::pair<double, std::string>> driver_value;  ///< SI and its text.
  std::optional<std::pair<double, std::string>> driver_rate;
};

Draw draw_values(const std::vector<VaryTarget>& targets, ProblemDraws& draws) {
  Draw draw;
  for (const VaryTarget& t : targets) {
    const double factor = unit_factor(t.unit);
    // The grid value as the file would write it in its unit (12 digits: no 0.30000000000000004).
    const double value = round_significant((t.vary->low + double(draws.below_or_equal(t.steps)) * t.vary->step) / factor, 12);
    const double si = value * factor;
    draw.given.push_back({t.vary->name, si, value, t.unit, grid_decimals(*t.vary, factor)});
    const std::string text = format_significant(value, 12) + (t.unit.empty() ? "" : " " + t.unit);
    if (t.kind == VaryKind::parameter) draw.parameters.emplace_back(t.vary->name, si);
    if (t.kind == VaryKind::driver_value) draw.driver_value.emplace(si, text);
    if (t.kind == VaryKind::driver_rate) draw.driver_rate.emplace(si, text);
  }
  return draw;
}

}  // namespace

std::vector<std::string> find_names(const ConstraintSystem& system) {
  std::vector<std::string> names;
  for (const ResultColumn& column : result_columns(system, OutputScale(system))) names.push_back(column.name);
  for (const PointObservable& p : system.points) {
    names.push_back("v" + p.name);
    names.push_back("a" + p.name);
  }
  return names;
}

std::vector<ProblemAnswer> problem_answers(const Model& variant, const std::vector<ProblemFind>& find,
                                           const std::vector<double>& at, const std::vector<std::string>& at_texts) {
  const ConstraintSystem& system = variant.system;
  const OutputScale scale(system);
  OutputScale si_scale = scale;  // lengths in metres; angles still in degrees (converted below)
  si_scale.length = 1.0;
  const std::vector<ResultColumn> columns = result_columns(system, scale);
  const MotionTable table = solve_motion(variant, at);
  std::vector<double> shown(columns.size()), si(columns.size());
  std::vector<ProblemAnswer> answers;
  const RowScales row_scales(system, columns);
  for (std::size_t row = 0; row < table.size(); ++row) {
    result_values(system, scale, table, row, shown.data());
    result_values(system, si_scale, table, row, si.data());
    const std::vector<double> with = row_scales(shown.data());
    for (const ProblemFind& f : find) {
      if (is_design_figure_name(f.name) && !column_of(system, columns, f.name)) continue;
      const std::size_t k = *column_of(system, columns, f.name);
      const double in_si = columns[k].unit == "deg" ? from_degrees(si[k]) : si[k];
      answers.push_back({f.name, row < at_texts.size() ? at_texts[row] : "", at[row], in_si, shown[k], columns[k].unit, "", false, with[k]});
    }
  }
  std::optional<std::vector<DesignAnswer>> figures;
  for (const ProblemFind& f : find) {
    if (!is_design_figure_name(f.name) || column_of(system, columns, f.name)) continue;
    if (!figures) figures = design_answers(variant);
    const std::optional<DesignAnswer> figure = design_answer(*figures, f.name);
    // A variant without the figure (a four-bar drawn into no four-bar cannot be: the
    // names are checked on the file) answers NaN, which min_answer refuses.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    answers.push_back(figure ? ProblemAnswer{f.name, "", 0.0, figure->si, figure->value, figure->unit, figure->text, true}
                             : ProblemAnswer{f.name, "", 0.0, nan, nan, "", "", true});
  }
  return answers;
}

std::vector<std::string> failed_conditions(const Model& variant, const Problem& problem, const std::vector<double>& at) {
  std::vector<std::string> failed;
  const MotionTable table = solve_motion(variant, at);
  for (std::size_t row = 0; row < table.size(); ++row) {
    if (table.status(row) != Status::ok) return {"assembles"};  // the other figures need it to move there
  }
  // A figure asked that this variant has not (a slider that turns back twice a turn has no
  // one stroke): always refused, as the figure it lacks.
  std::optional<std::vector<DesignAnswer>> figures;
  std::set<std::string> missing;
  for (const ProblemFind& f : problem.find) {
    if (!is_design_figure_name(f.name)) continue;
    if (!figures) figures = design_answers(variant);
    if (design_answer(*figures, f.name) || !missing.insert(f.name).second) continue;
    failed.push_back(missing_figure_reason(f.name));
  }
  const ProblemConditions& c = problem.conditions;
  if (!c.grashof.empty() || c.min_transmission_angle) {
    const std::optional<FourBarFigures> figures = four_bar_figures(variant);
    if (!c.grashof.empty() && (!figures || figures->grashof != c.grashof)) failed.push_back("grashof");
    if (c.min_transmission_angle) {
      const double least = to_degrees(*c.min_transmission_angle);
      // Within [least, 180 - least] over the whole turn (NaN where it does not turn fully fails).
      if (!figures || !(figures->least_transmission >= least && figures->greatest_transmission <= 180 - least))
        failed.push_back("min_transmission_angle");
    }
  }
  if (c.toggle_margin) {
    // Near a toggle or a slider's limit position the rates are large or change sense: no
    // fair problem either way.
    std::vector<double> folds;
    for (const Toggle& toggle : find_toggles(variant)) folds.push_back(toggle.input);
    for (const Strokes& s : slider_strokes(variant))  // every limit position, however many
      for (double limit : s.limit_inputs) folds.push_back(from_degrees(limit));
    bool near = false;
    for (double fold : folds)
      for (double value : at) near = near || std::fabs(std::remainder(value - fold, 2 * kPi)) < *c.toggle_margin;
    if (near) failed.push_back("toggle_margin");
  }
  if (c.min_answer) {
    bool small = false;
    for (const ProblemAnswer& answer : problem_answers(variant, problem.find, at, {})) {
      if (answer.figure && missing.count(answer.quantity)) continue;  // counted as missing above
      small = small || (answer.text.empty() && !(std::fabs(answer.value) >= *c.min_answer));
    }
    if (small) failed.push_back("min_answer");
  }
  return failed;
}

ProblemSet make_problem_set(const Model& model, const Problem& problem, std::size_t count, std::uint64_t seed) {
  const ConstraintSystem& system = model.system;
  if (count == 0 || count > kMaxProblemVariants)
    throw InputError("--count " + std::to_string(count) + ": a set has from 1 to " + std::to_string(kMaxProblemVariants) +
                     " variants");
  check_find_names(model, problem);
  std::vector<VaryTarget> targets;
  for (const ProblemVary& vary : problem.vary) targets.push_back(vary_target(system, vary));
  check_conditions_apply(model, problem);
  std::vector<double> file_at;
  std::vector<std::string> file_texts;
  asked_values(system, problem, file_at, file_texts);

  ProblemSet set;
  set.statement = problem.statement;
  set.seed = seed;
  set.count = count;
  set.tolerance = {problem.relative_tolerance, problem.sig_figs};
  std::map<std::string, std::size_t> refused;
  ProblemDraws draws(seed);
  std::size_t draws_since_met = 0;
  while (set.variants.size() < count) {
    if (draws_since_met >= kMaxDrawsPerVariant) {
      std::string why;
      for (const std::string& name : condition_names(problem))
        if (refused.count(name)) why += (why.empty() ? "" : ", ") + name + " " + std::to_string(refused[name]);
      throw InputError(problem.where.str() + ": [problem]: only " + std::to_string(set.variants.size()) + " of " +
                       std::to_string(count) + " variants met the conditions in " + std::to_string(set.draws) +
                       " draws, the last " + std::to_string(kMaxDrawsPerVariant) + " in a row meeting none (refused by: " +
                       why + "); widen the ranges or loosen [problem.conditions]");
    }
    ++set.draws;
    ++draws_since_met;
    Draw draw = draw_values(targets, draws);
    ProblemVariant variant;
    variant.model = with_parameters(model, draw.parameters);
    if (draw.driver_rate) {
      variant.model.system.input.rate_value = draw.driver_rate->first;
      variant.model.system.input.rate_text = draw.driver_rate->second;
    }
    variant.at = draw.driver_value ? std::vector<double>{draw.driver_value->first} : file_at;
    variant.at_texts = draw.driver_value ? std::vector<std::string>{draw.driver_value->second} : file_texts;
    variant.model.system.input.values = variant.at;  // what its worked solution states the driver at
    const std::vector<std::string> failed = failed_conditions(variant.model, problem, variant.at);
    if (!failed.empty()) {
      for (const std::string& name : failed) ++refused[name];
      continue;
    }
    draws_since_met = 0;
    variant.number = static_cast<int>(set.variants.size()) + 1;
    variant.given = std::move(draw.given);
    variant.answers = problem_answers(variant.model, problem.find, variant.at, variant.at_texts);
    set.variants.push_back(std::move(variant));
  }
  for (const std::string& name : condition_names(problem))
    if (refused.count(name)) set.redrawn.emplace_back(name, refused[name]);
  return set;
}

}  // namespace kinema
