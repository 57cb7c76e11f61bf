// "Three methods, one answer": each turning link's angular velocity as solved, as read off its velocity polygon (a relative velocity across the
// link, measured on the figure, over the link's length) and from its instant centres
// (the ratio to the driver's), side by side.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "engine/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/analysis/instant_centres.hpp"
#include "engine/analysis/polygons.hpp"

namespace kinema {

struct ThreeMethodsRow {
  std::size_t body = 0;  ///< As InstantCentres::bodies.
  double solved = 0;     ///< rad/s
  std::optional<double> from_polygon;  ///< Read off the figure (to 0.01 cm).
  std::string polygon_arrow;           ///< The arrow read (LaTeX), e.g. v_{CB}.
  double read_off = 0;                 ///< Its length read off, output units.
  double lever = 0;                    ///< The link vector's length, output units.
  std::optional<double> from_centres;
};

/// A row per link that turns on its own (not ground, not a slider block).
std::vector<ThreeMethodsRow> three_methods(const ConstraintSystem& system, const Polygon& velocity,
                                           const InstantCentres& centres);

void write_three_methods(std::ostream& out, const ConstraintSystem& system, const std::vector<ThreeMethodsRow>& rows,
                         const InstantCentres& centres);

}  // namespace kinema
