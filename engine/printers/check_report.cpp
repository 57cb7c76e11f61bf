#include "engine/printers/check_report.hpp"

#include <nlohmann/json.hpp>

#include "engine/base/number_format.hpp"

namespace kinema {

namespace {

std::string number(double value) { return format_significant(value, 6); }

// A design figure's line: no input value; a class in words as written.
std::string figure_line(const AnswerVerdict& v) {
  std::string line = v.where.str() + ": " + v.quantity + " (design figure): given ";
  const std::string unit = v.unit.empty() ? "" : " " + v.unit;
  if (!v.expected_text.empty()) {
    line += "\"" + v.given + "\", expected \"" + v.expected_text + "\": ";
  } else {
    line += number(v.given_value) + unit;
    if (v.unit_assumed && !v.unit.empty()) line += " (no unit: taken as " + v.unit + ")";
    line += ", expected " + number(v.expected) + unit + ": ";
  }
  return line + (v.right ? "right" : "wrong");
}

// "omega3 at 40 deg" with where it was written.
std::string answer_line(const AnswerVerdict& v) {
  if (v.figure) return figure_line(v);
  std::string line = v.where.str() + ": " + v.quantity;
  if (v.quantity != v.column) line += " (" + v.column + ")";
  line += " at " + v.at + ": given " + number(v.given_value) + " " + v.unit;
  if (v.unit_assumed) line += " (no unit: taken as " + v.unit + ", the file's output unit)";
  line += ", expected " + number(v.expected) + " " + v.unit + ": ";
  if (v.right) return line + "right";
  line += "wrong";
  if (v.mistakes.empty()) return line + "; no mistake of the catalogue gives " + number(v.given_value);
  const MistakeMatch& likely = v.mistakes.front();
  line += "; likely mistake: " + likely.words;
  if (!likely.detail.empty()) line += " (" + likely.detail + ")";
  line += ", which gives " + number(likely.value) + " " + v.unit;
  for (std::size_t k = 1; k < v.mistakes.size(); ++k) line += (k == 1 ? "; or " : ", or ") + v.mistakes[k].words;
  return line;
}

nlohmann::ordered_json mistake_json(const MistakeMatch& m) {
  return {{"name", m.name}, {"words", m.words}, {"detail", m.detail}, {"value", m.value}};
}

}  // namespace

std::string check_report_text(const CheckReport& report) {
  std::string text = "kinema check: " + report.answers_file + " against " + report.source;
  if (report.variant) text += ", variant " + std::to_string(*report.variant);
  text += ", within " + report.tolerance.describe() + "\n";
  for (const AnswerVerdict& v : report.verdicts) text += answer_line(v) + "\n";
  const std::size_t right = report.verdicts.size() - report.wrong_count();
  text += std::to_string(right) + " of " + std::to_string(report.verdicts.size()) + " right\n";
  return text;
}

std::string check_report_json(const CheckReport& report) {
  nlohmann::ordered_json root;
  root["answers_file"] = report.answers_file;
  root["source"] = report.source;
  root["variant"] = report.variant ? nlohmann::ordered_json(*report.variant) : nlohmann::ordered_json(nullptr);
  if (report.tolerance.kind == AnswerTolerance::Kind::relative) {
    root["tolerance"] = {{"relative", report.tolerance.relative}};
  } else {
    root["tolerance"] = {{"sig_figs", report.tolerance.figures}};
  }
  root["right"] = report.verdicts.size() - report.wrong_count();
  root["wrong"] = report.wrong_count();
  nlohmann::ordered_json answers = nlohmann::ordered_json::array();
  for (const AnswerVerdict& v : report.verdicts) {
    nlohmann::ordered_json mistakes = nlohmann::ordered_json::array();
    for (const MistakeMatch& m : v.mistakes) mistakes.push_back(mistake_json(m));
    answers.push_back({{"line", v.where.line},
                       {"quantity", v.quantity},
                       {"column", v.column},
                       {"at", v.at},
                       {"at_si", v.at_si},
                       {"given", v.given},
                       {"given_value", v.given_value},
                       {"unit", v.unit},
                       {"unit_assumed", v.unit_assumed},
                       {"expected", v.expected_text.empty() ? nlohmann::ordered_json(v.expected) : nlohmann::ordered_json(v.expected_text)},
                       {"figure", v.figure},
                       {"right", v.right},
                       {"mistake", v.mistakes.empty() ? nlohmann::ordered_json(nullptr) : mistake_json(v.mistakes.front())},
                       {"mistakes", mistakes}});
  }
  root["answers"] = answers;
  return root.dump(2) + "\n";
}

}  // namespace kinema
