// kinema problems (docs/problems.md): variants drawn from a seed meet their conditions
// (checked again here on the file edited to each variant's values), their answers are
// kinema eval's of that edited file, a seed gives the same bytes and another seed other
// ones, the Moodle XML reads back with every answer and its tolerance, the documents
// compile without an overfull line, and a bad [problem] is refused at its line.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <regex>

#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/toggles.hpp"
#include "engine/base/errors.hpp"
#include "engine/problems/problem_set.hpp"
#include "engine/base/number_format.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/problems/problem_documents.hpp"
#include "engine/run/problem_files.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/engine/printers/latex_pages.hpp"
#include "tests/engine/problems/xml_reader.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace kinema;

// The four-bar of samples/four_bar.toml as a problem: a and b varied so that some draws
// are not crank-rockers or transmit badly, and are redrawn.
const std::string kFourBarProblem = R"toml(
[problem]
statement = "Find the angular velocity of the coupler, the angular acceleration of the rocker and the speed of P."
find = ["omega3", "alpha4", "vP"]
at = ["40 deg", "200 deg"]
sig_figs = 3

[problem.vary]
a = { range = ["30 mm", "70 mm"], step = "2 mm" }
b = { range = ["100 mm", "140 mm"], step = "5 mm" }
omega2 = { range = ["5 rad/s", "15 rad/s"], step = "1 rad/s" }

[problem.conditions]
grashof = "crank-rocker"
min_transmission_angle = "35 deg"
toggle_margin = "5 deg"
min_answer = 0.2
)toml";

std::string four_bar_problem_text() {
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  // omega2, the crank's rate, named so that [problem] vary can draw it.
  return kinema_test::replaced("rate = \"10 rad/s\"", "rate = \"10 rad/s\"\nrate_name = \"omega2\"", text) + kFourBarProblem;
}

struct Loaded {
  Mechanism mechanism;
  Model model;
};

Loaded load(const std::string& text, const std::string& name) {
  Loaded loaded{read_mechanism_text(text, name), {}};
  loaded.model = make_model(loaded.mechanism);
  return loaded;
}

// The file's text with each varied parameter (and the driver's rate) written as the variant's
// value: what a teacher would edit by hand, read and derived from scratch.
std::string edited(std::string text, const ProblemVariant& variant, const std::string& rate_name) {
  for (const GivenValue& g : variant.given) {
    const std::string value = "\"" + format_significant(g.value, 12) + " " + g.unit + "\"";
    const std::regex line(g.name == rate_name ? "\\nrate = \"[^\"]*\"" : "\\n" + g.name + " = \"[^\"]*\"");
    REQUIRE(std::regex_search(text, line));
    text = std::regex_replace(text, line, "\n" + std::string(g.name == rate_name ? "rate" : g.name) + " = " + value,
                              std::regex_constants::format_first_only);
  }
  return text;
}

// kinema eval's value of column `name` (or vP, aP) at each asked value of `model`.
double eval_column(const Model& model, const std::string& name, double at) {
  const OutputScale scale(model.system);
  const std::vector<ResultColumn> columns = result_columns(model.system, scale);
  std::vector<double> values(columns.size());
  const MotionTable table = solve_motion(model, {at});
  REQUIRE(table.status(0) == Status::ok);
  result_values(model.system, scale, table, 0, values.data());
  std::string column = name;
  for (const PointObservable& p : model.system.points)
    if (name == "v" + p.name) column = p.name + "_speed";
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k].name == column) return values[k];
  FAIL("no column " << column);
  return 0;
}

}  // namespace

TEST_CASE("problems: draws are std::mt19937_64's as the standard gives them, mapped by our own rejection") {
  // The standard fixes the 10000th output of a default-seeded mt19937_64.
  std::mt19937_64 engine;
  engine.discard(9999);
  CHECK(engine() == 9981545732273789042ull);
  ProblemDraws draws(7), again(7);
  std::vector<int> seen(7, 0);
  for (int k = 0; k < 700; ++k) {
    const std::uint64_t x = draws.below_or_equal(6);
    REQUIRE(x <= 6);
    CHECK(x == again.below_or_equal(6));
    ++seen[x];
  }
  for (int count : seen) CHECK(count > 50);  // every grid value is drawn
}

