#include "linkages/linkage_loops.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <complex>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/user_text.hpp"
#include "engine/constraints/formula_reader.hpp"
#include "loops/planar_loops.hpp"
#include "readers/mechanism_file.hpp"  // check_shared_names

namespace kinema {
namespace {

using Point2 = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

// A given length may differ from the sketch by this much (relative): sketches are
// drawn to a few digits (Example 4.1 gives x_B = y_B = 0.256 m for |BC| = 0.3 m);
// more than this is a typo in one of the two.
constexpr double kSketchTolerance = 0.01;

// A signed term of a loop, as written ("BC*exp(I*phi2)").
struct Term {
  bool negative = false;
  std::string text;
};

std::vector<Term> negated(std::vector<Term> terms) {
  for (Term& t : terms) t.negative = !t.negative;
  return terms;
}

std::string sum_text(const std::vector<Term>& terms) {
  if (terms.empty()) return "0";
  std::string text;
  for (const Term& t : terms) {
    if (text.empty()) text = t.negative ? "-" + t.text : t.text;
    else text += (t.negative ? " - " : " + ") + t.text;
  }
  return text;
}

bool is_identifier(const std::string& text) {
  if (text.empty() || !std::isalpha(static_cast<unsigned char>(text[0]))) return false;
  return std::all_of(text.begin(), text.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// Angle in (-pi, pi].
double wrapped(double angle) {
  angle = std::remainder(angle, 2 * kPi);
  return angle <= -kPi ? angle + 2 * kPi : angle;
}

class LinkageWriter {
 public:
  explicit LinkageWriter(Mechanism& mechanism) : m_(mechanism), linkage_(*mechanism.linkage) {}

  /// The solving plan found by write().
  SolvingPlan plan() && { return std::move(plan_); }

  void write() {
    evaluate_parameters();
    place_joints();
    make_bodies();
    make_edges();
    check_connected();
    check_mobility();
    choose_driver();
    reserve_names();
    orient_bodies();
    name_coordinates();
    write_loops();
    write_points();
    decompose();
    export_plan();
  }

 private:
  struct Body {
    std::string name;            // "ground" or the link's name
    const Link* link = nullptr;  // nullptr for ground
    std::vector<std::size_t> joints;
    int slider = -1;             // joint index of the slider it is the block of
    std::string angle;           // formula of its angle ("0" for ground; a block: its guide's) ...
    double offset = 0;           // ... plus this constant (a block: its line's angle to its guide)
    double angle0 = 0;           // in the sketch (offset included)
    bool oriented = false;
    int parent_edge = -1;
    int parent = -1;
    std::size_t depth = 0;
  };
  struct Edge {
    std::size_t joint;
    std::size_t a, b;  // pin: the two bodies; slider: a = guide, b = block
    bool slider = false;
    bool in_tree = false;
  };

  Mechanism& m_;
  const Linkage& linkage_;
  SolvingPlan plan_;
  std::map<std::string, double> values_;  // parameters, SI
  GiNaC::exmap symbol_values_;            // the file's parameters by their symbols in reader_
  std::set<std::string> taken_;           // symbol names
  std::map<std::string, std::string> generated_;  // parameters made here, by the name wanted
  FormulaReader reader_;
  std::vector<Point2> at_;                // joints in the sketch
  std::vector<Body> bodies_;              // 0 = ground
  std::map<std::string, std::size_t> body_index_;
  std::map<std::string, std::size_t> joint_index_;
  std::vector<Edge> edges_;
  std::vector<std::array<std::size_t, 5>> dyad_edges_;  // first, second, outer edges and inner edge
  std::vector<std::string> slider_coordinate_;  // per joint (sliders)
  std::vector<double> slider_value0_;
  std::size_t driver_body_ = 0;
  int driver_slider_ = -1;

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw InputError(where.str() + ": " + message);
  }

  // ---- numbers -------------------------------------------------------------------

  void evaluate_parameters() {
    for (const Parameter& p : m_.parameters) taken_.insert(p.name);
    for (const Parameter& p : m_.parameters) {
      double value = 0;
      if (p.quantity) {
        value = p.quantity->si_value;
      } else {
        value = evaluate(p.formula, p.where, "parameter \"" + p.name + "\"");
      }
      values_[p.name] = value;
      const GiNaC::realsymbol symbol(p.name);
      reader_.define(p.name, symbol);
      symbol_values_[symbol] = value;
    }
  }

  double evaluate(const std::string& formula, const SourceLocation& where, const std::string& what) {
    const std::string context = where.str() + ": " + what;
    return formula_value(reader_.read(formula, context), symbol_values_, context, formula,
                         " once the parameters are put in");
  }

  // A length or angle as written: a quantity ("0.3 m") or a formula of the parameters.
  double value_of(const std::string& text, Dimension dimension, const SourceLocation& where, const std::string& what) {
    if (!looks_like_quantity(text)) return evaluate(text, where, what);
    return quantity_of_dimension(text, dimension, where.str() + ": " + what);
  }

  std::string fresh_name(const std::string& wanted) {
    std::string name = wanted;
    for (int k = 2; taken_.count(name); ++k) name = wanted + "_" + std::to_string(k);
    taken_.insert(name);
    return name;
  }

  // A generated parameter with an SI value; asked again for the same name and value,
  // the same parameter.
  std::string add_parameter(const std::string& wanted, double value, Dimension dimension, const SourceLocation& where) {
    const auto known = generated_.find(wanted);
    if (known != generated_.end() && values_.at(known->second) == value) return known->second;
    Parameter p;
    p.name = fresh_name(wanted);
    const double shown = dimension == Dimension::angle ? to_degrees(value) : value;
    p.text = format_round_trip(shown) + (dimension == Dimension::angle ? " deg" : " m");
    p.quantity = Quantity{value, dimension};
    p.where = where;
    m_.parameters.push_back(p);
    values_[p.name] = value;
    if (known == generated_.end()) generated_[wanted] = p.name;
    return p.name;
  }

  // A length or coordinate as a factor in a term: the parameter or formula as written,
  // or a parameter made for a quantity.
  std::string as_factor(const std::string& text, const std::string& wanted, Dimension dimension,
                        const SourceLocation& where, const std::string& what) {
    if (is_identifier(text)) return text;
    if (!looks_like_quantity(text)) return "(" + text + ")";
    return add_parameter(wanted, value_of(text, dimension, where, what), dimension, where);
  }

  // ---- structure -----------------------------------------------------------------

  void place_joints() {
    std::set<std::string> names;
    for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
      const Joint& joint = linkage_.joints[j];
      joint_index_[joint.name] = j;
      const double x = value_of(joint.x, Dimension::length, joint.where, "joint " + joint.name + " x");
      const double y = value_of(joint.y, Dimension::length, joint.where, "joint " + joint.name + " y");
      at_.emplace_back(x, y);
    }
  }

  void make_bodies() {
    Body ground;
    ground.name = "ground";
    bodies_.push_back(ground);
    body_index_["ground"] = 0;
    for (const Link& link : linkage_.links) {
      if (body_index_.count(link.name)) fail(link.where, "duplicate link name \"" + link.name + "\"");
      Body body;
      body.name = link.name;
      body.link = &link;
      for (const std::string& name : link.joints) {
        const auto it = joint_index_.find(name);
        if (it == joint_index_.end()) {
          fail(link.where, "link \"" + link.name + "\" lists joint \"" + name + "\", which is not in [joints]");
        }
        body.joints.push_back(it->second);
        if (linkage_.joints[it->second].kind == Joint::Kind::slider && linkage_.joints[it->second].guide != link.name) {
          if (body.slider >= 0) {
            fail(link.where, "link \"" + link.name + "\" is the block of two sliders (" +
                                 linkage_.joints[std::size_t(body.slider)].name + ", " + name +
                                 "); kinema takes one slider per block: make the second block a link of its own "
                                 "pinned to this one");
          }
          body.slider = static_cast<int>(it->second);
        }
      }
      body_index_[link.name] = bodies_.size();
      bodies_.push_back(body);
    }
  }

  std::string body_list(const std::vector<std::size_t>& bodies) const {
    std::string text;
    for (std::size_t b : bodies) text += (text.empty() ? "" : ", ") + bodies_[b].name;
    return text;
  }

  void make_edges() {
    for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
      const Joint& joint = linkage_.joints[j];
      std::vector<std::size_t> on;
      if (joint.ground) on.push_back(0);
      for (std::size_t b = 1; b < bodies_.size(); ++b) {
        if (std::find(bodies_[b].joints.begin(), bodies_[b].joints.end(), j) != bodies_[b].joints.end()) on.push_back(b);
      }
      if (joint.kind == Joint::Kind::slider) {
        // Its guide may list it too (it slides along that link's line); the block is the other.
        const std::size_t listed = on.size();
        on.erase(std::remove_if(on.begin(), on.end(), [&](std::size_t b) { return bodies_[b].name == joint.guide; }), on.end());
        if (on.empty() && listed > 0) {
          fail(joint.where, "slider \"" + joint.name + "\" slides on \"" + joint.guide +
                                "\", the only link that lists it: its block cannot be its guide; write slider = "
                                "\"ground\" for a fixed guide, or the name of the link that carries the guide");
        }
        if (on.size() != 1) {
          fail(joint.where, on.empty() ? "slider \"" + joint.name + "\" is on no link: list it in the joints of its block"
                                       : "slider \"" + joint.name + "\" is listed by links " + body_list(on) +
                                             "; only its block lists it (its guide is slider = \"...\")");
        }
        const auto guide = body_index_.find(joint.guide);
        if (guide == body_index_.end()) {
          fail(joint.where, "slider \"" + joint.name + "\" slides on \"" + joint.guide +
                                "\", which is not a link; write slider = \"ground\" for a fixed guide or the name of "
                                "the link that carries the guide");
        }
        if (guide->second == on[0]) {
          fail(joint.where, "slider \"" + joint.name + "\" slides on its own block \"" + joint.guide + "\"");
        }
        edges_.push_back(Edge{j, guide->second, on[0], true});
        continue;
      }
      if (on.size() < 2) {
        fail(joint.where, on.empty() ? "joint \"" + joint.name + "\" is on no link: list it in the joints of the links "
                                                                 "it joins (or remove it)"
                                     : "joint \"" + joint.name + "\" is used by link " + body_list(on) +
                                           " only; a pin joins two links: add it to the other link's joints, or set "
                                           "ground = true for a fixed pivot");
      }
      // A pin shared by k bodies is k - 1 joints (as Grübler counts it).
      for (std::size_t k = 1; k < on.size(); ++k) edges_.push_back(Edge{j, on[0], on[k], false});
    }
  }

