#include "engine/analysis/output_scale.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"

namespace kinema {

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
// position's, a slider block turns with its guide. Of a derivative's position (`at` holding
// the derivatives, the input's 0): the derivatives, a block's offset being a constant.
template <typename Vector>
Turning turning(const SolvingPlan& frames, const Position<Vector>& at, std::size_t body, bool derivative = false) {
  const SolvingPlan::Body& b = frames.bodies[body];
  if (b.unknown >= 0) {
    const auto i = Eigen::Index(b.unknown);
    return {at.q[i], at.qd[i], at.qdd[i]};
  }
  if (b.guide >= 0) {
    Turning t = turning(frames, at, std::size_t(b.guide), derivative);
    t.angle += derivative ? 0.0 : b.offset;
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
Sliding sliding(const SolvingPlan& frames, const Position<Vector>& at, const SolvingPlan::Slider& slider) {
  const Turning guide = turning(frames, at, slider.guide);
  const std::complex<double> u = std::polar(1.0, guide.angle + slider.direction);
  double s1 = at.rate, s2 = at.second_rate;  // the driver's, unless the slider's coordinate is an unknown
  if (slider.unknown >= 0) {
    s1 = at.qd[Eigen::Index(slider.unknown)];
    s2 = at.qdd[Eigen::Index(slider.unknown)];
  }
  return {s1 * u, s2 * u, 2 * guide.rate * std::complex<double>(0, 1) * s1 * u};
}

// The derivative of a slider's Sliding along `d` (the derivatives of `at`'s values; the
// input's 0): u turns by d(angle), so du = i u d(angle).
template <typename Vector>
Sliding sliding_derivative(const SolvingPlan& frames, const Position<Vector>& at, const Position<Vector>& d,
                           const SolvingPlan::Slider& slider) {
  const Turning guide = turning(frames, at, slider.guide), d_guide = turning(frames, d, slider.guide, true);
  const std::complex<double> i(0, 1), u = std::polar(1.0, guide.angle + slider.direction), du = i * u * d_guide.angle;
  double s1 = at.rate, s2 = at.second_rate, ds1 = 0, ds2 = 0;  // the driver's rates do not change
  if (slider.unknown >= 0) {
    const auto k = Eigen::Index(slider.unknown);
    s1 = at.qd[k];
    s2 = at.qdd[k];
    ds1 = d.qd[k];
    ds2 = d.qdd[k];
  }
  return {ds1 * u + s1 * du, ds2 * u + s2 * du, 2.0 * i * (d_guide.rate * s1 * u + guide.rate * (ds1 * u + s1 * du))};
}

// The joints-and-links values of an ok position (see result_columns), from `values` on.
template <typename Vector>
double* linkage_values(const ConstraintSystem& system, const OutputScale& scale, const LinkageColumns& columns,
                       const Position<Vector>& at, double* values) {
  const SolvingPlan& frames = *system.plan;
  // The blocks in the order of block_links (body order), without its names: this runs per row.
  for (std::size_t body = 1; body < frames.bodies.size(); ++body) {
    if (frames.bodies[body].guide < 0) continue;
    const Turning t = turning(frames, at, body);
    *values++ = scale.coordinate(Dimension::angle, t.angle);
    *values++ = t.rate;
    *values++ = t.second_rate;
  }
  for (const SolvingPlan::Slider& slider : frames.sliders) {
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

// The derivatives of linkage_values along `d` (the derivatives of `at`'s values and
// points), SI (block angles in rad), in its order.
template <typename Vector>
void linkage_derivative_values(const ConstraintSystem& system, const LinkageColumns& columns, const Position<Vector>& at,
                               const Position<Vector>& d, double* values) {
  const SolvingPlan& frames = *system.plan;
  for (std::size_t body = 1; body < frames.bodies.size(); ++body) {
    if (frames.bodies[body].guide < 0) continue;
    const Turning t = turning(frames, d, body, true);
    *values++ = t.angle;
    *values++ = t.rate;
    *values++ = t.second_rate;
  }
  const auto put = [&](const std::complex<double>& c) {
    *values++ = c.real();
    *values++ = c.imag();
  };
  for (const SolvingPlan::Slider& slider : frames.sliders) {
    const Sliding s = sliding_derivative(frames, at, d, slider);
    for (const std::complex<double>& c : {s.relative_velocity, s.relative_acceleration, s.coriolis}) put(c);
  }
  for (const GuidePoint& g : columns.guides) {
    const Sliding s = sliding_derivative(frames, at, d, frames.sliders[g.slider]);
    const PointMotion p = d.point(g.point);
    put(std::complex<double>(p.velocity[0], p.velocity[1]) - s.relative_velocity);
    put(std::complex<double>(p.acceleration[0], p.acceleration[1]) - s.relative_acceleration - s.coriolis);
  }
  for (const RelativeTurning& r : columns.turnings) {
    const Turning block = turning(frames, d, r.block, true), other = turning(frames, d, r.other, true);
    *values++ = block.rate - other.rate;
    *values++ = block.second_rate - other.second_rate;
  }
}

}  // namespace

void linkage_derivatives(const ConstraintSystem& system, const MotionTable& table, std::size_t row,
                         const Eigen::VectorXd& dq, const Eigen::VectorXd& dqd, const Eigen::VectorXd& dqdd,
                         const std::function<PointMotion(std::size_t)>& d_point, double* values) {
  const Eigen::VectorXd q = table.q(row), qd = table.qd(row), qdd = table.qdd(row);
  linkage_derivative_values(system, LinkageColumns(system),
                            Position<Eigen::VectorXd>{q, qd, qdd, table.input(row), table.input_rate(row),
                                                      table.input_second_rate(row),
                                                      [&](std::size_t p) { return table.point(row, p); }},
                            Position<Eigen::VectorXd>{dq, dqd, dqdd, 0.0, 0.0, 0.0, d_point}, values);
}

void linkage_values(const ConstraintSystem& system, const OutputScale& scale, const MotionState& state, double* values) {
  linkage_values(system, scale, LinkageColumns(system),
                 Position<Eigen::VectorXd>{state.q, state.qd, state.qdd, state.input, state.input_rate,
                                           state.input_second_rate, [&](std::size_t p) { return state.points[p]; }},
                 values);
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
  if (!system.plan) return;
  // Joints and links: the blocks' and sliders' values row by row (angles of their guides).
  const std::size_t linkage_count = stride - column - (table.is_circuit() ? system.plan->dyads.size() : 0);
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
  for (std::size_t k = 0; k < system.plan->dyads.size(); ++k) {
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

}  // namespace kinema
