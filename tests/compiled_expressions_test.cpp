#include <doctest/doctest.h>

#include <cmath>

#include "engine/compiled_expressions.hpp"

using namespace GiNaC;

TEST_CASE("compiled expressions equal GiNaC's own numeric evaluation") {
  realsymbol a("a"), t("t"), x("x");
  const std::vector<ex> outputs = {
      a * cos(t) - pow(x, 3) / (2 * a) + sin(t + x) * sin(t + x),
      sqrt(a * a + x * x) - atan2(x, a) + pow(a, -2) * exp(x) - 3 * cos(t) * sin(t),
      tan(t) + log(a) + abs(-x) + pow(a, x)};
  const kinema::CompiledExpressions compiled({a, t, x}, outputs);
  std::vector<double> workspace = compiled.make_workspace();
  for (double tv : {-2.0, 0.3, 1.1}) {
    const double in[3] = {1.7, tv, 0.4};
    double out[3];
    compiled.evaluate(in, out, workspace);
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const ex expected = evalf(outputs[i].subs(lst{a == 1.7, t == tv, x == 0.4}));
      CHECK(out[i] == doctest::Approx(ex_to<numeric>(expected).to_double()).epsilon(1e-13));
    }
  }
}

TEST_CASE("sin and cos of one argument share one instruction, and subexpressions are shared") {
  realsymbol t("t"), b("b");
  const kinema::CompiledExpressions once({t, b}, {sin(t) * b});
  const kinema::CompiledExpressions both({t, b}, {sin(t) * b, cos(t) * b, sin(t) * b + 1});
  // sin(t)*b: sincos + mul; adding cos(t)*b costs one mul, reusing sin(t)*b one add.
  CHECK(both.instruction_count() == once.instruction_count() + 2);
}

TEST_CASE("compiling refuses symbols that are not inputs") {
  realsymbol t("t"), y("y");
  CHECK_THROWS_AS(kinema::CompiledExpressions({t}, {t + y}), std::invalid_argument);
}
