// loops/planar_loops: a Mechanism's vector loops become a ConstraintSystem
// (labelled x/y equations, groups with their terms as written, points,
// parameters with dimensions, rate names, LaTeX names), and what cannot be
// compiled or counted is refused with file:line.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "loops/planar_loops.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using GiNaC::ex;
using GiNaC::I;
using kinema::ConstraintSystem;
using kinema::Dimension;
using kinema_test::four_bar_text;
using kinema_test::replaced;
using kinema_unit::same_meaning;
using kinema_unit::symbol_named;

namespace {

const std::string kLoop = "ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d\"";

ConstraintSystem build(const std::string& text) { return kinema_unit::system_from_text(text, "fb.toml"); }

std::string error_of(const std::string& text) {
  try {
    build(text);
  } catch (const kinema::InputError& error) {
    return error.what();
  }
  return "";
}

std::string latex_of(const ex& e) {
  std::ostringstream out;
  out << GiNaC::latex << e;
  return out.str();
}

}  // namespace

TEST_CASE("loops/planar_loops: a loop gives two labelled equations, its x and y parts") {
  const ConstraintSystem s = build(four_bar_text());
  const ex a = symbol_named(s, "a"), b = symbol_named(s, "b"), c = symbol_named(s, "c"), d = symbol_named(s, "d");
  const ex t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3"), t4 = symbol_named(s, "theta4");

  REQUIRE(s.equations.size() == 2);
  CHECK(s.equations[0].group == 0);
  CHECK(s.equations[0].component == "x");
  CHECK(s.equations[1].group == 0);
  CHECK(s.equations[1].component == "y");
  CHECK((s.equations[0].expression - (a * cos(t2) + b * cos(t3) - c * cos(t4) - d)).expand().is_zero());
  CHECK((s.equations[1].expression - (a * sin(t2) + b * sin(t3) - c * sin(t4))).expand().is_zero());
  // Real symbols: the parts hold no I, no real_part()/imag_part() left over.
  CHECK_FALSE(s.equations[0].expression.has(I));
  CHECK(s.equations[1].expression.imag_part().expand().is_zero());

  REQUIRE(s.groups.size() == 1);
  const kinema::EquationGroup& g = s.groups[0];
  CHECK(g.kind == "loop");
  CHECK(g.name == "ABCD");
  CHECK(g.where.str() == "fb.toml:15");
  CHECK(g.equations == std::vector<std::size_t>{0, 1});
  REQUIRE(g.vector);
  CHECK((*g.vector - (a * exp(I * t2) + b * exp(I * t3) - c * exp(I * t4) - d)).expand().is_zero());
  // Terms in the order written, summing to the loop.
  const std::vector<ex> written = {a * exp(I * t2), b * exp(I * t3), -c * exp(I * t4), -d};
  REQUIRE(g.terms.size() == written.size());
  ex sum = 0;
  for (std::size_t k = 0; k < written.size(); ++k) {
    CAPTURE(k);
    CHECK((g.terms[k] - written[k]).expand().is_zero());
    sum += g.terms[k];
  }
  CHECK((sum - *g.vector).expand().is_zero());
  CHECK(s.describe_group(0) == "loop \"ABCD\" (fb.toml:15)");
}

TEST_CASE("loops/planar_loops: terms keep the written order, not GiNaC's") {
  const ConstraintSystem s =
      build(replaced(kLoop, "ABCD = \"-d - c*exp(I*theta4) + b*exp(I*theta3) + a*exp(I*theta2)\""));
  const ex a = symbol_named(s, "a"), b = symbol_named(s, "b"), c = symbol_named(s, "c"), d = symbol_named(s, "d");
  const ex t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3"), t4 = symbol_named(s, "theta4");
  const std::vector<ex> written = {-d, -c * exp(I * t4), b * exp(I * t3), a * exp(I * t2)};
  const auto& terms = s.groups.at(0).terms;
  REQUIRE(terms.size() == written.size());
  for (std::size_t k = 0; k < written.size(); ++k) {
    CAPTURE(k);
    CHECK((terms[k] - written[k]).expand().is_zero());
  }
  // A term written as a sum in parentheses stays one term (a slider's ground vector).
  const ConstraintSystem slider = kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("slider_crank.toml")));
  const ex x = symbol_named(slider, "x"), e = symbol_named(slider, "e");
  const auto& slider_terms = slider.groups.at(0).terms;
  REQUIRE(slider_terms.size() == 3);
  CHECK((slider_terms[2] + x + I * e).expand().is_zero());
}

