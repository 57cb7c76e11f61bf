#include "engine/printers/latex/tikz_mechanism.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <string>

#include "engine/printers/latex/label_boxes.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/naming.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

constexpr double kCmPerPt = 2.54 / 72.27;
// Half a line's width in cm: thin (0.4 pt), thick (0.8 pt), very thick (1.2 pt), a bar's body (6 pt).
constexpr double kThin = 0.2 * kCmPerPt, kThick = 0.4 * kCmPerPt, kVeryThick = 0.6 * kCmPerPt, kBody = 3 * kCmPerPt;
// cm between a point's two arrows where they would meet: a thick -latex head reaches
// 3.75 (0.28 pt + 0.3 x 0.8 pt) = 0.07 cm either side of its shaft (pgfcorearrows), so two
// heads side by side need 0.14 cm; the rest is white between them.
constexpr double kArrowClearance = 0.25;
// An angle's arc: 0.55 cm from its vertex, wider up to 0.9 cm where its symbol then fits
// between the arms, and at most 0.8 of the link it measures.
constexpr double kArcSmallest = 0.55, kArcLargest = 0.9, kArcOnArm = 0.8;

using Planar = std::complex<double>;  // a point of the plane

// A label the drawing places once everything drawn is known: its TikZ node's options and
// text, its box, and what it names (a point or a box beside which it stands, or a link
// it stands beside); `path` the statement it ends (a point's dot, an arrow) or empty.
struct PendingLabel {
  std::string path, options, text;
  LabelBox size;
  LabelBox named;
  double preferred = 0;
  bool along = false;  // beside the line named.centre - end
  Planar end;
  int rank = 0;  // placed in rank order: what names a point first, an angle last
  std::vector<Planar> area{};  // a turned block's corners, when it names one
};

// The drawing of a planar mechanism in cm, as it is written: each shape into `out` and,
// as what its labels keep off, into `placed`; the labels after all of them.
class MechanismFigure {
 public:
  MechanismFigure(std::ostream& out, double cm, double size, Planar centre)
      : out_(out), cm_(cm), size_(size), centre_(centre) {}

  std::string xy(Planar p) const { return "(" + format_fixed(p.real() * cm_) + "," + format_fixed(p.imag() * cm_) + ")"; }
  Planar at_cm(Planar p) const { return p * cm_; }
  bool same(Planar a, Planar b) const { return std::abs(a - b) < 1e-9 * size_; }

  double cm() const { return cm_; }

  // The frame's axes, labelled beside their tips after every other label (they name no
  // part of the mechanism).
  void axes() {
    placed_.add_line(0, 1.2, kThin);
    placed_.add_line(0, Planar(0, 1.2), kThin);
  }
  void axis_labels() {
    for (const bool x : {true, false}) {
      const std::string name = x ? "$x$" : "$y$";
      pending_.push_back({x ? "\\draw[->, gray] (0,0) -- (1.2,0)" : "\\draw[->, gray] (0,0) -- (0,1.2)",
                          "font=\\scriptsize, inner sep=0pt", name, label_box(name, 8, 0), {x ? Planar(1.2) : Planar(0, 1.2), 0, 0},
                          x ? 0 : kPi / 2, false, 0});
    }
    place_labels();
  }

  // A fixed pivot: a triangle on hatched ground.
  void pivot(Planar at) {
    const std::string p = xy(at);
    out_ << "\\fill[pattern=north east lines] " << p << " ++(-0.3,-0.35) rectangle ++(0.6,0.15);\n"
         << "\\draw " << p << " ++(-0.3,-0.2) -- ++(0.6,0);\n"
         << "\\draw " << p << " -- ++(-0.15,-0.2) -- ++(0.3,0) -- cycle;\n";
    const Planar c = at_cm(at);
    placed_.add_area(parallelogram(c + Planar(-0.3, -0.35), 0.6, Planar(0, 0.15)));
    placed_.add_line(c + Planar(-0.3, -0.2), c + Planar(0.3, -0.2), kThin);
    placed_.add_area({c, c + Planar(-0.15, -0.2), c + Planar(0.15, -0.2)});
  }

