#include "engine/symbolic/dyad_method.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/base/work_count.hpp"
#include "engine/base/errors.hpp"
#include "engine/constraints/differentiate.hpp"
#include "engine/constraints/solving_plan.hpp"
#include "engine/base/units.hpp"

namespace kinema {

const char* method_name(DerivationMethod method) {
  switch (method) {
    case DerivationMethod::loops: return "loops";
    case DerivationMethod::relative_velocity: return "relative-velocity";
    case DerivationMethod::joint_coordinates: return "joint-coordinates";
  }
  return "?";
}

std::optional<DerivationMethod> find_method(std::string_view name) {
  for (DerivationMethod m : {DerivationMethod::loops, DerivationMethod::relative_velocity,
                             DerivationMethod::joint_coordinates}) {
    if (name == method_name(m)) return m;
  }
  return std::nullopt;
}

std::vector<std::string> method_names() {
  return {method_name(DerivationMethod::loops), method_name(DerivationMethod::relative_velocity),
          method_name(DerivationMethod::joint_coordinates)};
}

namespace {

using GiNaC::ex;

struct Vec {
  ex x = 0, y = 0;
};
Vec operator+(const Vec& a, const Vec& b) { return {a.x + b.x, a.y + b.y}; }
Vec operator-(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y}; }
Vec operator*(const ex& k, const Vec& a) { return {k * a.x, k * a.y}; }
Vec cross(const ex& w, const Vec& r) { return {-w * r.y, w * r.x}; }  // w k x r

// A relation as written, in text and LaTeX at once.
struct Words {
  std::string text, latex;
  void add(const std::string& t, const std::string& l) {
    text += t;
    latex += l;
  }
};

class Writer {
 public:
  Writer(const ConstraintSystem& system, DerivationMethod method)
      : system_(system), plan_(*system.plan), method_(method) {
  }

  DyadDerivation run() {
    result_.method = method_;
    driver();
    for (std::size_t k = 0; k < plan_.dyads.size(); ++k) dyad(k);
    return result_;
  }

 private:
  const ConstraintSystem& system_;
  const SolvingPlan& plan_;
  DerivationMethod method_;
  DyadDerivation result_;
  std::map<std::pair<std::size_t, std::size_t>, bool> defined_;  // (joint, body): its velocity has symbols

  // ---- names and symbols ----------------------------------------------------------

  const std::string& joint(std::size_t j) const { return plan_.joints[j].name; }
  std::string body(std::size_t b) const { return b == 0 ? "ground" : plan_.links[b - 1].name; }

  ex symbol(const std::string& name, const std::string& latex) {
    auto found = result_.symbols.find(name);
    if (found == result_.symbols.end()) found = result_.symbols.emplace(name, GiNaC::realsymbol(name, latex)).first;
    return found->second;
  }
  Vec position(std::size_t j) {
    return {symbol("x_" + joint(j), "x_{" + joint(j) + "}"), symbol("y_" + joint(j), "y_{" + joint(j) + "}")};
  }
  ex length(std::size_t a, std::size_t b) {
    return symbol("L_" + joint(a) + joint(b), "L_{" + joint(a) + joint(b) + "}");
  }

  bool is_slider_joint(std::size_t j) const {
    for (const auto& s : plan_.sliders)
      if (s.joint == j) return true;
    return false;
  }
  const SolvingPlan::Slider* slider_of(std::size_t j) const {
    for (const auto& s : plan_.sliders)
      if (s.joint == j) return &s;
    return nullptr;
  }
  // A slider joint's point on its guide is named after the guide: B_3 (seed 002's B3).
  std::string point_name(std::size_t j, std::size_t b) const {
    const SolvingPlan::Slider* s = slider_of(j);
    return s != nullptr && s->guide == b ? joint(j) + "_" + body(b) : joint(j);
  }
  std::string point_latex(std::size_t j, std::size_t b) const {
    const SolvingPlan::Slider* s = slider_of(j);
    return s != nullptr && s->guide == b ? joint(j) + "_{" + body(b) + "}" : joint(j);
  }
  Vec velocity_symbols(std::size_t j, std::size_t b) {
    const std::string n = point_name(j, b), l = point_latex(j, b);
    return {symbol("v_" + n + "x", "v_{" + l + "x}"), symbol("v_" + n + "y", "v_{" + l + "y}")};
  }
  Vec acceleration_symbols(std::size_t j, std::size_t b) {
    const std::string n = point_name(j, b), l = point_latex(j, b);
    return {symbol("a_" + n + "x", "a_{" + l + "x}"), symbol("a_" + n + "y", "a_{" + l + "y}")};
  }
  std::pair<std::size_t, std::size_t> key(std::size_t j, std::size_t b) const {
    return {j, is_slider_joint(j) ? b : 0};
  }

