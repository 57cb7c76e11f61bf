#include <kinema/engine/printers/latex/tikz_polygons.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>

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

// Where a label goes round a point: away from the polygon's centre.
std::string anchor_away(std::complex<double> from_centre) {
  if (std::abs(from_centre) == 0) return "above right";
  const double angle = std::arg(from_centre) * 180 / M_PI;
  static const char* anchors[] = {"right", "above right", "above", "above left", "left", "below left", "below", "below right"};
  const int sector = static_cast<int>(std::lround((angle < 0 ? angle + 360 : angle) / 45)) % 8;
  return anchors[sector];
}

}  // namespace

double drawing_scale(double extent, double centimetres) {
  if (!(extent > 0) || !std::isfinite(extent)) return 1;
  const double least = extent / centimetres;
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  for (double step : {1.0, 2.0, 2.5, 4.0, 5.0, 10.0})
    if (step * decade >= least * (1 - 1e-12)) return step * decade;
  return 10 * decade;
}

void write_tikz_polygon(std::ostream& out, const ConstraintSystem& system, const TextbookForm& form,
                        const Polygon& polygon) {
  const OutputScale scale(system);
  const bool velocity = polygon.order == 1;
  const std::string unit = "\\mathrm{" + scale.length_unit + (velocity ? "/s}" : "/s^{2}}");  // math mode
  // Extent of the figure in output units, pole included.
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  std::complex<double> centre = 0;
  for (const PolygonVertex& v : polygon.vertices) {
    const std::complex<double> p = v.at / scale.length;
    min_x = std::min(min_x, p.real());
    max_x = std::max(max_x, p.real());
    min_y = std::min(min_y, p.imag());
    max_y = std::max(max_y, p.imag());
    centre += p;
  }
  if (!polygon.vertices.empty()) centre /= static_cast<double>(polygon.vertices.size());
  const double per_cm = drawing_scale(std::max(max_x - min_x, max_y - min_y), 7.0);  // output units per cm
  const auto xy = [&](std::complex<double> si) {
    const std::complex<double> p = si / scale.length / per_cm;
    return "(" + format_fixed(p.real(), 3) + "," + format_fixed(p.imag(), 3) + ")";
  };
  out << "\\begin{center}\n\\begin{tikzpicture}[line cap=round, >=latex]\n";
  for (const PolygonArrow& a : polygon.arrows) {
    const double cm = a.length() / scale.length / per_cm;
    out << "\\draw[->, " << style(a.kind) << "] " << xy(a.from) << " -- " << xy(a.to);
    // Short arrows keep their names in the table only.
    if (cm >= 0.6) out << " node[midway, fill=white, inner sep=1pt, font=\\scriptsize] {$" << a.latex << "$}";
    out << ";\n";
  }
  for (const PolygonVertex& v : polygon.vertices) {
    const std::complex<double> p = v.at / scale.length;
    out << "\\fill " << xy(v.at) << " circle (0.05) node[" << anchor_away(p - centre) << ", font=\\small] {"
        << image_label(v.name) << "};\n";
  }
  out << "\\end{tikzpicture}\n\\end{center}\n";
  out << (velocity ? "Velocity" : "Acceleration") << " polygon, scale 1\\,cm = $" << latex_number(per_cm, 3) << "\\,"
      << unit << "$; pole $o$ (every fixed point).\n\n";
  // The arrows: read off the figure (its length in cm, to 0.01 cm, times the scale), the
  // formula and its value.
  out << "\\begin{tabular}{llrrl}\n\\toprule\n" << (velocity ? "velocity" : "acceleration")
      << " & kind & on the figure & read off & formula \\\\\n & & $\\mathrm{cm}$ & $" << unit << "$ & $" << unit
      << "$ \\\\\n\\midrule\n";
  for (const PolygonArrow& a : polygon.arrows) {
    const double cm = std::round(a.length() / scale.length / per_cm * 100) / 100;
    out << "$" << a.latex << "$ & " << kind_name(a.kind) << " & $" << format_fixed(cm, 2) << "$ & $"
        << latex_number(cm * per_cm, 4) << "$ & $";
    if (!a.formula.is_zero()) out << form(a.formula, TextbookForm::Style::latex) << " = ";
    out << latex_number(a.formula_value / scale.length, 6) << "$ \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\n";
}

}  // namespace kinema
