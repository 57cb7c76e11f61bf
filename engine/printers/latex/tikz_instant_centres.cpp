#include "engine/printers/latex/tikz_instant_centres.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "engine/printers/latex/label_boxes.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

std::string centre_latex(const InstantCentres& c, const InstantCentre& centre) {
  return "I_{" + latex_escape_text(c.bodies[centre.a]) + latex_escape_text(c.bodies[centre.b]) + "}";
}

// How a centre is shown, in cm: a dot at `to`, or an arrow from `from` to `to`.
struct CentreMark {
  bool dot = false;
  std::complex<double> from, to;
};

// Half a thin line and half a very thick one, in cm (0.4 and 1.2 pt).
constexpr double kThinHalf = 0.2 * 2.54 / 72.27, kVeryThickHalf = 0.6 * 2.54 / 72.27;

// The centres' dots and arrows, each labelled next to its dot or its arrow's tip where no
// other label, dot, pivot, block or line is (the shared LabelBoxes placing: `placed` holds
// what the figure drew before).
template <class MarkOf>
void write_centre_marks(std::ostream& out, const InstantCentres& c, LabelBoxes& placed, const MarkOf& mark_of) {
  const auto cm_xy = [](std::complex<double> p) {
    return "(" + format_fixed(p.real(), 3) + "," + format_fixed(p.imag(), 3) + ")";
  };
  std::vector<CentreMark> marks;
  for (const InstantCentre& centre : c.centres) {
    marks.push_back(mark_of(centre));
    if (marks.back().dot) placed.add({marks.back().to, 0.1, 0.1});
    else placed.add_line(marks.back().from, marks.back().to, kThinHalf);
  }
  const auto label_of = [&](std::size_t k) {
    return centre_latex(c, c.centres[k]) + (c.centres[k].at_infinity ? "\\to\\infty" : "");
  };
  // A dot's label above right, as a figure letters its points, or where the centres crowd
  // further out with a leader; an arrow's beyond its tip.
  std::vector<LabelRequest> requests;
  for (std::size_t k = 0; k < c.centres.size(); ++k)
    requests.push_back({{marks[k].to, 0, 0}, label_box("$" + label_of(k) + "$", 8, 0),
                        marks[k].dot ? kPi / 4 : std::arg(marks[k].to - marks[k].from), false, false, 0, marks[k].dot});
  const std::vector<PlacedLabel> placed_labels = placed.place_all(requests);
  for (std::size_t k = 0; k < c.centres.size(); ++k) {
    const CentreMark& m = marks[k];
    const PlacedLabel& chosen = placed_labels[k];
    if (chosen.led) out << "\\draw[red!75!black, very thin] " << cm_xy(chosen.leader_from) << " -- " << cm_xy(chosen.leader_to) << ";\n";
    out << (m.dot ? "\\filldraw[red!75!black, fill=white] " + cm_xy(m.to) + " circle (0.07)"
                  : std::string("\\draw[->, red!75!black") + (c.centres[k].at_infinity ? "" : ", dashed") + "] " +
                        cm_xy(m.from) + " -- " + cm_xy(m.to))
        << " node[font=\\scriptsize, inner sep=0pt] at " << cm_xy(chosen.box.centre) << " {$" << label_of(k) << "$};\n";
  }
}

