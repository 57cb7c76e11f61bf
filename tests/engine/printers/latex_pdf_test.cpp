// LaTeX output: names typeset as a reader expects, formulas that are the
// engine's (parsed back from the machine-readable comments), user text
// escaped, and the block compiles with pdflatex.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/run/view.hpp"
#include "engine/base/errors.hpp"
#include "engine/model.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/printer.hpp"
#include "engine/symbolic/dyad_method.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/base/naming.hpp"
#include "engine/symbolic/trig_simplify.hpp"
#include "engine/printers/latex_pages.hpp"
#include "tests/test_support.hpp"

namespace {

using kinema_test::kSamples;  // every bundled sample

using kinema_test::read_file;
using kinema_test::compile_document;
using kinema_test::Overfull;
using kinema_test::overfull_boxes;
using kinema_test::methods_of;

// Compiles an align* block in a minimal document; returns the log on failure.
bool compiles(const std::string& block, const std::string& name, std::string& log) {
  const auto directory = kinema_test::scratch_directory() / "latex";
  std::filesystem::create_directories(directory);
  const std::string tex = (directory / (name + ".tex")).string();
  std::ofstream(tex) << "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n"
                     << block << "\\end{document}\n";
  const std::string command = "cd '" + directory.string() + "' && pdflatex -interaction=batchmode -halt-on-error '" +
                              name + ".tex' > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  log = read_file((directory / (name + ".log")).string());
  return status == 0 && std::filesystem::exists(directory / (name + ".pdf")) &&
         log.find("Undefined control sequence") == std::string::npos;
}

// Every "% kinema: name = formula" comment in a LaTeX output, parsed back, must equal
// the derivation's formula by meaning; returns how many there were.
std::size_t formulas_parse_back(const std::string& output, const std::string& sample) {
  const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
  const auto& d = model.derivation;
  const auto& system = model.system;
  GiNaC::symtab table;
  std::map<std::string, GiNaC::ex> expected;
  for (const auto& p : system.parameters) table[p.symbol.get_name()] = p.symbol;
  for (const GiNaC::realsymbol& s : {system.input.symbol, system.input.rate, system.input.second_rate})
    table[s.get_name()] = s;
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    const auto& q = system.unknowns[i];
    for (const GiNaC::realsymbol& s : {q.symbol, q.rate, q.second_rate}) table[s.get_name()] = s;
    expected[q.rate.get_name()] = d.solved_rates[i];
    expected[q.second_rate.get_name()] = d.solved_second_rates[i];
  }
  GiNaC::parser reader(table, true);
  std::istringstream lines(output);
  std::string line;
  std::size_t parsed = 0;
  while (std::getline(lines, line)) {
    const auto at = line.find("% kinema: ");
    if (at == std::string::npos) continue;
    const std::string formula = line.substr(at + 10);
    const auto equals = formula.find(" = ");
    const std::string symbol = formula.substr(0, equals);
    REQUIRE(expected.count(symbol) == 1);
    const GiNaC::ex difference = GiNaC::normal(reader(formula.substr(equals + 3)) - expected[symbol]);
    // Symbolically, or (a formula past the simplification budget: a spatial closure) at
    // three sets of arbitrary values of its symbols.
    bool zero = kinema::combine_trig_products(difference.numer()).is_zero();
    if (!zero) {
      std::vector<GiNaC::ex> names;
      for (auto it = difference.preorder_begin(); it != difference.preorder_end(); ++it)
        if (GiNaC::is_a<GiNaC::symbol>(*it)) names.push_back(*it);
      zero = true;
      for (int trial = 1; trial <= 3; ++trial) {
        GiNaC::exmap values;
        for (std::size_t i = 0; i < names.size(); ++i) values[names[i]] = 0.3 + 0.7 * std::sin(1.3 * trial + 2.1 * double(i));
        const GiNaC::ex v = GiNaC::evalf(difference.subs(values, GiNaC::subs_options::no_pattern));
        zero = zero && GiNaC::is_a<GiNaC::numeric>(v) && std::fabs(GiNaC::ex_to<GiNaC::numeric>(v).to_double()) < 1e-9;
      }
    }
    CHECK(zero);
    ++parsed;
  }
  return parsed;
}

}  // namespace

