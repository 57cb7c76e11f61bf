// What the two lane-parallel solvers share (BatchWorkspace: kLanes consecutive values of
// one design; DesignLanes: one value of kLanes designs): the batch tape's registers, the
// column-scaled LU of Phi_q with each lane's pivot ratio, Newton's step and the rates
// from that factorisation. Scales are kept lane by lane (the same in every lane for one
// design). The loops are inlined into each caller's KINEMA_LANE_LOOPS clones.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/lane_lu.hpp"

namespace kinema {

class LaneSystem {
 public:
  static constexpr std::size_t kLanes = kLuLanes;

 protected:
  explicit LaneSystem(const Kinematics& k)
      : k_(k),
        layout_(k.layout()),
        n_(k.unknown_count()),
        registers_(k.evaluator().make_batch_workspace()),
        lu_(n_ * n_ * kLanes),
        pivots_(n_ * kLanes),
        x_(n_ * kLanes),
        column_scale_(n_ * kLanes) {}

  /// Lane l's column scales and length scale: those of `design`.
  void set_scales(std::size_t l, const Kinematics& design) {
    length_scale_[l] = design.length_scale();
    for (std::size_t i = 0; i < n_; ++i) column_scale_[i * kLanes + l] = design.column_scale()[i];
  }

  double* lanes(std::size_t reg) { return registers_.data() + reg * kLanes; }
  const double* output(std::size_t stage, std::size_t k) { return lanes(k_.evaluator().output_register(stage, k)); }

  /// max |Phi| of each lane at the position stage just evaluated (NaN where one is).
  KINEMA_INLINE_LANES void largest_phi(double* norm) {
    std::fill_n(norm, kLanes, 0.0);
    for (std::size_t i = 0; i < n_; ++i) {
      const double* phi = output(TapeLayout::kPositionStage, layout_.phi(i));
      for (std::size_t l = 0; l < kLanes; ++l) {
        const double magnitude = std::fabs(phi[l]);  // NaN stays: the comparison is false for it
        norm[l] = (magnitude > norm[l] || magnitude != magnitude) ? magnitude : norm[l];
      }
    }
  }

  /// Column-scaled Phi_q from the registers, factorised; each lane's min/max |pivot| into
  /// pivot_ratio_, as solver::pivot_ratio (NaN where a pivot is not finite).
  KINEMA_INLINE_LANES void factorise() {
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t j = 0; j < n_; ++j) {
        const double* phi_q = output(TapeLayout::kPositionStage, layout_.phi_q(i, j));
        const double* scale = column_scale_.data() + j * kLanes;
        double* target = lu_.data() + (i * n_ + j) * kLanes;
        for (std::size_t l = 0; l < kLanes; ++l) target[l] = phi_q[l] * scale[l];
      }
    lu_factor_lanes(lu_.data(), pivots_.data(), n_);
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

  /// Newton's step with the factorisation, from Phi at the position stage just evaluated:
  /// q += weight[l] * the step (weight 1 for a lane that steps, 0 for one that stays).
  KINEMA_INLINE_LANES void newton_step(const double* weight) {
    for (std::size_t i = 0; i < n_; ++i) {
      const double* phi = output(TapeLayout::kPositionStage, layout_.phi(i));
      for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi[l];
    }
    lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n_);
    for (std::size_t i = 0; i < n_; ++i) {
      double* q = lanes(layout_.q(i));
      const double* scale = column_scale_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) q[l] += weight[l] * x_[i * kLanes + l] * scale[l];
    }
  }

  /// Velocity, then acceleration, with the factorisation at the solution; then points.
  KINEMA_INLINE_LANES void solve_rates(double rate) {
    const auto& e = k_.evaluator();
    for (std::size_t i = 0; i < n_; ++i) {
      const double* phi_theta = output(TapeLayout::kPositionStage, layout_.phi_theta(i));
      for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi_theta[l] * rate;
    }
    lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n_);
    scaled_solution_into(&TapeLayout::qd);
    e.evaluate_stage_batch_from(TapeLayout::kAccelerationStage, TapeLayout::kInputLevel, registers_.data());
    for (std::size_t i = 0; i < n_; ++i)
      std::copy_n(output(TapeLayout::kAccelerationStage, i), kLanes, x_.data() + i * kLanes);
    lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n_);
    scaled_solution_into(&TapeLayout::qdd);
    e.evaluate_stage_batch_from(TapeLayout::kPointStage, TapeLayout::kInputLevel, registers_.data());
  }

  /// Each lane's sum of x * 0 over the points' outputs and the rates: 0 where all are
  /// finite, NaN otherwise (the scalar run calls a position singular where they are not).
  KINEMA_INLINE_LANES void nonfinite_results(double* nonfinite) {
    std::fill_n(nonfinite, kLanes, 0.0);
    const auto accumulate = [&](const double* v) {
      for (std::size_t l = 0; l < kLanes; ++l) nonfinite[l] += v[l] * 0.0;
    };
    for (std::size_t k = 0; k < layout_.observable_output_count(); ++k) accumulate(output(TapeLayout::kPointStage, k));
    for (std::size_t i = 0; i < n_; ++i) {
      accumulate(lanes(layout_.qd(i)));
      accumulate(lanes(layout_.qdd(i)));
    }
  }

  const Kinematics& k_;
  const TapeLayout& layout_;
  std::size_t n_;
  std::vector<double> registers_;  ///< Register r of lane l at r * kLanes + l.
  std::vector<double> lu_;         ///< Element (i, j) of lane l at (i n + j) kLanes + l.
  std::vector<double> pivots_;     ///< Row chosen at column c for lane l at c kLanes + l.
  std::vector<double> x_;          ///< Right-hand sides and solutions, row i of lane l at i kLanes + l.
  std::vector<double> column_scale_;  ///< Unknown i's column scale of lane l at i kLanes + l.
  double length_scale_[kLanes] = {}, pivot_ratio_[kLanes] = {};

 private:
  /// x_ times the column scales into the register of each unknown's `rate` (qd or qdd).
  KINEMA_INLINE_LANES void scaled_solution_into(std::size_t (TapeLayout::*rate)(std::size_t) const) {
    for (std::size_t i = 0; i < n_; ++i) {
      double* target = lanes((layout_.*rate)(i));
      const double* scale = column_scale_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) target[l] = x_[i * kLanes + l] * scale[l];
    }
  }
};

}  // namespace kinema