  // A binary link drawn as a body, as the textbooks do: a light bar with rounded ends under
  // its centre line (the line is what tests and readers measure).
  void bar(const std::vector<Planar>& path) {
    std::string drawn;
    for (const Planar& p : path) drawn += (drawn.empty() ? "" : " -- ") + xy(p);
    out_ << "\\draw[line width=6pt, line cap=round, line join=round, blue!12] " << drawn << ";\n"
         << "\\draw[very thick, blue!70!black] " << drawn << ";\n";
    for (std::size_t k = 1; k < path.size(); ++k) placed_.add_line(at_cm(path[k - 1]), at_cm(path[k]), kBody);
  }
  void plate(const std::vector<Planar>& corners, const std::string& style) {
    std::string drawn;
    for (const Planar& p : corners) drawn += xy(p) + " -- ";
    out_ << "\\filldraw[fill=blue!10, draw=blue!70!black, " << style << ", line join=round] " << drawn << "cycle;\n";
    for (std::size_t k = 0; k < corners.size(); ++k)
      placed_.add_line(at_cm(corners[k]), at_cm(corners[(k + 1) % corners.size()]), kVeryThick);
  }
  // A slider block, 0.7 by 0.4 cm, turned along its guide.
  void block(Planar at, double angle) {
    out_ << "\\draw[thick, fill=white, rotate around={" << format_fixed(to_degrees(angle)) << ":" << xy(at) << "}] " << xy(at)
         << " ++(-0.35,-0.2) rectangle ++(0.7,0.4);\n";
    placed_.add_area(block_corners(at_cm(at), std::polar(1.0, angle)));
  }
  static std::vector<Planar> block_corners(Planar centre, Planar along) {
    return parallelogram(centre - along * Planar(0.35, 0.2), along * 0.7, along * Planar(0, 0.4));
  }
  // A fixed guide from a to b, hatched on its right.
  void guide(Planar a, Planar b) {
    const Planar along = (b - a) / std::abs(b - a);
    out_ << "\\draw[gray] " << xy(a) << " -- " << xy(b) << ";\n"
         << "\\fill[pattern=north east lines, rotate around={" << format_fixed(to_degrees(std::arg(along))) << ":" << xy(a)
         << "}] " << xy(a) << " rectangle ++(" << format_fixed(std::abs(b - a) * cm_) << ",-0.15);\n";
    placed_.add_line(at_cm(a), at_cm(b), kThin);
    placed_.add_area(parallelogram(at_cm(a), at_cm(b - a), along * Planar(0, -0.15)));
  }
  void line(Planar a, Planar b, const std::string& style) {
    out_ << "\\draw[" << style << "] " << xy(a) << " -- " << xy(b) << ";\n";
    placed_.add_line(at_cm(a), at_cm(b), kThin);
  }
  void dot(Planar at, double radius, const std::string& command) {
    out_ << command << " " << xy(at) << " circle (" << format_fixed(radius, 2) << ");\n";
    placed_.add({at_cm(at), radius, radius});
  }
  // A named point: its dot, written with its letter (above left of it where that is free).
  void point(Planar at, const std::string& letter) {
    placed_.add({at_cm(at), 0.06, 0.06});
    pending_.push_back({"\\fill " + xy(at) + " circle (0.06)", "font=\\small, inner sep=0pt", letter, label_box(letter, 10, 0),
                        {at_cm(at), 0, 0}, 3 * kPi / 4, false, 0});
  }

