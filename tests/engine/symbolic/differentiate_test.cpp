// engine/symbolic/differentiate: partial() is GiNaC's diff, the same expression (not
// only the same meaning: printed formulas and the tape's order come from it), on the
// shapes a derivation meets and on what it hands back to GiNaC.
#include <doctest/doctest.h>

#include <kinema/engine/symbolic/differentiate.hpp>

#include <string>

using GiNaC::ex;
using GiNaC::symbol;

namespace {

std::string text(const ex& e) {
  std::ostringstream out;
  out << e;
  return out.str();
}

}  // namespace

TEST_CASE("engine/symbolic/differentiate: partial is e.diff(s) exactly, term for term") {
  const symbol a("a"), b("b"), x("x"), y("y"), w("w");
  const ex expressions[] = {
      0,
      7,
      x,
      y,
      a * GiNaC::cos(x) + b * GiNaC::cos(y) - 3,                       // a loop's x component
      a * GiNaC::sin(x) * w - b * GiNaC::sin(y) * GiNaC::pow(w, 2),     // products with powers
      -a * GiNaC::cos(x) * GiNaC::pow(w, 2) + a * GiNaC::sin(x + y) * x, // x in two factors
      GiNaC::sin(2 * x - y) * GiNaC::cos(x) / (b + x),                 // a quotient (power -1)
      GiNaC::exp(GiNaC::I * x) * a + GiNaC::exp(GiNaC::I * (x - y)),   // link vectors
      GiNaC::cos(GiNaC::sin(x) * y),                                   // nested chain rule
      GiNaC::sqrt(a * a + x * x - 2 * a * x * GiNaC::cos(y)),          // handed to GiNaC (power)
      GiNaC::atan2(GiNaC::sin(x), a + GiNaC::cos(x)),                  // handed to GiNaC (function)
      GiNaC::pow(GiNaC::sin(x), 3) * GiNaC::cos(y) * b,
      GiNaC::sin(y) * GiNaC::cos(y) + a * b,                            // no x anywhere
  };
  for (const ex& e : expressions) {
    for (const symbol& s : {x, y, w, a}) {
      CAPTURE(text(e));
      CAPTURE(s);
      const ex mine = kinema::partial(e, s), ginac = e.diff(s);
      CHECK(mine.is_equal(ginac));
      CHECK(text(mine) == text(ginac));
    }
  }
}

TEST_CASE("engine/symbolic/differentiate: a sum without the symbol is zero without differentiating it") {
  const symbol x("x"), y("y");
  const ex e = GiNaC::sin(y) + GiNaC::cos(y) * y;
  CHECK(kinema::partial(e, x).is_zero());
  CHECK(kinema::partial(GiNaC::sin(x) + e, x).is_equal(GiNaC::cos(x)));
}
