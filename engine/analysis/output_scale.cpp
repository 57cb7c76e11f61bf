#include "engine/analysis/output_scale.hpp"

#include <algorithm>
#include <cctype>
#include <complex>
#include <functional>
#include <limits>
#include <map>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/symbolic/naming.hpp"

#include <cmath>

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
  const auto add = [&](std::string name, std::string unit, const std::string& what, const SourceLocation& where) {
    columns.push_back({std::move(name), std::move(unit)});
    if (owners) owners->push_back({what, where});
  };
  const auto add_coordinate = [&](const Coordinate& q, const std::string& kind) {
    const std::string named = kind + " \"" + q.name + "\"";
    add(q.name, scale.coordinate_unit(q.dimension), named, q.where);
    add(q.rate.get_name(), scale.rate_unit(q.dimension), "the rate of " + named, q.where);
    add(q.second_rate.get_name(), scale.second_rate_unit(q.dimension), "the second rate of " + named, q.where);
  };
  add_coordinate(system.input, "input");
  for (const Coordinate& q : system.unknowns) add_coordinate(q, "unknown");
  const std::string& l = scale.length_unit;
  for (const PointObservable& p : system.points) {
    const std::string what = (p.is_joint ? "joint \"" : "point \"") + p.name + "\"";
    for (const auto& c : p.components) add(p.name + "_" + c, l, what, p.where);
    for (const auto& c : p.components) add(p.name + "_v" + c, l + "/s", what, p.where);
    add(p.name + "_speed", l + "/s", what, p.where);
    for (const auto& c : p.components) add(p.name + "_a" + c, l + "/s^2", what, p.where);
    add(p.name + "_acceleration", l + "/s^2", what, p.where);
  }
  for (const FrameObservable& f : system.frames) {
    const std::string what = "frame \"" + f.name + "\"";
    for (const char* c : {"x", "y", "z"}) add(f.name + "_omega_" + c, "rad/s", what, f.where);
    for (const char* c : {"x", "y", "z"}) add(f.name + "_alpha_" + c, "rad/s^2", what, f.where);
  }
  for (const auto& [body, angle] : block_links(system)) {
    const Link& link = system.linkage->links[body - 1];
    const std::string what = "slider block link \"" + link.name + "\"";
    add(angle, "deg", what, link.where);
    add(default_rate_name(angle, 1), "rad/s", what, link.where);
    add(default_rate_name(angle, 2), "rad/s^2", what, link.where);
  }
  if (system.linkage) {
    for (const LinkageFrames::Slider& slider : system.linkage->frames.sliders) {
      const Joint& joint = system.linkage->joints[slider.joint];
      const std::string what = "slider \"" + joint.name + "\"";
      for (const char* part : {"_vrel_x", "_vrel_y"}) add(joint.name + part, l + "/s", what, joint.where);
      for (const char* part : {"_arel_x", "_arel_y", "_coriolis_x", "_coriolis_y"})
        add(joint.name + part, l + "/s^2", what, joint.where);
    }
    for (const GuidePoint& g : guide_points(system)) {
      const LinkageFrames::Slider& slider = system.linkage->frames.sliders[g.slider];
      const Joint& joint = system.linkage->joints[slider.joint];
      const std::string what = "the point of link \"" + system.linkage->links[slider.guide - 1].name +
                               "\" under slider \"" + joint.name + "\"";
      for (const char* part : {"_vx", "_vy"}) add(g.name + part, l + "/s", what, joint.where);
      for (const char* part : {"_ax", "_ay"}) add(g.name + part, l + "/s^2", what, joint.where);
    }
    for (const RelativeTurning& r : relative_turnings(system)) {
      const Joint& joint = system.linkage->joints[r.joint];
      const std::string what = "the relative turning at pin \"" + joint.name + "\"";
      add(r.rate_name, "rad/s", what, joint.where);
      add(r.second_rate_name, "rad/s^2", what, joint.where);
    }
  }
  if (circuit) {
    for (const std::string& name : dyad_inner_joints(system)) {
      SourceLocation where;
      for (const Joint& j : system.linkage->joints) where = j.name == name ? j.where : where;
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
  if (!system.linkage) return blocks;
  const Linkage& linkage = *system.linkage;
  for (std::size_t b = 1; b < linkage.frames.bodies.size(); ++b) {
    if (linkage.frames.bodies[b].guide < 0) continue;
    const Link& link = linkage.links[b - 1];
    const bool numbered = !link.name.empty() && std::isdigit(static_cast<unsigned char>(link.name[0]));
    blocks.push_back({b, !link.angle_name.empty() ? link.angle_name : (numbered ? "theta" : "theta_") + link.name});
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
  if (!system.linkage) return points;
  const Linkage& linkage = *system.linkage;
  const LinkageFrames& frames = linkage.frames;
  const auto point_named = [&](const std::string& name) {
    for (std::size_t p = 0; p < system.points.size(); ++p)
      if (system.points[p].is_joint && system.points[p].name == name) return int(p);
    return -1;
  };
  for (std::size_t k = 0; k < frames.sliders.size(); ++k) {
    const LinkageFrames::Slider& slider = frames.sliders[k];
    if (slider.guide == 0) continue;  // a fixed guide's point does not move
    // The slider is shown as a point of its own, or by the block's pin at its place.
    int shown = point_named(linkage.joints[slider.joint].name);
    const auto& on_block = frames.bodies[slider.block].points;
    std::complex<double> at;
    for (const auto& [joint, local] : on_block) at = joint == slider.joint ? local : at;
    for (const auto& [joint, local] : on_block) {
      if (shown >= 0) break;
      if (joint != slider.joint && linkage.joints[joint].kind == Joint::Kind::pin &&
          std::abs(local - at) <= 1e-9 * system.length_scale)
        shown = point_named(linkage.joints[joint].name);
    }
    if (shown < 0) continue;
    points.push_back({k, std::size_t(shown), joined_names(system.points[std::size_t(shown)].name,
                                                          linkage.links[slider.guide - 1].name)});
  }
  return points;
}

std::vector<RelativeTurning> relative_turnings(const ConstraintSystem& system) {
  std::vector<RelativeTurning> turnings;
  if (!system.linkage) return turnings;
  const LinkageFrames& frames = system.linkage->frames;
  for (const LinkageFrames::Pin& pin : frames.pins) {
    const bool a_block = frames.bodies[pin.a].guide >= 0, b_block = frames.bodies[pin.b].guide >= 0;
    if (!a_block && !b_block) continue;
    const std::size_t block = a_block ? pin.a : pin.b, other = a_block ? pin.b : pin.a;
    if (other == 0 || int(other) == frames.bodies[block].guide) continue;  // its own turning, or none
    const std::string names = joined_names(system.linkage->links[block - 1].name, system.linkage->links[other - 1].name);
    const bool numbered = all_digits(system.linkage->links[block - 1].name);
    turnings.push_back({block, other, pin.joint, (numbered ? "omega" : "omega_") + names,
                        (numbered ? "alpha" : "alpha_") + names});
  }
  return turnings;
}

namespace {

struct Turning {
  double angle = 0, rate = 0, second_rate = 0;
};

// The unknowns and the input of one position (a table row, or a MotionState), and its points.
template <typename Vector>
struct Position {
  const Vector &q, &qd, &qdd;
  double input, rate, second_rate;
  std::function<PointMotion(std::size_t)> point;
};

// What the joints-and-links columns list beyond blocks and sliders, worked out once a run.
struct LinkageColumns {
  std::vector<GuidePoint> guides;
  std::vector<RelativeTurning> turnings;
  explicit LinkageColumns(const ConstraintSystem& system)
      : guides(guide_points(system)), turnings(relative_turnings(system)) {}
};

// A body's angle and rates: ground's are 0, an unknown's or the driver's are the
// position's, a slider block turns with its guide.
template <typename Vector>
Turning turning(const LinkageFrames& frames, const Position<Vector>& at, std::size_t body) {
  const LinkageFrames::Body& b = frames.bodies[body];
  if (b.unknown >= 0) {
    const auto i = Eigen::Index(b.unknown);
    return {at.q[i], at.qd[i], at.qdd[i]};
  }
  if (b.guide >= 0) {
    Turning t = turning(frames, at, std::size_t(b.guide));
    t.angle += b.offset;
    return t;
  }
  if (body != 0 && body == frames.driver_body && frames.driver_slider < 0) return {at.input, at.rate, at.second_rate};
  return {};
}

// A slider's motion along its line (u, turning with the guide): v_rel = s' u,
// a_rel = s'' u, and the Coriolis acceleration 2 omega_guide x v_rel.
struct Sliding {
  std::complex<double> relative_velocity, relative_acceleration, coriolis;
};

template <typename Vector>
Sliding sliding(const LinkageFrames& frames, const Position<Vector>& at, const LinkageFrames::Slider& slider) {
  const Turning guide = turning(frames, at, slider.guide);
  const std::complex<double> u = std::polar(1.0, guide.angle + slider.direction);
  double s1 = at.rate, s2 = at.second_rate;  // the driver's, unless the slider's coordinate is an unknown
  if (slider.unknown >= 0) {
    s1 = at.qd[Eigen::Index(slider.unknown)];
    s2 = at.qdd[Eigen::Index(slider.unknown)];
  }
  return {s1 * u, s2 * u, 2 * guide.rate * std::complex<double>(0, 1) * s1 * u};
}

// The joints-and-links values of an ok position (see result_columns), from `values` on.
template <typename Vector>
double* linkage_values(const ConstraintSystem& system, const OutputScale& scale, const LinkageColumns& columns,
                       const Position<Vector>& at, double* values) {
  const LinkageFrames& frames = system.linkage->frames;
  // The blocks in the order of block_links (body order), without its names: this runs per row.
  for (std::size_t body = 1; body < frames.bodies.size(); ++body) {
    if (frames.bodies[body].guide < 0) continue;
    const Turning t = turning(frames, at, body);
    *values++ = scale.coordinate(Dimension::angle, t.angle);
    *values++ = t.rate;
    *values++ = t.second_rate;
  }
  for (const LinkageFrames::Slider& slider : frames.sliders) {
    const Sliding s = sliding(frames, at, slider);
    for (const std::complex<double>& c : {s.relative_velocity, s.relative_acceleration, s.coriolis}) {
      *values++ = c.real() / scale.length;
      *values++ = c.imag() / scale.length;
    }
  }
  for (const GuidePoint& g : columns.guides) {
    // The slider point less its sliding: what the guide's own point there does.
    const Sliding s = sliding(frames, at, frames.sliders[g.slider]);
    const PointMotion p = at.point(g.point);
    const std::complex<double> v = std::complex<double>(p.velocity[0], p.velocity[1]) - s.relative_velocity;
    const std::complex<double> a = std::complex<double>(p.acceleration[0], p.acceleration[1]) - s.relative_acceleration -
                                   s.coriolis;
    for (const std::complex<double>& c : {v, a}) {
      *values++ = c.real() / scale.length;
      *values++ = c.imag() / scale.length;
    }
  }
  for (const RelativeTurning& r : columns.turnings) {
    const Turning block = turning(frames, at, r.block), other = turning(frames, at, r.other);
    *values++ = block.rate - other.rate;
    *values++ = block.second_rate - other.second_rate;
  }
  return values;
}

}  // namespace

void linkage_values(const ConstraintSystem& system, const OutputScale& scale, const MotionState& state, double* values) {
  linkage_values(system, scale, LinkageColumns(system),
                 Position<Eigen::VectorXd>{state.q, state.qd, state.qdd, state.input, state.input_rate,
                                           state.input_second_rate, [&](std::size_t p) { return state.points[p]; }},
                 values);
}

std::size_t result_column_count(const ConstraintSystem& system, bool circuit) {
  std::size_t count = kInputColumns + 3 * system.unknowns.size() + 6 * system.frames.size();
  for (const PointObservable& p : system.points) count += 3 * p.components.size() + 2;
  if (system.linkage) {
    for (const LinkageFrames::Body& body : system.linkage->frames.bodies) count += body.guide >= 0 ? 3 : 0;
    count += 6 * system.linkage->frames.sliders.size();
    count += 4 * guide_points(system).size() + 2 * relative_turnings(system).size();
    if (circuit) count += system.linkage->frames.dyads.size();  // an assembly sign each
  }
  return count;
}

void result_values(const ConstraintSystem& system, const OutputScale& scale, const MotionTable& table,
                   std::size_t row, double* values) {
  result_rows(system, scale, table, row, row + 1, values);
}

namespace {

// result_rows without the overflow check; `overflow` is set when a value is infinite.
void write_rows(const ConstraintSystem& system, const OutputScale& scale, const MotionTable& table,
                std::size_t first, std::size_t last, double* values, bool& overflow) {
  constexpr double undefined = std::numeric_limits<double>::quiet_NaN();
  const std::size_t stride = result_column_count(system, table.is_circuit());
  std::size_t column = 0;
  // Column `column` of every row from value(row); NaN unless the row is ok (needs ok) or
  // at least assembled (needs singular).
  const auto fill = [&](Status needs, auto value) {
    double* out = values + column++;
    for (std::size_t row = first; row < last; ++row, out += stride) {
      const Status status = table.status(row);
      const bool defined = needs == Status::ok ? status == Status::ok : status != Status::unassembled;
      *out = defined ? value(row) : undefined;
      overflow |= std::isinf(*out);
    }
  };
  const Dimension input_kind = system.input.dimension;
  {
    double* out = values + column;
    for (std::size_t row = first; row < last; ++row, out += stride) {
      out[0] = scale.input(table.input(row));
      out[1] = scale.rate(input_kind, table.input_rate(row));
      out[2] = scale.rate(input_kind, table.input_second_rate(row));
    }
    column += kInputColumns;
  }
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    const Dimension kind = system.unknowns[i].dimension;
    const double *q = table.q_column(i), *qd = table.qd_column(i), *qdd = table.qdd_column(i);
    fill(Status::singular, [&](std::size_t row) { return scale.coordinate(kind, q[row]); });
    fill(Status::ok, [&](std::size_t row) { return scale.rate(kind, qd[row]); });
    fill(Status::ok, [&](std::size_t row) { return scale.rate(kind, qdd[row]); });
  }
  const double f = scale.length;
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    const std::size_t dimension = system.points[p].components.size();
    const auto component = [&](std::size_t k) { return table.point_column(p, k); };
    const auto magnitude = [&](std::size_t k) {
      fill(Status::ok, [&, k](std::size_t row) {
        return vector_length(component(k)[row], component(k + 1)[row], dimension == 3 ? component(k + 2)[row] : 0.0) / f;
      });
    };
    for (std::size_t c = 0; c < dimension; ++c) fill(Status::ok, [&, v = component(c)](std::size_t row) { return v[row] / f; });
    for (std::size_t c = 0; c < dimension; ++c)
      fill(Status::ok, [&, v = component(dimension + c)](std::size_t row) { return v[row] / f; });
    magnitude(dimension);
    for (std::size_t c = 0; c < dimension; ++c)
      fill(Status::ok, [&, v = component(2 * dimension + c)](std::size_t row) { return v[row] / f; });
    magnitude(2 * dimension);
  }
  for (std::size_t k = 0; k < system.frames.size(); ++k) {
    for (std::size_t c = 0; c < 6; ++c) fill(Status::ok, [v = table.frame_column(k, c)](std::size_t row) { return v[row]; });
  }
  if (!system.linkage) return;
  // Joints and links: the blocks' and sliders' values row by row (angles of their guides).
  const std::size_t linkage_count = stride - column - (table.is_circuit() ? system.linkage->frames.dyads.size() : 0);
  const LinkageColumns linkage_columns(system);
  for (std::size_t row = first; row < last; ++row) {
    double* out = values + (row - first) * stride + column;
    if (table.status(row) != Status::ok) {
      std::fill_n(out, linkage_count, undefined);
    } else {
      linkage_values(system, scale, linkage_columns,
                     Position<MotionTable::Column>{table.q(row), table.qd(row), table.qdd(row), table.input(row),
                                                   table.input_rate(row), table.input_second_rate(row),
                                                   [&](std::size_t p) { return table.point(row, p); }},
                     out);
      for (std::size_t c = 0; c < linkage_count; ++c) overflow |= std::isinf(out[c]);
    }
  }
  column += linkage_count;
  if (!table.is_circuit()) return;
  for (std::size_t k = 0; k < system.linkage->frames.dyads.size(); ++k) {
    fill(Status::singular, [&](std::size_t row) { return double(table.assembly_sign(row, k)); });
  }
}

}  // namespace

