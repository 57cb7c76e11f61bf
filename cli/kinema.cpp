// kinema command-line tool: a thin layer over the library (engine/, loops/).
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <kinema/engine/printers/code/cpp_header.hpp>
#include <kinema/engine/errors.hpp>
#include <kinema/engine/model.hpp>
#include <kinema/engine/printers/printers.hpp>

namespace {

using namespace kinema;

// A command-line input value: "30" (deg, or the output length unit for a slider) or "30 deg".
double parse_input_value(const Mechanism& m, const std::string& text) {
  const Quantity q = parse_quantity(text);
  if (q.dimension == Dimension::number) {
    return m.input.dimension == Dimension::angle ? q.si_value * M_PI / 180.0
                                                 : q.si_value * m.output.length_factor;
  }
  if (q.dimension != m.input.dimension) {
    throw UnitError("input value \"" + text + "\" is a " + dimension_name(q.dimension) + ", but " +
                    m.input.name + " is a " + dimension_name(m.input.dimension));
  }
  return q.si_value;
}

// Output is built in memory and written at the end, so an error leaves nothing half-written.
void write_output(const std::string& text, const std::string& path) {
  if (path.empty() || path == "-") {
    std::cout << text;
    return;
  }
  const std::string temporary = path + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary);
    if (!file) throw InputError("cannot write " + path);
    file << text;
    if (!file) throw InputError("cannot write " + path);
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) throw InputError("cannot write " + path);
}

