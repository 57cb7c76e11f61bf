#include "engine/numeric/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "engine/constraints/complex_parts.hpp"
#include "engine/constraints/output_columns.hpp"
#include "engine/symbolic/centre_formulas.hpp"
#include "engine/base/units.hpp"
#include "engine/numeric/workspace.hpp"

namespace kinema {

using GiNaC::ex;

namespace {

static_assert(TapeLayout::kVectorPartCount == kLinkVectorParts, "the drawing stage holds every part of a link vector");

// The drawing stage's formulas, as TapeLayout places them.
std::vector<ex> drawing_stage(const ConstraintSystem& system, const PlanarLinkVectors& link_vectors) {
  std::vector<ex> outputs;
  const auto complex = [&](const ex& z) {
    outputs.push_back(real_part_of(z));
    outputs.push_back(imag_part_of(z));
  };
  for (const LinkVectorMotion& m : link_vectors.vectors) {
    complex(m.term);
    for (const ex& part : m.parts) complex(part);
    for (const ex& magnitude : m.magnitudes) outputs.push_back(magnitude.expand());
    complex(m.guide ? *m.guide : ex(0));
    complex(m.angle_rate);  // how fast its link turns (instant centres): complex where the angle is
  }
  for (const FrameObservable& frame : system.frames) {
    outputs.insert(outputs.end(), frame.origin.begin(), frame.origin.end());
    outputs.insert(outputs.end(), frame.rotation.begin(), frame.rotation.end());
  }
  return outputs;
}

// A body's angle, rate and second rate as formulas (output_scale.cpp's turning): ground's
// 0, an unknown's or the driver's its symbols, a slider block its guide's plus its offset.
struct Turning {
  ex angle, rate, second_rate;
};
Turning turning(const ConstraintSystem& system, std::size_t body) {
  const SolvingPlan& plan = *system.plan;
  const SolvingPlan::Body& b = plan.bodies[body];
  if (b.unknown >= 0) {
    const Coordinate& q = system.unknowns[std::size_t(b.unknown)];
    return {q.symbol, q.rate, q.second_rate};
  }
  if (b.guide >= 0) {
    Turning t = turning(system, std::size_t(b.guide));
    t.angle += b.offset;
    return t;
  }
  if (body != 0 && body == plan.driver_body && plan.driver_slider < 0)
    return {system.input.symbol, system.input.rate, system.input.second_rate};
  return {0, 0, 0};
}

// A slider's coordinate, its rate and second rate (the driver's when it drives).
Turning travel(const ConstraintSystem& system, const SolvingPlan::Slider& slider) {
  if (slider.unknown < 0) return {system.input.symbol, system.input.rate, system.input.second_rate};
  const Coordinate& q = system.unknowns[std::size_t(slider.unknown)];
  return {q.symbol, q.rate, q.second_rate};
}

// What a joints-and-links page draws and its result columns beyond the points, as
// TapeLayout places them after the link vectors: the same formulas as linkage_drawing and
// output_scale.cpp's linkage_values, written on the tape so that a page solving for other
// dimensions computes them. `points` is the point stage (each point's position, velocity,
// acceleration). Empty for anything else.
std::vector<ex> linkage_stage(const ConstraintSystem& system, const std::vector<ex>& points, TapeLayout& layout) {
  std::vector<ex> outputs;
  if (!system.plan || !system.frames.empty()) return outputs;
  const SolvingPlan& plan = *system.plan;
  const ex I = GiNaC::I;
  const auto point_named = [&](const std::string& name) -> int {
    for (std::size_t p = 0; p < system.points.size(); ++p)
      if (system.points[p].name == name) return int(p);
    return -1;
  };
  const auto point_at = [&](int p) { return system.points[std::size_t(p)].position[0] + I * system.points[std::size_t(p)].position[1]; };
  // Each joint where it is: a moving joint is its point; a slider shown at a pin of its
  // block (no point of its own) is that pin's; a ground joint its formula.
  std::vector<ex> joints;
  for (std::size_t j = 0; j < plan.joints.size(); ++j) {
    ex at;
    bool found = false;
    for (const auto& [name, where] : system.ground_joints)
      if (name == plan.joints[j].name) { at = where; found = true; }
    if (!found && point_named(plan.joints[j].name) >= 0) { at = point_at(point_named(plan.joints[j].name)); found = true; }
    for (std::size_t b = 1; !found && b < plan.bodies.size(); ++b) {
      std::complex<double> mine;
      bool on = false;
      for (const auto& [joint, v] : plan.bodies[b].points) if (joint == j) { mine = v; on = true; }
      for (const auto& [joint, v] : plan.bodies[b].points) {
        if (!on || found || joint == j || std::abs(v - mine) > 1e-12 || point_named(plan.joints[joint].name) < 0) continue;
        at = point_at(point_named(plan.joints[joint].name));
        found = true;
      }
    }
    if (!found) throw std::logic_error("linkage_stage: joint " + plan.joints[j].name + " has no formula");
    joints.push_back(at);
    outputs.push_back(real_part_of(at));
    outputs.push_back(imag_part_of(at));
  }
  layout.linkage_joint_count = plan.joints.size();
  layout.linkage_block_count = 0;
  for (std::size_t b = 1; b < plan.bodies.size(); ++b) {
    if (plan.bodies[b].guide < 0) continue;
    outputs.push_back(turning(system, b).angle);
    ++layout.linkage_block_count;
  }
  layout.linkage_guide_count = 0;
  for (const SolvingPlan::Slider& s : plan.sliders) {
    if (s.guide != 0) continue;
    // Its point where the coordinate is 0: the slider joint less its travel along the line.
    const ex along = ex(std::cos(s.direction)) + I * ex(std::sin(s.direction));
    const ex through = joints[s.joint] - travel(system, s).angle * along;
    outputs.push_back(real_part_of(through));
    outputs.push_back(imag_part_of(through));
    outputs.push_back(std::cos(s.direction));
    outputs.push_back(std::sin(s.direction));
    ++layout.linkage_guide_count;
  }
  // The result columns (output_scale.cpp linkage_values), SI.
  const std::size_t first = outputs.size();
  for (std::size_t b = 1; b < plan.bodies.size(); ++b) {
    if (plan.bodies[b].guide < 0) continue;
    const Turning t = turning(system, b);
    outputs.insert(outputs.end(), {t.angle, t.rate, t.second_rate});
  }
  struct Sliding {
    ex relative_velocity, relative_acceleration, coriolis;
  };
  const auto sliding = [&](const SolvingPlan::Slider& slider) {
    const Turning guide = turning(system, slider.guide), s = travel(system, slider);
    const ex u = GiNaC::exp(I * (guide.angle + slider.direction));
    return Sliding{s.rate * u, s.second_rate * u, 2 * guide.rate * I * s.rate * u};
  };
  const auto complex = [&](const ex& z) {
    outputs.push_back(real_part_of(z));
    outputs.push_back(imag_part_of(z));
  };
  for (const SolvingPlan::Slider& slider : plan.sliders) {
    const Sliding s = sliding(slider);
    for (const ex& c : {s.relative_velocity, s.relative_acceleration, s.coriolis}) complex(c);
  }
  for (const GuidePoint& g : guide_points(system)) {
    const Sliding s = sliding(plan.sliders[g.slider]);
    const std::size_t at = layout.point_output(g.point), d = layout.point_dimensions[g.point];
    complex(points[at + d] + I * points[at + d + 1] - s.relative_velocity);
    complex(points[at + 2 * d] + I * points[at + 2 * d + 1] - s.relative_acceleration - s.coriolis);
  }
  for (const RelativeTurning& r : relative_turnings(system)) {
    const Turning block = turning(system, r.block), other = turning(system, r.other);
    outputs.push_back(block.rate - other.rate);
    outputs.push_back(block.second_rate - other.second_rate);
  }
  layout.linkage_column_count = outputs.size() - first;
  return outputs;
}

}  // namespace

namespace {

// Phi, Phi_q and Phi_theta the same a turn on, at a few positions (the guesses moved):
// the input enters only through its sine and cosine.
bool position_periodic(const Kinematics& k) {
  Workspace workspace(k);
  Eigen::VectorXd phi[2], phi_theta[2];
  Eigen::MatrixXd phi_q[2];
  for (const double input : {0.3, 1.9, -2.6}) {
    Eigen::VectorXd q = k.guess();
    for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += 0.01 * double(i + 1) * input * k.column_scale()[std::size_t(i)];
    for (int turn = 0; turn < 2; ++turn) workspace.position_system(input + 2 * turn * kPi, q, phi[turn], phi_q[turn], phi_theta[turn]);
    const double tolerance = 1e-9 * k.length_scale();
    if (!phi[0].allFinite() || !phi_q[0].allFinite()) continue;
    if (!((phi[0] - phi[1]).lpNorm<Eigen::Infinity>() <= tolerance) ||
        !((phi_q[0] - phi_q[1]).lpNorm<Eigen::Infinity>() <= tolerance) ||
        !((phi_theta[0] - phi_theta[1]).lpNorm<Eigen::Infinity>() <= tolerance))
      return false;
  }
  return true;
}

}  // namespace

struct Kinematics::ParameterTapes {
  std::mutex mutex;
  std::map<std::pair<std::size_t, std::vector<bool>>, std::shared_ptr<const CompiledExpressions>> tapes;
};

Kinematics::Kinematics(const ConstraintSystem& system)
    : parameter_tapes_(std::make_shared<ParameterTapes>()), length_scale_(system.length_scale) {
  const std::size_t n = system.unknowns.size();
  layout_.parameter_count = system.parameters.size();
  layout_.unknown_count = n;
  for (const PointObservable& point : system.points) layout_.point_dimensions.push_back(point.position.size());
  layout_.frame_count = system.frames.size();
  for (const SystemParameter& parameter : system.parameters) {
    parameter_values_.push_back(parameter.value);
    sets_length_scale_.push_back(parameter.sets_length_scale);
  }
  length_input_ = system.input.dimension == Dimension::length;
  max_continuation_step_ = system.input.dimension == Dimension::angle  ? from_degrees(2.0)
                           : system.input.dimension == Dimension::time ? 0.01
                                                                       : 0.01 * length_scale_;
  guess_.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const Coordinate& q = system.unknowns[i];
    guess_[static_cast<Eigen::Index>(i)] = q.guess;
    column_scale_.push_back(q.dimension == Dimension::length ? length_scale_ : 1.0);
    length_unknown_.push_back(q.dimension == Dimension::length);
  }
  for (const Equation& equation : system.equations) equation_group_.push_back(equation.group);
  if (system.plan && system.plan->closed_form) closed_form_ = *system.plan;
  guess_input_ = system.plan ? system.plan->sketch_input : system.input.values.empty() ? 0.0 : system.input.values[0];
}

