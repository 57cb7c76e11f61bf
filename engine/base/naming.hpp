// Names of symbols, decided once when a front end creates them: the printed
// name of a rate (theta3 -> omega3) and the LaTeX spelling of a name
// (theta3 -> \theta_{3}), which GiNaC keeps with the symbol.
#pragma once

#include <string>

namespace kinema {

/// Conventional name of a coordinate's rate: theta3 -> omega3 / alpha3 (order 1 / 2),
/// r1 -> r1_dot / r1_ddot.
std::string default_rate_name(const std::string& coordinate, int order);

/// theta3 -> \theta_{3}, omega2 -> \omega_{2}, r1_dot -> \dot{r}_{1}, xE -> x_{E},
/// La -> L_{a}, AB -> \mathit{AB}. Names are identifiers, so nothing needs escaping.
std::string latex_symbol_name(const std::string& name);

/// Throws InputError ("context: LaTeX name ... what to write instead") unless a LaTeX
/// name given in a mechanism file follows the grammar of docs/mechanism-files.md, "LaTeX names":
/// letters, digits, , ' and subscripts _x or _{...}, balanced braces, Greek letters,
/// \prime, and \dot \ddot \hat \bar \tilde \vec \mathrm \mathit with a braced argument.
void check_latex_name(const std::string& latex, const std::string& context);

}  // namespace kinema
