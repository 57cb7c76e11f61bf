// The reading every form of mechanism file does alike (file_reader.hpp): one place for
// how a value is read and how a message about it is worded, so that the three forms
// read and refuse alike.
#include "readers/file_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

#include "engine/base/errors.hpp"
#include "engine/base/input_values.hpp"
#include "engine/base/naming.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/toml_ascii.hpp"
#include "engine/base/user_text.hpp"
#include "readers/sweep_syntax.hpp"

namespace kinema::reading {
namespace {

// Names GiNaC's parser gives a meaning of its own; a mechanism may not reuse them.
const std::set<std::string>& reserved_names() {
  static const std::set<std::string> names = {
      "I", "Pi", "Euler", "Catalan", "sin", "cos", "tan", "exp", "log", "sqrt", "abs",
      "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "pow", "t"};
  return names;
}

// Largest driver rate or second rate, SI (limits: docs/limits.md).
constexpr double kMaxRate = 1e9;

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& what) {
  const std::string a_what = (std::string("aeiou").find(what[0]) != std::string::npos ? "an " : "a ") + what;
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(path + ": is a directory, not " + a_what + "; give the path of the file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the " + what + " (does it exist?)");
  // Read at most a chunk past the limit: a stream that never ends (/dev/zero) stops
  // there. In chunks, so that a file of a few KiB touches a few KiB (not a zeroed MiB).
  std::string text;
  char chunk[16384];
  while (text.size() <= max_bytes && file.read(chunk, sizeof chunk).gcount() > 0)
    text.append(chunk, static_cast<std::size_t>(file.gcount()));
  if (text.size() > max_bytes) {
    throw InputError(path + ": the " + what + " is larger than " + std::to_string(max_bytes / 1024) +
                     " KiB; it is a few KiB of text");
  }
  return text;
}

toml::table FileReader::parse(const std::string& text, const std::string& what) const {
  toml::table root;
  try {
    root = toml::parse(ascii_toml(text, file_), file_);
  } catch (const toml::parse_error& error) {
    const auto& at = error.source().begin;
    throw InputError(file_ + ":" + std::to_string(at.line) + ": syntax error in the " + what + " (column " +
                     std::to_string(at.column) + "): " + one_line(std::string(error.description())));
  }
  check_text(root, "", false);
  return root;
}

void FileReader::check_text(const Node& node, const std::string& key, bool multi_line) const {
  if (const auto* table = node.as_table()) {
    for (const auto& [name, value] : *table) {
      const std::string child(name.str());
      const std::string path = key.empty() ? child : key + "." + child;
      check_string(child, {file_, static_cast<int>(name.source().begin.line)}, "the key \"" + one_line(child) + "\"",
                   false);
      check_text(value, path, key.empty() && (child == "title" || child == "description"));
    }
  } else if (const auto* array = node.as_array()) {
    for (std::size_t i = 0; i < array->size(); ++i) check_text(*array->get(i), key + "[" + std::to_string(i) + "]", false);
  } else if (node.is_string()) {
    check_string(node.as_string()->get(), where(node), "\"" + key + "\"", multi_line);
  }
}

void FileReader::check_string(const std::string& text, const SourceLocation& at, const std::string& what,
                              bool multi_line) const {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned long c = next_code_point(text, i);
    if (c == '\t' || (c == '\n' && multi_line)) continue;
    std::string why;
    if (c == '\n') why = "a line break; only title and description may have several lines";
    else if (is_control_character(c)) why = "the control character " + code_point_name(c) + "; remove it";
    else if (is_bidi_control(c))
      why = code_point_name(c) + ", a bidirectional control that reorders the text shown after it (in a terminal, "
            "an editor, generated code); remove it";
    if (!why.empty()) throw InputError(at.str() + ": " + what + " contains " + why);
  }
}

void FileReader::fail(const Node& value, const std::string& message) const {
  throw InputError(where(value).str() + ": " + message);
}

std::vector<std::pair<std::string, const Node*>> FileReader::ordered(const Node& table) const {
  std::vector<std::pair<std::string, const Node*>> entries;
  for (const auto& [key, value] : *table.as_table()) entries.emplace_back(std::string(key.str()), &value);
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return a.second->source().begin < b.second->source().begin;
  });
  return entries;
}

void FileReader::check_keys(const Node& table, std::initializer_list<const char*> allowed,
                            const std::string& context) const {
  for (const auto& [key, value] : ordered(table)) {
    bool known = false;
    std::string list;
    for (const char* name : allowed) {
      known = known || key == name;
      list += std::string(list.empty() ? "" : ", ") + name;
    }
    if (!known) fail(*value, "unknown key \"" + key + "\" in " + context + "; expected one of: " + list);
  }
}

