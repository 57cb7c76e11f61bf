#include "engine/symbolic/parameter_derivatives.hpp"

#include <string>

namespace kinema {

using GiNaC::ex;

namespace {

// What a stage differentiates through: q always (dq/dp is solved first), qd and qdd once
// their derivatives are known (the stage that solves one leaves it out).
enum class Through { parameters, q, q_and_rates, everything };

class Differentiator {
 public:
  Differentiator(const ConstraintSystem& system, std::size_t parameter) : system_(system) {
    for (const Coordinate& q : system.unknowns) {
      dq_.push_back(GiNaC::realsymbol("d" + q.symbol.get_name()));
      dqd_.push_back(GiNaC::realsymbol("d" + q.rate.get_name()));
      dqdd_.push_back(GiNaC::realsymbol("d" + q.second_rate.get_name()));
    }
    // d p_k / d p: 1 for p itself, the chain rule through the formula of each parameter
    // that follows it (a formula reads only earlier parameters), 0 for the rest.
    rates_.assign(system.parameters.size(), 0);
    rates_[parameter] = 1;
    for (std::size_t k = parameter + 1; k < system.parameters.size(); ++k) {
      const SystemParameter& p = system.parameters[k];
      if (!p.formula) continue;
      ex rate = 0;
      for (std::size_t m = parameter; m < k; ++m)
        if (!rates_[m].is_zero()) rate += p.formula->diff(system.parameters[m].symbol) * rates_[m];
      rates_[k] = rate;
    }
  }

  // The derivative of e in the parameter along the solution, through what `through` says.
  ex along(const ex& e, Through through) const {
    ex sum = 0;
    for (std::size_t k = 0; k < rates_.size(); ++k)
      if (!rates_[k].is_zero()) sum += e.diff(system_.parameters[k].symbol) * rates_[k];
    for (std::size_t j = 0; j < dq_.size() && through != Through::parameters; ++j) {
      const Coordinate& q = system_.unknowns[j];
      sum += e.diff(q.symbol) * dq_[j];
      if (through == Through::q) continue;
      sum += e.diff(q.rate) * dqd_[j];
      if (through == Through::everything) sum += e.diff(q.second_rate) * dqdd_[j];
    }
    return sum;
  }

  std::vector<ex> inputs() const {
    std::vector<ex> inputs;
    for (const SystemParameter& p : system_.parameters) inputs.push_back(p.symbol);
    inputs.insert(inputs.end(), {system_.input.symbol, system_.input.rate, system_.input.second_rate});
    for (const Coordinate& q : system_.unknowns) inputs.push_back(q.symbol);
    for (const Coordinate& q : system_.unknowns) inputs.push_back(q.rate);
    for (const Coordinate& q : system_.unknowns) inputs.push_back(q.second_rate);
    for (const auto* list : {&dq_, &dqd_, &dqdd_}) inputs.insert(inputs.end(), list->begin(), list->end());
    return inputs;
  }

 private:
  const ConstraintSystem& system_;
  std::vector<ex> dq_, dqd_, dqdd_;
  std::vector<ex> rates_;
};

}  // namespace

ParameterDerivatives parameter_derivatives(const ConstraintSystem& system, const Derivation& d,
                                           std::size_t parameter) {
  const Differentiator differentiate(system, parameter);
  ParameterDerivatives result;
  result.inputs = differentiate.inputs();
  result.stages.resize(4);
  const std::size_t n = system.unknowns.size();
  for (std::size_t i = 0; i < n; ++i) {
    // V and A as the solver solves them (Phi_q qd = -Phi_theta thetad, Phi_q qdd = gamma).
    ex velocity = d.input_jacobian(i, 0) * system.input.rate, acceleration = -d.acceleration_rhs[i];
    for (std::size_t j = 0; j < n; ++j) {
      velocity += d.jacobian(i, j) * system.unknowns[j].rate;
      acceleration += d.jacobian(i, j) * system.unknowns[j].second_rate;
    }
    result.stages[ParameterDerivatives::kPositionStage].push_back(
        differentiate.along(system.equations[i].expression, Through::parameters));
    result.stages[ParameterDerivatives::kVelocityStage].push_back(differentiate.along(velocity, Through::q));
    result.stages[ParameterDerivatives::kAccelerationStage].push_back(
        differentiate.along(acceleration, Through::q_and_rates));
  }
  // The point stage's outputs in its order (Kinematics' constructor).
  std::vector<ex>& observables = result.stages[ParameterDerivatives::kObservableStage];
  const auto add = [&](const std::vector<ex>& parts) {
    for (const ex& e : parts) observables.push_back(differentiate.along(e, Through::everything));
  };
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    add(system.points[p].position);
    add(d.points[p].velocity);
    add(d.points[p].acceleration);
  }
  for (const FrameObservable& frame : system.frames) {
    add(frame.angular_velocity);
    add(frame.angular_acceleration);
  }
  return result;
}

}  // namespace kinema
