// Textbook simplification of sums of products of sines and cosines:
// sin(a)cos(b) - cos(a)sin(b) -> sin(a-b). Every product of sin/cos factors
// is turned into a sum of single sines/cosines of combined angles
// (product-to-sum), and equal ones are collected.
//
// The simplification is for reading only (the evaluator compiles the plain
// equations), so it has a budget: an expression larger than kSimplifyBudget
// nodes, before or after product-to-sum, is returned as it is (expanded), and a
// ratio as numerator/denominator. A file cannot make kinema wait on it (issue 9).
#pragma once

#include <cstddef>

#include <ginac/ginac.h>

namespace kinema {

/// Largest expression (nodes) the simplification works on.
constexpr std::size_t kSimplifyBudget = 600;

/// Nodes of e, counted up to limit + 1.
std::size_t expression_size(const GiNaC::ex& e, std::size_t limit = kSimplifyBudget);

/// Sum of coefficient * sin(angle) / cos(angle) terms, each angle used once.
/// Coefficients are brought to normal form; the value is unchanged.
GiNaC::ex combine_trig_products(const GiNaC::ex& e);

/// combine_trig_products on numerator and denominator, then common factors cancelled.
GiNaC::ex simplify_ratio(const GiNaC::ex& numerator, const GiNaC::ex& denominator);

}  // namespace kinema
