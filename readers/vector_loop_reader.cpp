// Reads a file written as vector loops (docs/mechanism-files.md, "Vector loops"): [input],
// [unknowns], [loops] and [points], as written; loops/ builds their equations. A file of
// its own so that each form of mechanism file is read in one place.
#include "readers/file_reader.hpp"

#include "engine/base/errors.hpp"
#include "engine/base/naming.hpp"
#include "engine/base/units.hpp"
#include "readers/mechanism_file.hpp"  // check_shared_names

namespace kinema::reading {
namespace {

class VectorLoopReader : public FileReader {
 public:
  using FileReader::FileReader;

  // The top level of a file of vector loops (docs/mechanism-files.md, "Vector loops").
  void read(const Node& root, Mechanism& mechanism) const {
    check_keys(root, {"title", "description", "parameters", "input", "unknowns", "loops",
                      "points", "output", "problem"},
               "the top level");
    read_heading(root, mechanism);
    read_input(root, mechanism);
    read_unknowns(root, mechanism);
    read_loops(root, mechanism);
    read_points(root, mechanism);
    check_shared_names(mechanism);
  }

 private:
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
};

}  // namespace

void read_vector_loops(const std::string& file, const Node& root, Mechanism& mechanism) {
  VectorLoopReader(file).read(root, mechanism);
}

}  // namespace kinema::reading
