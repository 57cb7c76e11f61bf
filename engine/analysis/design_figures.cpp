#include "engine/analysis/design_figures.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "engine/base/work_count.hpp"
#include "engine/analysis/toggles.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/base/units.hpp"

namespace kinema {

using GiNaC::ex;

namespace {

// A side of the loop while the sides are told apart.
struct Side {
  enum class Kind { crank, unknown, ground } kind;
  FourBarSide side;
};

// Which of the four sides is which (indices into the loop's terms).
struct FourBarSides {
  std::size_t crank = 4, ground = 4, coupler = 4, rocker = 4;
};

// The loop's four terms as sides: the crank turns with the input, two turn with the
// unknowns, the ground is fixed; nullopt for a loop that is not a four-bar's.
std::optional<std::vector<Side>> loop_sides(const ConstraintSystem& system) {
  GiNaC::exmap parameters;
  for (const SystemParameter& p : system.parameters) parameters[p.symbol] = p.value;
  std::vector<Side> sides;
  for (const ex& term : system.groups.front().terms) {
    const LinkVector v = split_link_vector(term);
    const ex length = GiNaC::evalf(v.length.subs(parameters));
    if (!GiNaC::is_a<GiNaC::numeric>(length) || !GiNaC::ex_to<GiNaC::numeric>(length).is_real()) return std::nullopt;
    Side side{Side::Kind::ground, {v.length, GiNaC::ex_to<GiNaC::numeric>(length).to_double(), 0}};
    if (v.polar && v.angle.is_equal(system.input.symbol)) {
      side.kind = Side::Kind::crank;
    } else if (v.polar && !v.angle.has(system.input.symbol)) {
      bool found = false;
      for (std::size_t j = 0; j < 2; ++j) {
        if (v.angle.is_equal(system.unknowns[j].symbol)) {
          side.kind = Side::Kind::unknown;
          side.side.unknown = j;
          found = true;
        } else if (v.angle.has(system.unknowns[j].symbol)) {
          return std::nullopt;
        }
      }
      const ex angle = GiNaC::evalf(v.angle.subs(parameters));
      if (!found && !GiNaC::is_a<GiNaC::numeric>(angle)) return std::nullopt;
      if (!found) {
        const GiNaC::numeric value = GiNaC::ex_to<GiNaC::numeric>(angle);
        side.side.angle = v.angle;
        side.side.angle_value = value.is_real() ? value.to_double() : std::numeric_limits<double>::quiet_NaN();
      }
    } else if (v.polar) {
      return std::nullopt;
    }
    sides.push_back(side);
  }
  return sides;
}

// The crank, the ground, and of the two sides that turn with unknowns the coupler and the
// rocker; nullopt where they cannot be told apart.
std::optional<FourBarSides> name_sides(const ConstraintSystem& system, const std::vector<Side>& sides) {
  FourBarSides named;
  std::size_t unknown_sides = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    if (sides[k].kind == Side::Kind::crank) named.crank = named.crank == 4 ? k : 5;
    if (sides[k].kind == Side::Kind::ground) named.ground = named.ground == 4 ? k : 5;
    if (sides[k].kind == Side::Kind::unknown) ++unknown_sides;
  }
  if (named.crank >= 4 || named.ground >= 4 || unknown_sides != 2) return std::nullopt;
  if (system.plan) {
    // Joints and links: the rocker is the link other than the crank with a fixed pivot.
    const SolvingPlan& plan = *system.plan;
    int rocker_unknown = -1;
    for (std::size_t b = 1; b < plan.bodies.size(); ++b) {
      if (b == plan.driver_body && plan.driver_slider < 0) continue;
      for (const auto& point : plan.bodies[b].points)
        if (plan.joints[point.first].ground && !plan.joints[point.first].slider) rocker_unknown = plan.bodies[b].unknown;
    }
    for (std::size_t k = 0; k < 4; ++k) {
      if (sides[k].kind != Side::Kind::unknown) continue;
      (static_cast<int>(sides[k].side.unknown) == rocker_unknown ? named.rocker : named.coupler) = k;
    }
  } else if ((named.crank + 1) % 4 == named.ground || (named.ground + 1) % 4 == named.crank) {
    // Written round the loop: the coupler is opposite the ground, the rocker opposite the crank.
    named.coupler = (named.ground + 2) % 4;
    named.rocker = (named.crank + 2) % 4;
  }
  if (named.coupler >= 4 || named.rocker >= 4 || sides[named.coupler].kind != Side::Kind::unknown ||
      sides[named.rocker].kind != Side::Kind::unknown)
    return std::nullopt;
  return named;
}

// Grashof's inequality s + l against p + q (in the output unit) and the kind of four-bar
// the lengths make; false where there is nothing to classify.
bool classify(FourBarFigures& f, const OutputScale& scale) {
  const GrashofClass kind = grashof_class(f.ground, f.crank, f.coupler, f.rocker, scale.length);
  if (kind == GrashofClass::none) return false;
  const double lengths[4] = {f.ground, f.crank, f.coupler, f.rocker};
  const double s = *std::min_element(lengths, lengths + 4), l = *std::max_element(lengths, lengths + 4);
  const double p_q = f.ground + f.crank + f.coupler + f.rocker - s - l;
  const auto shown = [&](double x) { return format_significant(x / scale.length); };
  const char* relation = kind == GrashofClass::change_point ? "=" : kind == GrashofClass::triple_rocker ? ">" : "<";
  f.inequality = "s + l = " + shown(s) + " + " + shown(l) + " = " + shown(s + l) + " " + relation + " p + q = " +
                 shown(p_q) + " (" + scale.length_unit + ")";
  f.grashof = grashof_name(kind);
  return true;
}

// The transmission angle from the solved positions over a turn from the first input
// value: at the coupler-rocker joint, between the coupler (back towards the crank pin)
// and the rocker (on to its pivot), as the loop goes round; its least and greatest, and
// whether the whole turn assembles.
void transmission_over_a_turn(const Model& model, const FourBarLoop& loop, FourBarFigures& f) {
  const ConstraintSystem& system = model.system;
  std::vector<double> inputs;
  const double first = system.input.values.empty() ? 0.0 : system.input.values.front();
  for (int k = 0; k <= 360; ++k) inputs.push_back(first + k * kPi / 180);
  const MotionTable turn = solve_motion(model, inputs);
  const FourBarLoopValues values = loop.values();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f.least_transmission = f.greatest_transmission = f.least_at = f.greatest_at = nan;
  f.full_turn = true;
  for (std::size_t row = 0; row + 1 < turn.size(); ++row) {
    if (turn.status(row) == Status::unassembled) {
      f.full_turn = false;
      continue;
    }
    const double mu = transmission_angle(values, turn.q(row)[Eigen::Index(loop.coupler.unknown)],
                                         turn.q(row)[Eigen::Index(loop.rocker.unknown)]);
    double at = std::fmod(turn.input(row) * 180 / kPi, 360.0);
    if (at < 0) at += 360;
    if (!(mu >= f.least_transmission)) {
      f.least_transmission = mu;
      f.least_at = at;
    }
    if (!(mu <= f.greatest_transmission)) {
      f.greatest_transmission = mu;
      f.greatest_at = at;
    }
  }
}

}  // namespace