TEST_CASE("symbol names are typeset as a reader expects") {
  CHECK(kinema::latex_symbol_name("theta3") == "\\theta_{3}");
  CHECK(kinema::latex_symbol_name("omega2") == "\\omega_{2}");
  CHECK(kinema::latex_symbol_name("alpha") == "\\alpha");
  CHECK(kinema::latex_symbol_name("r2") == "r_{2}");
  CHECK(kinema::latex_symbol_name("r1_dot") == "\\dot{r}_{1}");
  CHECK(kinema::latex_symbol_name("r1_ddot") == "\\ddot{r}_{1}");
  CHECK(kinema::latex_symbol_name("xE") == "x_{E}");
  CHECK(kinema::latex_symbol_name("AB") == "\\mathit{AB}");
  CHECK(kinema::latex_symbol_name("theta2_given") == "\\theta_{2,\\mathrm{given}}");
}

// pdflatex's time grows with the square of an align*'s rows: a long one is written as
// several of kAlignBlockRows rows, each closed without an empty row; a short one stays whole.
TEST_CASE("a long align* is written as blocks of kAlignBlockRows rows, a short one whole") {
  const auto rows_of = [](std::size_t count) {
    std::vector<kinema::LatexRow> rows;
    for (std::size_t k = 0; k < count; ++k) rows.push_back({k % 3 == 0 ? "x_{" + std::to_string(k) + "} &= 1" : "&\\quad + 1", ""});
    return rows;
  };
  const auto count = [](const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
  };
  const std::string split = "\n\\end{align*}\n\\begin{align*}\n";
  const std::string whole = kinema::latex_align_rows(rows_of(kinema::kAlignBlockRows));
  CHECK(count(whole, split) == 0);
  CHECK(count(whole, " \\\\\n") == kinema::kAlignBlockRows - 1);
  const std::string blocks = kinema::latex_align_rows(rows_of(2 * kinema::kAlignBlockRows + 1));
  CHECK(count(blocks, split) == 2);
  CHECK(count(blocks, "\\\\" + split) == 0);  // no empty row at a block's end
  CHECK(count(blocks, " \\\\\n") == 2 * kinema::kAlignBlockRows + 1 - 3);  // every row ended but each block's last
}

TEST_CASE("user text is escaped and LaTeX names from files are checked") {
  CHECK(kinema::latex_escape_text("\\input{/etc/passwd} 100% & $x$ #1 a_b ^ ~") ==
        "\\textbackslash{}input\\{/etc/passwd\\} 100\\% \\& \\$x\\$ \\#1 a\\_b \\textasciicircum{} "
        "\\textasciitilde{}");
  CHECK_NOTHROW(kinema::check_latex_name("\\varphi_{2}", "here"));
  CHECK_NOTHROW(kinema::check_latex_name("\\dot{s}'", "here"));
  CHECK_THROWS_AS(kinema::check_latex_name("\\input{/etc/passwd}", "here"), kinema::InputError);
  CHECK_THROWS_AS(kinema::check_latex_name("x$y", "here"), kinema::InputError);
}

TEST_CASE("derive --format latex: the solved formulas are the engine's and the block compiles") {
  for (const char* sample : kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const auto result = kinema_test::run_kinema({"derive", "--format", "latex", kinema_test::sample(sample)});
    REQUIRE(result.exit_status == 0);
    CHECK(result.out.find("\\begin{align*}") != std::string::npos);
    // Phi_q as a matrix where it fits the page, else entry by entry.
    CHECK((result.out.find("\\begin{bmatrix}") != std::string::npos || result.out.find("(\\Phi_{q})_{11}") != std::string::npos));

    // A chain driven by its joints is worked out vector by vector at the instant (its
    // vectors tested in tests/loops/spatial_chain_test.cpp): no solved rates to read back.
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const bool chain = kinema::is_driven_chain(model.system);
    CHECK(formulas_parse_back(result.out, sample) == (chain ? 0 : 2 * model.system.unknowns.size()));
    if (chain) CHECK(result.out.find("% kinema vector: a_") != std::string::npos);

    std::string log;
    const bool ok = compiles(result.out, "derive_" + name.substr(0, name.find('.')), log);
    INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
    CHECK(ok);
  }
}

