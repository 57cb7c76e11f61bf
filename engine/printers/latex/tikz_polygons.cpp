#include "engine/printers/latex/tikz_polygons.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "engine/printers/latex/label_boxes.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

using Kind = PolygonArrow::Kind;

const char* style(Kind kind) {
  switch (kind) {
    case Kind::absolute: return "black, very thick";
    case Kind::relative: return "blue!70!black, thick";
    case Kind::sliding: return "violet, thick";
    case Kind::normal: return "red!75!black, thick";
    case Kind::tangential: return "orange!80!black, thick";
    case Kind::coriolis: return "green!50!black, thick";
  }
  return "black";
}

// Half an arrow's line, in cm (thick, 0.8 pt; the absolute ones very thick, 1.2 pt).
constexpr double kArrowHalfWidth = 0.6 * 2.54 / 72.27;

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::absolute: return "absolute";
    case Kind::relative: return "relative, across the link";
    case Kind::sliding: return "sliding, along the line";
    case Kind::normal: return "normal, towards the centre";
    case Kind::tangential: return "tangential, across the link";
    case Kind::coriolis: return "Coriolis, across the line";
  }
  return "";
}

// The image's label as textbooks print it: the point's letter in lower case (b for B).
std::string image_label(const std::string& name) {
  std::string label = name;
  if (!label.empty()) label[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(label[0])));
  std::string escaped;
  for (char c : label) escaped += c == '_' ? std::string("\\_") : std::string(1, c);
  return "$" + (label.find('_') == std::string::npos ? label : "\\mathit{" + escaped + "}") + "$";
}

}  // namespace