  // An arrow from a point, `tip` cm long, written with its name beyond its tip.
  void arrow(Planar from, Planar tip, const std::string& style, const std::string& name) {
    placed_.add_line(at_cm(from), at_cm(from) + tip, kThick);
    const std::string path = "\\draw[-latex, " + style + "] " + xy(from) + " -- ++(" + format_fixed(tip.real()) + "," +
                             format_fixed(tip.imag()) + ")";
    pending_.push_back({path, "inner sep=1pt, font=\\scriptsize, " + style.substr(0, style.find(", ")), name,
                        label_box(name, 8, 0), {at_cm(from) + tip, 0, 0}, std::arg(tip), false, 0, 2});
  }
  // Where a point's second arrow (`second`, cm) starts, from the point `at`: at the point
  // unless it would run into the first (`first`, drawn from the point: along it, or a few
  // degrees off with a head on the other's shaft); then beside it, as drawn by hand, at
  // least kArrowClearance from it: on the side away from the first arrow at that step,
  // unless it would run over what is drawn there (a block's edge, a link, hatching) and
  // a step further out (up to 1.8 times), or the other side, runs over less of it.
  // An arrow that would run along a link or a guide (most of it over what is drawn: a_B
  // toward the crank's pivot, hidden under the crank and ending on the pivot) is moved
  // beside it too; a point's first arrow is `second` with no `first`.
  Planar beside(Planar at, Planar first, Planar second, Planar first_offset = 0) const {
    const Planar from = at_cm(at), first_from = from + first_offset;
    const bool apart = std::abs(first) == 0 || arrows_distance(first_from, first, from, second) >= kArrowClearance;
    const bool hidden = along_drawing(from, second);
    if (apart && !hidden) return 0;
    const Planar left = second / std::abs(second) * Planar(0, 1);
    const double away = std::imag(first * std::conj(second)) > 0 ? -1 : 1;  // `first` on the left: step right
    Planar best = 0;
    // Along a link it moves, whatever it crosses beside it (a pivot's hatching, an axis).
    int least = apart && !hidden ? crowding(from, from + second) : -1;
    int rank = 0;  // each step out costs as much as two squares run over, the other side one
    for (const double step : {1.0, 1.4, 1.8}) {
      for (const double side : {away, -away}) {
        const Planar start = from + side * step * kArrowClearance * left;
        const int cost = crowding(start, start + second) + rank + (side == away ? 0 : 1);
        const bool clear = std::abs(first) == 0 || arrows_distance(first_from, first, start, second) >= kArrowClearance;
        if (clear && (least < 0 || cost < least)) {
          least = cost;
          best = start - from;
        }
      }
      rank += 2;
    }
    return best;
  }
  // Whether a point's two arrows, each from the point moved by its offset (cm), stand clear.
  bool arrows_clear(Planar at, Planar first, Planar first_offset, Planar second, Planar second_offset) const {
    if (std::abs(first) == 0 || std::abs(second) == 0) return true;
    const Planar from = at_cm(at);
    return arrows_distance(from + first_offset, first, from + second_offset, second) >= kArrowClearance;
  }
  // Whether an arrow from a, `tip` cm long, runs along what is drawn: more than half its
  // length (past the point's own dot) over lines, areas or dots.
  bool along_drawing(Planar a, Planar tip) const {
    const double length = std::abs(tip);
    if (length < 0.3) return false;
    const Planar start = a + tip / length * 0.15;  // past the dot and the joints' lines there
    const int squares = std::max(1, static_cast<int>(std::ceil((length - 0.15) / 0.07)));
    return 2 * crowding(start, a + tip) > squares + 1;
  }
  // How much of what is drawn (lines, areas, dots) a thick arrow from a to b (cm) would run
  // over: how many of the squares its head's width wide along it meet something.
  int crowding(Planar a, Planar b) const {
    const double half = 0.07;  // a thick -latex head's half-width, cm
    const int squares = std::max(1, static_cast<int>(std::ceil(std::abs(b - a) / half)));
    int met = 0;
    for (int k = 0; k <= squares; ++k) met += !placed_.free({a + (b - a) * (double(k) / squares), half, half});
    return met;
  }

