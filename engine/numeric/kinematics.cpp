#include "engine/numeric/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/constraints/complex_parts.hpp"

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

}  // namespace

Kinematics::Kinematics(const ConstraintSystem& system) : length_scale_(system.length_scale) {
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
  compile(system, {position, d.acceleration_rhs, points}, d.link_vectors);
}

Kinematics Kinematics::sharing_tape(const ConstraintSystem& system) const {
  Kinematics k(system);
  k.layout_.link_vector_count = layout_.link_vector_count;
  k.evaluator_ = evaluator_;
  k.drawable_ = drawable_;
  return k;
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
                         const PlanarLinkVectors& link_vectors) {
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
    evaluator_ = std::make_shared<const CompiledExpressions>(inputs, layout_.input_levels(), solving,
                                                             drawing_stage(system, link_vectors));
  } catch (const std::exception&) {
    // A drawing formula the tape cannot take: the model solves as before and its views
    // draw nothing (a solving formula it cannot take throws again here).
    layout_.link_vector_count = 0;
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
