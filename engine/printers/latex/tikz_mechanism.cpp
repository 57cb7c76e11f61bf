#include "engine/printers/latex/tikz_mechanism.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <string>

#include "engine/printers/latex/latex_format.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/naming.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

// A fixed pivot: a triangle on hatched ground.
void write_pivot(std::ostream& out, const std::string& at) {
  out << "\\fill[pattern=north east lines] " << at << " ++(-0.3,-0.35) rectangle ++(0.6,0.15);\n"
      << "\\draw " << at << " ++(-0.3,-0.2) -- ++(0.6,0);\n"
      << "\\draw " << at << " -- ++(-0.15,-0.2) -- ++(0.3,0) -- cycle;\n";
}

// A binary link drawn as a body, as the textbooks do: a light bar with rounded ends under
// its centre line (the line is what tests and readers measure).
void write_bar(std::ostream& out, const std::string& path) {
  out << "\\draw[line width=6pt, line cap=round, line join=round, blue!12] " << path << ";\n"
      << "\\draw[very thick, blue!70!black] " << path << ";\n";
}

// The anchor that puts an arrow's label beyond its tip, away from the arrow.
std::string anchor_beyond(std::complex<double> direction) {
  const double a = std::arg(direction) * 180 / kPi;
  if (a > -22.5 && a <= 22.5) return "west";
  if (a > 22.5 && a <= 67.5) return "south west";
  if (a > 67.5 && a <= 112.5) return "south";
  if (a > 112.5 && a <= 157.5) return "south east";
  if (a > -67.5 && a <= -22.5) return "north west";
  if (a > -112.5 && a <= -67.5) return "north";
  if (a > -157.5 && a <= -112.5) return "north east";
  return "east";
}

// Joints and links as drawn: fixed guides hatched, binary links as bars, links with
// more joints as plates, slider blocks as blocks on their lines, fixed pivots on ground.
template <typename Xy>
void write_links(std::ostream& out, const LinkageDrawing& drawing, const Xy& xy, std::complex<double> centre, double size,
                 double cm) {
  for (const LinkageDrawing::Guide& g : drawing.guides) {
    // The line across the drawing, hatched on one side: centred where the drawing's
    // centre projects onto it.
    const std::complex<double> middle = g.through + g.along * std::real((centre - g.through) * std::conj(g.along));
    const std::complex<double> a = middle - g.along * (0.6 * size), b = middle + g.along * (0.6 * size);
    const std::string angle = format_fixed(to_degrees(std::arg(g.along)));
    out << "\\draw[gray] " << xy(a) << " -- " << xy(b) << ";\n"
        << "\\fill[pattern=north east lines, rotate around={" << angle << ":" << xy(a) << "}] " << xy(a)
        << " rectangle ++(" << format_fixed(1.2 * size * cm) << ",-0.15);\n";
  }
  for (const LinkageDrawing::Link& link : drawing.links) {
    if (link.block) {
      const std::string at = xy(link.joints.front().at);
      out << "\\draw[thick, fill=white, rotate around={" << format_fixed(to_degrees(link.angle)) << ":" << at << "}] "
          << at << " ++(-0.35,-0.2) rectangle ++(0.7,0.4);\n";
      continue;
    }
    std::string path;
    for (const auto& joint : link.joints) path += (path.empty() ? "" : " -- ") + xy(joint.at);
    if (link.joints.size() >= 3) {
      out << "\\filldraw[fill=blue!10, draw=blue!70!black, very thick, line join=round] " << path << " -- cycle;\n";
    } else {
      write_bar(out, path);
    }
  }
  for (const auto& pivot : drawing.ground_pivots) {
    write_pivot(out, xy(pivot.at));
    out << "\\node[below right, font=\\small] at " << xy(pivot.at) << " {" << latex_escape_text(pivot.name) << "};\n";
  }
  for (const LinkageDrawing::Link& link : drawing.links)
    for (const auto& joint : link.joints) out << "\\filldraw[fill=white] " << xy(joint.at) << " circle (0.07);\n";
}

}  // namespace