  // ---- bodies: angle and rates ---------------------------------------------------

  ex angle(std::size_t b) const {
    const SolvingPlan::Body& f = plan_.bodies[b];
    if (f.unknown >= 0) return system_.unknowns[std::size_t(f.unknown)].symbol;
    if (f.guide >= 0) return angle(std::size_t(f.guide)) + exact_angle(f.offset);
    if (b != 0 && b == plan_.driver_body && plan_.driver_slider < 0) return system_.input.symbol;
    return 0;
  }
  ex omega(std::size_t b) const {
    const SolvingPlan::Body& f = plan_.bodies[b];
    if (f.unknown >= 0) return system_.unknowns[std::size_t(f.unknown)].rate;
    if (f.guide >= 0) return omega(std::size_t(f.guide));
    if (b != 0 && b == plan_.driver_body && plan_.driver_slider < 0) return system_.input.rate;
    return 0;
  }
  ex alpha(std::size_t b) const {
    const SolvingPlan::Body& f = plan_.bodies[b];
    if (f.unknown >= 0) return system_.unknowns[std::size_t(f.unknown)].second_rate;
    if (f.guide >= 0) return alpha(std::size_t(f.guide));
    if (b != 0 && b == plan_.driver_body && plan_.driver_slider < 0) return system_.input.second_rate;
    return 0;
  }
  // Multiples of 15 deg exactly (cos(theta + Pi/2) prints as -sin(theta)).
  static ex exact_angle(double radians) {
    const double twelfths = radians / (kPi / 12);
    if (std::fabs(twelfths - std::round(twelfths)) < 1e-9) return GiNaC::Pi * GiNaC::numeric(long(std::lround(twelfths)), 12);
    return radians;
  }
  Vec direction(const SolvingPlan::Slider& s) const {
    const ex a = angle(s.guide) + exact_angle(s.direction);
    return {GiNaC::cos(a), GiNaC::sin(a)};
  }
  ex slide_rate(const SolvingPlan::Slider& s) const {
    return s.unknown >= 0 ? ex(system_.unknowns[std::size_t(s.unknown)].rate) : ex(system_.input.rate);
  }
  ex slide_second_rate(const SolvingPlan::Slider& s) const {
    return s.unknown >= 0 ? ex(system_.unknowns[std::size_t(s.unknown)].second_rate) : ex(system_.input.second_rate);
  }
  std::string name_of(const ex& e) const { return GiNaC::ex_to<GiNaC::symbol>(e).get_name(); }
  std::string latex_of(const ex& e) const {
    std::ostringstream out;
    out << GiNaC::latex << e;
    return out.str();
  }

  // ---- known velocities ------------------------------------------------------------

  bool on_body(std::size_t j, std::size_t b) const {
    for (const auto& [joint_index, at] : plan_.bodies[b].points)
      if (joint_index == j) return true;
    return false;
  }
  // A fixed pivot (a joint of ground) is at rest on every body.
  bool at_rest(std::size_t j) const { return on_body(j, 0); }
  Vec velocity(std::size_t j, std::size_t b) {
    if (b == 0 || at_rest(j)) return {};
    return velocity_symbols(j, b);
  }
  Vec acceleration(std::size_t j, std::size_t b) {
    if (b == 0 || at_rest(j)) return {};
    return acceleration_symbols(j, b);
  }

  // Two joints at one point of body b for all time (a slider block's pin on its slide,
  // as seed 002 draws B and B2): the vector between them is zero, so no term has it. A
  // slider's point on its guide only passes a point of the guide, so it never counts.
  bool coincide(std::size_t a, std::size_t b_joint, std::size_t b) const {
    if (a == b_joint) return true;
    for (const SolvingPlan::Slider& s : plan_.sliders)
      if (s.guide == b && (s.joint == a || s.joint == b_joint)) return false;
    const std::complex<double>* pa = nullptr;
    const std::complex<double>* pb = nullptr;
    for (const auto& [joint_index, at] : plan_.bodies[b].points) {
      if (joint_index == a) pa = &at;
      if (joint_index == b_joint) pb = &at;
    }
    if (pa == nullptr || pb == nullptr) return false;
    return std::abs(*pa - *pb) <= 1e-12 * (1.0 + std::max(std::abs(*pa), std::abs(*pb)));
  }
  // r from joint `from` to joint `to` on body b (zero where they coincide).
  Vec arm(std::size_t from, std::size_t to, std::size_t b) {
    return coincide(from, to, b) ? Vec{} : position(to) - position(from);
  }

