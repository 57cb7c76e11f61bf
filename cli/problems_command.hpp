// kinema problems: a problem set from a mechanism file's [problem] table (docs/problems.md).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace kinema_cli {

struct ProblemsOptions {
  CLI::App* command = nullptr;
  std::string file, output_dir;
  std::size_t count = 30;
  std::uint64_t seed = 1;
};

/// The subcommand and its options, read into `options`.
void add_problems_command(CLI::App& app, ProblemsOptions& options);

/// Makes the set, writes its files into options.output_dir (made if missing) only when all
/// are made, and says on stderr how many variants were drawn and why any were redrawn.
int run_problems(const ProblemsOptions& options);

}  // namespace kinema_cli
