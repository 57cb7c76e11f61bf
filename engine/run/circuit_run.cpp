#include "engine/run/circuit_run.hpp"

#include <algorithm>
#include <cmath>

#include "engine/analysis/diagnostics.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/units.hpp"
#include "engine/input_value.hpp"

namespace kinema {

Circuit solve_circuit_from(const Model& model, const std::string& step_text, const std::vector<double>& inputs,
                           const CircuitAsked& asked) {
  const ConstraintSystem& m = model.system;
  const SolvingPlan* frames = model.kinematics.closed_form();
  if (frames == nullptr) {
    throw InputError(m.source_file + ": " + asked.step + " follows a mechanism described by joints and links whose links "
                     "all form dyads (solved in closed form); " +
                     (m.plan ? std::string("this one has a group that is not a dyad")
                                : std::string("this file is written as vector loops")));
  }
  CircuitSettings settings;
  try {
    settings.step = parse_input_value(m, step_text);
  } catch (const Error& error) {
    throw InputError(asked.step + " " + step_text + ": " + error.what());
  }
  if (!(settings.step > 0) || !std::isfinite(settings.step)) {
    throw InputError(asked.step + " " + step_text + ": the step must be a positive number, e.g. " + asked.example);
  }
  if (inputs.size() > 1) throw InputError(asked.step + " starts at one value: give one " + asked.start + " (or none: the file's)");
  if (inputs.empty() && m.input.values.empty()) {
    throw InputError(m.source_file + ": no input value to start the circuit at: give " + asked.start + " VALUE or value = "
                     "\"...\" under [input]");
  }
  settings.start = inputs.empty() ? m.input.values.front() : inputs.front();
  settings.rate = m.input.rate_value;
  settings.second_rate = m.input.second_rate_value;
  // Rows are bounded by the chain's size too, and a crank's turn that cannot fit in them is
  // refused before the walk (its rows would be computed first).
  const std::size_t unknowns = std::max<std::size_t>(1, m.unknowns.size());
  settings.max_rows = std::min(kMaxCircuitRows, kMaxCircuitRowUnknowns / unknowns);
  const bool holder_bound = asked.max_rows != 0 && asked.max_rows < settings.max_rows;
  if (holder_bound) settings.max_rows = asked.max_rows;
  const std::string bound_reason =
      holder_bound ? " rows " + asked.rows_holder + " may hold"
                   : " rows a circuit of " + std::to_string(unknowns) + " unknowns may have (" +
                         std::to_string(kMaxCircuitRowUnknowns) + " rows times unknowns: each row solves them all)";
  if (m.input.dimension == Dimension::angle && 2 * kPi / settings.step > double(settings.max_rows)) {
    throw InputError(asked.step + " " + step_text + ": a turn of the input is " +
                     std::to_string(static_cast<unsigned long long>(std::min(std::ceil(2 * kPi / settings.step), 1e18))) +
                     " rows, more than the " + std::to_string(settings.max_rows) + bound_reason +
                     "; give a step of at least " + format_significant(1.005 * 360.0 / double(settings.max_rows), 3) +
                     " deg");
  }
  const Circuit circuit = solve_circuit(model.kinematics, settings);
  switch (circuit.stop) {
    case Circuit::Stop::closed: break;
    case Circuit::Stop::start_open:
      throw AssemblyError(m.source_file + ": the circuit cannot start at " + describe_input(m, settings.start) + ": " +
                          describe_dyad(*m.plan, circuit.dyad) +
                          " cannot close there on the assembly of the sketch; give another " + asked.start);
    case Circuit::Stop::locked:
      throw AssemblyError(m.source_file + ": the circuit cannot move from " + describe_input(m, settings.start) +
                          ": " + describe_dyad(*m.plan, circuit.dyad) +
                          " is at a toggle on both sides (the mechanism is locked); check the lengths");
    case Circuit::Stop::too_many_rows:
      throw InputError(m.source_file + ": the circuit does not close within the " + std::to_string(settings.max_rows) +
                       bound_reason + ", at " + asked.step + " " + step_text + "; give a larger step");
  }
  return circuit;
}

}  // namespace kinema
