// Reads a mechanism file (TOML; format in docs/mechanism-files.md) into a Mechanism.
// Every error names file:line and the key, and says what to write instead.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "loops/mechanism.hpp"

#include "engine/numeric/input_values.hpp"

namespace kinema {

/// Largest mechanism file read (bytes): far above any mechanism, far below trouble.
constexpr std::size_t kMaxMechanismFileBytes = 1024 * 1024;

/// Most input values a file lists or sweeps: they are held in memory (8 bytes each), and
/// a library run of them (analyse) holds every row.
constexpr std::size_t kMaxValuesPerRun = 10'000'000;

/// Most values of a command-line sweep: streamed (computed, solved and written a block
/// at a time), so memory stays constant; the bound only keeps a typo from asking for
/// an output of petabytes.
constexpr std::size_t kMaxSweepValues = 1'000'000'000;

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

/// Parses a sweep "start:stop:step" (numbers in `unit_factor` units) into its SI values
/// (computed when asked); more than max_values of them are refused.
InputValues parse_sweep(const std::string& text, double unit_factor, std::size_t max_values = kMaxValuesPerRun);

/// The values from start to stop by step (numbers in `unit_factor` units), the last
/// within a billionth of a step of stop; `written` names the run in messages.
InputValues sweep_between(double start, double stop, double step, double unit_factor, std::size_t max_values,
                         const std::string& written);

}  // namespace kinema
