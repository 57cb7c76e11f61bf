#include "engine/printers/latex/label_boxes.hpp"
#include "engine/base/units.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>

namespace kinema {

namespace {

constexpr double kCmPerPt = 2.54 / 72.27;

// The width in pt of a run of math at `em` pt with no sub- or superscript in it: each
// glyph's share of its em, as Computer Modern sets it (script capitals are wide).
double run_width(const std::string& run, double em, bool script) {
  double width = 0;
  for (std::size_t i = 0; i < run.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(run[i]);
    if (c == '\\') {
      std::size_t end = i + 1;
      while (end < run.size() && std::isalpha(static_cast<unsigned char>(run[end]))) ++end;
      const std::string name = run.substr(i + 1, end - i - 1);
      if (name == "to") width += 1.7 * em;  // a relation, with its spaces
      else if (name == "infty") width += 1.05 * em;
      else if (name.empty()) width += 0.5 * em;  // \_ and the like
      else if (name != "mathbf" && name != "mathit" && name != "mathrm") width += 0.7 * em;  // a Greek letter
      i = name.empty() ? i + 1 : end - 1;
    } else if (c == '{' || c == '}' || c == '$') {
    } else if (std::isupper(c)) {
      width += (script ? 1.15 : 0.8) * em;
    } else if (c == '\'' || c == ' ') {
      width += 0.35 * em;
    } else if (c == ',') {
      width += 0.3 * em;
    } else {
      width += 0.6 * em;
    }
  }
  return width;
}

// The end of the group or single character after a ^ or _ at `at`.
std::size_t script_end(const std::string& latex, std::size_t at) {
  if (at + 1 >= latex.size() || latex[at + 1] != '{') return std::min(at + 2, latex.size());
  int depth = 0;
  for (std::size_t k = at + 1; k < latex.size(); ++k) {
    depth += latex[k] == '{' ? 1 : latex[k] == '}' ? -1 : 0;
    if (depth == 0) return k + 1;
  }
  return latex.size();
}

bool is_script_mark(const std::string& latex, std::size_t at) {
  return (latex[at] == '^' || latex[at] == '_') && !(at > 0 && latex[at - 1] == '\\');
}

}  // namespace

bool LabelBox::overlaps(const LabelBox& o) const {
  return std::fabs(o.centre.real() - centre.real()) < o.half_width + half_width &&
         std::fabs(o.centre.imag() - centre.imag()) < o.half_height + half_height;
}

double LabelBox::distance_to(std::complex<double> p) const {
  const double dx = std::max(std::fabs(p.real() - centre.real()) - half_width, 0.0);
  const double dy = std::max(std::fabs(p.imag() - centre.imag()) - half_height, 0.0);
  return std::sqrt(dx * dx + dy * dy);
}

namespace {

double point_to_segment(std::complex<double> p, std::complex<double> a, std::complex<double> b) {
  const std::complex<double> ab = b - a;
  const double length2 = std::norm(ab);
  const double t = length2 > 0 ? std::clamp(std::real((p - a) * std::conj(ab)) / length2, 0.0, 1.0) : 0.0;
  const std::complex<double> off = p - (a + ab * t);
  return std::sqrt(std::norm(off));
}

}  // namespace

double LabelBox::distance_to_segment(std::complex<double> a, std::complex<double> b) const {
  // Where the segment crosses the box (clipped to it, something is left), 0.
  const std::complex<double> d = b - a;
  double enter = 0, leave = 1;
  // The part of the segment where p * t <= q.
  const auto clip = [&](double p, double q) {
    if (p == 0) return q >= 0;
    const double t = q / p;
    if (p < 0) enter = std::max(enter, t);
    else leave = std::min(leave, t);
    return enter <= leave;
  };
  if (clip(-d.real(), a.real() - (centre.real() - half_width)) && clip(d.real(), centre.real() + half_width - a.real()) &&
      clip(-d.imag(), a.imag() - (centre.imag() - half_height)) && clip(d.imag(), centre.imag() + half_height - a.imag()))
    return 0;
  // Else two convex shapes apart are nearest at a corner of one: the segment's ends to the
  // box, the box's corners to the segment.
  double nearest = std::min(distance_to(a), distance_to(b));
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0})
      nearest = std::min(nearest, point_to_segment(centre + std::complex<double>(sx * half_width, sy * half_height), a, b));
  return nearest;
}

