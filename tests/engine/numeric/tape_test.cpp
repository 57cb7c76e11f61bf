#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "engine/numeric/tape.hpp"
#include "engine/numeric/simd_math.hpp"
#include "engine/printers/code/tape_emitter.hpp"

#include <algorithm>
#include <map>
#include <sstream>

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

TEST_CASE("stages share registers: a later stage reuses what an earlier one computed") {
  realsymbol t("t"), w("w"), a("a");
  const ex position = a * cos(t), velocity = -a * sin(t) * w;
  const kinema::CompiledExpressions separate_velocity({t, w, a}, {velocity});
  const kinema::CompiledExpressions staged({t, w, a}, std::vector<std::vector<ex>>{{position}, {velocity}});
  const kinema::CompiledExpressions separate_position({t, w, a}, {position});
  // The staged tape's velocity stage needs no second sincos.
  CHECK(staged.instruction_count() <
        separate_position.instruction_count() + separate_velocity.instruction_count());
  std::vector<double> workspace = staged.make_workspace();
  workspace[0] = 0.7;
  workspace[1] = 3.0;
  workspace[2] = 2.0;
  double p = 0, v = 0;
  staged.evaluate_stage(0, workspace, &p);
  staged.evaluate_stage(1, workspace, &v);
  CHECK(p == doctest::Approx(2.0 * std::cos(0.7)));
  CHECK(v == doctest::Approx(-2.0 * std::sin(0.7) * 3.0));
}

TEST_CASE("batch evaluation equals scalar evaluation lane by lane, to rounding") {
  realsymbol a("a"), t("t"), x("x");
  const std::vector<ex> stage0 = {a * cos(t) - pow(x, 3) / (2 * a), sqrt(a * a + x * x) * sin(t)};
  const std::vector<ex> stage1 = {atan2(x, a) + exp(x) * cos(t) - pow(a, -2) + tan(t) + abs(-x)};
  const kinema::CompiledExpressions tape({a, t, x}, std::vector<std::vector<ex>>{stage0, stage1});
  constexpr std::size_t lanes = kinema::CompiledExpressions::kBatchLanes;
  auto inputs = [](std::size_t l) {
    // Lane 5 has an angle beyond the polynomial reduction's range (libm path).
    return std::array<double, 3>{1.5 + 0.1 * l, l == 5 ? 1e7 + 0.3 : -1.0 + 0.3 * l, 0.2 * l};
  };
  std::vector<double> batch = tape.make_batch_workspace();
  for (std::size_t l = 0; l < lanes; ++l)
    for (std::size_t i = 0; i < 3; ++i) batch[i * lanes + l] = inputs(l)[i];
  tape.evaluate_stage_batch(0, batch.data());
  tape.evaluate_stage_batch(1, batch.data());
  std::vector<double> scalar = tape.make_workspace();
  for (std::size_t l = 0; l < lanes; ++l) {
    CAPTURE(l);
    double out[3];
    tape.evaluate(inputs(l).data(), out, scalar);
    // The AVX2 clone may fuse multiply-adds: equal to a few ulp, not bit for bit.
    CHECK(batch[tape.output_register(0, 0) * lanes + l] == doctest::Approx(out[0]).epsilon(1e-15));
    CHECK(batch[tape.output_register(0, 1) * lanes + l] == doctest::Approx(out[1]).epsilon(1e-15));
    CHECK(batch[tape.output_register(1, 0) * lanes + l] == doctest::Approx(out[2]).epsilon(1e-15));
    const auto in = inputs(l);
    CHECK(out[0] == doctest::Approx(in[0] * std::cos(in[1]) - std::pow(in[2], 3) / (2 * in[0])).epsilon(1e-13));
  }
}

TEST_CASE("the tape's sin and cos are within 2 ulp of libm, also past the reduction range") {
  std::mt19937_64 generator(7);
  for (const double range : {1.0, 100.0, 1e5, 1e8}) {
    std::uniform_real_distribution<double> uniform(-range, range);
    for (int i = 0; i < 20000; ++i) {
      const double x = uniform(generator);
      double s = 0, c = 0;
      kinema::simd::sincos(x, s, c);
      CAPTURE(x);
      CHECK(std::fabs(s - std::sin(x)) <= 2 * std::numeric_limits<double>::epsilon() * std::max(std::fabs(s), 0.5));
      CHECK(std::fabs(c - std::cos(x)) <= 2 * std::numeric_limits<double>::epsilon() * std::max(std::fabs(c), 0.5));
    }
  }
  double s = 0, c = 0;
  kinema::simd::sincos(std::nan(""), s, c);
  CHECK(std::isnan(s));
  CHECK(std::isnan(c));
  kinema::simd::sincos(0.0, s, c);
  CHECK(s == 0.0);
  CHECK(c == 1.0);
}