  // An angle that is a coordinate: a dashed x direction at `at` and an arc to `degrees`,
  // near the vertex and within the link it measures (`arm` long, in metres; 0: not known).
  void angle_arc(Planar at, double degrees, double arm, const std::string& symbol) {
    const LabelBox size = label_box(symbol, 8, 0);
    const double reach = std::hypot(size.half_width, size.half_height);
    const double r = angle_mark_radius(from_degrees(degrees), reach + 0.25, arm * cm_, kArcSmallest, kArcLargest, kArcOnArm);  // cm
    out_ << "\\draw[gray, dashed] " << xy(at) << " -- ++(" << format_fixed(r + 0.25) << ",0);\n"
         << "\\draw[->, gray] " << xy(at) << " ++(" << format_fixed(r) << ",0) arc[start angle=0, end angle="
         << format_fixed(degrees) << ", radius=" << format_fixed(r) << "];\n";
    const Planar c = at_cm(at);
    placed_.add_line(c, c + (r + 0.25), kThin);
    const int chords = std::max(1, static_cast<int>(std::ceil(std::fabs(degrees) / 10)));
    for (int k = 0; k < chords; ++k)
      placed_.add_line(c + std::polar(r, from_degrees(degrees * k / chords)),
                       c + std::polar(r, from_degrees(degrees * (k + 1) / chords)), kThin);
    // The symbol beyond the middle of its arc; where even there the angle is too narrow
    // for it (between the arms it would sit on a line, and the placing would move it
    // anywhere near, onto a neighbouring angle), past the end of its dashed x direction,
    // on the side away from the link: where the narrow angle opens.
    const double half = from_degrees(std::fabs(degrees) / 2);
    const bool between = (r + 2 * reach) * std::sin(half) >= reach;
    const Planar named = between ? c + std::polar(r, from_degrees(degrees / 2)) : c + (r + 0.25);
    const double preferred = from_degrees(between ? degrees / 2 : -std::copysign(45.0, degrees));
    pending_.push_back({"", "font=\\scriptsize, inner sep=0pt, gray!30!black", symbol, size, {named, 0, 0}, preferred, false, 0, 5});
  }

  void pivot_label(Planar at, const std::string& text) {
    pending_.push_back({"", "font=\\small, inner sep=0pt", text, label_box(text, 10, 0), {at_cm(at), 0, 0}, -kPi / 4, false, 0, 1});
  }
  // A length's name beside the line a-b it measures (drawn already, dashed).
  void dimension_label(Planar a, Planar b, const std::string& name) {
    pending_.push_back({"", "font=\\small, inner sep=1pt", name, label_box(name, 10, 1), {at_cm(a), 0, 0}, 0, true, at_cm(b), 4});
  }
  // A link's number, circled, beside the line a-b.
  void link_number(Planar a, Planar b, const std::string& number) {
    pending_.push_back({"", "circle, draw, inner sep=1pt, font=\\scriptsize", number, circled(label_box(number, 8, 1)),
                        {at_cm(a), 0, 0}, 0, true, at_cm(b), 4});
  }
  // A block's number, circled, beside its block (0.7 by 0.4 cm turned by `angle`), towards
  // `preferred` first.
  void block_number(Planar at, double angle, double preferred, const std::string& number) {
    const Planar along = std::polar(1.0, angle);
    pending_.push_back({"", "circle, draw, inner sep=1pt, font=\\scriptsize", number, circled(label_box(number, 8, 1)),
                        {at_cm(at), 0, 0}, preferred, false, 0, 3, block_corners(at_cm(at), along)});
  }

  // Every label, in the order asked, where it meets nothing drawn nor placed before it.
  void place_labels() {
    std::stable_sort(pending_.begin(), pending_.end(), [](const PendingLabel& a, const PendingLabel& b) { return a.rank < b.rank; });
    std::vector<LabelRequest> requests;
    for (const PendingLabel& l : pending_) requests.push_back({l.named, l.size, l.preferred, l.along, false, l.end, false, l.area});
    const std::vector<PlacedLabel> boxes = placed_.place_all(requests);
    for (std::size_t k = 0; k < pending_.size(); ++k) {
      const PendingLabel& l = pending_[k];
      const LabelBox& chosen = boxes[k].box;
      out_ << (l.path.empty() ? "\\node" : l.path + " node") << "[" << l.options << "] at ("
           << format_fixed(chosen.centre.real(), 3) << "," << format_fixed(chosen.centre.imag(), 3) << ") {" << l.text << "};\n";
    }
    pending_.clear();
  }

 private:
  std::ostream& out_;
  const double cm_, size_;
  const Planar centre_;
  LabelBoxes placed_;
  std::vector<PendingLabel> pending_;
};

