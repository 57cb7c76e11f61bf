#include <kinema/engine/symbolic/complex_parts.hpp>

#include <string>

namespace kinema {
namespace {

using GiNaC::ex;

// Whether a non-real number (I, 2*I, 1+I) occurs anywhere in e; has(I) misses 2*I.
bool has_imaginary(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return !e.info(GiNaC::info_flags::real);
  for (const ex& operand : e)
    if (has_imaginary(operand)) return true;
  return false;
}

// GiNaC leaves real_part(f) unevaluated for a call f it does not know to be real;
// without I inside, f is real here.
struct ResolveRealParts : GiNaC::map_function {
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string& name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      if ((name == "real_part" || name == "imag_part") && !has_imaginary(e.op(0))) {
        return name == "real_part" ? e.op(0).map(*this) : ex(0);
      }
    }
    return e.map(*this);
  }
};

}  // namespace

ComplexParts complex_parts(const ex& e) {
  if (!has_imaginary(e)) return {e, 0};
  if (GiNaC::is_a<GiNaC::numeric>(e)) return {e.real_part(), e.imag_part()};
  if (GiNaC::is_a<GiNaC::add>(e)) {
    GiNaC::exvector real, imag;
    for (const ex& term : e) {
      const ComplexParts p = complex_parts(term);
      real.push_back(p.real);
      imag.push_back(p.imag);
    }
    return {GiNaC::add(real), GiNaC::add(imag)};
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    ex real = 1, imag = 0;
    for (const ex& factor : e) {
      const ComplexParts p = complex_parts(factor);
      if (p.imag.is_zero()) {
        real *= p.real;
        imag *= p.real;
      } else {
        const ex next_real = real * p.real - imag * p.imag;
        imag = imag * p.real + real * p.imag;
        real = next_real;
      }
    }
    return {real, imag};
  }
  if (GiNaC::is_a<GiNaC::function>(e) && e.nops() == 1) {
    const std::string& name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    const bool known = name == "exp" || name == "sin" || name == "cos";
    if (known) {
      const ComplexParts u = complex_parts(e.op(0));
      if (name == "exp") return {GiNaC::exp(u.real) * GiNaC::cos(u.imag), GiNaC::exp(u.real) * GiNaC::sin(u.imag)};
      if (name == "sin") return {GiNaC::sin(u.real) * GiNaC::cosh(u.imag), GiNaC::cos(u.real) * GiNaC::sinh(u.imag)};
      return {GiNaC::cos(u.real) * GiNaC::cosh(u.imag), -GiNaC::sin(u.real) * GiNaC::sinh(u.imag)};
    }
  }
  // Powers and other calls with I inside, rare in a loop: GiNaC's own split.
  ResolveRealParts resolve;
  return {resolve(e.real_part()), resolve(e.imag_part())};
}

ex real_part_of(const ex& e) { return complex_parts(e).real.expand(); }

ex imag_part_of(const ex& e) { return complex_parts(e).imag.expand(); }

}  // namespace kinema
