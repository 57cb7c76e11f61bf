#include <kinema/engine/symbolic/differentiate.hpp>

#include <string>

namespace kinema {

GiNaC::ex partial(const GiNaC::ex& e, const GiNaC::symbol& s) {
  using GiNaC::ex;
  if (!e.has(s)) return 0;
  if (GiNaC::is_a<GiNaC::add>(e)) {  // the terms with s, each differentiated
    GiNaC::exvector terms;
    for (const ex& term : e) {
      const ex derivative = partial(term, s);  // 0 at once where s is absent
      if (!derivative.is_zero()) terms.push_back(derivative);
    }
    return GiNaC::add(terms);
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {  // product rule over the factors with s
    GiNaC::exvector terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex derivative = partial(e.op(i), s);
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
    if (name == "sin") return GiNaC::cos(e.op(0)) * partial(e.op(0), s);
    if (name == "cos") return -GiNaC::sin(e.op(0)) * partial(e.op(0), s);
    if (name == "exp") return e * partial(e.op(0), s);
  }
  return e.diff(s);
}

}  // namespace kinema