// Joints and links as drawn: fixed guides hatched, binary links as bars, links with
// more joints as plates, slider blocks as blocks on their lines, fixed pivots on ground;
// each link's number beside it, each pivot's name.
void draw_linkage(MechanismFigure& f, const LinkageDrawing& drawing, Planar centre, double size, bool numbered) {
  for (const LinkageDrawing::Guide& g : drawing.guides) {
    // The line across the drawing, hatched on one side: centred where the drawing's
    // centre projects onto it.
    const Planar middle = g.through + g.along * std::real((centre - g.through) * std::conj(g.along));
    f.guide(middle - g.along * (0.6 * size), middle + g.along * (0.6 * size));
  }
  for (const LinkageDrawing::Link& link : drawing.links) {
    if (link.block) {
      f.block(link.joints.front().at, link.angle);
      continue;
    }
    std::vector<Planar> path;
    for (const auto& joint : link.joints) path.push_back(joint.at);
    if (path.size() >= 3) f.plate(path, "very thick");
    else f.bar(path);
  }
  for (const auto& pivot : drawing.ground_pivots) {
    f.pivot(pivot.at);
    f.pivot_label(pivot.at, latex_escape_text(pivot.name));
  }
  for (const LinkageDrawing::Link& link : drawing.links)
    for (const auto& joint : link.joints) f.dot(joint.at, 0.07, "\\filldraw[fill=white]");
  for (const LinkageDrawing::Link& link : drawing.links) {
    const auto& joints = link.joints;
    if (!numbered || joints.empty()) continue;
    if (link.block) {  // a block: on the side of its guide away from the hatching first
      f.block_number(joints.front().at, link.angle, link.angle + kPi / 2, latex_escape_text(link.name));
    } else if (joints.size() >= 2 && !f.same(joints[1].at, joints[0].at)) {
      f.link_number(joints[0].at, joints[1].at, latex_escape_text(link.name));
    }
  }
}

// A vector-loop file's terms: ground lines between pivots, slider blocks on their guides,
// link vectors as bars; the points on links as plates or bars.
void draw_segments(MechanismFigure& f, const std::vector<DrawingSegment>& segments,
                   const std::vector<PointOnLink>& points_on_links, Planar centre, double size) {
  using Segment = DrawingSegment;
  for (const Segment& g : segments) {
    if (g.kind == Segment::Kind::ground) {
      f.line(g.from, g.to, "gray, dashed");
      if (g.pin_at_from) f.pivot(g.from);
      if (g.pin_at_to) f.pivot(g.to);
    } else if (g.kind == Segment::Kind::slider) {
      // The block at the slider's point, on the guide the geometry gives: a fixed guide
      // hatched across the drawing; a guide on a turning link drawn as that link, from the
      // term's other end through the block and on.
      const Planar other = f.same(g.block, g.to) ? g.from : g.to;
      if (g.fixed_guide) {
        const double t = std::real((centre - g.block) * std::conj(g.along));
        f.guide(g.block + g.along * std::min(t - 0.5 * size, -0.15 * size), g.block + g.along * std::max(t + 0.5 * size, 0.15 * size));
      } else {
        const Planar d = g.block - other;
        const bool on_line = std::abs(std::imag(d * std::conj(g.along))) < 1e-9 * size;
        if (on_line && std::abs(d) > 1e-9 * size) f.bar({other, g.block + d / std::abs(d) * (0.6 / f.cm())});
        else f.line(g.block - g.along * (0.25 * size), g.block + g.along * (0.25 * size), "gray, thin");
      }
      f.block(g.block, std::arg(g.along));
    } else {
      f.bar({g.from, g.to});
    }
  }
  // A point on a link drawn on it: a plate with a segment of the link from where the point's
  // own link vector starts; nothing more for a joint the loops already reach; else a bar.
  for (const PointOnLink& on : points_on_links) {
    const Segment* base = nullptr;
    bool joint = false;
    for (const Segment& g : segments) {
      if (g.link != on.link) continue;
      joint = joint || f.same(g.from, on.at) || f.same(g.to, on.at);
      if ((f.same(g.from, on.from) && !f.same(g.to, on.at)) || (f.same(g.to, on.from) && !f.same(g.from, on.at))) base = &g;
    }
    if (joint && !base) continue;
    if (base) f.plate({base->from, base->to, on.at}, "thick");
    else f.bar({on.from, on.at});
  }
  // The loops' origin is fixed: a link pinned there turns about a ground pivot (the
  // slider-crank's crank, whose loop has no ground term to draw one with).
  bool origin_drawn = false, origin_pinned = false;
  for (const Segment& g : segments) {
    origin_drawn = origin_drawn || (g.kind == Segment::Kind::ground && ((g.pin_at_from && f.same(g.from, 0)) || (g.pin_at_to && f.same(g.to, 0))));
    origin_pinned = origin_pinned || (g.kind == Segment::Kind::link && (f.same(g.from, 0) || f.same(g.to, 0)));
  }
  if (origin_pinned && !origin_drawn) f.pivot(0);
  for (const Segment& g : segments) {
    if (g.pin_at_from) f.dot(g.from, 0.07, "\\filldraw[fill=white]");
    if (g.pin_at_to) f.dot(g.to, 0.07, "\\filldraw[fill=white]");
  }
}

