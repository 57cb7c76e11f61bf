// The terms of a loop or a point as the joints-and-links front end writes them, each
// [-][I*]factor[*exp(I*(angle))] of names and the file's formulas. The same terms give
// the GiNaC expressions of the constraint system (no text written and read again) and
// the text `kinema loops` prints. Internal: only linkages/ includes it.
#pragma once

#include <string>
#include <vector>

#include "engine/base/source_location.hpp"
#include "engine/constraints/formula_reader.hpp"
#include "loops/planar_system.hpp"

namespace kinema::linkage_detail {

/// A name (of a parameter or a coordinate), or a formula as the file writes it.
struct Operand {
  std::string text;
  bool formula = false;  ///< Written in parentheses in a term.
};

/// A signed term: factor, times I if `times_i`, times exp(I*(sum of `angle`)) if any.
struct Term {
  bool negative = false;
  bool times_i = false;
  Operand factor;
  std::vector<Operand> angle;
};

/// A loop (= 0) or a point (its position) as a sum of terms.
struct TermSum {
  std::string name;
  SourceLocation where;
  std::vector<Term> terms;
  bool is_joint = false;  ///< A point: a joint's.
};

std::vector<Term> negated(std::vector<Term> terms);

/// As a vector-loop file writes it: "BC*exp(I*phi2) - I*y_D"; "0" for no terms.
std::string sum_text(const std::vector<Term>& terms);

/// The sum as expressions of the symbols `formulas` defines, the same that reading
/// sum_text would give; a formula of the file is read, a name is its symbol. `kind`
/// ("loop", "point") names it in messages.
PlanarVector planar_vector(const TermSum& sum, FormulaReader& formulas, const std::string& kind);

}  // namespace kinema::linkage_detail
