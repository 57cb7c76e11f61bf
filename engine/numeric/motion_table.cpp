#include "engine/numeric/motion_table.hpp"

#include <algorithm>

namespace kinema {

const char* status_name(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::singular: return "singular";
    case Status::unassembled: return "unassembled";
  }
  return "?";
}

MotionTable::MotionTable(const std::vector<double>& inputs, std::size_t unknowns,
                         const std::vector<std::size_t>& point_dimensions, double rate, double second_rate,
                         std::size_t frames)
    : n_(unknowns),
      frame_count_(frames),
      point_dimensions_(point_dimensions),
      rate_(rate),
      second_rate_(second_rate),
      input_(inputs),
      q_(inputs.size() * unknowns),
      qd_(inputs.size() * unknowns),
      qdd_(inputs.size() * unknowns),
      loop_residual_(inputs.size()),
      reciprocal_condition_(inputs.size()),
      status_(inputs.size(), Status::unassembled),
      failure_(inputs.size()) {
  std::size_t columns = 0;
  for (std::size_t dimension : point_dimensions) {
    point_offset_.push_back(columns);
    columns += 3 * dimension;
  }
  frame_offset_ = columns;
  points_.resize(inputs.size() * (columns + 6 * frames));
}

void MotionTable::assign_inputs(const InputValues& inputs, std::size_t first, std::size_t count) {
  batch_rows_ = 0;
  direction_.clear();
  assembly_.clear();
  input_.resize(count);
  for (std::size_t row = 0; row < count; ++row) input_[row] = inputs[first + row];
  // Values are left as they are (a row's status says which are valid, and the solver
  // sets every row it solves): clearing them cost more than solving.
  for (auto* values : {&q_, &qd_, &qdd_}) values->resize(count * n_);
  loop_residual_.resize(count);
  reciprocal_condition_.resize(count);
  status_.assign(count, Status::unassembled);
  failure_.assign(count, Failure{});
  points_.resize(count * (frame_offset_ + 6 * frame_count_));
}

std::size_t MotionTable::bytes() const {
  return sizeof(double) * (input_.capacity() + q_.capacity() + qd_.capacity() + qdd_.capacity() +
                           loop_residual_.capacity() + reciprocal_condition_.capacity() + points_.capacity()) +
         sizeof(Status) * status_.capacity() + sizeof(Failure) * failure_.capacity() + direction_.capacity() +
         sizeof(std::uint64_t) * assembly_.capacity();
}

PointMotion MotionTable::point(std::size_t row, std::size_t p) const {
  PointMotion motion;
  motion.dimension = point_dimensions_[p];
  const std::size_t rows = size();
  const double* v = points_.data() + point_offset_[p] * rows + row;
  for (std::size_t c = 0; c < motion.dimension; ++c) {
    motion.position[c] = v[c * rows];
    motion.velocity[c] = v[(motion.dimension + c) * rows];
    motion.acceleration[c] = v[(2 * motion.dimension + c) * rows];
  }
  return motion;
}

FrameMotion MotionTable::frame(std::size_t row, std::size_t f) const {
  FrameMotion motion;
  const std::size_t rows = size();
  const double* v = points_.data() + (frame_offset_ + 6 * f) * rows + row;
  for (std::size_t c = 0; c < 3; ++c) {
    motion.angular_velocity[c] = v[c * rows];
    motion.angular_acceleration[c] = v[(3 + c) * rows];
  }
  return motion;
}

MotionState MotionTable::operator[](std::size_t row) const {
  MotionState s;
  s.input = input_[row];
  s.input_rate = input_rate(row);
  s.input_second_rate = input_second_rate(row);
  s.status = status_[row];
  s.failure = failure_[row];
  s.loop_residual = loop_residual_[row];
  s.reciprocal_condition = reciprocal_condition_[row];
  if (s.status != Status::unassembled) s.q = q(row);
  if (s.status == Status::ok) {
    s.qd = qd(row);
    s.qdd = qdd(row);
    s.points.resize(point_count());
    for (std::size_t p = 0; p < point_count(); ++p) s.points[p] = point(row, p);
    s.frames.resize(frame_count_);
    for (std::size_t f = 0; f < frame_count_; ++f) s.frames[f] = frame(row, f);
  }
  return s;
}

void MotionTable::set(std::size_t row, const MotionState& s) {
  input_[row] = s.input;
  status_[row] = s.status;
  failure_[row] = s.failure;
  loop_residual_[row] = s.loop_residual;
  reciprocal_condition_[row] = s.reciprocal_condition;
  const std::size_t rows = size();
  auto copy = [&](const Eigen::VectorXd& from, std::vector<double>& to) {
    if (static_cast<std::size_t>(from.size()) != n_) return;
    for (std::size_t i = 0; i < n_; ++i) to[i * rows + row] = from[i];
  };
  copy(s.q, q_);
  copy(s.qd, qd_);
  copy(s.qdd, qdd_);
  if (s.points.size() == point_count()) {
    for (std::size_t p = 0; p < point_count(); ++p) {
      const PointMotion& m = s.points[p];
      double* v = points_.data() + point_offset_[p] * rows + row;
      const std::size_t d = point_dimensions_[p];
      for (std::size_t c = 0; c < d; ++c) {
        v[c * rows] = m.position[c];
        v[(d + c) * rows] = m.velocity[c];
        v[(2 * d + c) * rows] = m.acceleration[c];
      }
    }
  }
  if (s.frames.size() == frame_count_) {
    for (std::size_t f = 0; f < frame_count_; ++f) {
      double* v = points_.data() + (frame_offset_ + 6 * f) * rows + row;
      for (std::size_t c = 0; c < 3; ++c) {
        v[c * rows] = s.frames[f].angular_velocity[c];
        v[(3 + c) * rows] = s.frames[f].angular_acceleration[c];
      }
    }
  }
}

void MotionTable::set(std::size_t row, const MotionTable& from, std::size_t from_row) {
  input_[row] = from.input_[from_row];
  const Status status = status_[row] = from.status_[from_row];
  failure_[row] = from.failure_[from_row];
  loop_residual_[row] = from.loop_residual_[from_row];
  reciprocal_condition_[row] = from.reciprocal_condition_[from_row];
  const std::size_t rows = size(), from_rows = from.size();
  const auto copy = [&](const std::vector<double>& values, std::vector<double>& to) {
    for (std::size_t i = 0, columns = to.size() / std::max<std::size_t>(rows, 1); i < columns; ++i)
      to[i * rows + row] = values[i * from_rows + from_row];
  };
  if (status != Status::unassembled) copy(from.q_, q_);
  if (status != Status::ok) return;
  copy(from.qd_, qd_);
  copy(from.qdd_, qdd_);
  copy(from.points_, points_);  // the points' columns, then the frames'
}

void MotionTable::set_ok(std::size_t first, std::size_t count) {
  std::fill_n(status_.begin() + first, count, Status::ok);
  std::fill_n(failure_.begin() + first, count, Failure{});
}

}  // namespace kinema
