// A body whose instant centres the model's drawing stage holds (a vector-loop file's,
// engine/symbolic/centre_formulas.hpp; TapeLayout::centre_bodies lists them).
#pragma once

namespace kinema {

/// A link (LoopTerms' numbering), or the block of a slider term (its link vector).
struct CentreBody {
  int link = -1;
  int slider_term = -1;
};

}  // namespace kinema
