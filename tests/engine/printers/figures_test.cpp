// The worked solution's figures read back from its TikZ: slider blocks on the guides
// the loop equations put them on, instant centres, plots and polygons as drawn.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/printers/latex/label_boxes.hpp"
#include "engine/printers/printer.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/analysis/instant_centres.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/analysis/polygons.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::MotionTable;
using kinema::PrintKind;
using Point = std::complex<double>;

namespace {

std::string document(const kinema::Model& model, const MotionTable* values, const MotionTable* sweep = nullptr) {
  const kinema::Printer* printer = kinema::find_printer(PrintKind::document, "latex");
  REQUIRE(printer != nullptr);
  kinema::PrintJob job{model, values, sweep};
  job.fragment = true;
  std::ostringstream out;
  kinema::print_view(*printer, out, job);
  return out.str();
}

// The worked solution at the file's first value (or 0), with its plots over the range.
std::string document_at_first_value(const kinema::Model& model) {
  const double first = model.system.input.values.empty() ? 0.0 : model.system.input.values.front();
  const MotionTable values = kinema::solve_motion(model, {first});
  const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, first));
  return document(model, &values, &sweep);
}

// The math after the last " {$" of a line, up to its "$}".
std::string node_text(const std::string& line) {
  const auto open = line.rfind(" {$");
  REQUIRE(open != std::string::npos);
  return line.substr(open + 2, line.rfind("$}") + 1 - (open + 2));
}

// Every "(x,y)" of a line, in order.
std::vector<Point> coordinates(const std::string& line) {
  std::vector<Point> found;
  for (std::size_t at = line.find('('); at != std::string::npos; at = line.find('(', at + 1)) {
    double x, y;
    char close;
    if (std::sscanf(line.c_str() + at, "(%lf,%lf%c", &x, &y, &close) == 3 && close == ')') found.push_back({x, y});
  }
  return found;
}

std::vector<std::string> lines_starting(const std::string& figure, const std::string& start) {
  std::vector<std::string> found;
  std::istringstream in(figure);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(start, 0) == 0) found.push_back(line);
  return found;
}

// The mechanism's drawing: the first tikzpicture with its plain options.
std::string mechanism_figure(const std::string& tex, std::size_t from = 0) {
  const auto begin = tex.find("\\begin{tikzpicture}[line cap=round]\n", from);
  REQUIRE(begin != std::string::npos);
  return tex.substr(begin, tex.find("\\end{tikzpicture}", begin) - begin);
}

struct Line {
  Point a, b;
};

double distance_to_line(Point p, const Line& l) {
  const Point d = (l.b - l.a) / std::abs(l.b - l.a);
  return std::abs(std::imag((p - l.a) * std::conj(d)));
}

bool within(Point p, const Line& l, double slack) {
  const Point d = (l.b - l.a) / std::abs(l.b - l.a);
  const double t = std::real((p - l.a) * std::conj(d));
  return t >= -slack && t <= std::abs(l.b - l.a) + slack;
}

struct Block {
  Point centre;
  double degrees = 0;
};

struct Drawing {
  std::vector<Line> guides, bars;
  std::vector<Block> blocks;
  std::vector<std::pair<std::string, Point>> points;
  std::vector<Point> pivots;
};

Drawing read_drawing(const std::string& figure) {
  Drawing d;
  for (const std::string& line : lines_starting(figure, "\\draw[gray] ")) {
    const auto c = coordinates(line);
    if (c.size() == 2) d.guides.push_back({c[0], c[1]});
  }
  for (const std::string& line : lines_starting(figure, "\\draw[very thick, blue!70!black] ")) {
    const auto c = coordinates(line);
    for (std::size_t k = 1; k < c.size(); ++k) d.bars.push_back({c[k - 1], c[k]});
  }
  for (const std::string& line : lines_starting(figure, "\\draw[thick, fill=white, rotate around={")) {
    Block b;
    double x, y;
    REQUIRE(std::sscanf(line.c_str(), "\\draw[thick, fill=white, rotate around={%lf:(%lf,%lf)}]", &b.degrees, &x, &y) == 3);
    b.centre = {x, y};
    d.blocks.push_back(b);
  }
  for (const std::string& line : lines_starting(figure, "\\fill (")) {
    const auto c = coordinates(line);
    const auto open = line.rfind('{'), close = line.rfind('}');
    if (!c.empty() && open != std::string::npos) d.points.push_back({line.substr(open + 1, close - open - 1), c[0]});
  }
  for (const std::string& line : lines_starting(figure, "\\fill[pattern=north east lines] ")) d.pivots.push_back(coordinates(line)[0]);
  return d;
}

Point drawn_point(const Drawing& d, const std::string& name) {
  for (const auto& [n, at] : d.points)
    if (n == name) return at;
  FAIL("no point " << name << " drawn");
  return {};
}

}  // namespace

TEST_CASE("engine/printers/figures: every slider block on the guide its loop equation puts it on") {
  // The point that slides on a fixed guide in each vector-loop sample, and the guide's line.
  struct Case {
    const char* sample;
    std::vector<const char*> sliding;  ///< Named points on fixed guides.
  };
  for (const Case& c : {Case{"crank_shaper.toml", {"C"}}, Case{"slider_crank.toml", {"B"}},
                        Case{"problem_4_4_six_bar.toml", {"F"}}, Case{"example_4_2_r_rtr_rrt.toml", {"E"}},
                        Case{"problem_3_22_six_bar_sliders.toml", {"B", "D"}}, Case{"example_4_1_r_trr.toml", {}}}) {
    CAPTURE(std::string(c.sample));
    const kinema::Model model = kinema::load_model(kinema_test::sample(c.sample));
    const double input = model.system.input.values.empty() ? 0.5 : model.system.input.values.front();
    const MotionTable values = kinema::solve_motion(model, {input});
    REQUIRE(values.status(0) == kinema::Status::ok);
    const Drawing d = read_drawing(mechanism_figure(document(model, &values)));
    REQUIRE_FALSE(d.blocks.empty());
    // Every block's centre on a drawn guide (hatched line) or on the link that carries it,
    // turned along it.
    for (const Block& b : d.blocks) {
      CAPTURE(b.centre);
      bool on = false;
      for (const auto* lines : {&d.guides, &d.bars})
        for (const Line& l : *lines) {
          const double along = std::remainder(b.degrees - std::arg(l.b - l.a) * 180 / M_PI, 180.0);
          on = on || (distance_to_line(b.centre, l) < 0.02 && within(b.centre, l, 0.02) && std::fabs(along) < 0.1);
        }
      CHECK(on);
    }
    // Drawing units per metre, from the point furthest from the origin (drawn at (0,0)).
    double cm = 0, furthest = 0;
    for (std::size_t p = 0; p < model.system.points.size(); ++p) {
      const Point real(values[0].points[p].position[0], values[0].points[p].position[1]);
      if (std::abs(real) <= furthest) continue;
      furthest = std::abs(real);
      cm = std::abs(drawn_point(d, model.system.points[p].name)) / furthest;
    }
    REQUIRE(cm > 0);
    // The guide is the constraint's line: the sliding point, solved at two other inputs,
    // lies on the hatched line its block is drawn on.
    const MotionTable others = kinema::solve_motion(model, {input + 0.4, input + 1.3});
    for (const char* name : c.sliding) {
      CAPTURE(std::string(name));
      std::size_t p = 0;
      while (model.system.points[p].name != name) ++p;
      const Point at = drawn_point(d, name);
      bool block = false;
      for (const Block& b : d.blocks) block = block || std::abs(b.centre - at) < 0.02;
      CHECK(block);
      const Line* guide = nullptr;
      for (const Line& l : d.guides)
        if (distance_to_line(at, l) < 0.02) guide = &l;
      REQUIRE(guide);
      for (std::size_t k = 0; k < 2; ++k) {
        REQUIRE(others.status(k) == kinema::Status::ok);
        const Point moved = Point(others[k].points[p].position[0], others[k].points[p].position[1]) * cm;
        CHECK(std::abs(moved - at) > 0.05);  // it did move
        CHECK(distance_to_line(moved, *guide) < 0.02);
      }
    }
  }
  // Example 4.1: the block at B on crank 1 (drawn from A through B), ground at A and C only.
  const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_1_r_trr.toml"));
  const MotionTable values = kinema::solve_motion(model, model.system.input.values);
  const std::string figure = mechanism_figure(document(model, &values));
  const Drawing d = read_drawing(figure);
  const Point B = drawn_point(d, "B");
  REQUIRE(d.blocks.size() == 1);
  CHECK(std::abs(d.blocks[0].centre - B) < 0.02);
  bool crank = false;
  for (const Line& l : d.bars) crank = crank || (std::abs(l.a) < 0.02 && distance_to_line(B, l) < 0.02 && within(B, l, 0));
  CHECK(crank);
  const double AC_cm = 0.1 * std::abs(B) / std::abs(Point(values[0].points[0].position[0], values[0].points[0].position[1]));
  REQUIRE(d.pivots.size() == 2);
  for (const Point& p : d.pivots) CHECK((std::abs(p) < 0.02 || std::abs(p - AC_cm) < 0.02));
}

