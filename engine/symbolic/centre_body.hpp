// A body whose instant centres the model's drawing stage holds (a planar loop system's,
// engine/symbolic/centre_formulas.hpp; TapeLayout::centre_bodies lists them).
#pragma once

namespace kinema {

/// A link (LoopTerms' numbering), or the block of a slider term (its link vector).
struct CentreBody {
  int link = -1;
  int slider_term = -1;
  /// A joints-and-links file's: the SolvingPlan body it is (-1: none, or another file).
  int plan_body = -1;
};

}  // namespace kinema
