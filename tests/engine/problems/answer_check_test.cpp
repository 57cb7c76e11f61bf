// kinema check's engine: every mistake of the catalogue diagnosed from an answer crafted
// by the test (the mechanism edited by hand to the mistake, or the textbook's formula
// worked with kinema's correct numbers), never from the checker's own mistaken value; right
// answers pass; the tolerance's edges; answers read in their units.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "engine/base/errors.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/base/number_format.hpp"
#include "engine/problems/answer_check.hpp"
#include "engine/problems/mistake_catalogue.hpp"
#include "readers/answers_file.hpp"

#include "tests/test_support.hpp"

namespace {

using namespace kinema;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

Model sample_model(const std::string& name) {
  return load_model(kinema_test::sample(name), DerivationScope::evaluation);
}

// A mechanism file edited by hand (the mistake made in the file), loaded.
Model edited_model(const std::string& sample, const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string text = kinema_test::read_file(kinema_test::sample(sample));
  for (const auto& [from, to] : edits) text = kinema_test::replaced(from, to, text);
  return load_model(kinema_test::write_temporary("edited_" + sample, text), DerivationScope::evaluation);
}

// The model's state at one input value (SI), as kinema eval solves it.
MotionState state_at(const Model& model, double at) {
  const MotionTable table = solve_motion(model, {at});
  REQUIRE(table.status(0) == Status::ok);
  return table[0];
}

AnswersFile one_answer(const std::string& quantity, const std::string& at, const std::string& value) {
  AnswersFile file;
  file.path = "answers.toml";
  file.answers.push_back({quantity, at, value, {"answers.toml", 2}});
  return file;
}

// The verdict on one answer (a bare number: in the file's output unit).
AnswerVerdict verdict_on(const Model& model, const std::string& quantity, const std::string& at, double value,
                         const AnswerTolerance& tolerance = {}) {
  return check_answers(file_subject(model), one_answer(quantity, at, format_round_trip(value)), tolerance).verdicts.at(0);
}

// The answer is wrong and the likely mistake is `name`.
void check_diagnosed(const AnswerVerdict& verdict, const std::string& name) {
  CAPTURE(verdict.quantity);
  CAPTURE(verdict.given_value);
  CAPTURE(verdict.expected);
  CHECK_FALSE(verdict.right);
  REQUIRE_FALSE(verdict.mistakes.empty());
  CHECK(verdict.mistakes.front().name == name);
}

}  // namespace

TEST_CASE("check: the catalogue names each mistake once, in words") {
  std::vector<std::string> names;
  for (const Mistake& m : mistake_catalogue()) {
    CHECK(std::string(m.words).size() > 10);
    CHECK(std::find(names.begin(), names.end(), m.name) == names.end());
    names.push_back(m.name);
  }
  for (const char* wanted : {"sign_reversed", "degrees_for_radians", "radians_for_degrees", "rpm_as_rad_per_s",
                             "other_assembly", "coriolis_omitted", "coriolis_doubled", "relative_for_absolute",
                             "another_link_rate", "length_mm_as_m"}) {
    CHECK(std::find(names.begin(), names.end(), wanted) != names.end());
  }
}

TEST_CASE("check: right answers pass, in the output unit or any unit of their kind") {
  const Model model = sample_model("four_bar.toml");
  const MotionState s = state_at(model, 40 * kDeg);
  const double omega3 = s.qd[0];
  CHECK(verdict_on(model, "omega3", "40 deg", omega3).right);
  CHECK(verdict_on(model, "theta3", "40 deg", s.q[0] / kDeg).right);
  CHECK(verdict_on(model, "theta3", "40 deg", s.q[0] / kDeg + 360).right);  // angles to whole turns
  CHECK(verdict_on(model, "P_ax", "40 deg", s.points[2].acceleration[0] * 1000).right);
  CHECK(verdict_on(model, "vP", "40 deg", s.points[2].speed() * 1000).right);
  CHECK(verdict_on(model, "aB", "40 deg", s.points[1].acceleration_magnitude() * 1000).right);
  // The same numbers in other units: deg/s, m/s; the input value in rad.
  const auto given = [&](const std::string& quantity, const std::string& at, const std::string& value) {
    return check_answers(file_subject(model), one_answer(quantity, at, value), {}).verdicts.at(0);
  };
  const AnswerVerdict in_degrees = given("omega3", "40 deg", format_round_trip(omega3 / kDeg) + " deg/s");
  CHECK(in_degrees.right);
  CHECK_FALSE(in_degrees.unit_assumed);
  CHECK(given("vP", format_round_trip(40 * kDeg) + " rad", format_round_trip(s.points[2].speed()) + " m/s").right);
  CHECK(given("omega3", "40 deg", "-1 rad/s").right == false);
}