namespace {

// The text of the figure after `heading`: its first tikzpicture.
std::string figure_after(const std::string& tex, const std::string& heading, std::size_t from = 0) {
  const auto at = tex.find(heading, from);
  if (at == std::string::npos) return "";
  const auto begin = tex.find("\\begin{tikzpicture}", at);
  return tex.substr(begin, tex.find("\\end{tikzpicture}", begin) - begin);
}

std::string centre_label(const kinema::InstantCentres& c, std::size_t a, std::size_t b) {
  return "$I_{" + c.bodies[a] + c.bodies[b];
}

}  // namespace

TEST_CASE("engine/printers/figures: instant centres, every one listed and drawn or pointed to") {
  for (const char* name : {"four_bar.toml", "crank_shaper.toml", "problem_4_4_joints.toml", "triple_rocker_circuit.toml",
                           "example_4_2_joints.toml", "example_4_1_joints.toml", "problem_3_22_joints.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const double input = model.system.input.values.empty() ? 0.5 : model.system.input.values.front();
    const MotionTable values = kinema::solve_motion(model, {input});
    const auto centres = kinema::instant_centres(kinema::MechanismGeometry(model), values[0]);
    REQUIRE(centres);
    const std::string tex = document(model, &values);
    const auto heading = tex.find("\\subsubsection*{Instant centres}");
    REQUIRE(heading != std::string::npos);
    const std::string figure = figure_after(tex, "\\subsubsection*{Instant centres}");
    const std::string table = tex.substr(tex.find("centre & $x$ & $y$ & found by", heading));
    const std::string rows = table.substr(0, table.find("\\bottomrule"));
    const std::size_t n = centres->bodies.size();
    // n(n-1)/2 rows, one per pair.
    long listed = 0;
    for (auto row = rows.find("\n$I_{"); row != std::string::npos; row = rows.find("\n$I_{", row + 1)) ++listed;
    CHECK(listed == static_cast<long>(n * (n - 1) / 2));
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) CHECK(rows.find(centre_label(*centres, a, b) + "}$ &") != std::string::npos);
    // Figure units per metre, from the drawn centre furthest from the origin.
    double cm = 0, furthest = 0;
    for (const std::string& line : lines_starting(figure, "\\filldraw[red!75!black, fill=white] ")) {
      const Point drawn = coordinates(line)[0];
      for (const kinema::InstantCentre& c : centres->centres)
        if (line.find(centre_label(*centres, c.a, c.b) + "}$}") != std::string::npos && std::abs(c.at) > furthest) {
          furthest = std::abs(c.at);
          cm = std::abs(drawn) / furthest;
        }
    }
    REQUIRE(cm > 0);
    const auto arrows = lines_starting(figure, "\\draw[->, red!75!black");
    for (const kinema::InstantCentre& c : centres->centres) {
      const std::string label = centre_label(*centres, c.a, c.b);
      CAPTURE(label);
      bool drawn = false;
      for (const std::string& line : lines_starting(figure, "\\filldraw[red!75!black, fill=white] "))
        if (line.find(label + "}$}") != std::string::npos) {
          drawn = true;
          CHECK(std::abs(coordinates(line)[0] - c.at * cm) < 0.02);
        }
      for (const std::string& line : arrows) {
        if (line.find(label + "}$}") == std::string::npos && line.find(label + "}\\to\\infty$}") == std::string::npos) continue;
        drawn = true;
        const auto ends = coordinates(line);  // from, to, then where its label stands
        REQUIRE(ends.size() >= 2);
        const Point along = ends[1] - ends[0];
        // At infinity: along its direction, from its joint; off the figure: towards it.
        const Point towards = c.at_infinity ? c.at : c.at * cm - ends[1];
        CHECK(std::fabs(std::arg(along / towards)) < 0.02);
        if (c.at_infinity && c.seen_from) CHECK(std::abs(ends[0] - *c.seen_from * cm) < 0.02);
      }
      CHECK(drawn);
    }
    // Kennedy lines in every figure with four bodies or more.
    if (n >= 4) CHECK(figure.find("\\draw[gray!60, dashed]") != std::string::npos);
  }
  // Example 4.2: the arrow of I05 (slider 5 on the ground) starts at E, not at slider 2.
  const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_2_joints.toml"));
  const MotionTable values = kinema::solve_motion(model, model.system.input.values);
  const auto centres = kinema::instant_centres(kinema::MechanismGeometry(model), values[0]);
  REQUIRE(centres);
  const kinema::InstantCentre* i05 = centres->find(0, 5);
  REQUIRE(i05);
  REQUIRE(i05->seen_from);
  for (std::size_t p = 0; p < model.system.points.size(); ++p)
    if (model.system.points[p].name == "E")
      CHECK(std::abs(*i05->seen_from - Point(values[0].points[p].position[0], values[0].points[p].position[1])) < 1e-9);
  // The crank-shaper: no bar from C to O4 (the ram's vector is no link); the ram a block.
  const kinema::Model shaper = kinema::load_model(kinema_test::sample("crank_shaper.toml"));
  const MotionTable shaper_values = kinema::solve_motion(shaper, shaper.system.input.values);
  const std::string figure = figure_after(document(shaper, &shaper_values), "\\subsubsection*{Instant centres}");
  const Drawing d = read_drawing(figure);
  REQUIRE(d.blocks.size() == 2);  // blocks at A and C
  for (const Block& ram : d.blocks) {
    if (std::fabs(std::sin(ram.degrees * M_PI / 180)) > 1e-6) continue;  // the block in the rocker's slot
    for (const Line& bar : d.bars)
      CHECK_FALSE((std::abs(bar.a) < 0.02 && std::abs(bar.b - ram.centre) < 0.02));
  }
}

namespace {

struct Curve {
  std::string options;
  std::vector<Point> points;  ///< nan where there is a gap
};

// The \addplot curves of each axis after "\subsection*{Over the input range}".
std::vector<std::vector<Curve>> plotted_axes(const std::string& tex) {
  std::vector<std::vector<Curve>> axes;
  const auto start = tex.find("\\subsection*{Over the input range}");
  REQUIRE(start != std::string::npos);
  for (auto at = tex.find("\\begin{axis}", start); at != std::string::npos; at = tex.find("\\begin{axis}", at + 1)) {
    const std::string axis = tex.substr(at, tex.find("\\end{axis}", at) - at);
    if (axis.find("axis equal image") != std::string::npos) continue;  // the points' paths
    auto& curves = axes.emplace_back();
    for (const std::string& line : lines_starting(axis, "\\addplot+[")) {
      Curve c;
      c.options = line.substr(10, line.find("] coordinates") - 10);
      for (auto p = line.find(" ("); p != std::string::npos; p = line.find(" (", p + 1)) {
        const auto comma = line.find(',', p), close = line.find(')', p);
        const std::string x = line.substr(p + 2, comma - p - 2), y = line.substr(comma + 1, close - comma - 1);
        c.points.push_back({x == "nan" ? NAN : std::stod(x), y == "nan" ? NAN : std::stod(y)});
      }
      curves.push_back(c);
    }
  }
  return axes;
}

}  // namespace