TEST_CASE("derive --format latex: hostile titles print as text - names must be identifiers") {
  const std::string text = kinema_test::replaced(
      "ABCD = ", "A_B = ",
      kinema_test::replaced("title = \"four-bar\"", "title = \"\\\\input{/etc/passwd} 100% & $x$ \\\\write18{rm -rf ~}\""));
  const std::string path = kinema_test::write_temporary("hostile.toml", text);
  const auto result = kinema_test::run_kinema({"derive", "--format", "latex", path});
  REQUIRE(result.exit_status == 0);
  CHECK(result.out.find("\\input{") == std::string::npos);
  CHECK(result.out.find("\\write18") == std::string::npos);
  CHECK(result.out.find("\\textbackslash{}input\\{/etc/passwd\\}") != std::string::npos);
  CHECK(result.out.find("\\textbackslash{}write18\\{rm -rf \\textasciitilde{}\\}") != std::string::npos);
  CHECK(result.out.find("\\text{A\\_B:}") != std::string::npos);
  std::string log;
  CHECK(compiles(result.out, "hostile", log));
  // A loop name that is not an identifier never reaches a printer.
  const std::string refused_path = kinema_test::write_temporary(
      "hostile_name.toml", kinema_test::replaced("ABCD = ", "\"\\\\write18{rm -rf ~}\" = "));
  const auto refused_name = kinema_test::run_kinema({"derive", "--format", "latex", refused_path});
  CHECK(refused_name.exit_status == 2);
  CHECK(refused_name.out.empty());
  CHECK(refused_name.err.find("loop name") != std::string::npos);

  // A LaTeX name given in the file that is not a plain symbol is refused.
  const std::string bad = kinema_test::write_temporary(
      "bad_latex_name.toml", text.substr(0, text.find("theta3 = ")) +
                                 "theta3 = { guess = \"20 deg\", latex = \"\\\\input{x}\" }\n" +
                                 text.substr(text.find("theta4 = ")));
  const auto refused = kinema_test::run_kinema({"derive", "--format", "latex", bad});
  CHECK(refused.exit_status == 2);
  CHECK(refused.err.find("bad_latex_name.toml:12") != std::string::npos);
  CHECK(refused.err.find("\\input") != std::string::npos);
}

namespace {

// docs/outputs.md's table of pages: "| `four_bar.toml` | 6 |" (two samples a row).
int documented_pages(const std::string& sample) {
  const std::string outputs = read_file(kinema_test::sample("../docs/outputs.md"));
  const std::string cell = "| `" + sample + "` | ";
  const auto at = outputs.find(cell);
  return at == std::string::npos ? -1 : std::atoi(outputs.c_str() + at + cell.size());
}

// The samples [first, last): the check is two test cases, so that ctest -j runs them side by side.
void check_worked_solutions(std::size_t first, std::size_t last) {
  for (std::size_t k = first; k < last; ++k) {
    const char* sample = kSamples[k];
    const std::string name = sample;
    CAPTURE(name);
    const auto result = kinema_test::run_kinema({"latex", kinema_test::sample(sample)});
    REQUIRE(result.exit_status == 0);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const bool chain = kinema::is_driven_chain(model.system);
    std::vector<const char*> parts = {"\\documentclass", "\\subsection*{Data}", "\\subsection*{Results at",
                                      "\\begin{tikzpicture}", "\\begin{axis}", "\\addplot"};
    if (chain) {  // seed 000's form, and the chain drawn in 3-D
      for (const char* part : {"\\subsection*{The chain}", "\\subsection*{Angular velocities and accelerations}",
                               "\\subsection*{Velocities and accelerations of the points}", "\\usepackage{tikz-3dplot}",
                               "\\tdplotsetmaincoords", "\\boxed{"})
        parts.push_back(part);
    } else {
      // A closed spatial chain closes by distances, not by planar vector loops.
      parts.push_back(model.system.frames.empty() ? "\\subsection*{Vector loops}" : "\\subsection*{Closure of the spatial chain}");
      for (const char* part : {"\\subsection*{Velocity analysis}",
                               "\\subsection*{Acceleration analysis}"})
        parts.push_back(part);
    }
    for (const char* part : parts) {
      CAPTURE(part);
      CHECK(result.out.find(part) != std::string::npos);
    }
    // The solved rates and second rates in the document are the engine's.
    CHECK(formulas_parse_back(result.out, sample) == (chain ? 0 : 2 * model.system.unknowns.size()));
    // Compiled with its figures marked (labels in lines already there: the layout is the same).
    const kinema_test::MarkedFigures marked = kinema_test::mark_figures(result.out);
    const std::string document = "document_" + name.substr(0, name.find('.'));
    std::string log;
    const int pages = compile_document(marked.tex, document, log);
    INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
    // Data and equations, the results (drawing, polygons, centres), the plots: as docs/outputs.md
    // says, from every build (the sanitizer build's GiNaC orders terms otherwise).
    CHECK(pages >= 3);
    CHECK(pages == documented_pages(name));
    // No near-empty page, each figure with its caption and its introduction, nothing overfull.
    kinema_test::check_layout(document, marked, pages, log);
  }
}

}  // namespace

