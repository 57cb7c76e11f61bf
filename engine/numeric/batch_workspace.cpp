#include "engine/numeric/batch_workspace.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "engine/numeric/lane_lu.hpp"
#include "engine/numeric/solver.hpp"

namespace kinema {

BatchWorkspace::BatchWorkspace(const Kinematics& k) : LaneSystem(k), predicted_(n_ * kLanes) { reload_parameters(); }

void BatchWorkspace::reload_parameters() {
  for (std::size_t p = 0; p < layout_.parameter_count; ++p)
    std::fill_n(lanes(layout_.parameter(p)), kLanes, k_.parameter_values()[p]);
  for (std::size_t l = 0; l < kLanes; ++l) set_scales(l, k_);
  k_.evaluator().prepare_batch(registers_.data());
}

bool BatchWorkspace::clearly_regular() const {
  // Clearly regular pivots only; anything near a toggle goes to the scalar path,
  // which decides singularity with the singular values (NaN compares false: not regular).
  int irregular = 0;
  for (std::size_t l = 0; l < kLanes; ++l) irregular += !(pivot_ratio_[l] >= solver::kClearlyRegularPivotRatio);
  return irregular == 0;
}

bool BatchWorkspace::predict(const MotionTable& table, std::size_t first, std::size_t history_begin) {
  const double rate = table.input_rate(), second_rate = table.input_second_rate();
  const std::size_t last = first - 1;
  const double t1 = table.input(last);
  const double reach = 4 * k_.max_continuation_step();
  for (std::size_t l = 0; l < kLanes; ++l)
    if (!(std::fabs(table.input(first + l) - t1) <= reach)) return false;
  // Quintic Hermite through the last row and the one a block earlier (values, first
  // and second derivatives in the input) when both are on the same stretch of
  // solved rows; else Taylor to second order from the last row.
  bool hermite = last >= history_begin + kLanes;
  const std::size_t earlier = hermite ? last - kLanes : last;
  for (std::size_t row = earlier; hermite && row <= last; ++row)
    hermite = table.status(row) == Status::ok && (row == earlier || table.failure(row).kind == Failure::Kind::none);
  const double t0 = table.input(earlier), span = t1 - t0;
  hermite = hermite && span != 0 && std::fabs(span) <= reach;
  for (std::size_t i = 0; i < n_; ++i) {
    auto derivatives = [&](std::size_t row, double& value, double& slope, double& curvature) {
      value = table.q(row)[i];
      slope = table.qd(row)[i] / rate;
      curvature = (table.qdd(row)[i] - slope * second_rate) / (rate * rate);
    };
    double y1, d1, c1;
    derivatives(last, y1, d1, c1);
    double* out = predicted_.data() + i * kLanes;
    if (!hermite) {
      const double value = table.q(last)[i], value_rate = table.qd(last)[i], value_second_rate = table.qdd(last)[i];
      for (std::size_t l = 0; l < kLanes; ++l) {
        out[l] = solver::predict_second_order(value, value_rate, value_second_rate, rate, second_rate,
                                              table.input(first + l) - t1);
      }
      continue;
    }
    double y0, d0, c0;
    derivatives(earlier, y0, d0, c0);
    // Newton form on the nodes t0, t0, t0, t1, t1, t1 (confluent divided differences).
    const double f01 = (y1 - y0) / span;
    const double f001 = (f01 - d0) / span, f011 = (d1 - f01) / span;
    const double f0001 = (f001 - 0.5 * c0) / span, f0011 = (f011 - f001) / span, f0111 = (0.5 * c1 - f011) / span;
    const double f00011 = (f0011 - f0001) / span, f00111 = (f0111 - f0011) / span;
    const double f000111 = (f00111 - f00011) / span;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double u = table.input(first + l) - t0, v = table.input(first + l) - t1;
      out[l] = y0 + u * (d0 + u * (0.5 * c0 + u * (f0001 + v * (f00011 + v * f000111))));
    }
  }
  return true;
}

bool BatchWorkspace::solve(MotionTable& table, std::size_t first, std::size_t history_begin, int sign) {
  return solve_lanes(table, first, history_begin, sign);
}

