// engine/printers/latex/worked_solution: the document printer (kinema latex)
// through the library: its sections, the numbers of the run in the results
// tables and put into the solved formulas, the fragment form, failures in
// words. (tests/latex_test.cpp runs pdflatex on it; this file does not.)
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "engine/run/view.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/latex/three_methods.hpp"
#include "engine/printers/latex/tikz_polygons.hpp"
#include "engine/printers/printer.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/analysis/instant_centres.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/analysis/polygons.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::latex_number;
using kinema::MotionTable;
using kinema::PrintKind;
using kinema_unit::kDeg;

namespace {

std::string document(const kinema::Model& model, const MotionTable* values, const MotionTable* sweep,
                     bool fragment = false) {
  const kinema::Printer* printer = kinema::find_printer(PrintKind::document, "latex");
  REQUIRE(printer != nullptr);
  kinema::PrintJob job{model, values, sweep};
  job.fragment = fragment;
  std::ostringstream out;
  kinema::print_view(*printer, out, job);
  return out.str();
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

double wrapped_degrees(double radians) {
  double d = std::remainder(radians / kDeg, 360.0);
  return d <= -180 ? d + 360 : d;
}

}  // namespace

TEST_CASE("engine/printers/worked_solution: a standalone document with every section") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable values = kinema::solve_motion(model, {40 * kDeg});
  const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, 40 * kDeg));
  const std::string tex = document(model, &values, &sweep);
  CAPTURE(tex.substr(0, 3000));

  CHECK(tex.find("\\documentclass") == 0);
  CHECK(count(tex, "\\begin{document}") == 1);
  CHECK(tex.size() > 15);
  CHECK(tex.compare(tex.size() - 15, 15, "\\end{document}\n") == 0);
  for (const char* section : {"\\section*{Four-bar linkage (crank-rocker, open branch)}", "\\subsection*{Data}",
                              "\\subsection*{Vector loops}", "\\subsection*{Velocity analysis}",
                              "\\subsection*{Acceleration analysis}",
                              "\\subsection*{Results at $\\theta_{2} = 40^{\\circ}$}"}) {
    CAPTURE(section);
    CHECK(count(tex, section) == 1);
  }
  // In order: data, loops, velocity, acceleration, results, plots.
  CHECK(tex.find("\\subsection*{Data}") < tex.find("\\subsection*{Vector loops}"));
  CHECK(tex.find("\\subsection*{Vector loops}") < tex.find("\\subsection*{Velocity analysis}"));
  CHECK(tex.find("\\subsection*{Velocity analysis}") < tex.find("\\subsection*{Acceleration analysis}"));
  CHECK(tex.find("\\subsection*{Acceleration analysis}") < tex.find("\\subsection*{Results at"));
  CHECK(tex.find("\\subsection*{Results at") < tex.find("\\begin{axis}"));

  // Data as written, the input's motion in its units.
  CHECK(has(tex, "$a$ & $40\\,\\mathrm{mm}$ \\\\"));
  CHECK(has(tex, "$\\delta$ & $30^{\\circ}$ \\\\"));
  CHECK(has(tex, "$\\omega_{2} = 10\\,\\mathrm{rad/s}$"));
  // The loop as link vectors, as written.
  CHECK(has(tex, "a\\,e^{i\\theta_{2}} + b\\,e^{i\\theta_{3}} - c\\,e^{i\\theta_{4}} - d = 0"));
  // Each solved formula once, with its machine-readable comment.
  CHECK(count(tex, "% kinema: omega3 = ") == 1);
  CHECK(count(tex, "% kinema: alpha4 = ") == 1);

  // The results table holds the run's numbers.
  const kinema::MotionState s = values[0];
  REQUIRE(s.status == kinema::Status::ok);
  // The answers boxed (issue 32).
  CHECK(has(tex, "$\\theta_{3}$ & $" + latex_number(wrapped_degrees(s.q[0])) + "^{\\circ}$ & $\\omega_{3} = \\boxed{" +
                     latex_number(s.qd[0]) + "}\\,\\mathrm{rad/s}$ & $\\alpha_{3} = \\boxed{" + latex_number(s.qdd[0]) +
                     "}\\,\\mathrm{rad/s^2}$ \\\\"));
  CHECK(has(tex, "P & $" + latex_number(s.points[2].position[0] / 0.001, 5) + "$ & $" +
                     latex_number(s.points[2].position[1] / 0.001, 5) + "$"));
  // A drawing and plots.
  CHECK(count(tex, "\\begin{tikzpicture}[line cap=round]") == 1);
  CHECK(count(tex, "\\begin{axis}") >= 3);
}