std::optional<FourBarLoop> four_bar_loop(const ConstraintSystem& system) {
  if (system.input.dimension != Dimension::angle || !system.frames.empty()) return std::nullopt;
  if (system.groups.size() != 1 || system.groups.front().terms.size() != 4 || system.unknowns.size() != 2)
    return std::nullopt;
  const std::optional<std::vector<Side>> sides = loop_sides(system);
  if (!sides) return std::nullopt;
  const std::optional<FourBarSides> named = name_sides(system, *sides);
  if (!named) return std::nullopt;
  return FourBarLoop{(*sides)[named->ground].side, (*sides)[named->crank].side, (*sides)[named->coupler].side,
                     (*sides)[named->rocker].side};
}

std::optional<std::vector<MovingPointTerm>> moving_point_terms(const ConstraintSystem& system) {
  if (!system.frames.empty()) return std::nullopt;
  std::vector<ex> variables{system.input.symbol};
  for (const auto& u : system.unknowns) variables.push_back(u.symbol);
  const auto moves = [&](const ex& e) {
    return std::any_of(variables.begin(), variables.end(), [&](const ex& v) { return e.has(v); });
  };
  GiNaC::exmap parameters;
  for (const SystemParameter& p : system.parameters) parameters[p.symbol] = p.value;
  const auto real_number = [&](const ex& e) {
    const ex value = GiNaC::evalf(e.subs(parameters));
    return GiNaC::is_a<GiNaC::numeric>(value) && GiNaC::ex_to<GiNaC::numeric>(value).is_real();
  };
  std::vector<MovingPointTerm> terms;
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    const PointObservable& point = system.points[p];
    if (!point.written || point.written_terms.empty() || point.position.size() != 2) return std::nullopt;
    ex sum = 0;
    for (const ex& term : point.written_terms) sum += term;
    if (!(sum - *point.written).expand().is_zero()) return std::nullopt;
    for (const ex& term : point.written_terms) {
      if (!moves(term)) continue;
      const LinkVector v = split_link_vector(term);
      if (!v.polar || moves(v.length) || !real_number(v.length)) return std::nullopt;
      std::size_t found = variables.size();
      for (std::size_t k = 0; k < variables.size(); ++k)
        if (v.angle.has(variables[k])) found = found == variables.size() ? k : variables.size() + 1;
      if (found >= variables.size()) return std::nullopt;  // none (a moving length), or two
      const ex offset = (v.angle - variables[found]).expand();
      if (moves(offset) || !real_number(offset)) return std::nullopt;
      terms.push_back({p, static_cast<int>(found) - 1, v.length, offset});
    }
  }
  return terms;
}

