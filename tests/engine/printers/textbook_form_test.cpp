// Formulas as a textbook prints them (issue 13): loop terms in the order written,
// products as numbers, lengths, rates, functions; differences inside sin and cos with the
// positive term first; the four-bar's solved rates in Norton's form. These are about how
// a formula is printed, so they compare strings; the meaning is checked by reading the
// text back.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "engine/model.hpp"
#include "engine/printers/textbook_form.hpp"
#include "engine/constraints/expression_parts.hpp"

#include "tests/test_support.hpp"

namespace {

using GiNaC::ex;
using Style = kinema::TextbookForm::Style;

// The line of `text` that starts with `start` (the test fails if there is none).
std::string line_starting(const std::string& text, const std::string& start) {
  const auto at = text.find("\n" + start);
  REQUIRE_MESSAGE(at != std::string::npos, start);
  return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

GiNaC::symtab symbols(const kinema::ConstraintSystem& s) {
  GiNaC::symtab table;
  for (const auto& p : s.parameters) table[p.symbol.get_name()] = p.symbol;
  for (const kinema::Coordinate* q : {static_cast<const kinema::Coordinate*>(&s.input)}) {
    table[q->symbol.get_name()] = q->symbol;
    table[q->rate.get_name()] = q->rate;
    table[q->second_rate.get_name()] = q->second_rate;
  }
  for (const auto& q : s.unknowns)
    for (const GiNaC::realsymbol& x : {q.symbol, q.rate, q.second_rate}) table[x.get_name()] = x;
  return table;
}

}  // namespace

TEST_CASE("textbook form: the four-bar's solved rates read as Norton prints them, and mean the engine's") {
  const auto derive = kinema_test::run_kinema({"derive", kinema_test::sample("four_bar.toml")});
  REQUIRE(derive.exit_status == 0);
  CHECK(line_starting(derive.out, "    omega3 = ") == "    omega3 = a*omega2*sin(theta4 - theta2)/(b*sin(theta3 - theta4))");
  CHECK(line_starting(derive.out, "    omega4 = ") == "    omega4 = a*omega2*sin(theta2 - theta3)/(c*sin(theta4 - theta3))");
  CHECK(line_starting(derive.out, "    x:  ") == "    x:  a*cos(theta2) + b*cos(theta3) - c*cos(theta4) - d = 0");
  CHECK(line_starting(derive.out, "  ABCD.x:  [") == "  ABCD.x:  [ -b*sin(theta3),  c*sin(theta4) ]");
  CHECK(derive.out.find("sin(-") == std::string::npos);
  // The text reads back as the engine's formula.
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  GiNaC::parser read(symbols(model.system), true);
  for (std::size_t j = 0; j < 2; ++j) {
    const std::string name = model.system.unknowns[j].rate.get_name();
    const std::string line = line_starting(derive.out, "    " + name + " = ");
    const ex printed = read(line.substr(line.find(" = ") + 3));
    const ex difference = printed - model.derivation.solved_rates[j];
    GiNaC::exmap at;
    int k = 1;
    for (const auto& [text, symbol] : symbols(model.system)) at[symbol] = 0.37 * k++;
    CHECK(std::fabs(GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(difference.subs(at))).to_double()) < 1e-12);
  }

  // LaTeX: \sin\theta_{3} for one symbol, parentheses for a difference, \frac for a quotient.
  const auto latex = kinema_test::run_kinema({"derive", "--format", "latex", kinema_test::sample("four_bar.toml")});
  REQUIRE(latex.exit_status == 0);
  CHECK(latex.out.find("  & a \\cos\\theta_{2} + b \\cos\\theta_{3} - c \\cos\\theta_{4} - d = 0 \\\\\n") != std::string::npos);
  CHECK(latex.out.find("\\omega_{3} &= \\frac{a \\omega_{2} \\sin(\\theta_{4} - \\theta_{2})}{b \\sin(\\theta_{3} - \\theta_{4})}") !=
        std::string::npos);
  CHECK(latex.out.find("\\sin(-") == std::string::npos);
}

TEST_CASE("textbook form: Problem 4.4's loop equations with their terms in the order the file writes them") {
  const auto derive = kinema_test::run_kinema({"derive", kinema_test::sample("problem_4_4_six_bar.toml")});
  REQUIRE(derive.exit_status == 0);
  const std::string& out = derive.out;
  CHECK(out.find("  loop ABCD:  AB*exp(I*phi) - BC*exp(I*phi2) + CD*exp(I*phi3) - (La + I*Lb) = 0\n"
                 "    x:  AB*cos(phi) - BC*cos(phi2) + CD*cos(phi3) - La = 0\n"
                 "    y:  AB*sin(phi) - BC*sin(phi2) + CD*sin(phi3) - Lb = 0\n") != std::string::npos);
  CHECK(out.find("    x:  La - (CD + CE)*cos(phi3) - EF*cos(phi4) + Lc = 0\n"
                 "    y:  Lb - (CD + CE)*sin(phi3) - EF*sin(phi4) - yF = 0\n") != std::string::npos);
}