// Joints and links as placed; a vector-loop file's link vectors as segments.
LinkageDrawing drawing_for_centres(const ValueAnalysis& at) {
  std::optional<LinkageDrawing> drawing = at.linkage;
  if (!drawing) {
    drawing.emplace();
    for (const DrawingSegment& segment : at.segments) {
      if (segment.kind == DrawingSegment::Kind::ground) continue;
      if (segment.kind == DrawingSegment::Kind::slider) {
        // A block on its guide; a guide on a turning link drawn as that link up to the block.
        drawing->links.push_back({{{"", segment.block}}, true, std::arg(segment.along), "", -1, 0, {}});
        if (segment.fixed_guide) continue;
        const std::complex<double> other = segment.block == segment.to ? segment.from : segment.to;
        drawing->links.push_back({{{"", other}, {"", segment.block}}, false, 0, "", -1, 0, {}});
        continue;
      }
      drawing->links.push_back({{{"", segment.from}, {"", segment.to}}, false, 0, "", -1, 0, {}});
    }
    // Fixed pivots: each loop's start (the origin) and ground vectors' ends where pinned.
    const auto pivot = [&](std::complex<double> at) {
      for (const auto& p : drawing->ground_pivots)
        if (std::abs(p.at - at) <= 1e-9 * std::max(std::abs(at), 1.0)) return;
      drawing->ground_pivots.push_back({"", at});
    };
    for (const DrawingSegment& segment : at.segments) {
      if (segment.pin_at_from && (segment.loop_start || segment.kind == DrawingSegment::Kind::ground)) pivot(segment.from);
      if (segment.pin_at_to && segment.kind == DrawingSegment::Kind::ground) pivot(segment.to);
    }
  }
  return *drawing;
}

