#include <kinema/engine/model.hpp>

namespace kinema {

Model make_model(Mechanism mechanism) {
  Model model;
  model.mechanism = std::move(mechanism);
  model.derivation = derive(model.mechanism, build_loop_closure(model.mechanism));
  model.kinematics = std::make_unique<Kinematics>(model.mechanism, model.derivation);
  return model;
}

Model load_model(const std::string& path) { return make_model(read_mechanism_file(path)); }

}  // namespace kinema
