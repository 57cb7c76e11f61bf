#include "engine/model.hpp"

#include "chains/spatial_chain.hpp"
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

Model load_model(const std::filesystem::path& path, DerivationScope scope) {
  return make_model(read_mechanism_file(path.string()), scope);
}

MotionTable analyse(const Model& model, const std::vector<double>& inputs, const AnalysisOptions& options) {
  SweepSettings settings;
  settings.rate = options.rate.value_or(model.system.input.rate_value);
  settings.second_rate = options.second_rate.value_or(model.system.input.second_rate_value);
  settings.threads = options.threads;
  settings.simd = options.simd;
  return solve_sweep(model.kinematics, inputs, settings);
}

Workspace::Workspace(const Model& model) : Workspace(model.kinematics) {}

}  // namespace kinema