TEST_CASE("check: a relative tolerance and significant figures accept up to their edge") {
  const Model model = sample_model("four_bar.toml");
  const double omega3 = state_at(model, 40 * kDeg).qd[0];  // -1.648... rad/s
  AnswerTolerance percent;  // 1 %
  CHECK(verdict_on(model, "omega3", "40 deg", omega3 * 1.0099, percent).right);
  CHECK_FALSE(verdict_on(model, "omega3", "40 deg", omega3 * 1.0101, percent).right);
  const AnswerTolerance tenth = relative_tolerance("0.1%", "test");
  CHECK(verdict_on(model, "omega3", "40 deg", omega3 * 1.00099, tenth).right);
  CHECK_FALSE(verdict_on(model, "omega3", "40 deg", omega3 * 1.0011, tenth).right);

  // Three figures: the value as printed to three figures is right, one unit off in the
  // third figure is wrong.
  const AnswerTolerance figures = significant_figures(3, "test");
  char printed[32];
  std::snprintf(printed, sizeof printed, "%.3g", omega3);
  const double three = std::stod(printed);
  CHECK(verdict_on(model, "omega3", "40 deg", three, figures).right);
  CHECK_FALSE(verdict_on(model, "omega3", "40 deg", three + 0.01, figures).right);
  CHECK_FALSE(verdict_on(model, "omega3", "40 deg", three - 0.01, figures).right);
  std::snprintf(printed, sizeof printed, "%.2g", omega3);  // two figures are not three
  CHECK_FALSE(verdict_on(model, "omega3", "40 deg", std::stod(printed), figures).right);

  CHECK_THROWS_AS(relative_tolerance("150%", "test"), InputError);
  CHECK_THROWS_AS(relative_tolerance("one percent", "test"), InputError);
  CHECK_THROWS_AS(significant_figures(0, "test"), InputError);
}

TEST_CASE("check: sign reversed, degrees for radians, radians for degrees, another link's rate") {
  const Model model = sample_model("four_bar.toml");
  const MotionState s = state_at(model, 40 * kDeg);
  check_diagnosed(verdict_on(model, "omega3", "40 deg", -s.qd[0]), "sign_reversed");
  check_diagnosed(verdict_on(model, "alpha4", "40 deg", s.qdd[1] * 180 / 3.14159265358979323846), "degrees_for_radians");
  check_diagnosed(verdict_on(model, "theta4", "40 deg", s.q[1]), "radians_for_degrees");  // rad written as deg
  check_diagnosed(verdict_on(model, "omega3", "40 deg", s.qd[1]), "another_link_rate");   // omega4 for omega3
}

TEST_CASE("check: the driver's rpm used as rad/s (the file edited to say rad/s)") {
  const Model model = sample_model("slider_crank.toml");  // rate = "3000 rpm"
  const Model mistaken = edited_model("slider_crank.toml", {{"rate = \"3000 rpm\"", "rate = \"3000 rad/s\""}});
  const MotionState s = state_at(mistaken, 60 * kDeg);
  check_diagnosed(verdict_on(model, "omega3", "60 deg", s.qd[0]), "rpm_as_rad_per_s");
  check_diagnosed(verdict_on(model, "alpha3", "60 deg", s.qdd[0]), "rpm_as_rad_per_s");
}

