// The vector-loop front end: a Mechanism whose loops are written as complex
// sums of link vectors becomes a ConstraintSystem. Each loop gives two
// labelled scalar equations, its x (real) and y (imaginary) parts; all
// symbols are real (GiNaC realsymbol) so that those parts simplify.
#pragma once

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/formula_reader.hpp"  // understood_functions()
#include "readers/mechanism.hpp"

namespace kinema {

/// Parses every formula, checks names, units (lengths vs angles), functions and
/// counts; throws InputError naming file:line and what to change.
ConstraintSystem build_planar_loops(const Mechanism& mechanism);

/// Top-level terms of a formula as written ("a*exp(I*t) - d" -> "a*exp(I*t)", "-d").
std::vector<std::string> written_terms(const std::string& formula);

}  // namespace kinema