int run(int argc, char** argv) {
  CLI::App app{"kinema: velocity and acceleration analysis of mechanisms from vector loops"};
  app.require_subcommand(1);
  std::string file, output_path, format = "table", sweep;
  std::vector<std::string> angles;

  auto* derive_cmd = app.add_subcommand("derive", "print the symbolic derivation");
  derive_cmd->add_option("FILE", file, "mechanism file (TOML)")->required();
  derive_cmd->add_option("-o,--output", output_path, "write to this file instead of stdout");
  std::string derive_format = "text";
  derive_cmd->add_option("--format", derive_format, "text, or latex (an align* block for notes)")
      ->check(CLI::IsMember({"text", "latex"}));

  auto* eval_cmd = app.add_subcommand("eval", "evaluate positions, velocities and accelerations");
  eval_cmd->add_option("FILE", file, "mechanism file (TOML)")->required();
  eval_cmd->add_option("--angle,--at", angles,
                       "input value (deg for a crank, output length unit for a slider; or with a "
                       "unit, e.g. \"30 deg\"); repeat for a list");
  eval_cmd->add_option("--sweep", sweep, "start:stop:step in the same units, e.g. 0:360:1");
  eval_cmd->add_option("--format", format, "table, csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  eval_cmd->add_option("-o,--output", output_path, "write to this file instead of stdout");
  unsigned threads = 1;
  eval_cmd->add_option("--threads", threads, "threads for long sweeps (the branch is kept)")
      ->check(CLI::Range(1u, 256u));

  bool fragment = false;
  auto* latex_cmd = app.add_subcommand("latex", "write a worked solution in LaTeX (drawing, equations, plots)");
  latex_cmd->add_option("FILE", file, "mechanism file (TOML)")->required();
  latex_cmd->add_option("--angle,--at", angles, "input value(s) to work out, as for eval");
  latex_cmd->add_option("-o,--output", output_path, "write to this file instead of stdout");
  latex_cmd->add_flag("--fragment", fragment, "no preamble, for \\input into existing notes");

  std::string namespace_name;
  auto* codegen_cmd = app.add_subcommand("codegen", "write a standalone C++ header (position, velocity, acceleration)");
  codegen_cmd->add_option("FILE", file, "mechanism file (TOML)")->required();
  codegen_cmd->add_option("-o,--output", output_path, "header to write, e.g. four_bar.hpp")->required();
  codegen_cmd->add_option("--namespace", namespace_name, "namespace of the generated code (default: the header's name)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  Model model = load_model(file);
  const Mechanism& m = model.mechanism;
  std::ostringstream out;

  if (derive_cmd->parsed()) {
    if (derive_format == "latex") print_derivation_latex(out, m, model.derivation);
    else print_derivation_text(out, m, model.derivation);
    write_output(out.str(), output_path);
    return 0;
  }

  if (codegen_cmd->parsed()) {
    if (namespace_name.empty()) {
      std::string stem = output_path.substr(output_path.find_last_of('/') + 1);
      namespace_name = cpp_identifier(stem.substr(0, stem.find('.')));
    } else if (cpp_identifier(namespace_name) != namespace_name) {
      throw InputError("--namespace \"" + namespace_name + "\" is not a C++ identifier");
    }
    write_cpp_header(out, model, namespace_name);
    write_output(out.str(), output_path);
    return 0;
  }

  std::vector<double> inputs;
  for (const std::string& angle : angles) inputs.push_back(parse_input_value(m, angle));

  if (latex_cmd->parsed()) {
    if (inputs.empty()) inputs = m.input.values;
    if (inputs.empty()) {
      throw InputError(m.source_file + ": no input value: give --angle VALUE or value = \"...\" under [input]");
    }
    const auto at_values = analyse(*model.kinematics, inputs, m.input.rate, m.input.second_rate);
    for (const MotionState& s : at_values) {
      if (s.status == Status::unassembled) throw AssemblyError(m.source_file + ": " + s.message);
    }
    // The plots: a revolution for a crank, the neighbourhood of the values for a slider.
    std::vector<double> range;
    if (m.input.dimension == Dimension::angle) {
      for (int i = 0; i <= 180; ++i) range.push_back(inputs.front() + 2 * M_PI * i / 180.0);
    } else {
      const double span = model.kinematics->length_scale();
      for (int i = 0; i <= 200; ++i) range.push_back(inputs.front() - span / 2 + span * i / 200.0);
    }
    const auto sweep = analyse(*model.kinematics, range, m.input.rate, m.input.second_rate);
    print_latex_document(out, m, model.derivation, at_values, sweep, fragment);
    write_output(out.str(), output_path);
    return 0;
  }
  const bool is_sweep = !sweep.empty() || (inputs.empty() && m.input.values.size() > 1);
  if (!sweep.empty()) {
    const double unit = m.input.dimension == Dimension::angle ? M_PI / 180.0 : m.output.length_factor;
    for (double v : parse_sweep(sweep, unit)) inputs.push_back(v);
  }
  if (inputs.empty()) inputs = m.input.values;
  if (inputs.empty()) {
    throw InputError(m.source_file + ": no input value: give --angle VALUE or --sweep START:STOP:STEP, "
                     "or value = \"...\" under [input]");
  }

  const auto states = analyse(*model.kinematics, inputs, m.input.rate, m.input.second_rate, threads);
  std::size_t failures = 0;
  int status = 0;
  for (const MotionState& s : states) {
    if (s.status == Status::ok) continue;
    ++failures;
    if (!is_sweep) {
      std::cerr << "kinema: error: " << m.source_file << ": " << s.message << "\n";
      status = std::max(status, s.status == Status::singular ? SingularPositionError("").exit_status()
                                                             : AssemblyError("").exit_status());
    }
  }
  if (status != 0) return status;  // nothing printed for a failed list of values
  if (failures > 0) {
    std::cerr << "kinema: warning: " << failures << " of " << states.size()
              << " input values have no rates (status singular or unassembled in the output)";
    for (const MotionState& s : states)
      if (s.status != Status::ok) {
        std::cerr << "; first: " << s.message;
        break;
      }
    std::cerr << "\n";
  }
  if (format == "csv") print_results_csv(out, m, model.derivation, states);
  else if (format == "json") print_results_json(out, m, model.derivation, states);
  else print_results_table(out, m, model.derivation, states);
  write_output(out.str(), output_path);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const kinema::Error& error) {
    std::cerr << "kinema: error: " << error.what() << "\n";
    return error.exit_status();
  } catch (const std::exception& error) {
    std::cerr << "kinema: internal error: " << error.what() << "\n";
    return 1;
  }
}
