// Symbolic results compared by meaning: the difference, with products of
// sines and cosines combined, must vanish.
#include <doctest/doctest.h>

#include "engine/model.hpp"
#include "engine/symbolic/trig_simplify.hpp"
#include "tests/test_support.hpp"

using namespace GiNaC;
using kinema::Model;

namespace {

bool same_meaning(const ex& a, const ex& b) {
  const ex numerator = normal(a - b).numer();
  return kinema::combine_trig_products(numerator).is_zero();
}

ex symbol_named(const Model& m, const std::string& name) {
  const auto& system = m.system;
  for (const auto& p : system.parameters)
    if (p.symbol.get_name() == name) return p.symbol;
  for (const kinema::Coordinate* c : {static_cast<const kinema::Coordinate*>(&system.input)}) {
    for (const auto& s : {c->symbol, c->rate, c->second_rate})
      if (s.get_name() == name) return s;
  }
  for (const auto& q : system.unknowns)
    for (const auto& s : {q.symbol, q.rate, q.second_rate})
      if (s.get_name() == name) return s;
  throw std::runtime_error("no symbol " + name);
}

std::size_t unknown_index(const Model& m, const std::string& name) {
  for (std::size_t i = 0; i < m.system.unknowns.size(); ++i)
    if (m.system.unknowns[i].name == name) return i;
  throw std::runtime_error("no unknown " + name);
}

}  // namespace

TEST_CASE("trig products combine into single sines and cosines") {
  realsymbol x("x"), y("y"), a("a");
  const ex combined = kinema::combine_trig_products(a * (sin(x) * cos(y) - cos(x) * sin(y)));
  CHECK(kinema::combine_trig_products(combined - a * sin(x - y)).is_zero());
  CHECK(combined.nops() <= 3);  // one product a*sin(...), not a sum
  CHECK(kinema::combine_trig_products(pow(sin(x), 2) + pow(cos(x), 2)).is_equal(1));
  const ex cosine = kinema::combine_trig_products(cos(x) * cos(y) + sin(x) * sin(y));
  CHECK((cosine.is_equal(cos(x - y)) || cosine.is_equal(cos(y - x))));
}

TEST_CASE("four-bar: Jacobian and the textbook omega3 = a omega2 sin(theta4-theta2) / (b sin(theta3-theta4))") {
  const Model m = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const ex a = symbol_named(m, "a"), b = symbol_named(m, "b"), c = symbol_named(m, "c");
  const ex t2 = symbol_named(m, "theta2"), t3 = symbol_named(m, "theta3"), t4 = symbol_named(m, "theta4");
  const ex w2 = symbol_named(m, "omega2");
  const auto& d = m.derivation;
  CHECK(same_meaning(d.jacobian(0, 0), -b * sin(t3)));
  CHECK(same_meaning(d.jacobian(0, 1), c * sin(t4)));
  CHECK(same_meaning(d.jacobian(1, 0), b * cos(t3)));
  CHECK(same_meaning(d.jacobian(1, 1), -c * cos(t4)));
  CHECK(same_meaning(d.input_jacobian(0, 0), -a * sin(t2)));

  const ex omega3 = d.solved_rates[unknown_index(m, "theta3")];
  const ex omega4 = d.solved_rates[unknown_index(m, "theta4")];
  CHECK(same_meaning(omega3, a * w2 * sin(t4 - t2) / (b * sin(t3 - t4))));
  CHECK(same_meaning(omega4, a * w2 * sin(t2 - t3) / (c * sin(t4 - t3))));
  CHECK_FALSE(same_meaning(omega3, a * w2 * sin(t2 - t4) / (b * sin(t3 - t4))));  // the check can fail
  // Textbook form: a single product (one sine over one sine), no expanded sums.
  REQUIRE(is_a<mul>(omega3));
  for (const ex& factor : omega3) {
    CAPTURE(factor);
    CHECK_FALSE(is_a<add>(factor));
    CHECK_FALSE((is_a<power>(factor) && is_a<add>(factor.op(0))));
  }
}