TEST_CASE("engine/printers/worked_solution: the numbers are put into the solved formulas") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable values = kinema::solve_motion(model, {40 * kDeg});
  const std::string tex = document(model, &values, nullptr);
  const auto at = tex.find("Numeric substitution (lengths in mm):\n\\begin{align*}\n");
  REQUIRE(at != std::string::npos);
  const auto end = tex.find("\\end{align*}", at);
  const std::string block = tex.substr(at, end - at);
  CAPTURE(block);
  const kinema::MotionState s = values[0];
  // One row per rate and second rate; each ends with the computed value.
  std::istringstream rows(block);
  std::string row;
  std::size_t seen = 0;
  while (std::getline(rows, row)) {
    const auto equals = row.find(" &= ");
    if (equals == std::string::npos) continue;
    ++seen;
    CAPTURE(row);
    const auto last = row.rfind(" = ");
    REQUIRE(last > equals);
    const std::string substituted = row.substr(equals + 4, last - equals - 4);
    // Every symbol has become a number: no coordinate, rate or length names are left.
    for (const char* name : {"\\theta", "\\omega", "\\alpha", "\\mathit"}) CHECK_FALSE(has(substituted, name));
    CHECK(has(substituted, "40^{\\circ}"));  // theta2 in degrees
  }
  CHECK(seen == 4);
  // The values the formulas give, with their units.
  CHECK(has(block, "\\omega_{3} &= "));
  CHECK(has(block, " = " + latex_number(s.qd[0]) + "\\,\\mathrm{rad/s}"));
  CHECK(has(block, " = " + latex_number(s.qdd[1]) + "\\,\\mathrm{rad/s^2}"));
  // Lengths in mm and the crank's rate as given.
  CHECK(has(block, "(120)"));  // b
  CHECK(has(block, "(80)"));   // c
  CHECK(has(block, "(10)"));   // omega2
  CHECK(has(block, latex_number(wrapped_degrees(s.q[1]), 5) + "^{\\circ}"));  // theta4 (in a sine: no parentheses)
  // No sweep, no plots.
  CHECK_FALSE(has(tex, "\\begin{axis}"));
}

TEST_CASE("engine/printers/worked_solution: a fragment has no preamble and no document environment") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable values = kinema::solve_motion(model, {40 * kDeg});
  const std::string fragment = document(model, &values, nullptr, true);
  const std::string whole = document(model, &values, nullptr, false);
  for (const char* preamble : {"\\documentclass", "\\usepackage", "\\begin{document}", "\\end{document}"}) {
    CAPTURE(preamble);
    CHECK_FALSE(has(fragment, preamble));
    CHECK(has(whole, preamble));
  }
  CHECK(fragment.find("\\section*{") == 0);
  // The rest is the same.
  CHECK(has(whole, fragment));
  // Without values: the derivation only.
  const std::string derivation_only = document(model, nullptr, nullptr, true);
  CHECK_FALSE(has(derivation_only, "\\subsection*{Results at"));
  CHECK(has(derivation_only, "\\subsection*{Acceleration analysis}"));
}

