#include "loops/mechanism_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

// toml++ compiled into this file (header-only mode, not Debian's shared build) so that
// the sanitizer and fuzzer builds instrument the parser too. It bounds nesting (256)
// and refuses integers that do not fit in 64 bits; toml11 3.7 did neither (issue 9:
// stack overflow at 5,880 nested arrays, a heap over-read on 3 bytes). It is given
// ASCII only (toml_ascii.hpp says why).
#define TOML_HEADER_ONLY 1
#define TOML_ENABLE_FORMATTERS 0
#include <toml++/toml.h>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/user_text.hpp"
#include "engine/symbolic/naming.hpp"
#include "loops/linkage_loops.hpp"
#include "engine/base/toml_ascii.hpp"

namespace kinema {
namespace {

using Node = toml::node;

// Names GiNaC's parser gives a meaning of its own; a mechanism may not reuse them.
const std::set<std::string>& reserved_names() {
  static const std::set<std::string> names = {
      "I", "Pi", "Euler", "Catalan", "sin", "cos", "tan", "exp", "log", "sqrt", "abs",
      "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "pow", "t"};
  return names;
}

// Largest driver rate or second rate, SI (limits: docs/limits.md).
constexpr double kMaxRate = 1e9;

class FileReader {
 public:
  FileReader(std::string file) : file_(std::move(file)) {}

  Mechanism read(const std::string& text) {
    toml::table root;
    try {
      root = toml::parse(ascii_toml(text, file_), file_);
    } catch (const toml::parse_error& error) {
      const auto& at = error.source().begin;
      throw InputError(file_ + ":" + std::to_string(at.line) + ": syntax error in the mechanism file (column " +
                       std::to_string(at.column) + "): " + one_line(std::string(error.description())));
    }
    check_text(root, "", false);
    Mechanism mechanism;
    mechanism.source_file = file_;
    if (has(root, "frames") || has(root, "variables")) return read_chain(root, mechanism);
    if (has(root, "joints") || has(root, "links") || has(root, "driver")) return read_linkage(root, mechanism);
    check_keys(root, {"title", "description", "parameters", "input", "unknowns", "loops",
                      "points", "output"},
               "the top level");
    mechanism.title = optional_string(root, "title", "Untitled mechanism");
    mechanism.description = optional_string(root, "description", "");
    read_output(root, mechanism);
    read_parameters(root, mechanism);
    read_input(root, mechanism);
    read_unknowns(root, mechanism);
    read_loops(root, mechanism);
    read_points(root, mechanism);
    check_names(mechanism);
    return mechanism;
  }

 private:
  std::string file_;

  // Every key and string of the file, before anything reads them: no character that
  // controls how text is shown (engine/base/user_text.hpp) — ESC and the like would
  // reach the terminal, U+202E reorders a C++ comment or a message. Line breaks only in
  // the title and the description (`multi_line`); tabs anywhere.
  void check_text(const Node& node, const std::string& key, bool multi_line) const {
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

  void check_string(const std::string& text, const SourceLocation& at, const std::string& what, bool multi_line) const {
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

  SourceLocation where(const Node& value) const { return {file_, static_cast<int>(value.source().begin.line)}; }

  static bool has(const Node& table, const std::string& key) { return table.as_table()->contains(key); }
  static const Node& at(const Node& table, const std::string& key) { return *table.as_table()->get(key); }

  [[noreturn]] void fail(const Node& value, const std::string& message) const {
    throw InputError(where(value).str() + ": " + message);
  }

  // Table entries in the order they were written (TOML tables are unordered maps).
  std::vector<std::pair<std::string, const Node*>> ordered(const Node& table) const {
    std::vector<std::pair<std::string, const Node*>> entries;
    for (const auto& [key, value] : *table.as_table()) entries.emplace_back(std::string(key.str()), &value);
    std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
      return a.second->source().begin < b.second->source().begin;
    });
    return entries;
  }

  void check_keys(const Node& table, std::initializer_list<const char*> allowed,
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

  std::string string_value(const Node& value, const std::string& key) const {
    if (value.is_string()) return value.as_string()->get();
    if (value.is_integer()) return std::to_string(value.as_integer()->get());
    if (value.is_floating_point()) return format_round_trip(value.as_floating_point()->get());
    fail(value, "\"" + key + "\" must be a string such as \"150 mm\" or a formula");
  }

  std::string optional_string(const Node& table, const std::string& key,
                              const std::string& fallback) const {
    if (!has(table, key)) return fallback;
    const Node& value = at(table, key);
    if (!value.is_string()) fail(value, "\"" + key + "\" must be a string");
    return value.as_string()->get();
  }

  Quantity quantity(const Node& value, const std::string& key) const {
    try {
      return parse_quantity(string_value(value, key));
    } catch (const UnitError& error) {
      throw UnitError(where(value).str() + ": " + key + ": " + error.what());
    }
  }

  // A quantity that must have the given dimension (a bare number is taken as SI of it).
  double quantity_of(const Node& value, const std::string& key, Dimension expected) const {
    const Quantity q = quantity(value, key);
    if (q.dimension != expected && q.dimension != Dimension::number) {
      throw UnitError(where(value).str() + ": " + key + " = \"" + string_value(value, key) +
                      "\" is " + with_article(dimension_name(q.dimension)) + ", but " +
                      with_article(dimension_name(expected)) + " is needed here");
    }
    return q.si_value;
  }

  // ASCII letters, digits and _, starting with a letter: a name is safe in formulas,
  // CSV headers, LaTeX comments and generated code alike.
  static bool is_identifier(const std::string& name) {
    auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
    if (name.empty() || !letter(name[0])) return false;
    return std::all_of(name.begin(), name.end(),
                       [&](char c) { return letter(c) || (c >= '0' && c <= '9') || c == '_'; });
  }

  // Names of loops and points: identifiers (they head CSV columns and LaTeX text).
  void check_name(const Node& value, const std::string& name, const std::string& what) const {
    if (!is_identifier(name)) {
      fail(value, what + " name \"" + one_line(name) + "\" is not a valid name (letters, digits, _; "
                  "starting with a letter)");
    }
  }


  void check_identifier(const Node& value, const std::string& name,
                        const std::string& what) const {
    check_name(value, name, what);
    if (reserved_names().count(name)) {
      fail(value, what + " name \"" + name + "\" is reserved (it means a constant or a "
                  "function in formulas); rename it");
    }
  }

  // A driver rate: past kMaxRate (SI) the squared rates in the accelerations overflow
  // long before any machine turns that fast, so it is refused rather than reported as
  // non-finite results.
  double bounded_rate(const Node& value, const std::string& key, Dimension dimension) const {
    const double si = quantity_of(value, key, dimension);
    if (!(std::fabs(si) <= kMaxRate)) {
      fail(value, key + " = \"" + string_value(value, key) + "\" is too large: kinema takes driver rates up to " +
                      format_significant(kMaxRate) + " in SI units (rad/s, m/s and their per-second rates)");
    }
    return si;
  }

  // An optional rate name: a symbol in formulas, so an identifier that is not reserved.
  std::string optional_name(const Node& table, const std::string& key) const {
    const std::string name = optional_string(table, key, "");
    if (!name.empty()) check_identifier(at(table, key), name, key.substr(0, key.size() - 5));
    return name;
  }

  const Node& required_table(const Node& root, const std::string& key) const {
    if (!has(root, key)) {
      throw InputError(file_ + ": the section [" + key + "] is missing; see the file format "
                       "in docs/mechanism-files.md");
    }
    const Node& table = at(root, key);
    if (!table.is_table()) fail(table, "\"" + key + "\" must be a table ([" + key + "])");
    return table;
  }

  void read_output(const Node& root, Mechanism& mechanism) const {
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

  void read_parameters(const Node& root, Mechanism& mechanism) const {
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

  void read_input(const Node& root, Mechanism& mechanism) const {
    const Node& table = required_table(root, "input");
    check_keys(table, {"name", "value", "values", "sweep", "rate", "second_rate", "rate_name",
                       "second_rate_name"},
               "[input]");
    Input& input = mechanism.input;
    input.where = where(table);
    if (!has(table, "name")) {
      throw InputError(file_ + ": [input] needs name = \"...\" (the driver coordinate, e.g. theta2)");
    }
    input.name = string_value(at(table, "name"), "name");
    check_identifier(at(table, "name"), input.name, "input");
    input.where = where(at(table, "name"));
    read_motion(table, "[input]", input);
  }

  // The driver's values, rate and second rate, as [input] and [driver] give them.
  void read_motion(const Node& table, const std::string& section, Input& input) const {

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

  void read_unknowns(const Node& root, Mechanism& mechanism) const {
    const Node& table = required_table(root, "unknowns");
    for (const auto& [name, value] : ordered(table)) {
      check_identifier(*value, name, "unknown");
      Unknown unknown;
      unknown.name = name;
      unknown.where = where(*value);
      const Node* guess = value;
      if (value->is_table()) {
        check_keys(*value, {"guess", "rate_name", "second_rate_name", "latex"},
                   "unknown \"" + name + "\"");
        if (!has(*value, "guess")) fail(*value, "unknown \"" + name + "\" needs guess = \"...\"");
        guess = &at(*value, "guess");
        unknown.rate_name = optional_name(*value, "rate_name");
        unknown.second_rate_name = optional_name(*value, "second_rate_name");
        unknown.latex_name = optional_string(*value, "latex", "");
        if (!unknown.latex_name.empty())  // refused here, at its line, before any printer meets it
          check_latex_name(unknown.latex_name, where(at(*value, "latex")).str() + ": unknown \"" + name + "\"");
      }
      const Quantity q = quantity(*guess, name);
      if (q.dimension != Dimension::angle && q.dimension != Dimension::length) {
        throw UnitError(where(*guess).str() + ": the guess of unknown \"" + name + "\" (\"" +
                        string_value(*guess, name) + "\") needs an angle or a length unit, e.g. "
                        "\"20 deg\" or \"120 mm\": the unit says what kind of coordinate it is");
      }
      unknown.dimension = q.dimension;
      unknown.guess = q.si_value;
      mechanism.unknowns.push_back(unknown);
    }
    if (mechanism.unknowns.empty()) fail(table, "[unknowns] is empty: name the coordinates the loops determine");
  }

  void read_loops(const Node& root, Mechanism& mechanism) const {
    const Node& table = required_table(root, "loops");
    for (const auto& [name, value] : ordered(table)) {
      check_name(*value, name, "loop");
      Loop loop;
      loop.name = name;
      loop.where = where(*value);
      if (value->is_table()) {
        check_keys(*value, {"x", "y"}, "loop \"" + name + "\"");
        if (!has(*value, "x") || !has(*value, "y")) {
          fail(*value, "loop \"" + name + "\" written by components needs both x = \"...\" and y = \"...\"");
        }
        loop.x_formula = string_value(at(*value, "x"), "x");
        loop.y_formula = string_value(at(*value, "y"), "y");
      } else {
        loop.complex_formula = string_value(*value, name);
      }
      mechanism.loops.push_back(loop);
    }
    if (mechanism.loops.empty()) fail(table, "[loops] is empty: write at least one vector loop");
  }

  void read_points(const Node& root, Mechanism& mechanism) const {
    if (!has(root, "points")) return;
    const Node& table = at(root, "points");
    if (!table.is_table()) fail(table, "[points] must be a table of name = \"x + I*y formula\"");
    for (const auto& [name, value] : ordered(table)) {
      check_name(*value, name, "point");
      Point point;
      point.name = name;
      point.formula = string_value(*value, name);
      point.where = where(*value);
      mechanism.points.push_back(point);
    }
  }

  // A file written as joints and links (docs/mechanism-files.md, "Joints and links"): read here, then
  // written as vector loops by linkage_loops.
  Mechanism read_linkage(const Node& root, Mechanism& mechanism) const {
    check_keys(root, {"title", "description", "parameters", "driver", "joints", "links", "points", "output"},
               "the top level of a joints-and-links file (vector loops go in another file: [input], [unknowns], "
               "[loops])");
    mechanism.title = optional_string(root, "title", "Untitled mechanism");
    mechanism.description = optional_string(root, "description", "");
    read_output(root, mechanism);
    read_parameters(root, mechanism);
    Linkage& linkage = mechanism.linkage.emplace();
    read_joints(root, linkage);
    read_links(root, linkage);
    read_driver(root, mechanism);
    read_link_points(root, linkage);
    linkage_loops(mechanism);
    check_names(mechanism);
    return mechanism;
  }

  // A file written as a spatial chain of frames (docs/mechanism-files.md, "Spatial chains").
  Mechanism read_chain(const Node& root, Mechanism& mechanism) const {
    check_keys(root, {"title", "description", "parameters", "input", "variables", "frames", "points", "closures",
                      "output"},
               "the top level of a spatial chain (a file of frames; vector loops and joints and links are other forms)");
    mechanism.title = optional_string(root, "title", "Untitled mechanism");
    mechanism.description = optional_string(root, "description", "");
    read_output(root, mechanism);
    read_parameters(root, mechanism);
    SpatialChain& chain = mechanism.chain.emplace();
    if (has(root, "input")) {
      const Node& input = at(root, "input");
      if (!input.is_string()) fail(input, "input must name a driven variable of [variables], e.g. input = \"theta1\"");
      chain.input = input.value<std::string>().value_or("");
      chain.input_where = where(input);
    }
    if (has(root, "variables")) {
      const Node& table = at(root, "variables");
      if (!table.is_table()) fail(table, "[variables] must be a table of name = { value = \"0 deg\", rate = \"1 rad/s\" }");
      for (const auto& [name, value] : ordered(table)) {
        check_identifier(*value, name, "variable");
        if (!value->is_table()) fail(*value, "variable \"" + name + "\" must be a table { value = \"0 deg\", rate = \"1 rad/s\" }");
        check_keys(*value, {"value", "guess", "rate", "second_rate", "rate_name", "second_rate_name"},
                   "variable \"" + name + "\"");
        ChainVariable variable;
        variable.name = name;
        variable.where = where(*value);
        variable.unknown = has(*value, "guess");
        if (variable.unknown && (has(*value, "value") || has(*value, "rate") || has(*value, "second_rate"))) {
          fail(*value, "variable \"" + name + "\" has a guess, so the closures find it: it takes no value, rate or "
                       "second_rate (those are for a variable that drives the chain)");
        }
        const char* given = variable.unknown ? "guess" : "value";
        if (!has(*value, given)) {
          fail(*value, "variable \"" + name + "\" needs value = \"...\" (at t = 0: an angle or a length), or guess = "
                       "\"...\" for one the closures find");
        }
        const Quantity q = quantity(at(*value, given), given);
        if (q.dimension != Dimension::angle && q.dimension != Dimension::length) {
          fail(at(*value, "value"), "variable \"" + name + "\": value must be an angle (\"30 deg\") or a length (\"0.1 m\")");
        }
        variable.dimension = q.dimension;
        variable.value = q.si_value;
        const Dimension rate = rate_dimension(variable.dimension);
        if (has(*value, "rate")) variable.rate = bounded_rate(at(*value, "rate"), "rate", rate);
        if (has(*value, "second_rate")) {
          variable.second_rate = bounded_rate(at(*value, "second_rate"), "second_rate", rate_dimension(rate));
        }
        variable.rate_name = optional_name(*value, "rate_name");
        variable.second_rate_name = optional_name(*value, "second_rate_name");
        chain.variables.push_back(variable);
      }
    }
    const Node& frames = required_table(root, "frames");
    for (const auto& [name, value] : ordered(frames)) {
      check_name(*value, name, "frame");
      if (!value->is_table() || !has(*value, "parent")) {
        fail(*value, "frame \"" + name + "\" must be a table with its parent: { parent = \"E0\", origin = [\"x\", \"y\", "
                                           "\"z\"], turns = [[\"z\", \"theta1\"]] }");
      }
      check_keys(*value, {"parent", "origin", "turns"}, "frame \"" + name + "\"");
      ChainFrame frame;
      frame.name = name;
      frame.where = where(*value);
      frame.parent = string_value(at(*value, "parent"), "parent");
      if (has(*value, "origin")) read_vector(at(*value, "origin"), "origin", frame.origin);
      if (has(*value, "turns")) {
        const Node& turns = at(*value, "turns");
        if (!turns.is_array()) fail(turns, "turns must be a list of [axis, angle] pairs, e.g. [[\"z\", \"theta1\"]]");
        for (const auto& turn : *turns.as_array()) {
          const auto* pair = turn.as_array();
          if (pair == nullptr || pair->size() != 2) {
            fail(turn, "a turn is [axis, angle], e.g. [\"x\", \"-theta4\"] (axis x, y, z or -x, -y, -z)");
          }
          FrameTurn t;
          t.where = where(turn);
          if (!pair->get(0)->is_string()) {  // e.g. a direction vector, [0, 0, 0] among them
            fail(*pair->get(0), "frame \"" + name + "\": a turn's axis is named, \"x\", \"y\" or \"z\" (or \"-x\", ...): "
                                "one of the axes of the frame as turned so far (the parent's for the first turn), "
                                "not a direction vector; a frame whose axis is skew gets a turn first that lines an "
                                "axis up with it");
          }
          t.axis = string_value(*pair->get(0), "axis");
          t.angle = string_value(*pair->get(1), "angle");
          frame.turns.push_back(t);
        }
      }
      chain.frames.push_back(frame);
    }
    if (chain.frames.empty()) fail(frames, "[frames] is empty: name each frame with its parent");
    if (has(root, "points")) {
      const Node& table = at(root, "points");
      if (!table.is_table()) fail(table, "[points] must be a table of name = { frame = \"E3\", at = [\"x\", \"y\", \"z\"] }");
      for (const auto& [name, value] : ordered(table)) {
        check_name(*value, name, "point");
        if (!value->is_table() || !has(*value, "frame")) {
          fail(*value, "point \"" + name + "\" must be written { frame = \"E3\", at = [\"x\", \"y\", \"z\"] }");
        }
        check_keys(*value, {"frame", "at"}, "point \"" + name + "\"");
        ChainPoint point;
        point.name = name;
        point.where = where(*value);
        point.frame = string_value(at(*value, "frame"), "frame");
        if (has(*value, "at")) read_vector(at(*value, "at"), "at", point.at);
        chain.points.push_back(point);
      }
    }
    if (has(root, "closures")) {
      const Node& table = at(root, "closures");
      if (!table.is_table()) fail(table, "[closures] must be a table of name = { between = [\"B\", \"C\"], length = \"L3\" }");
      for (const auto& [name, value] : ordered(table)) {
        check_name(*value, name, "closure");
        if (!value->is_table() || !has(*value, "between") || !has(*value, "length")) {
          fail(*value, "closure \"" + name + "\" must be written { between = [\"B\", \"C\"], length = \"L3\" } (two points "
                       "a fixed distance apart)");
        }
        check_keys(*value, {"between", "length"}, "closure \"" + name + "\"");
        const auto* pair = at(*value, "between").as_array();
        if (pair == nullptr || pair->size() != 2) fail(at(*value, "between"), "between must name two points, e.g. [\"B\", \"C\"]");
        ChainClosure closure;
        closure.name = name;
        closure.where = where(*value);
        closure.from = string_value(*pair->get(0), "between");
        closure.to = string_value(*pair->get(1), "between");
        closure.length = string_value(at(*value, "length"), "length");
        chain.closures.push_back(closure);
      }
    }
    check_names(mechanism);
    return mechanism;
  }

  // A vector in a frame's axes ["x", "y", "z"]: quantities or formulas.
  void read_vector(const Node& value, const std::string& what, std::array<std::string, 3>& out) const {
    const auto* list = value.as_array();
    if (list == nullptr || list->size() != 3) {
      fail(value, what + " must be three components [\"x\", \"y\", \"z\"] in the frame's axes, e.g. "
                         "[\"0 m\", \"L2\", \"0 m\"]");
    }
    for (std::size_t c = 0; c < 3; ++c) out[c] = string_value(*list->get(c), what);
  }

  // A sketch position ["x", "y"]: two quantities or formulas of the parameters.
  void read_position(const Node& value, const std::string& what, std::string& x, std::string& y) const {
    const auto* list = value.as_array();
    if (list == nullptr || list->size() != 2) {
      fail(value, what + " must be a position [\"x\", \"y\"], e.g. [\"0.3 m\", \"Lb\"]");
    }
    x = string_value(*list->get(0), what + " x");
    y = string_value(*list->get(1), what + " y");
  }

  // [joints] or [links], refused past its limit.
  const Node& bounded_table(const Node& root, const std::string& key, std::size_t limit) const {
    const Node& table = required_table(root, key);
    if (table.as_table()->size() > limit) {
      fail(table, "[" + key + "] has " + std::to_string(table.as_table()->size()) + " " + key + "; kinema takes up to " +
                      std::to_string(limit) + " (a mechanism has tens)");
    }
    return table;
  }

  void read_joints(const Node& root, Linkage& linkage) const {
    const Node& table = bounded_table(root, "joints", kMaxJoints);
    for (const auto& [name, value] : ordered(table)) {
      check_identifier(*value, name, "joint");
      if (!value->is_table()) {
        fail(*value, "joint \"" + name + "\" must be a table, e.g. " + name +
                         " = { at = [\"0.1 m\", \"0.2 m\"] } (add ground = true for a fixed pivot)");
      }
      check_keys(*value,
                 {"at", "ground", "slider", "angle", "through", "coordinate", "rate_name", "second_rate_name", "assembly"},
                 "joint \"" + name + "\"");
      Joint joint;
      joint.name = name;
      joint.where = where(*value);
      if (!has(*value, "at")) fail(*value, "joint \"" + name + "\" needs at = [\"x\", \"y\"] (its place in the sketch)");
      read_position(at(*value, "at"), "at", joint.x, joint.y);
      if (has(*value, "ground")) {
        const Node& ground = at(*value, "ground");
        if (!ground.is_boolean()) fail(ground, "ground must be true or false");
        joint.ground = ground.as_boolean()->get();
      }
      if (has(*value, "assembly")) {
        joint.assembly = string_value(at(*value, "assembly"), "assembly");
        // Left out, the sketch's side holds; empty, it would silently say the same.
        if (joint.assembly.find_first_not_of(" \t") == std::string::npos) {
          fail(at(*value, "assembly"), "joint \"" + joint.name + "\": assembly = \"" + joint.assembly +
                                "\" is empty; write \"left of B-D\" or \"right of B-D\" (the side of the line between "
                                "two joints), or leave assembly out for the sketch's side");
        }
      }
      if (has(*value, "slider")) {
        joint.kind = Joint::Kind::slider;
        joint.guide = string_value(at(*value, "slider"), "slider");
        if (joint.ground) {
          fail(*value, "joint \"" + name + "\" is a slider and a ground pivot; a slider on a fixed guide is written "
                           "slider = \"ground\" (without ground = true)");
        }
        if (has(*value, "angle")) joint.angle = string_value(at(*value, "angle"), "angle");
        if (has(*value, "through")) read_position(at(*value, "through"), "through", joint.through_x, joint.through_y);
        if (has(*value, "coordinate")) {
          joint.coordinate = string_value(at(*value, "coordinate"), "coordinate");
          check_identifier(at(*value, "coordinate"), joint.coordinate, "slider coordinate");
        }
        joint.rate_name = optional_name(*value, "rate_name");
        joint.second_rate_name = optional_name(*value, "second_rate_name");
      } else {
        for (const char* key : {"angle", "through", "coordinate", "rate_name", "second_rate_name"}) {
          if (has(*value, key)) {
            fail(at(*value, key), std::string(key) + " belongs to a slider; joint \"" + name +
                                      "\" is a pin (add slider = \"<guide link>\" to make it a slider)");
          }
        }
      }
      linkage.joints.push_back(joint);
    }
    if (linkage.joints.empty()) fail(table, "[joints] is empty: name the joints of the mechanism as in its figure");
  }

  // Link names may start with a digit, as links are numbered in figures ("2", "3").
  void check_link_name(const Node& value, const std::string& name) const {
    if (!is_identifier("L" + name) || name == "ground") {
      fail(value, "link name \"" + one_line(name) + "\" is not valid (letters, digits, _; \"ground\" is the frame)");
    }
  }

  void read_links(const Node& root, Linkage& linkage) const {
    const Node& table = bounded_table(root, "links", kMaxLinks);
    for (const auto& [name, value] : ordered(table)) {
      check_link_name(*value, name);
      Link link;
      link.name = name;
      link.where = where(*value);
      const Node* joints = value;
      if (value->is_table()) {
        check_keys(*value, {"joints", "length", "lengths", "angles", "angle", "rate_name", "second_rate_name"},
                   "link \"" + name + "\"");
        if (!has(*value, "joints")) fail(*value, "link \"" + name + "\" needs joints = [\"B\", \"C\", ...]");
        joints = &at(*value, "joints");
        if (has(*value, "angle")) {
          link.angle_name = string_value(at(*value, "angle"), "angle");
          check_identifier(at(*value, "angle"), link.angle_name, "link angle");
        }
        link.rate_name = optional_name(*value, "rate_name");
        link.second_rate_name = optional_name(*value, "second_rate_name");
      }
      if (!joints->is_array()) fail(*joints, "the joints of link \"" + name + "\" must be a list, e.g. [\"B\", \"C\"]");
      for (const auto& joint : *joints->as_array()) {
        const std::string joint_name = string_value(joint, "joints");
        if (std::find(link.joints.begin(), link.joints.end(), joint_name) != link.joints.end()) {
          fail(joint, "link \"" + name + "\" lists joint \"" + one_line(joint_name) + "\" twice");
        }
        link.joints.push_back(joint_name);
      }
      if (value->is_table() && has(*value, "length")) {
        if (link.joints.size() != 2) {
          fail(at(*value, "length"), "length is for a link with two joints; link \"" + name + "\" has " +
                                         std::to_string(link.joints.size()) +
                                         ": write lengths = { \"C-D\" = \"...\", ... }");
        }
        link.lengths.push_back({{link.joints[0], link.joints[1]}, string_value(at(*value, "length"), "length")});
      }
      if (value->is_table() && has(*value, "lengths")) {
        const Node& lengths = at(*value, "lengths");
        if (!lengths.is_table()) fail(lengths, "lengths must be a table such as { \"C-D\" = \"CD\" }");
        for (const auto& [pair, length] : ordered(lengths)) {
          const auto dash = pair.find('-');
          const std::string a = pair.substr(0, dash), b = dash == std::string::npos ? "" : pair.substr(dash + 1);
          const auto on_link = [&](const std::string& j) {
            return std::find(link.joints.begin(), link.joints.end(), j) != link.joints.end();
          };
          if (dash == std::string::npos || !on_link(a) || !on_link(b) || a == b) {
            fail(*length, "\"" + one_line(pair) + "\" is not two joints of link \"" + name +
                              "\" joined by '-' (e.g. \"" + link.joints[0] + "-" +
                              (link.joints.size() > 1 ? link.joints[1] : std::string("B")) + "\")");
          }
          link.lengths.push_back({{a, b}, string_value(*length, pair)});
        }
      }
      if (value->is_table() && has(*value, "angles")) {
        const Node& angles = at(*value, "angles");
        if (!angles.is_table()) fail(angles, "angles must be a table such as { D = \"180 deg\" }");
        for (const auto& [joint, angle] : ordered(angles)) {
          if (link.joints.size() < 3 || std::find(link.joints.begin() + 2, link.joints.end(), joint) == link.joints.end()) {
            fail(*angle, "angles of link \"" + name + "\" are given for its joints after the second (the angle at its "
                         "first joint from its second to that joint); \"" + one_line(joint) + "\" is not one");
          }
          link.angles.push_back({joint, string_value(*angle, joint)});
        }
      }
      linkage.links.push_back(link);
    }
    if (linkage.links.empty()) fail(table, "[links] is empty: list each moving link and its joints");
  }

  void read_driver(const Node& root, Mechanism& mechanism) const {
    const Node& table = required_table(root, "driver");
    check_keys(table, {"link", "slider", "name", "value", "values", "sweep", "rate", "second_rate", "rate_name",
                       "second_rate_name"},
               "[driver]");
    Linkage& linkage = *mechanism.linkage;
    Input& input = mechanism.input;
    input.where = where(table);
    linkage.driver_where = where(table);
    if (has(table, "link") == has(table, "slider")) {
      fail(table, "[driver] needs either link = \"2\" (a crank: its angle is the input) or slider = \"F\" "
                  "(a slider joint: its coordinate is the input)");
    }
    if (has(table, "link")) linkage.driver_link = string_value(at(table, "link"), "link");
    if (has(table, "slider")) linkage.driver_slider = string_value(at(table, "slider"), "slider");
    if (has(table, "name")) {
      input.name = string_value(at(table, "name"), "name");
      check_identifier(at(table, "name"), input.name, "driver");
    }
    // A crank turns through angles, a slider moves through lengths: say so before the
    // rates are read in the units the values imply.
    const Dimension kind = has(table, "link") ? Dimension::angle : Dimension::length;
    for (const char* key : {"value", "values"}) {
      if (!has(table, key)) continue;
      const Node& node = at(table, key);
      const auto check = [&](const Node& value) {
        const Quantity q = quantity(value, key);
        if (q.dimension != kind && q.dimension != Dimension::number) {
          fail(value, std::string("the driver is a ") + (kind == Dimension::angle ? "crank: its values are angles, e.g. \"30 deg\""
                                                                                  : "slider: its values are lengths, e.g. \"0.2 m\""));
        }
      };
      if (node.is_array()) {
        for (const auto& value : *node.as_array()) check(value);
      } else {
        check(node);
      }
    }
    read_motion(table, "[driver]", input);
  }

  void read_link_points(const Node& root, Linkage& linkage) const {
    if (!has(root, "points")) return;
    const Node& table = at(root, "points");
    if (!table.is_table()) fail(table, "[points] must be a table of name = { link = \"3\", at = [\"x\", \"y\"] }");
    for (const auto& [name, value] : ordered(table)) {
      check_name(*value, name, "point");
      if (!value->is_table() || !has(*value, "link") || !has(*value, "at")) {
        fail(*value, "point \"" + name + "\" must be written { link = \"3\", at = [\"x\", \"y\"] } (the link it is "
                                          "on and its place in the sketch)");
      }
      check_keys(*value, {"link", "at"}, "point \"" + name + "\"");
      LinkPoint point;
      point.name = name;
      point.where = where(*value);
      point.link = string_value(at(*value, "link"), "link");
      read_position(at(*value, "at"), "at", point.x, point.y);
      linkage.points.push_back(point);
    }
  }

  // Parameters, the input and the unknowns share one name space (they are symbols in formulas).
  void check_names(const Mechanism& mechanism) const {
    std::map<std::string, SourceLocation> seen;
    auto add = [&](const std::string& name, const SourceLocation& at, const std::string& what) {
      auto [it, inserted] = seen.emplace(name, at);
      if (!inserted) {
        throw InputError(at.str() + ": duplicate name \"" + name + "\" (" + what +
                         "): it is already defined at " + it->second.str() + "; rename one of them");
      }
    };
    for (const auto& p : mechanism.parameters) add(p.name, p.where, "parameter");
    if (mechanism.chain) {
      for (const auto& v : mechanism.chain->variables) {
        add(v.name, v.where, "variable");
        if (!v.rate_name.empty()) add(v.rate_name, v.where, "rate name");
        if (!v.second_rate_name.empty()) add(v.second_rate_name, v.where, "second rate name");
      }
      return;
    }
    add(mechanism.input.name, mechanism.input.where, "input");
    for (const auto& u : mechanism.unknowns) add(u.name, u.where, "unknown");
  }
};

}  // namespace

InputValues parse_sweep(const std::string& text, double unit_factor, std::size_t max_values) {
  double start = 0, stop = 0, step = 0;
  char colon1 = 0, colon2 = 0;
  std::istringstream in(text);
  if (!(in >> start >> colon1 >> stop >> colon2 >> step) || colon1 != ':' || colon2 != ':' ||
      !(in >> std::ws).eof()) {
    throw InputError("sweep \"" + text + "\" is not start:stop:step (e.g. 0:360:1)");
  }
  return sweep_between(start, stop, step, unit_factor, max_values, "sweep \"" + text + "\"");
}

InputValues sweep_between(double start, double stop, double step, double unit_factor, std::size_t max_values,
                         const std::string& written) {
  if (!std::isfinite(start) || !std::isfinite(stop) || !std::isfinite(step) || step == 0 ||
      (stop - start) / step < 0) {
    throw InputError(written + " never reaches its stop: the step must be non-zero "
                     "and point from start to stop");
  }
  const double count = std::floor((stop - start) / step + 1e-9);
  if (count >= static_cast<double>(max_values)) {
    throw InputError(written + " has more than " + std::to_string(max_values) +
                     " values; use a larger step or split the range");
  }
  return InputValues::sweep(start, step, static_cast<std::size_t>(count) + 1, unit_factor);
}

Mechanism read_mechanism_text(const std::string& text, const std::string& name) {
  return FileReader(name).read(text);
}

Mechanism read_mechanism_file(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": is a directory, not a mechanism file; give the path of a .toml file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the mechanism file (does it exist?)");
  // Read at most one byte past the limit: a stream that never ends (/dev/zero) stops
  // there. In chunks, so that a file of a few KiB touches a few KiB (not a zeroed MiB).
  std::string text;
  char chunk[16384];
  while (text.size() <= kMaxMechanismFileBytes && file.read(chunk, sizeof chunk).gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(file.gcount()));
  }
  if (text.size() > kMaxMechanismFileBytes + 1) text.resize(kMaxMechanismFileBytes + 1);
  if (text.size() > kMaxMechanismFileBytes) {
    throw InputError(path + ": the mechanism file is larger than " + std::to_string(kMaxMechanismFileBytes / 1024) +
                     " KiB; a mechanism file is a few KiB of text");
  }
  return read_mechanism_text(text, path);
}

}  // namespace kinema
