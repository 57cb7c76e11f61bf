#include "engine/constraints/differentiate.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/work_count.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

// 10.3 million, 500 thousand: an estimate to three digits.
std::string approximate_count(double n) {
  if (n >= 1e12) return "over a million million";
  const char* unit = n >= 1e9 ? " billion" : n >= 1e6 ? " million" : n >= 1e3 ? " thousand" : "";
  const double scale = n >= 1e9 ? 1e9 : n >= 1e6 ? 1e6 : n >= 1e3 ? 1e3 : 1;
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", n / scale);
  return text + std::string(unit);
}

struct SizeEstimate {
  double nodes = 0, derivative = 0;  // of e and of d/dt e (0: e does not move)
};

// The product rule gives a copy of the other factors for each factor that moves, the
// chain rule a copy of the call (or power) times the argument's derivative.
SizeEstimate estimate_sizes(const ex& e, const GiNaC::exset& moving) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return {1, moving.count(e) != 0 ? 1.0 : 0.0};
  SizeEstimate total{1, 0};
  std::vector<SizeEstimate> parts;
  for (const ex& operand : e) {
    parts.push_back(estimate_sizes(operand, moving));
    total.nodes += parts.back().nodes;
  }
  for (const SizeEstimate& part : parts) {
    if (part.derivative == 0) continue;
    if (GiNaC::is_a<GiNaC::add>(e)) total.derivative += part.derivative;
    else if (GiNaC::is_a<GiNaC::mul>(e)) total.derivative += part.derivative + total.nodes - part.nodes;
    else total.derivative += total.nodes + part.derivative;
  }
  return total;
}

// d e / d s, term by term and factor by factor (partial's recursion, not counted again).
ex partial_derivative(const ex& e, const GiNaC::symbol& s) {
  if (!e.has(s)) return 0;
  if (GiNaC::is_a<GiNaC::add>(e)) {  // the terms with s, each differentiated
    GiNaC::exvector terms;
    for (const ex& term : e) {
      const ex derivative = partial_derivative(term, s);  // 0 at once where s is absent
      if (!derivative.is_zero()) terms.push_back(derivative);
    }
    return GiNaC::add(terms);
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {  // product rule over the factors with s
    GiNaC::exvector terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex derivative = partial_derivative(e.op(i), s);
      if (derivative.is_zero()) continue;
      GiNaC::exvector factors;
      factors.reserve(e.nops());
      for (std::size_t j = 0; j < e.nops(); ++j) factors.push_back(j == i ? derivative : e.op(j));
      terms.push_back(GiNaC::mul(factors));
    }
    return GiNaC::add(terms);
  }
  // GiNaC's chain rule for these: the registered derivative times the argument's.
  if (GiNaC::is_a<GiNaC::function>(e) && e.nops() == 1) {
    const std::string& name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if (name == "sin") return GiNaC::cos(e.op(0)) * partial_derivative(e.op(0), s);
    if (name == "cos") return -GiNaC::sin(e.op(0)) * partial_derivative(e.op(0), s);
    if (name == "exp") return e * partial_derivative(e.op(0), s);
  }
  return e.diff(s);
}

}  // namespace

GiNaC::ex partial(const GiNaC::ex& e, const GiNaC::symbol& s) {
  count_work(Work::differentiation);
  return partial_derivative(e, s);
}

double derivative_size_estimate(const GiNaC::ex& e, const GiNaC::exset& moving) {
  return estimate_sizes(e, moving).derivative;
}

void check_derivative_size(const GiNaC::ex& e, const GiNaC::exset& moving, const std::string& what,
                           const std::string& formula) {
  const double estimate = derivative_size_estimate(e, moving);
  if (estimate <= kDerivativeBudget) return;
  throw InputError(what + ": its " + formula + " formula would have about " + approximate_count(estimate) +
                   " terms and factors, and kinema derives up to " + approximate_count(kDerivativeBudget) +
                   ": write it with fewer nested products and functions (e.g. as a sum of link vectors)");
}

GiNaC::exset symbols_of(const GiNaC::ex& e) {
  GiNaC::exset found;
  const auto collect = [&found](const auto& self, const GiNaC::ex& x) -> void {
    if (GiNaC::is_a<GiNaC::symbol>(x)) found.insert(x);
    for (const GiNaC::ex& operand : x) self(self, operand);
  };
  collect(collect, e);
  return found;
}

GiNaC::ex time_derivative(const GiNaC::ex& e, const std::vector<SymbolMotion>& motions) {
  // Only the symbols e contains are differentiated: a system of many loops has thousands
  // of coordinates, and each of its formulas a handful.
  count_work(Work::differentiation);
  const GiNaC::exset symbols = symbols_of(e);
  GiNaC::exvector terms;
  for (const SymbolMotion& m : motions)
    if (symbols.count(m.symbol) != 0) terms.push_back(partial_derivative(e, GiNaC::ex_to<GiNaC::symbol>(m.symbol)) * m.rate);
  return GiNaC::add(terms);
}

}  // namespace kinema