FourBarLoopValues FourBarLoop::values() const {
  const auto numbers = [](const FourBarSide& side) { return FourBarSideValues{side.value, side.unknown, side.angle_value}; };
  return FourBarLoopValues{numbers(ground), numbers(crank), numbers(coupler), numbers(rocker)};
}

double transmission_angle(const FourBarLoopValues& loop, double coupler_angle, double rocker_angle) {
  // The signed terms are the edges of the loop as it goes round (crank O2-A, coupler
  // A-B, rocker B-O4, ground O4-O2): at B, between B-A (back along the coupler) and
  // B-O4 (on along the rocker), from the solved angles.
  const auto edge = [](const FourBarSideValues& side, double angle) { return std::polar(side.value < 0 ? -1.0 : 1.0, angle); };
  const std::complex<double> back = -edge(loop.coupler, coupler_angle), on = edge(loop.rocker, rocker_angle);
  double mu = std::abs(std::arg(on / back)) * 180 / kPi;
  if (mu < 1e-3) mu = 0;  // folded flat (a change point solved to sqrt(eps))
  if (mu > 180 - 1e-3) mu = 180;
  return mu;
}

GrashofClass grashof_class(double ground, double crank, double coupler, double rocker, double length_unit) {
  ground = std::fabs(ground), crank = std::fabs(crank), coupler = std::fabs(coupler), rocker = std::fabs(rocker);
  const double lengths[4] = {ground, crank, coupler, rocker};
  const double s = *std::min_element(lengths, lengths + 4), l = *std::max_element(lengths, lengths + 4);
  const double sum = ground + crank + coupler + rocker, p_q = sum - s - l;
  const double tolerance = 1e-9 * l;
  // A side of length zero is no four-bar to classify (a crank of length zero drives
  // nothing), and sums past the largest number in the output unit have no figures.
  if (!(s > 0) || !std::isfinite(sum / length_unit)) return GrashofClass::none;
  if (std::fabs(s + l - p_q) <= tolerance) return GrashofClass::change_point;
  if (s + l > p_q) return GrashofClass::triple_rocker;
  if (std::fabs(ground - s) <= tolerance) return GrashofClass::double_crank;
  if (std::fabs(crank - s) <= tolerance) return GrashofClass::crank_rocker;
  if (std::fabs(rocker - s) <= tolerance) return GrashofClass::rocker_crank;
  return GrashofClass::double_rocker;
}

