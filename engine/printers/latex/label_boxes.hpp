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
};

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

/// The boxes placed so far on one figure (labels, and the dots they must not cover): a new
/// label takes the first of its candidate places that overlaps none of them, always within
/// label_reach of what it names.
class LabelBoxes {
 public:
  void add(const LabelBox& box) { boxes_.push_back(box); }
  bool free(const LabelBox& box) const;
  /// A box of `size`'s half sizes beside the point `at`: first towards `preferred` (radians),
  /// then turning either way, then a little further out; placed and returned.
  LabelBox place_near(std::complex<double> at, const LabelBox& size, double preferred);
  /// A box of `size`'s half sizes on the segment a-b (nearest its middle) or just beside it.
  LabelBox place_along(std::complex<double> a, std::complex<double> b, const LabelBox& size);

 private:
  // The first free candidate, else the one overlapping the least; placed and returned.
  LabelBox place_first_free(const std::vector<LabelBox>& candidates);
  std::vector<LabelBox> boxes_;
};

}  // namespace kinema