TEST_CASE("problems: every variant meets its conditions, evaluated again from the file edited to its values") {
  const std::string text = four_bar_problem_text();
  const Loaded loaded = load(text, "four_bar_problem.toml");
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 8, 7);
  REQUIRE(set.variants.size() == 8);
  // Draws refused are counted per condition (a draw may fail more than one), and some are refused.
  std::size_t refused = 0;
  for (const auto& [condition, count] : set.redrawn) refused += count;
  CHECK(set.draws > set.variants.size());
  CHECK(refused >= set.draws - set.variants.size());
  for (const ProblemVariant& variant : set.variants) {
    CAPTURE(variant.number);
    const Model fresh = make_model(read_mechanism_text(edited(text, variant, "omega2"), "edited.toml"));
    const MotionTable table = solve_motion(fresh, variant.at);
    for (std::size_t row = 0; row < table.size(); ++row) CHECK(table.status(row) == Status::ok);
    const std::optional<FourBarFigures> figures = four_bar_figures(fresh);
    REQUIRE(figures);
    CHECK(figures->grashof == "crank-rocker");
    CHECK(figures->least_transmission >= 35);
    CHECK(figures->greatest_transmission <= 180 - 35);
    for (const Toggle& toggle : find_toggles(fresh))
      for (double at : variant.at) CHECK(std::fabs(std::remainder(at - toggle.input, 2 * M_PI)) >= 5 * M_PI / 180);
    for (const ProblemAnswer& answer : variant.answers) CHECK(std::fabs(answer.value) >= 0.2);
    // On the step grids.
    for (const GivenValue& g : variant.given) {
      const double step = g.name == "omega2" ? 1 : g.name == "a" ? 2 : 5, low = g.name == "omega2" ? 5 : g.name == "a" ? 30 : 100;
      CHECK(std::fabs(std::remainder(g.value - low, step)) < 1e-9);
    }
  }
}