void write_tikz_mechanism(std::ostream& out, const ConstraintSystem& system, const ValueAnalysis& at,
                          const std::vector<std::string>& link_labels, const MotionState& s) {
  const OutputScale scale(system);
  using Segment = DrawingSegment;
  // Joints and links: the links as bodies (bars, plates, blocks); vector loops: their terms.
  const std::optional<LinkageDrawing>& drawing = at.linkage;
  const std::vector<Segment>& segments = at.segments;
  std::vector<std::complex<double>> extent = {{0, 0}};
  for (const Segment& segment : segments) extent.push_back(segment.to);
  if (drawing) {
    for (const auto& link : drawing->links)
      for (const auto& joint : link.joints) extent.push_back(joint.at);
    for (const auto& pivot : drawing->ground_pivots) extent.push_back(pivot.at);
  }
  std::vector<std::complex<double>> points, velocities, accelerations;
  double fastest = 0, largest = 0;
  if (s.status == Status::ok) {
    for (const PointMotion& p : s.points) {
      points.push_back({p.position[0], p.position[1]});
      velocities.push_back({p.velocity[0], p.velocity[1]});
      accelerations.push_back({p.acceleration[0], p.acceleration[1]});
      fastest = std::max(fastest, std::abs(velocities.back()));
      largest = std::max(largest, std::abs(accelerations.back()));
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
  const double acceleration_scale = largest > 0 ? arrow_cm / largest : 0;  // cm per (m/s^2)
  auto xy = [&](std::complex<double> p) {
    return "(" + format_fixed(p.real() * cm) + "," + format_fixed(p.imag() * cm) + ")";
  };
  // Introduced by a sentence that stays with it (after the substitution's display).
  out << "\\par\\medskip\\noindent The mechanism at this instant, drawn to scale"
      << (velocity_scale > 0 || acceleration_scale > 0 ? ", with the velocities and accelerations of its points as arrows" : "")
      << ":\n" << kLatexFigureBegin << "\\begin{tikzpicture}[line cap=round]\n";
  // The frame the positions are in: x and y from the origin.
  out << "\\draw[->, gray] (0,0) -- (1.2,0) node[right, font=\\scriptsize] {$x$};\n"
      << "\\draw[->, gray] (0,0) -- (0,1.2) node[above, font=\\scriptsize] {$y$};\n";
  // Labels beside a link go on the side away from the fixed guides' hatching.
  std::vector<std::pair<std::complex<double>, std::complex<double>>> guide_lines;  // through, along
  if (drawing)
    for (const auto& g : drawing->guides) guide_lines.push_back({g.through, g.along});
  for (const Segment& g : segments)
    if (g.kind == Segment::Kind::slider && g.fixed_guide) guide_lines.push_back({g.block, g.along});
  const auto beside = [&](std::complex<double> middle, std::complex<double> across) {
    const auto clearance = [&](std::complex<double> p) {
      double least = 1e300;
      for (const auto& [through, along] : guide_lines)
        least = std::min(least, std::fabs(std::imag((p - through) * std::conj(along))));
      return least;
    };
    const std::complex<double> left = middle + across * (0.35 / cm), right = middle - across * (0.35 / cm);
    return clearance(left) >= 0.3 / cm || clearance(left) >= clearance(right) ? left : right;
  };
  if (drawing) {
    write_links(out, *drawing, xy, {(min_x + max_x) / 2, (min_y + max_y) / 2}, size, cm);
    // Link numbers beside each link (its first two joints), as the file names them.
    for (std::size_t k = 0; k < drawing->links.size() && system.plan; ++k) {
      const auto& joints = drawing->links[k].joints;
      if (drawing->links[k].block && !joints.empty()) {  // a block: on the side of its guide away from the hatching
        out << "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at "
            << xy(joints.front().at + std::polar(0.55 / cm, drawing->links[k].angle + kPi / 2)) << " {"
            << latex_escape_text(drawing->links[k].name) << "};\n";
        continue;
      }
      if (joints.size() < 2 || drawing->links[k].block || std::abs(joints[1].at - joints[0].at) < 1e-9 * size) continue;
      const std::complex<double> along = joints[1].at - joints[0].at;
      const std::complex<double> across = along / std::abs(along) * std::complex<double>(0, 1);
      out << "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at "
          << xy(beside((joints[0].at + joints[1].at) / 2.0, across)) << " {"
          << latex_escape_text(drawing->links[k].name) << "};\n";
    }
  }
  for (const Segment& g : segments) {
    if (g.kind == Segment::Kind::ground) {
      out << "\\draw[gray, dashed] " << xy(g.from) << " -- " << xy(g.to) << ";\n";
      for (const auto& end : {g.from, g.to}) write_pivot(out, xy(end));
    } else if (g.kind == Segment::Kind::slider) {
      // The block at the slider's point, on the guide the geometry gives: a fixed guide
      // hatched across the drawing; a guide on a turning link drawn as that link, from the
      // term's other end through the block and on.
      const double angle = to_degrees(std::arg(g.along));
      const std::complex<double> other = std::abs(g.block - g.to) < 1e-9 * size ? g.from : g.to;
      const std::complex<double> centre((min_x + max_x) / 2, (min_y + max_y) / 2);
      if (g.fixed_guide) {
        const double t = std::real((centre - g.block) * std::conj(g.along));
        const std::complex<double> a = g.block + g.along * std::min(t - 0.5 * size, -0.15 * size),
                                   b = g.block + g.along * std::max(t + 0.5 * size, 0.15 * size);
        out << "\\draw[gray] " << xy(a) << " -- " << xy(b) << ";\n"
            << "\\fill[pattern=north east lines, rotate around={" << format_fixed(angle) << ":" << xy(a) << "}] "
            << xy(a) << " rectangle ++(" << format_fixed(std::abs(b - a) * cm) << ",-0.15);\n";
      } else {
        const std::complex<double> d = g.block - other;
        const bool on_line = std::abs(std::imag(d * std::conj(g.along))) < 1e-9 * size;
        const std::complex<double> beyond = d / std::max(std::abs(d), 1e-30) * (0.6 / cm);
        if (on_line && std::abs(d) > 1e-9 * size) {
          write_bar(out, xy(other) + " -- " + xy(g.block + beyond));
        } else {
          out << "\\draw[gray, thin] " << xy(g.block - g.along * (0.25 * size)) << " -- "
              << xy(g.block + g.along * (0.25 * size)) << ";\n";
        }
      }
      out << "\\draw[thick, fill=white, rotate around={" << format_fixed(angle) << ":" << xy(g.block) << "}] "
          << xy(g.block) << " ++(-0.35,-0.2) rectangle ++(0.7,0.4);\n";
    } else {
      write_bar(out, xy(g.from) + " -- " + xy(g.to));
    }
  }
  // A point on a link of a vector-loop file drawn on it: a plate with a segment of the link
  // from where the point's own link vector starts; nothing more for a joint the loops
  // already reach; else a bar.
  for (const PointOnLink& on : at.points_on_links) {
    const auto near = [&](std::complex<double> a, std::complex<double> b) { return std::abs(a - b) < 1e-9 * size; };
    const Segment* base = nullptr;
    bool joint = false;
    for (const Segment& g : segments) {
      if (g.link != on.link) continue;
      joint = joint || near(g.from, on.at) || near(g.to, on.at);
      if ((near(g.from, on.from) && !near(g.to, on.at)) || (near(g.to, on.from) && !near(g.from, on.at))) base = &g;
    }
    if (joint && !base) continue;
    if (base) {
      out << "\\filldraw[fill=blue!10, draw=blue!70!black, thick, line join=round] " << xy(base->from) << " -- "
          << xy(base->to) << " -- " << xy(on.at) << " -- cycle;\n";
    } else {
      write_bar(out, xy(on.from) + " -- " + xy(on.at));
    }
  }
  // Link numbers beside each link's first segment.
  std::vector<bool> numbered(link_labels.size(), false);
  for (const Segment& g : segments) {
    if (g.link < 0 || numbered[g.link] || std::abs(g.to - g.from) < 1e-9 * size) continue;
    numbered[g.link] = true;
    const std::complex<double> across = (g.to - g.from) / std::abs(g.to - g.from) * std::complex<double>(0, 1);
    out << "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at "
        << xy(beside((g.from + g.to) / 2.0, across)) << " {" << latex_escape_text(link_labels[g.link])
        << "};\n";
  }
  // A link that is only a slider's guide (a crank carrying a slot): numbered beside it.
  for (const Segment& g : segments) {
    if (g.kind != Segment::Kind::slider || g.guide_link < 0 || numbered[g.guide_link] ||
        std::abs(g.to - g.from) < 1e-9 * size)
      continue;
    numbered[g.guide_link] = true;
    const std::complex<double> across = g.along * std::complex<double>(0, 1);
    out << "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at "
        << xy(beside((g.from + g.to) / 2.0, across)) << " {"
        << latex_escape_text(link_labels[g.guide_link]) << "};\n";
  }
  // Every block numbered: on the side of a fixed guide away from its hatching; beside a
  // block on a turning link, on the side away from its point's label (above left).
  for (const Segment& g : segments)
    if (g.kind == Segment::Kind::slider && !g.block_label.empty())
      out << "\\node[circle, draw, inner sep=1pt, font=\\scriptsize] at "
          << xy(g.block + g.along * std::complex<double>(0, (g.fixed_guide ? 0.55 : -0.55) / cm)) << " {"
          << latex_escape_text(g.block_label)
          << "};\n";
  // The angles that are coordinates, each once: an arc from the x direction at the joint
  // its link vector (or, for joints and links, its link) starts from.
  std::vector<bool> arced(system.unknowns.size() + 1, false);
  const auto arc = [&](int coordinate, double angle, std::complex<double> at) {
    const double degrees = std::remainder(to_degrees(angle), 360.0);
    if (coordinate < 0 || arced[std::size_t(coordinate)] || std::fabs(degrees) < 1) return;
    arced[std::size_t(coordinate)] = true;
    const GiNaC::ex symbol = coordinate == 0 ? GiNaC::ex(system.input.symbol)
                                             : GiNaC::ex(system.unknowns[std::size_t(coordinate) - 1].symbol);
    const double r = 0.55;  // cm
    out << "\\draw[gray, dashed] " << xy(at) << " -- ++(" << format_fixed(r + 0.25) << ",0);\n"
        << "\\draw[->, gray] " << xy(at) << " ++(" << format_fixed(r) << ",0) arc[start angle=0, end angle="
        << format_fixed(degrees) << ", radius=" << format_fixed(r) << "];\n"
        << "\\node[font=\\scriptsize, gray!30!black] at "
        << xy(at + std::polar((r + 0.3) / cm, from_degrees(degrees / 2))) << " {$" << to_latex(symbol) << "$};\n";
  };
  for (const Segment& g : segments)
    if (std::abs(g.to - g.from) >= 1e-9 * size) arc(g.coordinate, g.angle, g.angle_at);
  if (drawing)
    for (const LinkageDrawing::Link& link : drawing->links)
      if (!link.block) arc(link.coordinate, link.coordinate_angle, link.origin);
  for (const Segment& g : segments) {
    for (const auto& end : {g.from, g.to})
      out << "\\filldraw[fill=white] " << xy(end) << " circle (0.07);\n";
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    out << "\\fill " << xy(points[p]) << " circle (0.06) node[above left, font=\\small] {"
         << latex_escape_text(system.points[p].name) << "};\n";
    const std::string name = latex_symbol_name(system.points[p].name);  // v_B, a_B at the arrows' tips
    if (velocity_scale > 0 && std::abs(velocities[p]) > 0) {
      const std::complex<double> tip = velocities[p] * velocity_scale;
      out << "\\draw[-latex, red, thick] " << xy(points[p]) << " -- ++(" << format_fixed(tip.real()) << ","
           << format_fixed(tip.imag()) << ") node[anchor=" << anchor_beyond(tip) << ", inner sep=1pt, font=\\scriptsize, "
           << "red] {$\\mathbf{v}_{" << name << "}$};\n";
    }
    if (acceleration_scale > 0 && std::abs(accelerations[p]) > 0) {
      const std::complex<double> tip = accelerations[p] * acceleration_scale;
      out << "\\draw[-latex, green!50!black, thick, dashed] " << xy(points[p]) << " -- ++(" << format_fixed(tip.real())
          << "," << format_fixed(tip.imag()) << ") node[anchor=" << anchor_beyond(tip)
          << ", inner sep=1pt, font=\\scriptsize, green!50!black] {$\\mathbf{a}_{" << name << "}$};\n";
    }
  }
  // The scales in the caption: on the drawing's page, as its key.
  const double length_per_cm = 1.0 / cm / scale.length;
  std::string key = "The mechanism at the instant. Drawing scale: 1\\,cm = $" + latex_number(length_per_cm, 3) + "$\\," +
                    latex_escape_text(scale.length_unit);
  if (velocity_scale > 0) {
    key += "; velocity vectors (red): 1\\,cm = $" + latex_number(1.0 / velocity_scale / scale.length, 3) + "$\\," +
           latex_escape_text(scale.length_unit) + "/s";
  }
  if (acceleration_scale > 0) {
    key += "; acceleration vectors (green, dashed): 1\\,cm = $" + latex_number(1.0 / acceleration_scale / scale.length, 3) +
           "\\,\\mathrm{" + scale.length_unit + "/s^{2}}$";
  }
  out << "\\end{tikzpicture}\n" << latex_figure_caption(key + ".") << kLatexFigureEnd << "\n";
}

}  // namespace kinema
