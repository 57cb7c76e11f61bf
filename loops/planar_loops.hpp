// The vector-loop front end: a Mechanism whose loops are written as complex
// sums of link vectors (or by components) becomes a ConstraintSystem: its formulas
// are read here, and loops/planar_system builds the system from them.
#pragma once

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/formula_reader.hpp"  // understood_functions()
#include "readers/mechanism.hpp"

namespace kinema {

/// Reads every formula, checks names, units (lengths vs angles), functions and
/// counts; throws InputError naming file:line and what to change.
ConstraintSystem build_planar_loops(const Mechanism& mechanism);

/// Top-level terms of a formula as written ("a*exp(I*t) - d" -> "a*exp(I*t)", "-d").
std::vector<std::string> written_terms(const std::string& formula);

}  // namespace kinema