TEST_CASE("problems: the keys' answers are kinema eval's of the file edited to each variant") {
  for (const char* sample : {"four_bar", "problem_4_4_set"}) {
    CAPTURE(sample);
    const bool four_bar = std::string(sample) == "four_bar";
    const std::string text = four_bar ? four_bar_problem_text() : kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml"));
    const Loaded loaded = load(text, "set.toml");
    const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 4, 11);
    for (const ProblemVariant& variant : set.variants) {
      const Model fresh = make_model(read_mechanism_text(edited(text, variant, four_bar ? "omega2" : "omega1"), "edited.toml"),
                                     DerivationScope::evaluation);
      REQUIRE(variant.answers.size() == loaded.mechanism.problem->find.size() * variant.at.size());
      for (const ProblemAnswer& answer : variant.answers) {
        CAPTURE(answer.quantity);
        const double expected = eval_column(fresh, answer.quantity, answer.at_si);
        CHECK(answer.value == doctest::Approx(expected).epsilon(1e-9));
        // SI: the output unit's value times its unit (mm/s for the four-bar's vP).
        const double unit = answer.unit.rfind("mm", 0) == 0 ? 1e-3 : 1.0;
        CHECK(answer.si == doctest::Approx(expected * unit).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("problems: a design figure answers once per variant, the analysis' figure of the file edited to it") {
  // A four-bar's Grashof class (in words) and transmission angles.
  const std::string four_bar = kinema_test::replaced("find = [\"omega3\", \"alpha4\", \"vP\"]",
      "find = [\"omega3\", \"grashof\", \"min_transmission_angle\", \"max_transmission_angle\"]", four_bar_problem_text());
  const Loaded loaded = load(four_bar, "four_bar_figures.toml");
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 3, 7);
  for (const ProblemVariant& variant : set.variants) {
    CAPTURE(variant.number);
    REQUIRE(variant.answers.size() == variant.at.size() + 3);  // omega3 at each value, each figure once
    const std::optional<FourBarFigures> f =
        four_bar_figures(make_model(read_mechanism_text(edited(four_bar, variant, "omega2"), "edited.toml")));
    REQUIRE(f);
    const ProblemAnswer* grashof = &variant.answers[variant.at.size()];
    CHECK(grashof->figure);
    CHECK(grashof->at_text.empty());
    CHECK(grashof->text == f->grashof);
    CHECK(grashof[1].value == doctest::Approx(f->least_transmission).epsilon(1e-9));
    CHECK(grashof[1].si == doctest::Approx(f->least_transmission * M_PI / 180).epsilon(1e-9));
    CHECK(grashof[2].value == doctest::Approx(f->greatest_transmission).epsilon(1e-9));
  }
  // The class table and the exports carry them: the class as a short-answer question.
  CHECK(problem_class_csv(set).find("min_transmission_angle [deg]") != std::string::npos);
  CHECK(problem_class_json(set, "x.toml").find("\"text\": \"crank-rocker\"") != std::string::npos);
  const std::string moodle = problem_moodle_xml(set, "t");
  CHECK(moodle.find("<question type=\"shortanswer\">") != std::string::npos);
  CHECK(moodle.find("<text>crank-rocker</text>") != std::string::npos);

  // A slider's stroke and time ratio (the six-bar's slider 5).
  const std::string six_bar = kinema_test::replaced("find = [\"omega3\", \"alpha3\", \"vF\"]", "find = [\"stroke\", \"time_ratio\"]",
                                                    kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml")));
  const Loaded slider = load(six_bar, "six_bar_figures.toml");
  const ProblemSet strokes = make_problem_set(slider.model, *slider.mechanism.problem, 2, 7);
  for (const ProblemVariant& variant : strokes.variants) {
    CAPTURE(variant.number);
    const std::vector<Strokes> s = slider_strokes(make_model(read_mechanism_text(edited(six_bar, variant, "omega1"), "edited.toml")));
    REQUIRE(!s.empty());
    REQUIRE(variant.answers.size() == 2);
    CHECK(variant.answers[0].value == doctest::Approx(std::fabs(s[0].limit_values[1] - s[0].limit_values[0])).epsilon(1e-9));
    CHECK(variant.answers[1].value == doctest::Approx(s[0].time_ratio).epsilon(1e-9));
  }
}

TEST_CASE("problems: toggle_margin redraws a variant asked too near a slider's limit position") {
  // The offset slider-crank has no toggle; its piston's outer limit is where crank and rod
  // are in line, sin(theta2) = e / (a + b): 0.3 deg to 11.5 deg over the drawn offsets, so
  // the draws of e above about 17 mm put it within 5 deg of the asked 10 deg.
  const std::string text = kinema_test::read_file(kinema_test::sample("slider_crank.toml")) + R"toml(
[problem]
find = ["omega3"]
at = ["10 deg"]
[problem.vary]
e = { range = ["1 mm", "40 mm"], step = "1 mm" }
[problem.conditions]
toggle_margin = "5 deg"
)toml";
  const Loaded loaded = load(text, "slider_limits.toml");
  REQUIRE(find_toggles(loaded.model).empty());
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 8, 7);
  REQUIRE(set.redrawn.size() == 1);
  CHECK(set.redrawn[0].first == "toggle_margin");
  CHECK(set.redrawn[0].second > 0);
  for (const ProblemVariant& variant : set.variants) {
    const double e = variant.given.at(0).si, limit = std::asin(e / (0.05 + 0.15)) * 180 / M_PI;
    CAPTURE(e);
    CHECK(std::fabs(limit - 10) >= 5);
  }
}

// Issue 45: a slider that turns back twice a turn (Problem 4.4 with BC = 0.38 m, CD = 0.35 m)
// has four limit positions; toggle_margin keeps the asked value off each of them, found here
// by scanning the position solution.
TEST_CASE("problems: toggle_margin counts each of a slider's four limit positions") {
  const std::string text = kinema_test::six_bar_turning_back_text() + R"toml(
[problem]
find = ["omega3"]
at = ["30 deg"]
[problem.vary]
omega1 = { range = ["50 rpm", "70 rpm"], step = "5 rpm" }
[problem.conditions]
toggle_margin = "5 deg"
)toml";
  const Loaded loaded = load(text, "six_bar_turning_back.toml");
  const std::vector<kinema_test::ScannedExtremum> limits = kinema_test::scanned_extrema(loaded.model, 3);  // yF
  REQUIRE(limits.size() == 4);
  const Problem& problem = *loaded.mechanism.problem;
  const double degree = M_PI / 180;
  for (const kinema_test::ScannedExtremum& limit : limits) {
    CAPTURE(limit.input_deg);
    for (const double off : {-3.0, 3.0}) {
      const std::vector<std::string> failed = failed_conditions(loaded.model, problem, {(limit.input_deg + off) * degree});
      CHECK(std::find(failed.begin(), failed.end(), "toggle_margin") != failed.end());
    }
  }
  // Midway along the longest stroke: farther than the margin from every limit.
  double away = 0, longest = 0;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const double next = k + 1 < limits.size() ? limits[k + 1].input_deg : limits[0].input_deg + 360;
    if (next - limits[k].input_deg > longest) {
      longest = next - limits[k].input_deg;
      away = limits[k].input_deg + longest / 2;
    }
  }
  REQUIRE(longest > 12);
  CHECK(failed_conditions(loaded.model, problem, {away * degree}).empty());
  // A margin of 179 deg leaves no value a quarter of the turn from every limit: all refused.
  Problem wide = problem;
  wide.conditions.toggle_margin = 179 * degree;
  CHECK(failed_conditions(loaded.model, wide, {away * degree}) == std::vector<std::string>{"toggle_margin"});
}

