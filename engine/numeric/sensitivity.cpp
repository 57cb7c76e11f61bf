#include "engine/numeric/sensitivity.hpp"

#include <algorithm>
#include <stdexcept>

#include "engine/base/errors.hpp"
#include "engine/symbolic/parameter_derivatives.hpp"

namespace kinema {

namespace {

// The lengths and angles kinema took from a joints file's sketch (parameters it made) are
// constants of the file, held in a derivative as any constant is: right for a parameter
// they were not worked out from. One whose sketch places joints with the parameter (a joint
// at ["La", ...] a length is measured from) would move with it, and the derivative holding
// it would be wrong: refused, naming them.
void check_sketch_lengths(const ConstraintSystem& system, const std::string& name) {
  if (!system.plan) return;
  std::string made;
  for (const SystemParameter& p : system.parameters)
    if (!p.written && std::find(p.follows.begin(), p.follows.end(), name) != p.follows.end())
      made += (made.empty() ? "" : ", ") + p.symbol.get_name();
  if (!made.empty()) {
    throw InputError(system.source_file + ": no sensitivity in \"" + name + "\" for this joints file: kinema took " +
                     made + " from its sketch, which places joints with " + name + "; they would move with " + name +
                     " but are held as the file's constants; give them in [parameters] as formulas of " + name);
  }
}

}  // namespace

ParameterSensitivity::ParameterSensitivity(const ConstraintSystem& system, const Derivation& derivation,
                                           const Kinematics& kinematics, const std::string& name)
    : kinematics_(&kinematics), parameter_(written_parameter_index(system, name)) {
  check_sketch_lengths(system, name);
  std::vector<bool> follows_formula;
  for (const SystemParameter& p : system.parameters) follows_formula.push_back(bool(p.formula));
  tape_ = kinematics.parameter_tape(parameter_, follows_formula, [&] {
    const ParameterDerivatives derivatives = parameter_derivatives(system, derivation, parameter_);
    try {
      return std::make_shared<const CompiledExpressions>(derivatives.inputs, derivatives.stages);
    } catch (const std::invalid_argument& e) {
      throw InputError(system.source_file + ": the derivatives in \"" + name +
                       "\" cannot be evaluated: " + e.what());
    }
  });
}

SensitivityWorkspace::SensitivityWorkspace(const ParameterSensitivity& sensitivity)
    : sensitivity_(sensitivity),
      solver_(sensitivity.kinematics()),
      registers_(sensitivity.tape().make_workspace()) {
  const std::vector<double>& parameters = sensitivity.kinematics().parameter_values();
  std::copy(parameters.begin(), parameters.end(), registers_.begin());
}

// Stage `stage`'s right-hand side b solved as Phi_q x = -b into `derivative` and its
// registers (from first_register on), for the stages after it.
bool SensitivityWorkspace::solve(std::size_t stage, Eigen::VectorXd& derivative, std::size_t first_register) {
  const CompiledExpressions& tape = sensitivity_.tape();
  stage_out_.resize(tape.stage_output_count(stage));
  tape.evaluate_stage(stage, registers_, stage_out_.data());
  for (double& b : stage_out_) b = -b;
  derivative.resize(q_.size());
  if (!solver_.solve_jacobian(input_, q_, stage_out_.data(), derivative.data())) return false;
  for (Eigen::Index i = 0; i < derivative.size(); ++i) registers_[first_register + std::size_t(i)] = derivative[i];
  return true;
}

bool SensitivityWorkspace::at(const MotionTable& table, std::size_t row, StateDerivatives& out) {
  if (table.status(row) != Status::ok) return false;
  const TapeLayout& layout = sensitivity_.kinematics().layout();
  const std::size_t n = layout.unknown_count;
  input_ = table.input(row);
  q_ = table.q(row);
  registers_[layout.input()] = input_;
  registers_[layout.rate()] = table.input_rate(row);
  registers_[layout.second_rate()] = table.input_second_rate(row);
  for (std::size_t i = 0; i < n; ++i) {
    registers_[layout.q(i)] = q_[Eigen::Index(i)];
    registers_[layout.qd(i)] = table.qd(row)[Eigen::Index(i)];
    registers_[layout.qdd(i)] = table.qdd(row)[Eigen::Index(i)];
  }
  // dq/dp, dqd/dp, dqdd/dp are the tape's inputs after the model's (parameter_derivatives).
  const std::size_t dq = layout.input_register_count();
  if (!solve(ParameterDerivatives::kPositionStage, out.q, dq) ||
      !solve(ParameterDerivatives::kVelocityStage, out.qd, dq + n) ||
      !solve(ParameterDerivatives::kAccelerationStage, out.qdd, dq + 2 * n))
    return false;
  const CompiledExpressions& tape = sensitivity_.tape();
  out.observables.resize(tape.stage_output_count(ParameterDerivatives::kObservableStage));
  tape.evaluate_stage(ParameterDerivatives::kObservableStage, registers_, out.observables.data());
  return true;
}

}  // namespace kinema
