#include "tests/engine/printers/tikz_reader.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace kinema_test {

namespace {

constexpr double kCmPerPt = 2.54 / 72.27;
constexpr double kPi = 3.14159265358979323846;

// The text from `at` (an opening bracket or brace) to its match, both excluded; `at` moves past it.
std::string enclosed(const std::string& s, std::size_t& at, char open, char close) {
  int depth = 0;
  const std::size_t start = at + 1;
  for (; at < s.size(); ++at) {
    depth += s[at] == open ? 1 : s[at] == close ? -1 : 0;
    if (depth == 0) break;
  }
  const std::string inside = s.substr(start, at - start);
  ++at;
  return inside;
}

// A statement's or node's options, split at the commas outside braces.
std::vector<std::string> split_options(const std::string& options) {
  std::vector<std::string> parts(1);
  int depth = 0;
  for (char c : options) {
    depth += c == '{' ? 1 : c == '}' ? -1 : 0;
    if (c == ',' && depth == 0) parts.emplace_back();
    else parts.back() += c;
  }
  for (std::string& p : parts) {
    p.erase(0, p.find_first_not_of(' '));
    p.erase(p.find_last_not_of(' ') + 1);
  }
  return parts;
}

std::string option_value(const std::vector<std::string>& options, const std::string& key) {
  for (const std::string& o : options)
    if (o.rfind(key + "=", 0) == 0) return o.substr(key.size() + 1);
  return "";
}

bool has_option(const std::vector<std::string>& options, const std::string& option) {
  return std::find(options.begin(), options.end(), option) != options.end();
}

// Half the width of the lines a statement draws, in cm (TikZ's thin is 0.4 pt).
double half_line_width(const std::vector<std::string>& options) {
  const std::string width = option_value(options, "line width");
  if (!width.empty()) return std::stod(width) / 2 * kCmPerPt;
  double pt = 0.4;
  if (has_option(options, "ultra thick")) pt = 1.6;
  else if (has_option(options, "very thick")) pt = 1.2;
  else if (has_option(options, "thick")) pt = 0.8;
  else if (has_option(options, "very thin")) pt = 0.2;
  return pt / 2 * kCmPerPt;
}

double font_pt(const std::vector<std::string>& options) {
  const std::string font = option_value(options, "font");
  if (font == "\\tiny") return 6;
  if (font == "\\scriptsize") return 8;
  if (font == "\\footnotesize") return 9;
  if (font == "\\small") return 10;
  return 10.95;  // \normalsize of an 11 pt document
}

// The anchor a node's options put at its position: "north west" and the like, or "center".
std::string node_anchor(const std::vector<std::string>& options) {
  const std::string anchor = option_value(options, "anchor");
  if (!anchor.empty()) return anchor;
  for (const std::string& o : options) {
    std::string result;
    std::istringstream words(o);
    bool placement = true;
    for (std::string w; words >> w;) {
      if (w == "above") result += " south";
      else if (w == "below") result += " north";
      else if (w == "left") result += " east";
      else if (w == "right") result += " west";
      else placement = false;
    }
    if (placement && !result.empty()) return result.substr(1);
  }
  return "center";
}

// A node's box as a reader sees it: its text at its font, with its inner sep where the node
// is drawn round or filled (a circled number, a label on white); its anchor at `at`, then shifted.
kinema::LabelBox node_box(const std::vector<std::string>& options, const std::string& text, TikzPoint at) {
  const double pt = font_pt(options);
  const std::string sep_option = option_value(options, "inner sep");
  const double sep = sep_option.empty() ? pt / 3 : std::stod(sep_option);
  const bool seen_whole = has_option(options, "draw") || !option_value(options, "fill").empty();
  kinema::LabelBox box = kinema::label_box(text, pt, seen_whole ? sep : 0);
  if (has_option(options, "circle")) box = kinema::circled(box);
  // The anchor is on the node's outer box, its inner sep included.
  const std::string anchor = node_anchor(options);
  const double outer = seen_whole ? 0 : sep * kCmPerPt;
  const double reach_x = box.half_width + outer, reach_y = box.half_height + outer;
  TikzPoint centre = at;
  if (anchor.find("north") != std::string::npos) centre -= TikzPoint(0, reach_y);
  if (anchor.find("south") != std::string::npos) centre += TikzPoint(0, reach_y);
  if (anchor.find("east") != std::string::npos) centre -= TikzPoint(reach_x, 0);
  if (anchor.find("west") != std::string::npos) centre += TikzPoint(reach_x, 0);
  for (const char* shift : {"xshift", "yshift"}) {
    const std::string value = option_value(options, shift);
    if (value.empty()) continue;
    REQUIRE(value.substr(value.size() - 2) == "cm");
    centre += shift[0] == 'x' ? TikzPoint(std::stod(value), 0) : TikzPoint(0, std::stod(value));
  }
  box.centre = centre;
  return box;
}

TikzPoint read_point(const std::string& s, std::size_t& at) {
  double x = 0, y = 0;
  REQUIRE(std::sscanf(s.c_str() + at, "(%lf,%lf)", &x, &y) == 2);
  at = s.find(')', at) + 1;
  return {x, y};
}

// One statement's path, read in its own coordinates; turned at the end if its options say so.
class StatementReader {
 public:
  StatementReader(const std::string& s, int number, TikzFigure& figure) : s_(s), number_(number), figure_(figure) {}