TEST_CASE("loops/planar_loops: a loop by components") {
  const ConstraintSystem s = build(replaced(kLoop, "ABCD = { x = \"a*cos(theta2) + b*cos(theta3) - c*cos(theta4) - d\", "
                                                   "y = \"a*sin(theta2) + b*sin(theta3) - c*sin(theta4)\" }"));
  const ex a = symbol_named(s, "a"), b = symbol_named(s, "b"), c = symbol_named(s, "c"), d = symbol_named(s, "d");
  const ex t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3"), t4 = symbol_named(s, "theta4");
  REQUIRE(s.equations.size() == 2);
  CHECK(s.equations[0].component == "x");
  CHECK(s.equations[1].component == "y");
  CHECK((s.equations[0].expression - (a * cos(t2) + b * cos(t3) - c * cos(t4) - d)).expand().is_zero());
  CHECK((s.equations[1].expression - (a * sin(t2) + b * sin(t3) - c * sin(t4))).expand().is_zero());
  const auto& g = s.groups.at(0);
  REQUIRE(g.vector);
  CHECK((*g.vector - (s.equations[0].expression + I * s.equations[1].expression)).expand().is_zero());
  ex sum = 0;
  for (const ex& term : g.terms) sum += term;
  CHECK_FALSE(g.terms.empty());
  CHECK((sum - *g.vector).expand().is_zero());
  // Components must be real.
  CHECK(error_of(replaced(kLoop, "ABCD = { x = \"a*cos(theta2) - d + I*b\", y = \"c*sin(theta4) + b*sin(theta3)\" }"))
            .find("must be real") != std::string::npos);
}

TEST_CASE("loops/planar_loops: two loops give four equations, each labelled with its group") {
  const ConstraintSystem s = kinema_unit::system_from_text(
      kinema_test::read_file(kinema_test::sample("problem_4_4_six_bar.toml")), "six.toml");
  REQUIRE(s.equations.size() == 4);
  REQUIRE(s.groups.size() == 2);
  const std::vector<std::pair<std::size_t, std::string>> labels = {{0, "x"}, {0, "y"}, {1, "x"}, {1, "y"}};
  for (std::size_t i = 0; i < 4; ++i) {
    CAPTURE(i);
    CHECK(s.equations[i].group == labels[i].first);
    CHECK(s.equations[i].component == labels[i].second);
  }
  CHECK(s.groups[0].name == "ABCD");
  CHECK(s.groups[1].name == "DEF");
  CHECK(s.groups[1].equations == std::vector<std::size_t>{2, 3});
  // DEF as written has five terms: La, I*Lb, -(CD + CE)*exp(I*phi3), -EF*exp(I*phi4), -(-Lc + I*yF).
  CHECK(s.groups[1].terms.size() == 5);
  // Each group's x/y rows are the real and imaginary parts of its vector.
  for (const auto& g : s.groups) {
    CHECK((s.equations[g.equations[0]].expression - g.vector->real_part()).expand().is_zero());
    CHECK((s.equations[g.equations[1]].expression - g.vector->imag_part()).expand().is_zero());
  }
}