TEST_CASE("engine/printers/worked_solution: sliding links, failures in words, user text escaped") {
  // Example 4.1: the slider on the turning link, with its relative and Coriolis terms.
  const kinema::Model slider = kinema::load_model(kinema_test::sample("example_4_1_r_trr.toml"));
  const std::string tex = document(slider, nullptr, nullptr, true);
  CHECK(has(tex, "In loop ABC, the point at the end of $r\\,e^{i\\phi}$ slides along a turning link"));
  CHECK(has(tex, "the relative term $\\ddot{r}\\,e^{i\\phi}$"));
  CHECK(has(tex, "the Coriolis term $2 \\omega_{1} \\dot{r}\\,i\\,e^{i\\phi}$"));

  // The piston at its dead centre (singular) and beyond reach (unassembled).
  const kinema::Model piston = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  MotionTable values({0.2, 0.25}, 2, {2, 2}, -2.0, 5.0);
  kinema::Workspace workspace(piston);
  values.set(0, workspace.motion(0.2, -2.0, 5.0, Eigen::VectorXd::Zero(2)));
  values.set(1, kinema::solve_motion(piston, {0.25})[0]);
  REQUIRE(values.status(0) == kinema::Status::singular);
  REQUIRE(values.status(1) == kinema::Status::unassembled);
  const std::string failed = document(piston, &values, nullptr, true);
  CHECK(has(failed, "\\subsection*{Results at $x = 200\\,\\mathrm{mm}$}"));
  CHECK(has(failed, kinema::latex_escape_text(kinema::describe_failure(piston.system, values[0]))));
  CHECK(has(failed, "undefined & undefined"));
  CHECK(has(failed, "\\subsection*{Results at $x = 250\\,\\mathrm{mm}$}"));
  CHECK(has(failed, kinema::latex_escape_text(kinema::describe_failure(piston.system, values[1]))));
  CHECK_FALSE(has(failed, "Numeric substitution"));  // no rates to put in
  CHECK(count(failed, "\\begin{tabular}{lrrr}") == 1);  // the singular position's coordinates only

  // Hostile title and description print as text.
  const std::string hostile = kinema_test::replaced(
      "title = \"four-bar\"", "title = \"50% & \\\\input{evil}\"\ndescription = \"$x$ #1 ~\"");
  const kinema::Model model = kinema_unit::model_from_text(hostile, "hostile.toml");
  const std::string escaped = document(model, nullptr, nullptr);
  CHECK(has(escaped, "\\section*{50\\% \\& \\textbackslash{}input\\{evil\\}}"));
  CHECK(has(escaped, "\\$x\\$ \\#1 \\textasciitilde{}"));
  CHECK_FALSE(has(escaped, "\\input{evil}"));
}

TEST_CASE("engine/printers/worked_solution: a joints-and-links drawing follows the links") {
  // Problem 3.22 as drawn: the triangle coupler 3 as a plate, two slider blocks on two
  // hatched fixed guides, the crank as a bar, the fixed pivot O2; its loops are not drawn.
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_3_22_joints.toml"));
  const MotionTable values = kinema::solve_motion(model, model.system.input.values);
  // The mechanism's drawing: what comes before the polygons and instant centres.
  const std::string whole = document(model, &values, nullptr);
  const std::string tex = whole.substr(0, whole.find("\\subsubsection*{Velocity and acceleration polygons}"));
  CHECK(count(tex, "\\filldraw[fill=blue!10") == 1);                 // link 3: A, B, C
  CHECK(count(tex, "\\draw[thick, fill=white, rotate around=") == 2);  // blocks 4 and 6
  CHECK(count(tex, "\\fill[pattern=north east lines, rotate around=") == 2);  // guides x = 0 line and x = d
  CHECK(count(tex, "\\draw[very thick, blue!70!black]") == 2);       // bars 2 and 5
  CHECK(has(tex, "{O2};"));
  // No loop segments: the only dashed lines are the x directions the angle arcs start from.
  CHECK(count(tex, "\\draw[gray, dashed]") == count(tex, "arc[start angle=0"));
  CHECK(count(tex, "\\node[circle, draw, inner sep=1pt, font=\\scriptsize]") == 5);  // links 2, 3, 5 and blocks 4, 6 numbered
  // A vector-loop file is drawn from its loops; C, on link 3 by its formula, makes a plate
  // with link 3's vector from A (to B), its links numbered by their angles.
  const kinema::Model loops = kinema::load_model(kinema_test::sample("problem_3_22_six_bar_sliders.toml"));
  const MotionTable loop_values = kinema::solve_motion(loops, loops.system.input.values);
  const std::string loop_document = document(loops, &loop_values, nullptr);
  const std::string loop_drawing =
      loop_document.substr(0, loop_document.find("\\subsubsection*{Velocity and acceleration polygons}"));
  CHECK(count(loop_drawing, "\\filldraw[fill=blue!10") == 1);
  for (const char* number : {"{2};", "{3};", "{5};"}) CHECK(has(loop_drawing, number));
  // Each point's velocity (red) and acceleration (green, dashed) to stated scales.
  CHECK(count(loop_drawing, "\\draw[-latex, red, thick]") == 4);
  CHECK(count(loop_drawing, "\\draw[-latex, green!50!black, thick, dashed]") == 4);
  CHECK(has(loop_drawing, "acceleration vectors (green, dashed): 1\\,cm = $"));
}