  // "v_D + omega3 x r_DC" in words (terms that are zero left out); `body` turns with w_body.
  void words_transfer(Words& w, std::size_t from_joint, std::size_t from_body, const ex& w_body, std::size_t to_joint,
                      bool acceleration_order, const ex& a_body, bool leading, std::size_t body) {
    bool first = leading;
    const auto plus = [&] {
      if (!first) w.add(" + ", " + ");
      first = false;
    };
    const std::string n = point_name(from_joint, from_body), l = point_latex(from_joint, from_body);
    const char* v = acceleration_order ? "a" : "v";
    if (from_body != 0 && !at_rest(from_joint)) {
      plus();
      w.add(std::string(v) + "_" + n, std::string("\\mathbf{") + v + "}_{" + l + "}");
    }
    if (coincide(from_joint, to_joint, body)) {
      if (first) w.add("0", "\\mathbf{0}");
      return;
    }
    const std::string r = joint(from_joint) + joint(to_joint);
    if (acceleration_order) {
      if (!a_body.is_zero()) {
        plus();
        w.add(name_of(a_body) + " x r_" + r, "\\boldsymbol{" + latex_of(a_body) + "} \\times \\mathbf{r}_{" + r + "}");
      }
      if (!w_body.is_zero()) {
        w.add(first ? "-" : " - ", first ? "-" : " - ");
        first = false;
        w.add(name_of(w_body) + "^2 r_" + r, latex_of(w_body) + "^{2}\\,\\mathbf{r}_{" + r + "}");
      }
    } else if (!w_body.is_zero()) {
      plus();
      w.add(name_of(w_body) + " x r_" + r, "\\boldsymbol{" + latex_of(w_body) + "} \\times \\mathbf{r}_{" + r + "}");
    }
    if (first) w.add("0", "\\mathbf{0}");
  }

  // The velocity (or acceleration) of joint `to` on body b from joint `from` on b.
  Vec transfer(std::size_t from, std::size_t b, std::size_t to, bool second) {
    const Vec r = arm(from, to, b);
    const bool from_rest = at_rest(from);
    if (!second) return (from_rest ? Vec{} : velocity(from, b)) + cross(omega(b), r);
    return (from_rest ? Vec{} : acceleration(from, b)) + cross(alpha(b), r) - GiNaC::pow(omega(b), 2) * r;
  }

  // Defines every joint on body b not yet defined, from joint `from` (defined on b).
  void define_rest(MethodStep& step, std::size_t b, std::size_t from) {
    // Its joints, and the points of sliders it guides without listing them.
    std::vector<std::size_t> joints;
    for (const auto& [j, at] : plan_.bodies[b].points) joints.push_back(j);
    for (const SolvingPlan::Slider& s : plan_.sliders)
      if (s.guide == b && !on_body(s.joint, b)) joints.push_back(s.joint);
    const bool from_rest = at_rest(from);
    for (std::size_t j : joints) {
      if (defined_.count(key(j, b)) != 0 || at_rest(j)) continue;
      for (bool second : {false, true}) {
        Words w;
        const std::string n = point_name(j, b), l = point_latex(j, b);
        w.add(std::string(second ? "a_" : "v_") + n + " = ", std::string("\\mathbf{") + (second ? "a" : "v") + "}_{" + l + "} = ");
        words_transfer(w, from, from_rest ? 0 : b, omega(b), j, second, alpha(b), true, b);
        const Vec value = transfer(from, b, j, second);
        const Vec named = second ? acceleration_symbols(j, b) : velocity_symbols(j, b);
        auto& list = second ? step.acceleration : step.velocity;
        list.push_back({MethodRelation::Kind::statement, w.text, w.latex, 0, 0});
        list.push_back({MethodRelation::Kind::solution, "", "", named.x, value.x});
        list.push_back({MethodRelation::Kind::solution, "", "", named.y, value.y});
      }
      defined_[key(j, b)] = true;
    }
  }

  // ---- the driver --------------------------------------------------------------------