  void read() {
    at_ = s_.find_first_of("[ (", 0);
    const std::string command = s_.substr(0, at_);
    if (command != "\\draw" && command != "\\fill" && command != "\\filldraw" && command != "\\node" && command != "\\path")
      return;
    draws_ = command != "\\fill" && command != "\\path";
    skip();
    if (at_ < s_.size() && s_[at_] == '[') options_ = split_options(enclosed(s_, at_, '[', ']'));
    if (command == "\\node") {
      read_node(options_);  // \node[...]: its options are the node's
      return;
    }
    for (skip(); at_ < s_.size() && s_[at_] != ';'; skip()) step();
    turn();
  }

 private:
  void skip() {
    while (at_ < s_.size() && s_[at_] == ' ') ++at_;
  }
  bool next_is(const std::string& word) { return s_.compare(at_, word.size(), word) == 0; }

  void step() {
    if (next_is("++(")) {
      at_ += 2;
      move_to(current_ + read_point(s_, at_));
    } else if (next_is("(")) {
      move_to(read_point(s_, at_));
    } else if (next_is("--")) {
      at_ += 2;
      joint_ = "--";
    } else if (next_is("rectangle")) {
      at_ += 9;
      joint_ = "rectangle";
    } else if (next_is("cycle")) {
      at_ += 5;
      line(current_, start_);
      joint_.clear();
    } else if (next_is("circle")) {
      at_ += 6;
      skip();
      double r = 0;
      REQUIRE(std::sscanf(s_.c_str() + at_, "(%lf)", &r) == 1);
      at_ = s_.find(')', at_) + 1;
      area({current_ + TikzPoint(-r, -r), current_ + TikzPoint(r, -r), current_ + TikzPoint(r, r), current_ + TikzPoint(-r, r)},
           "dot");
    } else if (next_is("arc[")) {
      at_ += 3;
      arc(split_options(enclosed(s_, at_, '[', ']')));
    } else if (next_is("node")) {
      at_ += 4;
      skip();
      read_node({});
    } else {
      FAIL("a TikZ step not understood at '" << s_.substr(at_) << "' in " << s_);
    }
  }

  void move_to(TikzPoint p) {
    if (joint_ == "--") {
      line(current_, p);
    } else if (joint_ == "rectangle") {
      const std::vector<TikzPoint> corners = {current_, {p.real(), current_.imag()}, p, {current_.real(), p.imag()}};
      area(corners, has_option(options_, "pattern=north east lines") ? "hatching" : "block");
      if (draws_)
        for (std::size_t k = 0; k < 4; ++k) line(corners[k], corners[(k + 1) % 4]);
    } else {
      start_ = p;
    }
    joint_.clear();
    previous_ = current_;
    current_ = p;
  }

  void line(TikzPoint a, TikzPoint b) {
    if (draws_) figure_.lines.push_back({a, b, half_line_width(options_), number_});
  }
  void area(std::vector<TikzPoint> corners, const std::string& kind) {
    figure_.areas.push_back({std::move(corners), kind, number_});
  }

