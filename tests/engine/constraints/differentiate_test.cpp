// engine/symbolic/differentiate: partial() is GiNaC's diff, the same expression (not
// only the same meaning: printed formulas and the tape's order come from it), on the
// shapes a derivation meets and on what it hands back to GiNaC.
#include <doctest/doctest.h>

#include "engine/constraints/differentiate.hpp"

#include "engine/base/errors.hpp"

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

namespace {

// d/dt through x (rate w) and w (rate z), as a derivation builds it.
ex d_dt(const ex& e, const symbol& x, const symbol& w, const symbol& z) {
  return kinema::partial(e, x) * w + kinema::partial(e, w) * z;
}

std::size_t nodes(const ex& e) {
  std::size_t count = 0;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it) ++count;
  return count;
}

}  // namespace

// The estimate guards against formulas whose derivatives take minutes: within a small
// factor of the real size, or it would refuse files that are fine or let through the
// ones it is for.
TEST_CASE("engine/symbolic/differentiate: the size estimate of d/dt is within a factor of 4 of the real size") {
  const symbol a("a"), x("x"), w("w"), z("z");
  const GiNaC::exset moving{x, w};
  ex product = a, nested = x;
  for (int k = 0; k < 30; ++k) product *= GiNaC::cos(x + k);
  for (int k = 0; k < 20; ++k) nested = GiNaC::sin(nested);
  for (const ex& position : {ex(a * GiNaC::cos(x) + a * GiNaC::sin(x)), product, a * nested,
                             GiNaC::pow(a + x, 5) * GiNaC::exp(GiNaC::I * x)}) {
    CAPTURE(position);
    const ex velocity = d_dt(position, x, w, z), acceleration = d_dt(velocity, x, w, z);
    for (const auto& [e, derivative] : {std::pair{position, velocity}, std::pair{velocity, acceleration}}) {
      const double real = static_cast<double>(nodes(derivative));
      const double estimate = kinema::derivative_size_estimate(e, moving);
      CAPTURE(real);
      CHECK(estimate >= real / 4);
      CHECK(estimate <= real * 4);
    }
  }
}

TEST_CASE("engine/symbolic/differentiate: a formula over the budget is refused with what it is and the estimate") {
  const symbol a("a"), x("x"), w("w");
  ex product = a;
  for (int k = 0; k < 1000; ++k) product *= GiNaC::cos(x + k);  // about 4,000 nodes
  try {
    kinema::check_derivative_size(product, {x, w}, "file.toml:30: point \"P\"", "velocity");
    FAIL("a product of 1000 cosines passed");
  } catch (const kinema::InputError& error) {
    const std::string message = error.what();
    CHECK(message.rfind("file.toml:30: point \"P\": its velocity formula would have about ", 0) == 0);
    CHECK(message.find("about 4 million terms and factors, and kinema derives up to 500 thousand") != std::string::npos);
  }
  CHECK_NOTHROW(kinema::check_derivative_size(a * GiNaC::cos(x) * GiNaC::sin(x), {x, w}, "P", "velocity"));
}