TEST_CASE("kinema latex: every sample's worked solution compiles, with its pages and the engine's formulas (first half)" * doctest::skip(kinema_test::kSanitized)) {
  check_worked_solutions(0, std::size(kSamples) / 2);
}

TEST_CASE("kinema latex: every sample's worked solution compiles, with its pages and the engine's formulas (second half)" * doctest::skip(kinema_test::kSanitized)) {
  check_worked_solutions(std::size(kSamples) / 2, std::size(kSamples));
}

TEST_CASE("kinema latex: one results page per requested value, fragments and hostile titles") {
  const auto two = kinema_test::run_kinema({"latex", kinema_test::sample("four_bar.toml"), "--angle", "30", "--angle", "200"});
  REQUIRE(two.exit_status == 0);
  std::size_t results = 0;
  for (auto at = two.out.find("Results at"); at != std::string::npos; at = two.out.find("Results at", at + 1)) ++results;
  CHECK(results == 2);
  std::string log;
  const int one_value_pages = compile_document(
      kinema_test::run_kinema({"latex", kinema_test::sample("four_bar.toml")}).out, "four_bar_one", log);
  // Each value's results start a page and take at least one (drawing, polygons, centres).
  CHECK(compile_document(two.out, "four_bar_two", log) >= one_value_pages + 1);

  const auto fragment = kinema_test::run_kinema({"latex", kinema_test::sample("four_bar.toml"), "--fragment"});
  REQUIRE(fragment.exit_status == 0);
  CHECK(fragment.out.find("\\documentclass") == std::string::npos);
  CHECK(fragment.out.find("\\end{document}") == std::string::npos);
  const std::string wrapped = "\\documentclass{article}\n\\usepackage{amsmath,booktabs,tikz,pgfplots}\n"
                              "\\usetikzlibrary{patterns}\n\\begin{document}\n" + fragment.out + "\\end{document}\n";
  CHECK(compile_document(wrapped, "fragment", log) >= 3);

  std::string hostile_text = kinema_test::replaced(
      "title = \"four-bar\"", "title = \"\\\\input{/etc/passwd} $x$ & 100%\"\ndescription = \"\\\\write18{rm -rf ~} #1\"");
  const std::string hostile = kinema_test::write_temporary("hostile_document.toml", hostile_text);
  const auto document = kinema_test::run_kinema({"latex", hostile});
  REQUIRE(document.exit_status == 0);
  for (const char* injected : {"\\input{", "\\write18", "\\def\\x"}) {
    CAPTURE(injected);
    CHECK(document.out.find(injected) == std::string::npos);
  }
  CHECK(document.out.find("\\textbackslash{}input\\{/etc/passwd\\}") != std::string::npos);
  CHECK(compile_document(document.out, "hostile_document", log) >= 3);
}

TEST_CASE("kinema latex: a value that cannot be assembled is an error, nothing written") {
  const std::string output = (kinema_test::scratch_directory() / "never.tex").string();
  std::filesystem::remove(output);
  const auto result = kinema_test::run_kinema(
      {"latex", kinema_test::sample("piston_driven_crank.toml"), "--at", "260", "-o", output});
  CHECK(result.exit_status == 3);
  CHECK(result.err.find("x = 260 mm") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(output));
}