TEST_CASE("engine/printers/worked_solution: a joints-and-links document gives the slider blocks and the relative terms") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_1_joints.toml"));
  const MotionTable values = kinema::solve_motion(model, model.system.input.values);
  const std::string tex = document(model, &values, nullptr);
  CHECK(has(tex, "slider block & angle & $\\omega$ & $\\alpha$"));
  CHECK(has(tex, "2 & $45$ & $3.141$ & $0$"));  // block 2 turns with the crank
  // Example 4.1's relative velocity, relative acceleration and Coriolis term at B2.
  CHECK(has(tex, "B2 & $(-0.19514,\\ -0.19514)$ & $(-0.50033,\\ -0.50033)$ & $(1.2259,\\ -1.2259)$"));
}

namespace {

// "5", "2.5", "1\cdot 10^{-3}" as latex_number prints them.
double latex_value(const std::string& text) {
  const auto times = text.find("\\cdot 10^{");
  if (times == std::string::npos) return std::stod(text);
  return std::stod(text.substr(0, times)) * std::pow(10.0, std::stod(text.substr(times + 10)));
}

}  // namespace

TEST_CASE("engine/printers/worked_solution: polygons drawn to scale read off the analytic numbers") {
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.frames.empty()) continue;
    CAPTURE(std::string(name));
    const std::vector<double> inputs =
        model.system.input.values.empty() ? std::vector<double>{0.3} : model.system.input.values;
    const MotionTable values = kinema::solve_motion(model, inputs);
    const std::string tex = document(model, &values, nullptr, true);
    const kinema::PolygonBuilder builder(model);
    const kinema::OutputScale scale(model.system);
    std::size_t at = 0;
    int figures = 0;
    for (const kinema::MotionState& s : values) {
      const auto polygons = builder.polygons(s);
      if (!polygons) continue;
      for (const kinema::Polygon* polygon : {&polygons->first, &polygons->second}) {
        const std::string caption = polygon->order == 1 ? "Velocity polygon, scale 1\\,cm = $" : "Acceleration polygon, scale 1\\,cm = $";
        const auto begin = tex.find("\\begin{tikzpicture}[line cap=round, >=latex]", at);
        const auto stated = tex.find(caption, begin);
        REQUIRE(begin != std::string::npos);
        REQUIRE(stated != std::string::npos);
        at = stated + caption.size();
        const double per_cm = latex_value(tex.substr(at, tex.find("\\,", at) - at));
        const std::string figure = tex.substr(begin, stated - begin);
        ++figures;
        // The table under it: each arrow's read-off is its length on the figure times the
        // scale, written out as a number is in a table of lengths (7800, 78900: not
        // 7.89\cdot 10^{4} beside 4950; a read-off of 10000 was written 1\cdot 10^{4}).
        const auto rows = tex.find("\\midrule\n", at), end = tex.find("\\bottomrule", at);
        REQUIRE(rows < end);
        std::istringstream table(tex.substr(rows + 9, end - rows - 9));
        int read = 0;
        for (std::string row; std::getline(table, row);) {
          std::vector<std::string> cells;
          for (std::size_t from = 0, bar; from != std::string::npos; from = bar == std::string::npos ? bar : bar + 3) {
            bar = row.find(" & ", from);
            cells.push_back(row.substr(from, bar == std::string::npos ? bar : bar - from));
          }
          REQUIRE(cells.size() == 5);
          CAPTURE(row);
          const std::string cm = cells[2].substr(1, cells[2].size() - 2), value = cells[3].substr(1, cells[3].size() - 2);
          const double read_off = latex_value(value);
          CHECK(std::fabs(read_off - std::stod(cm) * per_cm) <= 5e-4 * std::fabs(read_off) + 1e-12 * per_cm);
          if (std::fabs(read_off) < 1e6) CHECK_FALSE(has(value, "\\cdot"));
          ++read;
        }
        CHECK(read >= 1);
        int labelled = 0;
        // \draw[->, style] (x1,y1) -- (x2,y2) node[...] {$label$};
        for (auto draw = figure.find("\\draw[->"); draw != std::string::npos; draw = figure.find("\\draw[->", draw + 1)) {
          const std::string line = figure.substr(draw, figure.find('\n', draw) - draw);
          double x1, y1, x2, y2;
          const auto coordinates = line.find("] (");
          REQUIRE(std::sscanf(line.c_str() + coordinates, "] (%lf,%lf) -- (%lf,%lf)", &x1, &y1, &x2, &y2) == 4);
          const auto label_at = line.find("{$");
          if (label_at == std::string::npos) continue;
          const std::string label = line.substr(label_at + 2, line.rfind("$}") - label_at - 2);
          const double read_off = std::hypot(x2 - x1, y2 - y1) * per_cm;  // output units
          CAPTURE(label);
          const kinema::PolygonArrow* arrow = nullptr;
          for (const kinema::PolygonArrow& a : polygon->arrows)
            if (a.latex == label) arrow = &a;
          REQUIRE(arrow);
          CHECK(read_off == doctest::Approx(arrow->formula_value / scale.length).epsilon(0.002 * per_cm / read_off));
          // An absolute arrow of a named point: its speed or acceleration from eval.
          for (std::size_t p = 0; p < model.system.points.size(); ++p) {
            const kinema::PointMotion& m = s.points[p];
            const std::string& point = model.system.points[p].name;
            if (label == "v_{" + point + "}") CHECK(read_off == doctest::Approx(m.speed() / scale.length).epsilon(0.002 * per_cm / read_off));
            if (label == "a_{" + point + "}")
              CHECK(read_off == doctest::Approx(m.acceleration_magnitude() / scale.length).epsilon(0.002 * per_cm / read_off));
          }
          ++labelled;
        }
        CHECK(labelled >= 1);
      }
    }
    CHECK(figures >= 2);
    // The three methods' table reads the same arrows off (v_A = 15710 mm/s, not
    // 1.571\cdot 10^{4} beside 8055).
    const auto methods = tex.find("\\subsubsection*{Three methods, one answer}");
    if (methods == std::string::npos) continue;
    const auto end = tex.find("\\bottomrule", methods);
    int read = 0;
    for (auto lever = tex.find(",\\ r = ", methods); lever < end; lever = tex.find(",\\ r = ", lever + 1), ++read) {
      const auto equals = tex.rfind(" = ", lever), unit = tex.rfind("\\,", lever);
      const std::string value = tex.substr(equals + 3, unit - equals - 3);
      CAPTURE(value);
      if (std::fabs(latex_value(value)) < 1e6) CHECK_FALSE(has(value, "\\cdot"));
    }
    CHECK(read >= 1);
  }
}

