// The seeds' methods (engine/symbolic/dyad_method) as rows of an amsmath align*, shared by
// `derive --format latex --method ...` and the worked solution of `kinema latex --method ...`.
#pragma once

#include <string>
#include <vector>

#include "engine/printers/latex/latex_format.hpp"
#include "engine/symbolic/dyad_derivation_types.hpp"

namespace kinema {

/// The velocity (or acceleration) relations of one step: its heading, each relation as
/// the method writes it, its scalar equations, and what they solve for, in textbook form.
/// Each row within `budget` glyphs after its & where it can be broken.
std::vector<LatexRow> method_rows(const MethodStep& step, bool acceleration, const TextbookForm& form,
                                  double budget = kLatexLineBudget);

/// "relative velocities" or "joint coordinates": how a document names the method.
std::string method_title(DerivationMethod method);

}  // namespace kinema
