#include "cli/check_command.hpp"

#include <optional>

#include "engine/base/errors.hpp"
#include "engine/model.hpp"
#include "engine/printers/check_report.hpp"
#include "engine/problems/answer_check.hpp"
#include "readers/answers_file.hpp"
#include "readers/class_table.hpp"
#include "readers/mechanism_file.hpp"

#include "cli/exit_status.hpp"
#include "cli/output_file.hpp"

namespace kinema_cli {

namespace {

using namespace kinema;

bool is_class_table(const std::string& path) {
  return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

// --tolerance or --sig-figs, else the class table's, else 1 %.
AnswerTolerance tolerance_of(const CheckLine& line, const std::optional<AnswerTolerance>& table) {
  if (!line.tolerance.empty()) return relative_tolerance(line.tolerance, "--tolerance");
  if (line.command->count("--sig-figs") > 0) return significant_figures(line.sig_figs, "--sig-figs");
  return table.value_or(AnswerTolerance{});
}

// The variant asked for: --variant, or the answers file's variant = N (the two must agree).
std::optional<long> variant_of(const CheckLine& line, const AnswersFile& answers) {
  const bool given = line.command->count("--variant") > 0;
  if (given && answers.variant && *answers.variant != line.variant) {
    throw InputError(answers.variant_where.str() + ": variant = " + std::to_string(*answers.variant) +
                     ", but --variant " + std::to_string(line.variant) + "; give one of them");
  }
  if (given) return line.variant;
  return answers.variant;
}

CheckReport check_class(const CheckLine& line, const AnswersFile& answers) {
  const ClassTable table = read_class_table(line.subject);
  const std::optional<long> number = variant_of(line, answers);
  if (!number) {
    throw InputError(line.subject + ": a class table has a variant for each student; give --variant N (or variant = N " +
                     "at the top of the answers file)");
  }
  const ClassVariant& variant = class_variant(table, *number);
  const Model source = make_model(read_mechanism_file(table.source), DerivationScope::evaluation);
  const Model model = variant_model(source, table, variant);
  return check_answers(variant_subject(model, table, variant), answers, tolerance_of(line, table.tolerance));
}

CheckReport check_file(const CheckLine& line, const AnswersFile& answers) {
  if (variant_of(line, answers)) {
    throw InputError((answers.variant ? answers.variant_where.str() : std::string("--variant")) +
                     ": a variant is one of a class table's (set/class.json); " + line.subject +
                     " is a mechanism file, checked with its own dimensions");
  }
  const Model model = make_model(read_mechanism_file(line.subject), DerivationScope::evaluation);
  return check_answers(file_subject(model), answers, tolerance_of(line, std::nullopt));
}

}  // namespace

void add_check_command(CLI::App& app, CheckLine& line) {
  CLI::App* check = line.command = app.add_subcommand(
      "check", "check a student's answers against a mechanism file or a class table's variant, naming the likely "
               "mistake of each wrong one (exit status 0: all right, 6: some wrong)");
  check->add_option("FILE_OR_CLASS", line.subject,
                    "mechanism file (TOML; the answers are for its own dimensions), or a class table written by "
                    "kinema problems (class.json, with --variant)")
      ->required();
  check->add_option("ANSWERS", line.answers,
                    "answers file: TOML ([[answer]] quantity, at, value) or CSV (quantity,at,value[,unit]); a value "
                    "without a unit is in the file's output unit")
      ->required();
  check->add_option("--variant", line.variant, "the class table's variant the answers are for (or variant = N in the answers file)");
  CLI::Option* tolerance = check->add_option(
      "--tolerance", line.tolerance, "relative tolerance, e.g. 1% or 0.01 (default: the class table's, else 1%)");
  check->add_option("--sig-figs", line.sig_figs, "right when it agrees to this many significant figures instead")
      ->excludes(tolerance);
  check->add_option("--format", line.format, "text (for people) or json (for a grader)")
      ->check(CLI::IsMember({"text", "json"}));
  check->add_option("-o,--output", line.output_path, "write to this file instead of stdout");
}

int run_check(const CheckLine& line) {
  check_output(line.output_path);
  const AnswersFile answers = read_answers_file(line.answers);
  const CheckReport report = is_class_table(line.subject) ? check_class(line, answers) : check_file(line, answers);
  write_output(line.format == "json" ? check_report_json(report) : check_report_text(report), line.output_path);
  return report.wrong_count() == 0 ? status::success : status::wrong_answers;
}

}  // namespace kinema_cli