// Issue 9, findings 1 and 19: no ^ in a LaTeX name (^^5c rebuilds any command),
// braces balanced, and control characters in user text do not stop pdflatex (a file's
// are refused when it is read since the audit of 2026-11-24: tests/cli/bad_input_test.cpp;
// a library caller's become spaces); a multi-line description typesets.
TEST_CASE("LaTeX names: ^^ notation and unbalanced braces refused - control characters as spaces, line breaks compile") {
  CHECK_THROWS_AS(kinema::check_latex_name("^^5cinput^^7b^^2fetc^^2fpasswd^^7d", "here"), kinema::InputError);
  CHECK_THROWS_AS(kinema::check_latex_name("x^{2}", "here"), kinema::InputError);
  CHECK_THROWS_AS(kinema::check_latex_name("}", "here"), kinema::InputError);
  CHECK_THROWS_AS(kinema::check_latex_name("{x", "here"), kinema::InputError);
  CHECK_THROWS_AS(kinema::check_latex_name("x}{", "here"), kinema::InputError);
  CHECK_NOTHROW(kinema::check_latex_name("\\hat{x}_{1}", "here"));

  const std::string injected = kinema_test::write_temporary(
      "caret_name.toml", kinema_test::replaced("theta3 = \"20 deg\"",
                                               "theta3 = { guess = \"20 deg\", latex = \"^^5cinput^^7b^^2fetc^^2fpasswd^^7d\" }"));
  const auto refused = kinema_test::run_kinema({"latex", injected});
  CHECK(refused.exit_status == 2);
  CHECK(refused.out.empty());
  CHECK(refused.err.find("caret_name.toml:12") != std::string::npos);

  CHECK(kinema::latex_escape_text("four\x1b-bar\x7f and\x01 more\xc2\x85.\n") == "four -bar  and  more . ");
  const std::string lines = kinema_test::write_temporary(
      "multi_line_title.toml",
      kinema_test::replaced("title = \"four-bar\"",
                            "title = \"four-bar\\nopen branch\"\ndescription = \"\"\"\nA crank-rocker.\n\nOpen branch.\"\"\""));
  const auto document = kinema_test::run_kinema({"latex", lines});
  REQUIRE(document.exit_status == 0);
  CHECK(document.out.find("\\section*{four-bar open branch}") != std::string::npos);
  std::string log;
  CHECK(compile_document(document.out, "multi_line_title", log) >= 3);
}

// Issue 9, finding 19: a title, description and names with characters past ASCII
// typeset (θ ≠ 0 was "Unicode character not set up"), and a character LaTeX has no
// spelling for is written as its code point.
TEST_CASE("user text past ASCII typesets: Greek, signs, accents, quotes - an emoji as its code point") {
  CHECK(kinema::latex_escape_text("θ ≠ 0") == "\\ensuremath{\\theta} \\ensuremath{\\neq} 0");
  CHECK(kinema::latex_escape_text("café — “x”") == "caf\\'e --- ``x''");
  CHECK(kinema::latex_escape_text("🙂") == "[U+1F642]");
  CHECK(kinema::latex_escape_text("a\xff") == "a[U+FFFD]");  // not UTF-8 (a library caller's text)
  const std::string path = kinema_test::write_temporary(
      "unicode_title.toml",
      kinema_test::replaced("title = \"four-bar\"",
                            "title = \"θ ≠ 0, α ≤ 90°, Ω — “quoted” café ß ½ 🙂 end\"\n"
                            "description = 'Ψ < φ > ω | ∞ ± µ'"));
  const auto document = kinema_test::run_kinema({"latex", path});
  REQUIRE(document.exit_status == 0);
  CHECK(document.out.find("\\ensuremath{\\theta}") != std::string::npos);
  std::string log;
  CHECK(compile_document(document.out, "unicode_title", log) >= 3);
  CHECK(log.find("not set up for use with LaTeX") == std::string::npos);
}