TEST_CASE("solved rates satisfy the velocity and acceleration equations (every sample)") {
  for (const char* name : {"four_bar.toml", "slider_crank.toml", "piston_driven_crank.toml",
                           "example_4_1_r_trr.toml", "example_4_2_r_rtr_rrt.toml",
                           "problem_4_4_six_bar.toml", "problem_3_22_six_bar_sliders.toml"}) {
    CAPTURE(name);
    const Model m = kinema::load_model(kinema_test::sample(name));
    const auto& d = m.derivation;
    // Solve in block order: substitute later blocks' rates by their formulas in earlier ones'.
    exmap rates, second_rates;
    for (const auto& block : d.blocks) {
      for (std::size_t j : block.unknowns) rates[m.system.unknowns[j].rate] = d.solved_rates[j].subs(rates);
    }
    for (const auto& block : d.blocks) {
      for (std::size_t j : block.unknowns)
        second_rates[m.system.unknowns[j].second_rate] = d.solved_second_rates[j].subs(second_rates);
    }
    for (std::size_t i = 0; i < d.velocity_equations.size(); ++i) {
      CAPTURE(i);
      CHECK(same_meaning(d.velocity_equations[i].subs(rates), 0));
      CHECK(same_meaning(d.acceleration_equations[i].subs(second_rates), 0));
    }
  }
}

TEST_CASE("Problem 3.22: the seed's solved rates, by meaning") {
  const Model m = kinema::load_model(kinema_test::sample("problem_3_22_six_bar_sliders.toml"));
  const ex r2 = symbol_named(m, "r2"), r3 = symbol_named(m, "r3"), a = symbol_named(m, "a"),
           r5 = symbol_named(m, "r5"), beta = symbol_named(m, "beta");
  const ex t2 = symbol_named(m, "theta2"), t3 = symbol_named(m, "theta3"), t5 = symbol_named(m, "theta5");
  const ex w2 = symbol_named(m, "omega2"), w3 = symbol_named(m, "omega3");
  const auto& d = m.derivation;
  REQUIRE(d.blocks.size() == 2);  // loop 1 first, then loop 2 with omega3 known
  CHECK(same_meaning(d.solved_rates[unknown_index(m, "theta3")], -r2 * cos(t2) * w2 / (r3 * cos(t3))));
  CHECK(same_meaning(d.solved_rates[unknown_index(m, "r1")],
                     (-r2 * sin(t2) + sin(t3) / cos(t3) * r2 * cos(t2)) * w2));
  CHECK(same_meaning(d.solved_rates[unknown_index(m, "theta5")],
                     (-r2 * sin(t2) * w2 - a * sin(t3 + beta) * w3) / (r5 * sin(t5))));
}

TEST_CASE("kinema derive prints every section and the four-bar's textbook omega3") {
  const auto result = kinema_test::run_kinema({"derive", kinema_test::sample("four_bar.toml")});
  REQUIRE(result.exit_status == 0);
  for (const char* section : {"Loop-closure equations", "Jacobian Phi_q", "Velocity equations",
                              "Acceleration equations", "Solved rates", "omega3 = ", "alpha4 = "}) {
    CHECK(result.out.find(section) != std::string::npos);
  }
  // Parse the printed omega3 back and compare by meaning.
  const Model m = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const std::string label = "\n    omega3 = ";  // the solved line, not the velocity equations
  REQUIRE(result.out.find(label) != std::string::npos);
  const auto start = result.out.find(label) + label.size();
  const std::string printed = result.out.substr(start, result.out.find('\n', start) - start);
  symtab table;
  for (const char* name : {"a", "b", "c", "theta2", "theta3", "theta4", "omega2"})
    table[name] = symbol_named(m, name);
  parser reader(table, true);
  CHECK(same_meaning(reader(printed), m.derivation.solved_rates[unknown_index(m, "theta3")]));
}