// The figure: the mechanism, the Kennedy lines and the centres (those off the figure as
// arrows at its edge), the drawing scale in its caption.
void write_centres_figure(std::ostream& out, const LinkageDrawing& linkage, const InstantCentres& c, const OutputScale& scale) {
  const LinkageDrawing* drawing = &linkage;
  // The mechanism's extent; centres within twice its size around it are drawn.
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  const auto grow = [&](std::complex<double> p) {
    min_x = std::min(min_x, p.real());
    max_x = std::max(max_x, p.real());
    min_y = std::min(min_y, p.imag());
    max_y = std::max(max_y, p.imag());
  };
  for (const auto& link : drawing->links)
    for (const auto& joint : link.joints) grow(joint.at);
  for (const auto& pivot : drawing->ground_pivots) grow(pivot.at);
  const double size = std::max({max_x - min_x, max_y - min_y, 1e-9});
  const std::complex<double> middle((min_x + max_x) / 2, (min_y + max_y) / 2);
  const auto on_figure = [&](const InstantCentre& centre) {
    return !centre.at_infinity && std::abs(centre.at.real() - middle.real()) <= 1.5 * size &&
           std::abs(centre.at.imag() - middle.imag()) <= 1.5 * size;
  };
  for (const InstantCentre& centre : c.centres)
    if (on_figure(centre)) grow(centre.at);
  const double cm = 11.0 / std::max({max_x - min_x, max_y - min_y, 1e-9});  // figure units per metre
  const auto xy = [&](std::complex<double> p) {
    return "(" + format_fixed(p.real() * cm, 3) + "," + format_fixed(p.imag() * cm, 3) + ")";
  };
  out << kLatexFigureBegin << "\\begin{tikzpicture}[line cap=round, >=latex]\n";
  // The figure's frame: a centre beyond it is an arrow at its edge pointing to it.
  const double fx0 = min_x * cm, fx1 = max_x * cm, fy0 = min_y * cm, fy1 = max_y * cm;
  const auto edge_towards = [&](std::complex<double> from, std::complex<double> along) {  // cm
    double t = 1e300;
    if (along.real() > 1e-12) t = std::min(t, (fx1 - from.real()) / along.real());
    if (along.real() < -1e-12) t = std::min(t, (fx0 - from.real()) / along.real());
    if (along.imag() > 1e-12) t = std::min(t, (fy1 - from.imag()) / along.imag());
    if (along.imag() < -1e-12) t = std::min(t, (fy0 - from.imag()) / along.imag());
    return from + along * std::max(t, 0.0);
  };
  const auto cm_xy = [&](std::complex<double> p) {
    return "(" + format_fixed(p.real(), 3) + "," + format_fixed(p.imag(), 3) + ")";
  };
  LabelBoxes placed;  // every line, block and pivot drawn, then the centres' labels
  // The Kennedy lines: each secondary centre on two lines of known centres; a line to a
  // centre off the figure runs to the figure's edge towards it.
  for (const InstantCentre& centre : c.centres) {
    if (centre.at_infinity) continue;
    for (const auto& [a, b] : centre.kennedy) {
      const InstantCentre* other = c.find(a, b);
      if (!other || other->at_infinity || (!on_figure(centre) && !on_figure(*other))) continue;
      const InstantCentre& near = on_figure(centre) ? centre : *other;
      const InstantCentre& far = on_figure(centre) ? *other : centre;
      if (std::abs(far.at - near.at) <= 1e-12 * size) continue;
      const std::complex<double> end =
          on_figure(far) ? far.at * cm : edge_towards(near.at * cm, (far.at - near.at) / std::abs(far.at - near.at));
      out << "\\draw[gray!60, dashed] " << xy(near.at) << " -- " << cm_xy(end) << ";\n";
      placed.add_line(near.at * cm, end, kThinHalf);
    }
  }
  for (const auto& link : drawing->links) {
    std::string path;
    for (const auto& joint : link.joints) path += (path.empty() ? "" : " -- ") + xy(joint.at);
    if (link.block) {  // 0.6 by 0.3 cm, turned by its angle
      const std::complex<double> at = link.joints.front().at * cm, along = std::polar(1.0, link.angle);
      out << "\\draw[thick, fill=white, rotate around={" << format_fixed(to_degrees(link.angle)) << ":"
          << xy(link.joints.front().at) << "}] " << xy(link.joints.front().at) << " ++(-0.3,-0.15) rectangle ++(0.6,0.3);\n";
      placed.add_area(parallelogram(at - along * std::complex<double>(0.3, 0.15), along * 0.6, along * std::complex<double>(0, 0.3)));
      continue;
    }
    out << "\\draw[very thick, blue!70!black] " << path << (link.joints.size() >= 3 ? " -- cycle" : "") << ";\n";
    for (std::size_t k = 0; k + 1 < link.joints.size() + (link.joints.size() >= 3 ? 1 : 0); ++k)
      placed.add_line(link.joints[k].at * cm, link.joints[(k + 1) % link.joints.size()].at * cm, kVeryThickHalf);
  }
  for (const auto& pivot : drawing->ground_pivots) {
    out << "\\draw " << xy(pivot.at) << " -- ++(-0.15,-0.25) -- ++(0.3,0) -- cycle;\n";
    placed.add_area(parallelogram(pivot.at * cm + std::complex<double>(-0.15, -0.25), 0.3, std::complex<double>(0, 0.25)));
  }
  write_centre_marks(out, c, placed, [&](const InstantCentre& centre) {
    if (centre.at_infinity) {  // an arrow from its joint (else the middle) towards it
      const std::complex<double> from = centre.seen_from.value_or(middle) * cm;
      return CentreMark{false, from, from + centre.at * 1.2};
    }
    if (!on_figure(centre)) {  // off the figure: an arrow at its edge pointing to it
      const std::complex<double> towards = (centre.at - middle) / std::abs(centre.at - middle);
      const std::complex<double> tip = edge_towards(middle * cm, towards);
      return CentreMark{false, tip - towards * 1.0, tip};
    }
    return CentreMark{true, centre.at * cm, centre.at * cm};
  });
  // The scale in the caption: on the drawing's page, as its key.
  out << "\\end{tikzpicture}\n"
      << latex_figure_caption("Instant centres. Drawing scale: 1\\,cm = $" + latex_number(1.0 / cm / scale.length, 3) +
                              "\\,\\mathrm{" + scale.length_unit + "}$.")
      << kLatexFigureEnd;
}

// What the figure shows, in a sentence.
void write_centres_sentence(std::ostream& out, const ConstraintSystem& system, const InstantCentres& c) {
  if (system.plan) {
    out << "Instant centres: the primary ones at the pins and, for a slider, at infinity across its line; every "
           "other by the Aronhold--Kennedy theorem, where two lines of centres it shares a body with cross (dashed).";
  } else {
    out << "Instant centres of the loops' links (a link vector of fixed length, known by a joint whose velocity is "
           "known) and slider blocks (at the sliding point, turning with the guide; numbered in the gaps the links "
           "leave), each where the two bodies' velocities agree, with two lines of centres through it (dashed, "
           "Aronhold--Kennedy); ground is link "
        << latex_escape_text(c.bodies[0]) << ".";
  }
  out << "\n\n";
}