Kinematics::Kinematics(const ConstraintSystem& system, const Derivation& d) : Kinematics(system) {
  const std::size_t n = system.unknowns.size();
  std::vector<ex> position(layout_.position_output_count());
  for (std::size_t i = 0; i < n; ++i) {
    position[layout_.phi(i)] = system.equations[i].expression;
    for (std::size_t j = 0; j < n; ++j) position[layout_.phi_q(i, j)] = d.jacobian(i, j);
    position[layout_.phi_theta(i)] = d.input_jacobian(i, 0);
  }
  std::vector<ex> points;
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    for (const auto* part : {&system.points[p].position, &d.points[p].velocity, &d.points[p].acceleration})
      points.insert(points.end(), part->begin(), part->end());
  }
  for (const FrameObservable& frame : system.frames) {
    points.insert(points.end(), frame.angular_velocity.begin(), frame.angular_velocity.end());
    points.insert(points.end(), frame.angular_acceleration.begin(), frame.angular_acceleration.end());
  }
  compile(system, {position, d.acceleration_rhs, points}, d);
  periodic_input_ = system.input.dimension == Dimension::angle && (closed_form_ || position_periodic(*this));
}

Kinematics Kinematics::sharing_tape(const ConstraintSystem& system) const {
  Kinematics k(system);
  k.layout_.link_vector_count = layout_.link_vector_count;
  k.layout_.linkage_joint_count = layout_.linkage_joint_count;
  k.layout_.linkage_block_count = layout_.linkage_block_count;
  k.layout_.linkage_guide_count = layout_.linkage_guide_count;
  k.layout_.linkage_column_count = layout_.linkage_column_count;
  k.layout_.centre_bodies = layout_.centre_bodies;
  k.evaluator_ = evaluator_;
  k.parameter_tapes_ = parameter_tapes_;
  k.drawable_ = drawable_;
  k.periodic_input_ = periodic_input_;
  return k;
}

