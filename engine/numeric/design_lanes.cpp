#include "engine/numeric/design_lanes.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "engine/numeric/solver.hpp"
#include "engine/numeric/sweep.hpp"

namespace kinema {

namespace {
// Newton iterations a lane gets; one that needs more is solved by the scalar run (a
// value predicted from 1 deg back converges in 3 or 4, the first one from the guesses
// in about 6).
constexpr int kLaneIterations = 10;
}  // namespace

struct DesignLanes::Lane {
  Lane(const Kinematics& k, const std::vector<double>& inputs, double rate, double second_rate)
      : kinematics(k),
        rows(kinematics),
        table(inputs, k.unknown_count(), k.layout().point_dimensions, rate, second_rate, k.frame_count()) {}
  Kinematics kinematics;  // the design's parameter values, the tape shared
  RowSolver rows;         // the values the lanes leave to the scalar run
  MotionTable table;
  bool last_in_lanes = false;  // the last row was solved in the lanes (rows not told yet)
};

DesignLanes::DesignLanes(const Kinematics& kinematics, const std::vector<double>& inputs, double rate,
                         double second_rate)
    : k_(kinematics),
      layout_(kinematics.layout()),
      n_(kinematics.unknown_count()),
      inputs_(inputs),
      rate_(rate),
      second_rate_(second_rate),
      registers_(kinematics.evaluator().make_batch_workspace()),
      lu_(n_ * n_ * kLanes),
      pivots_(n_ * kLanes),
      x_(n_ * kLanes),
      start_(n_ * kLanes),
      column_scale_(n_ * kLanes) {
  for (std::size_t l = 0; l < kLanes; ++l) {
    lanes_.push_back(std::make_unique<Lane>(kinematics, inputs, rate, second_rate));
    set_design(l, kinematics.parameter_values().data());
  }
  std::fill_n(lanes(layout_.rate()), kLanes, rate);
  std::fill_n(lanes(layout_.second_rate()), kLanes, second_rate);
}

DesignLanes::~DesignLanes() = default;

const MotionTable& DesignLanes::table(std::size_t lane) const { return lanes_[lane]->table; }

void DesignLanes::set_design(std::size_t l, const double* values) {
  Kinematics& k = lanes_[l]->kinematics;
  k.set_parameter_values(values);
  for (std::size_t p = 0; p < layout_.parameter_count; ++p) lanes(layout_.parameter(p))[l] = values[p];
  length_scale_[l] = k.length_scale();
  tolerance_[l] = solver::kNewtonTolerance * k.length_scale();
  for (std::size_t i = 0; i < n_; ++i) column_scale_[i * kLanes + l] = k.column_scale()[i];
}

void DesignLanes::solve(std::size_t count) {
  k_.evaluator().prepare_batch(registers_.data());  // each lane's work on its parameters
  for (std::size_t l = 0; l < count; ++l) {
    lanes_[l]->rows.start();
    lanes_[l]->last_in_lanes = false;
  }
  lane_values_ = 0;
  double take[kLanes], ok[kLanes];
  for (std::size_t row = 0; row < inputs_.size(); ++row) {
    if (choose_lanes(row, count, take)) {
      solve_value(inputs_[row], row > 0, take, ok);
    } else {
      std::fill_n(ok, kLanes, 0.0);
    }
    for (std::size_t l = 0; l < count; ++l) {
      Lane& lane = *lanes_[l];
      if (ok[l] != 0) {
        store(l, row);
        lane.last_in_lanes = true;
        ++lane_values_;
        continue;
      }
      if (lane.last_in_lanes) lane.rows.solved_elsewhere(lane.table, row - 1);
      lane.last_in_lanes = false;
      lane.rows.solve(lane.table, row);
    }
  }
  count_values_solved(lane_values_);
}

bool DesignLanes::choose_lanes(std::size_t row, std::size_t count, double* take) {
  const double input = inputs_[row];
  bool any = false;
  for (std::size_t l = 0; l < kLanes; ++l) {
    const Lane& lane = *lanes_[l];
    bool taken = false;
    if (l < count && row == 0) {
      // The first value from the guesses, as the scalar run starts (Newton alone).
      taken = lane.kinematics.closed_form() == nullptr;
    } else if (l < count) {
      // The scalar run's fast path: from the last row, ok, predicted by its rates.
      const double h = input - inputs_[row - 1];
      taken = (lane.last_in_lanes || lane.rows.on_branch()) &&
              std::fabs(h) <= lane.kinematics.max_continuation_step();
      for (std::size_t i = 0; taken && i < n_; ++i) {
        start_[i * kLanes + l] =
            solver::predict_second_order(lane.table.q_column(i)[row - 1], lane.table.qd_column(i)[row - 1],
                                         lane.table.qdd_column(i)[row - 1], rate_, second_rate_, h);
      }
    }
    if (!taken) {
      // Not solved here: any finite position keeps the lane's arithmetic quiet.
      for (std::size_t i = 0; i < n_; ++i) start_[i * kLanes + l] = lane.kinematics.guess()[Eigen::Index(i)];
    } else if (row == 0) {
      for (std::size_t i = 0; i < n_; ++i) start_[i * kLanes + l] = lane.kinematics.guess()[Eigen::Index(i)];
    }
    take[l] = taken ? 1.0 : 0.0;
    any = any || taken;
  }
  return any;
}

void DesignLanes::factorise() {
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t j = 0; j < n_; ++j) {
      const double* phi_q = output(TapeLayout::kPositionStage, layout_.phi_q(i, j));
      const double* scale = column_scale_.data() + j * kLanes;
      double* target = lu_.data() + (i * n_ + j) * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) target[l] = phi_q[l] * scale[l];
    }
  lu_factor_lanes(lu_.data(), pivots_.data(), n_);
  // min/max |pivot| per lane, as solver::pivot_ratio (NaN where a pivot is not finite).
  double smallest[kLanes], largest[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) {
    smallest[l] = INFINITY;
    largest[l] = n_ == 1 ? length_scale_[l] : 0;
  }
  for (std::size_t c = 0; c < n_; ++c) {
    const double* pivot = lu_.data() + (c * n_ + c) * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double magnitude = std::fabs(pivot[l]);
      smallest[l] = magnitude < smallest[l] ? magnitude : smallest[l];
      largest[l] = magnitude > largest[l] ? magnitude : largest[l];
    }
  }
  for (std::size_t l = 0; l < kLanes; ++l) pivot_ratio_[l] = smallest[l] / largest[l];
}

