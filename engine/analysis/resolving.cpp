#include "engine/analysis/resolving.hpp"

#include "engine/numeric/solver.hpp"

namespace kinema {

namespace {

// Each formula parameter's formula with the earlier formulas put in: a function of the
// parameters given values alone, as reading the file computes it in order.
void compile_formulas(const ConstraintSystem& system, Resolving& out) {
  std::vector<GiNaC::ex> inputs, outputs;
  GiNaC::exmap earlier;
  for (std::size_t p = 0; p < system.parameters.size(); ++p) {
    const SystemParameter& parameter = system.parameters[p];
    inputs.push_back(parameter.symbol);
    if (!parameter.formula) continue;
    const GiNaC::ex value = parameter.formula->subs(earlier);
    earlier[parameter.symbol] = value;
    outputs.push_back(value);
    out.formula_targets.push_back(p);
  }
  out.formulas = CompiledExpressions(inputs, outputs);
}

}  // namespace

std::optional<Resolving> resolving(const Model& model, const MotionTable* rows) {
  const ConstraintSystem& system = model.system;
  const Kinematics& k = model.kinematics;
  // Drawn from the drawing stage: a planar system's link vectors, a chain's frames.
  const bool drawn = system.frames.empty() ? k.layout().link_vector_count > 0 : k.drawable();
  if (!drawn) return std::nullopt;
  if (system.plan) {
    // Joints and links: solved by Newton from the file's guesses (as with_parameters does),
    // drawn and their extra columns computed from the drawing stage. Not where kinema took
    // a parameter from the sketch: that one follows the dimensions only through the sketch.
    if (k.layout().linkage_joint_count == 0) return std::nullopt;
    for (const SystemParameter& p : system.parameters)
      if (!p.written) return std::nullopt;
  }
  Resolving out;
  out.tape = &k.evaluator();
  out.layout = k.layout();
  for (const SystemParameter& p : system.parameters) {
    const bool dimensioned = p.dimension == Dimension::length || p.dimension == Dimension::angle;
    out.parameters.push_back({p.symbol.get_name(), p.value, p.dimension, p.written && !p.formula && dimensioned,
                              p.sets_length_scale, {}});
  }
  try {
    compile_formulas(system, out);
  } catch (const std::exception&) {
    return std::nullopt;  // a formula the tape cannot take: no sliders
  }
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    out.guess.push_back(k.guess()[Eigen::Index(i)]);
    out.length_unknowns.push_back(system.unknowns[i].dimension == Dimension::length);
  }
  out.guess_input = k.guess_input();
  out.periodic_input = k.periodic_input();
  out.rate = system.input.rate_value;
  out.second_rate = system.input.second_rate_value;
  out.max_step = k.max_continuation_step();
  out.max_step_follows_length = system.input.dimension == Dimension::length;
  out.constants = {{"newton_tolerance", solver::kNewtonTolerance},
                   {"rounding_tolerance", solver::kRoundingTolerance},
                   {"newton_iterations", solver::kNewtonIterations},
                   {"step_halvings", solver::kStepHalvings},
                   {"least_squares_pivot_ratio", solver::kLeastSquaresPivotRatio},
                   {"max_continuation_steps", solver::kMaxContinuationSteps},
                   {"branch_tolerance", solver::kBranchTolerance},
                   {"step_correction", solver::kStepCorrection},
                   {"least_step", solver::kLeastStep},
                   {"crossing_width", solver::kCrossingWidth},
                   {"crossing_residual", solver::kCrossingResidual},
                   {"crossing_jump", solver::kCrossingJump},
                   {"most_entry_steps", solver::kMostEntrySteps},
                   {"home_search_steps", solver::kHomeSearchSteps},
                   {"clearly_regular_pivot_ratio", solver::kClearlyRegularPivotRatio},
                   {"singular_threshold", solver::kSingularThreshold},
                   {"jacobi_sweeps", solver::kJacobiSweeps},
                   {"jacobi_tolerance", solver::kJacobiTolerance},
                   {"epsilon", solver::kEpsilon}};
  if (rows) {
    const std::vector<SliderRange> ranges = slider_ranges(model, out, *rows);
    for (std::size_t p = 0; p < ranges.size(); ++p) out.parameters[p].range = ranges[p];
  }
  return out;
}

}  // namespace kinema