TEST_CASE("check: the other assembly of a vector-loop four-bar (its guesses edited to the crossed branch)") {
  const Model model = sample_model("four_bar.toml");
  const MotionState s = state_at(model, 40 * kDeg);
  // The crossed branch by hand: B reflected in the line from A to O4 = (d, 0).
  const std::complex<double> a(s.points[0].position[0], s.points[0].position[1]),
      b(s.points[1].position[0], s.points[1].position[1]), d(0.1, 0);
  const std::complex<double> u = (d - a) / std::abs(d - a);
  const std::complex<double> crossed = a + u * std::conj((b - a) / u);
  const std::string theta3 = format_significant(std::arg(crossed - a) / kDeg, 8) + " deg";
  const std::string theta4 = format_significant(std::arg(crossed - d) / kDeg, 8) + " deg";
  const Model other = edited_model("four_bar.toml", {{"theta3 = \"20 deg\"", "theta3 = \"" + theta3 + "\""},
                                                    {"theta4 = \"80 deg\"", "theta4 = \"" + theta4 + "\""}});
  const MotionState o = state_at(other, 40 * kDeg);
  REQUIRE(std::abs(o.points[1].position[1] - crossed.imag()) < 1e-9);  // the edit is the crossed branch
  check_diagnosed(verdict_on(model, "omega3", "40 deg", o.qd[0]), "other_assembly");
  check_diagnosed(verdict_on(model, "alpha4", "40 deg", o.qdd[1]), "other_assembly");
}

TEST_CASE("check: the other assembly of a joints-and-links mechanism (its sketch edited to the other one)") {
  const Model model = sample_model("example_4_1_joints.toml");
  // Slider B2 on the crank's line y = x meets the circle about C at B = (0.256, 0.256) m,
  // left of A-C, and at (-0.156, -0.156) m: the file stating that assembly instead.
  const Model other = edited_model("example_4_1_joints.toml",
                                   {{"B = { at = [\"0.256 m\", \"0.256 m\"] }",
                                     "B = { at = [\"0.256 m\", \"0.256 m\"], assembly = \"right of A-C\" }"}});
  const MotionState o = state_at(other, 45 * kDeg);
  REQUIRE(o.q[1] < 0);  // r = AB < 0: B behind A on the crank's line
  const std::size_t omega3 = 0;  // unknowns phi3, r
  check_diagnosed(verdict_on(model, "omega3", "45 deg", o.qd[omega3]), "other_assembly");
}

TEST_CASE("check: the Coriolis term omitted or doubled (the crank-shaper's alpha4 worked by hand)") {
  const Model model = sample_model("crank_shaper.toml");
  const MotionState s = state_at(model, 30 * kDeg);
  // Unknowns s, theta4, theta5, x. From I d + a e^{i theta2} = s e^{i theta4}, twice
  // differentiated and taken across the slot: s alpha4 + 2 s' omega4 = Im(...), so
  // without the Coriolis term alpha4 is larger by 2 s' omega4 / s, with it twice smaller.
  const double slide = s.q[0], slide_rate = s.qd[0], omega4 = s.qd[1], alpha4 = s.qdd[1];
  const double coriolis = 2 * slide_rate * omega4 / slide;
  check_diagnosed(verdict_on(model, "alpha4", "30 deg", alpha4 + coriolis), "coriolis_omitted");
  check_diagnosed(verdict_on(model, "alpha4", "30 deg", alpha4 - coriolis), "coriolis_doubled");
}

TEST_CASE("check: a mechanism without a slider on a turning link has no Coriolis mistake to make") {
  const Model model = sample_model("four_bar.toml");
  const EvaluationPoint point{&model, 40 * kDeg, model.system.input.rate_value, 0.0, ""};
  const SolvedRow correct = solve_row(point);
  for (const Mistake& m : mistake_catalogue()) {
    CAPTURE(m.name);
    const std::string name = m.name;
    if (name == "coriolis_omitted" || name == "coriolis_doubled" || name == "rpm_as_rad_per_s")
      CHECK(m.rows(point, correct).empty());
    if (name == "sign_reversed" || name == "other_assembly") CHECK_FALSE(m.rows(point, correct).empty());
  }
}

