// The optional [problem] table (docs/problems.md), the same in every form of mechanism
// file: what a problem asks (find, at), what a problem set varies and the conditions
// every variant meets, and the grading tolerance. Names and values are read here as
// written; which names exist (output columns, parameters) engine/problems checks, with
// these lines in its messages.
#include <cmath>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "readers/file_reader.hpp"

namespace kinema::reading {
namespace {

// Most grid values of one varied parameter: a class's worth of variants needs tens.
constexpr double kMaxGridValues = 1e6;

// The unit a quantity is written in ("0.25 m" -> "m"); empty for a bare number.
std::string unit_of(const std::string& text) {
  const auto space = text.find_first_of(" \t");
  if (space == std::string::npos) return "";
  const auto start = text.find_first_not_of(" \t", space);
  return start == std::string::npos ? "" : text.substr(start);
}

class ProblemReader {
 public:
  ProblemReader(const FileReader& reader, Mechanism& mechanism) : r_(reader), mechanism_(mechanism) {}

  void read(const Node& table) {
    if (!table.is_table()) r_.fail(table, "[problem] must be a table");
    r_.check_keys(table, {"statement", "find", "at", "vary", "conditions", "tolerance", "sig_figs"}, "[problem]");
    Problem& problem = mechanism_.problem.emplace();
    problem.where = r_.where(table);
    problem.statement = r_.optional_string(table, "statement", "");
    read_find(table, problem);
    if (FileReader::has(table, "at")) {
      for (const Node* value : list(FileReader::at(table, "at"), "at", "[\"30 deg\", \"120 deg\"]", kMaxProblemAt))
        problem.at.push_back({r_.string_value(*value, "at"), r_.where(*value)});
    }
    if (FileReader::has(table, "vary")) read_vary(FileReader::at(table, "vary"), problem);
    if (FileReader::has(table, "conditions")) read_conditions(FileReader::at(table, "conditions"), problem.conditions);
    read_tolerance(table, problem);
  }

 private:
  const FileReader& r_;
  Mechanism& mechanism_;

  // A non-empty list's entries, at most `most` of them (checked before any is solved).
  std::vector<const Node*> list(const Node& value, const std::string& key, const std::string& example,
                                std::size_t most) const {
    if (!value.is_array() || value.as_array()->empty())
      r_.fail(value, "[problem] " + key + " must be a list of one or more entries, e.g. " + key + " = " + example);
    if (value.as_array()->size() > most)
      r_.fail(value, "[problem] " + key + " lists " + std::to_string(value.as_array()->size()) + " entries; a problem has at most " +
                         std::to_string(most) + " (each is answered on every variant's sheet and key): split it into several problems");
    std::vector<const Node*> entries;
    for (const auto& entry : *value.as_array()) entries.push_back(&entry);
    return entries;
  }

  void read_find(const Node& table, Problem& problem) const {
    if (!FileReader::has(table, "find"))
      throw InputError(problem.where.str() + ": [problem] needs find = [...], the quantities to find, e.g. "
                       "find = [\"omega3\", \"alpha3\"]");
    for (const Node* value : list(FileReader::at(table, "find"), "find", "[\"omega3\", \"alpha3\"]", kMaxProblemFind)) {
      if (!value->is_string()) r_.fail(*value, "[problem] find lists names of quantities as strings, e.g. \"omega3\"");
      problem.find.push_back({value->as_string()->get(), r_.where(*value)});
    }
  }

  // vary = { b = { range = ["0.25 m", "0.35 m"], step = "5 mm" }, ... }
  void read_vary(const Node& vary, Problem& problem) const {
    if (!vary.is_table()) r_.fail(vary, "[problem] vary must be a table, e.g. vary = { b = { range = [\"0.25 m\", \"0.35 m\"], step = \"5 mm\" } }");
    for (const auto& [name, entry] : r_.ordered(vary)) {
      const std::string context = "[problem] vary." + name;
      if (!entry->is_table()) r_.fail(*entry, context + " must be a table { range = [LOW, HIGH], step = STEP }");
      r_.check_keys(*entry, {"range", "step"}, context);
      if (!FileReader::has(*entry, "range") || !FileReader::has(*entry, "step"))
        r_.fail(*entry, context + " needs range = [LOW, HIGH] and step = STEP, e.g. range = [\"0.25 m\", \"0.35 m\"], step = \"5 mm\"");
      const Node& range = FileReader::at(*entry, "range");
      if (!range.is_array() || range.as_array()->size() != 2)
        r_.fail(range, context + ": range must list two values, the lowest and the highest, e.g. [\"0.25 m\", \"0.35 m\"]");
      const Node& low_node = *range.as_array()->get(0);
      const Quantity low = r_.quantity(low_node, "range");
      const Quantity high = r_.quantity(*range.as_array()->get(1), "range");
      const Quantity step = r_.quantity(FileReader::at(*entry, "step"), "step");
      if (low.dimension != high.dimension || low.dimension != step.dimension)
        r_.fail(range, context + ": the range's ends and the step must be of one kind (" +
                           dimension_name(low.dimension) + ", " + dimension_name(high.dimension) + ", " +
                           dimension_name(step.dimension) + ")");
      if (!(high.si_value > low.si_value))
        r_.fail(range, context + ": the range must go from the lower value to a higher one");
      if (!(step.si_value > 0))
        r_.fail(FileReader::at(*entry, "step"), context + ": the step must be positive");
      if ((high.si_value - low.si_value) / step.si_value > kMaxGridValues)
        r_.fail(FileReader::at(*entry, "step"), context + ": the step gives more than " +
                    format_significant(kMaxGridValues) + " values in the range; use a larger step");
      problem.vary.push_back({name, low.si_value, high.si_value, step.si_value, low.dimension,
                              unit_of(r_.string_value(low_node, "range")), r_.where(*entry)});
    }
  }