bool LabelBox::meets(const std::vector<std::complex<double>>& corners) const {
  // Separating axes: the box's two and each edge's normal; apart on one of them, apart.
  std::vector<std::complex<double>> axes = {{1, 0}, {0, 1}};
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const std::complex<double> edge = corners[(k + 1) % corners.size()] - corners[k];
    if (std::abs(edge) > 0) axes.push_back(edge * std::complex<double>(0, 1) / std::abs(edge));
  }
  for (const std::complex<double>& axis : axes) {
    const auto along = [&](std::complex<double> p) { return p.real() * axis.real() + p.imag() * axis.imag(); };
    const double reach = half_width * std::fabs(axis.real()) + half_height * std::fabs(axis.imag());
    double lo = INFINITY, hi = -INFINITY;
    for (const std::complex<double>& p : corners) lo = std::min(lo, along(p)), hi = std::max(hi, along(p));
    if (hi <= along(centre) - reach || lo >= along(centre) + reach) return false;
  }
  return true;
}

double LabelBox::distance_to_area(const std::vector<std::complex<double>>& corners) const {
  if (meets(corners)) return 0;
  double nearest = INFINITY;
  for (std::size_t k = 0; k < corners.size(); ++k)
    nearest = std::min(nearest, distance_to_segment(corners[k], corners[(k + 1) % corners.size()]));
  return nearest;
}

LabelBox label_box(const std::string& latex, double font_pt, double pad_pt, std::complex<double> centre) {
  // A script is 3/4 of \scriptsize's size, 7/10 of \small's; stacked scripts (a^{n}_{B})
  // take the wider one's width.
  const double script_em = font_pt * (font_pt >= 10 ? 0.7 : 0.75);
  double width = 0;
  for (std::size_t i = 0; i < latex.size();) {
    if (is_script_mark(latex, i)) {
      double widest = 0;
      while (i < latex.size() && is_script_mark(latex, i)) {
        const std::size_t end = script_end(latex, i);
        widest = std::max(widest, run_width(latex.substr(i + 1, end - i - 1), script_em, true));
        i = end;
      }
      width += widest;
      continue;
    }
    std::size_t end = i;
    while (end < latex.size() && !is_script_mark(latex, end)) ++end;
    width += run_width(latex.substr(i, end - i), font_pt, false);
    i = end;
  }
  // Height and depth with scripts (a^{t}_{B}): 1.2 em in all.
  return {centre, (width / 2 + pad_pt) * kCmPerPt, (0.6 * font_pt + pad_pt) * kCmPerPt};
}

void LabelBoxes::add_line(std::complex<double> a, std::complex<double> b, double half_width) {
  lines_.push_back({a, b, half_width});
}

double LabelBoxes::cost(const LabelBox& c, const Line* except) const {
  // Lines and areas kept a point clear of, as a reader sees a label touching one as on it.
  constexpr double clearance = 1 * kCmPerPt;
  const LabelBox widened{c.centre, c.half_width + clearance, c.half_height + clearance};
  const double met = 2 * c.half_width * c.half_height;
  double cost = 0;
  for (const LabelBox& o : boxes_)
    cost += std::max(0.0, o.half_width + c.half_width - std::fabs(o.centre.real() - c.centre.real())) *
            std::max(0.0, o.half_height + c.half_height - std::fabs(o.centre.imag() - c.centre.imag()));
  for (const Line& line : lines_)
    if (&line != except && widened.distance_to_segment(line.a, line.b) < line.half_width) cost += met;
  for (const auto& area : areas_)
    if (widened.meets(area)) cost += met;
  return cost;
}

PlacedLabel with_leader(std::complex<double> at, double dot, const LabelBox& box) {
  const std::complex<double> nearest(std::clamp(at.real(), box.centre.real() - box.half_width, box.centre.real() + box.half_width),
                                     std::clamp(at.imag(), box.centre.imag() - box.half_height, box.centre.imag() + box.half_height));
  const std::complex<double> along = (nearest - at) / std::abs(nearest - at);
  return {box, true, at + along * dot, nearest - along * kCmPerPt};
}

double LabelBoxes::leader_cost(const PlacedLabel& c) const {
  if (!c.led) return 0;
  double cost = 0;
  for (const LabelBox& o : boxes_)
    if (o.distance_to(c.leader_from) > 0 && o.distance_to_segment(c.leader_from, c.leader_to) < kCmPerPt)
      cost += 2 * c.box.half_width * c.box.half_height;
  return cost;
}

PlacedLabel LabelBoxes::place_first_free(const std::vector<PlacedLabel>& candidates, const Line* except) {
  const PlacedLabel* chosen = nullptr;
  double least = INFINITY;
  for (const PlacedLabel& c : candidates) {
    const double overlap = cost(c.box, except) + leader_cost(c);
    if (overlap < least) {
      least = overlap;
      chosen = &c;
    }
    if (overlap == 0) break;
  }
  last_cost_ = least;
  boxes_.push_back(chosen->box);
  if (chosen->led) lines_.push_back({chosen->leader_from, chosen->leader_to, kLeaderHalfWidth});
  return *chosen;
}

