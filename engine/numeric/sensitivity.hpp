// Exact sensitivities evaluated: the derivatives of a model's solved values in one of
// its parameters (engine/symbolic/parameter_derivatives), compiled into a tape of their
// own on demand (only for the parameters asked) and solved at each solved state with
// the solver's LU of Phi_q. A joints file solved in closed form has the same equations:
// its sensitivities are those of its solved state.
#pragma once

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/tape.hpp"
#include "engine/numeric/workspace.hpp"
#include "engine/symbolic/derivation.hpp"

namespace kinema {

/// One parameter's derivatives of a model's solved values, derived and compiled once for
/// every model that shares the tape (Kinematics::parameter_tape)
/// (immutable: threads share it, each with its SensitivityWorkspace). It holds the
/// model's compiled evaluator by reference: the model must outlive it.
class ParameterSensitivity {
 public:
  /// For the parameter the file writes as `name` (of the model made of these three);
  /// InputError naming it (and the file's parameters) for a name the file does not write,
  /// and for a joints file whose lengths kinema took from its sketch (what with_parameters
  /// refuses: those follow no parameter).
  ParameterSensitivity(const ConstraintSystem& system, const Derivation& derivation, const Kinematics& kinematics,
                       const std::string& name);
  const Kinematics& kinematics() const { return *kinematics_; }
  std::size_t parameter() const { return parameter_; }  ///< Index into the system's parameters.
  const CompiledExpressions& tape() const { return *tape_; }

 private:
  const Kinematics* kinematics_;
  std::size_t parameter_;
  std::shared_ptr<const CompiledExpressions> tape_;
};

/// The derivatives at one state (SI, per SI unit of the parameter): of q, qd, qdd, and
/// of each output of the model's point stage in its order (TapeLayout: points' positions,
/// velocities, accelerations; frames' angular velocities and accelerations).
struct StateDerivatives {
  Eigen::VectorXd q, qd, qdd;
  std::vector<double> observables;
};

/// The buffers of one caller (one thread) of a ParameterSensitivity.
class SensitivityWorkspace {
 public:
  explicit SensitivityWorkspace(const ParameterSensitivity& sensitivity);
  /// At row `row` of a table of the model; false unless the row is ok (Phi_q regular there).
  bool at(const MotionTable& table, std::size_t row, StateDerivatives& out);

 private:
  bool solve(std::size_t stage, Eigen::VectorXd& derivative, std::size_t first_register);
  const ParameterSensitivity& sensitivity_;
  Workspace solver_;  ///< The model's: its LU of Phi_q.
  std::vector<double> registers_, stage_out_;
  Eigen::VectorXd q_;
  double input_ = 0;
};

}  // namespace kinema
