// The velocity and acceleration polygons of a planar mechanism drawn to a stated scale
// in TikZ (pole, images of the points, each arrow labelled and styled by kind), each
// with a table of its arrows: the length read off the figure, the formula and its value.
#pragma once

#include <ostream>

#include <kinema/engine/constraint_system.hpp>
#include <kinema/engine/printers/textbook_form.hpp>
#include <kinema/engine/report/polygons.hpp>

namespace kinema {

/// A scale for a drawing: the round number (1, 2, 2.5 or 5 times a power of ten) of
/// units per centimetre that fits `extent` units into `centimetres`.
double drawing_scale(double extent, double centimetres);

void write_tikz_polygon(std::ostream& out, const ConstraintSystem& system, const TextbookForm& form,
                        const Polygon& polygon);

}  // namespace kinema
