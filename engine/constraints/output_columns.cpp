#include "engine/constraints/output_columns.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <map>

#include "engine/base/errors.hpp"
#include "engine/base/naming.hpp"

namespace kinema {

OutputScale::OutputScale(const ConstraintSystem& system)
    : length(system.output.length_factor),
      length_unit(system.output.length),
      input_dimension(system.input.dimension) {}

double OutputScale::coordinate(Dimension dimension, double si) const {
  if (dimension == Dimension::time) return si;
  if (dimension == Dimension::angle) {
    double degrees = to_degrees(si);
    if (degrees > -180.0 && degrees <= 180.0) return degrees;  // the common case, and exact
    degrees = std::remainder(degrees, 360.0);
    if (degrees <= -180.0) degrees += 360.0;
    return degrees;
  }
  return si / length;
}

double OutputScale::unwrapped(Dimension dimension, double si) const {
  if (dimension == Dimension::time) return si;
  return dimension == Dimension::angle ? to_degrees(si) : si / length;
}

double OutputScale::rate(Dimension dimension, double si) const {
  return dimension == Dimension::angle || dimension == Dimension::time ? si : si / length;
}

std::string OutputScale::coordinate_unit(Dimension dimension) const {
  if (dimension == Dimension::time) return "s";
  return dimension == Dimension::angle ? "deg" : length_unit;
}

std::string OutputScale::rate_unit(Dimension dimension) const {
  if (dimension == Dimension::time) return "s/s";  // time's rate: 1
  return dimension == Dimension::angle ? "rad/s" : length_unit + "/s";
}

std::string OutputScale::second_rate_unit(Dimension dimension) const {
  if (dimension == Dimension::time) return "1/s";
  return dimension == Dimension::angle ? "rad/s^2" : length_unit + "/s^2";
}

namespace {

// What a column's name comes from, as the file says it (for the message when two coincide).
struct ColumnOwner {
  std::string what;
  SourceLocation where;
};

// result_columns, and with owners given, what named each column (owners[k] for column k).
std::vector<ResultColumn> named_columns(const ConstraintSystem& system, const OutputScale& scale, bool circuit,
                                        std::vector<ColumnOwner>* owners) {
  std::vector<ResultColumn> columns;
  const auto add = [&](std::string name, std::string unit, const std::string& what, const SourceLocation& where,
                       Dimension dimension = Dimension::number, int order = 0) {
    columns.push_back({std::move(name), std::move(unit), dimension, order});
    if (owners) owners->push_back({what, where});
  };
  const auto add_coordinate = [&](const Coordinate& q, const std::string& kind) {
    const std::string named = kind + " \"" + q.name + "\"";
    add(q.name, scale.coordinate_unit(q.dimension), named, q.where, q.dimension, 0);
    add(q.rate.get_name(), scale.rate_unit(q.dimension), "the rate of " + named, q.where, q.dimension, 1);
    add(q.second_rate.get_name(), scale.second_rate_unit(q.dimension), "the second rate of " + named, q.where, q.dimension, 2);
  };
  add_coordinate(system.input, "input");
  for (const Coordinate& q : system.unknowns) add_coordinate(q, "unknown");
  const std::string& l = scale.length_unit;
  for (const PointObservable& p : system.points) {
    const std::string what = (p.is_joint ? "joint \"" : "point \"") + p.name + "\"";
    const Dimension length = Dimension::length;
    for (const auto& c : p.components) add(p.name + "_" + c, l, what, p.where, length, 0);
    for (const auto& c : p.components) add(p.name + "_v" + c, l + "/s", what, p.where, length, 1);
    add(p.name + "_speed", l + "/s", what, p.where, length, 1);
    for (const auto& c : p.components) add(p.name + "_a" + c, l + "/s^2", what, p.where, length, 2);
    add(p.name + "_acceleration", l + "/s^2", what, p.where, length, 2);
  }
  for (const FrameObservable& f : system.frames) {
    const std::string what = "frame \"" + f.name + "\"";
    for (const char* c : {"x", "y", "z"}) add(f.name + "_omega_" + c, "rad/s", what, f.where, Dimension::angle, 1);
    for (const char* c : {"x", "y", "z"}) add(f.name + "_alpha_" + c, "rad/s^2", what, f.where, Dimension::angle, 2);
  }
  for (const auto& [body, angle] : block_links(system)) {
    const SolvingPlan::Link& link = system.plan->links[body - 1];
    const std::string what = "slider block link \"" + link.name + "\"";
    add(angle, "deg", what, link.where, Dimension::angle, 0);
    add(default_rate_name(angle, 1), "rad/s", what, link.where, Dimension::angle, 1);
    add(default_rate_name(angle, 2), "rad/s^2", what, link.where, Dimension::angle, 2);
  }
  if (system.plan) {
    for (const SolvingPlan::Slider& slider : system.plan->sliders) {
      const SolvingPlan::Joint& joint = system.plan->joints[slider.joint];
      const std::string what = "slider \"" + joint.name + "\"";
      for (const char* part : {"_vrel_x", "_vrel_y"}) add(joint.name + part, l + "/s", what, joint.where, Dimension::length, 1);
      for (const char* part : {"_arel_x", "_arel_y", "_coriolis_x", "_coriolis_y"})
        add(joint.name + part, l + "/s^2", what, joint.where, Dimension::length, 2);
    }
    for (const GuidePoint& g : guide_points(system)) {
      const SolvingPlan::Slider& slider = system.plan->sliders[g.slider];
      const SolvingPlan::Joint& joint = system.plan->joints[slider.joint];
      const std::string what = "the point of link \"" + system.plan->links[slider.guide - 1].name +
                               "\" under slider \"" + joint.name + "\"";
      for (const char* part : {"_vx", "_vy"}) add(g.name + part, l + "/s", what, joint.where, Dimension::length, 1);
      for (const char* part : {"_ax", "_ay"}) add(g.name + part, l + "/s^2", what, joint.where, Dimension::length, 2);
    }
    for (const RelativeTurning& r : relative_turnings(system)) {
      const SolvingPlan::Joint& joint = system.plan->joints[r.joint];
      const std::string what = "the relative turning at pin \"" + joint.name + "\"";
      add(r.rate_name, "rad/s", what, joint.where, Dimension::angle, 1);
      add(r.second_rate_name, "rad/s^2", what, joint.where, Dimension::angle, 2);
    }
  }
  if (circuit) {
    for (const std::string& name : dyad_inner_joints(system)) {
      SourceLocation where;
      for (const SolvingPlan::Joint& j : system.plan->joints) where = j.name == name ? j.where : where;
      add("branch_" + name, "sign", "the assembly sign (--circuit) of joint \"" + name + "\"", where);
    }
  }
  return columns;
}

}  // namespace

std::vector<ResultColumn> result_columns(const ConstraintSystem& system, const OutputScale& scale, bool circuit) {
  return named_columns(system, scale, circuit, nullptr);
}

void check_column_names(const ConstraintSystem& system) {
  std::vector<ColumnOwner> owners;
  // With a circuit's columns: --circuit adds them to any run of the file.
  const std::vector<ResultColumn> columns = named_columns(system, OutputScale(system), true, &owners);
  std::map<std::string, std::size_t> seen;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const auto [it, inserted] = seen.emplace(columns[k].name, k);
    if (inserted) continue;
    const ColumnOwner &first = owners[it->second], &second = owners[k];
    throw InputError(second.where.str() + ": " + second.what + " and " + first.what + " (" + first.where.str() +
                     ") both give the output column \"" + columns[k].name +
                     "\" (CSV, JSON and npy need distinct names); rename one of them");
  }
}