// A vector-loop file's link numbers beside each link's first segment (or the guide a link
// only carries: a crank with a slot); every block numbered on the side away from its
// guide's hatching first, or from its point's label.
void number_segments(MechanismFigure& f, const std::vector<DrawingSegment>& segments,
                     const std::vector<std::string>& link_labels) {
  using Segment = DrawingSegment;
  std::vector<bool> numbered(link_labels.size(), false);
  for (const Segment& g : segments) {
    if (g.link < 0 || numbered[g.link] || f.same(g.to, g.from)) continue;
    numbered[g.link] = true;
    f.link_number(g.from, g.to, latex_escape_text(link_labels[g.link]));
  }
  for (const Segment& g : segments) {
    if (g.kind != Segment::Kind::slider || g.guide_link < 0 || numbered[g.guide_link] || f.same(g.to, g.from)) continue;
    numbered[g.guide_link] = true;
    f.link_number(g.block - g.along * std::abs(g.to - g.from) * 0.5, g.block + g.along * std::abs(g.to - g.from) * 0.5,
                  latex_escape_text(link_labels[g.guide_link]));
  }
  for (const Segment& g : segments)
    if (g.kind == Segment::Kind::slider && !g.block_label.empty())
      f.block_number(g.block, std::arg(g.along), std::arg(g.along) + (g.fixed_guide ? 1 : -1) * kPi / 2,
                     latex_escape_text(g.block_label));
}

}  // namespace