// A variant whose slider has four limit positions has no one stroke or time ratio: drawn
// again for that, said so, not counted as an answer too small (min_answer).
TEST_CASE("problems: a variant without the stroke asked is redrawn as missing it, not as min_answer") {
  const std::string text = kinema_test::replaced("find = [\"omega3\", \"alpha3\", \"vF\"]", "find = [\"stroke\", \"time_ratio\"]",
                                                 kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml")));
  const Loaded loaded = load(text, "six_bar_strokes.toml");
  const Problem& problem = *loaded.mechanism.problem;
  REQUIRE(problem.conditions.min_answer);
  const std::string no_stroke = "no stroke (not two limit positions over a whole turn)";
  const std::string no_ratio = "no time_ratio (not two limit positions over a whole turn)";
  // The file's own dimensions have both; BC = 0.38 m, CD = 0.35 m neither.
  CHECK(failed_conditions(loaded.model, problem, {M_PI / 6}).empty());
  const Model four_limits = with_parameters(loaded.model, {{"BC", 0.38}, {"CD", 0.35}});
  REQUIRE(slider_strokes(four_limits).at(0).limit_inputs.size() == 4);
  CHECK(failed_conditions(four_limits, problem, {M_PI / 6}) == std::vector<std::string>{no_stroke, no_ratio});
  // Every draw of those dimensions refused, and the report says why.
  const std::string only = kinema_test::replaced(
      "CD = { range = [\"0.35 m\", \"0.39 m\"], step = \"5 mm\" }", "CD = { range = [\"0.35 m\", \"0.351 m\"], step = \"5 mm\" }",
      kinema_test::replaced("BC = { range = [\"0.38 m\", \"0.42 m\"], step = \"5 mm\" }",
                            "BC = { range = [\"0.38 m\", \"0.381 m\"], step = \"5 mm\" }", text));
  const Loaded fixed = load(only, "six_bar_four_limits.toml");
  try {
    make_problem_set(fixed.model, *fixed.mechanism.problem, 1, 7);
    FAIL("every draw has four limit positions: no set");
  } catch (const InputError& error) {
    const std::string message = error.what();
    CAPTURE(message);
    CHECK(message.find("(refused by: " + no_stroke + " 200, " + no_ratio + " 200)") != std::string::npos);
    CHECK(message.find("min_answer") == std::string::npos);
  }
}

TEST_CASE("problems: the same seed gives the same bytes, another seed another set") {
  const std::string text = kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml"));
  const auto files_for = [&](std::uint64_t seed) {
    const Loaded loaded = load(text, "problem_4_4_set.toml");
    // The tables only: the documents are printed from them (tested for their content below).
    const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 5, seed);
    std::vector<NamedFile> files = problem_set_files(set, "problem_4_4_set.toml", loaded.mechanism.title);
    return files;
  };
  const std::vector<NamedFile> first = files_for(7), second = files_for(7), other = files_for(8);
  REQUIRE(first.size() == 2 * 5 + 4);
  REQUIRE(first.size() == second.size());
  for (std::size_t k = 0; k < first.size(); ++k) {
    CAPTURE(first[k].first);
    CHECK(first[k].first == second[k].first);
    CHECK(first[k].second == second[k].second);
  }
  bool differs = false;
  for (std::size_t k = 0; k < first.size(); ++k) differs = differs || first[k].second != other[k].second;
  CHECK(differs);
}