bool BatchWorkspace::solve_lanes(MotionTable& table, std::size_t first, std::size_t history_begin, int sign) {
  const std::size_t n = n_;
  const auto& e = k_.evaluator();
  const auto& column_scale = k_.column_scale();
  const double rate = table.input_rate(), second_rate = table.input_second_rate();
  const double tolerance = solver::kNewtonTolerance * k_.length_scale();
  if (!predict(table, first, history_begin)) return false;
  for (std::size_t l = 0; l < kLanes; ++l) {
    lanes(layout_.input())[l] = table.input(first + l);
    lanes(layout_.rate())[l] = rate;
    lanes(layout_.second_rate())[l] = second_rate;
  }
  for (std::size_t i = 0; i < n; ++i) std::copy_n(predicted_.data() + i * kLanes, kLanes, lanes(layout_.q(i)));

  // Newton on every lane at once; Phi_q is factorised at each iterate, so the last
  // factorisation (at the solution) also gives the rates. A lane that has converged
  // stays where it is, as the scalar solver stops there.
  double residual[kLanes];
  double unconverged[kLanes];  // 1 for a lane that steps on, 0 for one that has converged
  for (int iteration = 0;; ++iteration) {
    e.evaluate_stage_batch_from(TapeLayout::kPositionStage,
                                iteration == 0 ? TapeLayout::kInputLevel : TapeLayout::kCoordinateLevel,
                                registers_.data());
    largest_phi(residual);
    int nonfinite = 0, open = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      nonfinite += !(residual[l] <= DBL_MAX);
      unconverged[l] = residual[l] <= tolerance ? 0.0 : 1.0;
      open += !(residual[l] <= tolerance);
    }
    if (nonfinite) return false;
    factorise();
    if (!clearly_regular()) return false;
    if (open == 0) break;
    if (iteration == 6) return false;
    newton_step(unconverged);
  }
  // Same branch as predicted (as Workspace::predict_and_correct checks).
  int jumped = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double* q = lanes(layout_.q(i));
    const double* predicted = predicted_.data() + i * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l)
      jumped += !(std::fabs(q[l] - predicted[l]) <= solver::kBranchTolerance * column_scale[i]);
  }
  if (jumped) return false;
  // No toggle between the rows: det Phi_q keeps its sign (solver::lu_determinant_sign, lane by lane).
  if (sign == 0) return false;
  int turned = 0;
  for (std::size_t l = 0; l < kLanes; ++l) {
    int lane_sign = 1;
    for (std::size_t c = 0; c < n; ++c) {
      const double pivot = lu_[(c * n + c) * kLanes + l];
      lane_sign = (pivot < 0) != (pivots_[c * kLanes + l] != static_cast<double>(c)) ? -lane_sign : lane_sign;
    }
    turned += lane_sign != sign;
  }
  if (turned) return false;

  solve_rates(rate);
  const std::size_t point_values = layout_.observable_output_count();
  double nonfinite[kLanes];
  nonfinite_results(nonfinite);
  int bad = 0;
  for (std::size_t l = 0; l < kLanes; ++l) bad += nonfinite[l] != 0.0;
  if (bad) return false;

  // Lanes to rows: the table is column-major, so each quantity is one contiguous copy.
  table.set_ok(first, kLanes);
  const std::size_t rows = table.size();
  std::copy_n(residual, kLanes, table.loop_residuals() + first);
  std::copy_n(pivot_ratio_, kLanes, table.reciprocal_conditions() + first);
  for (std::size_t i = 0; i < n; ++i) {
    std::copy_n(lanes(layout_.q(i)), kLanes, table.q_values() + i * rows + first);
    std::copy_n(lanes(layout_.qd(i)), kLanes, table.qd_values() + i * rows + first);
    std::copy_n(lanes(layout_.qdd(i)), kLanes, table.qdd_values() + i * rows + first);
  }
  // The point stage's outputs (points, then frames) are in the table's point column order.
  for (std::size_t k = 0; k < point_values; ++k)
    std::copy_n(output(TapeLayout::kPointStage, k), kLanes, table.point_values() + k * rows + first);
  return true;
}

}  // namespace kinema
