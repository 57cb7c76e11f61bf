// engine/printers/latex: numbers shown to people in the worked solution (issue 32):
// round-off prints as 0, given data as the file gave it (not a machine's
// representation), formulas typeset rather than ASCII, the Coriolis sentence with its
// signs combined, and a spatial chain's substitution in one unit, so that each printed
// line evaluates to the value it states (read back and evaluated here).
#include <doctest/doctest.h>

#include <cctype>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/base/errors.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/symbolic/dyad_method.hpp"
#include "engine/printers/printer.hpp"
#include "tests/test_support.hpp"

using kinema::MotionTable;
using kinema::PrintKind;

namespace {

std::string print(PrintKind kind, const kinema::Model& model, const MotionTable* values) {
  const kinema::Printer* printer = kinema::find_printer(kind, "latex");
  REQUIRE(printer != nullptr);
  kinema::PrintJob job{model, values, nullptr};
  std::ostringstream out;
  kinema::print_view(*printer, out, job);
  return out.str();
}

// The worked solution of a sample at the file's own input values, as `kinema latex` writes it.
std::string worked_solution(const std::string& sample) {
  const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
  const MotionTable values = kinema::solve_motion(model, model.system.input.values);
  return print(PrintKind::document, model, &values);
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The text between `from` and the next `to` after it (empty when `from` is missing).
std::string between(const std::string& text, const std::string& from, const std::string& to) {
  const auto a = text.find(from);
  if (a == std::string::npos) return "";
  const auto b = text.find(to, a + from.size());
  return text.substr(a, b == std::string::npos ? std::string::npos : b - a);
}

// Text mode only: comments, displayed math, drawings and $...$ taken out.
std::string prose(const std::string& tex) {
  std::string t = std::regex_replace(tex, std::regex(R"((^|[^\\])%[^\n]*)"), "$1");
  for (const char* env : {"align\\*", "tikzpicture", "axis"})
    t = std::regex_replace(t, std::regex(std::string("\\\\begin\\{") + env + "\\}[\\s\\S]*?\\\\end\\{" + env + "\\}"), "");
  return std::regex_replace(t, std::regex(R"(\$[^$]*\$)"), "");
}

// A substituted line read back: numbers, + - and / (\bigm/), juxtaposition as a product,
// ( ) \bigl( \bigr) \left( \right) { }, \frac{}{}, \sin \cos, ^{\circ} and powers.
class LineValue {
 public:
  explicit LineValue(std::string text) : s_(std::move(text)) {}
  double value() {
    const double v = sum();
    skip();
    if (i_ != s_.size()) FAIL("unread: " << s_.substr(i_));
    return v;
  }

 private:
  std::string s_;
  std::size_t i_ = 0;

  void skip() {
    for (;;) {
      while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
      if (!eat_word("\\,") && !eat_word("\\quad") && !eat_word("&")) return;
    }
  }
  bool eat_word(const std::string& w) {
    if (s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  bool eat(const std::string& w) {
    skip();
    return eat_word(w);
  }
  double sum() {
    double v = 0;
    bool first = true;
    for (;;) {
      double sign = 1;
      if (eat("-")) sign = -1;
      else if (!first && !eat("+")) return v;
      v += sign * product();
      first = false;
    }
  }
  bool starts_factor() {
    skip();
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '(' || c == '{') return true;
    for (const char* w : {"\\bigl(", "\\left(", "\\frac", "\\sin", "\\cos"})
      if (s_.compare(i_, std::string(w).size(), w) == 0) return true;
    return false;
  }
  double product() {
    double v = power();
    for (;;) {
      if (eat("\\bigm/") || eat("/")) v /= power();
      else if (eat("\\cdot")) v *= power();
      else if (starts_factor()) v *= power();
      else return v;
    }
  }
  double power() {
    double v = primary();
    while (eat("^{")) {
      if (eat("\\circ}")) {
        v *= M_PI / 180;
        continue;
      }
      const double e = sum();
      REQUIRE(eat("}"));
      v = std::pow(v, e);
    }
    return v;
  }
  double primary() {
    skip();
    if (eat("\\bigl(")) return closed("\\bigr)");
    if (eat("\\left(")) return closed("\\right)");
    if (eat("(")) return closed(")");
    if (eat("{")) return closed("}");
    if (eat("\\frac{")) {
      const double top = closed("}");
      REQUIRE(eat("{"));
      return top / closed("}");
    }
    if (eat("\\sin")) return std::sin(power());
    if (eat("\\cos")) return std::cos(power());
    std::size_t used = 0;
    const double v = std::stod(s_.substr(i_), &used);
    i_ += used;
    return v;
  }
  double closed(const std::string& end) {
    const double v = sum();
    if (!eat(end)) FAIL("expected " << end << " at: " << s_.substr(i_));
    return v;
  }
};

struct Substituted {
  std::string lhs, rhs;  // rhs: the numbers put in, over one line
  double stated = 0;     // the value after the last " = "
};

// The rows of a document's "Numeric substitution" align*, one formula each.
std::vector<Substituted> substitutions(const std::string& tex) {
  const std::string body = between(between(tex, "Numeric substitution", "\\end{align*}"), "\\begin{align*}", "\\end{align*}");
  std::vector<Substituted> out;
  std::istringstream rows(body.substr(std::string("\\begin{align*}").size()));
  std::string row;
  while (std::getline(rows, row)) {
    row = std::regex_replace(row, std::regex(R"(\s*\\\\\s*$)"), "");
    if (row.find_first_not_of(' ') == std::string::npos) continue;
    const auto eq = row.find("&=");
    if (eq != std::string::npos && row.find_first_not_of(' ') != row.find('&')) {
      out.push_back({row.substr(0, eq), row.substr(eq + 2)});
    } else {
      REQUIRE(!out.empty());
      out.back().rhs += " " + row;
    }
  }
  for (Substituted& s : out) {
    const std::smatch m = [&] {
      std::smatch match;
      REQUIRE(std::regex_search(s.rhs, match, std::regex(R"(=\s*([-0-9.]+(\\cdot 10\^\{-?[0-9]+\})?)\\,\\mathrm\{[^}]*\}\s*$)")));
      return match;
    }();
    std::string number = m[1];
    s.stated = LineValue(number).value();
    s.rhs = s.rhs.substr(0, static_cast<std::size_t>(m.position(0)));
  }
  return out;
}

}  // namespace

TEST_CASE("engine/printers/latex: round-off prints as 0 at the problem's scale") {
  // The parallelogram at phi = 30 deg: theta2 is -6.6e-15 deg, omega2 2.5e-15 rad/s
  // by round-off; Problem 4.4's slider F5 moved 1.0e-16 m/s across.
  const std::string parallelogram = worked_solution("problem_4_1_parallelogram.toml");
  const std::string results = between(parallelogram, "\\subsection*{Results", "\\begin{tikzpicture}");
  REQUIRE(has(results, "Numeric substitution"));
  CHECK(!has(results, "10^{-1"));
  CHECK(has(results, "$\\theta_{2}$ & $0^{\\circ}$"));
  CHECK(has(results, "\\sin(0^{\\circ} - 30^{\\circ})"));
  const std::string joints = worked_solution("problem_4_4_joints.toml");
  const std::string sliders = between(joints, "relative velocity $\\mathbf{v}^r$", "\\end{tabular}");
  REQUIRE(has(sliders, "F5"));
  CHECK(!has(sliders, "10^{-"));
  CHECK(has(sliders, "F5 & $(0,\\ "));

  // The rule itself: 1e-12 of the mechanism's size for the kind of quantity.
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_1_parallelogram.toml"));
  const kinema::DocumentNumbers numbers(model.system);  // 0.09 m, 120 rpm
  CHECK(numbers(2.46716e-15, kinema::Dimension::angle, 1) == "0");
  CHECK(numbers(-2.22045e-13, kinema::Dimension::angle, 2) == "0");
  CHECK(numbers(1.00804e-16, kinema::Dimension::length, 1) == "0");
  CHECK(numbers(1e-9, kinema::Dimension::angle, 1) == "1\\cdot 10^{-9}");  // small, but no round-off
  CHECK(numbers(1e-16, kinema::Dimension::number, 0) == "1\\cdot 10^{-16}");  // a ratio has no scale
}

TEST_CASE("engine/printers/latex: no round-off anywhere in a worked solution, every sample and method") {
  // The parallelogram's polygon table printed BC omega2 = 2.22045e-16 m/s and its instant
  // centres' ratio omega2/omega1 = 1.96331e-16: no number stated in the document (comments,
  // which carry the solver's formulas, aside) has an exponent below -12.
  const std::regex noise(R"(10\^\{-(1[3-9]|[2-9][0-9]|[0-9]{3,})\}|[0-9]e-(1[3-9]|[2-9][0-9]|[0-9]{3,}))");
  for (const std::string sample : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const MotionTable values = kinema::solve_motion(model, model.system.input.values);
    for (kinema::DerivationMethod method : {kinema::DerivationMethod::loops, kinema::DerivationMethod::relative_velocity,
                                            kinema::DerivationMethod::joint_coordinates}) {
      if (method != kinema::DerivationMethod::loops) {
        try {
          kinema::check_method_applies(model.system, method);
        } catch (const kinema::InputError&) {
          continue;
        }
      }
      CAPTURE(sample);
      CAPTURE(kinema::method_name(method));
      kinema::PrintJob job{model, &values, nullptr};
      job.method = method;
      std::ostringstream out;
      kinema::print_view(*kinema::find_printer(PrintKind::document, "latex"), out, job);
      const std::string text = std::regex_replace(out.str(), std::regex(R"((^|[^\\])%[^\n]*)"), "$1");
      std::smatch found;
      if (std::regex_search(text, found, noise)) {
        const auto at = static_cast<std::size_t>(found.position(0));
        const auto from = text.rfind('\n', at);
        FAIL_CHECK("round-off stated: " << text.substr(from + 1, text.find('\n', at) - from - 1));
      }
    }
  }
}

TEST_CASE("engine/printers/latex: the parallelogram's polygon, centres and three methods state 0 for link 2") {
  const std::string tex = worked_solution("problem_4_1_parallelogram.toml");
  CHECK(has(tex, "$\\mathit{BC} \\omega_{2} = 0$"));
  CHECK(has(tex, "\\overline{I_{02}I_{12}}$ & $0$ & $0$"));
  CHECK(has(tex, "\n2 & $0$ & "));
}

TEST_CASE("engine/printers/latex: given data as the file gave it, never a machine representation") {
  // The triple rocker's x_D, r_2P and beta_2P are worked out from the joints (60 mm, ...):
  // in mm as the document, to its digits.
  const std::string rocker = worked_solution("triple_rocker_circuit.toml");
  const std::string data = between(rocker, "\\subsection*{Data}", "\\end{tabular}");
  CHECK(has(data, "$\\mathit{AB}$ & $50\\,\\mathrm{mm}$"));
  CHECK(has(data, "$x_{\\mathrm{D}}$ & $60\\,\\mathrm{mm}$"));
  CHECK(has(data, "$\\beta_{\\mathrm{2 P}}$ & $35.5377^{\\circ}$"));
  CHECK(!std::regex_search(data, std::regex("[0-9]{10}")));
  const std::string arm = between(worked_solution("robot_arm_slider.toml"), "\\subsection*{Data}", "\\end{tabular}");
  CHECK(has(arm, "$s_{\\mathrm{0}}$ & $0.1\\,\\mathrm{m}$"));
  CHECK(!std::regex_search(arm, std::regex("[0-9]{10}")));
  // The chain's values at the instant, written without unit by the front end, with theirs.
  CHECK(has(arm, "$\\theta_{1,\\mathrm{0}}$ & $0^{\\circ}$"));
  CHECK(has(arm, "$\\omega_{1,\\mathrm{0}}$ & $1\\,\\mathrm{rad/s}$"));
  CHECK(has(arm, "$v_{\\mathrm{s 0}}$ & $0.5\\,\\mathrm{m/s}$"));
  // A driver at 60 rpm is stated so, and in rad/s.
  const std::string six_bar = worked_solution("problem_4_4_joints.toml");
  CHECK(has(six_bar, "\\omega_{1} = 60\\,\\mathrm{rpm} = 6.283\\,\\mathrm{rad/s}"));
  // The document states the digits of its results.
  CHECK(has(six_bar, "Results to six significant digits"));
}

TEST_CASE("engine/printers/latex: no ASCII formula where the document typesets") {
  // Design figures were "phi = 0.0000 deg (-0.0344774 m)" in text mode.
  for (const std::string sample : kinema_test::kSamples) {
    CAPTURE(sample);
    const std::string text = prose(worked_solution(sample));
    CHECK(!std::regex_search(text, std::regex(R"(\bdeg\b|_dot|\*[^{]|[a-z]+ = [-0-9])")));
  }
  const std::string shaper = worked_solution("crank_shaper.toml");
  CHECK(has(shaper, "Slider: $s$ at its limits at $\\theta_{2} = 90^{\\circ}$ ($400\\,\\mathrm{mm}$)"));
  // Gruebler's count of Example 4.2 (six bodies with ground, seven joints).
  const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_2_joints.toml"));
  const std::string derivation = print(PrintKind::derivation, model, nullptr);
  CHECK(has(derivation, "3\\cdot 5 - 2\\cdot 7 = 1"));
  CHECK(!has(derivation, "3*5"));
}

TEST_CASE("engine/printers/latex: the Coriolis sentence has its signs combined") {
  // Example 4.2: C slides along link 3 at -CB e^{i phi3}.
  const std::string tex = worked_solution("example_4_2_r_rtr_rrt.toml");
  const std::string sentence = between(tex, "slides along a turning link", "\n");
  REQUIRE(!sentence.empty());
  CHECK(has(sentence, "the Coriolis term $-2 \\dot{\\mathit{CB}} \\omega_{3}\\,i\\,e^{i\\phi_{3}}$"));
  CHECK(has(sentence, "$\\mathit{CB} \\omega_{3}^{2}\\,e^{i\\phi_{3}}$"));
  CHECK(!has(sentence, "2\\,-"));
  CHECK(!has(sentence, "$--"));
  CHECK(!has(sentence, "$-\\,-"));
}

TEST_CASE("engine/printers/latex: each substituted line evaluates to the value it states") {
  // The RSSR's formulas carry its offsets as numbers in metres: its lengths were put
  // in in mm (the line evaluated to 0.000824 where it stated -0.212265).
  for (const std::string sample : kinema_test::kSamples) {
    CAPTURE(sample);
    const std::string tex = worked_solution(sample);
    if (!has(tex, "Numeric substitution")) continue;  // a chain driven in time: worked out at the instant
    const std::vector<Substituted> lines = substitutions(tex);
    REQUIRE(!lines.empty());
    for (const Substituted& line : lines) {
      CAPTURE(line.lhs);
      CAPTURE(line.rhs);
      const double value = LineValue(line.rhs).value();
      // Five digits put in: the line agrees with the value to about 1e-4.
      CHECK(std::fabs(value - line.stated) <= 2e-3 * std::fabs(line.stated) + 1e-9);
    }
  }
  // The closure says what it is, and has no empty equation.
  const std::string rssr = worked_solution("rssr_spatial_four_bar.toml");
  CHECK(has(rssr, "\\subsection*{Closure of the spatial chain}"));
  CHECK(has(rssr, "distance"));
  CHECK(!has(rssr, "real and imaginary parts"));
  CHECK(!std::regex_search(rssr, std::regex(R"(&\s*= 0)")));
  // derive --format latex the same: the closure's name on its equation.
  const kinema::Model model = kinema::load_model(kinema_test::sample("rssr_spatial_four_bar.toml"));
  const std::string derivation = print(PrintKind::derivation, model, nullptr);
  CHECK(!std::regex_search(derivation, std::regex(R"(&\s*= 0)")));
  CHECK(has(derivation, "\\text{BC:}\\quad & \\frac{"));
}

TEST_CASE("engine/printers/latex: the driver's rate as the file wrote it, and its SI value") {
  // Only a round number of rpm showed as rpm (60 rpm = 6.283 rad/s); 90 deg/s showed as
  // "15 rpm = 1.571 rad/s" and 12.3456 rpm as 1.29284 rad/s alone.
  const auto document_of = [](const std::string& name, const std::string& text) {
    const kinema::Model model = kinema::load_model(kinema_test::write_temporary(name, text));
    const MotionTable values = kinema::solve_motion(model, model.system.input.values);
    return std::make_pair(model.system.input.rate_text, print(PrintKind::document, model, &values));
  };
  const auto [degrees_text, degrees] =
      document_of("rate_in_deg_per_s.toml", kinema_test::replaced("rate = \"10 rad/s\"", "rate = \"90 deg/s\""));
  CHECK(degrees_text == "90 deg/s");
  CHECK(has(degrees, "= 90\\,\\mathrm{deg/s} = 1.571\\,\\mathrm{rad/s}"));
  CHECK(!has(degrees, "rpm"));
  // The joints-and-links front end carries it too, and `kinema loops` writes it as written.
  const std::string joints = kinema_test::replaced(
      "rate = \"60 rpm\"", "rate = \"12.3456 rpm\"", kinema_test::read_file(kinema_test::sample("problem_4_4_joints.toml")));
  const auto [rpm_text, rpm] = document_of("rate_in_rpm.toml", joints);
  CHECK(rpm_text == "12.3456 rpm");
  CHECK(has(rpm, "\\omega_{1} = 12.3456\\,\\mathrm{rpm} = 1.293\\,\\mathrm{rad/s}"));
  const auto loops = kinema_test::run_kinema({"loops", kinema_test::write_temporary("rate_in_rpm.toml", joints)});
  REQUIRE(loops.exit_status == 0);
  CHECK(has(loops.out, "rate = \"12.3456 rpm\""));
  // Written in the document's unit: once (10 rad/s, not 10 rad/s = 10 rad/s).
  const std::string four_bar = worked_solution("four_bar.toml");
  CHECK(has(four_bar, "= 10\\,\\mathrm{rad/s}$"));
  CHECK(!has(four_bar, "\\mathrm{rad/s} = 10"));
}

// A negative angle put in for a cosine's symbol is in parentheses once: the slider-crank's
// substitution read \cos((-12.827^\circ)), and Problem 3.22's \sin((-120^\circ)).
TEST_CASE("engine/printers/latex: a substituted negative angle in one pair of parentheses") {
  const std::regex doubled(R"(\\(sin|cos|tan)\(\([^()]*\)\))");
  for (const char* sample : {"slider_crank.toml", "problem_3_22_joints.toml", "piston_driven_crank.toml"}) {
    CAPTURE(std::string(sample));
    const std::string tex = worked_solution(sample);
    const std::string substitution = between(tex, "Numeric substitution", "\\end{align*}");
    REQUIRE(has(substitution, "(-"));  // it has negative numbers put in
    std::smatch match;
    const bool found = std::regex_search(substitution, match, doubled);
    CAPTURE(found ? match.str() : std::string());
    CHECK_FALSE(found);
    CHECK(std::regex_search(substitution, std::regex(R"(\\(sin|cos)\(-[0-9.]+\^\{?\\circ)")));  // still in parentheses
  }
}