  void driver() {
    MethodStep step;
    step.heading = structure_lines(plan_).front();
    const std::size_t b = plan_.driver_body;
    std::size_t from = 0;
    if (plan_.driver_slider >= 0) {
      // The block slides on a fixed guide: v_S = sdot u, a_S = sddot u.
      const SolvingPlan::Slider& s = plan_.sliders[std::size_t(plan_.driver_slider)];
      from = s.joint;
      const Vec u = direction(s);
      for (bool second : {false, true}) {
        const ex rate = second ? slide_second_rate(s) : slide_rate(s);
        const Vec named = second ? acceleration_symbols(s.joint, s.block) : velocity_symbols(s.joint, s.block);
        auto& list = second ? step.acceleration : step.velocity;
        const std::string v = second ? "a" : "v";
        list.push_back({MethodRelation::Kind::statement, v + "_" + joint(s.joint) + " = " + name_of(rate) + " u",
                        "\\mathbf{" + v + "}_{" + joint(s.joint) + "} = " + latex_of(rate) + "\\,\\mathbf{u}", 0, 0});
        list.push_back({MethodRelation::Kind::solution, "", "", named.x, rate * u.x});
        list.push_back({MethodRelation::Kind::solution, "", "", named.y, rate * u.y});
      }
      defined_[key(s.joint, s.block)] = true;
    } else {
      for (const SolvingPlan::Pin& pin : plan_.pins)
        if ((pin.a == 0 && pin.b == b) || (pin.b == 0 && pin.a == b)) from = pin.joint;
      defined_[key(from, b)] = true;  // the fixed pivot: at rest
    }
    define_rest(step, b, from);
    result_.steps.push_back(step);
  }

  // ---- dyads -------------------------------------------------------------------------

  struct Side {
    std::size_t link = 0;
    int edge = 0;
  };

  // The velocity (second: acceleration) of the middle joint J as a point of the side's
  // link, reached from its outer joint; in words too.
  Vec side_motion(const Side& side, std::size_t j, bool second, Words& w) {
    const std::size_t L = side.link;
    if (side.edge >= 0) {
      const SolvingPlan::Pin& pin = plan_.pins[std::size_t(side.edge)];
      const std::size_t known = pin.a == L ? pin.b : pin.a;
      words_transfer(w, pin.joint, known == 0 ? 0 : known, omega(L), j, second, alpha(L), true, L);
      const Vec r = arm(pin.joint, j, L);
      const Vec start = at_rest(pin.joint) ? Vec{} : (second ? acceleration(pin.joint, known) : velocity(pin.joint, known));
      return second ? start + cross(alpha(L), r) - GiNaC::pow(omega(L), 2) * r : start + cross(omega(L), r);
    }
    const SolvingPlan::Slider& s = plan_.sliders[std::size_t(-1 - side.edge)];
    const bool block = s.block == L;
    const std::size_t known = block ? s.guide : s.block;
    const Vec u = direction(s);
    const ex rate = slide_rate(s), second_rate = slide_second_rate(s);
    // The slider's point on L: its point on the known body, and the slide (with the
    // Coriolis term 2 omega_guide x sdot u in accelerations).
    Vec start = second ? acceleration(s.joint, known) : velocity(s.joint, known);
    const ex sign = block ? 1 : -1;
    const char* v = second ? "a" : "v";
    bool first = true;
    if (known != 0) {
      w.add(std::string(v) + "_" + point_name(s.joint, known), std::string("\\mathbf{") + v + "}_{" + point_latex(s.joint, known) + "}");
      first = false;
    }
    w.add(std::string(first ? (block ? "" : "-") : (block ? " + " : " - ")), std::string(first ? (block ? "" : "-") : (block ? " + " : " - ")));
    first = false;
    if (!second) {
      start = start + sign * rate * u;
      w.add(name_of(rate) + " u_" + joint(s.joint), latex_of(rate) + "\\,\\mathbf{u}_{" + joint(s.joint) + "}");
    } else {
      const ex w_guide = omega(s.guide);
      start = start + sign * (second_rate * u + 2 * cross(w_guide, rate * u));
      w.add(name_of(second_rate) + " u_" + joint(s.joint), latex_of(second_rate) + "\\,\\mathbf{u}_{" + joint(s.joint) + "}");
      if (!w_guide.is_zero()) {
        w.add(block ? " + 2 " : " - 2 ", block ? " + 2\\," : " - 2\\,");
        w.add(name_of(w_guide) + " x " + name_of(rate) + " u_" + joint(s.joint),
              "\\boldsymbol{" + latex_of(w_guide) + "} \\times " + latex_of(rate) + "\\,\\mathbf{u}_{" + joint(s.joint) + "}");
      }
    }
    if (!coincide(s.joint, j, L)) {
      // Its own words (leading: no sign of its own), after one " + ".
      Words rest;
      words_transfer(rest, s.joint, 0, omega(L), j, second, alpha(L), true, L);
      if (!rest.text.empty() && rest.text != "0") {
        const bool minus = rest.text[0] == '-';
        w.add(minus ? " - " : " + ", minus ? " - " : " + ");
        w.add(minus ? rest.text.substr(1) : rest.text, minus ? rest.latex.substr(1) : rest.latex);
      }
    }
    const Vec r = arm(s.joint, j, L);
    return second ? start + cross(alpha(L), r) - GiNaC::pow(omega(L), 2) * r : start + cross(omega(L), r);
  }