std::string FileReader::string_value(const Node& value, const std::string& key) const {
  if (value.is_string()) return value.as_string()->get();
  if (value.is_integer()) return std::to_string(value.as_integer()->get());
  if (value.is_floating_point()) return format_round_trip(value.as_floating_point()->get());
  fail(value, "\"" + key + "\" must be a string such as \"150 mm\" or a formula");
}

std::string FileReader::optional_string(const Node& table, const std::string& key, const std::string& fallback) const {
  if (!has(table, key)) return fallback;
  const Node& value = at(table, key);
  if (!value.is_string()) fail(value, "\"" + key + "\" must be a string");
  return value.as_string()->get();
}

Quantity FileReader::quantity(const Node& value, const std::string& key) const {
  try {
    return parse_quantity(string_value(value, key));
  } catch (const UnitError& error) {
    throw UnitError(where(value).str() + ": " + key + ": " + error.what());
  }
}

double FileReader::quantity_of(const Node& value, const std::string& key, Dimension expected) const {
  const Quantity q = quantity(value, key);
  if (q.dimension != expected && q.dimension != Dimension::number) {
    throw UnitError(where(value).str() + ": " + key + " = \"" + string_value(value, key) +
                    "\" is " + with_article(dimension_name(q.dimension)) + ", but " +
                    with_article(dimension_name(expected)) + " is needed here");
  }
  return q.si_value;
}

bool FileReader::is_identifier(const std::string& name) {
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (name.empty() || !letter(name[0])) return false;
  return std::all_of(name.begin(), name.end(),
                     [&](char c) { return letter(c) || (c >= '0' && c <= '9') || c == '_'; });
}

void FileReader::check_name(const Node& value, const std::string& name, const std::string& what) const {
  if (!is_identifier(name)) {
    fail(value, what + " name \"" + one_line(name) + "\" is not a valid name (letters, digits, _; "
                "starting with a letter)");
  }
}

void FileReader::check_identifier(const Node& value, const std::string& name, const std::string& what) const {
  check_name(value, name, what);
  if (reserved_names().count(name)) {
    fail(value, what + " name \"" + name + "\" is reserved (it means a constant or a "
                "function in formulas); rename it");
  }
}

double FileReader::bounded_rate(const Node& value, const std::string& key, Dimension dimension) const {
  const double si = quantity_of(value, key, dimension);
  if (!(std::fabs(si) <= kMaxRate)) {
    fail(value, key + " = \"" + string_value(value, key) + "\" is too large: kinema takes driver rates up to " +
                    format_significant(kMaxRate) + " in SI units (rad/s, m/s and their per-second rates)");
  }
  return si;
}

std::string FileReader::optional_name(const Node& table, const std::string& key) const {
  const std::string name = optional_string(table, key, "");
  if (!name.empty()) check_identifier(at(table, key), name, key.substr(0, key.size() - 5));
  return name;
}

const Node& FileReader::required_table(const Node& root, const std::string& key) const {
  if (!has(root, key)) {
    throw InputError(file_ + ": the section [" + key + "] is missing; see the file format "
                     "in docs/mechanism-files.md");
  }
  const Node& table = at(root, key);
  if (!table.is_table()) fail(table, "\"" + key + "\" must be a table ([" + key + "])");
  return table;
}

void FileReader::read_output(const Node& root, Mechanism& mechanism) const {
  if (!has(root, "output")) return;
  const Node& output = at(root, "output");
  if (!output.is_table()) fail(output, "[output] must be a table");
  check_keys(output, {"length"}, "[output]");
  if (has(output, "length")) {
    const Node& unit = at(output, "length");
    mechanism.output.length = string_value(unit, "length");
    try {
      mechanism.output.length_factor = length_unit_factor(mechanism.output.length);
    } catch (const UnitError& error) {
      throw UnitError(where(unit).str() + ": " + error.what());
    }
  }
}

void FileReader::read_parameters(const Node& root, Mechanism& mechanism) const {
  if (!has(root, "parameters")) return;
  const Node& table = at(root, "parameters");
  if (!table.is_table()) fail(table, "[parameters] must be a table");
  for (const auto& [name, value] : ordered(table)) {
    check_identifier(*value, name, "parameter");
    Parameter parameter;
    parameter.name = name;
    parameter.text = string_value(*value, name);
    parameter.where = where(*value);
    if (value->is_string() && !looks_like_quantity(parameter.text)) {
      parameter.formula = parameter.text;
    } else {
      parameter.quantity = quantity(*value, name);
    }
    mechanism.parameters.push_back(parameter);
  }
}