std::vector<PlacedLabel> LabelBoxes::place_all(const std::vector<LabelRequest>& requests) {
  std::vector<std::size_t> order(requests.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::vector<PlacedLabel> best;
  LabelBoxes best_figure;
  std::size_t fewest = requests.size() + 1;
  for (int round = 0; round < 4; ++round) {
    LabelBoxes trial = *this;
    std::vector<PlacedLabel> placed(requests.size());
    std::vector<std::size_t> crowded, free;
    for (std::size_t k : order) {
      placed[k] = trial.place(requests[k]);
      (trial.last_cost_ > 0 ? crowded : free).push_back(k);
    }
    if (crowded.size() < fewest) {
      fewest = crowded.size();
      best = placed;
      best_figure = trial;
    }
    if (crowded.empty()) break;
    order = crowded;
    order.insert(order.end(), free.begin(), free.end());
  }
  *this = best_figure;
  return best;
}

PlacedLabel LabelBoxes::place_near(const LabelBox& named, const LabelBox& size, double preferred, bool may_lead,
                                   const std::vector<std::complex<double>>& named_area) {
  std::vector<PlacedLabel> candidates;
  const double reach = label_reach(size);
  // The distance between the box's and what it names' nearest points.
  const auto apart = [&](const LabelBox& c) {
    if (!named_area.empty()) return c.distance_to_area(named_area);
    return std::hypot(std::max(std::fabs(c.centre.real() - named.centre.real()) - c.half_width - named.half_width, 0.0),
                      std::max(std::fabs(c.centre.imag() - named.centre.imag()) - c.half_height - named.half_height, 0.0));
  };
  // Within a label's height first; only where all that is taken, a little further, or
  // (a label that may be led) further still with a leader.
  std::vector<double> gaps = {0.12, 0.3, 0.5, 0.7, 0.85, 0.95};
  if (may_lead) {
    for (double gap = 1.25; gap <= kLeaderReach; gap += 0.25) gaps.push_back(gap);
  } else {
    gaps.insert(gaps.end(), {1.2, 1.5});
  }
  for (double gap : gaps) {
    for (int k = 0; k < 48; ++k) {
      const double angle = preferred + (k % 2 ? 1 : -1) * ((k + 1) / 2) * kPi / 24;
      const std::complex<double> along(std::cos(angle), std::sin(angle));
      // The distance out along `along` at which the box stands `gap` label heights off what it names.
      double lo = 0, hi = named.half_width + named.half_height + size.half_width + size.half_height + (gap + 1) * reach;
      for (int step = 0; step < 40; ++step) {
        const double mid = (lo + hi) / 2;
        if (apart({named.centre + mid * along, size.half_width, size.half_height}) < gap * reach) lo = mid;
        else hi = mid;
      }
      const LabelBox box{named.centre + hi * along, size.half_width, size.half_height};
      candidates.push_back(may_lead && gap > 1 ? with_leader(named.centre, kLeaderDot, box) : PlacedLabel{box});
    }
  }
  return place_first_free(candidates);
}

LabelBox LabelBoxes::place_along(std::complex<double> a, std::complex<double> b, const LabelBox& size, bool on_it) {
  std::vector<PlacedLabel> candidates;
  const std::complex<double> across = (b - a) / std::abs(b - a) * std::complex<double>(0, 1);
  // On it, then to either side, a little further each time; nearest the middle first.
  // First its middle half, either side before a step further out: a label slid along one
  // side to the line's end would stand on the joint there (a link's number on its pivot).
  // Then past the middle half and its ends too, where a label is still within reach of it.
  const auto add = [&](double side, double t) {
    const LabelBox c{a + (b - a) * t + across * (side * size.half_height), size.half_width, size.half_height};
    if (c.distance_to_segment(a, b) <= label_reach(size)) candidates.push_back({c});
  };
  const std::initializer_list<double> sides{0.0, 1.0, -1.0, 1.5, -1.5, 2.0, -2.0, 2.5, -2.5, 3.0, -3.0, 3.5, -3.5};
  for (double side : sides) {
    if (side == 0 && !on_it) continue;
    for (int k = 0; k < 11; ++k) add(side, 0.5 + (k % 2 ? 1 : -1) * ((k + 1) / 2) * 0.05);
  }
  for (double side : sides) {
    if (side == 0 && !on_it) continue;
    for (int k = 11; k < 35; ++k) add(side, 0.5 + (k % 2 ? 1 : -1) * ((k + 1) / 2) * 0.05);
  }
  // The line itself, when the label may stand on it.
  const Line* itself = nullptr;
  for (const Line& line : lines_)
    if (on_it && ((line.a == a && line.b == b) || (line.a == b && line.b == a))) itself = &line;
  return place_first_free(candidates, itself).box;
}

}  // namespace kinema
