// engine/symbolic/dyad_method: the seeds' ways of working out velocities and
// accelerations (relative velocity, joint coordinates), checked by meaning: the
// relations of every group, evaluated in order at a solved position (each solved rate
// and each joint's velocity taken from the lines before it), give the rates eval gives,
// the joints' velocities and accelerations eval gives, and every component equation
// and position relation holds.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <string>
#include <vector>

#include "engine/symbolic/dyad_method.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/constraints/differentiate.hpp"

#include "tests/test_support.hpp"

namespace {

using GiNaC::ex;
using kinema::DerivationMethod;
using kinema::MethodRelation;

double number(const ex& e, const GiNaC::exmap& values) {
  const ex v = GiNaC::evalf(e.subs(values, GiNaC::subs_options::no_pattern));
  REQUIRE_MESSAGE(GiNaC::is_a<GiNaC::numeric>(v), "not a number: " << e << " -> " << v);
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

// Checks every relation of `method` for a sample at its file value; returns how many
// solutions and components were checked.
std::size_t check_method(const std::string& name, DerivationMethod method) {
  CAPTURE(name);
  CAPTURE(kinema::method_name(method));
  const kinema::Model model = kinema::load_model(kinema_test::sample(name));
  const kinema::ConstraintSystem& system = model.system;
  const kinema::DyadDerivation derivation = kinema::derive_by_dyads(system, method);
  const double x = system.input.values.front();
  const kinema::MotionTable table = kinema::solve_motion(model, {x});
  REQUIRE(table.status(0) == kinema::Status::ok);
  const kinema::MotionState state = table[0];
  const kinema::SolvingPlan& frames = *system.plan;
  std::vector<kinema::BodyPose> poses;
  REQUIRE(kinema::place_dyads(frames, x, poses) == frames.dyads.size());

  GiNaC::exmap values;
  for (const auto& parameter : system.parameters) values[parameter.symbol] = parameter.value;
  values[system.input.symbol] = x;
  values[system.input.rate] = state.input_rate;
  values[system.input.second_rate] = state.input_second_rate;
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) values[system.unknowns[i].symbol] = state.q[Eigen::Index(i)];
  // Joint coordinates where the closed form places them; link lengths between joints
  // as the links are drawn (the frames), offsets from guide lines as placed.
  std::map<std::string, std::complex<double>> at;
  for (std::size_t j = 0; j < system.plan->joints.size(); ++j) {
    std::complex<double> p;
    REQUIRE(kinema::joint_position(frames, poses, j, p));
    at[system.plan->joints[j].name] = p;
  }
  // A slider joint is where its block puts it (a guide that lists it only has it pass
  // by: as drawn in the sketch, its point on the guide is not where the block is now).
  for (const kinema::SolvingPlan::Slider& s : frames.sliders)
    for (const auto& [j, v] : frames.bodies[s.block].points)
      if (j == s.joint) at[system.plan->joints[j].name] = poses[s.block].origin + v * std::polar(1.0, poses[s.block].angle);
  for (const auto& [symbol_name, symbol] : derivation.symbols) {
    const std::string rest = symbol_name.substr(2);
    if (symbol_name.rfind("x_", 0) == 0) values[symbol] = at.at(rest).real();
    if (symbol_name.rfind("y_", 0) == 0) values[symbol] = at.at(rest).imag();
    if (symbol_name.rfind("L_", 0) == 0) {
      // Two joint names run together: the split that names two joints.
      for (std::size_t cut = 1; cut < rest.size(); ++cut)
        if (at.count(rest.substr(0, cut)) && at.count(rest.substr(cut)))
          values[symbol] = std::abs(at.at(rest.substr(0, cut)) - at.at(rest.substr(cut)));
    }
  }
  std::size_t checked = 0;
  std::vector<std::pair<ex, ex>> components;
  for (const kinema::MethodStep& step : derivation.steps) {
    CAPTURE(step.heading);
    for (const auto* list : {&step.velocity, &step.acceleration}) {
      for (const MethodRelation& r : *list) {
        if (r.kind == MethodRelation::Kind::solution) {
          values[r.left] = number(r.right, values);
          ++checked;
        } else if (r.kind == MethodRelation::Kind::component) {
          if (r.text == "position") {
            // A guide line's offset h is whatever the placed position gives.
            for (const auto& [symbol_name, symbol] : derivation.symbols)
              if (symbol_name.rfind("h_", 0) == 0 && r.left.has(symbol) && values.count(symbol) == 0)
                values[symbol] = number(r.left + symbol, values);
          }
          components.push_back({r.left, r.right});
        }
      }
    }
  }
  for (const auto& [left, right] : components) {
    CAPTURE(left);
    const double a = number(left, values), b = number(right, values);
    CHECK(std::fabs(a - b) <= 1e-9 * (1 + std::fabs(a) + std::fabs(b)));
    ++checked;
  }
  // The rates solved group by group are eval's.
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    CAPTURE(system.unknowns[i].name);
    REQUIRE(values.count(system.unknowns[i].rate) == 1);
    REQUIRE(values.count(system.unknowns[i].second_rate) == 1);
    CHECK(GiNaC::ex_to<GiNaC::numeric>(values[system.unknowns[i].rate]).to_double() ==
          doctest::Approx(state.qd[Eigen::Index(i)]).epsilon(1e-9).scale(1));
    CHECK(GiNaC::ex_to<GiNaC::numeric>(values[system.unknowns[i].second_rate]).to_double() ==
          doctest::Approx(state.qdd[Eigen::Index(i)]).epsilon(1e-9).scale(1));
  }
  // The joints' velocities and accelerations are eval's (its points of the same names).
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    const std::string& point = system.points[p].name;
    const auto vx = derivation.symbols.find("v_" + point + "x");
    if (vx == derivation.symbols.end()) continue;
    CAPTURE(point);
    const auto& m = state.points[p];
    const auto component = [&](const std::string& symbol_name) {
      return GiNaC::ex_to<GiNaC::numeric>(values.at(derivation.symbols.at(symbol_name))).to_double();
    };
    CHECK(component("v_" + point + "x") == doctest::Approx(m.velocity[0]).epsilon(1e-9).scale(1));
    CHECK(component("v_" + point + "y") == doctest::Approx(m.velocity[1]).epsilon(1e-9).scale(1));
    CHECK(component("a_" + point + "x") == doctest::Approx(m.acceleration[0]).epsilon(1e-9).scale(1));
    CHECK(component("a_" + point + "y") == doctest::Approx(m.acceleration[1]).epsilon(1e-9).scale(1));
    checked += 4;
  }
  return checked;
}

}  // namespace