TEST_CASE("kinema problems writes the set into a directory, twice the same bytes; a bad file writes nothing") {
  const std::string one = kinema_test::fresh_directory("problems_one"), two = kinema_test::fresh_directory("problems_two");
  for (const std::string& directory : {one, two}) {
    const auto result = kinema_test::run_kinema({"problems", kinema_test::sample("problem_4_4_set.toml"), "--count", "2",
                                                 "--seed", "7", "-o", directory + "/set"});
    REQUIRE(result.exit_status == 0);
    CHECK(result.err.find("wrote 2 variants") != std::string::npos);
  }
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(one + "/set")) names.push_back(entry.path().filename().string());
  CHECK(names.size() == 2 * 2 + 5);  // sheets, keys, four tables, the mechanism file
  for (const std::string& name : names) {
    CAPTURE(name);
    CHECK(kinema_test::read_file(one + "/set/" + name) == kinema_test::read_file(two + "/set/" + name));
  }
  CHECK(kinema_test::read_file(one + "/set/problem_4_4_set.toml") ==
        kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml")));
  const nlohmann::json table = nlohmann::json::parse(kinema_test::read_file(one + "/set/class.json"));
  CHECK(table["source"] == "problem_4_4_set.toml");
  CHECK(table["seed"] == 7);
  CHECK(table["count"] == 2);
  CHECK(table["tolerance"]["relative"] == 0.01);
  CHECK(table["variants"][1]["variant"] == 2);
  CHECK(table["variants"][0]["parameters"]["BC"]["unit"] == "m");
  CHECK(table["variants"][0]["answers"][0]["quantity"] == "omega3");
  CHECK(table["variants"][0]["answers"][0]["at"] == "30 deg");
  CHECK(table["variants"][0]["answers"][0]["at_si"].get<double>() == doctest::Approx(M_PI / 6).epsilon(1e-15));

  // Draws refused are reported per condition (the four-bar's ranges hold non-crank-rockers).
  const std::string four_bar = kinema_test::write_temporary("four_bar_problem.toml", four_bar_problem_text());
  const auto redrawn = kinema_test::run_kinema({"problems", four_bar, "--count", "2", "--seed", "7", "-o", one + "/four_bar"});
  REQUIRE(redrawn.exit_status == 0);
  CAPTURE(redrawn.err);
  CHECK(redrawn.err.find(" redrawn; failed conditions: ") != std::string::npos);
  CHECK(redrawn.err.find("grashof ") != std::string::npos);

  // No [problem]: refused, nothing made.
  const std::string bad = kinema_test::fresh_directory("problems_bad") + "/set";
  const auto refused = kinema_test::run_kinema({"problems", kinema_test::sample("four_bar.toml"), "-o", bad});
  CHECK(refused.exit_status != 0);
  CHECK(refused.err.find("no [problem] table") != std::string::npos);
  CHECK(!std::filesystem::exists(bad));
}

TEST_CASE("problems: the Moodle XML is well formed and carries every answer with its tolerance") {
  const Loaded loaded = load(four_bar_problem_text(), "four_bar_problem.toml");
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 3, 5);
  // A title with XML's special characters, escaped.
  const kinema_test::XmlElement quiz = kinema_test::parse_xml(problem_moodle_xml(set, "Four-bar <A & B> \"quoted\""));
  CHECK(quiz.name == "quiz");
  CHECK(quiz.children.front().child("category").child("text").text == "$course$/kinema/Four-bar <A & B> \"quoted\"");
  std::size_t question = 1;  // after the category
  for (const ProblemVariant& variant : set.variants) {
    for (const ProblemAnswer& answer : variant.answers) {
      REQUIRE(question < quiz.children.size());
      const kinema_test::XmlElement& q = quiz.children[question++];
      CHECK(q.attributes.at("type") == "numerical");
      CHECK(q.child("name").child("text").text.find("Variant " + std::to_string(variant.number) + ": " + answer.quantity) == 0);
      const kinema_test::XmlElement& a = q.child("answer");
      CHECK(a.attributes.at("fraction") == "100");
      CHECK(std::stod(a.child("text").text) == answer.value);
      // Three significant figures: half a unit of the third.
      const double tolerance = std::stod(a.child("tolerance").text);
      CHECK(tolerance == doctest::Approx(0.5 * std::pow(10.0, std::floor(std::log10(std::fabs(answer.value))) - 2)));
    }
  }
  CHECK(question == quiz.children.size());
  CHECK_THROWS(kinema_test::parse_xml("<quiz><a></quiz>"));
  CHECK_THROWS(kinema_test::parse_xml("<quiz>&</quiz>"));
}