std::shared_ptr<const CompiledExpressions> Kinematics::parameter_tape(
    std::size_t parameter, const std::vector<bool>& follows_formula,
    const std::function<std::shared_ptr<const CompiledExpressions>()>& compile) const {
  if (!parameter_tapes_) return compile();  // a default-constructed Kinematics: nothing to share
  // Held while compiling: the derivation is GiNaC's, which is not thread-safe.
  const std::lock_guard<std::mutex> held(parameter_tapes_->mutex);
  std::shared_ptr<const CompiledExpressions>& tape = parameter_tapes_->tapes[{parameter, follows_formula}];
  if (!tape) tape = compile();
  return tape;
}

void Kinematics::set_parameter_values(const double* values) {
  std::copy(values, values + parameter_values_.size(), parameter_values_.begin());
  // length_scale_of's rule, on the values alone.
  double largest = 0;
  for (std::size_t p = 0; p < parameter_values_.size(); ++p)
    if (sets_length_scale_[p]) largest = std::max(largest, std::fabs(parameter_values_[p]));
  length_scale_ = largest > 0 ? largest : 1.0;
  if (length_input_) max_continuation_step_ = 0.01 * length_scale_;
  for (std::size_t i = 0; i < column_scale_.size(); ++i)
    if (length_unknown_[i]) column_scale_[i] = length_scale_;
}

