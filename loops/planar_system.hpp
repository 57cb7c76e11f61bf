// The planar constraint system built from GiNaC expressions, for both planar front ends:
// the vector-loop file reads its loops' text (loops/planar_loops), the joints-and-links
// front end builds its loops' expressions from their terms (linkages/linkage_loops).
// Each loop gives two labelled scalar equations, its x (real) and y (imaginary) parts;
// all symbols are real (GiNaC realsymbol) so that those parts simplify.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/formula_reader.hpp"
#include "engine/constraints/length_power.hpp"
#include "readers/mechanism.hpp"

namespace kinema {

/// A loop or a point as an expression of the builder's symbols.
struct PlanarVector {
  std::string name;
  SourceLocation where;
  GiNaC::ex vector;              ///< x + I*y
  std::vector<GiNaC::ex> terms;  ///< In the order written; their sum is `vector`.
  std::string formula;           ///< As written, for messages; empty when built from terms.
  bool is_joint = false;         ///< A point: a joint of a joints-and-links file.
};

/// Use in this order: construct, add_loop for each loop, end_loops, add_point for each
/// point, system. Each step throws InputError naming file:line and what to change.
class PlanarSystemBuilder {
 public:
  /// The parameters (a formula read here, of earlier parameters), the driver and the
  /// unknowns of `declarations` as symbols, rates after every coordinate; its loops and
  /// points are not read.
  explicit PlanarSystemBuilder(const Mechanism& declarations);

  /// Reads formulas of the symbols so far (and defines nothing else).
  FormulaReader& formulas() { return formulas_; }

  /// A loop written as one complex sum: x and y are its real and imaginary parts.
  void add_loop(const PlanarVector& loop);
  /// A loop written by components (real, checked by the caller); `loop.vector` is x + I*y.
  void add_loop(const PlanarVector& loop, const GiNaC::ex& x, const GiNaC::ex& y);
  /// After the loops: as many scalar equations as unknowns, each unknown in one.
  void end_loops();
  void add_point(const PlanarVector& point);

  ConstraintSystem system() &&;

 private:
  // A parameter written as a bare number ("40") is a plain number (a ratio: p = "k*a"),
  // not metres: powers_ leaves it out (a formula with it may be anything), plain_powers_
  // counts it as of no length. A formula that is a length with the one and not with the
  // other uses such a number as a length.
  struct PlainNumber {
    GiNaC::realsymbol symbol;
    std::string name, text;
    SourceLocation where;
  };

  const Mechanism& declarations_;
  ConstraintSystem system_;
  // One reader for every formula: its symbol table grows as names are defined
  // (a parser per formula copied the table each time: quadratic in the parameters).
  FormulaReader formulas_;
  LengthPower::Powers powers_;
  std::vector<PlainNumber> plain_numbers_;
  LengthPower::Powers plain_powers_;
  GiNaC::exmap formulas_of_parameters_;
  std::set<std::string> taken_;  ///< Names of symbols so far (rate names must not clash).

  void add_parameters();
  void add_coordinates();
  GiNaC::realsymbol symbol(const std::string& name, const std::string& latex = "");
  GiNaC::realsymbol rate_symbol(const std::string& given, const std::string& coordinate, int order,
                                const SourceLocation& where, const std::string& latex_coordinate);
  void check_length(const GiNaC::ex& e, const std::string& context, const std::string& what) const;
  bool misuses_plain_numbers(const GiNaC::ex& e, bool length) const;
  void check_plain_numbers(const GiNaC::ex& e, const std::string& used_in) const;
  std::string unknown_list() const;
};

}  // namespace kinema
