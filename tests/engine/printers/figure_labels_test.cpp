// The labels of the worked solution's figures read back from the TikZ every sample's
// document writes: each label's box from its text at its font, the lines and areas as drawn.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/analysis/plot_range.hpp"
#include "engine/base/units.hpp"
#include "engine/printers/printer.hpp"
#include "engine/run/view.hpp"
#include "tests/engine/printers/tikz_reader.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

namespace {

using kinema_test::TikzFigure;

// Coordinates are written to 0.001 cm and boxes are estimates: a touch this deep is no overlap.
constexpr double kSlack = 0.005;

kinema::LabelBox shrunk(kinema::LabelBox box) {
  box.half_width -= kSlack;
  box.half_height -= kSlack;
  return box;
}

std::string where(const kinema::LabelBox& box) {
  std::ostringstream s;
  s << "(" << box.centre.real() << "," << box.centre.imag() << ")";
  return s.str();
}

// What is wrong with each label of a figure: on another label, crossed by a line it does
// not label (a label on an arrow's own statement names that arrow), or on a hatching, a
// block or a dot.
std::vector<std::string> label_problems(const TikzFigure& figure) {
  std::vector<std::string> problems;
  for (std::size_t i = 0; i < figure.labels.size(); ++i) {
    const kinema_test::TikzLabel& label = figure.labels[i];
    const kinema::LabelBox box = shrunk(label.box);
    const std::string name = label.text + " at " + where(label.box);
    for (std::size_t j = 0; j < i; ++j)
      if (box.overlaps(shrunk(figure.labels[j].box))) problems.push_back(name + " on label " + figure.labels[j].text);
    for (const kinema_test::TikzLine& line : figure.lines) {
      if (line.statement == label.statement || box.distance_to_segment(line.a, line.b) >= line.half_width) continue;
      std::ostringstream s;
      s << name << " crossed by the line " << line.a << "-" << line.b;
      problems.push_back(s.str());
    }
    for (const kinema_test::TikzArea& area : figure.areas)
      if (area.statement != label.statement && kinema_test::box_meets_area(box, area, 0))
        problems.push_back(name + " on a " + area.kind);
  }
  return problems;
}

std::string document_at_first_value(const kinema::Model& model) {
  const kinema::Printer* printer = kinema::find_printer(kinema::PrintKind::document, "latex");
  REQUIRE(printer != nullptr);
  const kinema::MotionTable values =
      kinema::solve_motion(model, {model.system.input.values.empty() ? 0.5 : model.system.input.values.front()});
  kinema::PrintJob job{model, &values, nullptr};
  job.fragment = true;
  std::ostringstream out;
  kinema::print_view(*printer, out, job);
  return out.str();
}

}  // namespace

// Issue 32: labels lay on links, guides, Kennedy lines and arrows, and on the ground's
// hatching (the drawing placed its letters and numbers by fixed offsets; the polygons and
// centres kept labels off one another only). Read back from every sample's drawing,
// polygons and instant centres: no label on another, crossed by a line it does not name,
// or on a hatching, block or dot.
TEST_CASE("figures: no label of any sample's figures on another label, a line, a hatching, a block or a dot") {
  int figures = 0;
  for (const char* name : kinema_test::kSamples) {
    const std::string tex = document_at_first_value(kinema::load_model(kinema_test::sample(name)));
    int index = 0;
    for (const std::string& text : kinema_test::plane_figures(tex)) {
      ++figures;
      const TikzFigure figure = kinema_test::read_tikz(text);
      const std::vector<std::string> problems = label_problems(figure);
      for (const std::string& p : problems) MESSAGE(std::string(name) << ", figure " << index << " (" << figure.labels.size() << " labels): " << p);
      CAPTURE(name);
      CAPTURE(index);
      CHECK(problems.empty());
      ++index;
    }
  }
  CHECK(figures >= 40);  // drawings, polygons and instant centres of the planar samples
}

// The reader itself: a label on a line, one on a hatching and two on one another are found;
// apart, none is.
TEST_CASE("figures: the TikZ reader finds a label on a line, on a hatching and on another label") {
  const std::string apart =
      "\\draw[very thick] (0,0) -- (4,0);\n"
      "\\fill[pattern=north east lines, rotate around={90:(6,0)}] (6,0) rectangle ++(2,-0.15);\n"
      "\\node[font=\\scriptsize, inner sep=0pt] at (1,1) {$B$};\n"
      "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at (2,1) {2};\n";
  CHECK(label_problems(kinema_test::read_tikz(apart)).empty());
  const std::string on_line = "\\draw[very thick] (0,0) -- (4,0);\n\\node[font=\\scriptsize] at (1,0.05) {$B$};\n";
  CHECK(label_problems(kinema_test::read_tikz(on_line)).size() == 1);
  // The hatching is turned to stand from (6,0) to (6,2) on the guide's right: a label at (6.08,1) is on it.
  const std::string on_hatching =
      "\\fill[pattern=north east lines, rotate around={90:(6,0)}] (6,0) rectangle ++(2,-0.15);\n"
      "\\node[font=\\scriptsize, inner sep=0pt] at (6.08,1) {$B$};\n\\node[font=\\scriptsize, inner sep=0pt] at (5.5,1) {$C$};\n";
  const auto hatched = label_problems(kinema_test::read_tikz(on_hatching));
  REQUIRE(hatched.size() == 1);
  CHECK(hatched[0].find("$B$") == 0);
  const std::string on_label = "\\node[font=\\small] at (1,1) {B};\n\\node[below, font=\\small] at (1,1.3) {C};\n";
  CHECK(label_problems(kinema_test::read_tikz(on_label)).size() == 1);
  // A \node statement's own options give its font: its box is the \scriptsize one, as a
  // node on a path's is (read as \normalsize, every \node label was a third too large).
  for (const std::string& node : {std::string("\\node[font=\\scriptsize, inner sep=0pt] at (1,1) {$B$};\n"),
                                  std::string("\\path (1,1) node[font=\\scriptsize, inner sep=0pt] {$B$};\n")}) {
    const auto labels = kinema_test::read_tikz(node).labels;
    REQUIRE(labels.size() == 1);
    CHECK(labels[0].box.half_width == doctest::Approx(kinema::label_box("$B$", 8, 0).half_width));
    CHECK(labels[0].box.half_height == doctest::Approx(kinema::label_box("$B$", 8, 0).half_height));
  }
  // A label at its own arrow's tip is not crossed by the arrow it names.
  const std::string tip = "\\draw[-latex, red, thick] (0,0) -- ++(1,0) node[anchor=west, inner sep=1pt, font=\\scriptsize] {$v$};\n";
  CHECK(label_problems(kinema_test::read_tikz(tip)).empty());
}