  void check_connected() {
    std::vector<bool> reached(bodies_.size(), false);
    std::vector<std::size_t> queue{0};
    reached[0] = true;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t b = queue[head];
      for (std::size_t e = 0; e < edges_.size(); ++e) {
        const Edge& edge = edges_[e];
        if (edge.a != b && edge.b != b) continue;
        const std::size_t other = edge.a == b ? edge.b : edge.a;
        if (reached[other]) continue;
        reached[other] = true;
        edges_[e].in_tree = true;
        bodies_[other].parent_edge = static_cast<int>(e);
        bodies_[other].parent = static_cast<int>(b);
        bodies_[other].depth = bodies_[b].depth + 1;
        queue.push_back(other);
      }
    }
    std::vector<std::size_t> apart;
    for (std::size_t b = 1; b < bodies_.size(); ++b)
      if (!reached[b]) apart.push_back(b);
    if (!apart.empty()) {
      fail(bodies_[apart[0]].link->where,
           std::string(apart.size() == 1 ? "link " : "links ") + body_list(apart) +
               (apart.size() == 1 ? " shares" : " share") +
               " no joint with the rest: no chain of joints leads from ground to it; add the joint that attaches it, "
               "or give a fixed pivot ground = true");
    }
  }

  void check_mobility() {
    const long n = static_cast<long>(bodies_.size()), j = static_cast<long>(edges_.size());
    const long mobility = 3 * (n - 1) - 2 * j;
    if (mobility == 1) return;
    std::ostringstream message;
    message << "the mechanism's mobility is " << mobility << " (Grübler: 3(n - 1) - 2j with n = " << n
            << " bodies, ground included, and j = " << j << " joints: 3*" << (n - 1) << " - 2*" << j << " = " << mobility
            << "), but one driver moves a mechanism of mobility 1; ";
    if (mobility > 1) {
      message << "add " << (mobility - 1) << " constraint(s): a pin between two links, or a binary link with two pins "
              << "(each takes one degree of freedom away)";
    } else {
      message << "it is a structure: remove " << (1 - mobility)
              << " binary link(s) with their two pins, or free a joint (each gives one degree of freedom back)";
    }
    fail(linkage_.driver_where, message.str());
  }

