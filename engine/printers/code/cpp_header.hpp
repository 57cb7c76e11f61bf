// Exports a mechanism's compiled evaluator as a standalone C++ header (the
// standard library only), for controllers, simulations and microcontrollers.
// Its solver is the engine's own code (engine/numeric/solver.hpp, pasted in),
// so it calls the same positions singular as the engine.
#pragma once

#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "engine/model.hpp"

namespace kinema {

/// Writes the header; `name` becomes its namespace (a C++ identifier). Its
/// evaluate() returns Status::ok, singular (position solved, rates undefined)
/// or unassembled.
void write_cpp_header(std::ostream& out, const Model& model, const std::string& name);

/// True for a C++ keyword or alternative token (int, or, not, ...), the namespaces std
/// and posix, and the macros of the C library's headers and of g++'s GNU dialect (M_PI,
/// NAN, DBL_MAX, stdin, linux, ...): names generated code cannot use.
bool is_cpp_reserved(const std::string& name);

/// A C++ identifier made from a name or a file stem ("four-bar" -> "four_bar",
/// "int" -> "int_", "été" -> "mechanism_t_"; never a "__" or a leading "_"), safe in
/// generated code.
std::string cpp_identifier(const std::string& text);

/// cpp_identifier of each name, made distinct from each other and from `taken` by
/// numbering (int and int_ -> int_ and int_2; never a "__").
std::vector<std::string> cpp_identifiers(const std::vector<std::string>& names, const std::set<std::string>& taken = {});

}  // namespace kinema
