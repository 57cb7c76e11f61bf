// Partial derivatives as GiNaC's diff gives them, without its cost where the symbol is
// absent. GiNaC differentiates a function call (sin, cos) by first trying an explicit
// derivative, which throws and is caught before the chain rule is applied: a couple of
// microseconds each time, also when the argument does not contain the symbol at all
// (about 190 times for the four-bar, 500 for Problem 4.4, most of a model's derivation).
#pragma once

#include <string>

#include <ginac/ginac.h>

#include "engine/symbolic/expansion.hpp"

namespace kinema {

/// d e / d s: the same expression as e.diff(s). The terms of sums and the factors of
/// products that do not contain s are not differentiated, and sin, cos and exp by the
/// chain rule as GiNaC applies it (their derivatives as GiNaC registers them).
GiNaC::ex partial(const GiNaC::ex& e, const GiNaC::symbol& s);

/// Largest d/dt of a formula (nodes, estimated) kinema builds: a product of 100 cosines
/// has a million nodes in its acceleration, which take minutes to build, compile and print.
constexpr double kDerivativeBudget = 500000;

/// The size (nodes) of d/dt e through the moving symbols (coordinates and rates), as
/// estimated from e alone: the product rule copies the other factors for each factor
/// that moves, the chain rule the call for its argument's derivative.
double derivative_size_estimate(const GiNaC::ex& e, const GiNaC::exset& moving);

/// Throws InputError "<what>: its <formula> formula would have about N terms and
/// factors..." when derivative_size_estimate(e, moving) is over the budget.
void check_derivative_size(const GiNaC::ex& e, const GiNaC::exset& moving, const std::string& what,
                           const std::string& formula);

}  // namespace kinema
