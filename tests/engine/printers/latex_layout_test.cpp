// Issue 32: the worked solution's pages as a reader turns them, past the default document
// (tests/engine/printers/latex_pdf_test.cpp checks that one): with every --method and with
// several values worked out, no near-empty page, each figure on the page of its caption and
// of the heading or sentence that introduces it, nothing overfull.
#include <doctest/doctest.h>

#include "engine/model.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/symbolic/dyad_method.hpp"

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


// One document per sample and kind, to keep pdflatex runs few: each joints-and-links
// sample's first dyad method with three values, its other method at the file's value;
// a sample that takes only the loops with three values. The results of the first value are
// the default document's, so each method's derivation meets the results as it does alone.
void check_layouts(std::size_t first, std::size_t last) {
  for (std::size_t k = first; k < last; ++k) {
    const char* sample = kinema_test::kSamples[k];
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    std::vector<kinema::DerivationMethod> methods = kinema_test::methods_of(model);
    if (methods.size() > 1) methods.erase(methods.begin());  // the loops: the default document's
    const kinema::MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, model.system.input.values.front()));
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const std::vector<double> inputs =
          m == 0 ? three_values(model, sweep) : std::vector<double>{model.system.input.values.front()};
      const std::string document = "layout_" + name.substr(0, name.find('.')) + "_" + kinema::method_name(methods[m]) +
                                   "_" + std::to_string(inputs.size());
      CAPTURE(document);
      const kinema_test::MarkedFigures marked = kinema_test::mark_figures(kinema_test::worked_solution_sparse_plots(model, methods[m], inputs));
      std::string log;
      const int pages = kinema_test::compile_document(marked.tex, document, log);
      INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
      REQUIRE(pages > 0);
      kinema_test::check_layout(document, marked, pages, log);
    }
  }
}

}  // namespace

// Two test cases, so that ctest -j runs them side by side.
TEST_CASE("kinema latex: every method and three values - no near-empty page, figures with their captions and introductions (first half)" * doctest::skip(kinema_test::kSanitized)) {
  check_layouts(0, std::size(kinema_test::kSamples) / 2);
}

TEST_CASE("kinema latex: every method and three values - no near-empty page, figures with their captions and introductions (second half)" * doctest::skip(kinema_test::kSanitized)) {
  check_layouts(std::size(kinema_test::kSamples) / 2, std::size(kinema_test::kSamples));
}