TEST_CASE("loops/planar_loops: points have x, y components and their position expressions") {
  const ConstraintSystem s = kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("four_bar.toml")));
  const ex a = symbol_named(s, "a"), p = symbol_named(s, "p"), delta = symbol_named(s, "delta"),
           d = symbol_named(s, "d"), c = symbol_named(s, "c");
  const ex t2 = symbol_named(s, "theta2"), t3 = symbol_named(s, "theta3"), t4 = symbol_named(s, "theta4");
  REQUIRE(s.points.size() == 3);
  CHECK(s.points[0].name == "A");
  CHECK(s.points[1].name == "B");
  CHECK(s.points[2].name == "P");
  for (const auto& point : s.points) {
    CHECK(point.components == std::vector<std::string>{"x", "y"});
    REQUIRE(point.position.size() == 2);
    REQUIRE(point.written);
    CHECK((point.position[0] - point.written->real_part()).expand().is_zero());
    CHECK((point.position[1] - point.written->imag_part()).expand().is_zero());
  }
  CHECK((s.points[1].position[0] - (d + c * cos(t4))).expand().is_zero());
  CHECK((s.points[1].position[1] - c * sin(t4)).expand().is_zero());
  CHECK(same_meaning(s.points[2].position[0], a * cos(t2) + p * cos(t3 + delta)));
  CHECK(same_meaning(s.points[2].position[1], a * sin(t2) + p * sin(t3 + delta)));
  CHECK_FALSE(same_meaning(s.points[2].position[1], a * sin(t2) + p * sin(t3 - delta)));
}

TEST_CASE("loops/planar_loops: parameters keep dimension, SI value, text and formula - length scale") {
  const ConstraintSystem s = build(replaced("d = \"100 mm\"", "d = \"100 mm\"\ndelta = \"30 deg\"\np = \"b/2\"\nk = \"2\"\n"
                                                               "ratio = \"b/a\"\nturn = \"2*delta\"\n"
                                                               "tilt = \"asin(a/b)\"\nopen = \"delta + Pi/2 - atan2(a, b)\"\n"
                                                               "sine = \"sin(delta)\""));
  REQUIRE(s.parameters.size() == 12);
  const auto& p = s.parameters;
  CHECK(p[0].symbol.get_name() == "a");
  CHECK(p[0].value == doctest::Approx(0.04).epsilon(1e-15));
  CHECK(p[0].dimension == Dimension::length);
  CHECK(p[0].text == "40 mm");
  CHECK_FALSE(p[0].formula);
  CHECK(p[0].where.str() == "fb.toml:3");
  CHECK(p[4].symbol.get_name() == "delta");
  CHECK(p[4].dimension == Dimension::angle);
  CHECK(p[4].value == doctest::Approx(30 * kinema_unit::kDeg).epsilon(1e-15));
  // A formula of earlier parameters: its value, its dimension from theirs, the formula kept.
  CHECK(p[5].symbol.get_name() == "p");
  CHECK(p[5].dimension == Dimension::length);
  CHECK(p[5].value == doctest::Approx(0.06).epsilon(1e-15));
  REQUIRE(p[5].formula);
  CHECK((*p[5].formula - p[1].symbol / 2).expand().is_zero());
  CHECK(p[6].dimension == Dimension::number);
  CHECK(p[6].value == 2.0);
  CHECK(p[7].dimension == Dimension::number);  // length / length
  CHECK(p[7].value == doctest::Approx(3.0).epsilon(1e-15));
  CHECK(p[8].value == doctest::Approx(60 * kinema_unit::kDeg).epsilon(1e-15));
  // Formulas that measure angles are angles (printed in degrees); an angle's sine is not.
  CHECK(p[8].dimension == Dimension::angle);
  CHECK(p[9].dimension == Dimension::angle);
  CHECK(p[9].value == doctest::Approx(std::asin(1.0 / 3)).epsilon(1e-15));
  CHECK(p[10].dimension == Dimension::angle);
  CHECK(p[11].dimension == Dimension::number);
  // The largest length: b = 120 mm.
  CHECK(s.length_scale == doctest::Approx(0.12).epsilon(1e-15));

  // Lengths without units: refused where a loop uses them as lengths (a number without a
  // unit is a ratio).
  std::string plain = four_bar_text();
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"a = \"40 mm\"", "a = \"0.04\""}, {"b = \"120 mm\"", "b = \"0.12\""},
           {"c = \"80 mm\"", "c = \"0.08\""}, {"d = \"100 mm\"", "d = \"0.1\""}})
    plain = replaced(from, to, plain);
  const std::string unitless = error_of(plain);
  CHECK(unitless.find("fb.toml:3: parameter \"a\" = \"0.04\" has no unit") != std::string::npos);

  // A parameter formula may use only earlier parameters.
  const std::string later = error_of(replaced("a = \"40 mm\"", "a = \"b/3\""));
  CHECK(later.find("fb.toml:3") != std::string::npos);
  CHECK(later.find("\"b\"") != std::string::npos);
  // A rate is not a loop parameter.
  CHECK(error_of(replaced("a = \"40 mm\"", "a = \"40 mm/s\"")).find("fb.toml:3") != std::string::npos);
}

