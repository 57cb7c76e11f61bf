#include "readers/answers_file.hpp"

#include <cmath>
#include <cstdlib>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/user_text.hpp"
#include "readers/file_reader.hpp"

namespace kinema {

std::string AnswerTolerance::describe() const {
  if (kind == Kind::significant_figures) return std::to_string(figures) + " significant figures";
  return format_significant(relative * 100.0, 6) + " %";
}

bool AnswerTolerance::accepts(double given, double reference) const {
  if (!std::isfinite(given) || !std::isfinite(reference)) return false;
  const double difference = std::abs(given - reference);
  if (reference == 0.0) return difference == 0.0;  // no scale to be relative to
  if (kind == Kind::relative) return difference <= relative * std::abs(reference);
  // Half a unit in the last significant figure of the reference: 3 figures of 2.6213 is 0.005.
  const double exponent = std::floor(std::log10(std::abs(reference))) - (figures - 1);
  return difference <= 0.5 * std::pow(10.0, exponent) * (1 + 1e-12);  // the half-unit edge itself counts
}

AnswerTolerance relative_tolerance(const std::string& text, const std::string& context) {
  std::string number = text;
  double scale = 1.0;
  const std::size_t percent = number.find('%');
  if (percent != std::string::npos) {
    if (number.find_first_not_of(' ', percent + 1) != std::string::npos) number = "?";  // "1 % x"
    number.erase(percent);
    scale = 0.01;
  }
  while (!number.empty() && number.back() == ' ') number.pop_back();
  char* end = nullptr;
  const double value = number.empty() ? NAN : std::strtod(number.c_str(), &end) * scale;
  if (number.empty() || *end != '\0' || !(value > 0.0 && value < 1.0)) {
    throw InputError(context + ": tolerance \"" + one_line(text) +
                     "\" is not a relative tolerance; write it as a percentage (\"1%\") or a fraction (\"0.01\") "
                     "between 0 and 1");
  }
  AnswerTolerance tolerance;
  tolerance.relative = value;
  return tolerance;
}

AnswerTolerance significant_figures(long figures, const std::string& context) {
  if (figures < 1 || figures > 15) {
    throw InputError(context + ": " + std::to_string(figures) +
                     " significant figures; give from 1 to 15 (a double holds about 15)");
  }
  AnswerTolerance tolerance;
  tolerance.kind = AnswerTolerance::Kind::significant_figures;
  tolerance.figures = static_cast<int>(figures);
  return tolerance;
}

namespace {

constexpr std::size_t kMaxAnswersFileBytes = 1024 * 1024;

void add_answer(AnswersFile& file, WrittenAnswer answer) {
  if (file.answers.size() == kMaxAnswers) {
    throw InputError(answer.where.str() + ": more than " + std::to_string(kMaxAnswers) + " answers in one file");
  }
  file.answers.push_back(std::move(answer));
}

// [[answer]] tables: quantity, value, at (optional); a top-level variant = N.
AnswersFile read_toml(const std::string& text, const std::string& name) {
  const reading::FileReader reader(name);
  const toml::table root = reader.parse(text, "answers file");
  reader.check_keys(root, {"variant", "answer"}, "the answers file");
  AnswersFile file;
  file.path = name;
  if (const toml::node* variant = root.get("variant")) {
    if (!variant->is_integer()) reader.fail(*variant, "variant must be a whole number (the class table's variant)");
    file.variant = variant->as_integer()->get();
    file.variant_where = reader.where(*variant);
  }
  const toml::node* answers = root.get("answer");
  if (answers && !answers->is_array_of_tables()) reader.fail(*answers, "answer must be [[answer]] tables");
  if (answers) {
    for (const toml::node& entry : *answers->as_array()) {
      reader.check_keys(entry, {"quantity", "at", "value"}, "[[answer]]");
      WrittenAnswer answer;
      answer.where = reader.where(entry);
      for (const char* key : {"quantity", "value"}) {
        if (!reading::FileReader::has(entry, key)) {
          throw InputError(answer.where.str() + ": [[answer]] without " + key +
                           " (write quantity = \"omega3\", value = \"-2.35 rad/s\", and at = \"30 deg\")");
        }
      }
      answer.quantity = reader.string_value(reading::FileReader::at(entry, "quantity"), "quantity");
      answer.value = reader.string_value(reading::FileReader::at(entry, "value"), "value");
      if (reading::FileReader::has(entry, "at")) answer.at = reader.string_value(reading::FileReader::at(entry, "at"), "at");
      add_answer(file, std::move(answer));
    }
  }
  return file;
}

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") + 1 - first);
}

// One CSV line's fields: commas split, a field may be in double quotes (a "" inside is a quote).
std::vector<std::string> csv_fields(const std::string& line, const SourceLocation& where) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (quoted) throw InputError(where.str() + ": a quote (\") is not closed on this line");
  for (std::string& field : fields) field = trimmed(field);
  return fields;
}

// Rows quantity,at,value[,unit]; a first row "quantity,..." is the header; # starts a comment line.
AnswersFile read_csv(const std::string& text, const std::string& name) {
  AnswersFile file;
  file.path = name;
  std::size_t start = 0;
  for (int line_number = 1; start < text.size(); ++line_number) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    const SourceLocation where{name, line_number};
    reading::FileReader(name).check_string(line, where, "the line", false);
    if (trimmed(line).empty() || trimmed(line)[0] == '#') continue;
    const std::vector<std::string> fields = csv_fields(line, where);
    if (file.answers.empty() && fields[0] == "quantity") continue;  // the header
    if (fields.size() < 3 || fields.size() > 4) {
      throw InputError(where.str() + ": " + std::to_string(fields.size()) +
                       " fields; an answer is quantity,at,value or quantity,at,value,unit (e.g. omega3,30 deg,-2.35,rad/s)");
    }
    if (fields[0].empty() || fields[2].empty()) {
      throw InputError(where.str() + ": an answer needs its quantity (field 1) and its value (field 3)");
    }
    WrittenAnswer answer{fields[0], fields[1], fields[2], where};
    if (fields.size() == 4 && !fields[3].empty()) answer.value += " " + fields[3];
    add_answer(file, std::move(answer));
  }
  return file;
}

bool ends_with(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

}  // namespace

AnswersFile read_answers_text(const std::string& text, const std::string& name) {
  AnswersFile file = ends_with(name, ".csv") || ends_with(name, ".CSV") ? read_csv(text, name) : read_toml(text, name);
  if (file.answers.empty()) {
    throw InputError(name + ": no answers; write [[answer]] tables (TOML) or rows quantity,at,value[,unit] (CSV)");
  }
  return file;
}

AnswersFile read_answers_file(const std::string& path) {
  return read_answers_text(reading::read_text_file(path, kMaxAnswersFileBytes, "answers file"), path);
}

}  // namespace kinema
