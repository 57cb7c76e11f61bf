// An answer a problem asks, as the problem sets work it out and the documents print it:
// the data a printer shows from the problems stage, in a header of its own so that a
// printer sees the answer and not how problem sets are drawn and solved.
#pragma once

#include <string>

namespace kinema {

/// An asked answer: `quantity` (an output column) at input value `at_text`, or a design
/// figure (engine/problems/design_answers), asked once per variant: at_text empty.
struct ProblemAnswer {
  std::string quantity;
  std::string at_text;  ///< "30 deg", as the file (or the drawn driver value) writes it.
  double at_si = 0.0;
  double si = 0.0;      ///< In SI (rad, m, s).
  double value = 0.0;   ///< In the output units of kinema eval.
  std::string unit;     ///< Those units ("rad/s", "mm/s").
  std::string text;     ///< A figure that is a class in words (grashof); value and si NaN then.
  bool figure = false;  ///< A design figure: no input value (at_text empty).
  double scale = 0.0;   ///< What `value` is shown at for people (RowScales; 0: as it is).
};

}  // namespace kinema