TEST_CASE("loops/planar_loops: the driver and the unknowns with their SI values") {
  const ConstraintSystem s = build(replaced("rate = \"10 rad/s\"", "rate = \"10 rad/s\"\nsecond_rate = \"-3 rad/s^2\""));
  CHECK(s.title == "four-bar");
  CHECK(s.source_file == "fb.toml");
  CHECK(s.input.name == "theta2");
  CHECK(s.input.dimension == Dimension::angle);
  CHECK(s.input.rate_value == 10.0);
  CHECK(s.input.second_rate_value == -3.0);
  REQUIRE(s.input.values.size() == 1);
  CHECK(s.input.values[0] == doctest::Approx(40 * kinema_unit::kDeg));
  REQUIRE(s.unknowns.size() == 2);
  CHECK(s.unknowns[0].name == "theta3");
  CHECK(s.unknowns[0].guess == doctest::Approx(20 * kinema_unit::kDeg));
  CHECK(s.unknowns[1].where.str() == "fb.toml:14");  // one line below four_bar_text()'s: second_rate was added
  CHECK(s.frames.empty());
}

TEST_CASE("loops/planar_loops: rate names: textbook, on a clash, and as the file gives them") {
  const ConstraintSystem s = build(four_bar_text());
  CHECK(s.input.rate.get_name() == "omega2");
  CHECK(s.input.second_rate.get_name() == "alpha2");
  CHECK(s.unknowns[0].rate.get_name() == "omega3");
  CHECK(s.unknowns[0].second_rate.get_name() == "alpha3");
  CHECK(s.unknowns[1].rate.get_name() == "omega4");
  CHECK(s.unknowns[1].second_rate.get_name() == "alpha4");

  // A length unknown: r_dot, r_ddot (the slider-crank's x).
  const ConstraintSystem slider = kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("slider_crank.toml")));
  CHECK(slider.unknowns[1].name == "x");
  CHECK(slider.unknowns[1].rate.get_name() == "x_dot");
  CHECK(slider.unknowns[1].second_rate.get_name() == "x_ddot");

  // A parameter already called omega3: theta3's rate becomes theta3_dot, and the two are different symbols.
  const ConstraintSystem clash = build(replaced("d = \"100 mm\"", "d = \"100 mm\"\nomega3 = \"2\""));
  CHECK(clash.unknowns[0].rate.get_name() == "theta3_dot");
  CHECK(clash.unknowns[0].second_rate.get_name() == "alpha3");
  CHECK_FALSE(clash.unknowns[0].rate.is_equal(clash.parameters[4].symbol));
  // An unknown called omega2 does not lose its name to the input's rate.
  const ConstraintSystem taken = build(replaced("theta4", "omega2", replaced("theta4 = \"80 deg\"", "omega2 = \"80 deg\"")));
  CHECK(taken.unknowns[1].name == "omega2");
  CHECK(taken.input.rate.get_name() == "theta2_dot");

  // Names given in the file.
  const ConstraintSystem given = build(replaced(
      "theta3 = \"20 deg\"", "theta3 = { guess = \"20 deg\", rate_name = \"w3\", second_rate_name = \"dw3\" }",
      replaced("rate = \"10 rad/s\"", "rate = \"10 rad/s\"\nrate_name = \"omega1\"\nsecond_rate_name = \"alpha1\"")));
  CHECK(given.unknowns[0].rate.get_name() == "w3");
  CHECK(given.unknowns[0].second_rate.get_name() == "dw3");
  CHECK(given.input.rate.get_name() == "omega1");
  CHECK(given.input.second_rate.get_name() == "alpha1");
  // A given name that is taken is an error at the unknown's line.
  const std::string message = error_of(replaced("theta3 = \"20 deg\"", "theta3 = { guess = \"20 deg\", rate_name = \"b\" }"));
  CHECK(message.find("fb.toml:12") != std::string::npos);
  CHECK(message.find("\"b\"") != std::string::npos);
  CHECK(message.find("already used") != std::string::npos);
}