TEST_CASE("problems: the sample set's Moodle questions give each varied value with the sheet's digits") {
  const std::string text = kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml"));
  const Loaded loaded = load(text, "problem_4_4_set.toml");
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 4, 7);
  const kinema_test::XmlElement quiz = kinema_test::parse_xml(problem_moodle_xml(set, "t"));
  std::size_t question = 1, grid_digits_differ = 0;  // after the category
  for (const ProblemVariant& variant : set.variants) {
    const std::string sheet = problem_sheet(set, variant);
    for (std::size_t k = 0; k < variant.answers.size(); ++k) {
      REQUIRE(question < quiz.children.size());
      const std::string asked = quiz.children[question++].child("questiontext").child("text").text;
      CAPTURE(asked);
      for (const GivenValue& g : variant.given) {
        // "BC = 0.380 m" in the question, "$0.380\\,\\mathrm{m}$" on the sheet: the same digits.
        const std::string before = g.name + " = ", after = " " + g.unit;
        const std::size_t at = asked.find(before);
        REQUIRE(at != std::string::npos);
        const std::size_t first = at + before.size();
        const std::string number = asked.substr(first, asked.find(after, first) - first);
        CHECK(number == format_fixed(g.value, g.decimals));
        CHECK(sheet.find("$" + number + "\\,\\mathrm{" + g.unit + "}$") != std::string::npos);
        grid_digits_differ += k == 0 && number != format_significant(g.value, 12);
      }
    }
  }
  CHECK(question == quiz.children.size());
  CHECK(grid_digits_differ > 0);  // some value (0.380 m) whose shortest digits (0.38) would differ
}

TEST_CASE("problems: a variant's sheet and key compile with pdflatex, no overfull line; the sheet has no answer") {
  const std::string text = kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml"));
  const Loaded loaded = load(text, "problem_4_4_set.toml");
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 1, 7);
  const ProblemVariant& variant = set.variants.front();
  const std::string sheet = problem_sheet(set, variant), key = problem_key(variant);
  for (const ProblemAnswer& answer : variant.answers) {
    const std::string boxed = "\\boxed{" + latex_number(answer.value, 6) + "}";
    CHECK(key.find(boxed) != std::string::npos);
    CHECK(sheet.find(latex_number(answer.value, 6)) == std::string::npos);
  }
  CHECK(sheet.find("\\boxed") == std::string::npos);
  CHECK(sheet.find("velocity vectors") == std::string::npos);  // no arrow of an answer in the drawing
  // A varied length with its grid's digits (5 mm steps in m: 0.380, not 0.38 beside the file's 0.150).
  for (const GivenValue& g : variant.given) {
    if (g.unit != "m") continue;
    CHECK(g.decimals == 3);
    CHECK(sheet.find("$" + format_fixed(g.value, 3) + "\\,\\mathrm{m}$") != std::string::npos);
  }
  for (const auto& [name, document] : {std::make_pair(std::string("problem_sheet"), sheet), std::make_pair(std::string("problem_key"), key)}) {
    CAPTURE(name);
    std::string log;
    const int pages = kinema_test::compile_document(document, name, log);
    CHECK(pages > 0);
    // The sheet a class is handed: statement, data and drawing on one page.
    if (name == "problem_sheet") CHECK(pages == 1);
    // Issue 49: the key leads with its boxed answers (they were on page 8 of 9).
    if (name == "problem_key") {
      const std::string pdf = (kinema_test::scratch_directory() / "latex" / "problem_key.pdf").string();
      const std::string first_page = kinema_test::run_shell("pdftotext -f 1 -l 1 '" + pdf + "' -").out;
      CHECK(first_page.find("Answers") != std::string::npos);
      CHECK(first_page.find("The quantities the problem asks for") != std::string::npos);
      CHECK(key.find("\\subsection*{Answers}") < key.find("\\begin{tikzpicture}"));
    }
    for (const kinema_test::Overfull& box : kinema_test::overfull_boxes(log)) {
      INFO(box.text);
      CHECK(box.points <= 1);
    }
  }
}

