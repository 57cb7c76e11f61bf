// A plane TikZ figure read back as what a reader sees: its labels' boxes (from their text
// at their font, as the printers estimate them), the straight lines it draws (arcs as short
// chords), and the areas a label must not cover (hatching, blocks, dots). Only the forms
// kinema's printers write are understood: one statement a line, (x,y) and ++(dx,dy),
// --, rectangle, circle, arc[...], cycle, and nodes placed by anchor, pos, shift or at.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "engine/printers/latex/label_boxes.hpp"

namespace kinema_test {

using TikzPoint = std::complex<double>;

struct TikzLine {
  TikzPoint a, b;
  double half_width = 0;  ///< cm: half the drawn line's width (a bar's body: 3 pt)
  int statement = 0;      ///< the line of the figure that draws it
};

/// A convex area, its corners in order (a rectangle turned as drawn; a dot's square).
struct TikzArea {
  std::vector<TikzPoint> corners;
  std::string kind;  ///< "hatching", "block" or "dot"
  int statement = 0;
};

struct TikzLabel {
  std::string text;
  kinema::LabelBox box;
  int statement = 0;
};

struct TikzFigure {
  std::vector<TikzLine> lines;
  std::vector<TikzArea> areas;
  std::vector<TikzLabel> labels;
};

/// The figure between \begin{tikzpicture}[...] and \end{tikzpicture}.
TikzFigure read_tikz(const std::string& figure);

/// Every plane figure of a document: the tikzpictures whose options start "line cap=round"
/// (the mechanism's drawing, the polygons, the instant centres).
std::vector<std::string> plane_figures(const std::string& tex);

/// True when the box and the convex area share more than their edges (shrunk by `slack` cm).
bool box_meets_area(const kinema::LabelBox& box, const TikzArea& area, double slack);

}  // namespace kinema_test