  void dyad(std::size_t k) {
    const SolvingPlan::Dyad& d = plan_.dyads[k];
    MethodStep step;
    step.heading = describe_dyad(plan_, k);
    const std::size_t j = d.inner >= 0 ? plan_.pins[std::size_t(d.inner)].joint
                                       : plan_.sliders[std::size_t(-1 - d.inner)].joint;
    const Side first{d.first, d.outer_first}, second_side{d.second, d.outer_second};
    bool coordinates = method_ == DerivationMethod::joint_coordinates && d.inner >= 0;
    for (const Side& side : {first, second_side}) {
      if (side.edge < 0 && plan_.sliders[std::size_t(-1 - side.edge)].block != side.link) coordinates = false;
    }
    if (method_ == DerivationMethod::joint_coordinates && !coordinates) {
      step.note = "joint coordinates need the middle joint on two circles or guide lines; this dyad's " +
                  std::string(d.inner < 0 ? "middle joint is a slider" : "guide turns with one of its links") +
                  ", so it is written as relative velocities";
    }
    // Unknown rates of the dyad: its links' own angles, its sliders' coordinates.
    std::vector<ex> rates, second_rates;
    for (std::size_t b : {d.first, d.second}) {
      const int u = plan_.bodies[b].unknown;
      if (u >= 0) {
        rates.push_back(system_.unknowns[std::size_t(u)].rate);
        second_rates.push_back(system_.unknowns[std::size_t(u)].second_rate);
      }
    }
    for (int edge : {d.outer_first, d.inner, d.outer_second}) {
      if (edge >= 0) continue;
      const SolvingPlan::Slider& s = plan_.sliders[std::size_t(-1 - edge)];
      if (s.unknown < 0) continue;
      rates.push_back(system_.unknowns[std::size_t(s.unknown)].rate);
      second_rates.push_back(system_.unknowns[std::size_t(s.unknown)].second_rate);
    }
    if (coordinates) {
      joint_coordinates(step, d, j, first, second_side);
    } else {
      for (bool second : {false, true}) relative(step, d, j, first, second_side, second ? second_rates : rates, second);
    }
    // The other joints of its links, from the middle joint (a slider: each link's outer pin).
    if (d.inner >= 0) {
      defined_[key(j, d.first)] = defined_[key(j, d.second)] = true;
      define_rest(step, d.first, j);
      define_rest(step, d.second, j);
    } else {
      for (const Side& side : {first, second_side}) define_rest(step, side.link, plan_.pins[std::size_t(side.edge)].joint);
    }
    result_.steps.push_back(step);
  }

  // v_J from one side = v_J from the other (+ the slide of a middle slider), in components, solved.
  void relative(MethodStep& step, const SolvingPlan::Dyad& d, std::size_t j, const Side& first, const Side& second_side,
                const std::vector<ex>& unknowns, bool second) {
    auto& list = second ? step.acceleration : step.velocity;
    Words left, right;
    const char* v = second ? "a" : "v";
    left.add(std::string(v) + "_" + joint(j) + " = ", std::string("\\mathbf{") + v + "}_{" + joint(j) + "} = ");
    Vec a = side_motion(first, j, second, left);
    Vec b = side_motion(second_side, j, second, right);
    if (d.inner < 0) {  // J on the block = J on the guide + the slide
      const SolvingPlan::Slider& s = plan_.sliders[std::size_t(-1 - d.inner)];
      const Vec u = direction(s);
      const ex rate = slide_rate(s), second_rate = slide_second_rate(s);
      const Vec slide = second ? second_rate * u + 2 * cross(omega(s.guide), rate * u) : rate * u;
      const bool first_is_block = s.block == first.link;
      if (first_is_block) b = b + slide;
      else a = a + slide;
      Words& w = first_is_block ? right : left;
      w.add(" + " + name_of(second ? second_rate : rate) + " u_" + joint(j),
            " + " + latex_of(second ? second_rate : rate) + "\\,\\mathbf{u}_{" + joint(j) + "}");
      if (second && !omega(s.guide).is_zero()) {
        w.add(" + 2 " + name_of(omega(s.guide)) + " x " + name_of(rate) + " u_" + joint(j),
              " + 2\\,\\boldsymbol{" + latex_of(omega(s.guide)) + "} \\times " + latex_of(rate) + "\\,\\mathbf{u}_{" + joint(j) + "}");
      }
    }
    list.push_back({MethodRelation::Kind::statement, left.text + " = " + right.text, left.latex + " = " + right.latex, 0, 0});
    list.push_back({MethodRelation::Kind::component, "x", "x", a.x, b.x});
    list.push_back({MethodRelation::Kind::component, "y", "y", a.y, b.y});
    solve(list, {a.x - b.x, a.y - b.y}, unknowns);
    if (d.inner >= 0) {  // then the middle joint itself, from the first side
      const Vec named = second ? acceleration_symbols(j, first.link) : velocity_symbols(j, first.link);
      list.push_back({MethodRelation::Kind::solution, "", "", named.x, a.x});
      list.push_back({MethodRelation::Kind::solution, "", "", named.y, a.y});
    }
  }

