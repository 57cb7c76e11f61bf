// The facade's door for kinema's own views beside it (the Python module): a facade
// over an engine model they loaded, and the engine model behind a facade, so that a
// view reads names and solves through the facade and formats through the engine's
// printers from one model. Not installed: a program sees <kinema/kinema.hpp> only.
#pragma once

#include <memory>

#include <kinema/kinema.hpp>

#include "engine/model.hpp"

namespace kinema {

struct MechanismModel::Engine {
  std::shared_ptr<const Model> model;
};

struct EngineAccess {
  static MechanismModel facade(std::shared_ptr<const Model> model);
  static const Model& model(const MechanismModel& facade);
};

}  // namespace kinema
