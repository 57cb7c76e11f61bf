// Textbook simplification of sums of products of sines and cosines:
// sin(a)cos(b) - cos(a)sin(b) -> sin(a-b). Every product of sin/cos factors
// is turned into a sum of single sines/cosines of combined angles
// (product-to-sum), and equal ones are collected.
#pragma once

#include <ginac/ginac.h>

namespace kinema {

/// Sum of coefficient * sin(angle) / cos(angle) terms, each angle used once.
/// Coefficients are brought to normal form; the value is unchanged.
GiNaC::ex combine_trig_products(const GiNaC::ex& e);

/// combine_trig_products on numerator and denominator, then common factors cancelled.
GiNaC::ex simplify_ratio(const GiNaC::ex& numerator, const GiNaC::ex& denominator);

}  // namespace kinema
