// engine/symbolic/derivation: what tests/derivation_test.cpp does not cover:
// the chain rule itself, the velocity and acceleration equations against
// Phi_q and Phi_theta, the points' motion against hand-derived formulas, the
// sliding-link terms of Examples 4.1 and 4.2, and block order in the solved
// rates. Everything compared by meaning.
#include <doctest/doctest.h>

#include "engine/symbolic/derivation.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using GiNaC::ex;
using kinema::ConstraintSystem;
using kinema::Derivation;
using kinema_unit::same_meaning;
using kinema_unit::symbol_named;

namespace {

ConstraintSystem sample_system(const char* name) {
  return kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample(name)), name);
}

}  // namespace

TEST_CASE("engine/symbolic/derivation: time_derivative is the chain rule through q, qd, theta, thetad") {
  const ConstraintSystem s = sample_system("four_bar.toml");
  const ex a = symbol_named(s, "a"), t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3");
  const ex w2 = symbol_named(s, "omega2"), w3 = symbol_named(s, "omega3");
  const ex al2 = symbol_named(s, "alpha2"), al3 = symbol_named(s, "alpha3");
  CHECK(kinema::time_derivative(s, a).is_zero());  // parameters are constant
  CHECK((kinema::time_derivative(s, t2) - w2).expand().is_zero());
  CHECK((kinema::time_derivative(s, w3) - al3).expand().is_zero());
  CHECK((kinema::time_derivative(s, a * cos(t3)) + a * sin(t3) * w3).expand().is_zero());
  CHECK((kinema::time_derivative(s, t2 * w2) - (w2 * w2 + t2 * al2)).expand().is_zero());
  CHECK((kinema::time_derivative(s, sin(t2 - t3)) - cos(t2 - t3) * (w2 - w3)).expand().is_zero());
  CHECK_FALSE((kinema::time_derivative(s, a * cos(t3)) - a * sin(t3) * w3).expand().is_zero());
}

TEST_CASE("engine/symbolic/derivation: velocity and acceleration equations are Phi_q qd + Phi_theta thetad and "
          "Phi_q qdd - gamma") {
  for (const char* name : {"four_bar.toml", "example_4_2_r_rtr_rrt.toml", "problem_3_22_six_bar_sliders.toml"}) {
    CAPTURE(name);
    const ConstraintSystem s = sample_system(name);
    const Derivation d = kinema::derive(s);
    const std::size_t n = s.unknowns.size();
    REQUIRE(d.jacobian.rows() == n);
    REQUIRE(d.jacobian.cols() == n);
    REQUIRE(d.velocity_equations.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      CAPTURE(i);
      const ex& phi = s.equations[i].expression;
      ex velocity = d.input_jacobian(i, 0) * s.input.rate;
      ex second = 0;
      for (std::size_t j = 0; j < n; ++j) {
        CHECK((d.jacobian(i, j) - phi.diff(s.unknowns[j].symbol)).expand().is_zero());
        velocity += d.jacobian(i, j) * s.unknowns[j].rate;
        second += d.jacobian(i, j) * s.unknowns[j].second_rate;
      }
      CHECK((d.input_jacobian(i, 0) - phi.diff(s.input.symbol)).expand().is_zero());
      CHECK(same_meaning(d.velocity_equations[i], velocity));
      CHECK(same_meaning(d.acceleration_equations[i], second - d.acceleration_rhs[i]));
      // gamma holds no second rates of the unknowns; combined, it means the same.
      for (const auto& q : s.unknowns) CHECK_FALSE(d.acceleration_rhs[i].has(q.second_rate));
      CHECK(same_meaning(d.acceleration_rhs_combined[i], d.acceleration_rhs[i]));
    }
  }
}

