// Exports a mechanism's compiled evaluator as a standalone C++ header:
// no dependencies beyond <cmath>, for controllers, simulations and
// microcontrollers.
#pragma once

#include <ostream>
#include <string>

#include <kinema/engine/model.hpp>

namespace kinema {

/// Writes the header; `name` becomes its namespace (a C++ identifier).
void write_cpp_header(std::ostream& out, const Model& model, const std::string& name);

/// A C++ identifier made from a file stem ("four-bar.hpp" -> "four_bar").
std::string cpp_identifier(const std::string& text);

}  // namespace kinema