TEST_CASE("dyad_method: relative velocities and joint coordinates of every joints-and-links sample mean eval's numbers") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml", "problem_4_1_parallelogram.toml",
                           "problem_4_1_antiparallelogram.toml", "triple_rocker_circuit.toml"}) {
    for (DerivationMethod method : {DerivationMethod::relative_velocity, DerivationMethod::joint_coordinates}) {
      CHECK(check_method(name, method) > 10);
    }
  }
}

TEST_CASE("dyad_method: no empty terms, and no term of the zero vector between two joints at one point") {
  // Example 4.1 as the seed writes it (slider 2's pin B is its slide point B2): no
  // "+  +" (an empty term) and no omega1 x r_B2B, whose r_B2B is zero.
  {
    const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_1_joints.toml"));
    const kinema::DyadDerivation d = kinema::derive_by_dyads(model.system, DerivationMethod::relative_velocity);
    std::vector<std::string> statements;
    for (const auto& step : d.steps)
      for (const auto* list : {&step.velocity, &step.acceleration})
        for (const MethodRelation& r : *list)
          if (r.kind == MethodRelation::Kind::statement) statements.push_back(r.text);
    const auto has = [&](const std::string& s) { return std::find(statements.begin(), statements.end(), s) != statements.end(); };
    CHECK(has("v_B = v_B2_1 + r_dot u_B2 = omega3 x r_CB"));
    CHECK(has("a_B = a_B2_1 + r_ddot u_B2 + 2 omega1 x r_dot u_B2 = alpha3 x r_CB - omega3^2 r_CB"));
    CHECK(has("v_B2 = v_B"));
    CHECK(has("a_B2 = a_B"));
  }
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml", "problem_4_1_parallelogram.toml",
                           "problem_4_1_antiparallelogram.toml", "triple_rocker_circuit.toml"}) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::SolvingPlan& frames = *model.system.plan;
    // Joints at one point of a body (not a slide point on its guide, which only passes).
    std::vector<std::pair<std::string, std::string>> together;
    for (std::size_t b = 1; b < frames.bodies.size(); ++b) {
      const auto& points = frames.bodies[b].points;
      for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t k = i + 1; k < points.size(); ++k) {
          bool slides = false;
          for (const auto& s : frames.sliders)
            slides = slides || (s.guide == b && (s.joint == points[i].first || s.joint == points[k].first));
          if (!slides && std::abs(points[i].second - points[k].second) < 1e-12)
            together.push_back({model.system.plan->joints[points[i].first].name,
                                model.system.plan->joints[points[k].first].name});
        }
    }
    for (DerivationMethod method : {DerivationMethod::relative_velocity, DerivationMethod::joint_coordinates}) {
      CAPTURE(name);
      CAPTURE(kinema::method_name(method));
      const kinema::DyadDerivation d = kinema::derive_by_dyads(model.system, method);
      const auto symbol = [&](const std::string& n) {
        const auto found = d.symbols.find(n);
        return found == d.symbols.end() ? ex(0) : ex(found->second);
      };
      for (const auto& step : d.steps)
        for (const auto* list : {&step.velocity, &step.acceleration})
          for (const MethodRelation& r : *list) {
            CAPTURE(r.text);
            if (r.kind == MethodRelation::Kind::statement) {
              CHECK(r.text.find("  ") == std::string::npos);
              CHECK(r.text.find("+ +") == std::string::npos);
              CHECK(r.latex.find("+  +") == std::string::npos);
              for (const auto& [p, q] : together) {
                CHECK(r.text.find("r_" + p + q) == std::string::npos);
                CHECK(r.text.find("r_" + q + p) == std::string::npos);
              }
              continue;
            }
            if (r.text == "position") continue;  // the relation itself, not printed
            // A formula with both joints' coordinates has (x_P - x_Q)-like terms: zero.
            for (const auto& [p, q] : together)
              for (const char* axis : {"x_", "y_"}) {
                const ex xp = symbol(axis + p), xq = symbol(axis + q);
                if (xp.is_zero() || xq.is_zero()) continue;
                CAPTURE(p);
                CAPTURE(q);
                const bool both = (r.left.has(xp) || r.right.has(xp)) && (r.left.has(xq) || r.right.has(xq));
                CHECK_FALSE(both);
              }
          }
    }
  }
}