TEST_CASE("engine/symbolic/derivation: a four-bar's gamma is the textbook one") {
  const ConstraintSystem s = sample_system("four_bar.toml");
  const Derivation d = kinema::derive(s);
  const ex a = symbol_named(s, "a"), b = symbol_named(s, "b"), c = symbol_named(s, "c");
  const ex t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3"), t4 = symbol_named(s, "theta4");
  const ex w2 = symbol_named(s, "omega2"), w3 = symbol_named(s, "omega3"), w4 = symbol_named(s, "omega4");
  const ex al2 = symbol_named(s, "alpha2");
  // x: d2/dt2 (a cos t2 + b cos t3 - c cos t4 - d) = Phi_q qdd - gamma
  CHECK(same_meaning(d.acceleration_rhs[0], a * cos(t2) * w2 * w2 + a * sin(t2) * al2 + b * cos(t3) * w3 * w3 -
                                                c * cos(t4) * w4 * w4));
  CHECK(same_meaning(d.acceleration_rhs[1], a * sin(t2) * w2 * w2 - a * cos(t2) * al2 + b * sin(t3) * w3 * w3 -
                                                c * sin(t4) * w4 * w4));
}

TEST_CASE("engine/symbolic/derivation: points' velocity and acceleration are the time derivatives of position") {
  const ConstraintSystem s = sample_system("four_bar.toml");
  const Derivation d = kinema::derive(s);
  const ex a = symbol_named(s, "a"), p = symbol_named(s, "p"), delta = symbol_named(s, "delta");
  const ex t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3");
  const ex w2 = symbol_named(s, "omega2"), w3 = symbol_named(s, "omega3");
  const ex al2 = symbol_named(s, "alpha2"), al3 = symbol_named(s, "alpha3");
  REQUIRE(d.points.size() == 3);
  const auto& P = d.points[2];  // a e^{i t2} + p e^{i (t3 + delta)}
  REQUIRE(P.velocity.size() == 2);
  REQUIRE(P.acceleration.size() == 2);
  REQUIRE(P.acceleration_combined.size() == 2);
  CHECK(same_meaning(P.velocity[0], -a * sin(t2) * w2 - p * sin(t3 + delta) * w3));
  CHECK(same_meaning(P.velocity[1], a * cos(t2) * w2 + p * cos(t3 + delta) * w3));
  const ex ax = -a * cos(t2) * w2 * w2 - a * sin(t2) * al2 - p * cos(t3 + delta) * w3 * w3 - p * sin(t3 + delta) * al3;
  const ex ay = -a * sin(t2) * w2 * w2 + a * cos(t2) * al2 - p * sin(t3 + delta) * w3 * w3 + p * cos(t3 + delta) * al3;
  CHECK(same_meaning(P.acceleration[0], ax));
  CHECK(same_meaning(P.acceleration[1], ay));
  CHECK(same_meaning(P.acceleration_combined[0], ax));
  CHECK(same_meaning(P.acceleration_combined[1], ay));
  CHECK_FALSE(same_meaning(P.acceleration[1], ax));

  // Every point of every sample: velocity = d/dt position, acceleration = d/dt velocity.
  for (const char* name : {"slider_crank.toml", "problem_4_4_six_bar.toml"}) {
    CAPTURE(name);
    const ConstraintSystem system = sample_system(name);
    const Derivation derivation = kinema::derive(system);
    REQUIRE(derivation.points.size() == system.points.size());
    for (std::size_t k = 0; k < system.points.size(); ++k) {
      for (std::size_t c = 0; c < system.points[k].position.size(); ++c) {
        const ex v = kinema::time_derivative(system, system.points[k].position[c]);
        CHECK(same_meaning(derivation.points[k].velocity[c], v));
        CHECK(same_meaning(derivation.points[k].acceleration[c], kinema::time_derivative(system, v)));
      }
    }
  }
}

TEST_CASE("engine/symbolic/derivation: Example 4.1: the slider on link 1 and its Coriolis term") {
  const ConstraintSystem s = sample_system("example_4_1_r_trr.toml");
  const Derivation d = kinema::derive(s);
  const ex r = symbol_named(s, "r"), phi = symbol_named(s, "phi");
  const ex r_dot = symbol_named(s, "r_dot"), r_ddot = symbol_named(s, "r_ddot");
  const ex w1 = symbol_named(s, "omega1"), al1 = symbol_named(s, "alpha1");
  // Only r*exp(I*phi) slides: BC*exp(I*phi3) turns at fixed length, AC is ground.
  REQUIRE(d.sliding_links.size() == 1);
  const kinema::SlidingLinkTerms& t = d.sliding_links[0];
  CHECK(t.group == 0);
  CHECK((t.length - r).expand().is_zero());
  CHECK((t.angle - phi).expand().is_zero());
  CHECK(same_meaning(t.relative, r_ddot));
  CHECK(same_meaning(t.coriolis, r_dot * w1));  // d(length)/dt * d(angle)/dt
  CHECK(same_meaning(t.tangential, r * al1));
  CHECK(same_meaning(t.normal, r * w1 * w1));
  // The four terms are the acceleration of r e^{i phi}: (r'' - r w^2) + i (r al + 2 r' w), times e^{i phi}.
  const ex acceleration = kinema::time_derivative(s, kinema::time_derivative(s, r * exp(GiNaC::I * phi)));
  const ex named = (t.relative - t.normal + GiNaC::I * (t.tangential + 2 * t.coriolis)) * exp(GiNaC::I * phi);
  CHECK((acceleration - named).expand().is_zero());
}

