// Labels of a TikZ figure placed where no other label (nor a dot) is, each next to what
// it names: the polygons' and the instant centres' figures share this one placing.
#pragma once

#include <cmath>
#include <complex>
#include <string>
#include <vector>

namespace kinema {

/// A label's box on a figure, in cm: its centre and half sizes.
struct LabelBox {
  std::complex<double> centre;
  double half_width = 0, half_height = 0;
  bool overlaps(const LabelBox& other) const;
  /// From `p` to the nearest point of the box (0 inside it).
  double distance_to(std::complex<double> p) const;
  /// From the segment a-b to the nearest point of the box (0 where they meet).
  double distance_to_segment(std::complex<double> a, std::complex<double> b) const;
  /// True when the box and the convex polygon `corners` (in order) share more than an edge.
  bool meets(const std::vector<std::complex<double>>& corners) const;
  /// From the convex polygon `corners` to the nearest point of the box (0 where they meet).
  double distance_to_area(const std::vector<std::complex<double>>& corners) const;
};

/// The corners of the parallelogram from `corner` along `side` and `other_side`: a block or a
/// hatching turned as it is drawn.
inline std::vector<std::complex<double>> parallelogram(std::complex<double> corner, std::complex<double> side,
                                                       std::complex<double> other_side) {
  return {corner, corner + side, corner + side + other_side, corner + other_side};
}

/// The box of math `latex` ("$I_{12}$", "a^{n}_{B}") set at `font_pt` (8 for \scriptsize,
/// 10 for \small in an 11 pt document) and `pad_pt` of inner sep, centred at `centre`:
/// its glyphs estimated from the Computer Modern widths, never much under them (sub- and
/// superscripts stacked, markup not counted).
LabelBox label_box(const std::string& latex, double font_pt, double pad_pt, std::complex<double> centre = 0);

/// A circled label's box (a link's number): the circle round `text`'s box, as TikZ draws it.
inline LabelBox circled(LabelBox text) {
  text.half_width = text.half_height = std::hypot(text.half_width, text.half_height);
  return text;
}

/// How far a label may stand from what it names: one label height.
inline double label_reach(const LabelBox& box) { return 2 * box.half_height; }

/// A label to place: beside `named` towards `preferred` first (place_near), or with `along`
/// beside the line named.centre-end (place_along, on it first with `on_it`). With
/// `may_lead`, a label with no free place within label_reach stands further out, joined
/// to what it names by a leader. A turned block names by `named_area`, its corners: its
/// label's reach is measured from the block, not from the box round it.
struct LabelRequest {
  LabelBox named, size;
  double preferred = 0;
  bool along = false, on_it = false;
  std::complex<double> end;
  bool may_lead = false;
  std::vector<std::complex<double>> named_area{};
};

/// A label placed: its box and, where it stands beyond label_reach of what it names, its
/// leader, a thin line from beside what it names (past its dot) to 1 pt short of the box.
struct PlacedLabel {
  LabelBox box;
  bool led = false;
  std::complex<double> leader_from{}, leader_to{};
};

/// The leader from the point `at` (its dot `dot` cm round) to 1 pt short of `box`.
PlacedLabel with_leader(std::complex<double> at, double dot, const LabelBox& box);

/// What is on one figure so far: the labels placed and the dots they must not cover, the
/// lines they must not cross and the areas (hatching, blocks) they must not stand on. A new
/// label takes the first of its candidate places that meets none of them, always within
/// label_reach of what it names; the figure registers everything it draws before placing.
class LabelBoxes {
 public:
  void add(const LabelBox& box) { boxes_.push_back(box); }
  /// A drawn line, `half_width` cm either side of a-b (a bar's body: 3 pt).
  void add_line(std::complex<double> a, std::complex<double> b, double half_width);
  /// A convex area, its corners in order.
  void add_area(std::vector<std::complex<double>> corners) { areas_.push_back(std::move(corners)); }
  bool free(const LabelBox& box) const { return cost(box, nullptr) == 0; }
  /// A box of `size`'s half sizes beside `named` (a point's zero box, a block's box): first
  /// towards `preferred` (radians), then turning either way, then a little further out
  /// (with `may_lead`, out to kLeaderReach with a leader: `named` a point); its distance
  /// from `named_area` where that is given; placed and returned.
  PlacedLabel place_near(const LabelBox& named, const LabelBox& size, double preferred, bool may_lead = false,
                         const std::vector<std::complex<double>>& named_area = {});
  PlacedLabel place_near(std::complex<double> at, const LabelBox& size, double preferred) {
    return place_near(LabelBox{at, 0, 0}, size, preferred);
  }
  /// A box of `size`'s half sizes beside the line a-b (nearest its middle); with `on_it`,
  /// on the line first (a label set on white over the arrow it names, which is then no
  /// obstacle to it).
  LabelBox place_along(std::complex<double> a, std::complex<double> b, const LabelBox& size, bool on_it);
  /// Every request placed, as each alone would be, in the order that leaves fewest on
  /// something: as asked, then those that found no free place first (a crowded label takes
  /// its one free place before a freer neighbour does). Their boxes, as requested.
  std::vector<PlacedLabel> place_all(const std::vector<LabelRequest>& requests);

  /// How far out a led label may stand, in label heights.
  static constexpr double kLeaderReach = 4;
  /// A leader's dot: labels with leaders name points drawn as dots this size (cm).
  static constexpr double kLeaderDot = 0.1;
  /// Half a leader's width (very thin, 0.2 pt), in cm.
  static constexpr double kLeaderHalfWidth = 0.1 * 2.54 / 72.27;

 private:
  struct Line {
    std::complex<double> a, b;
    double half_width;
  };
  // 0 where the box meets nothing; else how badly it does (labels' overlap, and a share of
  // its area for each line or area it meets). `except` is a line it may cover.
  double cost(const LabelBox& box, const Line* except) const;
  // What a leader meets: a label or dot (not the one at its own start) it runs through.
  double leader_cost(const PlacedLabel& c) const;
  // The first free candidate, else the one that costs the least; placed (its leader a line
  // later labels keep off) and returned.
  PlacedLabel place_first_free(const std::vector<PlacedLabel>& candidates, const Line* except = nullptr);
  PlacedLabel place(const LabelRequest& r) {
    return r.along ? PlacedLabel{place_along(r.named.centre, r.end, r.size, r.on_it)}
                   : place_near(r.named, r.size, r.preferred, r.may_lead, r.named_area);
  }
  double last_cost_ = 0;  // what the last placed label meets
  std::vector<LabelBox> boxes_;
  std::vector<Line> lines_;
  std::vector<std::vector<std::complex<double>>> areas_;
};

}  // namespace kinema
