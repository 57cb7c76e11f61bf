#include "cli/problems_command.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/output_file.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/user_text.hpp"
#include "engine/model.hpp"
#include "engine/run/problem_files.hpp"
#include "readers/mechanism_file.hpp"

namespace kinema_cli {

void add_problems_command(CLI::App& app, ProblemsOptions& options) {
  options.command = app.add_subcommand(
      "problems", "write a problem set from the file's [problem] table: per variant a student sheet and a key "
                  "(LaTeX), the class table (CSV, JSON) and Moodle XML and formula-question CSV exports");
  options.command->add_option("FILE", options.file, "mechanism file (TOML) with a [problem] table")->required();
  options.command->add_option("--count", options.count, "variants in the set (default 30)")->check(CLI::Range(1, 1000));
  options.command->add_option("--seed", options.seed,
                              "seed of the draws: the same seed gives the same set on every machine (default 1)");
  options.command->add_option("-o,--output", options.output_dir, "directory to write the set into, e.g. set/")->required();
}

int run_problems(const ProblemsOptions& options) {
  using namespace kinema;
  const Mechanism mechanism = read_mechanism_file(options.file);
  if (!mechanism.problem) {
    throw InputError(options.file + ": the file has no [problem] table; add one (docs/problems.md), e.g. [problem] "
                     "find = [\"omega3\"] at = [\"30 deg\"]");
  }
  const Model model = make_model(mechanism);  // full scope: the keys print its formulas
  const ProblemSet set = make_problem_set(model, *mechanism.problem, options.count, options.seed);
  std::string source_name = std::filesystem::path(options.file).filename().string();
  std::vector<NamedFile> files = problem_set_files(set, source_name, mechanism.title);
  // The source's copy gets a name no generated file has (a mechanism file named class.json
  // would replace the class table, and check would then read the mechanism as one).
  const auto generated = [&files](const std::string& name) {
    return std::any_of(files.begin(), files.end(), [&name](const NamedFile& file) { return file.first == name; });
  };
  if (generated(source_name)) {
    while (generated(source_name)) source_name = "source_" + source_name;
    files = problem_set_files(set, source_name, mechanism.title);
  }
  std::ifstream source(options.file, std::ios::binary);
  std::ostringstream text;
  text << source.rdbuf();
  files.emplace_back(source_name, text.str());  // the set stands alone
  // Every file made before any is written: an error above leaves nothing behind.
  const std::filesystem::path directory(options.output_dir);
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (!std::filesystem::is_directory(directory)) {
    throw OutputError(options.output_dir + ": cannot make the directory" + (error ? " (" + error.message() + ")" : ""));
  }
  for (const auto& [name, content] : files) {  // nothing generated replaces the file read
    std::error_code same;
    if (name != source_name && std::filesystem::equivalent(directory / name, options.file, same)) {
      throw InputError(terminal_text(options.file) + ": writing the set into " + terminal_text(options.output_dir) +
                       " would replace this file with the set's " + terminal_text(name) +
                       "; give another directory (-o) or rename the file");
    }
  }
  for (const auto& [name, content] : files) {
    const std::filesystem::path path = directory / name;
    std::error_code same;
    if (name == source_name && std::filesystem::equivalent(path, options.file, same)) continue;  // the file itself
    write_output(content, path.string());
  }
  std::string why;
  for (const auto& [condition, refused] : set.redrawn) why += (why.empty() ? "" : ", ") + condition + " " + std::to_string(refused);
  std::cerr << "kinema: wrote " << set.variants.size() << " variants to " << terminal_text(options.output_dir) << " ("
            << set.draws << " drawn, " << (set.draws - set.variants.size()) << " redrawn"
            << (why.empty() ? "" : "; failed conditions: " + why) << ")\n";
  return 0;
}

}  // namespace kinema_cli