TEST_CASE("engine/printers/worked_solution: three methods, one answer for every joints-and-links sample") {
  int samples = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.plan) continue;
    CAPTURE(std::string(name));
    ++samples;
    const std::vector<double> inputs =
        model.system.input.values.empty() ? std::vector<double>{0.3} : model.system.input.values;
    const MotionTable values = kinema::solve_motion(model, inputs);
    const kinema::PolygonBuilder builder(model);
    const kinema::OutputScale scale(model.system);
    const std::string tex = document(model, &values, nullptr, true);
    CHECK(has(tex, "\\subsubsection*{Instant centres}"));
    CHECK(has(tex, "\\subsubsection*{Three methods, one answer}"));
    for (const kinema::MotionState& s : values) {
      const auto polygons = builder.polygons(s);
      const auto centres = kinema::instant_centres(kinema::MechanismGeometry(model), s);
      REQUIRE(polygons);
      REQUIRE(centres);
      const auto rows = kinema::three_methods(model.system, polygons->first, *centres);
      REQUIRE(!rows.empty());
      const double per_cm = kinema::polygon_units_per_cm(polygons->first, scale.length);
      for (const kinema::ThreeMethodsRow& row : rows) {
        CAPTURE(centres->bodies[row.body]);
        REQUIRE(row.from_centres);
        CHECK(*row.from_centres == doctest::Approx(row.solved).epsilon(1e-7).scale(1));
        REQUIRE(row.from_polygon);
        // Read off to 0.01 cm: within half of that, over the link's length.
        CHECK(std::fabs(*row.from_polygon - row.solved) <= 0.005 * per_cm / row.lever * (1 + 1e-9));
      }
    }
  }
  CHECK(samples >= 6);
  // A vector-loop file: its links known by the points on them (the four-bar: 2, 3, 4).
  const kinema::Model loops = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable one = kinema::solve_motion(loops, {40 * kDeg});
  const std::string tex = document(loops, &one, nullptr, true);
  CHECK(has(tex, "\\subsubsection*{Three methods, one answer}"));
  const auto polygons = kinema::PolygonBuilder(loops).polygons(one[0]);
  const auto centres = kinema::instant_centres(kinema::MechanismGeometry(loops), one[0]);
  REQUIRE(polygons);
  REQUIRE(centres);
  const auto rows = kinema::three_methods(loops.system, polygons->first, *centres);
  REQUIRE(rows.size() == 3);
  const double per_cm = kinema::polygon_units_per_cm(polygons->first, kinema::OutputScale(loops.system).length);
  for (const kinema::ThreeMethodsRow& row : rows) {
    REQUIRE(row.from_centres);
    REQUIRE(row.from_polygon);
    CHECK(*row.from_centres == doctest::Approx(row.solved).epsilon(1e-9));
    CHECK(std::fabs(*row.from_polygon - row.solved) <= 0.005 * per_cm / row.lever * (1 + 1e-9));
  }
}