std::size_t linkage_columns_begin(const ConstraintSystem& system) {
  std::size_t columns = kInputColumns + 3 * system.unknowns.size();
  for (const PointObservable& p : system.points) columns += 3 * p.components.size() + 2;
  return columns + 6 * system.frames.size();
}

std::vector<std::pair<std::size_t, std::string>> block_links(const ConstraintSystem& system) {
  std::vector<std::pair<std::size_t, std::string>> blocks;
  if (!system.plan) return blocks;
  const SolvingPlan& plan = *system.plan;
  for (std::size_t b = 1; b < plan.bodies.size(); ++b) {
    if (plan.bodies[b].guide < 0) continue;
    blocks.push_back({b, plan.links[b - 1].angle_name});
  }
  return blocks;
}

namespace {

bool all_digits(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

// The seed writes a point of a link or two links' relative turning with the links'
// numbers run together (B1, omega23); other link names keep an underscore between.
std::string joined_names(const std::string& first, const std::string& second) {
  return all_digits(second) ? first + second : first + "_" + second;
}

}  // namespace

std::vector<GuidePoint> guide_points(const ConstraintSystem& system) {
  std::vector<GuidePoint> points;
  if (!system.plan) return points;
  const SolvingPlan& plan = *system.plan;
  const SolvingPlan& frames = plan;
  const auto point_named = [&](const std::string& name) {
    for (std::size_t p = 0; p < system.points.size(); ++p)
      if (system.points[p].is_joint && system.points[p].name == name) return int(p);
    return -1;
  };
  for (std::size_t k = 0; k < frames.sliders.size(); ++k) {
    const SolvingPlan::Slider& slider = frames.sliders[k];
    if (slider.guide == 0) continue;  // a fixed guide's point does not move
    // The slider is shown as a point of its own, or by the block's pin at its place.
    int shown = point_named(plan.joints[slider.joint].name);
    const auto& on_block = frames.bodies[slider.block].points;
    std::complex<double> at;
    for (const auto& [joint, local] : on_block) at = joint == slider.joint ? local : at;
    for (const auto& [joint, local] : on_block) {
      if (shown >= 0) break;
      if (joint != slider.joint && !plan.joints[joint].slider &&
          std::abs(local - at) <= 1e-9 * system.length_scale)
        shown = point_named(plan.joints[joint].name);
    }
    if (shown < 0) continue;
    points.push_back({k, std::size_t(shown), joined_names(system.points[std::size_t(shown)].name,
                                                          plan.links[slider.guide - 1].name)});
  }
  return points;
}

std::vector<RelativeTurning> relative_turnings(const ConstraintSystem& system) {
  std::vector<RelativeTurning> turnings;
  if (!system.plan) return turnings;
  const SolvingPlan& frames = *system.plan;
  for (const SolvingPlan::Pin& pin : frames.pins) {
    const bool a_block = frames.bodies[pin.a].guide >= 0, b_block = frames.bodies[pin.b].guide >= 0;
    if (!a_block && !b_block) continue;
    const std::size_t block = a_block ? pin.a : pin.b, other = a_block ? pin.b : pin.a;
    if (other == 0 || int(other) == frames.bodies[block].guide) continue;  // its own turning, or none
    const std::string names = joined_names(system.plan->links[block - 1].name, system.plan->links[other - 1].name);
    const bool numbered = all_digits(system.plan->links[block - 1].name);
    turnings.push_back({block, other, pin.joint, (numbered ? "omega" : "omega_") + names,
                        (numbered ? "alpha" : "alpha_") + names});
  }
  return turnings;
}

std::size_t result_column_count(const ConstraintSystem& system, bool circuit) {
  std::size_t count = kInputColumns + 3 * system.unknowns.size() + 6 * system.frames.size();
  for (const PointObservable& p : system.points) count += 3 * p.components.size() + 2;
  if (system.plan) {
    for (const SolvingPlan::Body& body : system.plan->bodies) count += body.guide >= 0 ? 3 : 0;
    count += 6 * system.plan->sliders.size();
    count += 4 * guide_points(system).size() + 2 * relative_turnings(system).size();
    if (circuit) count += system.plan->dyads.size();  // an assembly sign each
  }
  return count;
}

std::vector<std::string> dyad_inner_joints(const ConstraintSystem& system) {
  std::vector<std::string> names;
  if (!system.plan) return names;
  for (const SolvingPlan::Step& group : system.plan->steps) {
    if (group.kind != "driver" && group.joints.size() == 3) names.push_back(group.joints[1]);
  }
  if (names.size() != system.plan->dyads.size()) names.clear();  // not all in closed form
  return names;
}

}  // namespace kinema
