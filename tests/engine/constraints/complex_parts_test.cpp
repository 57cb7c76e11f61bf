// engine/symbolic/complex_parts: the real and imaginary parts of planar formulas (all
// symbols real) mean what GiNaC's real_part/imag_part give, in one pass.
#include <doctest/doctest.h>

#include "engine/constraints/complex_parts.hpp"

#include <sstream>

using GiNaC::ex;

namespace {

bool same(const ex& a, const ex& b) { return (a - b).expand().is_zero(); }

// Equal in value at a point (Euler's formula, which expand() does not apply).
bool same_value(const ex& a, const ex& b, const GiNaC::exmap& at) {
  return GiNaC::abs(GiNaC::evalf((a - b).subs(at))) < 1e-12;
}

}  // namespace

TEST_CASE("engine/symbolic/complex_parts: the parts GiNaC gives, for link vectors and what else a loop holds") {
  const GiNaC::realsymbol a("a"), b("b"), x("x"), y("y");
  const ex expressions[] = {
      a * GiNaC::exp(GiNaC::I * x) + b * GiNaC::exp(GiNaC::I * y) - 3,  // a loop
      2 * GiNaC::I * x + a,                                           // a complex number as a coefficient
      (x + GiNaC::I * y) * GiNaC::exp(GiNaC::I * (x - y)),            // a slider's offset vector
      GiNaC::I * GiNaC::exp(GiNaC::I * x) * GiNaC::exp(-GiNaC::I * y),
      GiNaC::sin(x + GiNaC::I * y) + GiNaC::cos(2 * GiNaC::I * x - y),  // complex arguments
      GiNaC::pow(a + GiNaC::I * b, 2),                                 // handed to GiNaC
      a * GiNaC::cos(x) + b,                                          // real throughout
  };
  const GiNaC::exmap at{{a, 2.0}, {b, 0.7}, {x, 0.3}, {y, 1.1}};
  for (const ex& e : expressions) {
    CAPTURE(e);
    const kinema::ComplexParts parts = kinema::complex_parts(e);
    CHECK(same(parts.real, e.real_part()));
    CHECK(same(parts.imag, e.imag_part()));
    CHECK(same_value(kinema::real_part_of(e) + GiNaC::I * kinema::imag_part_of(e), e, at));
  }
}

TEST_CASE("engine/symbolic/complex_parts: a call without I is real, whatever GiNaC knows of it") {
  const GiNaC::realsymbol a("a"), x("x");
  // GiNaC leaves real_part(atan(x)) unevaluated.
  CHECK(kinema::real_part_of(a * GiNaC::atan(x) * GiNaC::exp(GiNaC::I * x)).is_equal(
      (a * GiNaC::atan(x) * GiNaC::cos(x)).expand()));
  CHECK(kinema::imag_part_of(GiNaC::sqrt(x) + GiNaC::atan(x)).is_zero());
}

// GiNaC splits sin(u) by asking for both parts of u, and so on down: 2^40 calls here.
TEST_CASE("engine/symbolic/complex_parts: nested calls split in one pass") {
  const GiNaC::realsymbol a("a"), x("x");
  ex nested = x;
  for (int k = 0; k < 40; ++k) nested = GiNaC::sin(nested);
  const kinema::ComplexParts parts = kinema::complex_parts(a * GiNaC::exp(GiNaC::I * nested));
  CHECK(parts.real.is_equal(a * GiNaC::cos(nested)));
  CHECK(parts.imag.is_equal(a * GiNaC::sin(nested)));
}