  // Two equations linear in two unknowns, by Cramer's rule with the known parts kept as
  // they are written (expanding them into one fraction triples a formula's length).
  void solve(std::vector<MethodRelation>& list, const std::vector<ex>& equations, const std::vector<ex>& unknowns) {
    if (equations.size() == 2 && unknowns.size() == 2) {
      GiNaC::exmap none;
      for (const ex& u : unknowns) none[u] = 0;
      ex m[2][2], r[2];
      for (int i = 0; i < 2; ++i) {
        const ex e = equations[std::size_t(i)];
        r[i] = -e.subs(none);
        for (int k = 0; k < 2; ++k) m[i][k] = e.expand().coeff(unknowns[std::size_t(k)], 1);
      }
      // Collected in the first column's symbols (x_B*(y_C - y_D) + ...), in name order.
      std::map<std::string, ex> column;
      for (const ex& s : symbols_of(m[0][0] + m[1][0])) column[GiNaC::ex_to<GiNaC::symbol>(s).get_name()] = s;
      GiNaC::lst by;
      for (const auto& [name, s] : column) by.append(s);
      const ex det = GiNaC::collect((m[0][0] * m[1][1] - m[0][1] * m[1][0]).expand(), by);
      list.push_back({MethodRelation::Kind::solution, "", "", unknowns[0], (r[0] * m[1][1] - r[1] * m[0][1]) / det});
      list.push_back({MethodRelation::Kind::solution, "", "", unknowns[1], (m[0][0] * r[1] - m[1][0] * r[0]) / det});
      return;
    }
    GiNaC::lst eqs, vars;
    for (const ex& e : equations) eqs.append(e == 0);
    for (const ex& u : unknowns) vars.append(u);
    const ex solution = GiNaC::lsolve(eqs, vars);
    for (const ex& s : solution) {
      // normal()'s numerator and denominator come factored in part or not, as GiNaC's
      // term order (hashes of addresses) falls: expanded, they are the same from every build.
      const ex quotient = s.rhs().normal().numer_denom();
      list.push_back({MethodRelation::Kind::solution, "", "", s.lhs(), quotient.op(0).expand() / quotient.op(1).expand()});
    }
  }

