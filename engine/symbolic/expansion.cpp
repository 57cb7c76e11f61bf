#include "engine/symbolic/expansion.hpp"

namespace kinema {

using GiNaC::ex;

double expanded_terms_estimate(const GiNaC::ex& e, double cap) {
  if (GiNaC::is_a<GiNaC::add>(e)) {
    double terms = 0;
    for (const ex& term : e)
      if ((terms += expanded_terms_estimate(term, cap)) > cap) break;
    return terms;
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    double terms = 1;
    for (const ex& factor : e)
      if ((terms *= expanded_terms_estimate(factor, cap)) > cap) break;
    return terms;
  }
  if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1)) &&
      GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_pos_integer()) {
    // Terms of (t1 + ... + tk)^n: C(n + k - 1, k - 1).
    const double k = expanded_terms_estimate(e.op(0), cap);
    const double n = GiNaC::ex_to<GiNaC::numeric>(e.op(1)).to_double();
    double terms = 1;
    for (double i = 1; i < k && terms <= cap; ++i) terms = terms * (n + i) / i;
    return terms;
  }
  return 1;
}

GiNaC::ex multiplied_out(const GiNaC::ex& e, double budget) {
  return expanded_terms_estimate(e, budget) <= budget ? e.expand() : e;
}

}  // namespace kinema