  // An arc as chords of at most 10 degrees.
  void arc(const std::vector<std::string>& options) {
    const double from = std::stod(option_value(options, "start angle")) * kPi / 180;
    const double to = std::stod(option_value(options, "end angle")) * kPi / 180;
    const double r = std::stod(option_value(options, "radius"));
    const TikzPoint centre = current_ - std::polar(r, from);
    const int chords = std::max(1, static_cast<int>(std::ceil(std::fabs(to - from) / (kPi / 18))));
    TikzPoint last = current_;
    for (int k = 1; k <= chords; ++k) {
      const TikzPoint p = centre + std::polar(r, from + (to - from) * k / chords);
      line(last, p);
      last = p;
    }
    previous_ = current_;
    current_ = last;
  }

  // A node: where the path is (or along its last step at pos), or at its own point;
  // `options` those already read (a \node statement's).
  void read_node(std::vector<std::string> options) {
    if (at_ < s_.size() && s_[at_] == '[') options = split_options(enclosed(s_, at_, '[', ']'));
    skip();
    TikzPoint where = current_;
    const std::string pos = option_value(options, "pos");
    if (!pos.empty()) where = previous_ + (current_ - previous_) * std::stod(pos);
    if (next_is("at ")) {
      at_ += 3;
      where = read_point(s_, at_);
      skip();
    }
    REQUIRE(next_is("{"));
    const std::string text = enclosed(s_, at_, '{', '}');
    figure_.labels.push_back({text, node_box(options, text, where), number_});
  }

  // rotate around={degrees:(x,y)}: the statement's lines and areas turned about that point.
  void turn() {
    const std::string around = option_value(options_, "rotate around");
    if (around.empty()) return;
    double degrees = 0, x = 0, y = 0;
    REQUIRE(std::sscanf(around.c_str(), "{%lf:(%lf,%lf)}", &degrees, &x, &y) == 3);
    const TikzPoint pivot(x, y), turn = std::polar(1.0, degrees * kPi / 180);
    for (TikzLine& l : figure_.lines)
      if (l.statement == number_) l.a = pivot + (l.a - pivot) * turn, l.b = pivot + (l.b - pivot) * turn;
    for (TikzArea& a : figure_.areas)
      if (a.statement == number_)
        for (TikzPoint& p : a.corners) p = pivot + (p - pivot) * turn;
  }

  const std::string& s_;
  const int number_;
  TikzFigure& figure_;
  std::size_t at_ = 0;
  bool draws_ = true;
  std::vector<std::string> options_;
  std::string joint_;
  TikzPoint current_, previous_, start_;
};

}  // namespace

TikzFigure read_tikz(const std::string& figure) {
  TikzFigure read;
  std::istringstream in(figure);
  int number = 0;
  for (std::string line; std::getline(in, line); ++number) {
    CAPTURE(line);
    StatementReader(line, number, read).read();
  }
  return read;
}

std::vector<std::string> plane_figures(const std::string& tex) {
  std::vector<std::string> figures;
  const std::string begin = "\\begin{tikzpicture}[line cap=round";
  for (auto at = tex.find(begin); at != std::string::npos; at = tex.find(begin, at + 1)) {
    const auto body = tex.find('\n', at) + 1;
    figures.push_back(tex.substr(body, tex.find("\\end{tikzpicture}", at) - body));
  }
  return figures;
}

bool box_meets_area(const kinema::LabelBox& box, const TikzArea& area, double slack) {
  // Separating axes: the box's two and each edge's normal.
  const double hw = box.half_width - slack, hh = box.half_height - slack;
  if (hw <= 0 || hh <= 0) return false;
  std::vector<TikzPoint> axes = {{1, 0}, {0, 1}};
  for (std::size_t k = 0; k < area.corners.size(); ++k) {
    const TikzPoint edge = area.corners[(k + 1) % area.corners.size()] - area.corners[k];
    if (std::abs(edge) > 0) axes.push_back(edge * TikzPoint(0, 1) / std::abs(edge));
  }
  for (const TikzPoint& axis : axes) {
    const auto along = [&](TikzPoint p) { return p.real() * axis.real() + p.imag() * axis.imag(); };
    const double reach = hw * std::fabs(axis.real()) + hh * std::fabs(axis.imag());
    const double c = along(box.centre);
    double lo = 1e300, hi = -1e300;
    for (const TikzPoint& p : area.corners) lo = std::min(lo, along(p)), hi = std::max(hi, along(p));
    if (hi <= c - reach || lo >= c + reach) return false;
  }
  return true;
}

}  // namespace kinema_test