TEST_CASE("engine/printers/worked_solution: the points' paths (coupler curves) over the run") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, 40 * kDeg));
  const std::string tex = document(model, nullptr, &sweep, true);
  const auto paths = tex.find("Paths of the points over the run");
  REQUIRE(paths != std::string::npos);
  CHECK(has(tex.substr(paths), "axis equal image"));
  // The coupler point P's curve: every row's position, in mm, in order.
  const auto legend = tex.find("\\addlegendentry{P}", paths);
  REQUIRE(legend != std::string::npos);
  const auto begin = tex.rfind("coordinates {", legend);
  REQUIRE(begin > paths);
  std::istringstream in(tex.substr(begin + 13, legend - begin - 13));
  std::size_t row = 0;
  char open, comma, close;
  double x, y;
  const std::size_t p = 2;
  REQUIRE(model.system.points[p].name == "P");
  while (in >> open >> x >> comma >> y >> close && row < sweep.size()) {
    CHECK(x == doctest::Approx(sweep.point(row, p).position[0] * 1000).epsilon(1e-6));
    CHECK(y == doctest::Approx(sweep.point(row, p).position[1] * 1000).epsilon(1e-6));
    ++row;
  }
  CHECK(row == sweep.size());
}

// Every path inside its box with room to spare: the crank-shaper's ram C slides along the
// line y = h, the top of the paths' extent, and was drawn on the axis's frame.
TEST_CASE("engine/printers/worked_solution: the points' paths are inside their box, none on its frame") {
  for (const char* name : {"crank_shaper.toml", "four_bar.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, model.system.input.values.at(0)));
    const std::string tex = document(model, nullptr, &sweep, true);
    const auto paths = tex.find("Paths of the points over the run");
    REQUIRE(paths != std::string::npos);
    const auto axis = tex.find("\\begin{axis}[", paths);
    const std::string options = tex.substr(axis, tex.find("]\n", axis) - axis);
    const auto limit = [&](const std::string& key) {
      const auto at = options.find(", " + key + "=");
      REQUIRE(at != std::string::npos);
      return std::stod(options.substr(at + key.size() + 3));
    };
    const double box[2][2] = {{limit("xmin"), limit("xmax")}, {limit("ymin"), limit("ymax")}};
    const double room = 0.01 * std::max(box[0][1] - box[0][0], box[1][1] - box[1][0]);
    std::size_t points = 0;
    const auto end = tex.find("\\end{axis}", axis);
    for (auto at = tex.find("coordinates {", axis); at < end; at = tex.find("coordinates {", at + 1)) {
      std::istringstream in(tex.substr(at + 13, tex.find('}', at) - at - 13));
      char open, comma, close;
      double xy[2];
      while (in >> open >> xy[0] >> comma >> xy[1] >> close) {
        for (const int k : {0, 1}) {
          CHECK(xy[k] >= box[k][0] + room);
          CHECK(xy[k] <= box[k][1] - room);
        }
        ++points;
      }
    }
    CHECK(points >= 2 * sweep.size());
  }
}

// A curve is cut at values far past its own typical size (a pole). Judged over the whole
// axis, a point a thousand times faster than eleven others (fewer than a tenth of the
// values) was past the axis's limit everywhere and vanished from the speeds plot.
TEST_CASE("engine/printers/worked_solution: a plot's gaps are judged curve by curve") {
  std::string points = "[points]\n";
  for (int i = 1; i <= 11; ++i) points += "Q" + std::to_string(i) + " = \"a*exp(I*theta2) + " + std::to_string(i) + "*b*exp(I*theta3)\"\n";
  points += "H = \"1e5*a*cos(theta2)\"\n";
  const kinema::Model model = kinema::load_model(kinema_test::write_temporary(
      "fast_point.toml", kinema_test::replaced("[points]\n", points)));
  const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, 40 * kDeg));
  const std::string tex = document(model, nullptr, &sweep, true);
  std::size_t curves = 0;
  for (auto legend = tex.find("\\addlegendentry{H}"); legend != std::string::npos;
       legend = tex.find("\\addlegendentry{H}", legend + 1), ++curves) {
    const auto begin = tex.rfind("coordinates {", legend);
    const std::string curve = tex.substr(begin, legend - begin);
    CAPTURE(curve.substr(0, 200));
    CHECK(count(curve, "nan") <= 2);  // the turn's wrap, not the curve
    CHECK(count(curve, ")") > sweep.size() / 2);
  }
  CHECK(curves >= 2);  // its path and its speed
}

