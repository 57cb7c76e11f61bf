// The whole pipeline in one call, for programs that link kinema:
// file -> Mechanism -> LoopClosure -> Derivation -> Kinematics (compiled).
#pragma once

#include <memory>
#include <string>

#include <kinema/engine/symbolic/derivation.hpp>
#include <kinema/engine/numeric/kinematics.hpp>
#include <kinema/loops/planar_loops.hpp>
#include <kinema/loops/mechanism.hpp>
#include <kinema/loops/mechanism_file.hpp>

namespace kinema {

struct Model {
  Mechanism mechanism;
  Derivation derivation;
  std::unique_ptr<Kinematics> kinematics;  ///< Compiled evaluator.
};

/// Reads, derives and compiles; throws InputError for a bad file.
Model load_model(const std::string& path);
Model make_model(Mechanism mechanism);

}  // namespace kinema