TEST_CASE("engine/printers/figures: plots unwrapped, without a line back to the start, curves told apart") {
  for (const char* name : {"example_4_1_joints.toml", "rssr_spatial_four_bar.toml", "four_bar.toml", "crank_shaper.toml",
                           "problem_4_4_six_bar.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const std::string tex = document_at_first_value(model);
    const auto axes = plotted_axes(tex);
    REQUIRE(axes.size() >= 3);
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const auto& curves = axes[a];
      for (std::size_t k = 0; k < curves.size(); ++k) {
        // Along a curve's drawn stretch x only grows (no line back to 0 at 360 deg) and an
        // angle (the first axis: angles) moves by less than 90 deg a step: no jump of 360.
        const auto& pts = curves[k].points;
        for (std::size_t i = 1; i < pts.size(); ++i) {
          if (!std::isfinite(pts[i].imag()) || !std::isfinite(pts[i - 1].imag())) continue;
          CHECK(pts[i].real() > pts[i - 1].real());
          if (a == 0) CHECK(std::fabs(pts[i].imag() - pts[i - 1].imag()) < 90);
        }
        // Each curve of an axis its own dash pattern and marks.
        for (std::size_t j = 0; j < k; ++j) CHECK(curves[j].options != curves[k].options);
        CHECK(curves[k].options.find("mark=none") == std::string::npos);
      }
    }
  }
  // Example 4.1 as joints: phi3 from its file value (about 58.6 deg), not 360-420 deg.
  const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_1_joints.toml"));
  const double first = model.system.input.values.front();
  const MotionTable sweep = kinema::solve_motion(model, kinema::plot_range(model.system, first));
  const MotionTable values = kinema::solve_motion(model, {first});
  const auto axes = plotted_axes(document(model, &values, &sweep));
  for (const Curve& c : axes[0])
    for (const Point& p : c.points)
      if (std::isfinite(p.imag())) CHECK(std::fabs(p.imag()) < 360);
}

TEST_CASE("engine/printers/figures: polygons fill the width at a round scale, every vertex lettered, no label on another") {
  for (const char* name : {"crank_shaper.toml", "problem_4_4_joints.toml", "four_bar.toml", "example_4_2_r_rtr_rrt.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const MotionTable values = kinema::solve_motion(model, model.system.input.values.empty() ? std::vector<double>{0.5}
                                                                                        : model.system.input.values);
    const auto polygons = kinema::PolygonBuilder(model).polygons(values[0]);
    REQUIRE(polygons);
    const std::string tex = document(model, &values);
    std::size_t at = tex.find("\\subsubsection*{Velocity and acceleration polygons}");
    REQUIRE(at != std::string::npos);
    for (const kinema::Polygon* polygon : {&polygons->first, &polygons->second}) {
      const auto begin = tex.find("\\begin{tikzpicture}[line cap=round, >=latex]", at);
      const auto end = tex.find("\\end{tikzpicture}", begin);
      const std::string figure = tex.substr(begin, end - begin);
      const auto stated = tex.find("scale 1\\,cm = $", end) + 15;
      at = stated;
      // A round scale: 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten.
      double per_cm = std::stod(tex.substr(stated, tex.find_first_of("\\$", stated) - stated));
      const auto power = tex.find("\\cdot 10^{", stated);
      if (power < tex.find('$', stated)) per_cm *= std::pow(10.0, std::stod(tex.substr(power + 10)));
      const double mantissa = per_cm / std::pow(10.0, std::floor(std::log10(per_cm) + 1e-12));
      bool round = false;
      for (double m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0}) round = round || std::fabs(mantissa - m) < 1e-9;
      CHECK(round);
      // The labels: the vertices' nodes, the arrows' at their pos and shift.
      std::vector<std::pair<std::string, Point>> labels;
      double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
      for (const std::string& line : lines_starting(figure, "\\node[font=\\small, inner sep=0pt] at ")) {
        const auto open = line.rfind('{');
        labels.push_back({line.substr(open + 1, line.rfind('}') - open - 1), coordinates(line)[0]});
      }
      for (const std::string& line : lines_starting(figure, "\\draw[->")) {
        const auto c = coordinates(line);
        for (const Point& p : c) {
          min_x = std::min(min_x, p.real()), max_x = std::max(max_x, p.real());
          min_y = std::min(min_y, p.imag()), max_y = std::max(max_y, p.imag());
        }
        double pos, xshift, yshift;
        const auto node = line.find("node[pos=");
        if (node == std::string::npos) continue;
        REQUIRE(std::sscanf(line.c_str() + node, "node[pos=%lf, xshift=%lfcm, yshift=%lfcm", &pos, &xshift, &yshift) == 3);
        const auto open = line.find("{$", node);
        labels.push_back({line.substr(open), c[0] + (c[1] - c[0]) * pos + Point(xshift, yshift)});
      }
      // Filling the width: 12 cm across or 7 cm high at most, more than 2/3 of one of them.
      CHECK(max_x - min_x <= 12.01);
      CHECK(max_y - min_y <= 7.01);
      CHECK((max_x - min_x > 8 || max_y - min_y > 5));
      // Every vertex lettered.
      for (const kinema::PolygonVertex& v : polygon->vertices) {
        std::string letter = v.name;
        letter[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(letter[0])));
        bool lettered = false;
        for (const auto& [text, where] : labels) lettered = lettered || text.find(letter) != std::string::npos;
        CAPTURE(letter);
        CHECK(lettered);
      }
      // No label on another: their centres apart by more than a line's height, or side by side.
      for (std::size_t i = 0; i < labels.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) {
          CAPTURE(labels[i].first);
          CAPTURE(labels[j].first);
          const Point d = labels[i].second - labels[j].second;
          CHECK((std::fabs(d.imag()) >= 0.3 || std::fabs(d.real()) >= 0.35));
        }
    }
  }
}

TEST_CASE("engine/printers/figures: the drawing's axes, angle arcs, numbered blocks and labels off the hatching") {
  for (const char* name : {"crank_shaper.toml", "slider_crank.toml", "problem_4_4_six_bar.toml", "example_4_2_r_rtr_rrt.toml",
                           "example_4_1_r_trr.toml", "four_bar.toml", "problem_3_22_joints.toml", "example_4_2_joints.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const MotionTable values = kinema::solve_motion(model, model.system.input.values.empty() ? std::vector<double>{0.5}
                                                                                        : model.system.input.values);
    const std::string figure = mechanism_figure(document(model, &values));
    const Drawing d = read_drawing(figure);
    // x and y from the origin.
    const auto x_axis = lines_starting(figure, "\\draw[->, gray] (0,0) -- (1.2,0) node[");
    const auto y_axis = lines_starting(figure, "\\draw[->, gray] (0,0) -- (0,1.2) node[");
    REQUIRE(x_axis.size() == 1);
    REQUIRE(y_axis.size() == 1);
    CHECK(node_text(x_axis[0]) == "$x$");
    CHECK(node_text(y_axis[0]) == "$y$");
    // Every block numbered: a circled number within one number's height of the block as
    // turned (a label's reach, as for every label; a fixed 0.6 cm from the block's centre
    // held only while numbers stood at fixed offsets, with arrows and letters under them),
    // off its guide's hatching.
    const auto numbers = lines_starting(figure, "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at ");
    for (const Block& b : d.blocks) {
      const Point along = std::polar(1.0, b.degrees * M_PI / 180);
      const std::vector<Point> corners = kinema::parallelogram(b.centre - along * Point(0.35, 0.2), along * 0.7, along * Point(0, 0.4));
      bool numbered = false;
      for (const std::string& line : numbers) {
        const std::string text = line.substr(line.rfind('{') + 1, line.rfind('}') - line.rfind('{') - 1);
        const kinema::LabelBox number = kinema::circled(kinema::label_box(text, 8, 1, coordinates(line)[0]));
        numbered = numbered || number.distance_to_area(corners) <= kinema::label_reach(number) + 0.002;
      }
      CAPTURE(b.centre);
      CHECK(numbered);
    }
    // No number on a guide's hatching (0.15 cm on one side of its line).
    for (const std::string& line : numbers) {
      const Point at = coordinates(line)[0];
      CAPTURE(line);
      for (const Line& g : d.guides)
        if (within(at, g, 0)) CHECK(distance_to_line(at, g) > 0.25);
    }
    if (model.system.plan) continue;
    // Each angle that is a coordinate of a link vector drawn: an arc to its solved value.
    std::vector<double> arcs;
    for (const std::string& line : lines_starting(figure, "\\draw[->, gray] (")) {
      const auto at = line.find("end angle=");
      if (at != std::string::npos) arcs.push_back(std::stod(line.substr(at + 10)));
    }
    const kinema::MechanismGeometry geometry(model);
    for (const kinema::DrawingSegment& g : geometry.segments(values[0])) {
      if (g.coordinate < 0 || g.kind != kinema::DrawingSegment::Kind::link) continue;
      const double degrees = std::remainder(g.angle * 180 / M_PI, 360.0);
      if (std::fabs(degrees) < 1) continue;
      bool drawn = false;
      for (double a : arcs) drawn = drawn || std::fabs(a - degrees) < 0.01;
      CAPTURE(degrees);
      CHECK(drawn);
    }
  }
}