TEST_CASE("engine/printers/worked_solution: textbook scaffolding - statement, numbered figures and equations, answers boxed") {
  for (const std::string sample : kinema_test::kSamples) {
    CAPTURE(sample);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const MotionTable values = kinema::solve_motion(model, model.system.input.values);
    const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, model.system.input.values.at(0)));
    const std::string tex = document(model, &values, &sweep);
    const kinema::ConstraintSystem& system = model.system;
    // "Given ... Find ...", naming the driver and every unknown.
    const auto given = tex.find("\\textbf{Given:}"), find = tex.find("\\textbf{Find:}");
    REQUIRE(given != std::string::npos);
    REQUIRE(find != std::string::npos);
    CHECK(given < tex.find("\\subsection*{Data}"));
    const std::string statement = tex.substr(given, tex.find("\n\n", find) - given);
    CHECK(has(statement, "$" + kinema::to_latex(system.input.symbol)));
    for (const kinema::Coordinate& q : system.unknowns) {
      CHECK(has(statement, "$" + kinema::to_latex(q.rate) + "$"));
      CHECK(has(statement, "$" + kinema::to_latex(q.second_rate) + "$"));
    }
    // One table of given data.
    CHECK(count(tex, "\\subsection*{Data}") == 1);
    // Every drawing and plot numbered.
    CHECK(count(tex, "\\end{tikzpicture}") == count(tex, "\\refstepcounter{figure}{\\small Figure~\\thefigure: "));
    // The loop equations numbered, and the text cites them.
    if (!kinema::is_driven_chain(system)) {
      for (std::size_t i = 1; i <= system.equations.size(); ++i) CHECK(count(tex, "\\tag{" + std::to_string(i) + "}") == 1);
      CHECK(has(tex, "Differentiating the loop equations (1)"));
    }
    // The answers boxed: each unknown's rate and second rate, each point's speed and acceleration.
    const std::string results = tex.substr(tex.find("\\subsection*{Results"));
    if (!system.unknowns.empty()) {
      CHECK(count(results, "\\boxed{") >= 2 * system.unknowns.size() + 2 * system.points.size());
      for (const kinema::Coordinate& q : system.unknowns) CHECK(has(results, kinema::to_latex(q.rate) + " = \\boxed{"));
    }
  }
}
