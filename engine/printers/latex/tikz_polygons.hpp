// The velocity and acceleration polygons of a planar mechanism drawn to a stated scale
// in TikZ (pole, images of the points, each arrow labelled and styled by kind), each
// with a table of its arrows: the length read off the figure, the formula and its value.
#pragma once

#include <ostream>

#include "engine/constraint_system.hpp"
#include "engine/printers/textbook_form.hpp"
#include "engine/analysis/polygons.hpp"

namespace kinema {

/// A scale for a drawing: the round number (1, 2, 2.5 or 5 times a power of ten) of
/// units per centimetre that fits `extent` units into `centimetres`.
double drawing_scale(double extent, double centimetres);

/// The polygon's drawing scale: output units (length unit/s or /s^2) per centimetre.
double polygon_units_per_cm(const Polygon& polygon, double metres_per_length_unit);

/// An arrow's length as read off its figure: to 0.01 cm, times the scale (output units).
double polygon_read_off(const PolygonArrow& arrow, double units_per_cm, double metres_per_length_unit);

void write_tikz_polygon(std::ostream& out, const ConstraintSystem& system, const TextbookForm& form,
                        const Polygon& polygon);

}  // namespace kinema
