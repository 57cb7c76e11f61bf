// The kinema command: its subcommands and options, read and run over the library
// (engine/, loops/); main (cli/main.cpp) maps what it throws to an exit status.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>
#include <thread>

#include "engine/base/errors.hpp"
#include "engine/input_value.hpp"
#include "engine/model.hpp"
#include "engine/numeric/circuit.hpp"
#include "engine/printers/code/cpp_header.hpp"
#include "engine/printers/printer.hpp"
#include "engine/run/circuit_run.hpp"
#include "engine/run/results_stream.hpp"
#include "engine/run/view.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/analysis/design_study.hpp"
#include "engine/printers/data/study_table.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/analysis/sensitivities.hpp"
#include "engine/constraints/solving_plan.hpp"
#include "engine/base/user_text.hpp"
#include "engine/symbolic/dyad_method.hpp"
#include "linkages/vector_loop_file.hpp"
#include "readers/mechanism_file.hpp"

#include "cli/check_command.hpp"
#include "cli/exit_status.hpp"
#include "cli/output_file.hpp"
#include "cli/problems_command.hpp"
#include "cli/progress_line.hpp"
#include "cli/run.hpp"
#include "cli/usage.hpp"
#include "engine/base/units.hpp"

#ifndef KINEMA_VERSION
#error "KINEMA_VERSION (the project version) must be defined by the build"
#endif