const char* grashof_name(GrashofClass kind) {
  switch (kind) {
    case GrashofClass::crank_rocker: return "crank-rocker";
    case GrashofClass::double_crank: return "double-crank";
    case GrashofClass::rocker_crank: return "rocker-crank";
    case GrashofClass::double_rocker: return "double-rocker";
    case GrashofClass::change_point: return "change point";
    case GrashofClass::triple_rocker: return "non-Grashof triple rocker";
    case GrashofClass::none: break;
  }
  return "n/a";
}

std::optional<FourBarFigures> four_bar_figures(const Model& model) {
  count_work(Work::design_figures);
  const std::optional<FourBarLoop> loop = four_bar_loop(model.system);
  if (!loop) return std::nullopt;
  FourBarFigures f;
  f.ground = std::fabs(loop->ground.value);
  f.crank = std::fabs(loop->crank.value);
  f.coupler = std::fabs(loop->coupler.value);
  f.rocker = std::fabs(loop->rocker.value);
  if (!classify(f, OutputScale(model.system))) return std::nullopt;
  transmission_over_a_turn(model, *loop, f);
  for (const Toggle& t : find_toggles(model)) f.toggles.push_back(t.input * 180 / kPi);
  return f;
}

std::string describe_four_bar(const FourBarFigures& f, const std::string& input_name) {
  std::string text = (f.grashof == "change point" || f.grashof.rfind("non-", 0) == 0 ? "" : "Grashof ") + f.grashof +
                     " (" + f.inequality + ")";
  if (std::isfinite(f.least_transmission)) {
    text += "; transmission angle from " + format_significant(f.least_transmission, 4) + " deg (" + input_name + " = " +
            format_significant(f.least_at, 4) + " deg) to " + format_significant(f.greatest_transmission, 4) + " deg (" +
            input_name + " = " + format_significant(f.greatest_at, 4) + " deg)" +
            (f.full_turn ? "" : " where it can be assembled");
  }
  if (f.toggles.empty()) return text + "; no toggle position";
  text += "; toggle positions at " + input_name + " =";
  for (std::size_t k = 0; k < f.toggles.size(); ++k)
    text += (k ? ", " : " ") + format_fixed(f.toggles[k], 4);
  return text + " deg";
}

