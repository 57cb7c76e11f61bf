// Velocity and acceleration polygons of a planar mechanism at one solved position,
// built from the exact solution the way a textbook draws them: from the pole o, the
// absolute velocity of each point; between points, the relative velocity of each
// link vector; for accelerations each link vector's normal (omega^2 r), tangential
// (alpha r), Coriolis (2 omega v_rel) and relative (sliding) parts, chained in that
// order. Every loop and every named point is a chain of link vectors from the fixed
// origin as written; its polygon chain closes because its derivative does.
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "engine/model.hpp"

namespace kinema {

/// One arrow of a polygon (SI: m/s or m/s^2), from the image of one point to another.
struct PolygonArrow {
  enum class Kind { absolute, relative, sliding, normal, tangential, coriolis };
  Kind kind = Kind::absolute;
  std::string name;   ///< Plain: "v_BA", "an_BA", "ac_BB'".
  std::string latex;  ///< v_{BA}, a^{n}_{BA}, a^{c}_{BB'}
  std::complex<double> from, to;
  /// The formula of its length (omega3*b, omega3^2*b, 2*omega4*sd, ...; 0 for an
  /// absolute arrow) and that formula's value from the coordinates and rates.
  GiNaC::ex formula = 0;
  double formula_value = 0;
  /// For a link's turning (relative or absolute velocity across a link): the angle's rate
  /// (omega3) and the link vector as drawn, so that to - from = i omega link.
  GiNaC::ex turning = 0;
  std::complex<double> link;
  double length() const { return std::abs(to - from); }
};

/// The image of a point in a polygon: a named point, the pole (every fixed point), or a
/// point of a turning line under a sliding point (B').
struct PolygonVertex {
  std::string name;  ///< "B", "o", "B'", "J1" (a joint the file does not name).
  std::complex<double> at;
};

struct Polygon {
  int order = 1;  ///< 1: velocities, 2: accelerations.
  std::vector<PolygonVertex> vertices;  ///< The pole first.
  std::vector<PolygonArrow> arrows;
  /// max over the chains of |end - start|: each loop's chain must come back to its start.
  double closure_error = 0;
};

/// Reads, per link vector, its position and the parts of its first and second time
/// derivatives from the model (derived with it, evaluated by its tape's drawing stage):
/// polygons() lays them end to end at a state. Planar systems only.
class PolygonBuilder {
 public:
  explicit PolygonBuilder(const Model& model);
  /// False for a spatial chain, a system without planar loops and points, and one whose
  /// link vectors GiNaC could not differentiate.
  bool available() const { return !chains_.empty(); }
  /// The velocity and the acceleration polygon at a state that is ok; nullopt otherwise.
  std::optional<std::pair<Polygon, Polygon>> polygons(const MotionState& state) const;

 private:
  /// A link vector's parts' lengths as shown (positive where the sign is the direction's),
  /// in textbook order (LinkVectorPart); and the angle's rate of a polar vector.
  struct LinkVectorParts {
    std::array<GiNaC::ex, kLinkVectorParts> formulas;
    GiNaC::ex turning = 0;
  };
  struct Chain {
    std::string point;  ///< The named point at its end (points' chains), or empty (a loop).
    std::vector<std::size_t> vectors;  ///< Into the model's link vectors (and parts_).
  };
  const Model* model_ = nullptr;
  std::vector<LinkVectorParts> parts_;  ///< Per link vector of the model.
  std::vector<Chain> chains_;           ///< The points' chains, then the loops'.
};

}  // namespace kinema
