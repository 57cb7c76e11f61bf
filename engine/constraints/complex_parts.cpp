#include "engine/constraints/complex_parts.hpp"

#include <optional>
#include <string>
#include <vector>

#include "engine/constraints/differentiate.hpp"

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

// The parts of e, or nullopt when no non-real number occurs in e (it is real as written).
// Bottom-up, so each node is looked at once: asking has_imaginary at every level of a
// nesting was quadratic in its depth.
std::optional<ComplexParts> split(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    if (e.info(GiNaC::info_flags::real)) return std::nullopt;
    return ComplexParts{e.real_part(), e.imag_part()};
  }
  const bool is_add = GiNaC::is_a<GiNaC::add>(e), is_mul = GiNaC::is_a<GiNaC::mul>(e);
  if (is_add || is_mul) {
    std::vector<std::optional<ComplexParts>> parts;
    parts.reserve(e.nops());
    bool complex = false;
    for (const ex& operand : e) {
      parts.push_back(split(operand));
      complex = complex || parts.back().has_value();
    }
    if (!complex) return std::nullopt;
    const auto part = [&](std::size_t i) { return parts[i] ? *parts[i] : ComplexParts{e.op(i), 0}; };
    if (is_add) {
      GiNaC::exvector real, imag;
      for (std::size_t i = 0; i < parts.size(); ++i) {
        const ComplexParts p = part(i);
        real.push_back(p.real);
        imag.push_back(p.imag);
      }
      return ComplexParts{GiNaC::add(real), GiNaC::add(imag)};
    }
    ex real = 1, imag = 0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const ComplexParts p = part(i);
      if (p.imag.is_zero()) {
        real *= p.real;
        imag *= p.real;
      } else {
        const ex next_real = real * p.real - imag * p.imag;
        imag = imag * p.real + real * p.imag;
        real = next_real;
      }
    }
    return ComplexParts{real, imag};
  }
  if (GiNaC::is_a<GiNaC::function>(e) && e.nops() == 1) {
    const std::string& name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if (name == "exp" || name == "sin" || name == "cos") {
      const std::optional<ComplexParts> u = split(e.op(0));
      if (!u) return std::nullopt;
      if (name == "exp") return ComplexParts{GiNaC::exp(u->real) * GiNaC::cos(u->imag), GiNaC::exp(u->real) * GiNaC::sin(u->imag)};
      if (name == "sin") return ComplexParts{GiNaC::sin(u->real) * GiNaC::cosh(u->imag), GiNaC::cos(u->real) * GiNaC::sinh(u->imag)};
      return ComplexParts{GiNaC::cos(u->real) * GiNaC::cosh(u->imag), -GiNaC::sin(u->real) * GiNaC::sinh(u->imag)};
    }
  }
  if (!has_imaginary(e)) return std::nullopt;
  // Powers and other calls with I inside, rare in a loop: GiNaC's own split.
  ResolveRealParts resolve;
  return ComplexParts{resolve(e.real_part()), resolve(e.imag_part())};
}

}  // namespace

ComplexParts complex_parts(const ex& e) {
  std::optional<ComplexParts> parts = split(e);
  return parts ? *parts : ComplexParts{e, 0};
}

ex real_part_of(const ex& e) { return multiplied_out(complex_parts(e).real); }

ex imag_part_of(const ex& e) { return multiplied_out(complex_parts(e).imag); }

}  // namespace kinema
