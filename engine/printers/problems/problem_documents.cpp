#include "engine/printers/problems/problem_documents.hpp"

#include <nlohmann/json.hpp>

#include <set>
#include <sstream>

#include "engine/analysis/output_scale.hpp"
#include "engine/base/naming.hpp"
#include "engine/base/number_format.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/latex/tikz_mechanism.hpp"

namespace kinema {
namespace {

// A CSV field, quoted where it holds a separator, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv_row(const std::vector<std::string>& fields) {
  std::string row;
  for (std::size_t k = 0; k < fields.size(); ++k) row += (k ? "," : "") + csv_field(fields[k]);
  return row + "\n";
}

// "b [mm]" and "omega3 @ 30 deg [rad/s]": the columns' headings.
std::string given_heading(const GivenValue& g) { return g.name + (g.unit.empty() ? "" : " [" + g.unit + "]"); }
std::string answer_heading(const ProblemAnswer& a) {
  if (a.figure) return a.quantity + (a.unit.empty() ? "" : " [" + a.unit + "]");
  return a.quantity + " @ " + a.at_text + " [" + a.unit + "]";
}

// An answer in a table: a number, or a class in words.
std::string answer_field(const ProblemAnswer& a) { return a.text.empty() ? format_round_trip(a.value) : a.text; }

// Headings of the given values and answers, from the first variant (every variant asks alike).
std::vector<std::string> headings(const ProblemSet& set, bool tolerances) {
  std::vector<std::string> row = {"variant"};
  if (set.variants.empty()) return row;
  const ProblemVariant& first = set.variants.front();
  for (const GivenValue& g : first.given) row.push_back(given_heading(g));
  for (std::size_t k = 0; k < first.answers.size(); ++k) {
    // A driver value that varies makes "at" differ per variant: headed by the answer's place.
    const ProblemAnswer& a = first.answers[k];
    const bool same_at = [&] {
      for (const ProblemVariant& v : set.variants)
        if (v.answers[k].at_text != a.at_text) return false;
      return true;
    }();
    const std::string heading = same_at ? answer_heading(a) : a.quantity + " [" + a.unit + "]";
    row.push_back(heading);
    if (tolerances) row.push_back(heading + " tolerance");
  }
  return row;
}

std::string tolerance_text(const ProblemTolerance& t) {
  return t.sig_figs > 0 ? std::to_string(t.sig_figs) + " significant figures"
                        : format_significant(t.relative * 100, 6) + "% relative";
}

// A unit in math mode: "\mathrm{rad/s^{2}}". Units are those kinema reads (parse_quantity
// refused any other) or prints: letters, /, ^ and digits only.
std::string latex_unit(const std::string& unit) {
  std::string text;
  for (std::size_t k = 0; k < unit.size(); ++k) {
    const bool power = unit[k] == '^' && k + 1 < unit.size();
    text += power ? "^{" + std::string(1, unit[k + 1]) + "}" : std::string(1, unit[k]);
    k += power ? 1 : 0;
  }
  return "\\mathrm{" + text + "}";
}

// A varied value's number with the digits of its grid, as the file writes its other values
// (0.380 m): the sheet and the Moodle question give it alike.
std::string given_number(const GivenValue& g) { return format_fixed(g.value, g.decimals); }

// A varied value in math mode as the sheet gives it ("0.380\,\mathrm{m}").
std::string latex_given(const GivenValue& g) {
  return given_number(g) + (g.unit.empty() ? "" : "\\," + latex_unit(g.unit));
}

// A design figure in math mode, in words: its name is no symbol of the mechanism.
std::string figure_latex(const std::string& name) {
  if (name == "grashof") return "\\text{Grashof class}";
  if (name == "min_transmission_angle") return "\\mu_{\\min}";
  if (name == "max_transmission_angle") return "\\mu_{\\max}";
  const bool stroke = name.rfind("stroke", 0) == 0;
  const std::string of = name.size() > (stroke ? 6u : 10u) ? name.substr(stroke ? 7 : 11) : "";
  return std::string(stroke ? "\\text{stroke}" : "\\text{time ratio}") +
         (of.empty() ? "" : "\\text{ of }" + latex_symbol_name(of));
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string problem_quantity_latex(const ConstraintSystem& system, const std::string& name) {
  std::vector<const Coordinate*> coordinates = {&system.input};
  for (const Coordinate& q : system.unknowns) coordinates.push_back(&q);
  for (const Coordinate* q : coordinates) {
    if (q->symbol.get_name() == name) return to_latex(q->symbol);
    if (q->rate.get_name() == name) return to_latex(q->rate);
    if (q->second_rate.get_name() == name) return to_latex(q->second_rate);
  }
  for (const PointObservable& p : system.points) {
    const std::string point = latex_symbol_name(p.name);
    if (name == "v" + p.name || name == p.name + "_speed") return "v_{" + point + "}";
    if (name == "a" + p.name || name == p.name + "_acceleration") return "a_{" + point + "}";
  }
  return "\\mathrm{" + latex_escape_text(name) + "}";
}

std::string problem_answers_latex(const ConstraintSystem& system, const std::vector<ProblemAnswer>& answers) {
  std::ostringstream out;
  out << "\\subsection*{Answers}\nThe quantities the problem asks for, as worked out below:\n\n"
      << "\\begin{tabular}{lll}\n\\toprule\nquantity & at & answer \\\\\n\\midrule\n";
  for (const ProblemAnswer& a : answers) {
    if (a.figure) {
      // Once for the mechanism: no input value.
      out << "$" << figure_latex(a.quantity) << "$ & --- & $\\boxed{"
          << (a.text.empty() ? latex_number(a.value, 6) : "\\text{" + latex_escape_text(a.text) + "}") << "}"
          << (a.unit.empty() ? "" : "\\," + latex_unit(a.unit)) << "$ \\\\\n";
      continue;
    }
    out << "$" << problem_quantity_latex(system, a.quantity) << "$ & $" << to_latex(system.input.symbol) << " = $ "
        << latex_escape_text(a.at_text) << " & $\\boxed{" << latex_number(zero_at_scale(a.value, a.scale), 6) << "}\\," << latex_unit(a.unit)
        << "$ \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\n";
  return out.str();
}

void write_problem_sheet(std::ostream& out, const ProblemSet& set, const ProblemVariant& variant,
                         const MotionState& state, const ValueAnalysis& at, const std::vector<std::string>& link_labels) {
  const ConstraintSystem& system = variant.model.system;
  const OutputScale scale(system);
  out << "\\documentclass[11pt]{article}\n\\usepackage[margin=2cm]{geometry}\n\\usepackage{amsmath,booktabs}\n"
      << "\\usepackage{tikz}\n\\usetikzlibrary{patterns}\n\\begin{document}\n"
      << "\\section*{" << latex_escape_text(system.title) << " --- variant " << variant.number << "}\n";
  if (!set.statement.empty()) out << latex_escape_text(set.statement) << "\n\n";
  // The given data: every parameter (a varied one in the file's unit), then the driver.
  std::set<std::string> varied;
  for (const GivenValue& g : variant.given) varied.insert(g.name);
  // The data and what to find side by side: the statement, the data and the drawing fit
  // on one page, the sheet a class is handed.
  out << "\\noindent\\begin{minipage}[t]{0.48\\textwidth}\n";
  out << "\\subsection*{Data}\n\\begin{tabular}{ll}\n\\toprule\nparameter & value \\\\\n\\midrule\n";
  for (const SystemParameter& p : system.parameters) {
    if (!p.written) continue;
    std::string value = latex_escape_text(p.text);
    for (const GivenValue& g : variant.given)
      if (g.name == p.symbol.get_name()) value = "$" + latex_given(g) + "$";
    // A parameter written as a formula of others is given as its value in this variant
    // (EF = CE is 0.230 m on the sheet: a student is given numbers, not the file's names).
    if (p.formula && !varied.count(p.symbol.get_name())) {
      const bool length = p.dimension == Dimension::length, angle = p.dimension == Dimension::angle;
      const double shown = length ? p.value / system.output.length_factor : angle ? to_degrees(p.value) : p.value;
      const std::string unit = length ? scale.coordinate_unit(Dimension::length) : angle ? "deg" : "";
      value = "$" + format_significant(shown, 6) + (unit.empty() ? "" : "\\," + latex_unit(unit)) + "$";
    }
    out << "$" << to_latex(p.symbol) << "$ & " << value << " \\\\\n";
  }
  const Driver& input = system.input;
  std::string at_list;
  for (const std::string& text : variant.at_texts) at_list += (at_list.empty() ? "" : ", ") + latex_escape_text(text);
  std::string rate = latex_escape_text(input.rate_text.empty() ? format_significant(input.rate_value) + " " + scale.rate_unit(input.dimension)
                                                               : input.rate_text);
  for (const GivenValue& g : variant.given)
    if (g.name == input.rate.get_name()) rate = "$" + latex_given(g) + "$";
  out << "\\midrule\n$" << to_latex(input.symbol) << "$ & " << at_list << " \\\\\n$" << to_latex(input.rate) << "$ & "
      << rate << " \\\\\n$" << to_latex(input.second_rate) << "$ & "
      << (input.second_rate_text.empty() ? "$0\\," + latex_unit(scale.second_rate_unit(input.dimension)) + "$"
                                          : latex_escape_text(input.second_rate_text))
      << " \\\\\n"
      << "\\bottomrule\n\\end{tabular}\n\n";
  out << "\\end{minipage}\\hfill\\begin{minipage}[t]{0.48\\textwidth}\n";
  out << "\\subsection*{Find}\nAt $" << to_latex(input.symbol) << " = $ " << at_list << ":\n\\begin{itemize}\n";
  for (const ProblemAnswer& a : variant.answers) {
    if (a.figure) continue;
    if (a.at_text != variant.answers.front().at_text) break;  // each value asks the same
    out << "\\item $" << problem_quantity_latex(system, a.quantity) << "$ in $" << latex_unit(a.unit) << "$\n";
  }
  for (const ProblemAnswer& a : variant.answers) {
    if (!a.figure) continue;
    out << "\\item $" << figure_latex(a.quantity) << "$"
        << (!a.text.empty() ? " (in words)" : a.unit.empty() ? "" : " in $" + latex_unit(a.unit) + "$")
        << " (of the mechanism, over a turn)\n";
  }
  out << "\\end{itemize}\nAnswers are graded to " << latex_escape_text(tolerance_text(set.tolerance))
      << ". Angles are measured counter-clockwise from the $x$ axis.\n\\end{minipage}\n\n";
  // The drawing at the first asked value, without the answers' arrows.
  write_tikz_mechanism(out, system, at, link_labels, state, false);
  out << "\\end{document}\n";
}

std::string problem_class_csv(const ProblemSet& set) {
  std::string text = csv_row(headings(set, false));
  for (const ProblemVariant& v : set.variants) {
    std::vector<std::string> row = {std::to_string(v.number)};
    for (const GivenValue& g : v.given) row.push_back(format_significant(g.value, 12));
    for (const ProblemAnswer& a : v.answers) row.push_back(answer_field(a));
    text += csv_row(row);
  }
  return text;
}

std::string problem_formula_csv(const ProblemSet& set) {
  std::string text = csv_row(headings(set, true));
  for (const ProblemVariant& v : set.variants) {
    std::vector<std::string> row = {std::to_string(v.number)};
    for (const GivenValue& g : v.given) row.push_back(format_significant(g.value, 12));
    for (const ProblemAnswer& a : v.answers) {
      // A class in words has no numeric tolerance: graded as text.
      row.push_back(answer_field(a));
      row.push_back(a.text.empty() ? format_round_trip(set.tolerance.absolute(a.value)) : "");
    }
    text += csv_row(row);
  }
  return text;
}

std::string problem_class_json(const ProblemSet& set, const std::string& source) {
  nlohmann::ordered_json root;
  root["source"] = source;
  root["seed"] = set.seed;
  root["count"] = set.count;
  root["tolerance"] = set.tolerance.sig_figs > 0 ? nlohmann::ordered_json{{"sig_figs", set.tolerance.sig_figs}}
                                                 : nlohmann::ordered_json{{"relative", set.tolerance.relative}};
  nlohmann::ordered_json variants = nlohmann::ordered_json::array();
  for (const ProblemVariant& v : set.variants) {
    nlohmann::ordered_json parameters = nlohmann::ordered_json::object();
    for (const GivenValue& g : v.given) parameters[g.name] = {{"si", g.si}, {"value", g.value}, {"unit", g.unit}};
    nlohmann::ordered_json answers = nlohmann::ordered_json::array();
    for (const ProblemAnswer& a : v.answers) {
      if (!a.text.empty()) {
        answers.push_back({{"quantity", a.quantity}, {"text", a.text}});
      } else if (a.figure) {  // once for the variant: no input value
        answers.push_back({{"quantity", a.quantity}, {"si", a.si}, {"value", a.value}, {"unit", a.unit}});
      } else {
        answers.push_back({{"quantity", a.quantity}, {"at", a.at_text}, {"at_si", a.at_si}, {"si", a.si}, {"value", a.value},
                           {"unit", a.unit}});
      }
    }
    variants.push_back({{"variant", v.number}, {"parameters", parameters}, {"answers", answers}});
  }
  root["variants"] = variants;
  return root.dump(1) + "\n";
}

std::string problem_moodle_xml(const ProblemSet& set, const std::string& title) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<quiz>\n"
      << "  <question type=\"category\">\n    <category><text>$course$/kinema/" << xml_escape(title)
      << "</text></category>\n  </question>\n";
  for (const ProblemVariant& v : set.variants) {
    std::string given;
    for (const GivenValue& g : v.given)
      given += (given.empty() ? "" : ", ") + g.name + " = " + given_number(g) + (g.unit.empty() ? "" : " " + g.unit);
    for (const ProblemAnswer& a : v.answers) {
      const std::string name = "Variant " + std::to_string(v.number) + ": " + a.quantity + (a.figure ? "" : " at " + a.at_text);
      std::string text = (set.statement.empty() ? title : set.statement) + " Variant " + std::to_string(v.number) +
                         (given.empty() ? "" : " (" + given + ")") + ": find " + a.quantity +
                         (a.figure ? "" : " at " + v.model.system.input.name + " = " + a.at_text) +
                         (!a.text.empty() ? ", in words." : a.unit.empty() ? "." : ", in " + a.unit + ".");
      if (!a.text.empty()) {  // a class in words: a short-answer question, graded as text
        out << "  <question type=\"shortanswer\">\n"
            << "    <name><text>" << xml_escape(name) << "</text></name>\n"
            << "    <questiontext format=\"plain_text\"><text>" << xml_escape(text) << "</text></questiontext>\n"
            << "    <defaultgrade>1</defaultgrade>\n    <usecase>0</usecase>\n"
            << "    <answer fraction=\"100\">\n      <text>" << xml_escape(a.text) << "</text>\n"
            << "      <feedback><text></text></feedback>\n    </answer>\n"
            << "  </question>\n";
        continue;
      }
      out << "  <question type=\"numerical\">\n"
          << "    <name><text>" << xml_escape(name) << "</text></name>\n"
          << "    <questiontext format=\"plain_text\"><text>" << xml_escape(text) << "</text></questiontext>\n"
          << "    <defaultgrade>1</defaultgrade>\n"
          << "    <answer fraction=\"100\">\n      <text>" << format_round_trip(a.value) << "</text>\n"
          << "      <tolerance>" << format_round_trip(set.tolerance.absolute(a.value)) << "</tolerance>\n"
          << "      <feedback><text></text></feedback>\n    </answer>\n"
          << "    <unitgradingtype>0</unitgradingtype>\n    <showunits>3</showunits>\n"
          << "  </question>\n";
    }
  }
  out << "</quiz>\n";
  return out.str();
}

}  // namespace kinema
