// The compiled model of one constraint system: the derivation compiled into
// one staged register tape (built once, immutable) and what the solvers need
// to know about the system (scales, guesses, which equation belongs to which
// group). Workspace and BatchWorkspace hold the buffers of one caller.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/tape.hpp"
#include "engine/numeric/tape_layout.hpp"
#include "engine/symbolic/derivation.hpp"

namespace kinema {

class Kinematics {
 public:
  Kinematics() = default;
  Kinematics(const ConstraintSystem& system, const Derivation& derivation);
  /// The same tape (shared, not copied) for `system`, this one's system with other
  /// parameter values: its parameters, scales and guesses read from `system`.
  Kinematics sharing_tape(const ConstraintSystem& system) const;
  /// Other parameter values (SI, one per parameter of the system, formula parameters
  /// already following theirs) in place, with the length scale and what follows from it
  /// as sharing_tape would set them from a system holding those values: what a design
  /// study changes per design without copying a system. A workspace built on this object
  /// sees them after its reload_parameters().
  void set_parameter_values(const double* values);

  std::size_t unknown_count() const { return layout_.unknown_count; }
  std::size_t point_count() const { return layout_.point_dimensions.size(); }
  std::size_t frame_count() const { return layout_.frame_count; }
  const TapeLayout& layout() const { return layout_; }
  /// One tape for position, acceleration and points (stages as in TapeLayout):
  /// sin/cos and every other subexpression computed once per input value.
  const CompiledExpressions& evaluator() const { return *evaluator_; }
  const std::vector<double>& parameter_values() const { return parameter_values_; }
  /// The drawing stage's outputs (TapeLayout::link_vector_output, frame_placement_output)
  /// at a state whose position is known: rates NaN where the state has none. Empty for a
  /// state of another system, and where the drawing formulas could not be compiled.
  std::vector<double> drawing_values(const MotionState& state) const;
  /// The drawing formulas compiled onto the tape (a formula the tape cannot take leaves none).
  bool drawable() const { return drawable_; }
  /// The compiled derivatives of the solved values in parameter `parameter`
  /// (engine/numeric/sensitivity): `compile`d the first time any model sharing this tape
  /// asks (with_parameters' copies too), then reused; the tape takes the parameters as
  /// inputs. They depend on which parameters follow formulas (`follows_formula`, one per
  /// parameter: with_parameters drops the formula of a parameter it is given). Thread-safe.
  std::shared_ptr<const CompiledExpressions> parameter_tape(
      std::size_t parameter, const std::vector<bool>& follows_formula,
      const std::function<std::shared_ptr<const CompiledExpressions>()>& compile) const;

  /// Typical length (largest length parameter), for tolerances and scaling.
  double length_scale() const { return length_scale_; }
  /// Scale of each column of Phi_q: the length scale for length unknowns (their
  /// columns are unitless), 1 for angles (their columns are lengths).
  const std::vector<double>& column_scale() const { return column_scale_; }
  /// Largest input step continuation takes at once (2 deg, or 1 % of the length scale).
  double max_continuation_step() const { return max_continuation_step_; }
  /// Starting guesses from the file, SI.
  const Eigen::VectorXd& guess() const { return guess_; }
  /// The input value the guesses stand for (SI): a joints file's sketch value, else the
  /// file's first input value (0 where it gives none). The file's assembly is the one the
  /// guesses give there, carried along the input (engine/numeric/sweep).
  double guess_input() const { return guess_input_; }
  /// An angle input on which the equations depend only through its sine and cosine: a
  /// value and that value plus a turn are the same position, reached the short way round.
  bool periodic_input() const { return periodic_input_; }
  /// The equation group of each row of Phi (for "which loop stays open").
  std::size_t equation_group(std::size_t row) const { return equation_group_[row]; }
  /// A joints-and-links mechanism whose every link is in a dyad: its positions in
  /// closed form (engine/numeric/dyad_positions), else nullptr (Newton alone).
  const SolvingPlan* closed_form() const { return closed_form_ ? &*closed_form_ : nullptr; }

 private:
  /// The layout, scales and guesses; no tape yet.
  explicit Kinematics(const ConstraintSystem& system);
  /// The tape: the solving stages, then the drawing stage apart (TapeLayout::kDrawingStage).
  void compile(const ConstraintSystem& system, const std::vector<std::vector<GiNaC::ex>>& solving,
               const Derivation& derivation);
  TapeLayout layout_;
  /// Shared by the models that differ only in parameter values (with_parameters).
  std::shared_ptr<const CompiledExpressions> evaluator_ = std::make_shared<const CompiledExpressions>();
  struct ParameterTapes;
  std::shared_ptr<ParameterTapes> parameter_tapes_;  ///< Shared as evaluator_ is.
  std::vector<double> parameter_values_;
  std::vector<bool> sets_length_scale_;  ///< Per parameter: counted in the length scale (length_scale_of).
  std::vector<bool> length_unknown_;     ///< Per unknown: a length (its column scaled by the length scale).
  bool length_input_ = false;            ///< The input is a length (its continuation step follows the scale).
  bool periodic_input_ = false;
  double guess_input_ = 0.0;
  double length_scale_ = 1.0, max_continuation_step_ = 0.0;
  std::vector<double> column_scale_;
  Eigen::VectorXd guess_;
  std::vector<std::size_t> equation_group_;
  std::optional<SolvingPlan> closed_form_;
  bool drawable_ = true;  ///< The drawing stage compiled.
};

}  // namespace kinema
