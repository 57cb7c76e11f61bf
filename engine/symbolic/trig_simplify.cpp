#include "engine/symbolic/trig_simplify.hpp"

#include "engine/constraints/expression_parts.hpp"

#include <map>
#include <vector>

namespace kinema {
namespace {

using GiNaC::ex;

struct TrigFactor {
  bool is_sin;
  ex angle;
};

struct Term {
  ex coefficient;
  std::vector<TrigFactor> factors;
};

// Splits one product into its sin/cos factors (with integer powers unrolled) and the rest.
Term split_term(const ex& term) {
  Term result{1, {}};
  auto take = [&](const ex& factor) {
    ex base = factor;
    int power = 1;
    if (GiNaC::is_a<GiNaC::power>(factor) && GiNaC::is_a<GiNaC::numeric>(factor.op(1)) &&
        GiNaC::ex_to<GiNaC::numeric>(factor.op(1)).is_pos_integer()) {
      base = factor.op(0);
      power = GiNaC::ex_to<GiNaC::numeric>(factor.op(1)).to_int();
    }
    if (is_function(base, "sin") || is_function(base, "cos")) {
      for (int i = 0; i < power; ++i) result.factors.push_back({is_function(base, "sin"), base.op(0)});
    } else {
      result.coefficient *= factor;
    }
  };
  if (GiNaC::is_a<GiNaC::mul>(term)) {
    for (const ex& factor : term) take(factor);
  } else {
    take(term);
  }
  return result;
}

// Product-to-sum until each term has at most one sin/cos factor (a term with k
// factors gives 2^(k-1) terms: the caller stops past the budget).
void reduce(const Term& term, std::vector<Term>& out) {
  if (out.size() > kSimplifyBudget) return;
  if (term.factors.size() <= 1) {
    out.push_back(term);
    return;
  }
  std::vector<TrigFactor> rest(term.factors.begin() + 2, term.factors.end());
  const TrigFactor& f = term.factors[0];
  const TrigFactor& g = term.factors[1];
  const ex sum = (f.angle + g.angle).expand();
  const ex difference = (f.angle - g.angle).expand();
  const ex half = term.coefficient / 2;
  auto with = [&](const ex& coefficient, bool is_sin, const ex& angle) {
    Term next{coefficient, rest};
    next.factors.push_back({is_sin, angle});
    reduce(next, out);
  };
  if (f.is_sin && g.is_sin) {         // sin f sin g = (cos(f-g) - cos(f+g))/2
    with(half, false, difference);
    with(-half, false, sum);
  } else if (!f.is_sin && !g.is_sin) {  // cos f cos g = (cos(f-g) + cos(f+g))/2
    with(half, false, difference);
    with(half, false, sum);
  } else if (f.is_sin) {              // sin f cos g = (sin(f+g) + sin(f-g))/2
    with(half, true, sum);
    with(half, true, difference);
  } else {                            // cos f sin g = (sin(f+g) - sin(f-g))/2
    with(half, true, sum);
    with(-half, true, difference);
  }
}

int negative_terms(const ex& e) {
  int count = 0;
  auto negative = [](const ex& term) {
    const ex c = GiNaC::is_a<GiNaC::mul>(term) ? term.op(term.nops() - 1) : ex(1);
    return GiNaC::is_a<GiNaC::numeric>(c) && GiNaC::ex_to<GiNaC::numeric>(c).is_negative();
  };
  if (GiNaC::is_a<GiNaC::add>(e)) {
    for (const ex& term : e) count += negative(term);
  } else {
    count += negative(e);
  }
  return count;
}

// Chooses between angle and -angle the spelling with fewer minus signs
// (cos(theta3), sin(theta4-theta2)), ties broken by GiNaC's canonical order.
ex canonical_angle(const ex& angle, bool& negated) {
  const ex a = angle.expand();
  const ex minus = (-angle).expand();
  const int na = negative_terms(a), nm = negative_terms(minus);
  negated = nm < na || (nm == na && GiNaC::ex_is_less()(minus, a));
  return negated ? minus : a;
}

}  // namespace

std::size_t expression_size(const GiNaC::ex& e, std::size_t limit) {
  std::size_t nodes = 0;
  for (auto it = e.preorder_begin(); it != e.preorder_end() && nodes <= limit; ++it) ++nodes;
  return nodes;
}

GiNaC::ex combine_trig_products(const GiNaC::ex& e) {
  if (expression_size(e) > kSimplifyBudget) return e;
  const ex expanded = e.expand();
  if (expression_size(expanded) > kSimplifyBudget) return expanded;
  std::vector<Term> terms;
  if (GiNaC::is_a<GiNaC::add>(expanded)) {
    for (const ex& term : expanded) reduce(split_term(term), terms);
  } else {
    reduce(split_term(expanded), terms);
  }
  if (terms.size() > kSimplifyBudget) return expanded;
  // Collect coefficients by the trig function they multiply (1 for none).
  std::map<ex, ex, GiNaC::ex_is_less> collected;
  for (const Term& term : terms) {
    ex coefficient = term.coefficient;
    ex key = 1;
    if (!term.factors.empty()) {
      bool negated = false;
      const ex angle = canonical_angle(term.factors[0].angle, negated);
      if (term.factors[0].is_sin) {
        key = GiNaC::sin(angle);
        if (negated) coefficient = -coefficient;
      } else {
        key = GiNaC::cos(angle);
      }
      // sin(0) and cos(0) evaluate to numbers: fold them into the constant term.
      if (GiNaC::is_a<GiNaC::numeric>(key)) {
        coefficient *= key;
        key = 1;
      }
    }
    auto found = collected.find(key);
    if (found == collected.end()) collected.emplace(key, coefficient);
    else found->second += coefficient;
  }
  ex result = 0;
  for (const auto& [key, coefficient] : collected) {
    const ex c = GiNaC::normal(coefficient);
    if (!c.is_zero()) result += c * key;
  }
  return result;
}

GiNaC::ex simplify_ratio(const GiNaC::ex& numerator, const GiNaC::ex& denominator) {
  if (expression_size(numerator) + expression_size(denominator) > kSimplifyBudget) return numerator / denominator;
  const ex n = combine_trig_products(numerator);
  const ex d = combine_trig_products(denominator);
  if (expression_size(n) + expression_size(d) > kSimplifyBudget) return numerator / denominator;
  // normal() treats sin/cos as opaque symbols, so it cancels common factors
  // such as link lengths without expanding the trig terms again.
  return GiNaC::normal(n / d);
}

}  // namespace kinema
