// The mechanism as the user described it: names, numbers in SI, and the
// formulas as written, each with the file line it came from (for messages).
// Nothing here is symbolic yet; loop_closure.hpp turns it into equations.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <kinema/loops/units.hpp>

namespace kinema {

/// Where something was written, for messages ("four_bar.toml:12").
struct SourceLocation {
  std::string file;
  int line = 0;
  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

/// A named constant: a quantity ("150 mm") or a formula of earlier parameters ("CD + CE").
struct Parameter {
  std::string name;
  std::string text;          ///< As written.
  std::optional<Quantity> quantity;  ///< Set when written as a quantity.
  std::string formula;       ///< Set when written as a formula.
  SourceLocation where;
};

/// A coordinate whose value the loops determine (angle or slider length).
struct Unknown {
  std::string name;
  Dimension dimension = Dimension::angle;  ///< angle or length
  double guess = 0.0;        ///< SI starting value: picks the assembly branch.
  std::string rate_name;     ///< Printed name of the first time derivative (e.g. omega3).
  std::string second_rate_name;  ///< Printed name of the second (e.g. alpha3).
  std::string latex_name;    ///< Optional LaTeX spelling (later printers).
  SourceLocation where;
};

/// The driver coordinate: crank angle or slider length, with its motion.
struct Input {
  std::string name;
  Dimension dimension = Dimension::angle;  ///< angle or length
  std::vector<double> values;  ///< SI values from the file (may be empty: CLI gives them).
  double rate = 0.0;           ///< SI; negative = clockwise / retracting.
  double second_rate = 0.0;    ///< SI.
  std::string rate_name;
  std::string second_rate_name;
  SourceLocation where;
};

/// A vector loop, = 0: either complex ("a*exp(I*theta2) + ...") or two scalar formulas.
struct Loop {
  std::string name;
  std::string complex_formula;  ///< Empty when x_formula / y_formula are given.
  std::string x_formula;
  std::string y_formula;
  SourceLocation where;
};

/// A named point whose position is a complex formula x + I*y.
struct Point {
  std::string name;
  std::string formula;
  SourceLocation where;
};

struct OutputUnits {
  std::string length = "m";  ///< Lengths in this unit, velocities in unit/s, ...
  double length_factor = 1.0;  ///< SI metres per output unit.
};

struct Mechanism {
  std::string title;
  std::string description;
  std::string source_file;  ///< Path as given (for messages).
  std::vector<Parameter> parameters;
  Input input;
  std::vector<Unknown> unknowns;
  std::vector<Loop> loops;
  std::vector<Point> points;
  OutputUnits output;
};

}  // namespace kinema
