// Counts of the engine's costly work done in this process, kind by kind, so that a test
// can show where work happens: once per command, in the analysis, and never while a
// printer formats (values solved are counted by engine/numeric/sweep's
// values_solved_in_process()).
#pragma once

#include <cstdint>

namespace kinema {

enum class Work {
  design_figures,   ///< four_bar_figures, slider_strokes: a turn solved, toggles and limits by Newton.
  dyad_derivation,  ///< derive_by_dyads.
  chain_at_instant, ///< chain_at_instant: a chain's formulas at the instant.
  drawing,          ///< Drawing geometry, polygons, instant centres, a chain's frames placed (each call).
  formula_read,     ///< FormulaReader::read: a formula's text parsed by GiNaC.
  count_            ///< The number of kinds (not a kind of work).
};

void count_work(Work work);
std::uint64_t work_done_in_process(Work work);

}  // namespace kinema