  void choose_driver() {
    if (!linkage_.driver_link.empty()) {
      const auto it = body_index_.find(linkage_.driver_link);
      if (it == body_index_.end() || it->second == 0) {
        fail(linkage_.driver_where, "[driver] link = \"" + linkage_.driver_link + "\" is not a link of [links]");
      }
      driver_body_ = it->second;
      const Body& body = bodies_[driver_body_];
      bool grounded = false;
      for (const Edge& e : edges_)
        grounded = grounded || (!e.slider && ((e.a == 0 && e.b == driver_body_) || (e.b == 0 && e.a == driver_body_)));
      if (!grounded) {
        fail(linkage_.driver_where, "the driver, link \"" + body.name +
                                        "\", is not attached to ground: a crank turns about a fixed pivot (a joint "
                                        "with ground = true on it)");
      }
      if (body.slider >= 0) {
        fail(linkage_.driver_where, "the driver, link \"" + body.name + "\", is a slider block: its angle is its "
                                        "guide's; drive the slider instead ([driver] slider = \"" +
                                        linkage_.joints[std::size_t(body.slider)].name + "\")");
      }
      if (m_.input.dimension != Dimension::angle && !m_.input.values.empty()) {
        fail(linkage_.driver_where, "the driver is a crank (link \"" + body.name + "\"): its values are angles, e.g. "
                                                                               "\"30 deg\"");
      }
      m_.input.dimension = Dimension::angle;
    } else {
      const auto it = joint_index_.find(linkage_.driver_slider);
      if (it == joint_index_.end() || linkage_.joints[it->second].kind != Joint::Kind::slider) {
        fail(linkage_.driver_where, "[driver] slider = \"" + linkage_.driver_slider + "\" is not a slider of [joints]");
      }
      driver_slider_ = static_cast<int>(it->second);
      if (linkage_.joints[it->second].guide != "ground") {
        fail(linkage_.driver_where, "the driver, slider \"" + linkage_.driver_slider +
                                        "\", is not attached to ground: a driven slider moves on a fixed guide "
                                        "(slider = \"ground\")");
      }
      if (m_.input.dimension != Dimension::length && !m_.input.values.empty()) {
        fail(linkage_.driver_where, "the driver is a slider: its values are lengths, e.g. \"0.2 m\"");
      }
      m_.input.dimension = Dimension::length;
    }
  }

  // ---- angles and coordinates ----------------------------------------------------

  std::string default_angle_name(const Body& body) const {
    return std::isdigit(static_cast<unsigned char>(body.name[0])) ? "theta" + body.name : "theta_" + body.name;
  }

