// kinema as a library: load a mechanism, then solve its motion (solve_motion); what the
// views show beyond that is engine/analysis/analysis.hpp's Analysis, computed apart.
//
//   auto model = kinema::load_model("samples/four_bar.toml");
//   kinema::MotionTable table = kinema::solve_motion(model, {0.1, 0.2, 0.3});  // SI inputs
//   double omega3 = table.qd(0)[0];
//
// load_model runs the whole pipeline once: file -> Mechanism (readers/) ->
// ConstraintSystem (its front end: loops/, linkages/ or chains/) -> Derivation
// (symbolic) -> Kinematics (compiled). A Model is immutable; Workspace holds one caller's buffers.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/base/errors.hpp"
#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/numeric/workspace.hpp"
#include "engine/symbolic/derivation.hpp"
#include "readers/mechanism.hpp"

namespace kinema {

struct Model {
  ConstraintSystem system;  ///< What the file says, as equations with labels.
  Derivation derivation;    ///< Jacobians, velocity and acceleration equations, solved rates.
  Kinematics kinematics;    ///< The compiled evaluator.

  Model() = default;
  Model(Model&&) = default;
  Model& operator=(Model&&) = default;
  Model(const Model&) = delete;  // workspaces refer to the compiled evaluator
  Model& operator=(const Model&) = delete;
};

/// Reads, derives and compiles a mechanism file; throws InputError for a bad file.
/// DerivationScope::evaluation skips the formulas only printers show (about a fifth
/// of the time of a one-value run); such a model evaluates the same numbers.
Model load_model(const std::filesystem::path& path, DerivationScope scope = DerivationScope::full);
/// The same from a description already in memory (readers/mechanism_file.hpp reads one).
Model make_model(const Mechanism& mechanism, DerivationScope scope = DerivationScope::full);

/// The same mechanism with other values (SI) of parameters the file writes, as the file
/// edited to them would give, without deriving or compiling anything: the copy shares the
/// derivation's formulas and the compiled tape, which take the parameters as inputs.
/// Parameters written as formulas of earlier ones follow them (EF = "CE" follows CE), and
/// the length scale is the edited file's. A joints-and-links file keeps its loops, but the
/// closed-form dyad positions hold numbers of the file's dimensions (each body's joints in
/// its frame): the copy solves by Newton from the file's sketch guesses instead (the same
/// numbers to rounding; no circuit or dyad-by-dyad derivation). A joints file for which
/// kinema made parameters from the sketch (a length the file does not give) is refused:
/// those numbers follow the dimensions only through the sketch. InputError names an
/// unknown parameter, one kinema made, or a value that is not finite; a later entry for
/// the same name wins.
Model with_parameters(const Model& model, const std::vector<std::pair<std::string, double>>& values);

/// The constraint system of a mechanism as written: built by the front end of its form
/// (vector loops, joints and links, a spatial chain), the dyads' assemblies settled.
ConstraintSystem build_constraint_system(const Mechanism& mechanism);

struct MotionOptions {
  std::optional<double> rate;         ///< Input rate (SI); default: the model's.
  std::optional<double> second_rate;  ///< Input second rate (SI); default: the model's.
  unsigned threads = 1;               ///< Long runs are split into chunks on this many threads.
  bool simd = true;                   ///< Sweeps in SIMD blocks where the motion is regular.
};

/// Solves at each input value (SI) in order, each continued from the previous one so
/// that the assembly branch of the file's guesses is kept. A value that cannot be
/// assembled or is singular is a row with that status and a Failure
/// (describe_failure(model.system, state) says it in words); nothing is thrown for it.
MotionTable solve_motion(const Model& model, const std::vector<double>& inputs, const MotionOptions& options = {});

}  // namespace kinema
