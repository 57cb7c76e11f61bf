// Reads a mechanism file (TOML; format in docs/mechanism-files.md) into a Mechanism:
// what the user wrote, in any of the three forms, as written. No front end runs here:
// the equations (and a joints-and-links file's loops and dyads) are built as a step of
// their own (engine/model.hpp, build_constraint_system). Every error names file:line and
// the key, and says what to write instead.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "readers/mechanism.hpp"
#include "readers/sweep_syntax.hpp"  // a file's sweep is written as --sweep is

namespace kinema {

/// Largest mechanism file read (bytes): far above any mechanism, far below trouble.
constexpr std::size_t kMaxMechanismFileBytes = 1024 * 1024;

/// Most input values `kinema latex` works out: the document has a results page for each
/// (100,001 values wrote 853 MB in 80 s); a table of many values is eval's work.
constexpr std::size_t kMaxLatexValues = 50;

/// Most joints and links of a joints-and-links file: a mechanism has tens; the structure
/// search and the loops it writes grow with the square of the count.
constexpr std::size_t kMaxJoints = 128;
constexpr std::size_t kMaxLinks = 64;

/// Reads and checks a mechanism file; throws InputError / UnitError.
Mechanism read_mechanism_file(const std::string& path);

/// Same, from text already in memory; `name` stands for the file in messages.
Mechanism read_mechanism_text(const std::string& text, const std::string& name);

/// Parameters, the input and the unknowns share one name space (they are symbols in
/// formulas): InputError at the second of two with one name. A front end that adds
/// names asks again.
void check_shared_names(const Mechanism& mechanism);

}  // namespace kinema
