#include <kinema/engine/printers/latex/tikz_mechanism.hpp>

#include <algorithm>
#include <cmath>
#include <complex>

#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>

namespace kinema {

void write_tikz_mechanism(std::ostream& out, const ConstraintSystem& system, const MechanismGeometry& geometry,
                        const MotionState& s) {
  const OutputScale scale(system);
  using Segment = DrawingSegment;
  const std::vector<Segment> segments = geometry.segments(s);
  std::vector<std::complex<double>> extent = {{0, 0}};
  for (const Segment& segment : segments) extent.push_back(segment.to);
  std::vector<std::complex<double>> points, velocities;
  double fastest = 0;
  if (s.status == Status::ok) {
    for (const PointMotion& p : s.points) {
      points.push_back({p.position[0], p.position[1]});
      velocities.push_back({p.velocity[0], p.velocity[1]});
      fastest = std::max(fastest, std::hypot(p.velocity[0], p.velocity[1]));
      extent.push_back(points.back());
    }
  }
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  for (const auto& p : extent) {
    min_x = std::min(min_x, p.real());
    max_x = std::max(max_x, p.real());
    min_y = std::min(min_y, p.imag());
    max_y = std::max(max_y, p.imag());
  }
  const double size = std::max({max_x - min_x, max_y - min_y, 1e-9});
  const double cm = 9.0 / size;  // drawing units per metre
  const double arrow_cm = 2.5;   // the fastest point's arrow
  const double velocity_scale = fastest > 0 ? arrow_cm / fastest : 0;  // cm per (m/s)
  auto xy = [&](std::complex<double> p) {
    return "(" + format_fixed(p.real() * cm) + "," + format_fixed(p.imag() * cm) + ")";
  };
  out << "\\begin{center}\n\\begin{tikzpicture}[line cap=round]\n";
  for (const Segment& g : segments) {
    if (g.kind == Segment::Kind::ground) {
      out << "\\draw[gray, dashed] " << xy(g.from) << " -- " << xy(g.to) << ";\n";
      for (const auto& end : {g.from, g.to}) {
        out << "\\fill[pattern=north east lines] " << xy(end) << " ++(-0.3,-0.35) rectangle ++(0.6,0.15);\n"
             << "\\draw " << xy(end) << " ++(-0.3,-0.2) -- ++(0.6,0);\n"
             << "\\draw " << xy(end) << " -- ++(-0.15,-0.2) -- ++(0.3,0) -- cycle;\n";
      }
    } else if (g.kind == Segment::Kind::slider) {
      // The block sits at the moving end: not on the ground (origin or a ground vector's end).
      bool to_is_ground = std::abs(g.to) < 1e-9 * size;
      for (const Segment& h : segments)
        if (h.kind == Segment::Kind::ground && (std::abs(h.to - g.to) < 1e-9 * size || std::abs(h.from - g.to) < 1e-9 * size))
          to_is_ground = true;
      const std::complex<double> block = to_is_ground ? g.from : g.to;
      const std::complex<double> d = g.to - g.from;
      const double angle = to_degrees(std::arg(d));
      out << "\\draw[gray, thin] " << xy(g.from - d * 0.1) << " -- " << xy(g.to + d * 0.1) << ";\n"
           << "\\draw[thick, fill=white, rotate around={" << format_fixed(angle) << ":" << xy(block) << "}] "
           << xy(block) << " ++(-0.35,-0.2) rectangle ++(0.7,0.4);\n";
    } else {
      out << "\\draw[very thick, blue!70!black] " << xy(g.from) << " -- " << xy(g.to) << ";\n";
    }
  }
  for (const Segment& g : segments) {
    for (const auto& end : {g.from, g.to})
      out << "\\filldraw[fill=white] " << xy(end) << " circle (0.07);\n";
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    out << "\\fill " << xy(points[p]) << " circle (0.06) node[above left, font=\\small] {"
         << latex_escape_text(system.points[p].name) << "};\n";
    if (velocity_scale > 0 && std::abs(velocities[p]) > 0) {
      const std::complex<double> tip = velocities[p] * velocity_scale;
      out << "\\draw[-latex, red, thick] " << xy(points[p]) << " -- ++(" << format_fixed(tip.real()) << ","
           << format_fixed(tip.imag()) << ");\n";
    }
  }
  out << "\\end{tikzpicture}\n\\end{center}\n";
  const double length_per_cm = 1.0 / cm / scale.length;
  out << "Drawing scale: 1\\,cm = $" << latex_number(length_per_cm, 3) << "$\\," << latex_escape_text(scale.length_unit);
  if (velocity_scale > 0) {
    out << "; velocity vectors (red): 1\\,cm = $" << latex_number(1.0 / velocity_scale / scale.length, 3) << "$\\,"
         << latex_escape_text(scale.length_unit) << "/s";
  }
  out << ".\n\n";
}

}  // namespace kinema
