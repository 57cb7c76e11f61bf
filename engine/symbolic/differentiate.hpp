// Partial derivatives as GiNaC's diff gives them, without its cost where the symbol is
// absent. GiNaC differentiates a function call (sin, cos) by first trying an explicit
// derivative, which throws and is caught before the chain rule is applied: a couple of
// microseconds each time, also when the argument does not contain the symbol at all
// (about 190 times for the four-bar, 500 for Problem 4.4, most of a model's derivation).
#pragma once

#include <ginac/ginac.h>

namespace kinema {

/// d e / d s: the same expression as e.diff(s). The terms of sums and the factors of
/// products that do not contain s are not differentiated, and sin, cos and exp by the
/// chain rule as GiNaC applies it (their derivatives as GiNaC registers them).
GiNaC::ex partial(const GiNaC::ex& e, const GiNaC::symbol& s);

}  // namespace kinema