void write_tikz_mechanism(std::ostream& out, const ConstraintSystem& system, const ValueAnalysis& at,
                          const std::vector<std::string>& link_labels, const MotionState& s, bool arrows) {
  const OutputScale scale(system);
  // Joints and links: the links as bodies (bars, plates, blocks); vector loops: their terms.
  const std::optional<LinkageDrawing>& drawing = at.linkage;
  const std::vector<DrawingSegment>& segments = at.segments;
  std::vector<Planar> extent = {{0, 0}};
  for (const DrawingSegment& segment : segments) extent.push_back(segment.to);
  if (drawing) {
    for (const auto& link : drawing->links)
      for (const auto& joint : link.joints) extent.push_back(joint.at);
    for (const auto& pivot : drawing->ground_pivots) extent.push_back(pivot.at);
  }
  std::vector<Planar> points, velocities, accelerations;
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
  const double velocity_scale = arrows && fastest > 0 ? arrow_cm / fastest : 0;  // cm per (m/s)
  const double acceleration_scale = arrows && largest > 0 ? arrow_cm / largest : 0;  // cm per (m/s^2)
  const Planar centre((min_x + max_x) / 2, (min_y + max_y) / 2);
  // Introduced by a sentence that stays with it (after the substitution's display).
  out << "\\par\\medskip\\noindent The mechanism at this instant, drawn to scale"
      << (velocity_scale > 0 || acceleration_scale > 0 ? ", with the velocities and accelerations of its points as arrows" : "")
      << ":\n" << kLatexFigureBegin << "\\begin{tikzpicture}[line cap=round]\n";
  MechanismFigure f(out, cm, size, centre);
  // The frame the positions are in: x and y from the origin.
  f.axes();
  if (drawing) draw_linkage(f, *drawing, centre, size, system.plan.has_value());
  draw_segments(f, segments, at.points_on_links, centre, size);
  for (const LetteredCorner& corner : at.lettered_corners) f.pivot_label(corner.at, latex_escape_text(corner.letter));
  for (const DrawnDimension& d : at.dimensions) {
    if (f.same(d.from, d.to)) continue;
    // A guide's offset is drawn here; a ground term's line is drawn already.
    const bool drawn = std::any_of(segments.begin(), segments.end(), [&](const DrawingSegment& g) {
      return g.kind == DrawingSegment::Kind::ground && ((f.same(g.from, d.from) && f.same(g.to, d.to)) || (f.same(g.from, d.to) && f.same(g.to, d.from)));
    });
    if (!drawn) f.line(d.from, d.to, "gray, dashed");
    f.dimension_label(d.from, d.to, "$" + to_latex(system.parameters[d.parameter].symbol) + "$");
  }
  number_segments(f, segments, link_labels);
  // The angles that are coordinates, each once: an arc from the x direction at the joint
  // its link vector (or, for joints and links, its link) starts from.
  std::vector<bool> arced(system.unknowns.size() + 1, false);
  const auto arc = [&](int coordinate, double angle, Planar from, double arm) {
    const double degrees = std::remainder(to_degrees(angle), 360.0);
    if (coordinate < 0 || arced[std::size_t(coordinate)] || std::fabs(degrees) < 1) return;
    arced[std::size_t(coordinate)] = true;
    const GiNaC::ex symbol = coordinate == 0 ? GiNaC::ex(system.input.symbol)
                                             : GiNaC::ex(system.unknowns[std::size_t(coordinate) - 1].symbol);
    f.angle_arc(from, degrees, arm, "$" + to_latex(symbol) + "$");
  };
  for (const DrawingSegment& g : segments)
    if (!f.same(g.to, g.from)) arc(g.coordinate, g.angle, g.angle_at, std::abs(g.to - g.from));
  if (drawing) {
    for (const LinkageDrawing::Link& link : drawing->links) {
      if (link.block) continue;
      // The link's reach from the vertex along its angle: its farthest joint that way.
      const Planar along = std::polar(1.0, link.coordinate_angle);
      double arm = 0;
      for (const auto& joint : link.joints) {
        const Planar d = (joint.at - link.origin) * std::conj(along);
        if (d.real() > 0 && std::fabs(d.imag()) <= 1e-9 * size) arm = std::max(arm, d.real());
      }
      arc(link.coordinate, link.coordinate_angle, link.origin, arm);
    }
  }
  // The points, their letters and their arrows (v_B, a_B at the arrows' tips).
  for (std::size_t p = 0; p < points.size(); ++p) {
    f.point(points[p], latex_escape_text(system.points[p].name));
    const std::string name = latex_symbol_name(system.points[p].name);
    // Each arrow beside what it would run along; where the acceleration then finds no
    // place clear of the velocity moved so, the velocity stays at the point.
    const Planar v = velocity_scale > 0 ? velocities[p] * velocity_scale : Planar(0);
    const Planar a = acceleration_scale > 0 ? accelerations[p] * acceleration_scale : Planar(0);
    Planar v_offset = std::abs(v) > 0 ? f.beside(points[p], 0, v) : Planar(0);
    Planar a_offset = std::abs(a) > 0 ? f.beside(points[p], v, a, v_offset) : Planar(0);
    if (!f.arrows_clear(points[p], v, v_offset, a, a_offset)) {
      v_offset = 0;
      a_offset = std::abs(a) > 0 ? f.beside(points[p], v, a) : Planar(0);
    }
    if (std::abs(v) > 0) f.arrow(points[p] + v_offset / f.cm(), v, "red, thick", "$\\mathbf{v}_{" + name + "}$");
    if (std::abs(a) > 0) {
      f.arrow(points[p] + a_offset / f.cm(), a, "green!50!black, thick, dashed",
              "$\\mathbf{a}_{" + name + "}$");
    }
  }
  f.place_labels();
  f.axis_labels();
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