// The distances the placing keeps labels off lines and blocks by: a segment through the box
// with both ends outside it meets it; beside it, by its nearest point or the box's nearest
// corner; a block by its nearest edge.
TEST_CASE("figures: a label box's distance to a segment and to a block") {
  const kinema::LabelBox box{0, 1, 0.5};
  CHECK(box.distance_to_segment({-3, 0}, {3, 0}) == 0);
  CHECK(box.distance_to_segment({-3, 1}, {3, 1}) == doctest::Approx(0.5));
  CHECK(box.distance_to_segment({3, 0}, {5, 0}) == doctest::Approx(2));
  CHECK(box.distance_to_segment({2, 0}, {0, 2}) == doctest::Approx(0.5 / std::sqrt(2.0)));  // from the corner (1, 0.5)
  CHECK(box.distance_to_segment({2, 0.5}, {2, 0.5}) == doctest::Approx(1));                 // a point
  const std::vector<std::complex<double>> block = kinema::parallelogram({2, -1}, 1.0, {0, 2});
  CHECK(box.distance_to_area(block) == doctest::Approx(1));
  CHECK(kinema::LabelBox{{2.2, 0}, 0.5, 0.5}.distance_to_area(block) == 0);
  // A block turned 45 degrees about (3, 0): its nearest corner is (3 - sqrt 2 / 2, 0) on the x axis.
  const std::complex<double> turn = std::polar(1.0, kinema::kPi / 4);
  const std::vector<std::complex<double>> turned =
      kinema::parallelogram(std::complex<double>(3, 0) + std::complex<double>(-0.5, -0.5) * turn, turn, turn * std::complex<double>(0, 1));
  CHECK(box.distance_to_area(turned) == doctest::Approx(2 - std::sqrt(0.5)));
}

namespace {

struct DrawnArrow {
  std::complex<double> from, to;
};

// The drawing's arrows of one colour, read back from "\draw[-latex, COLOUR..] (x,y) -- ++(dx,dy)".
std::vector<DrawnArrow> arrows_of(const std::string& figure, const std::string& colour) {
  std::vector<DrawnArrow> arrows;
  const std::string head = "\\draw[-latex, " + colour + ", ";
  std::istringstream lines(figure);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(head, 0) != 0) continue;
    double x = 0, y = 0, dx = 0, dy = 0;
    const std::size_t at = line.find("] (");
    REQUIRE(std::sscanf(line.c_str() + at, "] (%lf,%lf) -- ++(%lf,%lf)", &x, &y, &dx, &dy) == 4);
    arrows.push_back({{x, y}, {x + dx, y + dy}});
  }
  return arrows;
}

double distance_to_segment(std::complex<double> p, const DrawnArrow& s) {
  const std::complex<double> d = s.to - s.from;
  const double t = std::clamp(std::real((p - s.from) * std::conj(d)) / std::norm(d), 0.0, 1.0);
  return std::abs(p - (s.from + t * d));
}

}  // namespace

// A point's acceleration along its velocity was drawn on top of the velocity's arrow
// (example 4.2's E: both along the guide), so one of them could not be seen.
TEST_CASE("figures: no acceleration arrow of any sample's drawing lies on a velocity arrow") {
  int pairs = 0;
  for (const char* name : kinema_test::kSamples) {
    const std::string tex = document_at_first_value(kinema::load_model(kinema_test::sample(name)));
    const std::vector<std::string> figures = kinema_test::plane_figures(tex);
    if (figures.empty()) continue;
    const std::vector<DrawnArrow> velocities = arrows_of(figures.front(), "red");
    for (const DrawnArrow& a : arrows_of(figures.front(), "green!50!black")) {
      for (const DrawnArrow& v : velocities) {
        ++pairs;
        // On it: both ends of the shorter within a line's breadth of the longer.
        const bool a_shorter = std::abs(a.to - a.from) < std::abs(v.to - v.from);
        const DrawnArrow& shorter = a_shorter ? a : v;
        const DrawnArrow& longer = a_shorter ? v : a;
        const std::string sample = name;
        CAPTURE(sample);
        CHECK_FALSE((distance_to_segment(shorter.from, longer) < 0.05 && distance_to_segment(shorter.to, longer) < 0.05));
      }
    }
  }
  CHECK(pairs >= 20);
}
