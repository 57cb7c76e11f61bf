// engine/printers (derivation): the text and LaTeX printers of the symbolic
// derivation, through the library. What they print is read back with GiNaC's
// parser and compared with the model by meaning.
#include <doctest/doctest.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/printer.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using GiNaC::ex;
using kinema::PrintKind;
using kinema_unit::same_meaning;

namespace {

std::string print(const char* name, const kinema::Model& model) {
  const kinema::Printer* printer = kinema::find_printer(PrintKind::derivation, name);
  REQUIRE(printer != nullptr);
  std::ostringstream out;
  kinema::print_view(*printer, out, kinema::PrintJob{model});
  return out.str();
}

// Every symbol of the model by name, for GiNaC's parser.
GiNaC::symtab symbols(const kinema::ConstraintSystem& s) {
  GiNaC::symtab table;
  for (const auto& p : s.parameters) table[p.symbol.get_name()] = p.symbol;
  for (const GiNaC::realsymbol& x : {s.input.symbol, s.input.rate, s.input.second_rate}) table[x.get_name()] = x;
  for (const auto& q : s.unknowns)
    for (const GiNaC::realsymbol& x : {q.symbol, q.rate, q.second_rate}) table[x.get_name()] = x;
  return table;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// What follows `prefix` on the first line after line `from` that starts with it ("" if none).
std::string after(const std::vector<std::string>& lines, std::size_t from, const std::string& prefix,
                  std::size_t* found = nullptr) {
  for (std::size_t i = from; i < lines.size(); ++i) {
    if (lines[i].compare(0, prefix.size(), prefix) == 0) {
      if (found) *found = i;
      return lines[i].substr(prefix.size());
    }
  }
  return "";
}

std::string without_suffix(const std::string& text, const std::string& suffix) {
  REQUIRE(text.size() >= suffix.size());
  REQUIRE(text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0);
  return text.substr(0, text.size() - suffix.size());
}

}  // namespace

TEST_CASE("engine/printers/derivation: text: each loop's equations labelled, formulas read back equal") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"));
  const kinema::ConstraintSystem& s = model.system;
  const kinema::Derivation& d = model.derivation;
  const std::string text = print("text", model);
  CAPTURE(text);
  GiNaC::parser reader(symbols(s), true);
  const std::vector<std::string> lines = lines_of(text);

  CHECK(lines.at(0) == s.title);
  CHECK(text.find("unknowns: q = [phi2, phi3, phi4, yF]") != std::string::npos);
  CHECK(text.find("rates:    qd = [omega2, omega3, omega4, vF], qdd = [alpha2, alpha3, alpha4, aF]") !=
        std::string::npos);
  CHECK(text.find("input:    phi (rate omega1, second rate alpha1)") != std::string::npos);
  // The Jacobian's rows are named by loop and component.
  CHECK(text.find("Jacobian Phi_q (rows ABCD.x, ABCD.y, DEF.x, DEF.y; columns phi2, phi3, phi4, yF)") !=
        std::string::npos);

  // Each loop: its vector, then its x and y equations, read back equal to the system's.
  for (std::size_t k = 0; k < s.groups.size(); ++k) {
    const auto& group = s.groups[k];
    CAPTURE(group.name);
    std::size_t at = 0;
    const std::string vector = after(lines, 0, "  loop " + group.name + ":  ", &at);
    REQUIRE_FALSE(vector.empty());
    CHECK((reader(without_suffix(vector, " = 0")) - *group.vector).expand().is_zero());
    for (std::size_t c = 0; c < 2; ++c) {
      const std::size_t row = group.equations[c];
      const std::string equation = lines.at(at + 1 + c);
      const std::string prefix = "    " + s.equations[row].component + ":  ";
      REQUIRE(equation.compare(0, prefix.size(), prefix) == 0);
      CHECK((reader(without_suffix(equation.substr(prefix.size()), " = 0")) - s.equations[row].expression)
                .expand()
                .is_zero());
    }
    // The Jacobian's rows under their labels.
    for (std::size_t c = 0; c < 2; ++c) {
      const std::string label = group.name + "." + s.equations[group.equations[c]].component;
      const std::size_t jacobian = text.find("\n2. Jacobian");
      REQUIRE(jacobian != std::string::npos);
      CHECK(text.find("\n  " + label + ":  [ ", jacobian) != std::string::npos);
    }
  }