// Issue 49: a sheet gives every datum as a value with its unit: EF = CE and Lc = CD were
// given as those names, and the crank's angular acceleration as a bare 0.
TEST_CASE("problems: the sheet gives a parameter written as a formula, and the driver's second rate, as values with units") {
  const std::string text = kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml"));
  const Loaded loaded = load(text, "problem_4_4_set.toml");
  const ProblemSet set = make_problem_set(loaded.model, *loaded.mechanism.problem, 3, 7);
  for (const ProblemVariant& variant : set.variants) {
    const std::string sheet = problem_sheet(set, variant);
    double cd = 0;
    for (const GivenValue& g : variant.given)
      if (g.name == "CD") cd = g.si;
    REQUIRE(cd > 0);
    CAPTURE(cd);
    CHECK(sheet.find("$\\mathit{EF}$ & $0.23\\,\\mathrm{m}$") != std::string::npos);  // EF = CE, not varied
    CHECK(sheet.find("$L_{c}$ & $" + format_significant(cd, 6) + "\\,\\mathrm{m}$") != std::string::npos);  // Lc = CD, this variant's
    CHECK(sheet.find("\\mathit{CE}$ \\\\") == std::string::npos);
    CHECK(sheet.find("$\\alpha_{1}$ & $0\\,\\mathrm{rad/s^{2}}$") != std::string::npos);
    // Every dimension labelled on the figure, every pivot lettered.
    for (const char* label : {"{$L_{a}$}", "{$L_{b}$}", "{$L_{c}$}", "{A}", "{D}"}) CHECK(sheet.find(label) != std::string::npos);
  }
}

TEST_CASE("problems: a bad [problem] is refused at its line, saying what to write") {
  const std::string base = four_bar_problem_text();
  const auto refused = [&](const std::string& from, const std::string& to, const std::string& message) {
    CAPTURE(to);
    const std::string text = kinema_test::replaced(from, to, base);
    std::string error;
    try {
      const Loaded loaded = load(text, "bad.toml");
      make_problem_set(loaded.model, *loaded.mechanism.problem, 2, 1);
    } catch (const InputError& e) {
      error = e.what();
    }
    CAPTURE(error);
    CHECK(error.find("bad.toml:") == 0);
    CHECK(error.find(message) != std::string::npos);
  };
  refused("find = [\"omega3\", \"alpha4\", \"vP\"]", "find = [\"omega3\", \"omega9\"]",
          "no quantity \"omega9\" in this mechanism; the names are: theta2, omega2");
  refused("range = [\"30 mm\", \"70 mm\"]", "range = [\"70 mm\", \"30 mm\"]", "the range must go from the lower value");
  refused("range = [\"30 mm\", \"70 mm\"]", "range = [\"30 mm\", \"70 deg\"]", "must be of one kind");
  refused("step = \"2 mm\"", "step = \"0 mm\"", "the step must be positive");
  refused("a = { range", "zz = { range", "[problem] vary.zz");
  refused("a = { range", "delta = { range", "is a length, but \"delta\" is an angle");
  refused("toggle_margin = \"5 deg\"", "toggle_distance = \"5 deg\"", "unknown key \"toggle_distance\" in [problem.conditions]");
  refused("grashof = \"crank-rocker\"", "grashof = \"crank rocker\"", "is not a Grashof class");
  refused("sig_figs = 3", "tolerance = \"one percent\"", "not a relative tolerance");
  refused("sig_figs = 3", "sig_figs = 3\ntolerance = \"1%\"", "give one of them");
  refused("at = [\"40 deg\", \"200 deg\"]", "at = [\"40 mm\"]", "[problem] at = \"40 mm\"");
  refused("toggle_margin = \"5 deg\"", "toggle_margin = \"5 mm\"", "an angle is needed here");
  // Conditions no variant can meet: refused with how many draws each condition refused.
  refused("min_answer = 0.2", "min_answer = 1e9", "variants met the conditions in");
  // A condition the mechanism has no figure for.
  const std::string six_bar = kinema_test::read_file(kinema_test::sample("problem_4_4_set.toml"));
  std::string error;
  try {
    const Loaded loaded = load(kinema_test::replaced("min_answer = 0.05", "min_answer = 0.05\ngrashof = \"crank-rocker\"", six_bar), "six.toml");
    make_problem_set(loaded.model, *loaded.mechanism.problem, 1, 1);
  } catch (const InputError& e) {
    error = e.what();
  }
  CHECK(error.find("six.toml:") == 0);
  CHECK(error.find("grashof is for a four-bar") != std::string::npos);
}
