// Printers: each output format is a printer over the same results (the
// derivation and the motion states). They convert SI to the output units.
#pragma once

#include <ostream>
#include <vector>

#include <kinema/engine/symbolic/derivation.hpp>
#include <kinema/engine/numeric/kinematics.hpp>
#include <kinema/loops/mechanism.hpp>

namespace kinema {

/// The derivation in readable text: loops, scalar equations, Jacobian,
/// velocity and acceleration equations, solved rates, point motion.
void print_derivation_text(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation);

/// The derivation as a LaTeX align* block (amsmath), each solved formula followed
/// by a "% kinema: name = formula" comment in GiNaC syntax.
void print_derivation_latex(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation);

/// A worked solution: data, loops, velocity and acceleration analysis, results and
/// a TikZ drawing at each of at_values, pgfplots over sweep. A fragment (for
/// \input into notes) has no preamble; it needs amsmath, booktabs, tikz with the
/// patterns library, and pgfplots.
void print_latex_document(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation,
                          const MotionTable& at_values, const MotionTable& sweep,
                          bool fragment);

/// A complex vector loop as course notes write it: a\,e^{i\theta_{2}} + ...
/// `written` is the loop's formula as in the file: its terms keep their order.
std::string latex_vector_loop(const GiNaC::ex& loop, const GiNaC::exmap& names, const std::string& written = "");

/// Results for people: one block per input value.
void print_results_table(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation,
                         const MotionTable& states);

/// Results for spreadsheets: one row per input value, units in the header.
void print_results_csv(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation,
                       const MotionTable& states);

/// Results for programs (schema in README.md).
void print_results_json(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation,
                        const MotionTable& states);

/// Output-unit conversions shared by the printers.
struct OutputScale {
  explicit OutputScale(const Mechanism& mechanism);
  double length;  ///< SI metres per output length unit.
  std::string length_unit;
  bool input_is_angle;
  /// Coordinate value in output units (angles in deg, wrapped to (-180, 180]).
  double coordinate(Dimension dimension, double si) const;
  double rate(Dimension dimension, double si) const;  ///< rad/s or length/s (also for second rates)
  std::string coordinate_unit(Dimension dimension) const;
  std::string rate_unit(Dimension dimension) const;
  std::string second_rate_unit(Dimension dimension) const;
};

}  // namespace kinema