  // Seed 002's form: J on a circle about each pin (a link's length) or on a line of a
  // guide (at a fixed distance), differentiated in time; then each link's rates.
  void joint_coordinates(MethodStep& step, const SolvingPlan::Dyad& d, std::size_t j, const Side& first,
                         const Side& second_side) {
    // Time derivatives of the symbols a side's relation uses: d/dt x_O = v_Ox, d/dt theta = omega.
    GiNaC::exmap once, twice;
    const auto derivative = [&](const ex& e, const GiNaC::exmap& map) {
      ex total = 0;
      for (const auto& [s, rate] : map) total += partial(e, GiNaC::ex_to<GiNaC::symbol>(s)) * rate;
      return total;
    };
    const Vec r_j = position(j), v_j = velocity_symbols(j, d.first), a_j = acceleration_symbols(j, d.first);
    once[r_j.x] = v_j.x;
    once[r_j.y] = v_j.y;
    twice[v_j.x] = a_j.x;
    twice[v_j.y] = a_j.y;
    std::vector<ex> constraints;
    GiNaC::exmap same;  // a slide point that is J: its position is J's
    for (const Side& side : {first, second_side}) {
      Words w;
      ex c;
      if (side.edge >= 0) {
        const std::size_t o = plan_.pins[std::size_t(side.edge)].joint;
        const std::size_t known = plan_.pins[std::size_t(side.edge)].a == side.link ? plan_.pins[std::size_t(side.edge)].b
                                                                                     : plan_.pins[std::size_t(side.edge)].a;
        const Vec r = r_j - position(o);
        c = (GiNaC::pow(r.x, 2) + GiNaC::pow(r.y, 2) - GiNaC::pow(length(o, j), 2)) / 2;
        const Vec ro = position(o);
        if (known != 0 && !at_rest(o)) {
          const Vec vo = velocity(o, known), ao = acceleration(o, known);
          once[ro.x] = vo.x;
          once[ro.y] = vo.y;
          twice[vo.x] = ao.x;
          twice[vo.y] = ao.y;
        }
        step.velocity.push_back({MethodRelation::Kind::statement,
                                 "(x_" + joint(j) + " - x_" + joint(o) + ")^2 + (y_" + joint(j) + " - y_" + joint(o) +
                                     ")^2 = L_" + joint(o) + joint(j) + "^2",
                                 "(x_{" + joint(j) + "} - x_{" + joint(o) + "})^{2} + (y_{" + joint(j) + "} - y_{" + joint(o) +
                                     "})^{2} = L_{" + joint(o) + joint(j) + "}^{2}",
                                 0, 0});
      } else {
        const SolvingPlan::Slider& s = plan_.sliders[std::size_t(-1 - side.edge)];
        const Vec u = direction(s), r = r_j - position(s.joint);
        // J on the block's own slide point: on the line itself (h = 0), and where the
        // derivatives leave r_S - r_J it is zero (S is J's position on the guide).
        const bool on_line = coincide(s.joint, j, side.link);
        if (on_line) {
          same[position(s.joint).x] = r_j.x;
          same[position(s.joint).y] = r_j.y;
        }
        const ex h = on_line ? ex(0) : symbol("h_" + joint(j) + joint(s.joint), "h_{" + joint(j) + joint(s.joint) + "}");
        c = r.x * u.y - r.y * u.x - h;  // J's distance from the guide's line through S
        const Vec rs = position(s.joint);
        if (s.guide != 0) {
          const Vec vs = velocity(s.joint, s.guide), as = acceleration(s.joint, s.guide);
          once[rs.x] = vs.x;
          once[rs.y] = vs.y;
          twice[vs.x] = as.x;
          twice[vs.y] = as.y;
        }
        add_angle_rates(angle(s.guide), once, twice);
        step.velocity.push_back({MethodRelation::Kind::statement,
                                 "(r_" + joint(j) + " - r_" + joint(s.joint) + ") x u_" + joint(s.joint) + " = " +
                                     (on_line ? "0" : "h_" + joint(j) + joint(s.joint)),
                                 "(\\mathbf{r}_{" + joint(j) + "} - \\mathbf{r}_{" + joint(s.joint) + "}) \\times \\mathbf{u}_{" +
                                     joint(s.joint) + "} = " + (on_line ? "0" : "h_{" + joint(j) + joint(s.joint) + "}"),
                                 0, 0});
      }
      step.velocity.push_back({MethodRelation::Kind::component, "position", "position", c, 0});
      constraints.push_back(c);
    }
    // Velocity: d/dt of each relation, linear in v_J; acceleration: d/dt again, linear in a_J.
    std::vector<ex> velocity_equations, acceleration_equations;
    // Written collected in the rates, as the textbooks write them: (x_C - x_B)*v_Cx + ...,
    // not multiplied out term by term (collect keeps GiNaC's canonical order: the same
    // from every build, as expand's).
    GiNaC::lst rates, second_rates;
    for (const auto& [s, rate] : once) rates.append(rate);
    for (const auto& [s, rate] : twice) second_rates.append(rate);
    for (const ex& c : constraints) {
      const ex dc = derivative(c, once).expand();
      velocity_equations.push_back(GiNaC::collect(dc.subs(same).expand(), rates));
      GiNaC::exmap both = once;
      for (const auto& [s, rate] : twice) both[s] = rate;
      acceleration_equations.push_back(GiNaC::collect(derivative(dc, both).expand().subs(same).expand(), second_rates));
    }
    for (const ex& e : velocity_equations) step.velocity.push_back({MethodRelation::Kind::component, "d/dt", "\\tfrac{d}{dt}", e, 0});
    solve(step.velocity, velocity_equations, {v_j.x, v_j.y});
    for (const ex& e : acceleration_equations)
      step.acceleration.push_back({MethodRelation::Kind::component, "d2/dt2", "\\tfrac{d^{2}}{dt^{2}}", e, 0});
    solve(step.acceleration, acceleration_equations, {a_j.x, a_j.y});
    // Each link's rates from its joints: omega = (r_OJ x v_OJ) / L^2 about a pin, the
    // guide's about a slider; a slider's rate along its line.
    for (const Side& side : {first, second_side}) {
      if (side.edge >= 0) {
        const std::size_t o = plan_.pins[std::size_t(side.edge)].joint;
        const std::size_t known = plan_.pins[std::size_t(side.edge)].a == side.link ? plan_.pins[std::size_t(side.edge)].b
                                                                                     : plan_.pins[std::size_t(side.edge)].a;
        const bool from_rest = known == 0 || at_rest(o);
        const Vec r = r_j - position(o);
        const Vec rel_v = v_j - (from_rest ? Vec{} : velocity(o, known)), rel_a = a_j - (from_rest ? Vec{} : acceleration(o, known));
        const ex l2 = GiNaC::pow(length(o, j), 2);
        const int u = plan_.bodies[side.link].unknown;
        if (u < 0) continue;
        step.velocity.push_back({MethodRelation::Kind::solution, "", "", system_.unknowns[std::size_t(u)].rate,
                                 (r.x * rel_v.y - r.y * rel_v.x) / l2});
        step.acceleration.push_back({MethodRelation::Kind::solution, "", "", system_.unknowns[std::size_t(u)].second_rate,
                                     (r.x * rel_a.y - r.y * rel_a.x) / l2});
      } else {
        const SolvingPlan::Slider& s = plan_.sliders[std::size_t(-1 - side.edge)];
        if (s.unknown < 0) continue;
        const Vec u = direction(s), r = arm(s.joint, j, side.link);
        const ex w = omega(side.link), al = alpha(side.link);
        const Vec vs = s.guide == 0 ? Vec{} : velocity(s.joint, s.guide), as = s.guide == 0 ? Vec{} : acceleration(s.joint, s.guide);
        const Vec slide_v = v_j - vs - cross(w, r);
        const Vec slide_a = a_j - as - cross(al, r) + GiNaC::pow(w, 2) * r;
        step.velocity.push_back({MethodRelation::Kind::solution, "", "", system_.unknowns[std::size_t(s.unknown)].rate,
                                 slide_v.x * u.x + slide_v.y * u.y});
        step.acceleration.push_back({MethodRelation::Kind::solution, "", "", system_.unknowns[std::size_t(s.unknown)].second_rate,
                                     slide_a.x * u.x + slide_a.y * u.y});
      }
    }
  }

