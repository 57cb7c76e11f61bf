// Loop-closure equations Phi(q, theta) = 0, built symbolically from the
// mechanism's vector loops: each complex loop gives its x (real) and y
// (imaginary) scalar equations. All symbols are real (GiNaC realsymbol) so
// that real and imaginary parts simplify.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include <kinema/loops/mechanism.hpp>

namespace kinema {

struct LoopClosure {
  std::vector<GiNaC::realsymbol> parameters;  ///< In file order.
  std::vector<double> parameter_values;       ///< SI, same order.
  GiNaC::exmap parameter_formulas;            ///< Formula parameters -> their formula.
  GiNaC::realsymbol input;                    ///< The driver coordinate theta.
  std::vector<GiNaC::realsymbol> unknowns;    ///< q, in file order.

  std::vector<GiNaC::ex> loop_vectors;     ///< Each loop as a complex expression (= 0).
  std::vector<GiNaC::ex> equations;        ///< Scalar equations: loop k gives rows 2k (x), 2k+1 (y).
  std::vector<std::size_t> equation_loop;  ///< Loop index of each scalar equation.

  std::vector<GiNaC::ex> point_positions;  ///< Complex x + I*y of each named point.
  std::vector<GiNaC::ex> point_x;
  std::vector<GiNaC::ex> point_y;
};

/// Parses every formula, checks names, units (lengths vs angles) and counts;
/// throws InputError naming file:line and what to change.
LoopClosure build_loop_closure(const Mechanism& mechanism);

/// Replaces formula parameters by their formulas (down to quantity parameters).
GiNaC::ex expand_parameter_formulas(const LoopClosure& closure, const GiNaC::ex& e);

}  // namespace kinema