TEST_CASE("textbook form: products, sums and arguments, one rule at a time") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::TextbookForm form(model.system);
  GiNaC::symtab s = symbols(model.system);
  GiNaC::parser read(s, true);
  const auto text = [&](const char* formula) { return form(read(formula), Style::text); };
  const auto latex = [&](const char* formula) { return form(read(formula), Style::latex); };
  CHECK(text("sin(theta4)*omega4*c") == "c*omega4*sin(theta4)");             // lengths, rates, functions
  CHECK(text("sin(-theta4 + theta3)") == "sin(theta3 - theta4)");            // positive term first
  CHECK(text("sin(theta4 - theta3)") == "-sin(theta3 - theta4)");            // the sign out of an odd function
  CHECK(text("cos(theta4 - theta3)") == "cos(theta3 - theta4)");             // cos is even
  CHECK(text("omega3^2*b*cos(theta3) - d + a*cos(theta2)") == "a*cos(theta2) + b*omega3^2*cos(theta3) - d");
  CHECK(text("2*a*b*omega2") == "2*a*b*omega2");
  CHECK(text("a/(2*b)") == "a/(2*b)");
  CHECK(latex("sin(theta3)^2*b") == "b \\sin^{2}\\theta_{3}");
  CHECK(latex("a*sin(theta2 + delta)") == "a \\sin(\\theta_{2} + \\delta)");
  CHECK(latex("a/b") == "\\frac{a}{b}");
}

TEST_CASE("course notes: a crank's plots run from 0 to 360 deg whatever the requested value") {
  const auto document = kinema_test::run_kinema({"latex", kinema_test::sample("four_bar.toml"), "--angle", "40"});
  REQUIRE(document.exit_status == 0);
  CHECK(document.out.find("xmin=0.00, xmax=360.00, xtick={0,90,180,270,360}") != std::string::npos);
  // The first plotted point is at the wrap (0 deg, from 360 deg past the file's 40 deg),
  // and no x beyond 360 is drawn.
  // (The first curve of the first axis: solid, its marks; the points' paths have none.)
  const auto curve = document.out.find("\\addplot+[thick, solid, ");
  REQUIRE(curve != std::string::npos);
  const auto first = document.out.find("] coordinates { (", curve);
  REQUIRE(first != std::string::npos);
  CHECK(document.out.substr(first + 16, 10) == "(0.000000,");
  CHECK(document.out.find("(400.000000,") == std::string::npos);
  CHECK(document.out.find(" (nan,nan)") != std::string::npos);  // where the two parts of the turn meet
}

TEST_CASE("engine/printers/textbook_form: sums nested in products a hundred deep print (each level's sign judged once)") {
  // A file may nest parentheses 100 deep (loops/formula_reader). Judging a sum's sign by
  // printing its first term would print each level twice: 2^100 times the innermost.
  const GiNaC::symbol a("a"), c("c");
  ex e = a;
  for (int k = 0; k < 100; ++k) e = (e - GiNaC::symbol("b" + std::to_string(k))) * c;
  const kinema::TextbookForm form;
  for (const Style style : {Style::text, Style::latex}) {
    const std::string text = form(e, style);
    CHECK(std::count(text.begin(), text.end(), '(') == 100);
    CHECK(text.find("b99") != std::string::npos);
  }
}

// Audit 2026-11-24: an angle named u, or given latex = "q", printed as \cosu (an undefined
// command); a name with a prime squared as x'^{2} (a double superscript).
TEST_CASE("textbook form: a name after \\sin, \\cos, \\tan and a primed name in a power typeset") {
  const kinema::TextbookForm form;
  const GiNaC::realsymbol u("u", "u"), q("theta3", "q"), primed("s", "s'"), theta("theta2", "\\theta_{2}");
  CHECK(form(GiNaC::cos(u), Style::latex) == "\\cos u");
  CHECK(form(GiNaC::sin(q), Style::latex) == "\\sin q");
  CHECK(form(GiNaC::tan(q), Style::latex) == "\\tan q");
  CHECK(form(GiNaC::pow(GiNaC::sin(u), 2), Style::latex) == "\\sin^{2} u");
  CHECK(form(GiNaC::cos(theta), Style::latex) == "\\cos\\theta_{2}");  // a command needs no space
  CHECK(form(GiNaC::pow(primed, 2), Style::latex) == "(s')^{2}");
  CHECK(form(GiNaC::pow(u, 2), Style::latex) == "u^{2}");
}