// Audit 2026-11-24 (tests/fuzz/regressions/latex_single_letter_angle_name.toml,
// latex_name_plain_letter.toml): an angle named u, or an unknown given latex = "q", was
// written \cosu, an undefined command, and kinema exited 0.
TEST_CASE("kinema latex: an angle named with one letter and a LaTeX name that is a letter compile") {
  for (const auto& [file, written] : std::vector<std::pair<std::string, std::string>>{
           {"latex_single_letter_angle_name", "\\cos u"}, {"latex_name_plain_letter", "\\cos q"}}) {
    CAPTURE(file);
    const std::string path = kinema_test::sample("../tests/fuzz/regressions/" + file + ".toml");
    const auto document = kinema_test::run_kinema({"latex", path});
    REQUIRE(document.exit_status == 0);
    CHECK(document.out.find(written) != std::string::npos);
    std::string log;
    CHECK(compile_document(document.out, file, log) >= 3);
    const auto derived = kinema_test::run_kinema({"derive", "--format", "latex", path});
    REQUIRE(derived.exit_status == 0);
    CHECK(compiles(derived.out, "derive_" + file, log));
  }
}

// Audit 2026-11-24 (tests/fuzz/regressions/latex_name_trailing_underscore.toml): names that
// the old check let through and pdflatex stopped on. Each accepted name is typeset where
// the derivation puts a name (after \cos, under \dot and \ddot, in matrices) and compiles.
TEST_CASE("derive --format latex: LaTeX names the grammar accepts compile where kinema puts them") {
  for (const char* name : {"q", "x'", "\\hat{\\varphi}_{3}", "\\dot{s}'", "{x}_{1,\\mathrm{out}}", "x''_{1}",
                           "\\theta_3'", "\\bar{q} \\prime", "L a", "\\vec{r}_\\alpha", "x_{\\hat{y}}",
                           "\\mathrm{\\hat{x}}_{\\mathit{y}}"}) {
    const std::string shown = name;
    CAPTURE(shown);
    std::string basic;  // the name in a TOML basic string
    for (const char c : shown) basic += c == '\\' ? std::string("\\\\") : std::string(1, c);
    const std::string path = kinema_test::write_temporary(
        "latex_name.toml", kinema_test::replaced("theta3 = \"20 deg\"",
                                                 "theta3 = { guess = \"20 deg\", latex = \"" + basic + "\" }"));
    const auto derived = kinema_test::run_kinema({"derive", "--format", "latex", path});
    REQUIRE(derived.exit_status == 0);
    std::string log;
    CHECK(compiles(derived.out, "latex_name", log));
  }
}

// Audit 2026-11-24 (tests/fuzz/regressions/latex_point_pole.toml): a point at a*tan(theta2)
// is 1.6e16 a at 90 deg; its path and speed went into the plots as they were and pgfplots
// stopped ("divide by 0.0"). Such values are gaps now, and a path along a line widens the
// short side of the equal-scale box.
TEST_CASE("kinema latex: a point with a pole over the turn and a path along a line compile") {
  const std::string pole = kinema_test::sample("../tests/fuzz/regressions/latex_point_pole.toml");
  const std::string alone = kinema_test::write_temporary(
      "pole_alone.toml",
      kinema_test::replaced("P = \"a*exp(I*theta2)\"", "P = \"a*tan(theta2)\"",
                            kinema_test::replaced("[points]", "[points]\nQ = \"1e4*a*cos(theta2)\"")));
  for (const auto& [path, arguments] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {pole, {}}, {pole, {"--angle", "90"}}, {alone, {}}}) {
    std::vector<std::string> command = {"latex", path};
    command.insert(command.end(), arguments.begin(), arguments.end());
    CAPTURE(path);
    CAPTURE(arguments.size());
    const auto document = kinema_test::run_kinema(command);
    REQUIRE(document.exit_status == 0);
    CHECK(document.out.find("(90.000000,nan)") != std::string::npos);  // the pole is a gap
    std::string log;
    CHECK(compile_document(document.out, "point_pole", log) >= 3);
  }
}