  // Link angles, slider coordinates and the input are symbols: parameters made here
  // must not take their names.
  void reserve_names() {
    if (!m_.input.name.empty()) taken_.insert(m_.input.name);
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
      const Body& body = bodies_[b];
      if (body.slider < 0) taken_.insert(body.link->angle_name.empty() ? default_angle_name(body) : body.link->angle_name);
    }
    for (const Joint& joint : linkage_.joints)
      if (joint.kind == Joint::Kind::slider) taken_.insert(joint.coordinate.empty() ? "s_" + joint.name : joint.coordinate);
  }

  // Links with angles of their own first, then the driver's name, then slider blocks
  // (whose angles are their guides').
  void orient_bodies() {
    bodies_[0].oriented = true;
    bodies_[0].angle = "0";
    for (std::size_t b = 1; b < bodies_.size(); ++b)
      if (bodies_[b].slider < 0) orient(b, 0);
    if (driver_slider_ < 0) {
      Body& body = bodies_[driver_body_];
      if (m_.input.name.empty()) m_.input.name = body.angle;
      body.angle = m_.input.name;
    }
    for (std::size_t b = 1; b < bodies_.size(); ++b) orient(b, 0);
  }

  // The guide link, when it lists the slider (then the slider runs along the line from
  // the guide's first joint), else nullptr.
  const Body* listing_guide(std::size_t j) const {
    const auto it = body_index_.find(linkage_.joints[j].guide);
    if (it == body_index_.end() || it->second == 0) return nullptr;
    const Body& guide = bodies_[it->second];
    return std::find(guide.joints.begin(), guide.joints.end(), j) != guide.joints.end() ? &guide : nullptr;
  }

  double slider_direction(std::size_t j) {
    const Joint& joint = linkage_.joints[j];
    if (!joint.angle.empty()) {
      const double angle = value_of(joint.angle, Dimension::angle, joint.where, "slider " + joint.name + " angle");
      if (!(std::fabs(angle) <= from_degrees(kMaxAngleDegrees))) {  // as for the input
        fail(joint.where, "slider \"" + joint.name + "\": angle = \"" + joint.angle +
                              "\" is past 1e9 deg, where its direction is lost to rounding; give the direction of its "
                              "line within a turn (e.g. \"90 deg\")");
      }
      return angle;
    }
    const Body* guide = listing_guide(j);
    if (guide == nullptr || guide->joints[0] == j || std::abs(at_[j] - at_[guide->joints[0]]) < 1e-12) {
      fail(joint.where, "slider \"" + joint.name + "\" needs angle = \"...\", the direction of its line in the sketch "
                        "(e.g. \"90 deg\"); or list it in the joints of its guide link, after the first: it then "
                        "slides along the line from that joint");
    }
    return std::arg(at_[j] - at_[guide->joints[0]]);
  }

  void orient(std::size_t b, int depth) {
    Body& body = bodies_[b];
    if (body.oriented) return;
    if (depth > static_cast<int>(bodies_.size())) {
      fail(body.link->where, "link \"" + body.name + "\": its slider's guides form a cycle; one of them must be a "
                                                    "link with an angle of its own");
    }
    if (body.slider >= 0) {
      const std::size_t j = static_cast<std::size_t>(body.slider);
      const std::size_t guide = body_index_.at(linkage_.joints[j].guide);
      orient(guide, depth + 1);
      const Body& g = bodies_[guide];
      body.angle0 = slider_direction(j);
      body.angle = g.angle;
      body.offset = wrapped(g.offset + body.angle0 - g.angle0);
    } else if (body.joints.size() < 2) {
      // A link with one joint carries the guide of a slider (a crank with a block sliding
      // on it): its angle is the direction of that line.
      int guided = -1;
      for (std::size_t j = 0; j < linkage_.joints.size() && guided < 0; ++j)
        if (linkage_.joints[j].kind == Joint::Kind::slider && linkage_.joints[j].guide == body.name) guided = static_cast<int>(j);
      if (guided < 0 || body.joints.empty()) {
        fail(body.link->where, "link \"" + body.name + "\" has " + std::to_string(body.joints.size()) +
                                   " joint; a link joins at least two (a crank that only guides a slider: its pivot, "
                                   "and the slider names it, slider = \"" + body.name + "\")");
      }
      body.angle0 = slider_direction(std::size_t(guided));
      body.angle = body.link->angle_name.empty() ? default_angle_name(body) : body.link->angle_name;
    } else {
      const Point2 d = at_[body.joints[1]] - at_[body.joints[0]];
      if (std::abs(d) <= 1e-12 * (1 + std::abs(at_[body.joints[0]]))) {
        fail(body.link->where, "link \"" + body.name + "\": its first two joints, " + linkage_.joints[body.joints[0]].name +
                                   " and " + linkage_.joints[body.joints[1]].name +
                                   ", are at the same place in the sketch; its angle is the direction from the first "
                                   "to the second: list a joint elsewhere second");
      }
      body.angle0 = std::arg(d);
      body.angle = body.link->angle_name.empty() ? default_angle_name(body) : body.link->angle_name;
    }
    body.oriented = true;
  }

  void name_coordinates() {
    slider_coordinate_.assign(linkage_.joints.size(), "");
    slider_value0_.assign(linkage_.joints.size(), 0.0);
    for (const Edge& e : edges_) {
      if (!e.slider) continue;
      const Joint& joint = linkage_.joints[e.joint];
      slider_coordinate_[e.joint] = joint.coordinate.empty() ? "s_" + joint.name : joint.coordinate;
      const Point2 from = through0(e.joint);
      slider_value0_[e.joint] = std::real((at_[e.joint] - from) * std::polar(1.0, -slider_direction(e.joint)));
      const double off = std::imag((at_[e.joint] - from) * std::polar(1.0, -slider_direction(e.joint)));
      if (std::fabs(off) > kSketchTolerance * std::max(std::abs(at_[e.joint] - from), 1e-9) + 1e-9) {
        fail(joint.where, "slider \"" + joint.name + "\": its place in the sketch is " + format_significant(std::fabs(off)) +
                              " m off its line (through the point given and at its angle); put it on the line");
      }
    }
    // The input: a crank's angle or a slider's coordinate.
    Input& input = m_.input;
    if (driver_slider_ >= 0) {
      const Joint& joint = linkage_.joints[std::size_t(driver_slider_)];
      if (input.name.empty()) input.name = slider_coordinate_[std::size_t(driver_slider_)];
      slider_coordinate_[std::size_t(driver_slider_)] = input.name;
      if (input.rate_name.empty()) input.rate_name = joint.rate_name;
      if (input.second_rate_name.empty()) input.second_rate_name = joint.second_rate_name;
    } else {
      const Body& body = bodies_[driver_body_];
      if (input.rate_name.empty()) input.rate_name = body.link->rate_name;
      if (input.second_rate_name.empty()) input.second_rate_name = body.link->second_rate_name;
    }
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
      const Body& body = bodies_[b];
      if (body.slider >= 0 || b == driver_body_) continue;
      Unknown u;
      u.name = body.angle;
      u.dimension = Dimension::angle;
      u.guess = body.angle0;
      u.rate_name = body.link->rate_name;
      u.second_rate_name = body.link->second_rate_name;
      u.where = body.link->where;
      m_.unknowns.push_back(u);
    }
    for (const Edge& e : edges_) {
      if (!e.slider || static_cast<int>(e.joint) == driver_slider_) continue;
      const Joint& joint = linkage_.joints[e.joint];
      Unknown u;
      u.name = slider_coordinate_[e.joint];
      u.dimension = Dimension::length;
      u.guess = slider_value0_[e.joint];
      u.rate_name = joint.rate_name;
      u.second_rate_name = joint.second_rate_name;
      u.where = joint.where;
      m_.unknowns.push_back(u);
    }
  }

  // The point a slider's coordinate is measured from, in the sketch.
  Point2 through0(std::size_t j) {
    const Joint& joint = linkage_.joints[j];
    if (joint.through_x.empty()) {
      const Body* guide = listing_guide(j);
      return guide != nullptr ? at_[guide->joints[0]] : at_[j];
    }
    return {value_of(joint.through_x, Dimension::length, joint.where, "slider " + joint.name + " through x"),
            value_of(joint.through_y, Dimension::length, joint.where, "slider " + joint.name + " through y")};
  }

  // ---- vectors ---------------------------------------------------------------------

  const std::string* given_length(const Body& body, const std::string& a, const std::string& b) const {
    if (body.link == nullptr) return nullptr;
    for (const auto& [pair, text] : body.link->lengths) {
      if ((pair.first == a && pair.second == b) || (pair.first == b && pair.second == a)) return &text;
    }
    return nullptr;
  }

  // The distance between two joints of a body: as given (checked against the sketch),
  // else the sketch's.
  double length_value(const Body& body, std::size_t ja, std::size_t jb) {
    const std::string& a = linkage_.joints[ja].name;
    const std::string& b = linkage_.joints[jb].name;
    const double sketch = std::abs(at_[jb] - at_[ja]);
    const std::string* text = given_length(body, a, b);
    if (text == nullptr) return sketch;
    const SourceLocation& where = body.link->where;
    const double given = value_of(*text, Dimension::length, where, "link " + body.name + " length " + a + "-" + b);
    if (!(given > 0)) fail(where, "link \"" + body.name + "\": the length " + a + "-" + b + " = \"" + *text + "\" is not positive");
    if (std::fabs(given - sketch) > kSketchTolerance * given) {
      fail(where, "link \"" + body.name + "\": the length " + a + "-" + b + " = \"" + *text + "\" is " +
                      format_significant(given) + " m, but the sketch puts " + a + " and " + b + " " +
                      format_significant(sketch) + " m apart (" +
                      format_significant(100 * std::fabs(given - sketch) / given, 3) + " %); correct the sketch or the length");
    }
    return given;
  }

  // The same distance as a factor of a term.
  std::string length_factor(const Body& body, std::size_t ja, std::size_t jb) {
    const std::string& a = linkage_.joints[ja].name;
    const std::string& b = linkage_.joints[jb].name;
    const std::string pair = a < b ? a + b : b + a;
    const double value = length_value(body, ja, jb);
    if (const std::string* text = given_length(body, a, b)) {
      return as_factor(*text, pair, Dimension::length, body.link->where, "link " + body.name + " length");
    }
    return add_parameter(pair, value, Dimension::length, body.link->where);
  }

  // The angle of the vector from the body's first joint to joint j, minus the body's
  // angle: exact from three given lengths (side from the sketch), else the sketch's.
  double offset(const Body& body, std::size_t j, double d_first_j) {
    const std::size_t first = body.joints[0];
    const Point2 v = at_[j] - at_[first];
    double beta = wrapped(std::arg(v) - body.angle0);
    if (body.link != nullptr) {
      for (const auto& [joint, text] : body.link->angles) {
        if (joint != linkage_.joints[j].name) continue;
        const double given = value_of(text, Dimension::angle, body.link->where, "link " + body.name + " angle at " + joint);
        if (std::fabs(wrapped(given - beta)) > kSketchTolerance) {
          fail(body.link->where, "link \"" + body.name + "\": the angle at " + linkage_.joints[first].name + " to " + joint +
                                     " = \"" + text + "\" is " + format_significant(to_degrees(given)) +
                                     " deg, but the sketch has " + format_significant(to_degrees(beta)) +
                                     " deg; correct the sketch or the angle");
        }
        return wrapped(given);
      }
    }
    if (body.slider < 0 && body.joints.size() >= 2 && j != body.joints[1]) {
      const std::size_t second = body.joints[1];
      const std::string& f = linkage_.joints[first].name;
      const std::string& s = linkage_.joints[second].name;
      const std::string& n = linkage_.joints[j].name;
      if (given_length(body, f, n) && given_length(body, s, n) && d_first_j > 0 && length_value(body, first, second) > 0) {
        const double a = length_value(body, first, second), c = length_value(body, second, j);
        double cosine = (a * a + d_first_j * d_first_j - c * c) / (2 * a * d_first_j);
        if (std::fabs(cosine) > 1 + kSketchTolerance) {
          fail(body.link->where, "link \"" + body.name + "\": the lengths of " + f + ", " + s + " and " + n +
                                     " do not make a triangle; correct them");
        }
        cosine = std::clamp(cosine, -1.0, 1.0);
        const double exact = std::fabs(cosine) > 1 - 1e-12 ? (cosine > 0 ? 0.0 : kPi) : std::acos(cosine);
        beta = (beta < 0 && exact != kPi ? -exact : exact);
      }
    } else if (body.joints.size() >= 2 && j == body.joints[1] && body.slider < 0) {
      beta = 0;
    }
    return beta;
  }

  // factor * e^{i(angle + beta)} as a term of a loop.
  // An angle written as a formula (`beta`) stays that formula in the loop.
  Term rotated(const std::string& factor, const std::string& angle, double beta, const std::string& beta_name,
               const SourceLocation& where, const std::string& written = "") {
    const double tolerance = 1e-12;
    bool negative = false;
    std::string unit;  // "" = 1, or "I"
    std::string argument = angle;
    if (!written.empty()) {
      const std::string term = is_identifier(written) ? written : "(" + written + ")";
      argument = angle == "0" ? term : angle + " + " + term;
    } else if (std::fabs(beta) < tolerance) {
    } else if (std::fabs(std::fabs(beta) - kPi) < tolerance) {
      negative = true;
    } else if (std::fabs(beta - kPi / 2) < tolerance) {
      unit = "I";
    } else if (std::fabs(beta + kPi / 2) < tolerance) {
      unit = "I";
      negative = true;
    } else {
      const std::string name = add_parameter(beta_name, beta, Dimension::angle, where);
      argument = angle == "0" ? name : angle + " + " + name;
    }
    std::string text = factor;
    if (!unit.empty()) text = unit + "*" + text;
    if (argument != "0") text += "*exp(I*" + (argument.find(' ') != std::string::npos ? "(" + argument + ")" : argument) + ")";
    return Term{negative, text};
  }

  // The vector from body b's first joint to joint j (empty when they coincide).
  std::vector<Term> body_vector(std::size_t b, std::size_t j) {
    const Body& body = bodies_[b];
    const std::size_t first = body.joints[0];
    if (j == first || std::abs(at_[j] - at_[first]) <= 1e-12 * (1 + std::abs(at_[first]))) return {};
    const double beta = offset(body, j, length_value(body, first, j));
    std::string written;  // the angle as the file writes it, when a formula (and the body no block)
    if (body.link != nullptr && body.offset == 0) {
      for (const auto& [joint, text] : body.link->angles)
        if (joint == linkage_.joints[j].name && !looks_like_quantity(text)) written = text;
    }
    return {rotated(length_factor(body, first, j), body.angle, wrapped(beta + body.offset),
                    "beta_" + body.name + "_" + linkage_.joints[j].name, body.link->where, written)};
  }

  // A point of ground as written: x + I*y.
  std::vector<Term> ground_point(const std::string& x, const std::string& y, const std::string& name,
                                 const SourceLocation& where) {
    std::vector<Term> terms;
    const auto zero = [&](const std::string& text) {
      return looks_like_quantity(text) && value_of(text, Dimension::length, where, name) == 0;
    };
    const auto term = [&](const std::string& text, const std::string& wanted, const std::string& unit) {
      const bool negative = text.size() > 1 && text[0] == '-' && is_identifier(text.substr(1));  // "-Lc"
      return Term{negative, unit + as_factor(negative ? text.substr(1) : text, wanted, Dimension::length, where, wanted)};
    };
    if (!zero(x)) terms.push_back(term(x, "x_" + name, ""));
    if (!zero(y)) terms.push_back(term(y, "y_" + name, "I*"));
    return terms;
  }

  // The point a slider's coordinate is measured from, on its guide, from the guide's first joint.
  std::vector<Term> through_vector(std::size_t j) {
    const Joint& joint = linkage_.joints[j];
    const std::size_t g = body_index_.at(joint.guide);
    if (g == 0) {
      return joint.through_x.empty() ? ground_point(joint.x, joint.y, joint.name, joint.where)
                                     : ground_point(joint.through_x, joint.through_y, joint.name, joint.where);
    }
    const Body& guide = bodies_[g];
    const Point2 t = through0(j), first = at_[guide.joints[0]];
    if (std::abs(t - first) <= 1e-12 * (1 + std::abs(first))) return {};
    const std::string factor = add_parameter("r_" + guide.name + "_" + joint.name, std::abs(t - first), Dimension::length, joint.where);
    const double beta = wrapped(std::arg(t - first) - guide.angle0 + guide.offset);
    return {rotated(factor, guide.angle, beta, "beta_" + guide.name + "_" + joint.name, joint.where)};
  }

  // s * e^{i(guide angle + line offset)}: the slider's travel along its line.
  Term travel(std::size_t j) {
    const Joint& joint = linkage_.joints[j];
    const Body& guide = bodies_[body_index_.at(joint.guide)];
    const double beta = wrapped(slider_direction(j) - guide.angle0 + guide.offset);
    return rotated(slider_coordinate_[j], guide.angle, beta, "gamma_" + joint.name, joint.where);
  }

  // Where a joint is on a body: ground's points as written, a link's from its first joint.
  struct Path {
    std::vector<std::pair<int, std::vector<Term>>> steps;  // (tree edge, its terms) from ground
  };

  Path position(std::size_t b, std::size_t j) {
    Path path = reference(b);
    if (b == 0) path.steps.push_back({-1, ground_point(linkage_.joints[j].x, linkage_.joints[j].y, linkage_.joints[j].name,
                                                       linkage_.joints[j].where)});
    else path.steps.push_back({-1, body_vector(b, j)});
    return path;
  }

  // The body's first joint, from ground along the tree.
  Path reference(std::size_t b) {
    if (b == 0) return {};
    const Body& body = bodies_[b];
    const Edge& e = edges_[std::size_t(body.parent_edge)];
    const std::size_t parent = std::size_t(body.parent);
    Path path;
    std::vector<Term> terms;
    if (!e.slider) {
      path = position(parent, e.joint);
      terms = negated(body_vector(b, e.joint));
    } else if (parent == e.a) {  // guide -> block
      path = reference(parent);
      terms = through_vector(e.joint);
      terms.push_back(travel(e.joint));
      for (const Term& t : negated(body_vector(b, e.joint))) terms.push_back(t);
    } else {  // block -> guide
      path = position(parent, e.joint);
      terms = negated(std::vector<Term>{travel(e.joint)});
      for (const Term& t : negated(through_vector(e.joint))) terms.push_back(t);
    }
    // The last step of position() is the parent's vector to the joint: same tree edge.
    std::vector<Term> step = path.steps.empty() || path.steps.back().first != -1 ? std::vector<Term>{} : path.steps.back().second;
    if (!path.steps.empty() && path.steps.back().first == -1) path.steps.pop_back();
    for (const Term& t : terms) step.push_back(t);
    path.steps.push_back({body.parent_edge, step});
    return path;
  }

  static std::vector<Term> flatten(const Path& path, std::size_t from) {
    std::vector<Term> terms;
    for (std::size_t k = from; k < path.steps.size(); ++k)
      for (const Term& t : path.steps[k].second) terms.push_back(t);
    return terms;
  }

  std::string cycle_name(const Path& a, const Path& b, std::size_t common, std::size_t closing) const {
    std::vector<std::string> names;
    for (std::size_t k = common; k < a.steps.size(); ++k)
      if (a.steps[k].first >= 0) names.push_back(linkage_.joints[edges_[std::size_t(a.steps[k].first)].joint].name);
    names.push_back(linkage_.joints[closing].name);
    for (std::size_t k = b.steps.size(); k-- > common;)
      if (b.steps[k].first >= 0) names.push_back(linkage_.joints[edges_[std::size_t(b.steps[k].first)].joint].name);
    std::string name;
    for (const std::string& n : names) name += n;
    return name;
  }

  void write_loops() {
    std::set<std::string> loop_names;
    for (const Edge& e : edges_) {
      if (e.in_tree) continue;
      Path a, b;
      std::vector<Term> extra;
      if (!e.slider) {
        a = position(e.a, e.joint);
        b = position(e.b, e.joint);
      } else {  // block's joint = guide's through point + travel
        a = position(e.b, e.joint);
        b = reference(e.a);
        std::vector<Term> along = through_vector(e.joint);
        along.push_back(travel(e.joint));
        b.steps.push_back({-1, along});
      }
      std::size_t common = 0;
      while (common < a.steps.size() && common < b.steps.size() && a.steps[common].first >= 0 &&
             a.steps[common].first == b.steps[common].first)
        ++common;
      // A walk round the loop: out along a to the closing joint, back along b (its terms
      // in reverse order, negated), so that every partial sum is a joint (course notes
      // read the loop so, and its polygon's vertices are the joints).
      std::vector<Term> terms = flatten(a, common);
      const std::vector<Term> back = negated(flatten(b, common));
      terms.insert(terms.end(), back.rbegin(), back.rend());
      Loop loop;
      loop.name = cycle_name(a, b, common, e.joint);
      while (!loop_names.insert(loop.name).second) loop.name += "_";
      loop.complex_formula = sum_text(terms);
      loop.where = linkage_.joints[e.joint].where;
      m_.loops.push_back(loop);
    }
  }

  void write_points() {
    for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
      const Joint& joint = linkage_.joints[j];
      if (joint.ground) continue;
      // From the body nearest ground: the shortest sum (a slider's point from its guide).
      std::size_t body = 0;
      for (std::size_t b = 1; b < bodies_.size(); ++b) {
        const bool on = std::find(bodies_[b].joints.begin(), bodies_[b].joints.end(), j) != bodies_[b].joints.end() &&
                        !(joint.kind == Joint::Kind::slider && bodies_[b].name == joint.guide);
        if (on && (body == 0 || bodies_[b].depth < bodies_[body].depth)) body = b;
      }
      // A slider where a pin of its block is: the pin names the point.
      bool shown = false;
      if (joint.kind == Joint::Kind::slider) {
        for (std::size_t k : bodies_[body].joints)
          shown = shown || (k != j && linkage_.joints[k].kind == Joint::Kind::pin && std::abs(at_[k] - at_[j]) < 1e-12);
      }
      if (shown) continue;
      Point point;
      point.name = joint.name;
      point.formula = sum_text(flatten(position(body, j), 0));
      point.where = joint.where;
      point.is_joint = true;
      m_.points.push_back(point);
    }
    for (const LinkPoint& p : linkage_.points) {
      const auto it = body_index_.find(p.link);
      if (it == body_index_.end() || it->second == 0) {
        fail(p.where, "point \"" + p.name + "\" is on link \"" + p.link + "\", which is not a link of [links]");
      }
      const Body& body = bodies_[it->second];
      const Point2 at(value_of(p.x, Dimension::length, p.where, "point " + p.name + " x"),
                      value_of(p.y, Dimension::length, p.where, "point " + p.name + " y"));
      std::vector<Term> terms = flatten(reference(it->second), 0);
      const Point2 v = at - at_[body.joints[0]];
      if (std::abs(v) > 1e-12 * (1 + std::abs(at))) {
        const std::string factor = add_parameter("r_" + body.name + "_" + p.name, std::abs(v), Dimension::length, p.where);
        terms.push_back(rotated(factor, body.angle, wrapped(std::arg(v) - body.angle0 + body.offset),
                                "beta_" + body.name + "_" + p.name, p.where));
      }
      Point point;
      point.name = p.name;
      point.formula = sum_text(terms);
      point.where = p.where;
      m_.points.push_back(point);
    }
  }

  // ---- structure -------------------------------------------------------------------

  // The driver, then dyads in solving order: two links not yet placed that share one
  // joint and each have one joint to what is placed. Links left over form no dyad.
  void decompose() {
    plan_.body_count = static_cast<int>(bodies_.size());
    plan_.joint_count = static_cast<int>(edges_.size());
    std::vector<int> known(bodies_.size(), -1);  // step at which the body became known
    known[0] = 0;
    SolvingPlan::Step driver;
    driver.kind = "driver";
    std::size_t driver_body = driver_body_;
    if (driver_slider_ >= 0) {
      for (const Edge& e : edges_)
        if (e.slider && static_cast<int>(e.joint) == driver_slider_) driver_body = e.b;
      driver.joints.push_back(linkage_.joints[std::size_t(driver_slider_)].name);
    } else {
      for (const Edge& e : edges_)
        if (!e.slider && e.a == 0 && e.b == driver_body && driver.joints.empty()) driver.joints.push_back(linkage_.joints[e.joint].name);
    }
    driver.links.push_back(bodies_[driver_body].name);
    known[driver_body] = 1;
    plan_.steps.push_back(driver);
    const auto letter = [](const Edge& e) { return e.slider ? "T" : "R"; };
    for (int step = 2;; ++step) {
      bool found = false;
      // One pass over the joints: each unplaced link's joints to what is placed, and the
      // joints between two unplaced links; then the first pair (in link order) that is a dyad.
      std::vector<int> to_known(bodies_.size(), 0), known_edge(bodies_.size(), -1);
      std::map<std::pair<std::size_t, std::size_t>, std::pair<int, int>> between;  // count, edge
      for (std::size_t k = 0; k < edges_.size(); ++k) {
        const std::size_t a = edges_[k].a, b = edges_[k].b;
        if (known[a] >= 0 && known[b] < 0) {
          ++to_known[b];
          known_edge[b] = static_cast<int>(k);
        } else if (known[b] >= 0 && known[a] < 0) {
          ++to_known[a];
          known_edge[a] = static_cast<int>(k);
        } else if (known[a] < 0 && known[b] < 0) {
          auto& [count, edge] = between[{std::min(a, b), std::max(a, b)}];
          ++count;
          edge = static_cast<int>(k);
        }
      }
      for (const auto& [pair, link] : between) {
        const auto [l1, l2] = pair;
        if (link.first != 1 || to_known[l1] != 1 || to_known[l2] != 1) continue;
        int outer1 = known_edge[l1], outer2 = known_edge[l2];
        const int inner = link.second;
        // Read from the side of the body placed last (the moving one), pins first on a tie.
        const auto other = [&](int k, std::size_t b) {
          const Edge& e = edges_[std::size_t(k)];
          return e.a == b ? e.b : e.a;
        };
        std::size_t first = l1, second = l2;
        const int k1 = known[other(outer1, l1)], k2 = known[other(outer2, l2)];
        if (k2 > k1 || (k2 == k1 && edges_[std::size_t(outer1)].slider && !edges_[std::size_t(outer2)].slider)) {
          std::swap(first, second);
          std::swap(outer1, outer2);
        }
        SolvingPlan::Step dyad;
        dyad.kind = std::string(letter(edges_[std::size_t(outer1)])) + letter(edges_[std::size_t(inner)]) +
                    letter(edges_[std::size_t(outer2)]);
        dyad.links = {bodies_[first].name, bodies_[second].name};
        dyad.joints = {linkage_.joints[edges_[std::size_t(outer1)].joint].name,
                       linkage_.joints[edges_[std::size_t(inner)].joint].name,
                       linkage_.joints[edges_[std::size_t(outer2)].joint].name};
        plan_.steps.push_back(dyad);
        dyad_edges_.push_back({first, second, std::size_t(outer1), std::size_t(inner), std::size_t(outer2)});
        known[l1] = known[l2] = step;
        found = true;
        break;
      }
      if (!found) break;
    }
    SolvingPlan::Step rest;
    rest.kind = "group";
    for (std::size_t b = 1; b < bodies_.size(); ++b)
      if (known[b] < 0) rest.links.push_back(bodies_[b].name);
    if (!rest.links.empty()) plan_.steps.push_back(rest);
  }

  // The joints and links by name, and the numbers the closed-form solution needs
  // (engine/numeric/dyad_positions), the same lengths and angles as the loops', with the
  // sketch the dyads' assemblies are read from (engine/numeric/assemblies).
  void export_plan() {
    SolvingPlan& f = plan_;
    const auto unknown_index = [&](const std::string& name) {
      for (std::size_t i = 0; i < m_.unknowns.size(); ++i)
        if (m_.unknowns[i].name == name) return static_cast<int>(i);
      return -1;
    };
    for (const Joint& joint : linkage_.joints)
      f.joints.push_back({joint.name, joint.kind == Joint::Kind::slider, joint.ground, joint.where});
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
      const Link& link = *bodies_[b].link;
      f.links.push_back({link.name, link.angle_name.empty() ? default_angle_name(bodies_[b]) : link.angle_name, link.where});
    }
    f.bodies.assign(bodies_.size(), {});
    for (std::size_t j = 0; j < linkage_.joints.size(); ++j)
      if (linkage_.joints[j].ground) f.bodies[0].points.push_back({j, at_[j]});
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
      const Body& body = bodies_[b];
      SolvingPlan::Body& frame = f.bodies[b];
      frame.sketch_origin = at_[body.joints[0]];
      frame.sketch_angle = body.angle0;
      for (std::size_t j : body.joints) {
        Point2 v;
        if (j != body.joints[0] && std::abs(at_[j] - at_[body.joints[0]]) > 1e-12 * (1 + std::abs(at_[body.joints[0]]))) {
          const double d = length_value(body, body.joints[0], j);
          v = std::polar(d, offset(body, j, d));
        }
        frame.points.push_back({j, v});
      }
      if (body.slider >= 0) {
        frame.guide = static_cast<int>(body_index_.at(linkage_.joints[std::size_t(body.slider)].guide));
        frame.offset = wrapped(body.angle0 - bodies_[std::size_t(frame.guide)].angle0);
      } else if (b != driver_body_ || driver_slider_ >= 0) {
        frame.unknown = unknown_index(body.angle);
      }
    }
    std::vector<int> edge_ref(edges_.size());
    for (std::size_t k = 0; k < edges_.size(); ++k) {
      const Edge& e = edges_[k];
      if (!e.slider) {
        edge_ref[k] = static_cast<int>(f.pins.size());
        f.pins.push_back({e.joint, e.a, e.b});
        continue;
      }
      SolvingPlan::Slider s;
      s.joint = e.joint;
      s.guide = e.a;
      s.block = e.b;
      const Body& guide = bodies_[e.a];
      const Point2 t = through0(e.joint);
      s.through = e.a == 0 ? t : (t - at_[guide.joints[0]]) * std::polar(1.0, -guide.angle0);
      s.direction = wrapped(slider_direction(e.joint) - guide.angle0);
      s.unknown = static_cast<int>(e.joint) == driver_slider_ ? -1 : unknown_index(slider_coordinate_[e.joint]);
      if (static_cast<int>(e.joint) == driver_slider_) f.driver_slider = static_cast<int>(f.sliders.size());
      edge_ref[k] = -1 - static_cast<int>(f.sliders.size());
      f.sliders.push_back(s);
    }
    f.driver_body = driver_body_;
    f.sketch_input = driver_slider_ >= 0 ? slider_value0_[std::size_t(driver_slider_)] : bodies_[driver_body_].angle0;
    f.closed_form = true;
    for (const SolvingPlan::Step& group : plan_.steps) f.closed_form = f.closed_form && group.kind != "group";
    for (const auto& [first, second, outer1, inner, outer2] : dyad_edges_) {
      SolvingPlan::Dyad d;
      d.first = first;
      d.second = second;
      d.outer_first = edge_ref[outer1];
      d.inner = edge_ref[inner];
      d.outer_second = edge_ref[outer2];
      // A slider inside a dyad is solved here only between two pins (RTR).
      if (d.inner < 0 && (d.outer_first < 0 || d.outer_second < 0)) f.closed_form = false;
      f.dyads.push_back(d);
    }
    check_assembly_joints();
    if (f.closed_form) state_assemblies();
  }

  // A joint may state its dyad's assembly only if it is a dyad's middle joint.
  void check_assembly_joints() const {
    for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
      const Joint& joint = linkage_.joints[j];
      if (joint.assembly.empty()) continue;
      bool inner = false;
      for (const auto& edges : dyad_edges_) inner = inner || edges_[edges[3]].joint == j;
      if (!inner) {
        std::string middles;
        for (const auto& edges : dyad_edges_) middles += (middles.empty() ? "" : ", ") + linkage_.joints[edges_[edges[3]].joint].name;
        fail(joint.where, "joint \"" + joint.name + "\" states an assembly, but it is not the middle joint of a dyad" +
                              (middles.empty() ? std::string(" (this mechanism has no dyads)")
                                               : " (the middle joints: " + middles + ")") +
                              "; state it on the middle joint of the dyad it chooses");
      }
      if (!plan_.closed_form) {
        fail(joint.where, "joint \"" + joint.name + "\" states an assembly, but its links are solved by Newton with the "
                          "others (not dyad by dyad); draw the sketch on the assembly wanted instead");
      }
    }
  }

  // Dyads whose middle joint states "left of X-Y" or "right of X-Y": the statement read
  // into the plan (which assembly that is, engine/numeric/assemblies reads at the sketch).
  void state_assemblies() {
    for (std::size_t k = 0; k < plan_.dyads.size(); ++k) {
      SolvingPlan::Dyad& d = plan_.dyads[k];
      const Joint& joint = linkage_.joints[edges_[dyad_edges_[k][3]].joint];
      if (joint.assembly.empty()) continue;
      const std::string& text = joint.assembly;
      const std::string what = "joint \"" + joint.name + "\": assembly = \"" + text + "\"";
      const std::size_t of = text.find(" of ");
      const std::size_t dash = text.find('-', of == std::string::npos ? 0 : of);
      const std::string side = of == std::string::npos ? "" : text.substr(0, of);
      if ((side != "left" && side != "right") || dash == std::string::npos) {
        fail(joint.where, what + " is not a side: write \"left of B-D\" or \"right of B-D\" (the side of the line "
                          "from joint B to joint D that " + joint.name + " is on, as the driver is sketched)");
      }
      const std::string from = text.substr(of + 4, dash - of - 4), to = text.substr(dash + 1);
      for (const std::string& name : {from, to}) {
        if (joint_index_.count(name) == 0) fail(joint.where, what + ": there is no joint \"" + name + "\"");
      }
      if (from == to) fail(joint.where, what + ": a line needs two different joints");
      d.stated = text;
      d.left = side == "left";
      d.from = joint_index_.at(from);
      d.to = joint_index_.at(to);
      plan_.steps[k + 1].assembly = joint.name + " " + text;
    }
  }
};

}  // namespace

LinkageLoops linkage_loops(const Mechanism& written) {
  LinkageLoops result{written, {}};
  LinkageWriter writer(result.loops);
  writer.write();
  result.plan = std::move(writer).plan();
  result.loops.linkage.reset();  // a vector-loop mechanism now: the front end's work is done
  return result;
}

ConstraintSystem build_linkage_system(const Mechanism& written) {
  LinkageLoops derived = linkage_loops(written);
  check_shared_names(derived.loops);
  ConstraintSystem system = build_planar_loops(derived.loops);
  system.plan = std::move(derived.plan);
  return system;
}

}  // namespace kinema
