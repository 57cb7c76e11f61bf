#include "engine/numeric/kinematics.hpp"

namespace kinema {

using GiNaC::ex;

Kinematics::Kinematics(const ConstraintSystem& system, const Derivation& d)
    : length_scale_(system.length_scale) {
  const std::size_t n = system.unknowns.size();
  layout_.parameter_count = system.parameters.size();
  layout_.unknown_count = n;
  for (const PointObservable& point : system.points) layout_.point_dimensions.push_back(point.position.size());
  layout_.frame_count = system.frames.size();
  for (const SystemParameter& parameter : system.parameters) parameter_values_.push_back(parameter.value);
  max_continuation_step_ = system.input.dimension == Dimension::angle  ? from_degrees(2.0)
                           : system.input.dimension == Dimension::time ? 0.01
                                                                       : 0.01 * length_scale_;
  guess_.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const Coordinate& q = system.unknowns[i];
    guess_[static_cast<Eigen::Index>(i)] = q.guess;
    column_scale_.push_back(q.dimension == Dimension::length ? length_scale_ : 1.0);
  }
  for (const Equation& equation : system.equations) equation_group_.push_back(equation.group);
  if (system.plan && system.plan->closed_form) closed_form_ = *system.plan;

  // Inputs in the order of TapeLayout.
  std::vector<ex> inputs;
  for (const SystemParameter& parameter : system.parameters) inputs.push_back(parameter.symbol);
  inputs.push_back(system.input.symbol);
  inputs.push_back(system.input.rate);
  inputs.push_back(system.input.second_rate);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.symbol);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.rate);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.second_rate);

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
  evaluator_ = CompiledExpressions(inputs, layout_.input_levels(), {position, d.acceleration_rhs, points});
}

}  // namespace kinema