  void read_conditions(const Node& table, ProblemConditions& c) const {
    if (!table.is_table()) r_.fail(table, "[problem] conditions must be a table ([problem.conditions])");
    r_.check_keys(table, {"grashof", "min_transmission_angle", "assembles", "toggle_margin", "min_answer"},
                  "[problem.conditions]");
    if (FileReader::has(table, "grashof")) {
      const Node& value = FileReader::at(table, "grashof");
      c.grashof = r_.string_value(value, "grashof");
      c.grashof_where = r_.where(value);
      static const char* const kinds[] = {"crank-rocker", "double-crank", "rocker-crank", "double-rocker",
                                          "change point", "non-Grashof triple rocker"};
      bool known = false;
      std::string names;
      for (const char* kind : kinds) {
        known = known || c.grashof == kind;
        names += std::string(names.empty() ? "" : ", ") + "\"" + kind + "\"";
      }
      if (!known) r_.fail(value, "[problem.conditions] grashof = \"" + c.grashof + "\" is not a Grashof class; use one of " + names);
    }
    if (FileReader::has(table, "min_transmission_angle")) {
      const Node& value = FileReader::at(table, "min_transmission_angle");
      c.min_transmission_angle = r_.quantity_of(value, "min_transmission_angle", Dimension::angle);
      c.transmission_where = r_.where(value);
      if (!(*c.min_transmission_angle > 0 && *c.min_transmission_angle < kPi / 2))
        r_.fail(value, "min_transmission_angle must be between 0 and 90 deg");
    }
    if (FileReader::has(table, "assembles")) {
      const Node& value = FileReader::at(table, "assembles");
      if (!value.is_boolean() || !value.as_boolean()->get())
        r_.fail(value, "assembles = true is the only value: every variant must assemble at the asked values to have answers");
    }
    if (FileReader::has(table, "toggle_margin")) {
      const Node& value = FileReader::at(table, "toggle_margin");
      // An angle of the crank: toggles are found over its turn.
      const double margin = r_.quantity_of(value, "toggle_margin", Dimension::angle);
      if (!(margin > 0)) r_.fail(value, "toggle_margin must be positive, e.g. \"10 deg\"");
      c.toggle_margin = margin;
      c.toggle_where = r_.where(value);
    }
    if (FileReader::has(table, "min_answer")) {
      const Node& value = FileReader::at(table, "min_answer");
      const double least = value.value<double>().value_or(0);
      if (!value.is_number() || !(least > 0) || !std::isfinite(least))
        r_.fail(value, "min_answer must be a positive finite number (in the answers' output units), e.g. min_answer = 0.01");
      c.min_answer = value.value<double>().value_or(0);
      c.min_answer_where = r_.where(value);
    }
  }

  // tolerance = "1%" (relative) or sig_figs = 3, not both; default 1%.
  void read_tolerance(const Node& table, Problem& problem) const {
    const bool relative = FileReader::has(table, "tolerance"), figures = FileReader::has(table, "sig_figs");
    if (relative && figures)
      r_.fail(FileReader::at(table, "sig_figs"), "[problem] gives tolerance and sig_figs; give one of them");
    if (relative) {
      const Node& value = FileReader::at(table, "tolerance");
      const std::string text = r_.string_value(value, "tolerance");
      std::size_t used = 0;
      double percent = 0;
      try {
        percent = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      const std::string rest = text.substr(used);
      if (used == 0 || rest.find_first_not_of(" ") == std::string::npos || rest.substr(rest.find_first_not_of(" ")) != "%" ||
          !(percent > 0 && percent < 100))
        r_.fail(value, "tolerance = \"" + text + "\" is not a relative tolerance; write a percentage such as \"1%\"");
      problem.relative_tolerance = percent / 100;
    }
    if (figures) {
      const Node& value = FileReader::at(table, "sig_figs");
      const long long n = value.is_integer() ? value.as_integer()->get() : 0;
      if (n < 1 || n > 15) r_.fail(value, "sig_figs must be a whole number from 1 to 15, e.g. sig_figs = 3");
      problem.sig_figs = static_cast<int>(n);
    }
  }
};

}  // namespace

void FileReader::read_problem(const Node& root, Mechanism& mechanism) const {
  if (has(root, "problem")) ProblemReader(*this, mechanism).read(at(root, "problem"));
}

}  // namespace kinema::reading