// Issue 32: every arrow of the drawing is labelled at its tip (v_B, a_B), and each bar is
// drawn as a body (a light band under its centre line), for every planar sample.
TEST_CASE("figures: every velocity and acceleration arrow is labelled, every bar has its body") {
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.frames.empty()) continue;  // spatial chains are drawn in projection elsewhere
    CAPTURE(name);
    const MotionTable values = kinema::solve_motion(model, {model.system.input.values.front()});
    const std::string figure = mechanism_figure(document(model, &values));
    const auto velocities = lines_starting(figure, "\\draw[-latex, red, thick] ");
    const auto accelerations = lines_starting(figure, "\\draw[-latex, green!50!black, thick, dashed] ");
    CHECK(!velocities.empty());
    for (const std::string& line : velocities) {
      CAPTURE(line);
      CHECK(line.find(" node[") != std::string::npos);
      CHECK(line.find("{$\\mathbf{v}_{") != std::string::npos);
    }
    for (const std::string& line : accelerations) {
      CAPTURE(line);
      CHECK(line.find("{$\\mathbf{a}_{") != std::string::npos);
    }
    const auto bars = lines_starting(figure, "\\draw[very thick, blue!70!black] ");
    const auto bodies = lines_starting(figure, "\\draw[line width=6pt, line cap=round, line join=round, blue!12] ");
    REQUIRE(bodies.size() == bars.size());
    for (std::size_t k = 0; k < bars.size(); ++k) CHECK(coordinates(bars[k]) == coordinates(bodies[k]));
  }
}

// Issue 32: a joints-and-links drawing had no angle arcs; each link whose angle is a
// coordinate (the driver's, the unknowns') now has one at its first joint, from the x
// direction to the coordinate's value, labelled with its symbol.
TEST_CASE("figures: a joints-and-links drawing marks each link angle that is a coordinate with its arc") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_joints.toml"));
  const MotionTable values = kinema::solve_motion(model, {model.system.input.values.front()});
  const std::string figure = mechanism_figure(document(model, &values));
  std::vector<double> drawn;
  for (const std::string& line : lines_starting(figure, "\\draw[->, gray] ")) {
    const auto at = line.find("arc[start angle=0, end angle=");
    if (at == std::string::npos) continue;  // the axes
    drawn.push_back(std::stod(line.substr(at + 29)));
  }
  const auto wrapped = [](double radians) { return std::remainder(radians * 180 / M_PI, 360.0); };
  std::vector<double> expected = {wrapped(values.input(0))};
  for (std::size_t i = 0; i < model.system.unknowns.size(); ++i)
    if (model.system.unknowns[i].dimension == kinema::Dimension::angle) expected.push_back(wrapped(values.q(0)[Eigen::Index(i)]));
  REQUIRE(drawn.size() == expected.size());  // phi, phi2, phi3, phi4
  std::sort(drawn.begin(), drawn.end());
  std::sort(expected.begin(), expected.end());
  for (std::size_t k = 0; k < drawn.size(); ++k) CHECK(drawn[k] == doctest::Approx(expected[k]).epsilon(1e-3));
  for (const char* symbol : {"{$\\phi$}", "{$\\phi_{2}$}", "{$\\phi_{3}$}", "{$\\phi_{4}$}"}) {
    CAPTURE(symbol);
    CHECK(figure.find(symbol) != std::string::npos);
  }
}

namespace {

// A label read back from a figure: its box (from its text at its font, as the printer
// estimates it) and what it names, a point (from == to) or an arrow.
struct ReadLabel {
  std::string text;
  kinema::LabelBox box;
  Point from, to;
  bool led = false;  // joined to its point by a leader from..to: from beside the point, to beside the label
  Point leader_from{}, leader_to{};
};


// The centre of a label at `at` by a TikZ placement (above right, right, ...), with
// inner sep 1/3 em of its 8 pt font: what the printer wrote before it stated each place.
Point anchored(Point at, const std::string& line, const kinema::LabelBox& box) {
  const double sep = 8.0 / 3 * 2.54 / 72.27;
  const Point x(box.half_width + sep, 0), y(0, box.half_height + sep);
  if (line.find("node[above right") != std::string::npos) return at + x + y;
  if (line.find("node[above") != std::string::npos) return at + y;
  if (line.find("node[below") != std::string::npos) return at - y;
  if (line.find("node[right") != std::string::npos) return at + x;
  if (line.find("node[left") != std::string::npos) return at - x;
  FAIL("no place for the label of " << line);
  return at;
}

// Each label on none other nor on a dot, pivot or block (`blocks`: each one's corners, as
// turned), and within a label's height of what it names.
void check_labels(const std::vector<ReadLabel>& labels, const std::vector<kinema::LabelBox>& dots,
                  const std::vector<std::vector<Point>>& blocks = {}) {
  for (std::size_t i = 0; i < labels.size(); ++i) {
    CAPTURE(labels[i].text);
    CAPTURE(labels[i].box.centre);
    // Within a label's height (coordinates are written to 0.001 cm); a label further out is
    // led: its leader runs from its point's dot to a point's width off the label.
    if (labels[i].led) {
      CHECK(std::abs(labels[i].leader_from - labels[i].to) <= kinema::LabelBoxes::kLeaderDot + 0.002);
      CHECK(labels[i].box.distance_to(labels[i].leader_to) <= 2.54 / 72.27 + 0.002);
    } else {
      const double off = labels[i].from == labels[i].to ? labels[i].box.distance_to(labels[i].to)
                                                        : labels[i].box.distance_to_segment(labels[i].from, labels[i].to);
      CHECK(off <= kinema::label_reach(labels[i].box) + 0.002);
    }
    for (std::size_t j = 0; j < i; ++j) {
      CAPTURE(labels[j].text);
      CAPTURE(labels[j].box.centre);
      CHECK_FALSE(labels[i].box.overlaps(labels[j].box));
    }
    for (const kinema::LabelBox& dot : dots) {
      CAPTURE(dot.centre);
      CHECK_FALSE(labels[i].box.overlaps(dot));
    }
    for (const std::vector<Point>& block : blocks) {
      CAPTURE(block[0]);
      CHECK_FALSE(labels[i].box.meets(block));
    }
  }
}

}  // namespace

