// The derivation as MathML for the web page: the LaTeX kinema's derivation printer writes
// (engine/printers/latex, `kinema derive --format latex`), read as the small part of LaTeX
// it uses (align* and bmatrix, fractions, sub- and superscripts, accents, Greek letters,
// \mathit/\mathbf/\mathrm/\text, spacing) and written as MathML Core, which Chromium and
// Firefox render without a script or a font of their own. So the page shows the same
// derivation as the notes, formatted once. Every text reaches the markup escaped.
#pragma once

#include <stdexcept>
#include <string>

namespace kinema {

/// A command or an environment the reader does not know: a printer started to write
/// LaTeX this reader does not read (a test runs every sample through it).
struct MathmlError : std::logic_error {
  using std::logic_error::logic_error;
};

/// HTML of a derivation document: each align* as a block <math> of one table (its rows,
/// their & columns), each paragraph of text as <p> with its $...$ as inline <math>.
/// LaTeX comments, \begingroup and the like are left out. MathmlError for LaTeX outside
/// the part it reads.
std::string mathml_of_latex(const std::string& latex);

}  // namespace kinema