TEST_CASE("engine/symbolic/derivation: Example 4.2: the slider along turning link 3 - none in a four-bar") {
  const ConstraintSystem s = sample_system("example_4_2_r_rtr_rrt.toml");
  const Derivation d = kinema::derive(s);
  REQUIRE(d.sliding_links.size() == 1);
  const auto& t = d.sliding_links[0];
  CHECK(t.group == 0);
  // The loop writes the link vector as -CB*exp(I*phi3): its length is -CB.
  CHECK((t.length + symbol_named(s, "CB")).expand().is_zero());
  CHECK((t.angle - symbol_named(s, "phi3")).expand().is_zero());
  CHECK(same_meaning(t.coriolis, -symbol_named(s, "CB_dot") * symbol_named(s, "omega3")));
  CHECK(same_meaning(t.relative, -symbol_named(s, "CB_ddot")));
  CHECK(same_meaning(t.tangential, -symbol_named(s, "CB") * symbol_named(s, "alpha3")));
  CHECK(same_meaning(t.normal, -symbol_named(s, "CB") * pow(symbol_named(s, "omega3"), 2)));

  for (const char* name : {"four_bar.toml", "problem_3_22_six_bar_sliders.toml", "slider_crank.toml"}) {
    CAPTURE(name);
    CHECK(kinema::derive(sample_system(name)).sliding_links.empty());
  }
}

TEST_CASE("engine/symbolic/derivation: rates of a later block use the earlier blocks' rates, never later ones") {
  const ConstraintSystem s = sample_system("problem_3_22_six_bar_sliders.toml");
  const Derivation d = kinema::derive(s);
  REQUIRE(d.blocks.size() == 2);
  const ex w3 = symbol_named(s, "omega3"), al3 = symbol_named(s, "alpha3");
  // theta5 (block 2) is written with omega3 and alpha3 (block 1) ...
  CHECK(d.solved_rates[2].has(w3));
  CHECK(d.solved_second_rates[2].has(al3));
  // ... and no rate is written with its own block's or a later block's rates.
  for (std::size_t b = 0; b < d.blocks.size(); ++b) {
    for (std::size_t j : d.blocks[b].unknowns) {
      for (std::size_t later = b; later < d.blocks.size(); ++later) {
        for (std::size_t k : d.blocks[later].unknowns) {
          CAPTURE(j);
          CAPTURE(k);
          CHECK_FALSE(d.solved_rates[j].has(s.unknowns[k].rate));
          CHECK_FALSE(d.solved_second_rates[j].has(s.unknowns[k].second_rate));
        }
      }
    }
  }
}

