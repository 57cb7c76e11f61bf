// LaTeX spelling of names and user text, shared by the LaTeX printers.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include <kinema/engine/symbolic/derivation.hpp>
#include <kinema/loops/mechanism.hpp>

namespace kinema {

/// theta3 -> \theta_{3}, omega2 -> \omega_{2}, r1_dot -> \dot{r}_{1}, xE -> x_{E},
/// La -> L_{a}, AB -> \mathit{AB}. Names are identifiers, so nothing needs escaping.
std::string latex_symbol_name(const std::string& name);

/// User text (titles, descriptions) for LaTeX text mode: every special character
/// is printed as itself, so a file cannot inject commands (\input{...} prints as text).
std::string latex_escape_text(const std::string& text);

/// Throws InputError unless a LaTeX name given in a mechanism file uses only
/// letters, digits, _ ^ { } ' and the commands for Greek letters and accents.
void check_latex_name(const std::string& latex, const std::string& context);

/// Substitution that gives every symbol of the derivation its LaTeX name
/// (the file's `latex` for unknowns, latex_symbol_name otherwise).
GiNaC::exmap latex_symbols(const Mechanism& mechanism, const Derivation& derivation);

/// e^{i angle} (the angle parenthesised when it is a sum).
std::string latex_exp(const GiNaC::ex& angle, const GiNaC::exmap& names);

/// A column vector and a matrix as amsmath bmatrix.
std::string latex_column(const std::vector<GiNaC::ex>& entries, const GiNaC::exmap& names);
std::string latex_matrix(const GiNaC::matrix& matrix, const GiNaC::exmap& names);

/// Top-level terms of a formula as written ("a*exp(I*t) - d" -> "a*exp(I*t)", "-d").
std::vector<std::string> written_terms(const std::string& formula);

/// An expression in LaTeX with those names.
std::string to_latex(const GiNaC::ex& e, const GiNaC::exmap& names);

}  // namespace kinema
