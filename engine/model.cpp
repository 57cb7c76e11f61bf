#include "engine/model.hpp"

#include "chains/spatial_chain.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/constraints/formula_reader.hpp"  // formula_value: a formula parameter as the reader computes it
#include "engine/constraints/output_columns.hpp"  // check_column_names: the output columns named apart before any run
#include "engine/numeric/assemblies.hpp"
#include "engine/numeric/sweep.hpp"
#include "readers/mechanism_file.hpp"
#include "linkages/linkage_loops.hpp"
#include "loops/planar_loops.hpp"

namespace kinema {

ConstraintSystem build_constraint_system(const Mechanism& mechanism) {
  ConstraintSystem system = mechanism.chain     ? build_spatial_system(mechanism)
                            : mechanism.linkage ? build_linkage_system(mechanism)
                                                : build_planar_loops(mechanism);
  settle_assemblies(system);
  return system;
}

Model make_model(const Mechanism& mechanism, DerivationScope scope) {
  Model model;
  model.system = build_constraint_system(mechanism);
  check_column_names(model.system);
  model.derivation = derive(model.system, scope);
  model.kinematics = Kinematics(model.system, model.derivation);
  return model;
}

namespace {

// A value as a file would write it, for the documents that show a parameter's text.
std::string si_text(double value, Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return format_round_trip(value) + " m";
    case Dimension::angle: return format_round_trip(to_degrees(value)) + " deg";
    default: return format_round_trip(value);
  }
}

// Sets the parameters to the values, then each formula parameter from the earlier ones,
// and the length scale, as reading the edited file would.
void set_parameter_values(ConstraintSystem& system, const std::vector<std::pair<std::string, double>>& values) {
  for (const auto& [name, value] : values) {
    SystemParameter& p = system.parameters[written_parameter_index(system, name)];
    if (!std::isfinite(value)) {
      throw InputError(system.source_file + ": parameter \"" + name + "\" = " + format_significant(value) +
                       " is not a finite number");
    }
    p.value = value;
    p.text = si_text(value, p.dimension);
    p.formula.reset();  // given a value, as a file would write it
  }
  GiNaC::exmap known;
  for (SystemParameter& p : system.parameters) {
    if (p.formula) {
      p.value = formula_value(*p.formula, known, p.where.str() + ": parameter \"" + p.symbol.get_name() + "\"",
                              p.text, " (only earlier parameters can be used)");
    }
    known[p.symbol] = p.value;
  }
  system.length_scale = length_scale_of(system.parameters);
}

// The closed-form dyad positions of a joints file keep the file's dimensions: refused
// where the sketch gave parameters, else dropped (Newton solves the same loops).
void drop_closed_form(ConstraintSystem& system) {
  if (!system.plan) return;
  std::string made;
  for (const SystemParameter& p : system.parameters)
    if (!p.written) made += (made.empty() ? "" : ", ") + p.symbol.get_name();
  if (!made.empty()) {
    throw InputError(system.source_file + ": other parameter values cannot be given to this joints file without "
                     "reading it again: kinema took " + made + " from its sketch; edit the file and load it");
  }
  system.plan->closed_form = false;
}

}  // namespace

Model with_parameters(const Model& model, const std::vector<std::pair<std::string, double>>& values) {
  Model copy;
  copy.system = model.system;
  set_parameter_values(copy.system, values);
  drop_closed_form(copy.system);
  copy.derivation = model.derivation;  // GiNaC expressions are shared, not copied
  copy.kinematics = model.kinematics.sharing_tape(copy.system);
  return copy;
}

Model load_model(const std::filesystem::path& path, DerivationScope scope) {
  return make_model(read_mechanism_file(path.string()), scope);
}

MotionTable solve_motion(const Model& model, const std::vector<double>& inputs, const MotionOptions& options) {
  SweepSettings settings;
  settings.rate = options.rate.value_or(model.system.input.rate_value);
  settings.second_rate = options.second_rate.value_or(model.system.input.second_rate_value);
  settings.threads = options.threads;
  settings.simd = options.simd;
  return solve_sweep(model.kinematics, inputs, settings);
}

Workspace::Workspace(const Model& model) : Workspace(model.kinematics) {}

}  // namespace kinema
