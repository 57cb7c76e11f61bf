#include "engine/printers/latex/three_methods.hpp"

#include <cmath>

#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/latex/tikz_polygons.hpp"
#include "engine/analysis/output_scale.hpp"

namespace kinema {

std::vector<ThreeMethodsRow> three_methods(const ConstraintSystem& system, const Polygon& velocity,
                                           const InstantCentres& centres) {
  std::vector<ThreeMethodsRow> rows;
  const OutputScale scale(system);
  const double per_cm = polygon_units_per_cm(velocity, scale.length);
  const double driver_omega = centres.angular_velocities[centres.driver];
  for (std::size_t b = 1; b < centres.bodies.size(); ++b) {
    const GiNaC::ex& rate = centres.rates[b];
    if (rate.is_zero()) continue;  // a slider block turns with its guide
    ThreeMethodsRow row;
    row.body = b;
    row.solved = centres.angular_velocities[b];
    // The longest arrow across this link reads best.
    const PolygonArrow* best = nullptr;
    for (const PolygonArrow& a : velocity.arrows)
      if (a.turning.is_equal(rate) && std::abs(a.link) > 0 && (!best || a.length() > best->length())) best = &a;
    if (best) {
      const std::complex<double> turning = (best->to - best->from) / best->link;  // i omega
      row.polygon_arrow = best->latex;
      row.read_off = polygon_read_off(*best, per_cm, scale.length);
      row.lever = std::abs(best->link) / scale.length;
      row.from_polygon = std::copysign(row.read_off / row.lever, turning.imag());
    }
    if (b == centres.driver && centres.driver != 0) {
      row.from_centres = driver_omega;
    } else {
      for (const VelocityRatio& r : centres.ratios)
        if (r.body == b) row.from_centres = r.from_centres * driver_omega;
    }
    rows.push_back(row);
  }
  return rows;
}

void write_three_methods(std::ostream& out, const ConstraintSystem& system, const std::vector<ThreeMethodsRow>& rows,
                         const InstantCentres& centres) {
  if (rows.empty()) return;
  const OutputScale scale(system);
  const DocumentNumbers number(system);  // round-off as 0
  const Dimension angle = Dimension::angle, length = Dimension::length;
  const std::string velocity_unit = "\\mathrm{" + scale.length_unit + "/s}", length_unit = "\\mathrm{" + scale.length_unit + "}";
  out << "\\subsubsection*{Three methods, one answer}\nEach link's angular velocity as solved from the loop "
         "equations; read off the velocity polygon (an arrow across the link measured on the figure, over the "
         "link's length; the sense from the arrow's); and from the instant centres (its ratio to the driver's). "
         "Positive is counter-clockwise.\n\n"
      << "\\begin{tabular}{lrlrr}\n\\toprule\nlink & solved & polygon & & centres \\\\\n & $\\mathrm{rad/s}$ & "
         "read off & $\\mathrm{rad/s}$ & $\\mathrm{rad/s}$ \\\\\n\\midrule\n";
  for (const ThreeMethodsRow& row : rows) {
    out << latex_escape_text(centres.bodies[row.body]) << " & $" << number(row.solved, angle, 1, 5) << "$ & ";
    if (row.from_polygon) {
      out << "$" << row.polygon_arrow << " = " << number.read_off(row.read_off, length, 1) << "\\," << velocity_unit << ",\\ r = "
          << number(row.lever, length, 0, 4) << "\\," << length_unit << "$ & $" << number(*row.from_polygon, angle, 1, 3) << "$";
    } else {
      out << "--- & ---";
    }
    out << " & ";
    out << (row.from_centres ? "$" + number(*row.from_centres, angle, 1, 5) + "$" : std::string("---")) << " \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\n";
}

}  // namespace kinema
