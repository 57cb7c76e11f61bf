// What a view needs to solve the mechanism again for other dimensions, as the web page's
// sliders do: the model's compiled tape (parameters are among its inputs, so new
// dimensions need no derivation), the parameters that can be moved and the formulas of
// those that follow them (compiled to a tape of their own), and the solver's rules
// (engine/numeric/solver.hpp). The page runs both tapes with a runner generated from the
// one op table and follows the sweep's Newton continuation.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/analysis/slider_ranges.hpp"
#include "engine/model.hpp"

namespace kinema {

struct Resolving {
  const CompiledExpressions* tape = nullptr;  ///< The model's.
  TapeLayout layout;
  struct Parameter {
    std::string name;
    double value = 0;  ///< SI.
    Dimension dimension = Dimension::number;
    bool slider = false;             ///< Written with a value (not a formula), a length or an angle.
    bool sets_length_scale = false;  ///< Counted in the length scale (ConstraintSystem::length_scale).
    SliderRange range;               ///< A slider's, where resolving() is given the rows (else NaN).
  };
  std::vector<Parameter> parameters;
  /// Inputs: the parameters in order; output k: the value of parameter formula_targets[k],
  /// written as a formula of earlier ones (those formulas put in, so each reads only values).
  CompiledExpressions formulas;
  std::vector<std::size_t> formula_targets;
  std::vector<double> guess;            ///< The file's guesses (SI): the branch a run starts on.
  double guess_input = 0;               ///< Kinematics::guess_input: the value the guesses stand for.
  bool periodic_input = false;          ///< Kinematics::periodic_input.
  std::vector<bool> length_unknowns;    ///< Column scaled by the length scale (else 1).
  double rate = 0, second_rate = 0;     ///< The input's (SI).
  double max_step = 0;                  ///< Kinematics::max_continuation_step at the file's dimensions.
  bool max_step_follows_length = false; ///< A length input: the step is 1 % of the length scale.
  /// The solver's constants by name (solver.hpp), as the page's Newton uses them.
  std::vector<std::pair<std::string, double>> constants;
};

/// Nullopt where the page cannot solve again: a model whose tape has no drawing stage,
/// parameter formulas the tape cannot take, or a joints-and-links file with a parameter
/// kinema took from its sketch. A joints-and-links file is solved by Newton from its
/// guesses; its joints, blocks, guides and extra columns are the drawing stage's
/// (TapeLayout::linkage_joint_output on); a spatial chain's frames are placed by the
/// drawing stage (TapeLayout::frame_placement_output). Given the page's rows, each
/// slider's range over their input values (slider_ranges).
std::optional<Resolving> resolving(const Model& model, const MotionTable* rows = nullptr);

}  // namespace kinema