TEST_CASE("loops/planar_loops: symbols carry their LaTeX names") {
  const ConstraintSystem s = build(four_bar_text());
  CHECK(latex_of(s.unknowns[0].symbol) == "\\theta_{3}");
  CHECK(latex_of(s.unknowns[0].rate) == "\\omega_{3}");
  CHECK(latex_of(s.unknowns[1].second_rate) == "\\alpha_{4}");
  CHECK(latex_of(s.input.symbol) == "\\theta_{2}");
  CHECK(latex_of(s.parameters[0].symbol) == "a");
  CHECK(latex_of(s.unknowns[0].symbol) != s.unknowns[0].symbol.get_name());  // not just the plain name

  // A LaTeX name from the file, and its dots on the rates.
  const ConstraintSystem named =
      build(replaced("theta3 = \"20 deg\"", "theta3 = { guess = \"20 deg\", latex = '\\varphi_{3}' }"));
  CHECK(latex_of(named.unknowns[0].symbol) == "\\varphi_{3}");
  CHECK(latex_of(named.unknowns[0].rate) == "\\dot{\\varphi_{3}}");
  CHECK(latex_of(named.unknowns[0].second_rate) == "\\ddot{\\varphi_{3}}");
  CHECK(named.unknowns[0].rate.get_name() == "omega3");  // the printed name stays the textbook's
  // An expression prints with them.
  CHECK(latex_of(named.equations[1].expression).find("\\varphi_{3}") != std::string::npos);

  const std::string message =
      error_of(replaced("theta3 = \"20 deg\"", "theta3 = { guess = \"20 deg\", latex = '\\input{x}' }"));
  CHECK(message.find("fb.toml:12") != std::string::npos);
  CHECK(message.find("\\input") != std::string::npos);
}

TEST_CASE("loops/planar_loops: a function the evaluator does not run is refused with the list") {
  for (const auto& [text, line] : std::vector<std::pair<std::string, std::string>>{
           {replaced(kLoop, "ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d*sinh(theta3)\""),
            "fb.toml:15"},
           {replaced("P = \"a*exp(I*theta2)\"", "P = \"a*sinh(theta2)\""), "fb.toml:17"},
           {replaced("d = \"100 mm\"", "d = \"100 mm\"\ne = \"a*sinh(1)\""), "fb.toml:7"}}) {
    const std::string message = error_of(text);
    CAPTURE(message);
    CHECK(message.find(line) != std::string::npos);
    CHECK(message.find("sinh") != std::string::npos);
    CHECK(message.find(kinema::understood_functions()) != std::string::npos);
  }
  // The understood ones are accepted (sqrt and ^ are powers, atan2 of two lengths is an angle).
  CHECK(error_of(replaced("P = \"a*exp(I*theta2)\"", "P = \"sqrt(a^2 + b^2)*exp(I*atan2(b, a)) + abs(c)*cos(theta3)\""))
            .empty());
}