void Kinematics::compile(const ConstraintSystem& system, const std::vector<std::vector<ex>>& solving,
                         const Derivation& derivation) {
  const PlanarLinkVectors& link_vectors = derivation.link_vectors;
  // Inputs in the order of TapeLayout.
  std::vector<ex> inputs;
  for (const SystemParameter& parameter : system.parameters) inputs.push_back(parameter.symbol);
  inputs.push_back(system.input.symbol);
  inputs.push_back(system.input.rate);
  inputs.push_back(system.input.second_rate);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.symbol);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.rate);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.second_rate);

  layout_.link_vector_count = link_vectors.vectors.size();
  try {
    std::vector<ex> drawing = drawing_stage(system, link_vectors);
    const std::vector<ex> linkage = linkage_stage(system, solving.size() > 2 ? solving[2] : std::vector<ex>{}, layout_);
    drawing.insert(drawing.end(), linkage.begin(), linkage.end());
    std::vector<ex> centres;
    try {
      centres = centre_stage(system, derivation, layout_.centre_bodies);
    } catch (const std::exception&) {
      layout_.centre_bodies.clear();  // no centres on the tape: the views show none
    }
    drawing.insert(drawing.end(), centres.begin(), centres.end());
    evaluator_ = std::make_shared<const CompiledExpressions>(inputs, layout_.input_levels(), solving, drawing);
  } catch (const std::exception&) {
    // A drawing formula the tape cannot take: the model solves as before and its views
    // draw nothing (a solving formula it cannot take throws again here).
    layout_.link_vector_count = 0;
    layout_.linkage_joint_count = layout_.linkage_block_count = layout_.linkage_guide_count = 0;
    layout_.linkage_column_count = 0;
    layout_.centre_bodies.clear();
    evaluator_ = std::make_shared<const CompiledExpressions>(inputs, layout_.input_levels(), solving,
                                                             std::vector<ex>{});
    drawable_ = false;
  }
}

std::vector<double> Kinematics::drawing_values(const MotionState& state) const {
  const std::size_t n = layout_.unknown_count;
  if (!drawable_ || static_cast<std::size_t>(state.q.size()) != n) return {};
  std::vector<double> registers = evaluator_->make_workspace();
  for (std::size_t p = 0; p < parameter_values_.size(); ++p) registers[layout_.parameter(p)] = parameter_values_[p];
  registers[layout_.input()] = state.input;
  registers[layout_.rate()] = state.input_rate;
  registers[layout_.second_rate()] = state.input_second_rate;
  const bool rates = static_cast<std::size_t>(state.qd.size()) == n && static_cast<std::size_t>(state.qdd.size()) == n;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Index j = static_cast<Eigen::Index>(i);
    registers[layout_.q(i)] = state.q[j];
    registers[layout_.qd(i)] = rates ? state.qd[j] : NAN;  // a position without rates: its rates' parts NaN
    registers[layout_.qdd(i)] = rates ? state.qdd[j] : NAN;
  }
  // The drawing stage reads the registers of the stages before it, run on the same inputs.
  std::vector<double> outputs;
  for (std::size_t stage = 0; stage < TapeLayout::kStageCount; ++stage) {
    outputs.assign(evaluator_->stage_output_count(stage), 0.0);
    evaluator_->evaluate_stage(stage, registers, outputs.data());
  }
  return outputs;
}

}  // namespace kinema
