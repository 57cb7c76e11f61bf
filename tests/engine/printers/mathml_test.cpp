// The page's derivation in MathML (engine/printers/web/mathml): the LaTeX kinema's
// derivation printer writes, read as MathML Core; every sample's reads whole.
#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "engine/model.hpp"
#include "engine/printers/printer.hpp"
#include "engine/printers/web/mathml.hpp"
#include "engine/run/view.hpp"
#include "tests/test_support.hpp"

namespace {

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

std::string math(const std::string& formula) {
  const std::string html = kinema::mathml_of_latex("\\begin{align*}\n  " + formula + "\n\\end{align*}\n");
  const std::string open = "<mtd>", close = "</mtd>";
  const std::size_t begin = html.find(open) + open.size();
  return html.substr(begin, html.find(close, begin) - begin);
}

}  // namespace

TEST_CASE("engine/printers/web/mathml: the LaTeX of the derivations as MathML Core") {
  CHECK(math("\\theta_{3}") == "<msub><mi>θ</mi><mn>3</mn></msub>");
  CHECK(math("\\omega_{4}^{2}") == "<msubsup><mi>ω</mi><mn>4</mn><mn>2</mn></msubsup>");
  CHECK(math("a\\,e^{i\\theta_{2}}") ==
        "<mi>a</mi><mspace width=\"0.1667em\"></mspace><msup><mi>e</mi><mrow><mi>i</mi><msub><mi>θ</mi><mn>2</mn></msub></mrow></msup>");
  CHECK(math("\\frac{a}{b c}") ==
        "<mrow displaystyle=\"true\"><mfrac><mrow displaystyle=\"true\"><mi>a</mi></mrow><mrow displaystyle=\"true\"><mi>b</mi><mi>c</mi></mrow></mfrac></mrow>");
  CHECK(math("\\mathit{AB} - 2") == "<mi class=\"it\">AB</mi><mo>−</mo><mn>2</mn>");
  CHECK(math("\\mathrm{m/s^2}") == "<mrow><mi mathvariant=\"normal\">m</mi><mo>/</mo><msup><mi mathvariant=\"normal\">s</mi><mn>2</mn></msup></mrow>");
  CHECK(math("\\hat{\\mathbf{x}}") == "<mover accent=\"true\"><mi mathvariant=\"normal\" class=\"bold\">x</mi><mo>^</mo></mover>");
  CHECK(math("\\dot{s}") == "<mover accent=\"true\"><mi>s</mi><mo>˙</mo></mover>");
  CHECK(kinema::mathml_of_latex("$\\begin{bmatrix} a & b \\\\ c & d \\end{bmatrix}$") == "<p><math>" 
        "<mrow><mo>[</mo><mtable class=\"bmatrix\"><mtr><mtd><mi>a</mi></mtd><mtd><mi>b</mi></mtd></mtr><mtr><mtd><mi>c</mi></mtd>"
        "<mtd><mi>d</mi></mtd></mtr></mtable><mo>]</mo></mrow></math></p>\n");
  // Text reaches the markup as text.
  CHECK(math("\\text{<script>&\"}") == "<mtext>&lt;script&gt;&amp;&quot;</mtext>");
  CHECK(kinema::mathml_of_latex("\\noindent a <b> \\& $x$\\\\\n") == "<p>a &lt;b&gt; &amp; <math><mi>x</mi></math></p>\n");
  // Comments are left out; rows and columns kept.
  const std::string table = kinema::mathml_of_latex("\\begin{align*}\n  x &= 1 \\\\ % one\n  y &= 2\n\\end{align*}\n");
  CHECK(occurrences(table, "<mtr>") == 2);
  CHECK(occurrences(table, "<mtd>") == 4);
  CHECK(table.find("one") == std::string::npos);
  // LaTeX the reader does not know is an error, not a silent gap.
  CHECK_THROWS_AS(kinema::mathml_of_latex("$\\unknowncommand$"), kinema::MathmlError);
  CHECK_THROWS_AS(kinema::mathml_of_latex("\\begin{align*} \\begin{cases} x \\end{cases} \\end{align*}"), kinema::MathmlError);
  CHECK_THROWS_AS(kinema::mathml_of_latex("$x"), kinema::MathmlError);
}

TEST_CASE("engine/printers/web/mathml: every sample's derivation reads whole, a row of MathML for each row of LaTeX") {
  const kinema::Printer& latex = *kinema::find_printer(kinema::PrintKind::derivation, "latex");
  for (const char* sample : kinema_test::kSamples) {
    CAPTURE(sample);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    std::ostringstream out;
    kinema::print_view(latex, out, kinema::PrintJob{model});
    const std::string tex = out.str();
    std::string html;
    REQUIRE_NOTHROW(html = kinema::mathml_of_latex(tex));
    CHECK(occurrences(html, "<math display=\"block\">") == occurrences(tex, "\\begin{align*}"));
    // Every align row that holds anything (its line ends with \\, the last with \end) is a row.
    std::size_t rows = 0;
    std::istringstream lines(tex);
    bool inside = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.find("\\begin{align*}") != std::string::npos) inside = true;
      else if (line.find("\\end{align*}") != std::string::npos) inside = false;
      else if (inside && line.find_first_not_of(' ') != std::string::npos && line.find_first_not_of(' ') != line.find('%')) ++rows;
    }
    CHECK(occurrences(html, "<mtr>") >= rows);
    CHECK(html.find("\\") == std::string::npos);  // no LaTeX left over
  }
}