void FileReader::read_motion(const Node& table, const std::string& section, Input& input) const {

  // The driver's kind comes from its values' unit; default to a crank angle.
  std::optional<Dimension> kind;
  auto take_value = [&](const Node& value, const std::string& key) {
    const Quantity q = quantity(value, key);
    if (q.dimension != Dimension::angle && q.dimension != Dimension::length) {
      throw UnitError(where(value).str() + ": " + key + " = \"" + string_value(value, key) +
                      "\" is " + with_article(dimension_name(q.dimension)) +
                      "; the input must be an angle (e.g. \"30 deg\") or a length (e.g. \"2 in\")");
    }
    if (kind && *kind != q.dimension) {
      throw UnitError(where(value).str() + ": " + key + " mixes angles and lengths");
    }
    kind = q.dimension;
    input.values.push_back(q.si_value);
  };
  if (has(table, "value")) take_value(at(table, "value"), "value");
  if (has(table, "values")) {
    const Node& list = at(table, "values");
    if (!list.is_array()) fail(list, "values must be a list, e.g. [\"30 deg\", \"45 deg\"]");
    if (list.as_array()->empty()) {
      fail(list, "values = [] lists no value; give one or more, e.g. values = [\"30 deg\", \"45 deg\"], or leave "
                 "values out and give them on the command line (--angle, --sweep)");
    }
    for (const auto& value : *list.as_array()) take_value(value, "values");
  }
  if (has(table, "sweep")) {
    const Node& sweep = at(table, "sweep");
    const std::string text = string_value(sweep, "sweep");
    // "0:360:1 deg": the unit after the numbers applies to all three.
    const auto space = text.find_first_of(" \t");
    const std::string numbers = text.substr(0, space);
    const std::string unit = space == std::string::npos ? "" : text.substr(space);
    if (unit.find_first_not_of(" \t") == std::string::npos) {
      fail(sweep, "sweep needs a unit, e.g. \"0:360:1 deg\"");
    }
    Quantity unit_q;
    try {
      unit_q = parse_quantity("1 " + unit);
    } catch (const UnitError&) {
      fail(sweep, "sweep unit \"" + unit.substr(unit.find_first_not_of(" \t")) + "\" is not understood; use one of " +
                      understood_units());
    }
    if (unit_q.dimension != Dimension::angle && unit_q.dimension != Dimension::length) {
      fail(sweep, "sweep unit must be an angle or a length unit");
    }
    if (kind && *kind != unit_q.dimension) fail(sweep, "sweep mixes angles and lengths");
    kind = unit_q.dimension;
    try {
      const InputValues values = parse_sweep(numbers, unit_q.si_value);
      if (input.values.size() + values.size() > kMaxValuesPerRun) {
        fail(sweep, "the input has more than " + std::to_string(kMaxValuesPerRun) +
                        " values (a file's values are held in memory); use a larger step, or --sweep on the "
                        "command line (streamed)");
      }
      const std::vector<double> swept = values.to_vector();
      input.values.insert(input.values.end(), swept.begin(), swept.end());
    } catch (const InputError& error) {
      fail(sweep, error.what());
    }
  }
  input.dimension = kind.value_or(Dimension::angle);
  const Dimension rate = rate_dimension(input.dimension);
  const Dimension second = rate_dimension(rate);
  if (!has(table, "rate")) {
    throw InputError(input.where.str() + ": " + section + " needs rate = \"...\" (the driver's speed, "
                     "e.g. \"60 rpm\" or \"-42 rad/s\" for clockwise)");
  }
  input.rate = bounded_rate(at(table, "rate"), "rate", rate);
  input.rate_text = string_value(at(table, "rate"), "rate");
  if (has(table, "second_rate")) {
    input.second_rate = bounded_rate(at(table, "second_rate"), "second_rate", second);
    input.second_rate_text = string_value(at(table, "second_rate"), "second_rate");
  }
  input.rate_name = optional_name(table, "rate_name");
  input.second_rate_name = optional_name(table, "second_rate_name");
}

void FileReader::read_heading(const Node& root, Mechanism& mechanism) const {
  mechanism.title = optional_string(root, "title", "Untitled mechanism");
  mechanism.description = optional_string(root, "description", "");
  read_output(root, mechanism);
  read_parameters(root, mechanism);
  read_problem(root, mechanism);
}

}  // namespace kinema::reading