void result_rows(const ConstraintSystem& system, const OutputScale& scale, const MotionTable& table,
                 std::size_t first, std::size_t last, double* values) {
  bool overflow = false;
  write_rows(system, scale, table, first, last, values, overflow);
  if (!overflow) return;
  // A finite result in SI can pass the largest double in the output unit (1.8e308 m in
  // mm), and a formula's huge numbers can overflow in SI: not a result to print.
  const std::vector<ResultColumn> columns = result_columns(system, scale, table.is_circuit());
  for (std::size_t row = first; row < last; ++row) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (!std::isinf(values[(row - first) * columns.size() + c])) continue;
      throw InputError(system.source_file + ": " + columns[c].name + " at " + system.input.name + " = " +
                       format_significant(values[(row - first) * columns.size()]) + " " + columns[0].unit +
                       " is beyond the largest number (1.8e308 " + columns[c].unit +
                       "): check the sizes of the numbers in the file's formulas and parameters");
    }
  }
}

std::vector<std::string> dyad_inner_joints(const ConstraintSystem& system) {
  std::vector<std::string> names;
  if (!system.linkage) return names;
  for (const StructureGroup& group : system.linkage->structure) {
    if (group.kind != "driver" && group.joints.size() == 3) names.push_back(group.joints[1]);
  }
  if (names.size() != system.linkage->frames.dyads.size()) names.clear();  // not all in closed form
  return names;
}

}  // namespace kinema