std::vector<Strokes> slider_strokes(const Model& model) {
  count_work(Work::design_figures);
  std::vector<Strokes> all;
  const ConstraintSystem& system = model.system;
  if (system.input.dimension != Dimension::angle || !system.frames.empty()) return all;
  if (system.unknowns.size() > kMaxStrokeUnknowns) return all;
  const OutputScale scale(system);
  std::vector<std::size_t> lengths;
  for (std::size_t j = 0; j < system.unknowns.size(); ++j)
    if (system.unknowns[j].dimension == Dimension::length) lengths.push_back(j);
  bool whole_turn = false;
  const std::vector<std::vector<Toggle>> found = find_limit_positions(model, lengths, &whole_turn);  // one sweep for all
  for (std::size_t w = 0; w < lengths.size(); ++w) {
    const std::size_t j = lengths[w];
    const std::vector<Toggle>& limits = found[w];
    if (limits.empty()) continue;
    // A coordinate that does not move (its rate 0 at every row, or rounding's sign) has none.
    double low = limits.front().q[Eigen::Index(j)], high = low;
    for (const Toggle& limit : limits) {
      low = std::min(low, limit.q[Eigen::Index(j)]);
      high = std::max(high, limit.q[Eigen::Index(j)]);
    }
    if (high - low <= 1e-9 * system.length_scale) continue;
    Strokes s;
    s.name = system.unknowns[j].name;
    for (const Toggle& limit : limits) {
      s.limit_inputs.push_back(limit.input * 180 / kPi);
      s.limit_values.push_back(limit.q[Eigen::Index(j)] / scale.length);
      s.maxima.push_back(limit.maximum);
    }
    // Across a part of the turn that does not assemble the crank does not pass from one
    // limit to the next: no strokes.
    s.whole_turn = whole_turn;
    if (whole_turn) set_strokes(s, system.input.rate_value);
    all.push_back(s);
  }
  return all;
}

void set_strokes(Strokes& s, double rate) {
  // The crank turns the way its rate says: each stroke from a limit to the next it reaches.
  const std::size_t n = s.limit_inputs.size();
  s.strokes.clear();
  s.time_ratio = std::numeric_limits<double>::quiet_NaN();
  if (n < 2) return;
  for (std::size_t k = 0; k < n; ++k) {
    const double ahead = k + 1 < n ? s.limit_inputs[k + 1] - s.limit_inputs[k] : 360 - (s.limit_inputs[k] - s.limit_inputs[0]);
    const double behind = k > 0 ? s.limit_inputs[k] - s.limit_inputs[k - 1] : 360 - (s.limit_inputs[n - 1] - s.limit_inputs[0]);
    s.strokes.push_back(rate >= 0 ? ahead : behind);
  }
  // A quick return's figure: with more limit positions the slider turns back on its way.
  if (n == 2) s.time_ratio = std::max(s.strokes[0], s.strokes[1]) / std::min(s.strokes[0], s.strokes[1]);
}

std::string describe_strokes(const Strokes& s, const std::string& input_name, const std::string& unit) {
  // The limits shown together: a limit at round-off from 0 beside the others is 0.
  const double with = largest_magnitude(s.limit_values.data(), s.limit_values.size());
  if (s.two_limits()) {
    return s.name + " at its limits at " + input_name + " = " + format_fixed(s.limit_inputs[0], 4) + " deg (" +
           format_at_scale(s.limit_values[0], with) + " " + unit + ") and " + format_fixed(s.limit_inputs[1], 4) +
           " deg (" + format_at_scale(s.limit_values[1], with) + " " + unit + "); strokes of " +
           format_significant(s.strokes[0]) + " and " + format_significant(s.strokes[1]) +
           " deg of crank, time ratio " + format_significant(s.time_ratio);
  }
  // Other than two: each limit said a maximum or a minimum (with four, one maximum may lie
  // below the other's value), and the strokes between them.
  const std::size_t n = s.limit_inputs.size();
  const auto separator = [n](std::size_t k) { return k == 0 ? " " : k + 1 == n ? " and " : ", "; };
  std::string text = s.name + " at " + std::to_string(n) + (n == 1 ? " limit position" : " limit positions") + " at " +
                     input_name + " =";
  for (std::size_t k = 0; k < n; ++k)
    text += separator(k) + format_fixed(s.limit_inputs[k], 4) + " deg (" + (s.maxima[k] ? "maximum " : "minimum ") +
            format_at_scale(s.limit_values[k], with) + " " + unit + ")";
  if (!s.whole_turn) return text + "; no strokes: part of the turn does not assemble";
  if (s.strokes.empty()) return text;
  text += "; strokes of";
  for (std::size_t k = 0; k < n; ++k) text += separator(k) + format_significant(s.strokes[k]);
  return text + " deg of crank, each from a limit to the next";
}

}  // namespace kinema
