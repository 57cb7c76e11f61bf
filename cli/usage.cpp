#include "cli/usage.hpp"

#include <iostream>

#include "engine/base/user_text.hpp"

#include "cli/exit_status.hpp"

namespace kinema_cli {

namespace {

// CLI11's text on one line: newlines and runs of spaces become one space.
std::string one_line(const std::string& text) {
  std::string line;
  for (char c : text) {
    const bool space = c == '\n' || c == '\r' || c == '\t' || c == ' ';
    if (space) {
      if (!line.empty() && line.back() != ' ') line += ' ';
    } else {
      line += c;
    }
  }
  while (!line.empty() && (line.back() == ' ' || line.back() == '.')) line.pop_back();
  return line;
}

std::string in_quotes(const std::string& word) { return "\"" + word + "\""; }

bool is_option(const std::string& word) { return word.size() > 1 && word[0] == '-'; }

std::string command_list(const CLI::App& app) {
  std::string list;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (!list.empty()) list += ", ";
    list += command->get_name();
  }
  return list;
}

// The arguments nothing took: unknown options, extra words, an unknown command.
std::string unexpected(const std::vector<std::string>& words) {
  for (const std::string& word : words) {
    if (is_option(word)) return "unknown option " + in_quotes(word);
  }
  return "unexpected argument " + in_quotes(words.front());
}

}  // namespace

std::string usage_message(const CLI::App& app, const CLI::ParseError& error) {
  const auto commands = app.get_subcommands();  // those given, even when parsing stopped in one
  const CLI::App* command = commands.empty() ? nullptr : commands.front();
  const std::vector<std::string> left = app.remaining(true);
  std::string what;
  if (command == nullptr) {
    std::string first_word;
    for (const std::string& word : left)
      if (!is_option(word)) {
        first_word = word;
        break;
      }
    if (!first_word.empty()) what = "unknown command " + in_quotes(first_word) + " (commands: " + command_list(app) + ")";
    else if (!left.empty()) what = unexpected(left);
    else if (dynamic_cast<const CLI::RequiredError*>(&error)) what = "a command is required (" + command_list(app) + ")";
    else what = one_line(error.what());
  } else if (dynamic_cast<const CLI::ExtrasError*>(&error) && !left.empty()) {
    what = command->get_name() + ": " + unexpected(left);
  } else if (dynamic_cast<const CLI::ArgumentMismatch*>(&error) && one_line(error.what()).find(" missing") != std::string::npos) {
    // "--threads: 1 required UINT:UINT in [1 - 256] missing"
    const std::string text = one_line(error.what());
    what = command->get_name() + ": " + text.substr(0, text.find(':')) + " needs a value";
  } else {
    what = command->get_name() + ": " + one_line(error.what());
  }
  const std::string help = command == nullptr ? "kinema --help" : "kinema " + command->get_name() + " --help";
  return "kinema: usage error: " + what + "; run '" + help + "'";
}

int report_parse_error(const CLI::App& app, const CLI::ParseError& error) {
  const int status = exit_status(error);
  if (status == status::success) return app.exit(error, std::cout, std::cerr);  // --help, --version
  std::cerr << kinema::terminal_text(usage_message(app, error)) << "\n";  // a path's ESC or U+202E shown, not acted on
  return status;
}

}  // namespace kinema_cli