// Every pair of bodies, n(n-1)/2 rows: where its centre is and how it was found.
void write_centres_table(std::ostream& out, const ConstraintSystem& system, const InstantCentres& c, const OutputScale& scale) {
  const std::string l = scale.length_unit;
  const DocumentNumbers number(system);  // round-off as 0, as everywhere in the document
  out << "\\medskip\n\\begin{tabular}{lrrl}\n\\toprule\ncentre & $x$ & $y$ & found by \\\\\n & $\\mathrm{" << l << "}$ & $\\mathrm{"
      << l << "}$ & \\\\\n\\midrule\n";
  // Those no two lines fix say so; two bodies at rest relative to each other have any point.
  for (std::size_t a = 0; a < c.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < c.bodies.size(); ++b) {
      const InstantCentre* found = c.find(a, b);
      if (!found) {
        const bool as_one = std::find(c.moving_as_one.begin(), c.moving_as_one.end(), std::pair(a, b)) != c.moving_as_one.end();
        out << "$I_{" << latex_escape_text(c.bodies[a]) << latex_escape_text(c.bodies[b]) << "}$ & \\multicolumn{2}{c}{"
            << (as_one ? "any point} & the two move as one for the instant" : "not found} & no two lines of known centres cross there")
            << " \\\\\n";
        continue;
      }
      const InstantCentre& centre = *found;
      out << "$" << centre_latex(c, centre) << "$ & ";
      if (centre.at_infinity) {
        // Its direction's round-off as 0 (-7.017e-15 deg was "10^{-15}^{\\circ}", a double superscript
        // pdflatex stops on), braced so that the degree sign never follows another superscript.
        out << "\\multicolumn{2}{c}{at infinity, ${" << number(to_degrees(std::arg(centre.at)), Dimension::angle, 0, 4)
            << "}^{\\circ}$}";
      } else {
        // A coordinate that is rounding noise next to the mechanism's size prints as 0.
        const auto shown = [&](double v) { return number(v / scale.length, Dimension::length, 0, 5); };
        out << "$" << shown(centre.at.real()) << "$ & $" << shown(centre.at.imag()) << "$";
      }
      std::string how = centre.found_by;
      // Pins and sliders name their joint; the others the two lines of centres they are on.
      if (!centre.kennedy.empty() && system.plan) how = "Kennedy: lines " + how;
      out << " & " << latex_escape_text(how) << " \\\\\n";
    }
  }
  out << "\\bottomrule\n\\end{tabular}\n\n";
}

// The angular-velocity ratios from the centres beside the solved ones.
void write_ratios_table(std::ostream& out, const ConstraintSystem& system, const InstantCentres& c) {
  const DocumentNumbers number(system);
  const std::string driver = latex_escape_text(c.bodies[c.driver]);
  out << "\\begin{tabular}{lrr}\n\\toprule\nratio & from the centres & solved \\\\\n\\midrule\n";
  for (const VelocityRatio& r : c.ratios) {
    const std::string j = latex_escape_text(c.bodies[r.body]);
    const std::string ground = latex_escape_text(c.bodies[0]);
    out << "$\\omega_{" << j << "}/\\omega_{" << driver << "} = \\overline{I_{" << ground << driver << "}I_{" << driver << j
        << "}}/\\overline{I_{" << ground << j << "}I_{" << driver << j << "}}$ & $" << number.ratio(r.from_centres, 6) << "$ & $"
        << number.ratio(r.analytic, 6) << "$ \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\n";
}

}  // namespace

void write_tikz_instant_centres(std::ostream& out, const ConstraintSystem& system, const ValueAnalysis& at,
                                const InstantCentres& c) {
  const OutputScale scale(system);
  write_centres_figure(out, drawing_for_centres(at), c, scale);
  write_centres_sentence(out, system, c);
  write_centres_table(out, system, c, scale);
  if (!c.ratios.empty()) write_ratios_table(out, system, c);
}

}  // namespace kinema