// Issue 32: in busy figures the centres' labels lay on one another (example_4_2_joints) or
// on a slider's block (crank_shaper); each now stands where no other label, dot, pivot or
// block is, next to its centre.
TEST_CASE("figures: instant centres' labels on no other label, dot, pivot or block, each next to its centre") {
  int figures = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const MotionTable values = kinema::solve_motion(model, {model.system.input.values.empty() ? 0.5 : model.system.input.values.front()});
    const std::string figure = figure_after(document(model, &values), "\\subsubsection*{Instant centres}");
    if (figure.empty()) continue;
    CAPTURE(std::string(name));
    ++figures;
    std::vector<ReadLabel> labels;
    std::vector<kinema::LabelBox> dots;
    std::istringstream lines(figure);
    std::vector<Point> leader;  // the leader just drawn, for the centre after it
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("\\draw[red!75!black, very thin] ", 0) == 0) leader = coordinates(line);
      if (line.rfind("\\filldraw[red!75!black, fill=white] ", 0) != 0) continue;
      const auto c = coordinates(line);
      dots.push_back({c[0], 0.07, 0.07});
      const kinema::LabelBox box = kinema::label_box(node_text(line), 8, 0);
      labels.push_back({node_text(line), {c.size() > 1 ? c[1] : anchored(c[0], line, box), box.half_width, box.half_height}, c[0], c[0]});
      if (leader.size() == 2) labels.back().led = true, labels.back().leader_from = leader[0], labels.back().leader_to = leader[1];
      leader.clear();
    }
    for (const std::string& line : lines_starting(figure, "\\draw[->, red!75!black")) {
      const auto c = coordinates(line);
      const kinema::LabelBox box = kinema::label_box(node_text(line), 8, 0);
      labels.push_back({node_text(line), {c.size() > 2 ? c[2] : anchored(c[1], line, box), box.half_width, box.half_height}, c[0], c[1]});
    }
    for (const std::string& line : lines_starting(figure, "\\draw (")) {  // a ground pivot's triangle under it
      if (line.find("-- ++(-0.15,-0.25) -- ++(0.3,0) -- cycle") == std::string::npos) continue;
      dots.push_back({coordinates(line)[0] + Point(0, -0.125), 0.15, 0.125});
    }
    std::vector<std::vector<Point>> blocks;
    for (const Block& b : read_drawing(figure).blocks) {  // 0.6 by 0.3 cm, turned as drawn
      const Point along = std::polar(0.6, b.degrees * M_PI / 180), across = along * Point(0, 0.5);
      blocks.push_back(kinema::parallelogram(b.centre - along / 2.0 - across / 2.0, along, across));
    }
    REQUIRE(labels.size() >= 3);
    check_labels(labels, dots, blocks);
  }
  CHECK(figures >= 8);  // every planar joints-and-links and vector-loop sample with centres
}

// Issue 32: a polygon's label stood up to 3 label heights from its point or arrow; each is
// now within one, and on no other label nor a vertex's dot.
TEST_CASE("figures: polygon labels on no other label nor dot, each within a label's height of its point or arrow") {
  int figures = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const MotionTable values = kinema::solve_motion(model, {model.system.input.values.empty() ? 0.5 : model.system.input.values.front()});
    const std::string tex = document(model, &values);
    for (auto at = tex.find("\\begin{tikzpicture}[line cap=round, >=latex]\n\\draw[->, "); at != std::string::npos;
         at = tex.find("\\begin{tikzpicture}[line cap=round, >=latex]\n\\draw[->, ", at + 1)) {
      const std::string figure = tex.substr(at, tex.find("\\end{tikzpicture}", at) - at);
      if (figure.find("\\node[font=\\small, inner sep=0pt] at ") == std::string::npos) continue;  // no polygon
      CAPTURE(std::string(name));
      ++figures;
      std::vector<ReadLabel> labels;
      std::vector<kinema::LabelBox> dots;
      std::istringstream in(figure);
      Point vertex;
      for (std::string line; std::getline(in, line);) {
        if (line.rfind("\\fill (", 0) == 0) {  // a vertex's dot, its label on the next line
          vertex = coordinates(line)[0];
          dots.push_back({vertex, 0.05, 0.05});
        } else if (line.rfind("\\node[font=\\small, inner sep=0pt] at ", 0) == 0) {
          const std::string text = line.substr(line.find(") {") + 3, line.rfind('}') - line.find(") {") - 3);
          labels.push_back({text, kinema::label_box(text, 10, 0, coordinates(line)[0]), vertex, vertex});
        } else if (line.rfind("\\draw[->", 0) == 0 && line.find("node[pos=") != std::string::npos) {
          const auto c = coordinates(line);
          double pos, xshift, yshift;
          REQUIRE(std::sscanf(line.c_str() + line.find("node[pos="), "node[pos=%lf, xshift=%lfcm, yshift=%lfcm", &pos, &xshift,
                              &yshift) == 3);
          const std::string text = node_text(line);
          labels.push_back({text, kinema::label_box(text, 8, 1, c[0] + (c[1] - c[0]) * pos + Point(xshift, yshift)), c[0], c[1]});
        }
      }
      check_labels(labels, dots);
    }
  }
  CHECK(figures >= 20);  // a velocity and an acceleration polygon of each planar sample that has them
}

namespace {

// The value of option `key` in an axis's options ("width=5.4cm" -> "5.4cm", "xtick={0,90}" -> "0,90").
std::string axis_option(const std::string& options, const std::string& key) {
  auto at = options.find(", " + key + "=");
  if (at == std::string::npos && options.rfind(key + "=", 0) == 0) at = static_cast<std::size_t>(-2);
  if (at == std::string::npos) return "";
  at += key.size() + 3;
  if (options[at] == '{') return options.substr(at + 1, options.find("}, ", at) - at - 1);
  return options.substr(at, options.find(", ", at) - at);
}

std::vector<std::string> split_commas(const std::string& list) {
  std::vector<std::string> parts;
  std::istringstream in(list);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

}  // namespace

// Issue 32: nothing kept a plot's tick labels apart (pgfplots chose them). Each axis now
// states its ticks and labels; read back, neighbouring labels' boxes (\scriptsize, as the
// printer estimates them) do not meet at the axis's stated length, on x side by side and
// on y one above the other, and each label is its tick's value, inside the axis's range.
TEST_CASE("figures: every plot's tick labels apart at the axis's length, each its tick's value") {
  int axes = 0;
  for (const char* name : kinema_test::kSamples) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const std::string tex = document_at_first_value(model);
    for (auto at = tex.find("\\begin{axis}["); at != std::string::npos; at = tex.find("\\begin{axis}[", at + 1)) {
      const std::string options = tex.substr(at + 13, tex.find("]\n", at) - at - 13);
      CAPTURE(options);
      ++axes;
      REQUIRE(options.find("scale only axis") != std::string::npos);  // the stated width is the axis's
      for (const char axis : {'x', 'y'}) {
        const std::string a(1, axis);
        const std::string length = axis_option(options, axis == 'x' ? "width" : "height");
        REQUIRE(length.size() > 2);
        REQUIRE(length.substr(length.size() - 2) == "cm");
        const double lo = std::stod(axis_option(options, a + "min")), hi = std::stod(axis_option(options, a + "max"));
        const double cm_per_unit = std::stod(length) / (hi - lo);
        const auto ticks = split_commas(axis_option(options, a + "tick"));
        const auto labels = split_commas(axis_option(options, a + "ticklabels"));
        // Labels of large values count in the power of ten the axis's label states.
        const std::string axis_label = axis_option(options, a + "label");
        const auto power_at = axis_label.find("10^{");
        const double unit = power_at == std::string::npos ? 1.0 : std::pow(10.0, std::stoi(axis_label.substr(power_at + 4)));
        REQUIRE(!ticks.empty());
        REQUIRE(labels.size() == ticks.size());
        for (std::size_t i = 0; i < ticks.size(); ++i) {
          CAPTURE(labels[i]);
          const double tick = std::stod(ticks[i]);
          CHECK(tick >= lo - 1e-9 * (hi - lo));
          CHECK(tick <= hi + 1e-9 * (hi - lo));
          CHECK(std::stod(labels[i].substr(1)) * unit == doctest::Approx(tick).epsilon(1e-9));
          CHECK(labels[i].size() <= 2 + 6);  // "$-25000$" at most: -2000000 was written out
          if (i == 0) continue;
          const kinema::LabelBox previous = kinema::label_box(labels[i - 1], 8, 0), box = kinema::label_box(labels[i], 8, 0);
          const double room = axis == 'x' ? previous.half_width + box.half_width : previous.half_height + box.half_height;
          CHECK((tick - std::stod(ticks[i - 1])) * cm_per_unit > room);
        }
      }
    }
  }
  CHECK(axes >= 5 * 18);  // every sample's plots
}

