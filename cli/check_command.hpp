// kinema check FILE_OR_CLASS ANSWERS: a student's answers checked against a mechanism file
// or a variant of a class table (docs/check.md); exit status 0 when all are right,
// status::wrong_answers when some are wrong.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace kinema_cli {

/// The check command's arguments as parsed.
struct CheckLine {
  CLI::App* command = nullptr;
  std::string subject, answers, tolerance, format = "text", output_path;
  long variant = 0;
  int sig_figs = 0;
};

/// Adds `check` and its options to the program's commands.
void add_check_command(CLI::App& app, CheckLine& line);

/// Runs it: the report printed, the exit status returned; kinema::Error for bad input.
int run_check(const CheckLine& line);

}  // namespace kinema_cli
