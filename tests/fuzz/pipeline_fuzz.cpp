// libFuzzer target: the whole pipeline as `kinema` runs it on a file — read,
// build the constraint system, derive, compile, analyse a few input values and
// a short range, then every printer of every kind, and the range streamed. A file may be refused
// (kinema::Error, which the CLI prints with its exit status); any other exception
// is an "internal error" and stops the fuzzer, as do crashes, runs over the
// -timeout and memory over -rss_limit_mb (tests/fuzz/run_fuzzers.sh sets both).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/base/errors.hpp"
#include "engine/model.hpp"
#include "engine/numeric/circuit.hpp"
#include "engine/printers/printer.hpp"
#include "engine/run/results_stream.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/analysis/plot_range.hpp"
#include "readers/mechanism_file.hpp"
#include "chains/spatial_chain.hpp"
#include "engine/run/results_stream.hpp"

namespace {

using namespace kinema;

void print_everything(const Model& model, const MotionTable& values, const MotionTable& range) {
  for (PrintKind kind : {PrintKind::derivation, PrintKind::results, PrintKind::document, PrintKind::code}) {
    for (const std::string& name : printer_names(kind)) {
      PrintJob job{model, &values, &range};
      job.code_namespace = "fuzz";
      std::ostringstream out;
      kinema::print_view(*find_printer(kind, name), out, job);
      job.fragment = true;
      if (kind == PrintKind::document) kinema::print_view(*find_printer(kind, name), out, job);
    }
  }
}

// The file's first few input values, or one if it gives none.
std::vector<double> first_values(const ConstraintSystem& system) {
  std::vector<double> values = system.input.values;
  if (values.size() > 4) values.resize(4);
  if (values.empty()) values = {0.5};
  return values;
}

// A spatial chain whose input is time, run as --input VARIABLE does with each driven
// variable in turn (the rows, the derivation and the worked solution).
void chain_by_its_variables(const std::string& text) {
  try {
    const Mechanism file = read_mechanism_text(text, "fuzz.toml");
    if (!file.chain || !file.chain->input.empty()) return;
    for (const ChainVariable& variable : file.chain->variables) {
      if (variable.unknown) continue;
      Mechanism mechanism = file;
      mechanism.chain->input = variable.name;
      try {
        const Model model = make_model(mechanism);
        const std::vector<double> inputs = first_values(model.system);
        const MotionTable values = solve_motion(model, inputs);
        print_everything(model, values, values);
      } catch (const kinema::Error&) {
        // An input without a rate, or with a second rate while others follow: refused.
      }
    }
  } catch (const kinema::Error&) {
  } catch (const std::exception&) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 16 * 1024) return -1;  // a mechanism is a few hundred bytes; keep runs short
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Mechanism mechanism = read_mechanism_text(text, "fuzz.toml");
    if (mechanism.chain) {  // a spatial chain: the library's front end, every point at the instant
      const SpatialKinematics chain = build_spatial_chain(mechanism);
      const GiNaC::exmap instant = chain.instant();
      try {
        for (const ChainPointMotion& point : chain.points)
          for (const auto* vector : {&point.position, &point.velocity, &point.acceleration})
            for (const GiNaC::ex& component : *vector) (void)GiNaC::evalf(component.subs(instant));
      } catch (const std::domain_error&) {
        // GiNaC's own refusal, in this harness's substitution: a motion with no rate at the
        // instant (abs(t) at t = 0). kinema's derive reports it as status 4 (checked below).
      }
    }
    // What kinema eval does: a model derived for evaluation only, its values in every
    // results format as streamed. Then the full derivation and everything printed from it.
    {
      const Model evaluation = make_model(mechanism, DerivationScope::evaluation);
      const std::vector<double> values = first_values(evaluation.system);
      for (const std::string& name : printer_names(PrintKind::results)) {
        StreamSettings settings;
        settings.printer = find_results_printer(name);
        std::size_t bytes = 0;
        settings.write = [&](std::string_view text) { bytes += text.size(); };
        stream_results(evaluation, InputValues(values), {}, settings);
      }
    }
    const Model model = make_model(mechanism);
    // A chain worked out at the instant along its last frame's axes (derive --basis).
    if (is_driven_chain(model.system)) (void)chain_at_instant(model.system, model.system.frames.back().name);
    const std::vector<double> inputs = first_values(model.system);
    const MotionTable values = solve_motion(model, inputs);
    // Every fifth value of the worked solution's plot range: the same code, a fifth of the time.
    std::vector<double> range;
    const std::vector<double> full = plot_range(model.system, inputs.front());
    for (std::size_t i = 0; i < full.size(); i += 5) range.push_back(full[i]);
    const MotionTable over_range = solve_motion(model, range);
    print_everything(model, values, over_range);
    // The range again as kinema eval streams it: small blocks, formatted on two threads.
    for (const std::string& name : printer_names(PrintKind::results)) {
      StreamSettings settings;
      settings.printer = find_results_printer(name);
      settings.threads = 2;
      settings.block_rows = 7;
      std::size_t bytes = 0;
      settings.write = [&](std::string_view text) { bytes += text.size(); };
      stream_results(model, InputValues(range), {}, settings);
    }
    // Joints and links: the circuit through the toggles (kinema eval --circuit), coarse.
    if (model.kinematics.closed_form() != nullptr) {
      CircuitSettings circuit_settings;
      circuit_settings.start = inputs.front();
      circuit_settings.step = model.system.input.dimension == Dimension::angle ? 0.1 : 0.05 * model.system.length_scale;
      circuit_settings.rate = model.system.input.rate_value;
      circuit_settings.max_rows = 2000;
      const Circuit circuit = solve_circuit(model.kinematics, circuit_settings);
      for (const std::string& name : printer_names(PrintKind::results)) {
        PrintJob job{model, &circuit.table};
        job.circuit = circuit.stop == Circuit::Stop::closed;
        std::ostringstream out;
        kinema::print_view(*find_printer(PrintKind::results, name), out, job);
      }
    }
  } catch (const kinema::Error&) {
    // Refused or reported: what should happen to a bad file or an unassemblable value.
  } catch (const std::exception&) {
    std::abort();
  }
  chain_by_its_variables(text);
  return 0;
}