namespace {

// The sample and method whose part of a concatenated .tex holds `line`.
std::string part_at(const std::vector<std::pair<std::size_t, std::string>>& starts, std::size_t line) {
  std::string part = "?";
  for (const auto& [start, name] : starts)
    if (start <= line) part = name;
  return part;
}

std::size_t lines_in(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

// kinema latex --method of each sample: tests/engine/printers/latex_layout_test.cpp.
TEST_CASE("derive --format latex: every sample with every method fits the page - no overfull box") {
  // derive --format latex of every sample and method in one plain article (one pdflatex
  // run): each block breaks across pages and keeps every line inside 345 pt.
  std::string tex = "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n";
  std::vector<std::pair<std::size_t, std::string>> starts;
  const kinema::Printer* derivation = kinema::find_printer(kinema::PrintKind::derivation, "latex");
  REQUIRE(derivation != nullptr);
  for (const char* sample : kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    for (kinema::DerivationMethod method : methods_of(model)) {
      kinema::PrintJob job{model};
      job.method = method;
      std::ostringstream out;
      kinema::print_view(*derivation, out, job);
      starts.push_back({lines_in(tex) + 1, std::string(sample) + " " + kinema::method_name(method)});
      tex += "\\clearpage\n" + out.str();
    }
  }
  {
    // Seed 000's arm at non-zero joint angles: its formulas carry sqrt(3)/2 and floats
    // (a \frac{...}{2} of a whole sum was 1191 pt too wide).
    std::string arm = read_file(kinema_test::sample("robot_arm_seed000.toml"));
    for (const char* angle : {"30 deg", "-20 deg", "50 deg"}) arm.replace(arm.find("value = \"0 deg\"") + 9, 5, angle);
    const kinema::Model model = kinema::load_model(kinema_test::write_temporary("arm_turned.toml", arm));
    kinema::PrintJob job{model};
    std::ostringstream out;
    kinema::print_view(*derivation, out, job);
    starts.push_back({lines_in(tex) + 1, "robot_arm_seed000.toml at 30, -20, 50 deg"});
    tex += "\\clearpage\n" + out.str();
  }
  tex += "\\end{document}\n";
  std::string log;
  CHECK(compile_document(tex, "derive_every_method", log) > 0);
  for (const Overfull& box : overfull_boxes(log)) {
    INFO(part_at(starts, box.line) << ": " << box.text);
    CHECK(box.points <= 1.0);
  }

}

// Issue 33: sin nested 40 deep in a loop was accepted (parentheses up to 100 deep) and gave
// pdflatex "Dimension too large" in kinema latex and derive --format latex (60 deep
// overflowed its buffer). The deepest formula the reader accepts now typesets in both; one
// level more is refused with file:line.
TEST_CASE("the deepest nesting the formula reader accepts typesets in derive --format latex and kinema latex") {
  const auto nested_loop = [](int depth) {
    std::string nested = "theta3";
    for (int k = 0; k < depth; ++k) nested = "sin(" + nested + ")";
    return kinema_test::replaced("d = \"100 mm\"", "d = \"100 mm\"\nk = \"1e-9 mm\"",
                                 kinema_test::replaced("- d\"", "- d + k*" + nested + "\""));
  };
  const std::string deepest = kinema_test::write_temporary("deepest_formula.toml", nested_loop(32));
  const auto document = kinema_test::run_kinema_bounded({"latex", deepest});
  REQUIRE(document.exit_status == 0);
  std::string log;
  CHECK(compile_document(document.out, "deepest_formula", log) >= 3);
  const auto derived = kinema_test::run_kinema_bounded({"derive", "--format", "latex", deepest});
  REQUIRE(derived.exit_status == 0);
  CHECK(compiles(derived.out, "deepest_formula_derive", log));
  const auto deeper = kinema_test::run_kinema_bounded(
      {"latex", kinema_test::write_temporary("deeper_formula.toml", nested_loop(33))});
  CHECK(deeper.exit_status == 2);
  CHECK(deeper.err.find("deeper_formula.toml:") != std::string::npos);
  CHECK(deeper.err.find("more than 32 deep") != std::string::npos);
}

// Issue 33: what the reader accepts must typeset. tan nested 8 deep took past 30 s in
// kinema latex (each nesting level's order worked out again) and tan or asin nested 5 to 8
// deep, sqrt 8 deep, gave pdflatex "Dimension too large". The deepest nest of each function
// the reader accepts (sin, cos, exp, abs as deep as parentheses go; the functions whose
// derivatives divide, sqrt, fractional powers and divisions 3 deep) now loads, derives,
// generates code and typesets within the bounded run; one level more is refused with
// file:line. sin has its own test above (a document of its own).
namespace {

struct Nest {
  const char* name;
  const char* open;   // written around the formula once per level: open + inner + close
  const char* close;
  int depth;
};

// Each nest loaded, derived, generated and typeset within the bounds, one level more refused;
// the derivations in one document and the worked solutions in another (`document` names them).
void check_deepest_nests(const std::vector<Nest>& nests, const std::string& document_name) {
  const auto nested_loop = [](const Nest& nest, int depth) {
    std::string nested = "theta3";
    for (int k = 0; k < depth; ++k) nested = nest.open + nested + nest.close;
    return kinema_test::replaced("d = \"100 mm\"", "d = \"100 mm\"\nk = \"1e-9 mm\"",
                                 kinema_test::replaced("- d\"", "- d + k*" + nested + "\""));
  };
  const auto bounded = [](const std::vector<std::string>& arguments) {
    const auto result = kinema_test::run_kinema_bounded(arguments, kinema_test::kFinishCpuSeconds);
    INFO(arguments.front() << " " << arguments.back() << ": " << result.err);
    CHECK(result.exit_status == 0);
    CHECK(result.peak_kilobytes < kinema_test::kFinishPeakKilobytes);
    return result;
  };
  std::string derivations, document;
  for (const Nest& nest : nests) {
    const std::string name = std::string("deepest_") + nest.name;
    const std::string path = kinema_test::write_temporary(name + ".toml", nested_loop(nest, nest.depth));
    bounded({"eval", path});
    bounded({"derive", path});
    bounded({"codegen", path, "-o", kinema_test::write_temporary(name + ".hpp", "")});
    derivations += bounded({"derive", "--format", "latex", path}).out;
    bounded({"derive", "--format", "latex", "--method", "loops", path});
    for (const char* method : {"relative-velocity", "joint-coordinates"}) {  // joints and links only: refused
      const auto refused = kinema_test::run_kinema_bounded({"derive", "--format", "latex", "--method", method, path});
      CHECK(refused.exit_status == 2);
    }
    bounded({"latex", path});
    // Its worked solution's body into the shared document (one pdflatex run for all), made
    // in process with sparse plots: what is typeset is the nest's formulas (the plots are
    // the four-bar's, compiled in full with every sample's document).
    const kinema::Model model = kinema::load_model(path);
    const std::string full = kinema_test::worked_solution_sparse_plots(model, kinema::DerivationMethod::loops,
                                                                      {model.system.input.values.front()});
    if (document.empty()) document = full.substr(0, full.find("\\begin{document}") + 17);
    const std::size_t body = full.find("\\begin{document}") + 17;
    document += "\\clearpage\n" + full.substr(body, full.rfind("\\end{document}") - body);
    // One level more is refused before any work.
    const auto deeper = kinema_test::run_kinema_bounded(
        {"latex", kinema_test::write_temporary(name + "_deeper.toml", nested_loop(nest, nest.depth + 1))});
    CHECK(deeper.exit_status == 2);
    CHECK(deeper.err.find(name + "_deeper.toml:") != std::string::npos);
    CHECK(deeper.err.find("more than " + std::to_string(nest.depth) + " deep") != std::string::npos);
  }
  // Two pdflatex runs for all of them: the derivations in one document, the worked
  // solutions' fragments in another.
  std::string log;
  CHECK(compiles(derivations, document_name + "_derive", log));
  document += "\\end{document}\n";
  const int pages = compile_document(document, document_name + "_latex", log);
  INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
  CHECK(pages > 0);
}

}  // namespace

// Two test cases, so that ctest -j runs them side by side.
TEST_CASE("the deepest nest of every function the formula reader accepts is derived, generated and typeset (cos, exp, abs)") {
  check_deepest_nests({{"cos", "cos(", ")", 32}, {"exp", "exp(0.1*", ")", 32}, {"abs", "abs(1 + ", ")", 32}},
                      "deepest_nests_32");
}

TEST_CASE("the deepest nest of every function the formula reader accepts is derived, generated and typeset (3 deep)") {
  check_deepest_nests({{"tan", "tan(0.5*", ")", 3},     {"asin", "asin(0.5*", ")", 3},
                       {"acos", "acos(0.5*", ")", 3},   {"atan", "atan(1 + ", ")", 3},
                       {"atan2", "atan2(", ", 2)", 3},  {"log", "log(10 + ", ")", 3},
                       {"sqrt", "sqrt(10 + ", ")", 3},  {"power", "(1 + 0.1*", ")^1.5", 3},
                       {"division", "1/(2 + ", ")", 3}},
                      "deepest_nests_3");
}
