// The exit statuses of the kinema command-line tool, and the one place that
// decides which status an exception means (the library's exceptions say what
// went wrong; the tool decides what a shell sees).
#pragma once

#include <exception>

namespace kinema_cli {

namespace status {
constexpr int success = 0;
constexpr int internal = 1;     ///< a bug or an unexpected failure
constexpr int bad_input = 2;    ///< the file (syntax, names, units, counts, values) or the command line
constexpr int unassembled = 3;  ///< a requested value cannot be assembled
constexpr int singular = 4;     ///< a requested value is a singular position
constexpr int output = 5;       ///< the output cannot be written
/// kinema check: some answers are wrong (the report is written; a grader that reads only
/// the status tells this from every failure of kinema itself).
constexpr int wrong_answers = 6;
}  // namespace status

/// The exit status for an error: kinema's exception classes, CLI11's parse
/// errors (help and version are 0, the rest usage errors) and anything else (internal).
int exit_status(const std::exception& error);

}  // namespace kinema_cli
