// What the shell user sees when the command line cannot be parsed: help and
// version on stdout (status 0), or one line on stderr that says what is wrong
// and which --help to read (status 2).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace kinema_cli {

/// One line, e.g. "kinema: usage error: eval: FILE is required; run 'kinema eval --help'".
std::string usage_message(const CLI::App& app, const CLI::ParseError& error);

/// Prints help or version (stdout) or the usage message (stderr); returns the exit status.
int report_parse_error(const CLI::App& app, const CLI::ParseError& error);

}  // namespace kinema_cli
