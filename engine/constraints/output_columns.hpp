// The output of a system: its columns, each with a name and a unit in the units the
// file asks for (OutputScale), listed once for every view (CSV, npy, JSON, the tables,
// the worked solution). The names are the system's: make_model checks them apart
// (check_column_names) before anything runs, so that no data tool meets two columns of
// one name. Values for the columns: engine/analysis/output_scale.hpp.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "engine/constraints/constraint_system.hpp"

namespace kinema {

/// SI values converted to the output units the file asks for (lengths in its unit,
/// angles in degrees), the same for every format.
struct OutputScale {
  explicit OutputScale(const ConstraintSystem& system);
  double length;  ///< SI metres per output length unit.
  std::string length_unit;
  Dimension input_dimension;
  /// Coordinate value in output units (angles in deg, wrapped to (-180, 180]).
  double coordinate(Dimension dimension, double si) const;
  /// Coordinate value in output units, angles not wrapped (continuous curves, inputs).
  double unwrapped(Dimension dimension, double si) const;
  double input(double si) const { return unwrapped(input_dimension, si); }
  double rate(Dimension dimension, double si) const;  ///< rad/s or length/s (also for second rates)
  std::string coordinate_unit(Dimension dimension) const;
  std::string rate_unit(Dimension dimension) const;
  std::string second_rate_unit(Dimension dimension) const;
};

/// A column of the tabular formats (CSV, npy): its name and output unit, and the kind of
/// quantity it holds (a length, an angle or a number, differentiated `order` times): the
/// views of numbers for people show its values at the problem's size for that kind.
struct ResultColumn {
  std::string name, unit;
  Dimension dimension = Dimension::number;
  int order = 0;
};

/// The value columns of one row, in order: input, its rate and second rate; each
/// unknown with its rate and second rate; each point's position, velocity, speed,
/// acceleration and its magnitude; for spatial chains, each frame's angular velocity and
/// angular acceleration (x, y, z in the observer's basis); for joints and links, each slider block's angle and
/// rates (its guide's turning), then each slider's relative velocity, relative
/// acceleration and Coriolis acceleration (x, y), each guide point's velocity and
/// acceleration (x, y; guide_points), each relative turning's rate and second rate
/// (relative_turnings); along a circuit, each dyad's assembly
/// sign (+1 or -1, "branch_" and its inner joint). The first kInputColumns are the input's.
std::vector<ResultColumn> result_columns(const ConstraintSystem& system, const OutputScale& scale,
                                         bool circuit = false);
constexpr std::size_t kInputColumns = 3;

/// Throws InputError (file:line, both names, "rename one of them") when two result
/// columns, a circuit's among them, would have one name: data tools refuse or
/// silently merge such columns (npy fields, JSON keys of points, CSV headers).
void check_column_names(const ConstraintSystem& system);

/// How many columns result_columns gives (without naming them).
std::size_t result_column_count(const ConstraintSystem& system, bool circuit = false);

/// Joints and links solved in closed form: the inner joint of each dyad, in solving
/// order (what names its assembly sign); else empty.
std::vector<std::string> dyad_inner_joints(const ConstraintSystem& system);

/// Where the joints-and-links columns (blocks, sliders, guide points, relative turnings) begin in result_columns (after
/// the points and frames).
std::size_t linkage_columns_begin(const ConstraintSystem& system);

/// Joints and links: the links that are slider blocks (bodies of SolvingPlan) and the
/// name of each one's angle, in the order of their columns.
std::vector<std::pair<std::size_t, std::string>> block_links(const ConstraintSystem& system);

/// Joints and links: at a slider on a moving guide, the guide's point where the slider is
/// now (the seed's v_B1: B on link 1), whose velocity and acceleration are the slider
/// point's without the sliding: v = v_S - v_rel, a = a_S - a_rel - 2 w x v_rel.
struct GuidePoint {
  std::size_t slider = 0;  ///< Index into SolvingPlan::sliders.
  std::size_t point = 0;   ///< Index into ConstraintSystem::points: the point that shows the slider.
  std::string name;        ///< The point's name and the guide's ("B" on link "1": "B1", on "crank": "B_crank").
};
std::vector<GuidePoint> guide_points(const ConstraintSystem& system);

/// Joints and links: at each pin of a slider block to a moving link, the block's turning
/// relative to that link (the seed's omega23 = omega2 - omega3, its alpha23).
struct RelativeTurning {
  std::size_t block = 0, other = 0;  ///< Bodies of SolvingPlan.
  std::size_t joint = 0;             ///< The pin (index into SolvingPlan::joints).
  std::string rate_name, second_rate_name;  ///< "omega23", "alpha23" (links 2 and 3).
};
std::vector<RelativeTurning> relative_turnings(const ConstraintSystem& system);

}  // namespace kinema
