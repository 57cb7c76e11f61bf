#include "engine/problems/answer_check.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <map>

#include "engine/analysis/output_scale.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/user_text.hpp"
#include "engine/input_value.hpp"
#include "engine/problems/design_answers.hpp"
#include "engine/problems/mistake_catalogue.hpp"

namespace kinema {

namespace {

bool is_rate_name(const ConstraintSystem& system, const std::string& name) {
  return name == system.input.rate.get_name() || name == system.input.second_rate.get_name();
}

// What a column measures, from its output unit; nullopt for one of no unit a value can carry.
std::optional<Dimension> column_dimension(const std::string& unit, const OutputScale& scale) {
  const std::string& l = scale.length_unit;
  if (unit == "deg") return Dimension::angle;
  if (unit == "rad/s") return Dimension::angular_velocity;
  if (unit == "rad/s^2") return Dimension::angular_acceleration;
  if (unit == l) return Dimension::length;
  if (unit == l + "/s") return Dimension::velocity;
  if (unit == l + "/s^2") return Dimension::acceleration;
  return std::nullopt;
}

// A value in SI of that dimension in the output unit of its column.
double in_output_unit(double si, Dimension dimension, const OutputScale& scale) {
  switch (dimension) {
    case Dimension::angle: return to_degrees(si);
    case Dimension::length:
    case Dimension::velocity:
    case Dimension::acceleration: return si / scale.length;
    default: return si;
  }
}

// An angle compares to whole turns (350 deg is -10 deg): `given` moved by whole turns to
// the nearest of `reference`.
double nearest_turn(double given, double reference, const std::string& unit) {
  if (unit != "deg" || !std::isfinite(given) || !std::isfinite(reference)) return given;
  return reference + std::remainder(given - reference, 360.0);
}

bool within(const AnswerTolerance& tolerance, double given, double reference, const std::string& unit) {
  return tolerance.accepts(nearest_turn(given, reference, unit), reference);
}

// The answer's value in the column's unit; a bare number is taken as that unit.
void read_given(const WrittenAnswer& answer, const OutputScale& scale, AnswerVerdict& verdict) {
  Quantity q;
  try {
    q = parse_quantity(answer.value);
  } catch (const UnitError& error) {
    throw UnitError(answer.where.str() + ": value of " + answer.quantity + ": " + error.what());
  }
  verdict.given = answer.value;
  if (q.dimension == Dimension::number) {
    verdict.given_value = q.si_value;
    verdict.unit_assumed = true;
    return;
  }
  const std::optional<Dimension> wanted = column_dimension(verdict.unit, scale);
  if (!wanted || q.dimension != *wanted) {
    throw UnitError(answer.where.str() + ": value \"" + one_line(answer.value) + "\" is " +
                    with_article(dimension_name(q.dimension)) + ", but " + answer.quantity + " is " +
                    (wanted ? with_article(dimension_name(*wanted)) + " (" + verdict.unit + ")"
                            : "in " + verdict.unit + " (write the number alone)"));
  }
  verdict.given_value = in_output_unit(q.si_value, q.dimension, scale);
}

// The input value an answer is at: as written, else the key's for its quantity, else the
// file's one value.
void read_at(const CheckSubject& subject, const WrittenAnswer& answer, AnswerVerdict& verdict) {
  const ConstraintSystem& system = subject.model->system;
  if (!answer.at.empty()) {
    try {
      verdict.at_si = parse_input_value(system, answer.at);
    } catch (const InputError& error) {
      throw UnitError(answer.where.str() + ": at of " + answer.quantity + ": " + error.what());
    }
    verdict.at = answer.at;
    return;
  }
  std::vector<const ClassAnswer*> keyed;
  for (const ClassAnswer& asked : subject.asked) {
    try {
      if (answer_column(system, asked.quantity, {}) == verdict.column) keyed.push_back(&asked);
    } catch (const InputError&) {  // a key's quantity this file does not know names no answer here
    }
  }
  if (keyed.size() == 1) {
    verdict.at_si = keyed[0]->at_si;
    verdict.at = keyed[0]->at;
    return;
  }
  if (keyed.empty() && system.input.values.size() == 1) {
    const OutputScale scale(system);
    verdict.at_si = system.input.values[0];
    verdict.at = format_significant(scale.input(verdict.at_si), 6) + " " + scale.coordinate_unit(system.input.dimension);
    return;
  }
  throw InputError(answer.where.str() + ": " + answer.quantity + " without at; write the input value the answer is for " +
                   "(at = \"30 deg\" in TOML, the second field in CSV)");
}

// What one input value's answers are checked against: the solved row, and each mistake's
// rows once a wrong answer asks for them.
struct Evaluated {
  EvaluationPoint point;
  SolvedRow correct;
  std::optional<std::vector<std::vector<MistakenRow>>> mistakes;
};

Evaluated& evaluated_at(std::map<double, Evaluated>& cache, const CheckSubject& subject, const AnswerVerdict& verdict) {
  const auto found = cache.find(verdict.at_si);
  if (found != cache.end()) return found->second;
  try {  // one angle limit for every command: what eval refuses is not graded
    check_input_range(subject.model->system, std::vector<double>{verdict.at_si});
  } catch (const InputError& error) {
    throw InputError(verdict.where.str() + ": " + verdict.quantity + " at " + verdict.at + ": " + error.what());
  }
  const EvaluationPoint point{subject.model, verdict.at_si, subject.rate, subject.second_rate, subject.rate_text};
  SolvedRow correct;
  try {
    correct = solve_row(point);
  } catch (const AssemblyError& error) {
    throw AssemblyError(verdict.where.str() + ": " + verdict.quantity + " at " + verdict.at + ": " + error.what());
  } catch (const SingularPositionError& error) {
    throw SingularPositionError(verdict.where.str() + ": " + verdict.quantity + " at " + verdict.at + ": " + error.what());
  }
  return cache.emplace(verdict.at_si, Evaluated{point, std::move(correct), std::nullopt}).first->second;
}

// The mistakes whose value gives the answer (and not the right one), catalogue order.
std::vector<MistakeMatch> matching_mistakes(Evaluated& evaluated, std::size_t column, const AnswerVerdict& verdict,
                                            const AnswerTolerance& tolerance) {
  const std::vector<Mistake>& catalogue = mistake_catalogue();
  if (!evaluated.mistakes) {
    evaluated.mistakes.emplace();
    for (const Mistake& mistake : catalogue) evaluated.mistakes->push_back(mistake.rows(evaluated.point, evaluated.correct));
  }
  std::vector<MistakeMatch> matches;
  for (std::size_t m = 0; m < catalogue.size(); ++m) {
    for (const MistakenRow& row : (*evaluated.mistakes)[m]) {
      const double value = row.values[column];
      if (!std::isfinite(value) || within(tolerance, value, verdict.expected, verdict.unit)) continue;
      if (!within(tolerance, verdict.given_value, value, verdict.unit)) continue;
      matches.push_back({catalogue[m].name, catalogue[m].words, row.detail, value});
      break;  // one way of making each mistake is enough to name it
    }
  }
  return matches;
}

// Words compared as a person would: case and spaces around them aside ("Crank-Rocker ").
std::string folded(const std::string& text) {
  const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
  std::string out = first == std::string::npos ? "" : text.substr(first, last - first + 1);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// A design figure's answer: once for the mechanism (no at), a number within the tolerance
// or a class in words. No mistake of the catalogue is sought: it is made at an input value.
AnswerVerdict figure_verdict(const CheckSubject& subject, const WrittenAnswer& answer,
                             std::optional<std::vector<DesignAnswer>>& figures, const AnswerTolerance& tolerance) {
  const ConstraintSystem& system = subject.model->system;
  if (!answer.at.empty())
    throw InputError(answer.where.str() + ": " + answer.quantity + " is a design figure of the whole mechanism; "
                     "write it without at");
  if (!figures) figures = design_answers(*subject.model);
  const std::optional<DesignAnswer> figure = design_answer(*figures, answer.quantity);
  if (!figure) {
    std::string names;
    for (const DesignAnswer& f : *figures) names += (names.empty() ? "" : ", ") + f.name;
    throw InputError(answer.where.str() + ": " + system.source_file + " has no design figure \"" +
                     one_line(answer.quantity) + "\"" + (names.empty() ? "" : "; its figures: " + names));
  }
  AnswerVerdict verdict;
  verdict.where = answer.where;
  verdict.quantity = verdict.column = answer.quantity;
  verdict.figure = true;
  verdict.unit = figure->unit;
  if (!figure->text.empty()) {
    verdict.given = answer.value;
    verdict.given_value = verdict.expected = std::numeric_limits<double>::quiet_NaN();
    verdict.expected_text = figure->text;
    verdict.right = folded(answer.value) == folded(figure->text);
    return verdict;
  }
  read_given(answer, OutputScale(system), verdict);
  verdict.expected = figure->value;
  verdict.right = within(tolerance, verdict.given_value, verdict.expected, verdict.unit);
  return verdict;
}

}  // namespace

CheckSubject file_subject(const Model& model) {
  CheckSubject subject;
  subject.model = &model;
  subject.source = model.system.source_file;
  subject.rate = model.system.input.rate_value;
  subject.second_rate = model.system.input.second_rate_value;
  subject.rate_text = model.system.input.rate_text;
  return subject;
}

Model variant_model(const Model& source, const ClassTable& table, const ClassVariant& variant) {
  std::vector<std::pair<std::string, double>> values;
  for (const ClassParameter& p : variant.parameters)
    if (!is_rate_name(source.system, p.name)) values.emplace_back(p.name, p.si);
  try {
    return with_parameters(source, values);
  } catch (const InputError& error) {
    throw InputError(table.path + ": variant " + std::to_string(variant.number) + ": " + error.what());
  }
}

CheckSubject variant_subject(const Model& model, const ClassTable& table, const ClassVariant& variant) {
  CheckSubject subject = file_subject(model);
  subject.source = table.source;
  subject.variant = variant.number;
  subject.asked = variant.answers;
  for (const ClassParameter& p : variant.parameters) {
    if (p.name == model.system.input.rate.get_name()) {
      subject.rate = p.si;
      subject.rate_text = p.unit.empty() ? p.value : p.value + " " + p.unit;
    } else if (p.name == model.system.input.second_rate.get_name()) {
      subject.second_rate = p.si;
    }
  }
  return subject;
}

std::string answer_column(const ConstraintSystem& system, const std::string& quantity, const SourceLocation& where) {
  const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system));
  for (const ResultColumn& c : columns)
    if (c.name == quantity) return c.name;
  // vP, aP: a point's speed and acceleration magnitude, as textbooks write them.
  for (const PointObservable& p : system.points) {
    if (quantity == "v" + p.name) return p.name + "_speed";
    if (quantity == "a" + p.name) return p.name + "_acceleration";
  }
  std::string names;
  for (const ResultColumn& c : columns) names += (names.empty() ? "" : ", ") + c.name;
  throw InputError((where.line > 0 ? where.str() + ": " : "") + "unknown quantity \"" + one_line(quantity) +
                   "\"; the quantities of " + system.source_file + ": " + names +
                   " (and vP, aP for a point P's speed and acceleration)");
}