namespace {

// A chain's figure, from its \tdplotsetmaincoords{theta}{phi} to its \end{tikzpicture}, and
// where that view puts a point of it on the page (cm): tikz-3dplot's main rotation.
struct ChainFigure {
  std::string text;
  double theta = 0, phi = 0;
  Point on_page(double x, double y, double z) const {
    const double t = theta * M_PI / 180, f = phi * M_PI / 180;
    return {x * std::cos(f) + y * std::sin(f), -x * std::cos(t) * std::sin(f) + y * std::cos(t) * std::cos(f) + z * std::sin(t)};
  }
};

std::vector<ChainFigure> chain_figures(const std::string& tex) {
  std::vector<ChainFigure> figures;
  for (auto begin = tex.find("\\tdplotsetmaincoords{"); begin != std::string::npos;
       begin = tex.find("\\tdplotsetmaincoords{", begin + 1)) {
    ChainFigure figure;
    figure.text = tex.substr(begin, tex.find("\\end{tikzpicture}", begin) - begin);
    REQUIRE(std::sscanf(figure.text.c_str(), "\\tdplotsetmaincoords{%lf}{%lf}", &figure.theta, &figure.phi) == 2);
    figures.push_back(figure);
  }
  return figures;
}

}  // namespace

// The spatial chains' names of frames and points: in the robot arm with a sleeve "C" was
// set on "E3, A" and the RSSR's "rocker" on "ground, crank" and on the triads, each name
// anchored at its place whatever was there.
TEST_CASE("figures: a spatial chain's names on no other name nor dot, each next to a place drawn") {
  for (const char* name : {"robot_arm_slider.toml", "robot_arm_seed000.toml", "rssr_spatial_four_bar.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const std::vector<ChainFigure> figures = chain_figures(document_at_first_value(model));
    REQUIRE(!figures.empty());
    const auto chain_on_page = [&](double x, double y, double z) { return figures.front().on_page(x, y, z); };
    std::istringstream figure(figures.front().text);
    std::vector<Point> dots;
    std::vector<kinema::LabelBox> names;
    for (std::string line; std::getline(figure, line);) {
      double x, y, z;
      if (std::sscanf(line.c_str(), "\\fill (%lf,%lf,%lf) circle", &x, &y, &z) == 3 ||
          std::sscanf(line.c_str(), "\\filldraw[fill=white] (%lf,%lf,%lf) circle", &x, &y, &z) == 3)
        dots.push_back(chain_on_page(x, y, z));
      if (line.rfind("\\node[", 0) != 0 || line.find("font=\\small") == std::string::npos) continue;
      const std::string text = line.substr(line.rfind(" {") + 2, line.rfind("};") - line.rfind(" {") - 2);
      kinema::LabelBox box = kinema::label_box(text, 10, 2);
      const auto at = line.find(" at (");
      if (std::sscanf(line.c_str() + at, " at (canvas cs:x=%lfcm,y=%lfcm)", &x, &y) == 2) {
        box.centre = Point(x, y);
      } else {  // anchored north east at a place of the figure
        REQUIRE(std::sscanf(line.c_str() + at, " at (%lf,%lf,%lf)", &x, &y, &z) == 3);
        box.centre = chain_on_page(x, y, z) - Point(box.half_width, box.half_height);
      }
      names.push_back(box);
    }
    REQUIRE(names.size() >= 3);
    REQUIRE(dots.size() >= names.size());
    const double dot = 1.5 * 2.54 / 72.27;
    for (std::size_t i = 0; i < names.size(); ++i) {
      CAPTURE(i);
      for (std::size_t j = 0; j < i; ++j) CHECK_FALSE(names[i].overlaps(names[j]));
      double nearest = INFINITY;
      for (const Point& d : dots) {
        CHECK(names[i].distance_to(d) > dot / 2);  // on no dot
        nearest = std::min(nearest, names[i].distance_to(d));
      }
      CHECK(nearest <= 2 * kinema::label_reach(names[i]));  // beside a place
    }
  }
}

// Issue 49: the RSSR was drawn as its frames joined to the observer's origin (a blue line
// from the origin to the rocker's pivot D), without the crank AB, the coupler BC or the
// rocker DC, and from a view that put D beside the origin. At four crank angles: bars
// A-B, D-C and B-C and no other, each frame on a ground pivot, its joint lettered, and the
// places seen apart.
TEST_CASE("figures: the RSSR spatial four-bar is drawn as its crank, coupler and rocker at every value drawn") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("rssr_spatial_four_bar.toml"));
  const MotionTable values = kinema::solve_motion(model, {0.0, M_PI / 2, M_PI, 3 * M_PI / 2});
  const std::vector<ChainFigure> figures = chain_figures(document(model, &values));
  REQUIRE(figures.size() == 4);
  for (const ChainFigure& figure : figures) {
    CAPTURE(figure.text);
    using Place = std::array<double, 3>;
    std::vector<Place> pivots, points;
    std::vector<std::array<Place, 2>> bars;
    std::istringstream lines(figure.text);
    for (std::string line; std::getline(lines, line);) {
      Place a, b;
      if (std::sscanf(line.c_str(), "\\filldraw[fill=white] (%lf,%lf,%lf) circle", &a[0], &a[1], &a[2]) == 3) pivots.push_back(a);
      if (std::sscanf(line.c_str(), "\\fill (%lf,%lf,%lf) circle", &a[0], &a[1], &a[2]) == 3) points.push_back(a);
      if (std::sscanf(line.c_str(), "\\draw[very thick, blue!70!black] (%lf,%lf,%lf) -- (%lf,%lf,%lf);", &a[0], &a[1], &a[2],
                      &b[0], &b[1], &b[2]) == 6)
        bars.push_back({a, b});
    }
    REQUIRE(pivots.size() == 2);  // A (the crank's frame) and D (the rocker's)
    REQUIRE(points.size() == 2);  // B and C
    const auto same = [](const Place& p, const Place& q) { return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) < 1e-3; };
    const auto joined = [&](const Place& p, const Place& q) {
      return std::count_if(bars.begin(), bars.end(), [&](const std::array<Place, 2>& bar) {
        return (same(bar[0], p) && same(bar[1], q)) || (same(bar[0], q) && same(bar[1], p));
      });
    };
    CHECK(bars.size() == 3);
    CHECK(joined(points[0], points[1]) == 1);  // the coupler BC
    CHECK(joined(pivots[0], pivots[1]) == 0);  // no line from the origin to D
    for (const Place& point : points) CHECK(joined(pivots[0], point) + joined(pivots[1], point) == 1);
    for (const Place& pivot : pivots) CHECK(joined(pivot, points[0]) + joined(pivot, points[1]) == 1);
    // Two ground pivots, each hatched; the joints lettered beside their frames' names.
    std::size_t hatched = 0;
    for (auto at = figure.text.find("pattern=north east lines"); at != std::string::npos;
         at = figure.text.find("pattern=north east lines", at + 1))
      ++hatched;
    CHECK(hatched == 2);
    CHECK(figure.text.find("A, crank}") != std::string::npos);
    CHECK(figure.text.find("{D, rocker}") != std::string::npos);
    // The places seen apart: the nearest two at least a fifth of the widest (the usual view
    // put D beside A, a tenth).
    std::vector<Point> seen;
    for (const Place& p : pivots) seen.push_back(figure.on_page(p[0], p[1], p[2]));
    for (const Place& p : points) seen.push_back(figure.on_page(p[0], p[1], p[2]));
    double nearest = INFINITY, widest = 0;
    for (std::size_t i = 0; i < seen.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        nearest = std::min(nearest, std::abs(seen[i] - seen[j]));
        widest = std::max(widest, std::abs(seen[i] - seen[j]));
      }
    CHECK(nearest > 0.2 * widest);
  }
}