double drawing_scale(double extent, double centimetres) {
  if (!(extent > 0) || !std::isfinite(extent)) return 1;
  const double least = extent / centimetres;
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  for (double step : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (step * decade >= least * (1 - 1e-12)) return step * decade;
  return 10 * decade;
}

double polygon_units_per_cm(const Polygon& polygon, double metres_per_length_unit) {
  // Extent of the figure in output units, pole included.
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  const auto grow = [&](std::complex<double> si) {
    const std::complex<double> p = si / metres_per_length_unit;
    min_x = std::min(min_x, p.real());
    max_x = std::max(max_x, p.real());
    min_y = std::min(min_y, p.imag());
    max_y = std::max(max_y, p.imag());
  };
  for (const PolygonVertex& v : polygon.vertices) grow(v.at);
  for (const PolygonArrow& a : polygon.arrows) {  // a normal part ends where no vertex is
    grow(a.from);
    grow(a.to);
  }
  // The text's width across, at most 7 cm high (two polygons and their tables to a page).
  return std::max(drawing_scale(max_x - min_x, 12.0), drawing_scale(max_y - min_y, 7.0));
}

double polygon_read_off(const PolygonArrow& arrow, double units_per_cm, double metres_per_length_unit) {
  return std::round(arrow.length() / metres_per_length_unit / units_per_cm * 100) / 100 * units_per_cm;
}

void write_tikz_polygon(std::ostream& out, const ConstraintSystem& system, const TextbookForm& form,
                        const Polygon& polygon) {
  const OutputScale scale(system);
  const bool velocity = polygon.order == 1;
  const std::string unit = "\\mathrm{" + scale.length_unit + (velocity ? "/s}" : "/s^{2}}");  // math mode
  std::complex<double> centre = 0;
  for (const PolygonVertex& v : polygon.vertices) centre += v.at / scale.length;
  if (!polygon.vertices.empty()) centre /= static_cast<double>(polygon.vertices.size());
  const double per_cm = polygon_units_per_cm(polygon, scale.length);
  const auto xy = [&](std::complex<double> si) {
    const std::complex<double> p = si / scale.length / per_cm;
    return "(" + format_fixed(p.real(), 3) + "," + format_fixed(p.imag(), 3) + ")";
  };
  // The polygon and its table in one box: a table is never a page of its own after its figure.
  // The velocity polygon on the page of the paragraph that introduces both.
  out << (velocity ? "\\par\\nopagebreak" : "\\par") << "\\noindent\\begin{minipage}{\\linewidth}\n\\begin{center}\n\\begin{tikzpicture}[line cap=round, >=latex]\n";
  const auto cm_of = [&](std::complex<double> si) { return si / scale.length / per_cm; };
  // The vertices' letters first, each round its point away from the polygon's centre, or
  // the next way round that is free; points drawn at one place share one label (o, c).
  LabelBoxes placed;
  std::vector<std::pair<std::complex<double>, std::string>> places;  // cm, names
  for (const PolygonVertex& v : polygon.vertices) {
    const std::complex<double> p = cm_of(v.at);
    bool joined = false;
    for (auto& [at, names] : places)
      if (std::abs(at - p) < 0.08) {
        names += ", " + v.name;
        joined = true;
        break;
      }
    if (!joined) places.push_back({p, v.name});
  }
  for (const auto& [at, names] : places) placed.add({at, 0.06, 0.06});  // the dots
  // The arrows drawn: not one too short to see, nor one another's double (v_B = v_C: the
  // first name on the figure); each a line the labels keep off.
  std::vector<const PolygonArrow*> drawn;
  for (std::size_t k = 0; k < polygon.arrows.size(); ++k) {
    const PolygonArrow& a = polygon.arrows[k];
    if (a.length() / scale.length / per_cm < 0.005) continue;  // a link that does not turn: in the table only
    bool twice = false;
    for (std::size_t j = 0; j < k; ++j)
      twice = twice || (std::abs(polygon.arrows[j].from - a.from) + std::abs(polygon.arrows[j].to - a.to) <=
                        1e-9 * std::max(a.length(), 1e-300));
    if (twice) continue;
    drawn.push_back(&a);
    placed.add_line(cm_of(a.from), cm_of(a.to), kArrowHalfWidth);
  }
  // The vertices' labels, then the arrows' (short arrows keep their names in the table
  // only; the others' on the arrow where no other label or line is, nearest its middle,
  // else beside it), placed together.
  const std::complex<double> middle = centre / per_cm;
  std::vector<LabelRequest> requests;
  std::vector<std::string> vertex_labels;
  for (const auto& [at, names] : places) {
    std::string label;
    for (std::size_t start = 0; start <= names.size();) {
      const auto comma = names.find(", ", start);
      label += (label.empty() ? "" : ", ") + image_label(names.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 2;
    }
    vertex_labels.push_back(label);
    // Away from the polygon's middle, else the next free way round, within a label's height.
    requests.push_back({{at, 0, 0}, label_box(label, 10, 0), std::abs(at - middle) > 0 ? std::arg(at - middle) : kPi / 4, false, false, 0});
  }
  const auto labelled = [&](const PolygonArrow& a) { return a.length() / scale.length / per_cm >= 0.6; };
  for (const PolygonArrow* a : drawn)
    if (labelled(*a)) requests.push_back({{cm_of(a->from), 0, 0}, label_box("$" + a->latex + "$", 8, 1), 0, true, true, cm_of(a->to)});
  const std::vector<PlacedLabel> boxes = placed.place_all(requests);
  std::size_t next = places.size();
  for (const PolygonArrow* arrow : drawn) {
    const PolygonArrow& a = *arrow;
    out << "\\draw[->, " << style(a.kind) << "] " << xy(a.from) << " -- " << xy(a.to);
    if (labelled(a)) {
      const std::complex<double> p = cm_of(a.from), q = cm_of(a.to);
      const LabelBox& chosen = boxes[next++].box;
      const double pos = std::real((chosen.centre - p) / (q - p));
      const std::complex<double> offset = chosen.centre - (p + (q - p) * pos);
      out << " node[pos=" << format_fixed(pos, 3) << ", xshift=" << format_fixed(offset.real(), 3)
          << "cm, yshift=" << format_fixed(offset.imag(), 3) << "cm, fill=white, inner sep=1pt, font=\\scriptsize] {$"
          << a.latex << "$}";
    }
    out << ";\n";
  }
  for (std::size_t k = 0; k < places.size(); ++k) {
    const std::complex<double> at = places[k].first, label = boxes[k].box.centre;
    out << "\\fill (" << format_fixed(at.real(), 3) << "," << format_fixed(at.imag(), 3) << ") circle (0.05);\n\\node[font=\\small, inner sep=0pt] at ("
        << format_fixed(label.real(), 3) << "," << format_fixed(label.imag(), 3) << ") {" << vertex_labels[k] << "};\n";
  }
  out << "\\end{tikzpicture}\n" << latex_figure_caption(velocity ? "Velocity polygon" : "Acceleration polygon") << "\\end{center}\n";
  out << (velocity ? "Velocity" : "Acceleration") << " polygon, scale 1\\,cm = $" << latex_number(per_cm, 3) << "\\,"
      << unit << "$; pole $o$ (every fixed point).\n\n";
  // The arrows: read off the figure (its length in cm, to 0.01 cm, times the scale), the
  // formula and its value.
  out << "\\begin{tabular}{llrrl}\n\\toprule\n" << (velocity ? "velocity" : "acceleration")
      << " & kind & on the figure & read off & formula \\\\\n & & $\\mathrm{cm}$ & $" << unit << "$ & $" << unit
      << "$ \\\\\n\\midrule\n";
  // The document's numbers: a relative velocity across a link that does not turn is 0, not
  // its round-off (BC omega2 = 2.2e-16 m/s in the parallelogram).
  const DocumentNumbers number(system);
  for (const PolygonArrow& a : polygon.arrows) {
    const double read_off = polygon_read_off(a, per_cm, scale.length);
    out << "$" << a.latex << "$ & " << kind_name(a.kind) << " & $" << format_fixed(read_off / per_cm, 2) << "$ & $"
        << number.read_off(read_off, Dimension::length, polygon.order) << "$ & $";
    if (!a.formula.is_zero()) out << form(a.formula, TextbookForm::Style::latex) << " = ";
    out << number(a.formula_value / scale.length, Dimension::length, polygon.order, 6) << "$ \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\\end{minipage}\n\n";
}

}  // namespace kinema
