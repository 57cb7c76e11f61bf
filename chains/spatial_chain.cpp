#include "chains/spatial_chain.hpp"

#include <optional>
#include <set>

#include "engine/base/errors.hpp"
#include "engine/constraints/differentiate.hpp"
#include "engine/base/naming.hpp"
#include "engine/base/number_format.hpp"
#include "engine/constraints/formula_reader.hpp"
#include "engine/constraints/length_power.hpp"

namespace kinema {

GiNaC::exmap SpatialKinematics::instant() const {
  GiNaC::exmap values;
  for (const SystemParameter& p : parameters) values[p.symbol] = p.value;
  for (std::size_t i = 0; i < variables.size(); ++i) {
    values[variables[i].symbol] = this->values[i];
    values[variables[i].rate] = rates[i];
    values[variables[i].second_rate] = second_rates[i];
  }
  values[time] = 0;
  return values;
}

std::vector<SymbolMotion> SpatialKinematics::motions() const {
  std::vector<SymbolMotion> motions;
  for (const Coordinate& v : variables) {
    motions.push_back({v.symbol, v.rate});
    motions.push_back({v.rate, v.second_rate});
  }
  motions.push_back({time, 1});
  return motions;
}

namespace {

using GiNaC::ex;

Vector3 operator+(const Vector3& a, const Vector3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vector3 operator*(const ex& k, const Vector3& a) { return {k * a[0], k * a[1], k * a[2]}; }
Vector3 cross(const Vector3& a, const Vector3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vector3 times(const GiNaC::matrix& m, const Vector3& v) {
  Vector3 r{0, 0, 0};
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned k = 0; k < 3; ++k) r[i] += m(i, k) * v[k];
  return r;
}
Vector3 column(const GiNaC::matrix& m, unsigned c) { return {m(0, c), m(1, c), m(2, c)}; }

// cos and sin of x + k Pi/2 as those of x (the seed writes e2'' = sin(alpha) E2 - cos(alpha) E3,
// not cos(alpha - Pi/2) E2 + ...).
std::pair<ex, ex> cos_sin(const ex& angle) {
  const ex expanded = angle.expand();
  const ex quarter_turns = expanded.coeff(GiNaC::Pi, 1) * 2;
  if (expanded.degree(GiNaC::Pi) == 1 && GiNaC::is_a<GiNaC::numeric>(quarter_turns) &&
      GiNaC::ex_to<GiNaC::numeric>(quarter_turns).is_integer()) {
    const ex x = expanded - quarter_turns * GiNaC::Pi / 2;
    const long k = ((GiNaC::ex_to<GiNaC::numeric>(quarter_turns).to_long() % 4) + 4) % 4;
    const ex c = GiNaC::cos(x), s = GiNaC::sin(x);
    switch (k) {
      case 1: return {-s, c};
      case 2: return {-c, -s};
      case 3: return {s, -c};
      default: return {c, s};
    }
  }
  return {GiNaC::cos(angle), GiNaC::sin(angle)};
}

// The rotation by `angle` about a coordinate axis (0, 1, 2).
GiNaC::matrix turn(unsigned axis, const ex& angle) {
  const auto [c, s] = cos_sin(angle);
  GiNaC::matrix r(3, 3);
  const unsigned a = (axis + 1) % 3, b = (axis + 2) % 3;
  r(axis, axis) = 1;
  r(a, a) = c;
  r(a, b) = -s;
  r(b, a) = s;
  r(b, b) = c;
  return r;
}

constexpr std::size_t kMaxChainFrames = 64;  ///< frames in one file
constexpr std::size_t kMaxChainTurns = 14;   ///< turns from the observer to any frame

class ChainBuilder {
 public:
  explicit ChainBuilder(const Mechanism& m) : m_(m), chain_(*m.chain) {}

  SpatialKinematics build() {
    parameters();
    variables();
    // Time may be written in the chain's formulas (not in parameters: they are constants).
    if (symbol_names_.count("t") == 0) reader_.define("t", k_.time);
    moving_.insert(k_.time);
    frames();
    points();
    closures();
    return k_;
  }

 private:
  const Mechanism& m_;
  const SpatialChain& chain_;
  SpatialKinematics k_;
  FormulaReader reader_;
  GiNaC::exmap values_;  // parameters, for evaluating their formulas
  LengthPower::Powers powers_;  // what each parameter and variable measures, where known
  std::set<GiNaC::ex, GiNaC::ex_is_less> angles_;  // the angle parameters so far
  std::set<std::string> symbol_names_;
  std::map<std::string, std::size_t> frame_index_;
  GiNaC::exset moving_;  // time, the variables and their rates: what d/dt goes through

  [[noreturn]] static void fail(const SourceLocation& where, const std::string& message) {
    throw InputError(where.str() + ": " + message);
  }

  // d/dt of a formula from the file, refused (at where) when too large to build.
  ex derivative(const ex& e, const std::string& what, const char* formula) const {
    check_derivative_size(e, moving_, what, formula);
    return time_derivative(e, k_.motions());
  }

  GiNaC::realsymbol symbol(const std::string& name) {
    GiNaC::realsymbol s(name, latex_symbol_name(name));
    reader_.define(name, s);
    symbol_names_.insert(name);
    return s;
  }

  void parameters() {
    for (const Parameter& p : m_.parameters) {
      SystemParameter entry;
      entry.text = p.text;
      entry.where = p.where;
      const std::string context = p.where.str() + ": parameter \"" + p.name + "\"";
      std::optional<int> power;  // of length, where known
      if (p.quantity) {
        entry.value = p.quantity->si_value;
        entry.dimension = p.quantity->dimension == Dimension::length || p.quantity->dimension == Dimension::angle
                              ? p.quantity->dimension
                              : Dimension::number;
        if (entry.dimension != Dimension::number) power = entry.dimension == Dimension::length ? 1 : 0;
      } else {
        const ex formula = reader_.read(p.formula, context);
        entry.formula = formula;
        entry.value = formula_value(formula, values_, context, p.formula, " (only earlier parameters can be used)");
        power = LengthPower(powers_).of(formula.expand(), context);
        entry.dimension = power == 1 ? Dimension::length
                          : power == 0 && measures_an_angle(formula, angles_) ? Dimension::angle
                                                                              : Dimension::number;
      }
      entry.symbol = symbol(p.name);
      if (entry.dimension == Dimension::angle) angles_.insert(entry.symbol);
      if (power) powers_[entry.symbol] = *power;
      values_[entry.symbol] = entry.value;
      k_.parameters.push_back(entry);
    }
  }

  void variables() {
    for (const ChainVariable& v : chain_.variables) {
      Coordinate c;
      c.name = v.name;
      c.dimension = v.dimension;
      c.where = v.where;
      c.symbol = symbol(v.name);
      powers_[c.symbol] = v.dimension == Dimension::length ? 1 : 0;
      const auto rate_name = [&](const std::string& given, int order) {
        if (!given.empty()) return given;
        return default_rate_name(v.name, order);
      };
      c.rate = symbol(rate_name(v.rate_name, 1));
      c.second_rate = symbol(rate_name(v.second_rate_name, 2));
      k_.variables.push_back(c);
      moving_.insert({c.symbol, c.rate});
      k_.unknown.push_back(v.unknown);
      k_.values.push_back(v.value);
      k_.rates.push_back(v.rate);
      k_.second_rates.push_back(v.second_rate);
    }
  }

  // A component or an angle as written: a quantity, or a formula of parameters and variables.
  ex value_of(const std::string& text, const SourceLocation& where, const std::string& what, Dimension dimension) {
    if (looks_like_quantity(text)) return quantity_of_dimension(text, dimension, where.str() + ": " + what);
    try {
      return reader_.read(text, where.str() + ": " + what);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& error) {  // GiNaC's poles and overflows while it simplifies
      fail(where, what + " = \"" + text + "\" cannot be evaluated (" + error.what() + ")");
    }
  }

  void frames() {
    k_.observer = chain_.frames.front().parent;
    for (const ChainFrame& f : chain_.frames) {
      if (f.name == k_.observer) {
        fail(f.where, "frame \"" + f.name + "\" is the observer (the first frame's parent), which is not moved or "
                      "placed; give the moving frames only");
      }
      if (frame_index_.count(f.name)) fail(f.where, "duplicate frame \"" + f.name + "\"");
      frame_index_[f.name] = k_.frames.size();
      k_.frames.emplace_back();
    }
    check_chain_size();
    std::vector<int> state(chain_.frames.size(), 0);  // 0 new, 1 in progress, 2 done
    for (std::size_t i = 0; i < chain_.frames.size(); ++i) place(i, state);
  }

  // Each turn along a chain multiplies the rotation before it, and the derivatives grow
  // with the product: 20 turns in a row took 34 s to derive, 24 never ended. Checked
  // before any symbolic work (docs/limits.md).
  void check_chain_size() const {
    if (chain_.frames.size() > kMaxChainFrames) {
      fail(chain_.frames[kMaxChainFrames].where, "the chain has more than " + std::to_string(kMaxChainFrames) +
                                                     " frames; kinema derives chains of up to " +
                                                     std::to_string(kMaxChainFrames) + " frames");
    }
    for (std::size_t i = 0; i < chain_.frames.size(); ++i) {
      std::size_t turns = 0, steps = 0;
      for (std::size_t j = i; steps <= chain_.frames.size(); ++steps) {  // a cycle stops here; place() names it
        turns += chain_.frames[j].turns.size();
        const auto parent = frame_index_.find(chain_.frames[j].parent);
        if (parent == frame_index_.end()) break;
        j = parent->second;
      }
      if (turns > kMaxChainTurns) {
        const ChainFrame& f = chain_.frames[i];
        fail(f.where, "frame \"" + f.name + "\" is " + std::to_string(turns) +
                          " turns from the observer (its own and its ancestors'); kinema derives chains of up to " +
                          std::to_string(kMaxChainTurns) +
                          " turns in a row, whose formulas grow with each turn: split the chain, or give fixed "
                          "turns as one");
      }
    }
  }

  // A frame after its parent (a parent defined later in the file is placed first).
  void place(std::size_t i, std::vector<int>& state) {
    if (state[i] == 2) return;
    const ChainFrame& f = chain_.frames[i];
    if (state[i] == 1) fail(f.where, "frame \"" + f.name + "\" is its own ancestor (a cycle of parents)");
    state[i] = 1;
    ChainFrameMotion& motion = k_.frames[i];
    motion.name = f.name;
    motion.parent = f.parent;
    GiNaC::matrix rotation = GiNaC::ex_to<GiNaC::matrix>(GiNaC::unit_matrix(3));
    Vector3 origin{0, 0, 0}, omega{0, 0, 0};
    if (f.parent != k_.observer) {
      const auto parent = frame_index_.find(f.parent);
      if (parent == frame_index_.end()) {
        fail(f.where, "frame \"" + f.name + "\": its parent \"" + f.parent + "\" is not a frame of the file (the "
                      "observer is \"" + k_.observer + "\", the first frame's parent)");
      }
      place(parent->second, state);
      const ChainFrameMotion& p = k_.frames[parent->second];
      rotation = p.rotation;
      origin = p.origin;
      omega = p.angular_velocity;
      motion.angular_velocity_terms = p.angular_velocity_terms;
    }
    Vector3 local;
    for (std::size_t c = 0; c < 3; ++c) {
      local[c] = value_of(f.origin[c], f.where, "frame \"" + f.name + "\" origin " + "xyz"[c], Dimension::length);
    }
    motion.origin = origin + times(rotation, local);
    for (const FrameTurn& t : f.turns) {
      std::string axis = t.axis;
      int sign = 1;
      if (!axis.empty() && (axis[0] == '-' || axis[0] == '+')) {
        sign = axis[0] == '-' ? -1 : 1;
        axis = axis.substr(1);
      }
      if (axis != "x" && axis != "y" && axis != "z") {
        fail(t.where, "frame \"" + f.name + "\": axis \"" + t.axis + "\" is not one of the frame's axes x, y, z "
                      "(or -x, -y, -z)");
      }
      const unsigned a = static_cast<unsigned>(axis[0] - 'x');
      const std::string what = "frame \"" + f.name + "\" turn angle";
      const ex angle = sign * value_of(t.angle, t.where, what, Dimension::angle);
      const auto power = LengthPower(powers_).of(angle.expand(), t.where.str() + ": " + what);
      if (power && *power != 0) {
        fail(t.where, what + " \"" + t.angle + "\" is " + with_article(LengthPower::describe(*power)) +
                          ", but a turn is an angle (e.g. \"30 deg\", or a parameter or variable in deg or rad)");
      }
      const Vector3 direction = column(rotation, a);  // the axis, as turned so far
      const std::string turn_of = t.where.str() + ": frame \"" + f.name + "\" turn angle";
      const ex rate = derivative(angle, turn_of, "angular velocity");
      if (!rate.is_zero()) {
        const Vector3 term = rate * direction;
        // Its derivative in the observer: the rate's own change along the axis, and the
        // axis carried round by the frame it is fixed in, whose angular velocity so far is
        // omega (w x term is the same with this term added: term x term = 0).
        const Vector3 rate_change = derivative(rate, turn_of, "angular acceleration") * direction;
        const Vector3 carried = cross(omega, term);
        omega = omega + term;
        // The rate about the axis it turns about: the parent's, for a frame's first
        // turn; after that the frame's own, as turned so far.
        const auto list = [](const Vector3& v) { return std::vector<ex>(v.begin(), v.end()); };
        motion.angular_velocity_terms.push_back(
            {rate, axis, &t == &f.turns.front() ? f.parent : f.name, list(term), list(rate_change), list(carried)});
      }
      rotation = rotation.mul(turn(a, angle));
    }
    motion.rotation = rotation;
    motion.angular_velocity = omega;
    for (std::size_t c = 0; c < 3; ++c) motion.angular_acceleration[c] = time_derivative(omega[c], k_.motions());
    state[i] = 2;
  }

  void points() {
    for (const ChainPoint& p : chain_.points) {
      const auto frame = frame_index_.find(p.frame);
      if (frame == frame_index_.end() && p.frame != k_.observer) {
        fail(p.where, "point \"" + p.name + "\": frame \"" + p.frame + "\" does not exist (frames: " + frame_list() + ")");
      }
      const std::string what = p.where.str() + ": point \"" + p.name + "\"";
      ChainPointMotion m;
      m.name = p.name;
      m.frame = p.frame;
      GiNaC::matrix rotation = GiNaC::ex_to<GiNaC::matrix>(GiNaC::unit_matrix(3));
      Vector3 origin{0, 0, 0}, omega{0, 0, 0}, alpha{0, 0, 0};
      if (frame != frame_index_.end()) {
        const ChainFrameMotion& f = k_.frames[frame->second];
        rotation = f.rotation;
        origin = f.origin;
        omega = f.angular_velocity;
        alpha = f.angular_acceleration;
      }
      Vector3 local, local_rate, local_second_rate;
      for (std::size_t c = 0; c < 3; ++c) {
        local[c] = value_of(p.at[c], p.where, "point \"" + p.name + "\" " + "xyz"[c], Dimension::length);
        local_rate[c] = derivative(local[c], what, "velocity");
        local_second_rate[c] = derivative(local_rate[c], what, "acceleration");
      }
      const Vector3 r = times(rotation, local);
      m.position = origin + r;
      for (std::size_t c = 0; c < 3; ++c) {
        m.frame_velocity[c] = derivative(origin[c], what, "frame velocity");
        m.frame_acceleration[c] = derivative(m.frame_velocity[c], what, "frame acceleration");
      }
      m.transport = cross(omega, r);
      m.relative_velocity = times(rotation, local_rate);
      m.tangential = cross(alpha, r);
      m.centripetal = cross(omega, cross(omega, r));
      m.coriolis = ex(2) * cross(omega, m.relative_velocity);
      m.relative_acceleration = times(rotation, local_second_rate);
      m.velocity = m.frame_velocity + m.transport + m.relative_velocity;
      m.acceleration = m.frame_acceleration + m.tangential + m.centripetal + m.coriolis + m.relative_acceleration;
      k_.points.push_back(m);
    }
  }

  void closures() {
    std::size_t unknowns = 0;
    for (const ChainVariable& v : chain_.variables) unknowns += v.unknown ? 1 : 0;
    if (unknowns != chain_.closures.size()) {
      const SourceLocation& where = chain_.closures.empty() ? chain_.variables.front().where : chain_.closures.front().where;
      fail(where, std::to_string(unknowns) + " variable(s) with a guess (found by the closures) but " +
                      std::to_string(chain_.closures.size()) + " closure(s): each closure finds one variable; give "
                      "as many of each");
    }
    const auto find = [&](const std::string& name, const ChainClosure& c) -> const ChainPointMotion& {
      for (const ChainPointMotion& p : k_.points)
        if (p.name == name) return p;
      fail(c.where, "closure \"" + c.name + "\": there is no point \"" + name + "\" in [points]");
    };
    for (const ChainClosure& c : chain_.closures) {
      const ChainPointMotion &a = find(c.from, c), &b = find(c.to, c);
      if (c.from == c.to) fail(c.where, "closure \"" + c.name + "\" needs two different points");
      const ex length = value_of(c.length, c.where, "closure \"" + c.name + "\" length", Dimension::length);
      const double value = formula_value(length, values_, c.where.str() + ": closure \"" + c.name + "\" length", c.length);
      if (!(value > 0)) fail(c.where, "closure \"" + c.name + "\": the length must be positive (it is " + format_significant(value) + " m)");
      // (|d|^2 - L^2) / 2L: a length, about |d| - L near the solution, so that its row of
      // Phi_q is on the scale of the others (the solvers' tolerances are lengths).
      ex residual = -GiNaC::pow(length, 2);
      for (std::size_t i = 0; i < 3; ++i) residual += GiNaC::pow(a.position[i] - b.position[i], 2);
      k_.closures.push_back({c.name, residual / (2 * length)});
    }
  }

  std::string frame_list() const {
    std::string list = k_.observer;
    for (const ChainFrame& f : chain_.frames) list += ", " + f.name;
    return list;
  }
};

}  // namespace

SpatialKinematics build_spatial_chain(const Mechanism& mechanism) {
  if (!mechanism.chain) throw InputError(mechanism.source_file + ": not a spatial chain (no [frames])");
  try {
    return ChainBuilder(mechanism).build();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& error) {  // GiNaC on a product of turns: a pole, an overflow
    throw InputError(mechanism.source_file + ": the chain's kinematics cannot be formed (" + error.what() +
                     "); check the frames' angles and origins");
  }
}

namespace {

// The index of the chain's input variable (SpatialChain::input), or variables.size() for time.
std::size_t chain_input(const Mechanism& mechanism, const SpatialKinematics& k) {
  const SpatialChain& chain = *mechanism.chain;
  if (chain.input.empty()) return k.variables.size();
  const std::string where = chain.input_where.line > 0 ? chain.input_where.str() + ": input \"" + chain.input + "\""
                                                       : mechanism.source_file + ": --input " + chain.input;
  std::string driven;
  for (std::size_t i = 0; i < k.variables.size(); ++i)
    if (!k.unknown[i]) driven += (driven.empty() ? "" : ", ") + k.variables[i].name;
  for (std::size_t i = 0; i < k.variables.size(); ++i) {
    if (k.variables[i].name != chain.input) continue;
    if (k.unknown[i]) {
      throw InputError(where + ": this variable is found by the closures (it has a guess); the input is a variable "
                               "that drives the chain (" + (driven.empty() ? "none here" : driven) + "), or time");
    }
    bool moving = false;
    for (std::size_t j = 0; j < k.variables.size(); ++j)
      moving = moving || (j != i && !k.unknown[j] && (k.rates[j] != 0 || k.second_rates[j] != 0));
    if (k.rates[i] == 0 && moving) {
      throw InputError(where + ": it has no rate, so the other driven variables cannot follow it (they move at the "
                               "time it reaches each value at its rate); give it a rate, or keep time as the input");
    }
    // With a second rate the input's rate changes along the time run, but an input run
    // gives every value one rate: the followers would move at the wrong instant (each
    // gaining omega_i alpha_in / omega_in), a motion the file does not describe.
    if (k.second_rates[i] != 0 && moving) {
      const std::string unit = k.variables[i].dimension == Dimension::angle ? " rad/s^2" : " m/s^2";
      throw InputError(where + ": it has a second rate (" + format_significant(k.second_rates[i]) + unit +
                       "), so its rate changes from value to value along the file's motion, while an input run "
                       "gives every value one rate and the other driven variables could not follow it; keep "
                       "time as the input (kinema eval FILE --at T), or give it no second rate");
    }
    return i;
  }
  throw InputError(where + ": no such variable; the input is one of the driven variables of [variables] (" +
                   (driven.empty() ? "none here" : driven) + "), or time (no input)");
}

// The system's input: time t, or the driven variable the chain names as its input.
// Returns its index among the variables (their count for time).
std::size_t set_chain_input(ConstraintSystem& system, const Mechanism& mechanism, const SpatialKinematics& k) {
  const std::size_t input = chain_input(mechanism, k);
  Driver& t = system.input;
  if (input == k.variables.size()) {
    t.name = "t";
    t.dimension = Dimension::time;
    t.symbol = k.time;  // the same symbol as in the chain's formulas of time
    t.rate = GiNaC::realsymbol("t_rate", "\\dot{t}");
    t.second_rate = GiNaC::realsymbol("t_second_rate", "\\ddot{t}");
    t.values = {0.0};
    t.rate_value = 1.0;
    t.second_rate_value = 0.0;
  } else {
    bool timed = false;
    for (const ChainPointMotion& p : k.points)
      for (const ex& c : p.position) timed = timed || c.has(k.time);
    for (const ChainFrameMotion& f : k.frames)
      for (const ex& c : f.origin) timed = timed || c.has(k.time) || f.rotation.has(k.time);
    if (timed) {
      throw InputError(mechanism.chain->input_where.line > 0
                           ? mechanism.chain->input_where.str() + ": input \"" + mechanism.chain->input +
                                 "\": the chain has formulas of time t; keep time as its input"
                           : mechanism.source_file + ": --input " + mechanism.chain->input +
                                 ": the chain has formulas of time t; keep time as its input");
    }
    static_cast<Coordinate&>(t) = k.variables[input];
    t.values = {k.values[input]};
    t.rate_value = k.rates[input];
    t.second_rate_value = k.second_rates[input];
  }
  return input;
}

// The chain's points (with the terms of their velocities and accelerations) and frames.
void add_chain_observables(ConstraintSystem& system, const Mechanism& mechanism, const SpatialKinematics& k) {
  for (const ChainPointMotion& p : k.points) {
    PointObservable point;
    point.name = p.name;
    for (const auto& spot : mechanism.chain->points)
      if (spot.name == p.name) point.where = spot.where;
    point.components = {"x", "y", "z"};
    const auto list = [](const Vector3& v) { return std::vector<ex>(v.begin(), v.end()); };
    point.position = list(p.position);
    RelativeMotionTerms terms;
    terms.frame = p.frame;
    Vector3 origin{0, 0, 0};
    for (const ChainFrameMotion& f : k.frames)
      if (f.name == p.frame) origin = f.origin;
    terms.relative_position = {p.position[0] - origin[0], p.position[1] - origin[1], p.position[2] - origin[2]};
    terms.frame_velocity = list(p.frame_velocity);
    terms.transport = list(p.transport);
    terms.relative_velocity = list(p.relative_velocity);
    terms.frame_acceleration = list(p.frame_acceleration);
    terms.tangential = list(p.tangential);
    terms.centripetal = list(p.centripetal);
    terms.coriolis = list(p.coriolis);
    terms.relative_acceleration = list(p.relative_acceleration);
    point.terms = terms;
    system.points.push_back(point);
  }
  for (const ChainFrameMotion& f : k.frames) {
    FrameObservable frame;
    frame.name = f.name;
    frame.parent = f.parent;
    for (const auto& source : mechanism.chain->frames)
      if (source.name == f.name) {
        frame.where = source.where;
        frame.joint = source.joint;
      }
    frame.origin.assign(f.origin.begin(), f.origin.end());
    for (unsigned r = 0; r < 3; ++r)
      for (unsigned c = 0; c < 3; ++c) frame.rotation.push_back(f.rotation(r, c));
    frame.angular_velocity.assign(f.angular_velocity.begin(), f.angular_velocity.end());
    frame.angular_velocity_terms = f.angular_velocity_terms;
    frame.angular_acceleration.assign(f.angular_acceleration.begin(), f.angular_acceleration.end());
    system.frames.push_back(frame);
  }
}

}  // namespace

ConstraintSystem build_spatial_system(const Mechanism& mechanism) {
  const SpatialKinematics k = build_spatial_chain(mechanism);
  ConstraintSystem system;
  system.title = mechanism.title;
  system.description = mechanism.description;
  system.source_file = mechanism.source_file;
  system.output = mechanism.output;
  system.parameters = k.parameters;
  for (SystemParameter& p : system.parameters) p.sets_length_scale = p.dimension == Dimension::length && !p.formula;
  system.length_scale = length_scale_of(system.parameters);
  const std::size_t input = set_chain_input(system, mechanism, k);
  Driver& t = system.input;
  const auto parameter = [&](const std::string& name, double value, Dimension dimension, const SourceLocation& where) {
    SystemParameter p;
    p.symbol = GiNaC::realsymbol(name, latex_symbol_name(name));
    p.value = value;
    p.dimension = dimension;
    p.text = format_round_trip(value);
    p.where = where;
    p.written = false;  // the variable's motion at the instant, as the file gives it
    system.parameters.push_back(p);
    return p.symbol;
  };
  // The time since the instant: t itself, or for a variable as the input the time at
  // which it reaches its value at its rate of the file, tau = (theta - theta_0) / omega_0.
  ex tau = t.symbol;
  if (input < k.variables.size()) {
    bool followers = false;
    for (std::size_t i = 0; i < k.variables.size(); ++i) followers = followers || (i != input && !k.unknown[i]);
    tau = 0;
    if (followers && k.rates[input] != 0) {
      const Coordinate& q = k.variables[input];
      tau = (t.symbol - parameter(q.name + "_0", k.values[input], q.dimension, q.where)) /
            parameter(q.rate.get_name() + "_0", k.rates[input], Dimension::number, q.where);
    }
  }
  if (input < k.variables.size() && k.rates[input] != 0) {
    t.follower_origin = k.values[input];
    t.follower_scale = k.rates[input];
  }
  for (std::size_t i = 0; i < k.variables.size(); ++i) {
    if (i == input || k.unknown[i] || k.variables[i].dimension != Dimension::angle) continue;
    if (input < k.variables.size() && k.rates[input] == 0) continue;  // nothing moves with a still input
    t.followers.push_back({k.variables[i].name, k.values[i], k.rates[i], k.second_rates[i]});
  }
  for (std::size_t i = 0; i < k.variables.size(); ++i) {
    if (i == input) continue;
    Coordinate q = k.variables[i];
    q.guess = k.values[i];
    if (k.unknown[i]) {  // found by a closure
      system.unknowns.push_back(q);
      continue;
    }
    const ex start = parameter(q.name + "_0", k.values[i], q.dimension, q.where);
    const ex rate = parameter(q.rate.get_name() + "_0", k.rates[i], Dimension::number, q.where);
    const ex second = parameter(q.second_rate.get_name() + "_0", k.second_rates[i], Dimension::number, q.where);
    EquationGroup group;
    group.kind = "motion";
    group.name = q.name;
    group.where = q.where;
    group.equations = {system.equations.size()};
    system.groups.push_back(group);
    Equation e;
    // Times the length scale: a length, like a closure's row (the solvers scale by lengths).
    e.expression = system.length_scale * (q.symbol - (start + rate * tau + second * GiNaC::pow(tau, 2) / 2));
    e.group = system.groups.size() - 1;
    e.component = "value";
    system.equations.push_back(e);
    system.unknowns.push_back(q);
  }
  for (const auto& [name, residual] : k.closures) {
    EquationGroup group;
    group.kind = "closure";
    group.name = name;
    for (const ChainClosure& c : mechanism.chain->closures)
      if (c.name == name) {
        group.where = c.where;
        group.between = {c.from, c.to};
      }
    group.equations = {system.equations.size()};
    system.groups.push_back(group);
    Equation e;
    e.expression = residual;
    e.group = system.groups.size() - 1;
    e.component = "distance";
    system.equations.push_back(e);
  }
  add_chain_observables(system, mechanism, k);
  return system;
}

}  // namespace kinema
