// The terms of a vector-loop file's loops classed once, from their formulas: ground, link
// or slider; the link each turns with (links numbered by the rate they turn at); a slider's
// guide and the link it turns with; the named points that lie on a link. The drawings
// (engine/analysis/geometry.hpp) and the instant centres' formulas on the tape
// (engine/symbolic/centre_formulas.hpp) read the same classes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "engine/constraints/constraint_system.hpp"
#include "engine/symbolic/link_vectors.hpp"

namespace kinema {

enum class LoopTermKind { ground, link, slider };

/// A link of a vector-loop file known by the angle it turns with: its number, the digits
/// the angle's coordinate name ends in (theta3 -> "3"), else that name; empty when the
/// angle is not a coordinate's.
std::string link_label(const ConstraintSystem& system, const GiNaC::ex& angle);

struct LoopTerms {
  /// Per loop term (the first link vectors of the model, loop by loop): its kind, its link
  /// or -1, whether it has a guide, whether that turns and with which link (or -1), its
  /// angle's coordinate (0: the input, k + 1: unknown k) or -1.
  std::vector<std::size_t> loop_term_count;  ///< Terms of each loop, in order.
  std::vector<LoopTermKind> kinds;
  std::vector<int> term_links;
  std::vector<bool> has_guide, guide_turns;
  std::vector<int> guide_links;
  std::vector<int> term_coordinates;
  /// A named point on a link: its formula's last term is a link vector of fixed length
  /// turning with that link.
  struct OnLink {
    std::size_t point = 0, vector = 0;  ///< The point and its last term's link vector.
    int link = 0;
  };
  std::vector<OnLink> points;
  std::vector<GiNaC::ex> link_rates;         ///< Per link: the rate it turns with.
  std::vector<std::size_t> link_vectors;     ///< Per link: a link vector turning with it (its first).
  std::vector<std::string> link_labels;
};

LoopTerms classify_loop_terms(const ConstraintSystem& system, const PlanarLinkVectors& link_vectors);

}  // namespace kinema
