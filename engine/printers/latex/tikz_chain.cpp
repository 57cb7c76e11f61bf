#include "engine/printers/latex/tikz_chain.hpp"

#include <algorithm>
#include <array>
#include <complex>
#include <cmath>
#include <map>

#include "engine/printers/latex/label_boxes.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"

namespace kinema {
namespace {

using Point3 = std::array<double, 3>;

}  // namespace

void write_tikz_chain(std::ostream& out, const ConstraintSystem& system, const std::vector<PlacedFrame>& frames,
                      const MotionState& s) {
  const std::string observer = chain_observer(system);
  const auto origin_of = [&](const std::string& name) {
    for (const PlacedFrame& f : frames)
      if (f.name == name) return f.origin;
    return Point3{0, 0, 0};
  };

  const ChainBodies bodies = chain_bodies(system);
  std::vector<Point3> points;
  if (s.status == Status::ok)
    for (const PointMotion& p : s.points) points.push_back({p.position[0], p.position[1], p.position[2]});
  const ChainView view = chain_view(system, frames, points);
  const auto on_page = [&](const Point3& p) { return view.on_page(p); };

  double size = 0;  // the drawing's extent from the observer's origin
  for (const PlacedFrame& f : frames)
    for (double x : f.origin) size = std::max(size, std::fabs(x));
  double fastest = 0;
  if (s.status == Status::ok) {
    for (const PointMotion& p : s.points) {
      for (double x : p.position) size = std::max(size, std::fabs(x));
      fastest = std::max(fastest, p.speed());
    }
  }
  size = std::max(size, 1e-9);
  const double cm = 5.0 / size;    // drawing units per metre
  const double axis_cm = 1.0;      // each frame's triad
  const double velocity_scale = fastest > 0 ? 2.0 / fastest : 0;  // cm per (m/s)
  // One text per place (-0 and rounding noise as 0): places that coincide share a label.
  const auto coordinate = [](double x) {
    const double rounded = std::round(x * 1e4) / 1e4;
    return format_fixed(rounded == 0 ? 0.0 : rounded, 4);
  };
  const auto at = [&](const Point3& p) {
    return "(" + coordinate(p[0] * cm) + "," + coordinate(p[1] * cm) + "," + coordinate(p[2] * cm) + ")";
  };
  const auto plus = [](const Point3& d, double cm_along) {
    return "(" + format_fixed(d[0] * cm_along) + "," + format_fixed(d[1] * cm_along) + "," +
           format_fixed(d[2] * cm_along) + ")";
  };

  out << "\\par\\medskip\\noindent The chain at this instant, drawn in three dimensions"
      << (velocity_scale > 0 ? " with the velocities of its points as arrows" : "") << ":\n"
      << kLatexFigureBegin << "\\tdplotsetmaincoords{" << format_fixed(view.theta, 0) << "}{" << format_fixed(view.phi, 0)
      << "}\n"
      << "\\begin{tikzpicture}[tdplot_main_coords, line cap=round, >=latex]\n";
  const std::string o = latex_escape_text(observer);
  const double reach = 5.0 + 0.8;
  out << "\\draw[->, gray] (0,0,0) -- (" << format_fixed(reach) << ",0,0) node[anchor=north east] {$x_{\\text{" << o
      << "}}$};\n"
      << "\\draw[->, gray] (0,0,0) -- (0," << format_fixed(reach) << ",0) node[anchor=north west] {$y_{\\text{" << o
      << "}}$};\n"
      << "\\draw[->, gray] (0,0,0) -- (0,0," << format_fixed(reach) << ") node[anchor=south] {$z_{\\text{" << o
      << "}}$};\n";
  // What is drawn is kept, on the page, so that the names are set where they cover none of it.
  LabelBoxes drawn;
  const double dot = 1.5 * 2.54 / 72.27;  // a place's dot (1.5 pt), cm
  const auto page_of = [&](const Point3& p) { return on_page({p[0] * cm, p[1] * cm, p[2] * cm}); };
  const auto line_on_page = [&](const Point3& a, const Point3& b) { drawn.add_line(page_of(a), page_of(b), 0.03); };
  // The bodies (ChainBodies), as the planar figures draw a link: a light bar under its line.
  const auto bar = [&](const Point3& a, const Point3& b) {
    line_on_page(a, b);
    if (at(a) == at(b)) return;  // a point at its frame's origin: no body to draw
    out << "\\draw[line width=6pt, line cap=round, blue!12] " << at(a) << " -- " << at(b) << ";\n"
        << "\\draw[very thick, blue!70!black] " << at(a) << " -- " << at(b) << ";\n";
  };
  const auto point_at = [&](std::size_t p) {
    const PointMotion& m = s.points[p];
    return Point3{m.position[0], m.position[1], m.position[2]};
  };
  // Each frame on its parent's body, or on a ground pivot (its parent the observer).
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (!bodies.ground_frames[k]) bar(origin_of(frames[k].parent), frames[k].origin);
  if (s.status == Status::ok) {
    for (std::size_t p = 0; p < s.points.size(); ++p)
      if (!bodies.point_frames[p].empty()) bar(origin_of(bodies.point_frames[p]), point_at(p));
    for (const auto& ends : bodies.couplers) bar(point_at(ends[0]), point_at(ends[1]));
  }
  // Each frame's triad; the names of the frames and points at each place, once.
  // A ground pivot as the planar figures draw one, a triangle on hatched ground, set on the
  // page under the place (cm).
  const auto ground_pivot = [&](std::complex<double> c) {
    using P = std::complex<double>;
    const auto canvas = [](P p) {
      return "(canvas cs:x=" + format_fixed(p.real(), 3) + "cm,y=" + format_fixed(p.imag(), 3) + "cm)";
    };
    out << "\\fill[pattern=north east lines] " << canvas(c + P(-0.3, -0.35)) << " rectangle " << canvas(c + P(0.3, -0.2))
        << ";\n"
        << "\\draw " << canvas(c + P(-0.3, -0.2)) << " -- " << canvas(c + P(0.3, -0.2)) << ";\n"
        << "\\draw[fill=white] " << canvas(c) << " -- " << canvas(c + P(-0.15, -0.2)) << " -- " << canvas(c + P(0.15, -0.2))
        << " -- cycle;\n";
    drawn.add_area({c + P(-0.3, -0.35), c + P(0.3, -0.35), c + P(0.3, -0.2), c + P(-0.3, -0.2)});
    drawn.add_area({c, c + P(-0.15, -0.2), c + P(0.15, -0.2)});
  };
  for (int c = 0; c < 3; ++c) {
    Point3 end{0, 0, 0};
    end[c] = reach / cm;
    line_on_page({0, 0, 0}, end);
  }
  std::map<std::string, std::pair<Point3, std::string>> names_at;  // by the place as written
  const auto name_at = [&](const Point3& p, const std::string& name) {
    auto& [place, names] = names_at[at(p)];
    place = p;
    names += (names.empty() ? "" : ", ") + latex_escape_text(name);
  };
  name_at({0, 0, 0}, observer);
  for (const PlacedFrame& f : frames) {
    static const char* const axis_names[3] = {"x", "y", "z"};
    for (std::size_t c = 0; c < 3; ++c) {
      out << "\\draw[->, thin] " << at(f.origin) << " -- ++" << plus(f.axes[c], axis_cm)
          << " node[font=\\tiny, anchor=west] {$" << axis_names[c] << "$};\n";
      const std::complex<double> from = page_of(f.origin);
      const std::complex<double> tip = from + on_page({f.axes[c][0] * axis_cm, f.axes[c][1] * axis_cm, f.axes[c][2] * axis_cm});
      drawn.add_line(from, tip, 0.02);
      LabelBox letter = label_box(axis_names[c], 5, 1.5);  // \tiny, anchored west at the tip
      letter.centre = tip + letter.half_width;
      drawn.add(letter);
    }
    const std::size_t k = std::size_t(&f - frames.data());
    if (!bodies.joints[k].empty()) name_at(f.origin, bodies.joints[k]);
    name_at(f.origin, f.name);
    drawn.add(LabelBox{page_of(f.origin), dot, dot});
    if (bodies.ground_frames[k]) ground_pivot(page_of(f.origin));
    out << "\\filldraw[fill=white] " << at(f.origin) << " circle (1.5pt);\n";
  }
  if (s.status == Status::ok) {
    for (std::size_t p = 0; p < s.points.size(); ++p) {
      const PointMotion& m = s.points[p];
      const Point3 position{m.position[0], m.position[1], m.position[2]};
      out << "\\fill " << at(position) << " circle (1.5pt);\n";
      drawn.add(LabelBox{page_of(position), dot, dot});
      name_at(position, system.points[p].name);
      if (velocity_scale > 0 && m.speed() > 0) {
        out << "\\draw[->, red, thick] " << at(position) << " -- ++"
            << plus({m.velocity[0], m.velocity[1], m.velocity[2]}, velocity_scale) << ";\n";
        const std::complex<double> from = page_of(position);
        drawn.add_line(from, from + on_page({m.velocity[0] * velocity_scale, m.velocity[1] * velocity_scale,
                                             m.velocity[2] * velocity_scale}), 0.03);
      }
    }
  }
  // Each name beside its place, below and left first (where the frames' axes seldom go),
  // on no other name, dot, link or arrow where there is room: set on the page's own axes.
  for (const auto& entry : names_at) {
    const auto& [place, names] = entry.second;
    const PlacedLabel label = drawn.place_near(page_of(place), label_box(names, 10, 2), -3 * M_PI / 4);
    out << "\\node[font=\\small, inner sep=2pt] at (canvas cs:x=" << format_fixed(label.box.centre.real(), 3)
        << "cm,y=" << format_fixed(label.box.centre.imag(), 3) << "cm) {" << names << "};\n";
  }
  // The scales in the caption: on the drawing's page, as its key.
  const OutputScale scale(system);
  std::string key = "The chain at the instant. Drawing scale: 1\\,cm = $" + latex_number(1.0 / cm / scale.length, 3) + "$\\," +
                    latex_escape_text(scale.length_unit) + "; each frame's axes drawn 1\\,cm long";
  if (velocity_scale > 0) {
    key += "; velocity vectors (red): 1\\,cm = $" + latex_number(1.0 / velocity_scale / scale.length, 3) + "$\\," +
           latex_escape_text(scale.length_unit) + "/s";
  }
  out << "\\end{tikzpicture}\n" << latex_figure_caption(key + ".") << kLatexFigureEnd << "\n";
}

}  // namespace kinema
