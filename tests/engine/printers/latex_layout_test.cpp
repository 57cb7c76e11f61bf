// Issue 32: the worked solution's pages as a reader turns them, past the default document
// (tests/engine/printers/latex_pdf_test.cpp checks that one): with every --method and with
// several values worked out, no near-empty page, each figure on the page of its caption and
// of the heading or sentence that introduces it, nothing overfull.
#include <doctest/doctest.h>

#include "engine/run/view.hpp"
#include "engine/model.hpp"
#include "engine/printers/printer.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/symbolic/dyad_method.hpp"

#include <sstream>

#include "engine/printers/latex_pages.hpp"
#include "tests/test_support.hpp"

namespace {

// The file's value and two more a third and two thirds along the plotted range, each the
// nearest that assembles without a singularity: three results parts, as --at 40 --at 160
// --at 280 gives them.
std::vector<double> three_values(const kinema::Model& model, const kinema::MotionTable& sweep) {
  std::vector<double> values = {model.system.input.values.front()};
  for (const std::size_t third : {sweep.size() / 3, 2 * sweep.size() / 3}) {
    std::size_t row = third;
    while (row < sweep.size() && sweep.status(row) != kinema::Status::ok) ++row;
    REQUIRE(row < sweep.size());
    values.push_back(sweep.input(row));
  }
  return values;
}

// kinema latex in-process (the program is not the subject here): the document the CLI writes,
// its plots from every sixth value of the run (the same boxes, each of a page's plots the
// size it is in the full run; pgfplots took half of each pdflatex run over 181 values).
std::string worked_solution(const kinema::Model& model, kinema::DerivationMethod method, const std::vector<double>& inputs) {
  const kinema::MotionTable values = kinema::analyse(model, inputs);
  const std::vector<double> range = kinema::plot_range(model.system, inputs.front());
  std::vector<double> coarse;
  for (std::size_t k = 0; k < range.size(); k += 6) coarse.push_back(range[k]);
  if (coarse.back() != range.back()) coarse.push_back(range.back());  // the run's last value kept
  const kinema::MotionTable sweep = kinema::analyse(model, coarse);
  kinema::PrintJob job{model, &values, &sweep};
  job.method = method;
  std::ostringstream out;
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::document, "latex"), out, job);
  return out.str();
}

}  // namespace

// One document per sample and kind, to keep pdflatex runs few: each joints-and-links
// sample's first dyad method with three values, its other method at the file's value;
// a sample that takes only the loops with three values. The results of the first value are
// the default document's, so each method's derivation meets the results as it does alone.
TEST_CASE("kinema latex: every method and three values - no near-empty page, figures with their captions and introductions") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    std::vector<kinema::DerivationMethod> methods = kinema_test::methods_of(model);
    if (methods.size() > 1) methods.erase(methods.begin());  // the loops: the default document's
    const kinema::MotionTable sweep = kinema::analyse(model, kinema::plot_range(model.system, model.system.input.values.front()));
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const std::vector<double> inputs =
          m == 0 ? three_values(model, sweep) : std::vector<double>{model.system.input.values.front()};
      const std::string document = "layout_" + name.substr(0, name.find('.')) + "_" + kinema::method_name(methods[m]) +
                                   "_" + std::to_string(inputs.size());
      CAPTURE(document);
      const kinema_test::MarkedFigures marked = kinema_test::mark_figures(worked_solution(model, methods[m], inputs));
      std::string log;
      const int pages = kinema_test::compile_document(marked.tex, document, log);
      INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
      REQUIRE(pages > 0);
      kinema_test::check_layout(document, marked, pages, log);
    }
  }
}
