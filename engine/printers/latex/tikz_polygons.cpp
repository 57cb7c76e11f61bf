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

double polygon_units_per_cm(const Polygon& polygon, double metres_per_length_unit) {
  // Extent of the figure in output units, pole included.
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  for (const PolygonVertex& v : polygon.vertices) {
    const std::complex<double> p = v.at / metres_per_length_unit;
    min_x = std::min(min_x, p.real());
    max_x = std::max(max_x, p.real());
    min_y = std::min(min_y, p.imag());
    max_y = std::max(max_y, p.imag());
  }
  return drawing_scale(std::max(max_x - min_x, max_y - min_y), 7.0);
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
  out << "\\begin{center}\n\\begin{tikzpicture}[line cap=round, >=latex]\n";
  for (std::size_t k = 0; k < polygon.arrows.size(); ++k) {
    const PolygonArrow& a = polygon.arrows[k];
    const double cm = a.length() / scale.length / per_cm;
    if (cm < 0.005) continue;  // a link that does not turn: in the table only
    bool drawn = false;  // one arrow for two names (v_B = v_C): the first name on the figure
    for (std::size_t j = 0; j < k; ++j)
      drawn = drawn || (std::abs(polygon.arrows[j].from - a.from) + std::abs(polygon.arrows[j].to - a.to) <=
                        1e-9 * std::max(a.length(), 1e-300));
    if (drawn) continue;
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
    const double read_off = polygon_read_off(a, per_cm, scale.length);
    out << "$" << a.latex << "$ & " << kind_name(a.kind) << " & $" << format_fixed(read_off / per_cm, 2) << "$ & $"
        << latex_number(read_off, 4) << "$ & $";
    if (!a.formula.is_zero()) out << form(a.formula, TextbookForm::Style::latex) << " = ";
    out << latex_number(a.formula_value / scale.length, 6) << "$ \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\n";
}

}  // namespace kinema