  // Solved rates, block by block, each read back equal to the derivation's.
  std::size_t solved = text.find("5. Solved rates");
  REQUIRE(solved != std::string::npos);
  CHECK(text.find("  from loop ABCD:", solved) != std::string::npos);
  CHECK(text.find("  from loop DEF:", solved) > text.find("  from loop ABCD:", solved));
  std::size_t start = 0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i] == "5. Solved rates (Cramer's rule, block by block)") start = i;
  REQUIRE(start > 0);
  for (std::size_t j = 0; j < s.unknowns.size(); ++j) {
    const auto& q = s.unknowns[j];
    CAPTURE(q.name);
    const std::string rate = after(lines, start, "    " + q.rate.get_name() + " = ");
    const std::string second = after(lines, start, "    " + q.second_rate.get_name() + " = ");
    REQUIRE_FALSE(rate.empty());
    REQUIRE_FALSE(second.empty());
    CHECK(same_meaning(reader(rate), d.solved_rates[j]));
    CHECK(same_meaning(reader(second), d.solved_second_rates[j]));
  }

  // Points: position and velocity components read back.
  std::size_t points = 0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i] == "6. Points") points = i;
  REQUIRE(points > 0);
  std::size_t at = 0;
  after(lines, points, "  E = ", &at);
  REQUIRE(at > points);
  CHECK((reader(after(lines, at, "    x   = ")) - s.points[2].position[0]).expand().is_zero());
  CHECK(same_meaning(reader(after(lines, at, "    vy  = ")), d.points[2].velocity[1]));
  CHECK(same_meaning(reader(after(lines, at, "    ax  = ")), d.points[2].acceleration[0]));
}

TEST_CASE("engine/printers/derivation: latex: link vectors as written, every % kinema: formula read back equal") {
  for (const char* sample : {"four_bar.toml", "problem_3_22_six_bar_sliders.toml"}) {
    CAPTURE(sample);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const kinema::ConstraintSystem& s = model.system;
    const std::string latex = print("latex", model);
    CAPTURE(latex);
    CHECK(latex.find("\\begin{align*}") != std::string::npos);
    CHECK(latex.find("\\end{align*}") != std::string::npos);
    CHECK(latex.find("\\documentclass") == std::string::npos);  // a block to paste, not a document

    std::map<std::string, ex> expected;
    std::map<std::string, std::string> typeset;  // the symbol as its row begins
    for (std::size_t j = 0; j < s.unknowns.size(); ++j) {
      const auto& q = s.unknowns[j];
      expected[q.rate.get_name()] = model.derivation.solved_rates[j];
      expected[q.second_rate.get_name()] = model.derivation.solved_second_rates[j];
      typeset[q.rate.get_name()] = kinema::to_latex(q.rate);
      typeset[q.second_rate.get_name()] = kinema::to_latex(q.second_rate);
    }
    GiNaC::parser reader(symbols(s), true);
    std::map<std::string, int> seen;
    for (const std::string& line : lines_of(latex)) {
      const auto at = line.find("% kinema: ");
      if (at == std::string::npos) continue;
      const std::string formula = line.substr(at + 10);
      const auto equals = formula.find(" = ");
      REQUIRE(equals != std::string::npos);
      const std::string name = formula.substr(0, equals);
      CAPTURE(name);
      REQUIRE(expected.count(name) == 1);
      CHECK(same_meaning(reader(formula.substr(equals + 3)), expected[name]));
      // The comment belongs to the row that typesets the same symbol.
      CHECK(line.find("  " + typeset[name] + " &= ") == 0);
      ++seen[name];
    }
    CHECK(seen.size() == 2 * s.unknowns.size());
    for (const auto& [name, count] : seen) CHECK(count == 1);
  }

  // The four-bar's loop as link vectors in the order written, and its x, y equations.
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const std::string latex = print("latex", model);
  CHECK(latex.find("\\text{ABCD:}\\quad & a\\,e^{i\\theta_{2}} + b\\,e^{i\\theta_{3}} - c\\,e^{i\\theta_{4}} - d = 0") !=
        std::string::npos);
  CHECK(latex.find("% loop ABCD") != std::string::npos);
  CHECK(latex.find("\\omega_{3} &= ") != std::string::npos);
  CHECK(latex.find("\\alpha_{4} &= ") != std::string::npos);
}

TEST_CASE("engine/printers/derivation: user text cannot break out of LaTeX comments or commands") {
  const std::string text = kinema_test::replaced(
      "title = \"four-bar\"", "title = \"50% \\\\input{evil}\\nnext line\"",
      kinema_test::replaced("ABCD = \"", "A_B = \""));
  const kinema::Model model = kinema_unit::model_from_text(text, "hostile.toml");
  const std::string latex = print("latex", model);
  CAPTURE(latex);
  CHECK(latex.find("\\input{evil}") == std::string::npos);
  CHECK(latex.find("\\textbackslash{}input\\{evil\\}") != std::string::npos);
  // The title's newline stays inside its comment line.
  CHECK(latex.find("\nnext line") == std::string::npos);
  CHECK(latex.find("\\text{A\\_B:}") != std::string::npos);
  // The text printer prints names as they are.
  CHECK(print("text", model).find("loop A_B:") != std::string::npos);
}