// Issue 49: the joint-coordinates method printed its differentiated relations multiplied
// out (v_Bx*x_B - v_Bx*x_C + ...): each rate is now written once, times its collected
// coefficient, and the determinant once for each x coordinate.
TEST_CASE("dyad_method: joint coordinates' differentiated relations are collected in the rates") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml", "triple_rocker_circuit.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::DyadDerivation d = kinema::derive_by_dyads(model.system, DerivationMethod::joint_coordinates);
    std::size_t checked = 0;
    const auto once_each = [&](const ex& e, const std::string& prefix) {
      // Each symbol named prefix... occurs as a factor of one term of the sum, not of several.
      if (!GiNaC::is_a<GiNaC::add>(e)) return;
      std::map<std::string, int> terms_with;
      for (const ex& term : e) {
        for (const ex& s : kinema::symbols_of(term)) {
          const std::string n = GiNaC::ex_to<GiNaC::symbol>(s).get_name();
          if (n.rfind(prefix, 0) == 0 && term.degree(s) == 1) ++terms_with[n];
        }
      }
      for (const auto& [symbol, count] : terms_with) {
        CAPTURE(e);
        CAPTURE(symbol);
        CHECK(count == 1);
        ++checked;
      }
    };
    for (const auto& step : d.steps) {
      for (const MethodRelation& r : step.velocity)
        if (r.kind == MethodRelation::Kind::component && r.text == "d/dt") once_each(r.left, "v_");
      for (const MethodRelation& r : step.acceleration)
        if (r.kind == MethodRelation::Kind::component && r.text == "d2/dt2") once_each(r.left, "a_");
      for (const MethodRelation& r : step.velocity)
        if (r.kind == MethodRelation::Kind::solution && GiNaC::ex_to<GiNaC::symbol>(r.left).get_name().rfind("v_", 0) == 0)
          for (const ex& factor : r.right)  // the determinant: the factor to the power -1, as printed
            if (GiNaC::is_a<GiNaC::power>(factor) && factor.op(1) == -1) once_each(factor.op(0), "x_");
    }
    CHECK(checked > 4);
  }
}
