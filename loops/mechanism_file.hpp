// Reads a mechanism file (TOML; format in README.md) into a Mechanism.
// Every error names file:line and the key, and says what to write instead.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <kinema/loops/mechanism.hpp>

namespace kinema {

/// Largest mechanism file read (bytes): far above any mechanism, far below trouble.
constexpr std::size_t kMaxMechanismFileBytes = 1024 * 1024;

/// Most input values one run solves: the results (and their text) are held in memory.
constexpr std::size_t kMaxValuesPerRun = 10'000'000;

/// Reads and checks a mechanism file; throws InputError / UnitError.
Mechanism read_mechanism_file(const std::string& path);

/// Same, from text already in memory; `name` stands for the file in messages.
Mechanism read_mechanism_text(const std::string& text, const std::string& name);

/// Parses a sweep "start:stop:step" (numbers in `unit_factor` units) into SI values.
std::vector<double> parse_sweep(const std::string& text, double unit_factor);

}  // namespace kinema
