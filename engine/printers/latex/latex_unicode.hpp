// Characters past ASCII in user text (a title "θ ≠ 0", a description with "café")
// as LaTeX that pdflatex typesets with no package: Greek letters and mathematical
// signs in \ensuremath, accented Latin letters as accent commands, typographic
// quotes and dashes as TeX ligatures. A character with no such spelling (an emoji)
// is written as its code point, "[U+1F642]", so the document always compiles.
#pragma once

#include <string>

namespace kinema {

/// The LaTeX for one Unicode code point past ASCII.
std::string latex_for_code_point(unsigned long code_point);

}  // namespace kinema