namespace {

using namespace kinema;
using kinema_cli::write_output;  // output is built in memory and written at the end: an error leaves nothing

// The printer of that kind and name (the command line's own check named the choices).
const Printer& printer(PrintKind kind, const std::string& name) {
  const Printer* found = find_printer(kind, name);
  if (!found) throw InputError("no output format \"" + name + "\"");
  return *found;
}

// A circuit as the command line asks for it (engine/run/circuit_run words its messages so).
const CircuitAsked kCommandLineCircuit{"--circuit", "--circuit 1", "--angle"};

// Rows a page holds: each is drawn and plotted in the browser, and the file grows by about a
// kilobyte a row. A circuit on a page is held to them too.
constexpr std::size_t kMaxPageRows = 20000;
const CircuitAsked kPageCircuit{"--circuit", "--circuit 1", "--angle", kMaxPageRows, "a page"};

const ResultsPrinter& results_printer(const std::string& format) {
  const ResultsPrinter* found = find_results_printer(format);
  if (!found) throw InputError("no output format \"" + format + "\"");
  return *found;
}

// kinema eval --circuit: the whole circuit solved, then printed a block of rows at a time.
void write_circuit(const Model& model, const std::string& step_text, const std::vector<double>& inputs,
                   const std::string& format, int precision, const std::string& output_path,
                   const Sensitivities* sensitivities) {
  Circuit circuit = solve_circuit_from(model, step_text, inputs, kCommandLineCircuit);
  const ResultsPrinter* results = &results_printer(format);
  PrintJob job{model, &circuit.table};
  job.circuit = true;
  job.precision = precision;
  if (sensitivities) {
    sensitivities->fill(circuit.table);
    job.sensitivities = &sensitivities->columns();
  }
  const Analysis analysis = analyse_for_printer(*results, job);  // what the head shows, once
  job.analysis = &analysis;
  kinema_cli::Output output(output_path);
  const std::size_t rows = circuit.table.size();
  std::string text;
  results->head(text, job, rows);
  for (std::size_t first = 0; first < rows; first += 1024) {
    results->rows(text, job, circuit.table, first, std::min(rows, first + 1024), first);
    output.write(text);
    text.clear();
  }
  results->tail(text, job, rows);
  output.write(text);
  output.commit();
}

// --sweep START:STOP:STEP in the input's units (deg, s, or the output length unit).
InputValues sweep_values(const ConstraintSystem& m, const std::string& sweep, std::size_t max_values) {
  const double unit = m.input.dimension == Dimension::angle  ? kRadiansPerDegree
                      : m.input.dimension == Dimension::time ? 1.0
                                                             : m.output.length_factor;
  return parse_sweep(sweep, unit, max_values);
}


// kinema page: the rows solved once (a sweep, a circuit, or by default the worked solution's
// plotting range: a turn of a crank from the file's value), then the page printed over them.
void write_page_file(const Model& model, const std::string& sweep, const std::string& circuit_step,
                     const std::vector<double>& inputs, const std::string& output_path) {
  const ConstraintSystem& m = model.system;
  std::optional<Circuit> circuit;
  MotionTable swept;
  if (!circuit_step.empty()) {
    circuit = solve_circuit_from(model, circuit_step, inputs, kPageCircuit);
  } else {
    if (!sweep.empty() && !inputs.empty()) throw InputError("page: give --sweep or --angle (the start of the default turn), not both");
    const double first = !inputs.empty() ? inputs.front() : m.input.values.empty() ? 0.0 : m.input.values.front();
    const std::vector<double> values = sweep.empty() ? plot_range(m, first) : sweep_values(m, sweep, kMaxPageRows).to_vector();
    check_input_range(m, values);
    swept = solve_motion(model, values);
  }
  std::ostringstream out;
  print_page(out, model, circuit ? circuit->table : swept, circuit.has_value());
  write_output(out.str(), output_path);
}

// An option given an empty value ("-o ''", a shell variable that was not set) is a
// mistake, not the option left out: it would have meant stdout, the file's input, ...
const CLI::Validator kNotEmpty(
    [](std::string& value) { return value.empty() ? std::string("an empty value; give one or leave the option out") : std::string(); },
    "");

// Every command takes a file in any of the three forms; its help says so.
const char* const kFileHelp =
    "mechanism file (TOML) written as vector loops, as joints and links, or as a spatial chain of frames";

// kinema eval of a list of values (--angle, or the file's one value): all or nothing,
// so solved once as one table, every value's failure reported, and printed only if
// every value is assembled and regular.
int write_list(const Model& model, const InputValues& inputs, const std::string& format, int precision,
               const std::string& output_path, const Sensitivities* sensitivities) {
  const ConstraintSystem& m = model.system;
  MotionTable table = solve_motion(model, inputs.to_vector());
  int status = 0;
  for (const MotionState& state : table) {
    if (state.status == Status::ok) continue;
    std::cerr << "kinema: error: " << terminal_text(m.source_file + ": " + describe_failure(m, state.input, state.failure))
              << "\n";
    // A point's formula without a number there is the file's, not a singular position.
    const int row = state.failure.kind == Failure::Kind::point_undefined ? kinema_cli::status::bad_input
                    : state.status == Status::singular                   ? kinema_cli::status::singular
                                                                         : kinema_cli::status::unassembled;
    status = std::max(status, row);
  }
  if (status != 0) return status;
  PrintJob job{model, &table};
  job.precision = precision;
  if (sensitivities) {
    sensitivities->fill(table);
    job.sensitivities = &sensitivities->columns();
  }
  std::ostringstream out;  // a value past the output unit's range throws here, before anything is written
  print_view(results_printer(format), out, job);
  write_output(out.str(), output_path);
  return 0;
}

// The command line as parsed: the subcommand given and every option's value.
struct CommandLine {
  CLI::App* derive = nullptr;
  CLI::App* eval = nullptr;
  CLI::App* latex = nullptr;
  CLI::App* codegen = nullptr;
  CLI::App* loops = nullptr;
  CLI::App* page = nullptr;
  std::string file, output_path, format = "table", sweep, derive_format = "text", method = "loops";
  std::vector<std::string> angles, vary;
  std::vector<std::string> sensitivities;  // eval --sensitivity: "b" or "omega3:b"
  int precision = 0;
  unsigned threads = 0;  // one per core: formatting on more threads changes no byte
  std::string circuit_step, namespace_name, chain_input, basis;
  std::string page_sweep, page_circuit;
  bool quiet = false, fragment = false;
  kinema_cli::CheckLine check;
};

// Every subcommand with its options, their values read into `line`.
void add_subcommands(CLI::App& app, CommandLine& line) {
  line.derive = app.add_subcommand("derive", "print the symbolic derivation");
  line.derive->add_option("FILE", line.file, kFileHelp)->required();
  line.derive->add_option("-o,--output", line.output_path, "write to this file instead of stdout");
  line.derive->add_option("--format", line.derive_format, "text, or latex (an align* block for notes)")
      ->check(CLI::IsMember(printer_names(PrintKind::derivation)));
  const std::string method_help =
      "loops (the loop equations in matrix form), or for joints and links dyad by dyad as the seeds work "
      "them out: relative-velocity (v_C = v_B + omega x r_BC = ...) or joint-coordinates (the joints on "
      "circles and guide lines, differentiated)";
  line.derive->add_option("--method", line.method, method_help)->check(CLI::IsMember(method_names()));

  CLI::App* eval = line.eval = app.add_subcommand("eval", "evaluate positions, velocities and accelerations");
  eval->add_option("FILE", line.file, kFileHelp)->required();
  eval->add_option("--angle,--at", line.angles,
                   "input value (deg for a crank, output length unit for a slider; or with a "
                   "unit, e.g. \"30 deg\"); repeat for a list");
  eval->add_option("--sweep", line.sweep, "start:stop:step in the same units, e.g. 0:360:1");
  eval->add_option("--format", line.format, "table, csv, json, or npy (a NumPy structured array)")
      ->check(CLI::IsMember(printer_names(PrintKind::results)));
  eval->add_option("-o,--output", line.output_path, "write to this file instead of stdout");
  eval->add_option("--precision", line.precision,
                   "significant digits in table, csv and json (default: 6 in the table, 12 in csv, "
                   "round-trip in json)")
      ->check(kNotEmpty)  // before the range, whose message would not say what is wrong
      ->check(CLI::Range(1, 17));
  eval->add_option("--threads", line.threads,
                   "threads formatting and writing the output of long runs, a block each in turn (default: "
                   "one per core); the solve stays serial, so the output is the same bytes whatever the count; with --vary, "
                   "threads solving the designs (each design alone: the same rows whatever the count)")
      ->check(kNotEmpty)
      ->check(CLI::Range(1u, 256u));
  eval->add_option("--circuit", line.circuit_step,
                   "joints and links: follow the motion through its toggles, where the input reverses and a "
                   "dyad changes assembly, from the file's value (or one --angle) until it closes; rows every "
                   "STEP of the input (as --angle: deg or the length unit), e.g. --circuit 1")
      ->option_text("STEP")
      ->excludes(eval->get_option("--sweep"));
  eval->add_option("--vary", line.vary,
                   "a design study: NAME=FIRST:LAST:STEP, a parameter the file writes over a range (in the file's "
                   "units, or each with its unit, e.g. b=110:130:1 or \"b=0.11 m:0.13 m:1 mm\"); repeat for a grid "
                   "of every combination. One row per design of its figures over the run (Grashof class, least "
                   "transmission angle, time ratio, whether every value assembles, largest rates and point speeds "
                   "and accelerations), as csv, json or npy")
      ->option_text("NAME=RANGE")
      ->excludes(eval->get_option("--circuit"));
  eval->add_option("--sensitivity", line.sensitivities,
                   "the derivative of output columns in a parameter, derived exactly: PARAMETER for every column "
                   "that has one (unknowns, rates, second rates, points, frames), or COLUMN:PARAMETER for one, e.g. "
                   "--sensitivity b or --sensitivity omega3:b; adds the columns d_COLUMN_d_PARAMETER in the column's "
                   "unit per the parameter's (rad/s/mm); repeat for more")
      ->option_text("[COLUMN:]PARAMETER")
      ->allow_extra_args(false);
  eval->add_flag("-q,--quiet", line.quiet, "no progress line and no warnings on stderr (errors still)");

  line.latex = app.add_subcommand("latex", "write a worked solution in LaTeX (drawing, equations, plots)");
  line.latex->add_option("FILE", line.file, kFileHelp)->required();
  line.latex->add_option("--angle,--at", line.angles, "input value(s) to work out, as for eval");
  line.latex->add_option("-o,--output", line.output_path, "write to this file instead of stdout");
  line.latex->add_flag("--fragment", line.fragment, "no preamble, for \\input into existing notes");
  line.latex->add_option("--method", line.method, method_help)->check(CLI::IsMember(method_names()));

  line.codegen = app.add_subcommand("codegen", "write a standalone C++ header (position, velocity, acceleration)");
  line.codegen->add_option("FILE", line.file, kFileHelp)->required();
  line.codegen->add_option("-o,--output", line.output_path, "header to write, e.g. four_bar.hpp")->required();
  line.codegen->add_option("--namespace", line.namespace_name,
                           "namespace of the generated code (default: the header's name)");

  CLI::App* page = line.page = app.add_subcommand(
      "page", "write one self-contained web page (HTML) with the mechanism animated over its solved rows, its "
              "readout and plots");
  page->add_option("FILE", line.file, kFileHelp)->required();
  page->add_option("--sweep", line.page_sweep, "start:stop:step of the input, as for eval (default: a turn of a crank "
                                               "from the file's value, 2 deg apart)");
  page->add_option("--circuit", line.page_circuit, "joints and links: follow the motion through its toggles, as for eval")
      ->option_text("STEP")
      ->excludes(page->get_option("--sweep"));
  page->add_option("--angle,--at", line.angles, "the value a circuit or the default turn starts from, as for eval");
  page->add_option("-o,--output", line.output_path, "write to this file instead of stdout, e.g. mech.html");

  const std::string input_help =
      "spatial chains: a driven variable of [variables] as the input instead of time (--at and --sweep in its "
      "units; the other driven variables follow it), e.g. --input theta1";
  for (auto* command : {line.derive, line.eval, line.latex, line.codegen, line.page})
    command->add_option("--input", line.chain_input, input_help)->option_text("VARIABLE");
  for (auto* command : {line.derive, line.latex}) {
    command->add_option("--basis", line.basis,
                        "spatial chains: give the worked-out vectors along this frame's axes (default: the "
                        "observer's), e.g. --basis E2")
        ->option_text("FRAME");
  }

  line.loops = app.add_subcommand(
      "loops", "write the mechanism as a vector-loop file (for joints and links: the loops kinema found)");
  line.loops->add_option("FILE", line.file,
                         "mechanism file (TOML) written as vector loops or as joints and links (a spatial chain "
                         "of frames has no vector loops)")->required();
  line.loops->add_option("-o,--output", line.output_path, "write to this file instead of stdout");

  kinema_cli::add_check_command(app, line.check);

  for (CLI::App* command : app.get_subcommands({})) {
    for (CLI::Option* option : command->get_options()) {
      if (!option->get_positional() && option->get_type_size() != 0) option->check(kNotEmpty);
    }
  }
}

// kinema latex works out each value on a page of its own: too many values are refused
// before any symbolic work (their plots sample the turn on their own).
void check_latex_values(std::size_t count, const std::string& where) {
  if (count <= kMaxLatexValues) return;
  throw InputError(where + ": kinema latex works out each input value on a results page of its own, and " +
                   std::to_string(count) + " values are more than " + std::to_string(kMaxLatexValues) +
                   "; give at most that many (--angle VALUE, or a coarser sweep in the file), or tabulate them with kinema eval " +
                   "(--sweep START:STOP:STEP, --format csv)");
}

// The mechanism file read, with what the command line changes in it (--input), after
// the checks that need no file (the output is not the file, and can be written).
Mechanism read_mechanism(const CommandLine& line) {
  std::error_code same_error;  // never replace the mechanism file with its own results
  if (!line.output_path.empty() && line.output_path != "-" &&
      std::filesystem::equivalent(line.file, line.output_path, same_error)) {
    throw InputError("-o " + line.output_path + " is the mechanism file itself; write the output to another file");
  }
  kinema_cli::check_output(line.output_path);  // as the shell refuses a > before it runs anything
  Mechanism mechanism = read_mechanism_file(line.file);
  if (!line.chain_input.empty()) {
    if (!mechanism.chain) {
      throw InputError(line.file + ": --input " + line.chain_input + " is for spatial chains (a file of [frames] and "
                       "[variables]); this file's input is set in the file");
    }
    mechanism.chain->input = line.chain_input;
    mechanism.chain->input_where = {};
  }
  if (line.latex->parsed()) {
    const std::vector<std::string>& angles = line.angles;
    check_latex_values(angles.empty() ? mechanism.input.values.size() : angles.size(),
                       angles.empty() && mechanism.input.where.line > 0 ? mechanism.input.where.str() : line.file);
  }
  return mechanism;
}

// --basis: for a chain driven by its joints, and a frame of it; refused before anything
// is worked out or written.
void check_basis(const ConstraintSystem& m, const CommandLine& line) {
  if (line.basis.empty()) return;
  if (!is_driven_chain(m)) {
    throw InputError(line.file + ": --basis " + line.basis + " is for spatial chains driven by their joints (worked out at " +
                     "the instant, vector by vector); " +
                     (m.frames.empty() ? "this file is not a chain of frames" : "this chain closes a loop and is printed as its equations"));
  }
  check_chain_basis(m, line.basis);
}

// kinema derive: the derivation in the format and method asked for.
int run_derive(const Model& model, const CommandLine& line) {
  PrintJob job{model};
  job.method = *find_method(line.method);
  check_method_applies(model.system, job.method);
  job.basis = line.basis;
  std::ostringstream out;
  print_view(printer(PrintKind::derivation, line.derive_format), out, job);
  write_output(out.str(), line.output_path);
  return 0;
}

// kinema codegen: the header, in the namespace given or named after the header's file.
int run_codegen(const Model& model, const CommandLine& line) {
  PrintJob job{model};
  if (line.namespace_name.empty()) {
    std::string stem = line.output_path.substr(line.output_path.find_last_of('/') + 1);
    job.code_namespace = cpp_identifier(stem.substr(0, stem.find('.')));
  } else if (cpp_identifier(line.namespace_name) != line.namespace_name) {
    throw InputError("--namespace \"" + line.namespace_name + "\" is not a C++ identifier (or is a C++ keyword or macro); try \"" +
                     cpp_identifier(line.namespace_name) + "\"");
  } else {
    job.code_namespace = line.namespace_name;
  }
  std::ostringstream out;
  print_view(printer(PrintKind::code, "cpp"), out, job);
  write_output(out.str(), line.output_path);
  return 0;
}

// kinema latex: the worked solution at the values asked for (or the file's), with plots
// over the input's range; refused if a value cannot be assembled.
int run_latex(const Model& model, const CommandLine& line, std::vector<double> inputs) {
  const ConstraintSystem& m = model.system;
  if (inputs.empty()) inputs = m.input.values;
  check_latex_values(inputs.size(), m.input.where.line > 0 ? m.input.where.str() : line.file);
  if (inputs.empty()) {
    throw InputError(m.source_file + ": no input value: give --angle VALUE or value = \"...\" under [input]");
  }
  check_input_range(m, inputs);
  const MotionTable at_values = solve_motion(model, inputs);
  for (const MotionState& s : at_values) {
    if (s.status == Status::unassembled) throw AssemblyError(m.source_file + ": " + describe_failure(m, s));
  }
  const MotionTable sweep_table = solve_motion(model, plot_range(m, inputs.front()));
  PrintJob job{model, &at_values, &sweep_table};
  job.fragment = line.fragment;
  job.method = *find_method(line.method);
  check_method_applies(model.system, job.method);
  job.basis = line.basis;
  std::ostringstream out;
  print_view(printer(PrintKind::document, "latex"), out, job);
  write_output(out.str(), line.output_path);
  return 0;
}

// The values kinema eval runs over: --sweep (after any --angle), the --angle list, or the
// file's values.
InputValues eval_inputs(const ConstraintSystem& m, const CommandLine& line, std::vector<double> inputs) {
  InputValues run_inputs;
  if (!line.sweep.empty()) {
    run_inputs = sweep_values(m, line.sweep, kMaxSweepValues);
    if (!inputs.empty()) {
      if (run_inputs.size() > kMaxValuesPerRun) {
        throw InputError("--sweep \"" + line.sweep + "\" with --angle: a list of more than " +
                         std::to_string(kMaxValuesPerRun) +
                         " values (held in memory); give the --sweep alone (streamed) or a larger step");
      }
      const std::vector<double> swept = run_inputs.to_vector();
      inputs.insert(inputs.end(), swept.begin(), swept.end());
      run_inputs = std::move(inputs);
    }
  } else {
    run_inputs = inputs.empty() ? m.input.values : std::move(inputs);
  }
  if (run_inputs.empty()) {
    throw InputError(m.source_file + ": no input value: give --angle VALUE or --sweep START:STOP:STEP, "
                     "or value = \"...\" under [input]");
  }
  check_input_range(m, run_inputs);
  return run_inputs;
}

// kinema eval over a --sweep (or the file's sweep): solved, formatted and written a block
// at a time, with a progress line; a file appears only when complete.
int write_sweep(const Model& model, const CommandLine& line, const InputValues& run_inputs,
                const Sensitivities* sensitivities) {
  StreamSettings settings;
  settings.sensitivities = sensitivities;
  settings.threads = line.threads > 0 ? line.threads : std::max(1u, std::thread::hardware_concurrency());
  kinema_cli::Output output(line.output_path);
  // Not when the results themselves scroll by on the same terminal.
  const bool results_on_terminal =
      (line.output_path.empty() || line.output_path == "-") && ::isatty(STDOUT_FILENO) == 1;
  kinema_cli::ProgressLine progress(!line.quiet && !results_on_terminal);
  settings.printer = &results_printer(line.format);
  settings.precision = line.precision;
  settings.write = [&](std::string_view text) { output.write(text); };
  settings.progress = [&](std::size_t done, std::size_t total) { progress.update(done, total); };
  const RunSummary summary = stream_results(model, run_inputs, {}, settings);
  output.commit();
  progress.finish();
  if (summary.failures > 0 && !line.quiet) {
    std::cerr << "kinema: warning: " << summary.failures << " of " << summary.values
              << " input values have no rates (status singular or unassembled in the output); first: "
              << terminal_text(describe_failure(model.system, summary.first_failure->input, summary.first_failure->failure))
              << "\n";
  }
  return 0;
}

// kinema eval --vary: the grid of designs, each solved over the run's values, a row of
// figures a design (computed by the engine, printed here as the format says).
int write_study(const Model& model, const CommandLine& line, const InputValues& run_inputs) {
  const ConstraintSystem& m = model.system;
  if (line.format != "csv" && line.format != "json" && line.format != "npy")
    throw InputError("--vary writes a row of figures a design as csv, json or npy; give --format csv (or json, npy)");
  std::vector<std::string> names;
  std::vector<std::vector<double>> axes;
  for (const std::string& vary : line.vary) {
    const std::size_t equals = vary.find('=');
    if (equals == std::string::npos || equals == 0)
      throw InputError("--vary \"" + vary + "\" is not NAME=FIRST:LAST:STEP (e.g. b=110:130:1)");
    names.push_back(vary.substr(0, equals));
    axes.push_back(parameter_range(m, names.back(), vary.substr(equals + 1)));
  }
  StudyOptions options;
  options.threads = line.threads > 0 ? line.threads : std::max(1u, std::thread::hardware_concurrency());
  const Designs designs = design_grid(names, axes);
  check_study_size(designs.size(), run_inputs.size(), "--vary");
  const StudyResults results = run_design_study(model, designs, run_inputs.to_vector(), options);
  write_output(print_study_table(study_columns(m, designs, results, StudyUnits::file), line.format, line.precision),
               line.output_path);
  return 0;
}

// kinema eval: along a circuit, over a list of values, or over a sweep; a design study with --vary.
int run_eval(const Model& model, const CommandLine& line, std::vector<double> inputs) {
  const ConstraintSystem& m = model.system;
  if (!line.vary.empty()) {
    if (!line.sensitivities.empty())
      throw InputError("--sensitivity adds columns to the rows of one design; --vary writes a row a design: give one of them");
    return write_study(model, line, eval_inputs(m, line, std::move(inputs)));
  }
  // --sensitivity: each parameter's derivatives derived and compiled here, once.
  std::optional<Sensitivities> sensitivities;
  if (!line.sensitivities.empty()) sensitivities.emplace(model, sensitivity_columns(m, line.sensitivities));
  const Sensitivities* derived = sensitivities ? &*sensitivities : nullptr;
  if (!line.circuit_step.empty()) {
    write_circuit(model, line.circuit_step, inputs, line.format, line.precision, line.output_path, derived);
    return 0;
  }
  // A --sweep alone is computed value by value (a run of 10^9 holds none of them).
  const bool is_sweep = !line.sweep.empty() || (inputs.empty() && m.input.values.size() > 1);
  const InputValues run_inputs = eval_inputs(m, line, std::move(inputs));
  if (!is_sweep) return write_list(model, run_inputs, line.format, line.precision, line.output_path, derived);
  return write_sweep(model, line, run_inputs, derived);
}

}  // namespace