TEST_CASE("check: a relative velocity given for the absolute one (v_PA = omega3 p)") {
  const Model model = sample_model("four_bar.toml");
  const MotionState s = state_at(model, 40 * kDeg);
  const double p = 60;  // mm: P is p from A on the coupler
  check_diagnosed(verdict_on(model, "vP", "40 deg", std::abs(s.qd[0]) * p), "relative_for_absolute");
}

TEST_CASE("check: a length in mm taken as m (the file edited to say m)") {
  const Model model = sample_model("four_bar.toml");
  const Model mistaken = edited_model("four_bar.toml", {{"p = \"60 mm\"", "p = \"60 m\""}});
  const MotionState s = state_at(mistaken, 40 * kDeg);
  check_diagnosed(verdict_on(model, "vP", "40 deg", s.points[2].speed() * 1000), "length_mm_as_m");
}

TEST_CASE("check: a wrong answer no mistake gives is wrong with none named") {
  const Model model = sample_model("four_bar.toml");
  const AnswerVerdict v = verdict_on(model, "omega3", "40 deg", 123.0);
  CHECK_FALSE(v.right);
  CHECK(v.mistakes.empty());
}

TEST_CASE("check: an unknown quantity lists the mechanism's; a value of another kind names both") {
  const Model model = sample_model("four_bar.toml");
  try {
    check_answers(file_subject(model), one_answer("omega9", "40 deg", "1"), {});
    FAIL("no error");
  } catch (const InputError& error) {
    const std::string message = error.what();
    CHECK(message.find("answers.toml:2") != std::string::npos);
    CHECK(message.find("\"omega9\"") != std::string::npos);
    CHECK(message.find("omega3, alpha3") != std::string::npos);
    CHECK(message.find("P_speed") != std::string::npos);
  }
  CHECK_THROWS_WITH_AS(check_answers(file_subject(model), one_answer("omega3", "40 deg", "2 mm/s"), {}),
                       doctest::Contains("answers.toml:2: value \"2 mm/s\" is a velocity, but omega3 is an angular velocity"),
                       UnitError);
  CHECK_THROWS_WITH_AS(check_answers(file_subject(model), one_answer("omega3", "40 mm", "2"), {}),
                       doctest::Contains("answers.toml:2: at of omega3"), InputError);
}

TEST_CASE("check: a design figure is graded once, without at; a class in words as text") {
  const Model model = sample_model("four_bar.toml");
  const std::optional<FourBarFigures> f = four_bar_figures(model);
  REQUIRE(f);
  const AnswerVerdict least = verdict_on(model, "min_transmission_angle", "", f->least_transmission);
  CHECK(least.figure);
  CHECK(least.right);
  CHECK_FALSE(verdict_on(model, "min_transmission_angle", "", f->least_transmission + 5).right);
  CHECK_FALSE(verdict_on(model, "max_transmission_angle", "", f->least_transmission).right);
  // The same angle in radians is the same answer.
  CHECK(check_answers(file_subject(model), one_answer("min_transmission_angle", "", format_round_trip(f->least_transmission * kDeg) + " rad"), {})
            .verdicts.at(0).right);
  const auto grashof = [&](const std::string& words) {
    return check_answers(file_subject(model), one_answer("grashof", "", words), {}).verdicts.at(0);
  };
  REQUIRE(f->grashof == "crank-rocker");
  CHECK(grashof(" Crank-Rocker").right);
  CHECK_FALSE(grashof("double-rocker").right);
  CHECK(grashof("double-rocker").expected_text == "crank-rocker");
  // A figure is of the whole turn: an input value is refused; a figure the mechanism lacks too.
  CHECK_THROWS_AS(check_answers(file_subject(model), one_answer("grashof", "30 deg", "crank-rocker"), {}), InputError);
  CHECK_THROWS_AS(check_answers(file_subject(model), one_answer("time_ratio", "", "1.2"), {}), InputError);
}