TEST_CASE("engine/symbolic/derivation: the evaluation scope derives what the evaluator needs, the same, and no more") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const ConstraintSystem s = sample_system(sample);
    const Derivation full = kinema::derive(s);
    const Derivation evaluation = kinema::derive(s, kinema::DerivationScope::evaluation);
    CHECK(full.scope == kinema::DerivationScope::full);
    CHECK(evaluation.scope == kinema::DerivationScope::evaluation);
    const std::size_t n = s.unknowns.size();
    REQUIRE(evaluation.jacobian.rows() == n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) CHECK(same_meaning(evaluation.jacobian(i, j), full.jacobian(i, j)));
      CHECK(same_meaning(evaluation.input_jacobian(i, 0), full.input_jacobian(i, 0)));
      CHECK(same_meaning(evaluation.acceleration_rhs[i], full.acceleration_rhs[i]));
    }
    REQUIRE(evaluation.points.size() == full.points.size());
    for (std::size_t p = 0; p < full.points.size(); ++p) {
      REQUIRE(evaluation.points[p].acceleration.size() == full.points[p].acceleration.size());
      for (std::size_t c = 0; c < full.points[p].acceleration.size(); ++c) {
        CHECK(same_meaning(evaluation.points[p].velocity[c], full.points[p].velocity[c]));
        CHECK(same_meaning(evaluation.points[p].acceleration[c], full.points[p].acceleration[c]));
      }
      CHECK(evaluation.points[p].acceleration_combined.empty());
    }
    CHECK(full.solved_rates.size() == n);
    CHECK(evaluation.solved_rates.empty());
    CHECK(evaluation.solved_second_rates.empty());
    CHECK(evaluation.acceleration_rhs_combined.empty());
    CHECK(evaluation.sliding_links.empty());
    CHECK(&kinema::full_derivation(full) == &full);
    CHECK_THROWS_AS(kinema::full_derivation(evaluation), std::logic_error);
  }
  // Both scopes refuse unknowns that are not independent (only their sum appears).
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  const std::string written = "b*exp(I*theta3) - c*exp(I*theta4)";
  REQUIRE(text.find(written) != std::string::npos);
  text.replace(text.find(written), written.size(), "b*exp(I*(theta3 + theta4))");
  const ConstraintSystem dependent = kinema_unit::system_from_text(text, "dependent.toml");
  for (const auto scope : {kinema::DerivationScope::full, kinema::DerivationScope::evaluation})
    CHECK_THROWS_WITH_AS(kinema::derive(dependent, scope), doctest::Contains("not independent"), kinema::InputError);
}

// Issue 33: log nested 8 deep in a loop never finished deriving (6 deep took 5 s): GiNaC's
// determinant normalised the chain rule's products. Such a block is solved by cofactors.
// The reader now refuses such functions nested past 3 deep (their derivatives could not be
// typeset); the deepest it accepts goes through the cofactors.
TEST_CASE("derivation: a loop with functions nested as deep as accepted is derived at once, its rates the same numbers") {
  const auto nested_logs = [](int depth) {
    std::string nested = "theta3 + 30";
    for (int k = 0; k < depth; ++k) nested = "log(10 + " + nested + ")";
    return kinema_test::replaced("- d\"", "- d - 1e-3*d*" + nested + "\"");
  };
  const auto deeper = kinema_test::run_kinema_bounded(
      {"derive", kinema_test::write_temporary("nested_logs_8.toml", nested_logs(8))});
  CHECK(deeper.exit_status == 2);
  CHECK(deeper.err.find("nested_logs_8.toml:") != std::string::npos);
  const std::string path = kinema_test::write_temporary("nested_logs.toml", nested_logs(3));
  const auto derived = kinema_test::run_kinema_bounded({"derive", path});
  CHECK(derived.exit_status == 0);
  CHECK(derived.peak_kilobytes < 2 * 1024 * 1024);
  // The solved formulas give eval's numbers (finite differences check eval elsewhere).
  const kinema::Model model = kinema::load_model(path);
  const kinema::MotionTable t = kinema::solve_motion(model, {0.7});
  REQUIRE(t.status(0) == kinema::Status::ok);
  GiNaC::exmap at;
  for (std::size_t p = 0; p < model.system.parameters.size(); ++p)
    at[model.system.parameters[p].symbol] = model.system.parameters[p].value;
  at[model.system.input.symbol] = 0.7;
  at[model.system.input.rate] = model.system.input.rate_value;
  at[model.system.input.second_rate] = model.system.input.second_rate_value;
  for (std::size_t i = 0; i < model.system.unknowns.size(); ++i) at[model.system.unknowns[i].symbol] = t.q(0)[Eigen::Index(i)];
  for (std::size_t i = 0; i < model.system.unknowns.size(); ++i) {
    const double rate = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(model.derivation.solved_rates[i].subs(at))).to_double();
    CHECK(rate == doctest::Approx(t.qd(0)[Eigen::Index(i)]).epsilon(1e-9));
  }
}
