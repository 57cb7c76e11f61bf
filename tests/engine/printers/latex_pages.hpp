// Compiling the worked solution and reading its pages back: how full each page is
// (pdftotext -bbox), where each figure, its caption and the text that introduces it
// land (labels pdflatex writes to the .aux), and the overfull boxes of the log.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/symbolic/dyad_method.hpp"

namespace kinema_test {

/// Compiles a whole document under $TMPDIR/kinema_tests/latex; returns its page count (0
/// when it does not compile cleanly) and its log in `log`.
int compile_document(const std::string& tex_text, const std::string& name, std::string& log);

/// Each page's text height over the page's (pdftotext -bbox of NAME.pdf: from the top of its
/// first word to the foot of its last, the page number under the text left out).
std::vector<double> text_heights(const std::string& name);

/// Every overfull box of a pdflatex log over 1 pt: "Overfull \hbox (12.3pt too wide) ...
/// at lines 40--41" (or "detected at line 40"), with the source line it names.
struct Overfull {
  double points = 0;
  std::size_t line = 0;
  std::string text;
};
std::vector<Overfull> overfull_boxes(const std::string& log);

/// A worked solution with its figures marked for pdflatex to tell where each lands: in the
/// drawing's own line (so that no break is added or taken away) \label{kinema-figure-K},
/// in its caption \label{kinema-caption-K}, and at the end of the heading or sentence before
/// it \label{kinema-intro-K}, where that is not another figure (a plot beside a plot, the
/// acceleration polygon under the velocity polygon).
struct MarkedFigures {
  std::string tex;
  std::size_t figures = 0;
  std::vector<bool> captioned;  ///< Per figure: a caption follows the drawing.
  std::vector<bool> follows_figure;  ///< Per figure: what comes before it is another figure.
  std::vector<std::string> before;  ///< Per figure: the source line before it (in messages).
};
MarkedFigures mark_figures(const std::string& tex);

/// The page of each \label, from NAME.aux ("\newlabel{key}{{3}{7}}": page 7).
std::map<std::string, int> label_pages(const std::string& name);

/// The layout checks of a compiled worked solution (doctest CHECKs): no page but the last
/// under a quarter full, each figure on its caption's page and on the page of the text that
/// introduces it (or after another figure), no overfull box over 1 pt.
void check_layout(const std::string& name, const MarkedFigures& marked, int pages, const std::string& log);

/// kinema latex in process (for tests whose subject is not the program): the document the
/// CLI writes at `inputs`, its plots from every sixth value of the run (the same boxes, each
/// plot the size it is in the full run; pgfplots takes half of a pdflatex run over 181 values).
std::string worked_solution_sparse_plots(const kinema::Model& model, kinema::DerivationMethod method,
                                         const std::vector<double>& inputs);

/// The methods a sample takes: dyad by dyad only for joints and links solved in dyads.
std::vector<kinema::DerivationMethod> methods_of(const kinema::Model& model);

}  // namespace kinema_test