CheckReport check_answers(const CheckSubject& subject, const AnswersFile& answers, const AnswerTolerance& tolerance) {
  const ConstraintSystem& system = subject.model->system;
  const OutputScale scale(system);
  const std::vector<ResultColumn> columns = result_columns(system, scale);
  CheckReport report{answers.path, subject.source, subject.variant, tolerance, {}};
  std::map<double, Evaluated> cache;
  std::optional<std::vector<DesignAnswer>> figures;  // a turn's solve: once, when one is answered
  for (const WrittenAnswer& answer : answers.answers) {
    const bool column_named = [&] {
      for (const ResultColumn& c : columns)
        if (c.name == answer.quantity) return true;
      return false;
    }();
    if (!column_named && is_design_figure_name(answer.quantity)) {
      report.verdicts.push_back(figure_verdict(subject, answer, figures, tolerance));
      continue;
    }
    AnswerVerdict verdict;
    verdict.where = answer.where;
    verdict.quantity = answer.quantity;
    verdict.column = answer_column(system, answer.quantity, answer.where);
    std::size_t column = 0;
    while (columns[column].name != verdict.column) ++column;
    verdict.unit = columns[column].unit;
    read_given(answer, scale, verdict);
    read_at(subject, answer, verdict);
    Evaluated& evaluated = evaluated_at(cache, subject, verdict);
    verdict.expected = evaluated.correct.values[column];
    verdict.right = within(tolerance, verdict.given_value, verdict.expected, verdict.unit);
    if (!verdict.right) verdict.mistakes = matching_mistakes(evaluated, column, verdict, tolerance);
    report.verdicts.push_back(std::move(verdict));
  }
  return report;
}

}  // namespace kinema