void DesignLanes::solve_value(double input, bool check_branch, const double* take, double* ok) {
  const std::size_t n = n_;
  const auto& e = k_.evaluator();
  std::fill_n(lanes(layout_.input()), kLanes, input);
  for (std::size_t i = 0; i < n; ++i) std::copy_n(start_.data() + i * kLanes, kLanes, lanes(layout_.q(i)));
  // Workspace::solve_position's Newton lane by lane: a lane stops where max |Phi| is
  // within its tolerance; a step that does not lower it (the scalar solver would halve
  // it), a pivot not clearly regular or too many iterations leave the value to the
  // scalar run.
  double pending[kLanes], failed[kLanes], previous[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) {
    pending[l] = take[l];
    failed[l] = 1.0 - take[l];
    previous[l] = INFINITY;
  }
  for (int iteration = 0;; ++iteration) {
    e.evaluate_stage_batch_from(TapeLayout::kPositionStage,
                                iteration == 0 ? TapeLayout::kInputLevel : TapeLayout::kCoordinateLevel,
                                registers_.data());
    std::fill_n(residual_, kLanes, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double* phi = output(TapeLayout::kPositionStage, layout_.phi(i));
      for (std::size_t l = 0; l < kLanes; ++l) {
        const double magnitude = std::fabs(phi[l]);  // NaN stays: the comparison is false for it
        residual_[l] = (magnitude > residual_[l] || magnitude != magnitude) ? magnitude : residual_[l];
      }
    }
    factorise();
    int open = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const bool worse = !(residual_[l] < previous[l]) || !(pivot_ratio_[l] >= solver::kClearlyRegularPivotRatio);
      const bool lost = pending[l] != 0 && worse;
      failed[l] = lost ? 1.0 : failed[l];
      pending[l] = pending[l] != 0 && !lost && !(residual_[l] <= tolerance_[l]) ? 1.0 : 0.0;
      open += pending[l] != 0;
    }
    if (open == 0) break;
    if (iteration + 1 == kLaneIterations) {
      for (std::size_t l = 0; l < kLanes; ++l) failed[l] = pending[l] != 0 ? 1.0 : failed[l];
      break;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double* phi = output(TapeLayout::kPositionStage, layout_.phi(i));
      for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi[l];
    }
    lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
      double* q = lanes(layout_.q(i));
      const double* scale = column_scale_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) q[l] += pending[l] * x_[i * kLanes + l] * scale[l];
    }
    std::copy_n(residual_, kLanes, previous);
  }
  for (std::size_t l = 0; l < kLanes; ++l) ok[l] = failed[l] == 0 ? 1.0 : 0.0;
  // A predicted value stays on its branch (Workspace::predict_and_correct's test).
  if (check_branch) {
    for (std::size_t i = 0; i < n; ++i) {
      const double* q = lanes(layout_.q(i));
      const double* start = start_.data() + i * kLanes;
      const double* scale = column_scale_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l)
        ok[l] = std::fabs(q[l] - start[l]) / scale[l] > solver::kBranchTolerance ? 0.0 : ok[l];
    }
  }
  // Velocity, then acceleration, with the factorisation at the solution; then points.
  for (std::size_t i = 0; i < n; ++i) {
    const double* phi_theta = output(TapeLayout::kPositionStage, layout_.phi_theta(i));
    for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi_theta[l] * rate_;
  }
  lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    double* qd = lanes(layout_.qd(i));
    const double* scale = column_scale_.data() + i * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) qd[l] = x_[i * kLanes + l] * scale[l];
  }
  e.evaluate_stage_batch_from(TapeLayout::kAccelerationStage, TapeLayout::kInputLevel, registers_.data());
  for (std::size_t i = 0; i < n; ++i)
    std::copy_n(output(TapeLayout::kAccelerationStage, i), kLanes, x_.data() + i * kLanes);
  lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    double* qdd = lanes(layout_.qdd(i));
    const double* scale = column_scale_.data() + i * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) qdd[l] = x_[i * kLanes + l] * scale[l];
  }
  e.evaluate_stage_batch_from(TapeLayout::kPointStage, TapeLayout::kInputLevel, registers_.data());
  // x * 0 is 0 for finite x and NaN otherwise: one sum per lane says whether all are
  // finite (the scalar run calls a position singular where they are not).
  double nonfinite[kLanes] = {};
  const auto accumulate = [&](const double* v) {
    for (std::size_t l = 0; l < kLanes; ++l) nonfinite[l] += v[l] * 0.0;
  };
  for (std::size_t k = 0; k < layout_.observable_output_count(); ++k) accumulate(output(TapeLayout::kPointStage, k));
  for (std::size_t i = 0; i < n; ++i) {
    accumulate(lanes(layout_.qd(i)));
    accumulate(lanes(layout_.qdd(i)));
  }
  for (std::size_t l = 0; l < kLanes; ++l) ok[l] = nonfinite[l] == 0.0 ? ok[l] : 0.0;
}

void DesignLanes::store(std::size_t l, std::size_t row) {
  MotionTable& table = lanes_[l]->table;
  const std::size_t rows = table.size();
  table.set_ok(row, 1);
  table.loop_residuals()[row] = residual_[l];
  table.reciprocal_conditions()[row] = pivot_ratio_[l];
  for (std::size_t i = 0; i < n_; ++i) {
    table.q_values()[i * rows + row] = lanes(layout_.q(i))[l];
    table.qd_values()[i * rows + row] = lanes(layout_.qd(i))[l];
    table.qdd_values()[i * rows + row] = lanes(layout_.qdd(i))[l];
  }
  // The point stage's outputs (points, then frames) are in the table's point column order.
  double* points = table.point_values();
  for (std::size_t k = 0; k < layout_.observable_output_count(); ++k)
    points[k * rows + row] = output(TapeLayout::kPointStage, k)[l];
}

}  // namespace kinema