  // d/dt theta = omega, d/dt omega = alpha for the angle symbols in theta.
  void add_angle_rates(const ex& theta, GiNaC::exmap& once, GiNaC::exmap& twice) const {
    for (std::size_t i = 0; i < system_.unknowns.size(); ++i) {
      const Coordinate& q = system_.unknowns[i];
      if (theta.has(q.symbol)) {
        once[q.symbol] = q.rate;
        twice[q.rate] = q.second_rate;
      }
    }
    if (theta.has(system_.input.symbol)) {
      once[system_.input.symbol] = system_.input.rate;
      twice[system_.input.rate] = system_.input.second_rate;
    }
  }
};

bool solved_dyad_by_dyad(const ConstraintSystem& system) { return system.plan && system.plan->closed_form; }

[[noreturn]] void refuse_method(const ConstraintSystem& system, DerivationMethod method) {
  const char* what = system.plan          ? " (this one has links solved together by Newton)"
                     : !system.frames.empty() ? " (this file is a spatial chain of frames)"
                                              : " (this file is vector loops)";
  throw InputError(system.source_file + ": --method " + method_name(method) +
                   " works dyad by dyad: it needs a mechanism written as joints and links whose links all form "
                   "dyads" + what + "; --method loops works for every file");
}

}  // namespace

void check_method_applies(const ConstraintSystem& system, DerivationMethod method) {
  if (method != DerivationMethod::loops && !solved_dyad_by_dyad(system)) refuse_method(system, method);
}

DyadDerivation derive_by_dyads(const ConstraintSystem& system, DerivationMethod method) {
  count_work(Work::dyad_derivation);
  if (!solved_dyad_by_dyad(system)) refuse_method(system, method);
  return Writer(system, method).run();
}

}  // namespace kinema