int kinema_cli::run(int argc, char** argv) {
  CLI::App app{"kinema: velocity and acceleration analysis of mechanisms written as vector loops, as joints and "
               "links, or as spatial chains of frames",
               "kinema"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "kinema " KINEMA_VERSION, "print the version and exit");
  CommandLine line;
  add_subcommands(app, line);
  kinema_cli::ProblemsOptions problems;
  kinema_cli::add_problems_command(app, problems);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return kinema_cli::report_parse_error(app, error);  // help and version: 0; usage errors: one line, 2
  }
  if (line.check.command->parsed()) return kinema_cli::run_check(line.check);  // its FILE may be a class table

  if (problems.command->parsed()) return kinema_cli::run_problems(problems);
  const Mechanism mechanism = read_mechanism(line);
  // A file kinema cannot analyse is not written as loops either. Only derive, latex and
  // page print the formulas solved in closed form: the others do without them (faster).
  const bool prints_formulas = line.derive->parsed() || line.latex->parsed() || line.page->parsed();
  const Model model = make_model(mechanism, prints_formulas ? DerivationScope::full : DerivationScope::evaluation);
  check_basis(model.system, line);
  if (line.loops->parsed()) {
    write_output(vector_loop_file(mechanism, model.system), line.output_path);
    return 0;
  }
  if (line.derive->parsed()) return run_derive(model, line);
  if (line.codegen->parsed()) return run_codegen(model, line);
  std::vector<double> inputs;
  for (const std::string& angle : line.angles) inputs.push_back(parse_input_value(model.system, angle));
  if (line.page->parsed()) {
    write_page_file(model, line.page_sweep, line.page_circuit, inputs, line.output_path);
    return 0;
  }
  if (line.latex->parsed()) return run_latex(model, line, std::move(inputs));
  return run_eval(model, line, std::move(inputs));
}