TEST_CASE("loops/planar_loops: counts, unused unknowns, units and names are checked") {
  const std::string count = error_of(replaced("theta4 = \"80 deg\"", "theta4 = \"80 deg\"\ntheta5 = \"10 deg\""));
  CAPTURE(count);
  CHECK(count.find("fb.toml") != std::string::npos);
  CHECK(count.find("2 scalar equations") != std::string::npos);
  CHECK(count.find("3 unknowns") != std::string::npos);
  CHECK(count.find("theta3, theta4, theta5") != std::string::npos);

  const std::string unused = error_of(replaced(
      kLoop, kLoop + "\nEF = \"c*exp(I*theta5) - d\"",
      replaced("theta4 = \"80 deg\"", "theta4 = \"80 deg\"\ntheta5 = \"10 deg\"\ntheta6 = \"10 deg\"")));
  CAPTURE(unused);
  CHECK(unused.find("fb.toml:15") != std::string::npos);  // theta6's line
  CHECK(unused.find("\"theta6\" appears in no loop") != std::string::npos);

  const std::string mixed = error_of(replaced(kLoop, "ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - theta3\""));
  CHECK(mixed.find("fb.toml:15") != std::string::npos);
  CHECK(mixed.find("different units") != std::string::npos);

  const std::string in_exp = error_of(replaced(kLoop, "ABCD = \"a*exp(I*b) + b*exp(I*theta3) - c*exp(I*theta4) - d\""));
  CHECK(in_exp.find("fb.toml:15") != std::string::npos);
  CHECK(in_exp.find("exp") != std::string::npos);

  const std::string angle_loop = error_of(replaced(kLoop, "ABCD = { x = \"theta2 - theta3\", y = \"theta4\" }"));
  CHECK(angle_loop.find("fb.toml:15") != std::string::npos);
  CHECK(angle_loop.find("link vectors") != std::string::npos);

  const std::string name = error_of(replaced(kLoop, "ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - dd\""));
  CHECK(name.find("fb.toml:15") != std::string::npos);
  CHECK(name.find("unknown name \"dd\"") != std::string::npos);

  const std::string syntax = error_of(replaced(kLoop, "ABCD = \"a*exp(I*theta2) + + * b\""));
  CHECK(syntax.find("fb.toml:15") != std::string::npos);

  const std::string ground = error_of(replaced(kLoop, kLoop + "\nGround = \"a - d\""));
  CHECK(ground.find("fb.toml:16") != std::string::npos);
  CHECK(ground.find("none of the unknowns") != std::string::npos);

  const std::string point = error_of(replaced("P = \"a*exp(I*theta2)\"", "P = \"theta2\""));
  CHECK(point.find("fb.toml:17") != std::string::npos);
  CHECK(point.find("point \"P\"") != std::string::npos);
}

TEST_CASE("loops/planar_loops: written_terms splits at top-level signs only") {
  using V = std::vector<std::string>;
  CHECK(kinema::written_terms("a*exp(I*t) - d") == V{"a*exp(I*t) ", "- d"});
  CHECK(kinema::written_terms("-a + b") == V{"-a ", "+ b"});
  CHECK(kinema::written_terms("1e-3*x + (a - b)*exp(I*(t - s))") == V{"1e-3*x ", "+ (a - b)*exp(I*(t - s))"});
  CHECK(kinema::written_terms("2E+3*x-y") == V{"2E+3*x", "-y"});
  CHECK(kinema::written_terms("  ").empty());
}

// Issue 9, finding 12: atan, asin, acos of real symbols are real, in complex and in
// component loops; the motion they give agrees with finite differences.
TEST_CASE("loops/planar_loops: inverse trigonometric functions of coordinates compile and move right") {
  for (const std::string& loop :
       {std::string("ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d + 0.001*a*atan(theta3)\""),
        std::string("ABCD = { x = \"a*cos(theta2) + b*cos(theta3) - c*cos(theta4) - d + 0.001*a*acos(0.5*cos(theta3))\", "
                    "y = \"a*sin(theta2) + b*sin(theta3) - c*sin(theta4) + 0.001*a*asin(0.5*sin(theta4))\" }")}) {
    CAPTURE(loop);
    const kinema::Model model = kinema_unit::model_from_text(
        kinema_test::replaced("ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d\"", loop));
    for (const auto& equation : model.system.equations) {
      CHECK_FALSE(equation.expression.has(GiNaC::real_part(GiNaC::wild())));
      CHECK_FALSE(equation.expression.has(GiNaC::imag_part(GiNaC::wild())));
    }
    const double h = 1e-5, theta = 0.7;
    const auto table = kinema::solve_motion(model, {theta - h, theta, theta + h});
    REQUIRE(table.status(1) == kinema::Status::ok);
    const double rate = model.system.input.rate_value;
    for (Eigen::Index i = 0; i < table.q(1).size(); ++i) {
      const double difference = (table.q(2)[i] - table.q(0)[i]) / (2 * h) * rate;
      CHECK(table.qd(1)[i] == doctest::Approx(difference).epsilon(1e-6));
    }
  }
}