namespace {

// The worked solution's drawings at several values of each planar sample: the file's own
// values and eight more spread over the plotting range (a turn of a crank), each drawing
// the tikzpicture after the sentence that introduces it.
struct DrawnAt {
  std::string sample, figure;
  double input = 0;
};

std::vector<DrawnAt> drawings_over_the_range() {
  std::vector<DrawnAt> drawn;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.frames.empty()) continue;  // spatial chains: no planar drawing
    const double first = model.system.input.values.empty() ? 0.0 : model.system.input.values.front();
    const std::vector<double> range = kinema::plot_range(model.system, first);
    std::vector<double> inputs = model.system.input.values;
    for (std::size_t k = 0; k < 8; ++k) inputs.push_back(range[k * (range.size() - 1) / 8]);
    const MotionTable values = kinema::solve_motion(model, inputs);
    const std::string tex = document(model, &values);
    const std::string sentence = "The mechanism at this instant, drawn to scale";
    std::size_t row = 0;
    for (std::size_t at = tex.find(sentence); at != std::string::npos; at = tex.find(sentence, at + 1)) {
      // Each drawing follows its value's substitutions; rows that do not assemble have none.
      while (row < values.size() && values.status(row) == kinema::Status::unassembled) ++row;
      drawn.push_back({name, mechanism_figure(tex, at), row < values.size() ? values.input(row) : 0.0});
      ++row;
    }
  }
  return drawn;
}

struct Arrow {
  Point from, to;
};

double distance_to_segment(Point p, const Arrow& s) {
  const Point d = s.to - s.from;
  const double t = std::norm(d) > 0 ? std::clamp(std::real((p - s.from) * std::conj(d)) / std::norm(d), 0.0, 1.0) : 0.0;
  return std::abs(p - (s.from + t * d));
}

bool segments_cross(const Arrow& a, const Arrow& b) {
  const auto side = [](Point p, Point q, Point r) { return std::imag((q - p) * std::conj(r - p)); };
  return side(a.from, a.to, b.from) * side(a.from, a.to, b.to) < 0 && side(b.from, b.to, a.from) * side(b.from, b.to, a.to) < 0;
}

// A drawing's arrows of one kind by the point they belong to ("E" from {$\mathbf{v}_{E}$}).
std::vector<std::pair<std::string, Arrow>> point_arrows(const std::string& figure, const std::string& style) {
  std::vector<std::pair<std::string, Arrow>> arrows;
  for (const std::string& line : lines_starting(figure, "\\draw[-latex, " + style + "] ")) {
    double x = 0, y = 0, dx = 0, dy = 0;
    REQUIRE(std::sscanf(line.c_str() + line.find("] (") + 2, "(%lf,%lf) -- ++(%lf,%lf)", &x, &y, &dx, &dy) == 4);
    const auto name = line.find("}_{", line.rfind(" {$"));
    REQUIRE(name != std::string::npos);
    arrows.push_back({line.substr(name + 3, line.find("}$}", name) - name - 3), {{x, y}, {x + dx, y + dy}}});
  }
  return arrows;
}

}  // namespace

// Issue 45: a point's acceleration along its velocity (example 4.2's E, on its guide; 4.4's
// F) was drawn 0.12 cm beside it, where the two arrowheads touch each other's shafts, and
// one starting a few degrees off it ran its head into the other's. Read back at values
// over a turn: both arrows of a point from the point with each tip clear of the other
// arrow, or side by side, no nearer anywhere; clear meaning the two heads' half-widths
// and a gap between the lines (a thick -latex head is 3.75 (0.28 pt + 0.3 x 0.8 pt) each
// side of its shaft, pgfcorearrows.code.tex).
TEST_CASE("figures: a point's velocity and acceleration arrows stand apart at every value drawn") {
  constexpr double kCmPerPt = 2.54 / 72.27;
  const double head = 3.75 * (0.28 + 0.3 * 0.8) * kCmPerPt;
  const double apart = 2 * head + 0.05;
  int pairs = 0, side_by_side = 0;
  for (const DrawnAt& d : drawings_over_the_range()) {
    const auto velocities = point_arrows(d.figure, "red, thick");
    for (const auto& [point, a] : point_arrows(d.figure, "green!50!black, thick, dashed")) {
      for (const auto& [other, v] : velocities) {
        if (other != point) continue;
        ++pairs;
        CAPTURE(d.sample);
        CAPTURE(d.input);
        CAPTURE(point);
        const bool from_one_point = std::abs(a.from - v.from) < 0.002;
        side_by_side += !from_one_point;
        double nearest = std::min(distance_to_segment(a.to, v), distance_to_segment(v.to, a));
        if (!from_one_point) {
          nearest = std::min({nearest, distance_to_segment(a.from, v), distance_to_segment(v.from, a)});
          CHECK_FALSE(segments_cross(a, v));
        }
        CHECK(nearest >= apart);
      }
    }
  }
  CHECK(pairs >= 100);
  CHECK(side_by_side >= 1);  // example 4.2's E at least: along its guide
}

// Issue 49: an arrow along a link hid under it (Problem 4.4's a_B, toward the crank's pivot
// A, ran the crank's length under it and ended on the pivot, labelled there). Read back at
// values over a turn: no arrow at least 0.5 cm long runs over a link (within the bar's half
// width) for more than half its length, sampled along it.
TEST_CASE("figures: no velocity or acceleration arrow runs along a link at any value drawn") {
  int arrows = 0, moved = 0;
  for (const DrawnAt& d : drawings_over_the_range()) {
    std::vector<Arrow> links;
    for (const std::string& line : lines_starting(d.figure, "\\draw[very thick, blue!70!black] ")) {
      const auto c = coordinates(line);
      for (std::size_t k = 1; k < c.size(); ++k) links.push_back({c[k - 1], c[k]});
    }
    for (const char* style : {"red, thick", "green!50!black, thick, dashed"}) {
      for (const auto& [point, arrow] : point_arrows(d.figure, style)) {
        const double length = std::abs(arrow.to - arrow.from);
        if (length < 0.5) continue;
        ++arrows;
        int over = 0;
        constexpr int kSamples = 20;
        for (int k = 1; k <= kSamples; ++k) {
          const Point p = arrow.from + (arrow.to - arrow.from) * (double(k) / kSamples);
          bool on_link = false;
          for (const Arrow& link : links) on_link = on_link || distance_to_segment(p, link) < 0.06;
          over += on_link;
        }
        CAPTURE(d.sample);
        CAPTURE(d.input);
        CAPTURE(point);
        CAPTURE(style);
        CHECK(2 * over <= kSamples);
        bool at_joint = false;
        for (const Arrow& link : links) at_joint = at_joint || std::abs(link.from - arrow.from) < 0.002 || std::abs(link.to - arrow.from) < 0.002;
        moved += !at_joint;
      }
    }
  }
  CHECK(arrows >= 200);
  CHECK(moved >= 1);  // Problem 4.4's a_B at least: beside the crank
}

// Issue 49: the slider-crank's and the piston-driven crank's crank pivot (the loops' origin,
// no ground term ending there) was drawn as a bare pin, with no ground symbol.
TEST_CASE("figures: a crank pivoted at the loops' origin stands on a ground symbol at every value drawn") {
  int drawn = 0;
  for (const DrawnAt& d : drawings_over_the_range()) {
    if (d.sample != "slider_crank.toml" && d.sample != "piston_driven_crank.toml") continue;
    ++drawn;
    CAPTURE(d.sample);
    CAPTURE(d.input);
    CHECK(d.figure.find("\\fill[pattern=north east lines] (0.000000,0.000000) ++(-0.3,-0.35)") != std::string::npos);
  }
  CHECK(drawn >= 10);
}