// Issue 9, finding 17: GiNaC orders the terms of a sum by hashes that depend on how
// the symbols came about (serial numbers, addresses); the tape takes operands in an
// order of their structure and names, so the same formula gives the same tape.
TEST_CASE("the tape is the same whatever order GiNaC keeps the terms in") {
  auto tape_text = [](const std::vector<std::string>& creation_order, std::string& ginac_order) {
    std::map<std::string, realsymbol> s;
    for (const auto& name : creation_order) s.emplace(name, realsymbol(name));
    const ex sum = s.at("a") * sin(s.at("t")) + s.at("b") * cos(s.at("t")) - s.at("c") * s.at("t") +
                   s.at("d") * s.at("d") + s.at("e") / s.at("a") + 3 * s.at("b") * s.at("e");
    std::ostringstream printed;
    printed << sum;
    ginac_order = printed.str();
    const kinema::CompiledExpressions tape({s.at("a"), s.at("b"), s.at("c"), s.at("d"), s.at("e"), s.at("t")}, {sum});
    std::ostringstream code;
    kinema::write_tape_stage_cpp(code, tape, {"a", "b", "c", "d", "e", "t"}, 0, {"out"}, "");
    return code.str();
  };
  std::string first_order, other_order;
  const std::string first = tape_text({"a", "b", "c", "d", "e", "t"}, first_order);
  bool orders_differed = false;
  std::vector<std::string> names = {"t", "e", "d", "c", "b", "a"};
  for (int attempt = 0; attempt < 20; ++attempt) {
    std::next_permutation(names.begin(), names.end());
    CHECK(tape_text(names, other_order) == first);
    orders_differed = orders_differed || other_order != first_order;
  }
  CHECK(orders_differed);  // else this test would show nothing
}

TEST_CASE("a stage apart reads the earlier stages' registers and changes none of their instructions") {
  realsymbol t("t"), w("w"), a("a"), b("b");
  const std::vector<ex> inputs{a, b, t, w};
  const std::vector<int> levels{0, 0, 1, 2};
  // a*cos(t) is used once in the first stage (fused into its sum there); the stage apart
  // reads it again, alone and times w.
  const std::vector<std::vector<ex>> solving{{a * cos(t) + b}, {a * sin(t) * w}};
  const kinema::CompiledExpressions plain(inputs, levels, solving);
  const kinema::CompiledExpressions with(inputs, levels, solving, {a * cos(t), a * cos(t) * w, sin(t) * b});
  REQUIRE(with.stage_count() == 3);
  for (std::size_t stage = 0; stage < 2; ++stage) {
    CAPTURE(stage);
    REQUIRE(with.stage_end(stage) == plain.stage_end(stage));
    std::ostringstream plain_code, with_code;
    kinema::write_tape_stage_cpp(plain_code, plain, {"a", "b", "t", "w"}, stage, {"out[0]"}, "");
    kinema::write_tape_stage_cpp(with_code, with, {"a", "b", "t", "w"}, stage, {"out[0]"}, "");
    CHECK(with_code.str() == plain_code.str());
  }
  std::vector<double> workspace = with.make_workspace();
  const double av = 2.0, bv = 0.5, tv = 0.7, wv = 3.0;
  workspace[0] = av;
  workspace[1] = bv;
  workspace[2] = tv;
  workspace[3] = wv;
  double out[3] = {0, 0, 0};
  for (std::size_t stage = 0; stage < 3; ++stage) with.evaluate_stage(stage, workspace, out);
  CHECK(out[0] == doctest::Approx(av * std::cos(tv)));
  CHECK(out[1] == doctest::Approx(av * std::cos(tv) * wv));
  CHECK(out[2] == doctest::Approx(std::sin(tv) * bv));
  // Rerunning from the rate level only (its lower levels kept) gives the same.
  workspace[3] = 2 * wv;
  with.evaluate_stage_from(2, 2, workspace, out);
  CHECK(out[0] == doctest::Approx(av * std::cos(tv)));
  CHECK(out[1] == doctest::Approx(av * std::cos(tv) * 2 * wv));
}
