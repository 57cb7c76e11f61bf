// Multiplying a formula out within a budget of terms, for printing and for solving: its
// own header, so that a printer that shows a formula multiplied out includes no header
// of the derivation.
#pragma once

#include <ginac/ginac.h>

namespace kinema {

/// How many terms e has once multiplied out (GiNaC's expand(), which leaves function
/// arguments and negative or fractional powers as they are), estimated from the top and
/// capped just past `cap`: a product of n sums of two terms has 2^n.
double expanded_terms_estimate(const GiNaC::ex& e, double cap);

/// Terms a formula is multiplied out to (its terms collected, for printing and solving);
/// past it the formula is left as it is: the chain rule of tan nested n deep is a product
/// of n sums 1 + tan^2(...), 2^n terms multiplied out (tan nested 10 deep never finished
/// loading). The samples' formulas have tens of terms.
constexpr double kMultiplyOutBudget = 256;

/// e.expand() when that has at most `budget` terms (estimated first), else e.
GiNaC::ex multiplied_out(const GiNaC::ex& e, double budget = kMultiplyOutBudget);

}  // namespace kinema
