// The page's constructions of every row as JSON data: the velocity and acceleration
// polygons and the instant centres with their Kennedy lines, from the analysis
// (ViewNeeds::motion). Rows share the structure of their constructions (names, kinds,
// which centres a Kennedy line joins), given once in a list; each row gives only its
// coordinates, so that a long run's page stays small.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "engine/analysis/analysis.hpp"

namespace kinema {

/// {"polygon_structures", "centre_structures", "rows"}: per row null (nothing to construct)
/// or {"polygons": two (velocity, acceleration) [structure, each vertex's x y, then the x y
/// of each point a construction adds; a structure's arrow names its ends by index into these], "centres":
/// [structure, each centre's x y unless the structure names the joint it is at (a unit
/// direction when at infinity; then the point it is seen from when the structure says so)]}. Lengths in the output unit (`per_unit` metres each), times in s.
nlohmann::ordered_json constructions_json(const std::vector<ValueAnalysis>& values, const MotionDrawing& drawing,
                                          double per_unit);

}  // namespace kinema