// Issue 45: a small angle's arc was drawn up to 2.5 cm from its vertex (wide enough for its
// symbol between the arms), far out along or past the link it measures. Read back at values
// over a turn: every arc within a centimetre of its vertex, and ending on the link whose
// angle it marks (a bar or plate edge drawn from the vertex that way, at least as long).
TEST_CASE("figures: an angle's arc stays by its vertex and ends on its link at every value drawn") {
  int arcs = 0, small = 0;
  for (const DrawnAt& d : drawings_over_the_range()) {
    // The links as drawn: bars and plates' edges.
    std::vector<Line> links;
    for (const std::string& line : lines_starting(d.figure, "\\draw[very thick, blue!70!black] ")) {
      const auto c = coordinates(line);
      for (std::size_t k = 1; k < c.size(); ++k) links.push_back({c[k - 1], c[k]});
    }
    for (const std::string& line : lines_starting(d.figure, "\\filldraw[fill=blue!10, draw=blue!70!black")) {
      const auto c = coordinates(line);
      for (std::size_t k = 0; k < c.size(); ++k) links.push_back({c[k], c[(k + 1) % c.size()]});
    }
    for (const std::string& line : lines_starting(d.figure, "\\draw[->, gray] (")) {
      double x = 0, y = 0, dx = 0, dy = 0, degrees = 0, radius = 0;
      if (std::sscanf(line.c_str(), "\\draw[->, gray] (%lf,%lf) ++(%lf,%lf) arc[start angle=0, end angle=%lf, radius=%lf]", &x,
                      &y, &dx, &dy, &degrees, &radius) != 6)
        continue;  // the axes
      ++arcs;
      small += std::fabs(degrees) < 25;
      const Point vertex(x, y), towards = std::polar(1.0, degrees * M_PI / 180);
      // The longest link drawn from the vertex in the angle's direction.
      double arm = 0;
      for (const Line& l : links)
        for (const auto& [from, to] : {std::pair{l.a, l.b}, std::pair{l.b, l.a}})
          if (std::abs(from - vertex) < 0.002 && std::abs(to - from) > 0 &&
              std::fabs(std::arg((to - from) / towards)) < 0.01)
            arm = std::max(arm, std::abs(to - from));
      CAPTURE(d.sample);
      CAPTURE(d.input);
      CAPTURE(line);
      CHECK(radius <= 1.0);
      CHECK(arm > 0);
      CHECK(radius <= arm);
    }
  }
  CHECK(arcs >= 100);
  CHECK(small >= 5);  // angles under 25 degrees among them
}

// Issue 49: the pivots of vector-loop drawings were unlettered (Problem 4.4's A and D, though
// its statement says "crank AB"). A corner the file's lengths letter (AB, CD: lettered_corners)
// is where the same mechanism's joints-and-links file puts the joint of that letter, at
// every value of a turn drawn; the worked solution and the page set the letter there; a file
// whose lengths name no corner (the four-bar's a, b, c, d) gets none.
TEST_CASE("figures: a vector-loop file's corners lettered by its lengths' names, where the joints file puts them") {
  const std::vector<std::pair<const char*, const char*>> pairs = {
      {"problem_4_4_six_bar.toml", "problem_4_4_joints.toml"},
      {"example_4_1_r_trr.toml", "example_4_1_joints.toml"},
      {"example_4_2_r_rtr_rrt.toml", "example_4_2_joints.toml"}};
  for (const auto& [loops_file, joints_file] : pairs) {
    CAPTURE(std::string(loops_file));
    const kinema::Model loops = kinema::load_model(kinema_test::sample(loops_file));
    const kinema::Model joints = kinema::load_model(kinema_test::sample(joints_file));
    const kinema::MechanismGeometry geometry(loops);
    std::vector<double> inputs;
    for (int k = 0; k < 12; ++k) inputs.push_back(loops.system.input.values.front() + k * 30 * M_PI / 180);
    const MotionTable on_loops = kinema::solve_motion(loops, inputs), on_joints = kinema::solve_motion(joints, inputs);
    std::size_t lettered = 0;
    for (std::size_t r = 0; r < on_loops.size(); ++r) {
      if (on_loops.status(r) != kinema::Status::ok || on_joints.status(r) != kinema::Status::ok) continue;
      CAPTURE(on_loops.input(r));
      const auto segments = geometry.segments(on_loops[r]);
      const auto corners = geometry.lettered_corners(on_loops[r], segments);
      const auto drawing = kinema::linkage_drawing(joints.system, on_joints[r]);
      REQUIRE(drawing);
      CHECK(corners.size() == 2);
      for (const kinema::LetteredCorner& corner : corners) {
        CAPTURE(corner.letter);
        const auto& s = segments.at(corner.segment);
        CHECK(std::abs((corner.at_to ? s.to : s.from) - corner.at) == 0);
        bool found = false;
        const auto check = [&](const kinema::LinkageDrawing::Joint& joint) {
          if (joint.name != corner.letter) return;
          found = true;
          CHECK(std::abs(joint.at - corner.at) < 1e-9);
        };
        for (const auto& pivot : drawing->ground_pivots) check(pivot);
        for (const auto& link : drawing->links)
          for (const auto& joint : link.joints) check(joint);
        CHECK(found);
        ++lettered;
      }
    }
    CHECK(lettered >= 2 * 8);
    // The worked solution sets each letter on its figure.
    const std::string tex = document_at_first_value(loops);
    for (const kinema::LetteredCorner& corner : geometry.lettered_corners(on_loops[0], geometry.segments(on_loops[0])))
      CHECK(tex.find("{" + corner.letter + "};") != std::string::npos);
  }
  const kinema::Model four_bar = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::MechanismGeometry geometry(four_bar);
  const MotionTable at = kinema::solve_motion(four_bar, four_bar.system.input.values);
  CHECK(geometry.lettered_corners(at[0], geometry.segments(at[0])).empty());
}

// Issue 49: the sheet's La, Lb and Lc were unlabelled dashed lines. A ground length that one
// parameter gives is drawn and labelled with its name (dimensions), at every value drawn:
// Problem 4.4's La from the origin along x, Lb up to D, Lc from the origin to the guide of
// slider 5; the slider-crank's offset e.
TEST_CASE("figures: ground lengths named by one parameter are drawn and labelled at every value drawn") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"));
  const kinema::MechanismGeometry geometry(model);
  const auto value_of = [&](const std::string& name) {
    for (const auto& p : model.system.parameters)
      if (p.symbol.get_name() == name) return p.value;
    FAIL("no parameter " << name);
    return 0.0;
  };
  std::vector<double> inputs;
  for (int k = 0; k < 6; ++k) inputs.push_back(model.system.input.values.front() + k * 60 * M_PI / 180);
  const MotionTable table = kinema::solve_motion(model, inputs);
  for (std::size_t r = 0; r < table.size(); ++r) {
    if (table.status(r) != kinema::Status::ok) continue;
    CAPTURE(table.input(r));
    std::map<std::string, std::pair<Point, Point>> drawn;
    for (const kinema::DrawnDimension& d : geometry.dimensions(geometry.segments(table[r])))
      drawn[model.system.parameters[d.parameter].symbol.get_name()] = {d.from, d.to};
    REQUIRE(drawn.size() == 3);
    const auto& [la_from, la_to] = drawn.at("La");
    const auto& [lb_from, lb_to] = drawn.at("Lb");
    const auto& [lc_from, lc_to] = drawn.at("Lc");
    CHECK(std::abs(la_from) < 1e-12);
    CHECK(std::abs(la_to - Point(value_of("La"), 0)) < 1e-12);
    CHECK(std::abs(lb_from - Point(value_of("La"), 0)) < 1e-12);
    CHECK(std::abs(lb_to - Point(value_of("La"), value_of("Lb"))) < 1e-12);
    CHECK(std::abs(lc_from) < 1e-12);
    CHECK(std::abs(lc_to - Point(-value_of("Lc"), 0)) < 1e-12);
  }
  const std::string tex = document_at_first_value(model);
  for (const char* name : {"{$L_{a}$}", "{$L_{b}$}", "{$L_{c}$}"}) CHECK(tex.find(name) != std::string::npos);
  const kinema::Model slider = kinema::load_model(kinema_test::sample("slider_crank.toml"));
  const std::string slider_tex = document_at_first_value(slider);
  CHECK(slider_tex.find("{$e$}") != std::string::npos);
}
