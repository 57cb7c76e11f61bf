// The motion of each link vector of a planar system, derived once with the model: the
// one builder of relative-motion and Coriolis terms. A vector length*e^{i angle} has the
// textbook's parts: in velocity its rotation (i angle' r) and its sliding (length' e);
// in acceleration its normal (-angle'^2 r), tangential (i angle'' r), Coriolis
// (2 i angle' length' e) and relative (length'' e) parts. The derivation's sliding links,
// the polygons and the drawings read them; the compiled model evaluates them
// (TapeLayout::kDrawingStage), so that no view differentiates again.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/expression_parts.hpp"

namespace kinema {

/// The parts of a link vector's motion, in textbook order: velocity, then acceleration.
enum LinkVectorPart : std::size_t { rotation, sliding, normal, tangential, coriolis, relative, kLinkVectorParts };

struct LinkVectorMotion {
  GiNaC::ex term;
  LinkVector link;  ///< term as length*e^{i angle} (link.polar), or not of that form.
  /// A link vector the textbook way: polar with a real length and angle. Its parts are
  /// those of the rotation and the sliding; any other vector's are its whole derivatives
  /// (its velocity as sliding, its acceleration as relative).
  bool textbook = false;
  /// False when GiNaC could not differentiate the term (a power of 0): no rates or parts.
  bool derived = false;
  GiNaC::ex length_rate = 0, angle_rate = 0, length_second_rate = 0, angle_second_rate = 0;  ///< Polar terms.
  std::array<GiNaC::ex, kLinkVectorParts> parts;  ///< Complex, each a vector.
  /// Each part's length as derived (angle_rate*length, ...; its sign the direction's);
  /// 0 for the parts of a vector of no textbook form.
  std::array<GiNaC::ex, kLinkVectorParts> magnitudes;
  /// A slider's term: d(term)/d(slide), the way it moves as its sliding length changes
  /// with the other coordinates held (sliding_length); nullopt for other terms.
  std::optional<GiNaC::ex> guide;
};

/// The motion of one link vector; throws what GiNaC throws for a term it cannot differentiate.
LinkVectorMotion link_vector_motion(const ConstraintSystem& system, const GiNaC::ex& term);

/// The length that slides in a term: the input when the term has it and it is a length,
/// else the first unknown of dimension length the term has; nullopt for none.
std::optional<GiNaC::ex> sliding_length(const ConstraintSystem& system, const GiNaC::ex& term);

/// A planar system's link vectors as the compiled model holds them: each vector loop's
/// terms in the order written, then each named point's written terms; empty for a spatial
/// chain. A term GiNaC cannot differentiate is kept with derived = false.
struct PlanarLinkVectors {
  std::vector<LinkVectorMotion> vectors;
  /// Per vector loop (its group) and per point with written terms: its vectors' indices.
  struct Chain {
    std::optional<std::size_t> group, point;
    std::vector<std::size_t> vectors;
  };
  std::vector<Chain> chains;
};
PlanarLinkVectors planar_link_vectors(const ConstraintSystem& system);

}  // namespace kinema
