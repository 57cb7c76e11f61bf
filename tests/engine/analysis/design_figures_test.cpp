// Design figures of four-bars (issue 13): Grashof class from the link lengths for the four
// Grashof cases, a change point and a non-Grashof linkage; the transmission angle's
// extremes against the closed form cos(mu) = (b^2 + c^2 - a^2 - d^2 + 2 a d cos(theta2)) / 2bc.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/model.hpp"
#include "engine/analysis/toggles.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/base/number_format.hpp"
#include "readers/mechanism_file.hpp"

#include "tests/test_support.hpp"

namespace {

// The bundled four-bar with other lengths (mm).
std::optional<kinema::FourBarFigures> four_bar_with(const std::string& a, const std::string& b, const std::string& c,
                                                    const std::string& d) {
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  text = kinema_test::replaced(R"(a = "40 mm")", "a = \"" + a + " mm\"", text);
  text = kinema_test::replaced(R"(b = "120 mm")", "b = \"" + b + " mm\"", text);
  text = kinema_test::replaced(R"(c = "80 mm")", "c = \"" + c + " mm\"", text);
  text = kinema_test::replaced(R"(d = "100 mm")", "d = \"" + d + " mm\"", text);
  return kinema::four_bar_figures(kinema::make_model(kinema::read_mechanism_text(text, "four_bar.toml")));
}

}  // namespace

