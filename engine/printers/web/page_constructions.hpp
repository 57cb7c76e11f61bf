// The page's constructions of every row as JSON data: the velocity and acceleration
// polygons and the instant centres with their Kennedy lines, from the analysis
// (ViewNeeds::motion). Rows share the structure of their constructions (names, kinds,
// which centres a Kennedy line joins), given once in a list; each row gives only its
// coordinates, so that a long run's page stays small.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/analysis/analysis.hpp"

namespace kinema {

/// Where each planar point's velocity and acceleration (x, then y) are among a row's CSV
/// fields, by the point's name.
using PointFields = std::map<std::string, std::pair<std::size_t, std::size_t>>;

/// {"polygon_structures", "centre_structures", "kennedy_sets", "rows"}: per row null (nothing to construct)
/// or {"polygons": two (velocity, acceleration) [structure, the x y of each vertex the
/// structure does not place (the pole is at 0; a named point's image is its velocity or
/// acceleration, the CSV field `point_fields` gives), then of each point a construction
/// adds; a structure's arrow names its ends by index into the vertices, then those], "centres":
/// [structure, Kennedy set (per centre, its lines: pairs of indices into the centres), each centre's x y unless the structure names the joint it is at (a unit
/// direction when at infinity; then the point it is seen from when the structure says so)]}. Lengths in the output unit (`per_unit` metres each), times in s.
/// With `centre_tape` (the model's layout, for a page whose sliders solve again) each centre
/// of a structure read from the tape (InstantCentres::tape_bodies: a vector-loop or a
/// joints-and-links file's) also says where its values are among the drawing stage's outputs ("tape": the offset of its N and D, the sign to read them with, its two
/// bodies' angular velocities' offsets, the offsets of the points it is seen from; -1 for
/// ground's and the origin), and "centre_parallel_tolerance" is kCentreParallelTolerance:
/// the page finds a solved row's centres as the analysis does, from the same outputs.
/// Each coordinate is written zero at its scale (zero_at_scale): a polygon's at its
/// largest vertex's, a centre's at the larger of the drawing's joints and `size` (metres:
/// the mechanism's, ProblemScale), a direction's at 1.
nlohmann::ordered_json constructions_json(const std::vector<ValueAnalysis>& values, const MotionDrawing& drawing,
                                          double per_unit, const PointFields& point_fields,
                                          const TapeLayout* centre_tape = nullptr, double size = 0);

}  // namespace kinema