TEST_CASE("design figures: Grashof class of a four-bar from its lengths") {
  CHECK(four_bar_with("40", "120", "80", "100")->grashof == "crank-rocker");   // s = crank
  CHECK(four_bar_with("60", "90", "80", "30")->grashof == "double-crank");     // s = ground
  CHECK(four_bar_with("80", "120", "40", "100")->grashof == "rocker-crank");   // s = rocker
  CHECK(four_bar_with("100", "40", "80", "120")->grashof == "double-rocker");  // s = coupler
  CHECK(four_bar_with("40", "100", "40", "100")->grashof == "change point");   // s + l = p + q
  CHECK(four_bar_with("50", "70", "45", "60")->grashof == "non-Grashof triple rocker");
  // Session 30's review: a crank of length zero is no crank-rocker (it drives nothing),
  // and lengths whose sum passes the largest number in mm gave "s + l = inf".
  CHECK_FALSE(four_bar_with("0", "120", "80", "100").has_value());
  CHECK_FALSE(four_bar_with("1e308", "1e308", "1e308", "1e308").has_value());
  CHECK(four_bar_with("1e300", "3e300", "2e300", "2.5e300")->grashof == "crank-rocker");
  const auto crank_rocker = four_bar_with("40", "120", "80", "100");
  CHECK(crank_rocker->inequality == "s + l = 40 + 120 = 160 < p + q = 180 (mm)");
  // The same from files written as joints and links.
  const auto parallelogram = kinema::four_bar_figures(kinema::load_model(kinema_test::sample("problem_4_1_parallelogram.toml")));
  REQUIRE(parallelogram);
  CHECK(parallelogram->grashof == "change point");
  const auto triple = kinema::four_bar_figures(kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml")));
  REQUIRE(triple);
  CHECK(triple->grashof == "non-Grashof triple rocker");
  CHECK_FALSE(triple->full_turn);
  // Not four-bars: nothing.
  CHECK_FALSE(kinema::four_bar_figures(kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"))));
  CHECK_FALSE(kinema::four_bar_figures(kinema::load_model(kinema_test::sample("slider_crank.toml"))));
}

TEST_CASE("design figures: the transmission angle's extremes are where and what the closed form says") {
  const auto f = kinema::four_bar_figures(kinema::load_model(kinema_test::sample("four_bar.toml")));
  REQUIRE(f);
  CHECK(f->full_turn);
  const double a = 40, b = 120, c = 80, d = 100;
  const auto mu = [&](double theta2) {
    return std::acos((b * b + c * c - a * a - d * d + 2 * a * d * std::cos(theta2)) / (2 * b * c)) * 180 / M_PI;
  };
  CHECK(f->least_transmission == doctest::Approx(mu(0)).epsilon(1e-9));  // crank along the ground, inwards
  CHECK(f->least_at == doctest::Approx(0).scale(1));
  CHECK(f->greatest_transmission == doctest::Approx(mu(M_PI)).epsilon(1e-9));
  CHECK(f->greatest_at == doctest::Approx(180));
  // In eval's table and JSON.
  const auto table = kinema_test::run_kinema({"eval", kinema_test::sample("four_bar.toml")});
  CHECK(table.out.find("four-bar: Grashof crank-rocker (s + l = 40 + 120 = 160 < p + q = 180 (mm)); transmission angle "
                       "from 26.38 deg (theta2 = 0 deg) to 86.42 deg (theta2 = 180 deg); no toggle position\n") != std::string::npos);
  const nlohmann::json doc = kinema_test::eval_json("four_bar.toml");
  CHECK(doc["four_bar"]["grashof"] == "crank-rocker");
  CHECK(doc["four_bar"]["transmission_angle"]["least"].get<double>() == doctest::Approx(mu(0)).epsilon(1e-9));
  CHECK(doc["four_bar"]["lengths"]["coupler"].get<double>() == doctest::Approx(120));
  CHECK_FALSE(kinema_test::eval_json("problem_4_4_six_bar.toml").contains("four_bar"));
}

TEST_CASE("design figures: toggle positions solved from det Phi_q = 0, where the law of cosines puts them") {
  // The triple rocker (AB = 50, BC = 70, CD = 45, AD = 60 mm) folds where B, C and D are in
  // line with BD = BC - CD = 25 mm: cos(phi) = (50^2 + 60^2 - 25^2) / (2 * 50 * 60) = 0.9125.
  const kinema::Model model = kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"));
  const std::vector<kinema::Toggle> toggles = kinema::find_toggles(model);
  REQUIRE(toggles.size() == 2);
  const double phi = std::acos(0.9125);
  CHECK(toggles[0].input == doctest::Approx(phi).epsilon(1e-10));
  CHECK(toggles[1].input == doctest::Approx(2 * M_PI - phi).epsilon(1e-10));
  // There, B, C and D are in line: the coupler and the rocker are parallel.
  for (const kinema::Toggle& t : toggles) CHECK(std::fabs(std::sin(t.q[0] - t.q[1])) < 1e-9);
  // A crank-rocker never folds; a parallelogram at its change points (0 and 180 deg).
  CHECK(kinema::find_toggles(kinema::load_model(kinema_test::sample("four_bar.toml"))).empty());
  const auto change = kinema::find_toggles(kinema::load_model(kinema_test::sample("problem_4_1_parallelogram.toml")));
  REQUIRE(change.size() == 2);
  CHECK(change[0].input == doctest::Approx(0).scale(1));
  CHECK(change[1].input == doctest::Approx(M_PI).epsilon(1e-7));
  // And in eval's table.
  const auto table = kinema_test::run_kinema({"eval", kinema_test::sample("triple_rocker_circuit.toml")});
  CHECK(table.out.find("; toggle positions at phi = 24.1468, 335.8532 deg\n") != std::string::npos);
}

TEST_CASE("design figures: an offset slider-crank's limit positions and time ratio against the closed form") {
  // a = 50, b = 150, e = 10 mm: the piston is farthest with crank and rod in line,
  // sin(theta) = e / (a + b), nearest with the rod folded over the crank,
  // theta = 180 deg + asin(e / (b - a)); the strokes are the crank angles between.
  const auto strokes = kinema::slider_strokes(kinema::load_model(kinema_test::sample("slider_crank.toml")));
  REQUIRE(strokes.size() == 1);
  const kinema::Strokes& s = strokes.front();
  CHECK(s.name == "x");
  const double degree = 180 / M_PI;
  const double extended = std::asin(10.0 / 200) * degree, folded = 180 + std::asin(10.0 / 100) * degree;
  CHECK(s.limit_inputs[0] == doctest::Approx(extended).epsilon(1e-9));
  CHECK(s.limit_inputs[1] == doctest::Approx(folded).epsilon(1e-9));
  CHECK(s.limit_values[0] == doctest::Approx(std::sqrt(200.0 * 200 - 100)).epsilon(1e-9));  // x = sqrt((a+b)^2 - e^2)
  CHECK(s.limit_values[1] == doctest::Approx(std::sqrt(100.0 * 100 - 100)).epsilon(1e-9));
  REQUIRE(s.strokes.size() == 2);
  CHECK(s.strokes[0] == doctest::Approx(folded - extended).epsilon(1e-9));  // the crank turns counter-clockwise
  CHECK(s.time_ratio == doctest::Approx((folded - extended) / (360 - folded + extended)).epsilon(1e-9));
  // Problem 4.4's slider F reaches its limits where its velocity changes sign (eval's rows).
  const auto six = kinema::slider_strokes(kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml")));
  REQUIRE(six.size() == 1);
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"));
  for (double at : six.front().limit_inputs) {
    const kinema::MotionTable t = kinema::solve_motion(model, {M_PI / 6, at / degree});
    REQUIRE(t.status(1) == kinema::Status::ok);
    CHECK(std::fabs(t.qd(1)[3]) < 1e-8);  // vF = 0 there
  }
  const auto table = kinema_test::run_kinema({"eval", kinema_test::sample("slider_crank.toml")});
  CHECK(table.out.find("slider: x at its limits at theta2 = 2.8660 deg (199.75 mm) and 185.7392 deg (99.4987 mm); "
                       "strokes of 182.873 and 177.127 deg of crank, time ratio 1.03244\n") != std::string::npos);
  CHECK(kinema_test::eval_json("slider_crank.toml")["strokes"][0]["time_ratio"].get<double>() ==
        doctest::Approx(s.time_ratio));
}

TEST_CASE("design figures: a crank-shaper's time ratio against the closed form") {
  // The ram's limits are the rocker's: the crank at right angles to the slot,
  // theta2 = 270 deg -+ acos(a/d) (O2 is d above O4); the return takes 2 acos(a/d) of crank.
  const auto strokes = kinema::slider_strokes(kinema::load_model(kinema_test::sample("crank_shaper.toml")));
  const kinema::Strokes* ram = nullptr;
  for (const kinema::Strokes& s : strokes)
    if (s.name == "x") ram = &s;
  REQUIRE(ram);
  const double degree = 180 / M_PI, phi = std::acos(100.0 / 300) * degree;
  CHECK(ram->limit_inputs[0] == doctest::Approx(270 - phi).epsilon(1e-9));
  CHECK(ram->limit_inputs[1] == doctest::Approx(270 + phi).epsilon(1e-9));
  CHECK(ram->time_ratio == doctest::Approx((360 - 2 * phi) / (2 * phi)).epsilon(1e-9));
  CHECK(ram->time_ratio == doctest::Approx(1.5521).epsilon(1e-4));  // as the sample's comment says
}

namespace {

// n loops a*exp(I*theta2) = x_k + I*y_k: 2n sliding lengths, each at its limits a quarter
// turn apart (x_k at 0 and 180 deg, y_k at 90 and 270 deg).
std::string many_sliders(int n) {
  std::string text = "title = \"many sliders\"\n[parameters]\na = \"50 mm\"\n[input]\nname = \"theta2\"\n"
                     "value = \"30 deg\"\nrate = \"10 rad/s\"\n[output]\nlength = \"mm\"\n[unknowns]\n";
  for (int k = 0; k < n; ++k) text += "x" + std::to_string(k) + " = \"40 mm\"\ny" + std::to_string(k) + " = \"20 mm\"\n";
  text += "[loops]\n";
  for (int k = 0; k < n; ++k)
    text += "L" + std::to_string(k) + " = \"a*exp(I*theta2) - (x" + std::to_string(k) + " + I*y" + std::to_string(k) + ")\"\n";
  return text;
}

}  // namespace

// Issue 33: the limit search ran Newton in (q, theta) once per length unknown, O(n^4) a step:
// 16 loops of 32 sliders took 15-23 s in the table's and JSON's header, 64 loops past 200 s.
// One sweep of the turn now serves every slider; past kMaxStrokeUnknowns there are no strokes.
TEST_CASE("design figures: the strokes of 128 sliders in eval's header within the time limit") {
  const std::string path = kinema_test::write_temporary("many_sliders.toml", many_sliders(64));
  const auto table = kinema_test::run_kinema_bounded({"eval", path});
  REQUIRE(table.exit_status == 0);
  std::size_t lines = 0;
  for (auto at = table.out.find("slider: "); at != std::string::npos; at = table.out.find("slider: ", at + 1)) ++lines;
  CHECK(lines == 128);
  CHECK(table.out.find("slider: x63 at its limits at theta2 = 0.0000 deg (50 mm) and 180.0000 deg (-50 mm); strokes of "
                       "180 and 180 deg of crank, time ratio 1\n") != std::string::npos);
  CHECK(table.out.find("slider: y0 at its limits at theta2 = 90.0000 deg (50 mm) and 270.0000 deg (-50 mm)") !=
        std::string::npos);
  const auto json = kinema_test::run_kinema_bounded({"eval", path, "--format", "json"});
  REQUIRE(json.exit_status == 0);
  std::size_t ratios = 0;
  for (auto at = json.out.find("\"time_ratio\""); at != std::string::npos; at = json.out.find("\"time_ratio\"", at + 1)) ++ratios;
  CHECK(ratios == 128);
  CHECK(json.peak_kilobytes < 2 * 1024 * 1024);
  // The largest system (256 unknowns) has no strokes: its header costs nothing.
  const auto largest = kinema_test::run_kinema_bounded({"eval", kinema_test::write_temporary("most_sliders.toml", many_sliders(128))});
  REQUIRE(largest.exit_status == 0);
  CHECK(largest.out.find("slider: ") == std::string::npos);
  CHECK(kinema::kMaxStrokeUnknowns == 128);
}

// Issue 45: Problem 4.4 with BC = 0.38 m and CD = 0.35 m moves its slider up, down, up a
// little and down again over a turn. Every limit position is listed, each where a scan of
// the position solution (no rates) finds an extremum of the same kind, its value the
// position solved there and beyond both neighbours; the strokes are the crank angles
// between consecutive ones; text, JSON and LaTeX show them all.
TEST_CASE("design figures: a slider that turns back twice a turn has every limit position listed, each an extremum") {
  const std::string forms[] = {kinema_test::six_bar_turning_back_text(), kinema_test::six_bar_turning_back_joints_text()};
  for (const std::string& text : forms) {
    const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(text, "six_bar_turning_back.toml"));
    CAPTURE(model.system.title);
    std::size_t yF = 0;
    while (yF < model.system.unknowns.size() && model.system.unknowns[yF].name != "yF") ++yF;
    REQUIRE(yF < model.system.unknowns.size());
    const std::vector<kinema_test::ScannedExtremum> scan = kinema_test::scanned_extrema(model, yF);
    REQUIRE(scan.size() == 4);  // what makes this variant the issue's
    const std::vector<kinema::Strokes> strokes = kinema::slider_strokes(model);
    REQUIRE(strokes.size() == 1);
    const kinema::Strokes& s = strokes.front();
    CHECK(s.name == "yF");
    REQUIRE(s.limit_inputs.size() == scan.size());
    REQUIRE(s.limit_values.size() == scan.size());
    REQUIRE(s.maxima.size() == scan.size());
    const double degree = M_PI / 180, nudge = 0.01 * degree;
    for (std::size_t k = 0; k < scan.size(); ++k) {
      CAPTURE(k);
      CHECK(std::fabs(s.limit_inputs[k] - scan[k].input_deg) <= 0.05);  // within the scan's step
      CHECK(s.maxima[k] == scan[k].maximum);
      // The position solution at the limit and either side of it: the value listed, an extremum.
      const double at = s.limit_inputs[k] * degree;
      const kinema::MotionTable near = kinema::solve_motion(model, {at - nudge, at, at + nudge});
      for (std::size_t r = 0; r < 3; ++r) REQUIRE(near.status(r) == kinema::Status::ok);
      const double before = near.q(0)[Eigen::Index(yF)], here = near.q(1)[Eigen::Index(yF)], after = near.q(2)[Eigen::Index(yF)];
      CHECK(s.limit_values[k] == doctest::Approx(here).epsilon(1e-12));
      CHECK((scan[k].maximum ? here > before && here > after : here < before && here < after));
      CHECK(here == doctest::Approx(scan[k].value).epsilon(1e-6));
    }
    // Strokes: the crank angle from each limit to the next (counter-clockwise), round to the first.
    REQUIRE(s.strokes.size() == scan.size());
    double turn = 0;
    for (std::size_t k = 0; k < scan.size(); ++k) {
      const double next = k + 1 < scan.size() ? s.limit_inputs[k + 1] : s.limit_inputs[0] + 360;
      CHECK(s.strokes[k] == doctest::Approx(next - s.limit_inputs[k]).epsilon(1e-12));
      turn += s.strokes[k];
    }
    CHECK(turn == doctest::Approx(360).epsilon(1e-12));
    CHECK(std::isnan(s.time_ratio));  // no quick-return figure with four limits

    // Every view: the table's header line, JSON, the worked solution.
    const std::string file = kinema_test::write_temporary("six_bar_turning_back.toml", text);
    const kinema_test::CommandResult table = kinema_test::run_kinema({"eval", file});
    REQUIRE(table.exit_status == 0);
    const std::size_t line = table.out.find("slider: yF at 4 limit positions at phi = ");
    REQUIRE(line != std::string::npos);
    const std::string header = table.out.substr(line, table.out.find('\n', line) - line);
    CAPTURE(header);
    for (std::size_t k = 0; k < scan.size(); ++k) {
      CHECK(header.find(kinema::format_fixed(s.limit_inputs[k], 4) + " deg (" + (s.maxima[k] ? "maximum " : "minimum ") +
                        kinema::format_significant(s.limit_values[k]) + " m)") != std::string::npos);
      CHECK(header.find(kinema::format_significant(s.strokes[k])) != std::string::npos);
    }
    const kinema_test::CommandResult json_run = kinema_test::run_kinema({"eval", file, "--format", "json"});
    REQUIRE(json_run.exit_status == 0);
    const nlohmann::json json = nlohmann::json::parse(json_run.out)["strokes"][0];
    REQUIRE(json["limit_inputs"].size() == scan.size());
    REQUIRE(json["strokes"].size() == scan.size());
    for (std::size_t k = 0; k < scan.size(); ++k) {
      CHECK(json["limit_inputs"][k].get<double>() == doctest::Approx(s.limit_inputs[k]).epsilon(1e-12));
      CHECK(json["limit_values"][k].get<double>() == doctest::Approx(s.limit_values[k]).epsilon(1e-12));
      CHECK(json["strokes"][k].get<double>() == doctest::Approx(s.strokes[k]).epsilon(1e-12));
    }
    CHECK(json["time_ratio"].is_null());
    const std::string tex = kinema_test::write_temporary("six_bar_turning_back.tex", "");
    REQUIRE(kinema_test::run_kinema({"latex", file, "-o", tex}).exit_status == 0);
    const std::string latex = kinema_test::read_file(tex);
    const std::size_t sentence = latex.find("Slider: $y_{F}$ at 4 limit positions at $\\phi = ");
    REQUIRE(sentence != std::string::npos);
    const std::string said = latex.substr(sentence, latex.find("\n", sentence) - sentence);
    CAPTURE(said);
    std::size_t maxima = 0, minima = 0;
    for (auto at = said.find("(maximum $"); at != std::string::npos; at = said.find("(maximum $", at + 1)) ++maxima;
    for (auto at = said.find("(minimum $"); at != std::string::npos; at = said.find("(minimum $", at + 1)) ++minima;
    CHECK(maxima == 2);
    CHECK(minima == 2);
    CHECK(said.find("strokes of $") != std::string::npos);
  }
}

// A length unknown that does not move over the turn (a loop the input does not reach) has
// no limit positions: its rate is 0 at every row, not a limit at each.
TEST_CASE("design figures: a slider coordinate that does not move has no limit positions") {
  const std::string text = R"toml(title = "a slider that does not move"
[parameters]
a = "50 mm"
b = "150 mm"
c = "80 mm"
d = "60 mm"
[input]
name = "theta2"
value = "30 deg"
rate = "10 rad/s"
[unknowns]
theta3 = "-10 deg"
x = "190 mm"
theta4 = "50 deg"
s = "60 mm"
[loops]
ABC = "a*exp(I*theta2) + b*exp(I*theta3) - x"
DE = "c*exp(I*theta4) - (d + I*s)"
)toml";
  const std::vector<kinema::Strokes> strokes =
      kinema::slider_strokes(kinema::make_model(kinema::read_mechanism_text(text, "still.toml")));
  REQUIRE(strokes.size() == 1);
  CHECK(strokes[0].name == "x");
  CHECK(strokes[0].limit_inputs.size() == 2);
}
