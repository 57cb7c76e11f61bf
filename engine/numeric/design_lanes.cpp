#include "engine/numeric/design_lanes.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>

#include "engine/numeric/solver.hpp"
#include "engine/numeric/sweep.hpp"

namespace kinema {

namespace {
// Newton iterations a lane gets; one that needs more is solved by the scalar run (a
// value predicted from 1 deg back converges in 3 or 4, the first one from the guesses
// in about 6).
constexpr int kLaneIterations = 10;

// The closed form is used where the two branches lie further apart than this fraction of
// the terms' lengths (its angles then good to about 1e-16 over it), and the prediction
// within a tenth of that distance of its branch (clearly on it) and 0.02 rad.
constexpr double kFoldedTriangle = 1e-3;
constexpr double kLargestCorrection = 0.02;

// `guess` moved to the angle of (cos_angle, sin_angle) nearest it, without atan2 (which
// has no vector form): atan of the difference's tangent by its series, which to t^11 is
// exact in doubles for |t| < kLargestCorrection. `usable` falls to 0 where the difference's
// tangent squared is not below `largest_square` (NaN too).
inline double angle_near(double guess, double cos_guess, double sin_guess, double cos_angle, double sin_angle,
                         double largest_square, double& usable) {
  const double sin_difference = sin_angle * cos_guess - cos_angle * sin_guess;
  const double cos_difference = cos_angle * cos_guess + sin_angle * sin_guess;
  const double t = sin_difference / cos_difference, t2 = t * t;
  usable = ((cos_difference > 0) & (t2 < largest_square)) ? usable : 0.0;
  const double atan_t =
      t * (1 + t2 * (-1.0 / 3 + t2 * (1.0 / 5 + t2 * (-1.0 / 7 + t2 * (1.0 / 9 + t2 * (-1.0 / 11))))));
  return guess + atan_t;
}
}  // namespace

LoopReach::LoopReach(double crank, double fixed_x, double fixed_y, double first, double second)
    : crank_(crank), fixed_x_(fixed_x), fixed_y_(fixed_y), first_(std::fabs(first)), second_(std::fabs(second)) {
  // A margin of a thousand times Newton's rounding tolerance of the lengths' sum (at
  // least the length scale Newton's tests use): nearer the reach, Newton decides.
  const double fixed = std::hypot(fixed_x, fixed_y), turning = std::fabs(crank);
  const double margin = 1e3 * solver::kRoundingTolerance * (turning + fixed + first_ + second_);
  const double far = first_ + second_ + margin, near = std::fabs(first_ - second_) - margin;
  // NaN anywhere: no reach (every comparison false).
  if (!(far > 0)) return;
  far_square_ = far * far;
  near_square_ = near > 0 ? near * near : -INFINITY;
  // The known sum's length runs over [|fixed - turning|, fixed + turning] in a turn.
  ever_open_ = fixed + turning > far || std::fabs(fixed - turning) < near;
}

double LoopReach::distance(double input) const {
  const double x = crank_ * std::cos(input) + fixed_x_, y = crank_ * std::sin(input) + fixed_y_;
  const double known_sum = std::hypot(x, y);
  return std::max(known_sum - (first_ + second_), std::fabs(first_ - second_) - known_sum);
}

double LoopReach::limit(double from, double to) const {
  for (int halving = 0; halving < 60 && from != to; ++halving) {
    const double middle = from + (to - from) / 2;
    if (middle == from || middle == to) break;
    (distance(middle) <= 0 ? from : to) = middle;
  }
  return from;
}

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
    : LaneSystem(kinematics),
      inputs_(inputs),
      cos_inputs_(inputs.size()),
      sin_inputs_(inputs.size()),
      rate_(rate),
      second_rate_(second_rate),
      start_(n_ * kLanes),
      step_(n_ * kLanes),
      phi_(n_ * kLanes),
      previous_(3 * n_ * kLanes),
      largest_speed_(kinematics.point_count() * kLanes),
      largest_acceleration_(kinematics.point_count() * kLanes),
      largest_speed_square_(kinematics.point_count() * kLanes),
      largest_acceleration_square_(kinematics.point_count() * kLanes),
      largest_rate_(n_ * kLanes),
      largest_second_rate_(n_ * kLanes),
      predicted_(n_ * kLanes) {
  for (std::size_t row = 0; row < inputs.size(); ++row) {
    cos_inputs_[row] = std::cos(inputs[row]);
    sin_inputs_[row] = std::sin(inputs[row]);
  }
  for (std::size_t l = 0; l < kLanes; ++l) {
    lanes_.push_back(std::make_unique<Lane>(kinematics, inputs, rate, second_rate));
    set_design(l, kinematics.parameter_values().data());
  }
  std::fill_n(measure_offset_, kLanes, NAN);
  std::fill_n(lanes(layout_.rate()), kLanes, rate);
  std::fill_n(lanes(layout_.second_rate()), kLanes, second_rate);
}

DesignLanes::~DesignLanes() = default;

const MotionTable& DesignLanes::table(std::size_t lane) const { return lanes_[lane]->table; }

void DesignLanes::set_design(std::size_t l, const double* values) {
  Kinematics& k = lanes_[l]->kinematics;
  k.set_parameter_values(values);
  for (std::size_t p = 0; p < layout_.parameter_count; ++p) lanes(layout_.parameter(p))[l] = values[p];
  set_scales(l, k);
  tolerance_[l] = solver::kNewtonTolerance * k.length_scale();
}

void DesignLanes::set_reach(std::size_t lane, const LoopReach& reach) {
  // A design within reach all round: no test per value.
  reach_[lane] = reach.ever_open() ? reach : LoopReach();
}

void DesignLanes::set_closure(std::size_t lane, const LoopClosure& closure) {
  closes_[lane] = 1.0;
  closure_crank_[lane] = closure.crank;
  closure_fixed_x_[lane] = closure.fixed_x;
  closure_fixed_y_[lane] = closure.fixed_y;
  closure_over_first_[lane] = 1 / closure.first;
  closure_over_second_[lane] = 1 / closure.second;
  closure_over_length_square_[lane] = 1 / std::max(closure.first * closure.first, closure.second * closure.second);
  closure_first_[lane] = closure.first;
  closure_second_[lane] = closure.second;
  closure_unknowns_[0] = closure.first_unknown;
  closure_unknowns_[1] = closure.second_unknown;
}

void DesignLanes::set_point_terms(const std::vector<ClosedPointTerm>& terms) {
  point_terms_ = terms;
  point_term_factors_.assign(2 * terms.size() * kLanes, 0.0);
  closed_points_.assign(layout_.point_output_count() * kLanes, 0.0);
  // Two angles and planar points only: what the loop's closed form covers.
  closed_rates_ = n_ == 2 && layout_.frame_count == 0 &&
                  std::all_of(layout_.point_dimensions.begin(), layout_.point_dimensions.end(),
                              [](std::size_t d) { return d == 2; });
}

void DesignLanes::set_point_term_values(std::size_t lane, const double* factors) {
  for (std::size_t t = 0; t < 2 * point_terms_.size(); ++t) point_term_factors_[t * kLanes + lane] = factors[t];
}

void DesignLanes::solve(std::size_t count) {
  k_.evaluator().prepare_batch(registers_.data());  // each lane's work on its parameters
  for (std::size_t l = 0; l < count; ++l) {
    lanes_[l]->rows.start();
    lanes_[l]->last_in_lanes = false;
    // Every row ok with nothing to report until the scalar run stores one (store() then
    // writes only the numbers).
    lanes_[l]->table.set_ok(0, inputs_.size());
  }
  lane_values_ = 0;
  closed_form_values_ = 0;
  closed_rate_values_ = 0;
  std::fill(largest_speed_.begin(), largest_speed_.end(), NAN);
  std::fill(largest_acceleration_.begin(), largest_acceleration_.end(), NAN);
  std::fill(largest_speed_square_.begin(), largest_speed_square_.end(), 0.0);
  std::fill(largest_acceleration_square_.begin(), largest_acceleration_square_.end(), 0.0);
  std::fill(largest_rate_.begin(), largest_rate_.end(), NAN);
  std::fill(largest_second_rate_.begin(), largest_second_rate_.end(), NAN);
  std::fill_n(least_measure_, kLanes, NAN);
  std::fill_n(least_first_, kLanes, NAN);  // a design that never assembles has no angles
  std::fill_n(least_second_, kLanes, NAN);
  if (positions_and_rates_) {
    kept_.resize(2 * n_ * inputs_.size() * kLanes);
    kept_ok_.resize(inputs_.size() * kLanes);
  }
  double take[kLanes], ok[kLanes], restart[kLanes], open[kLanes], out_of_reach[kLanes];
  for (std::size_t row = 0; row < inputs_.size(); ++row) {
    bool restarts = choose_lanes(row, count, take, restart, out_of_reach);
    std::fill_n(ok, kLanes, 0.0);
    std::fill_n(open, kLanes, 0.0);
    bool closed = false;
    if (std::find(take, take + kLanes, 1.0) != take + kLanes) {
      // Lanes on the loop's closed form take its numbers, the others Newton's: each lane's
      // the same whichever designs share the batch.
      const std::size_t taken = static_cast<std::size_t>(std::count(take, take + kLanes, 1.0));
      const bool some = closed_rates_ && closed_lanes_ > 0, every = some && closed_lanes_ == taken;
      if (!every) solve_value(inputs_[row], row > 0, take, ok);
      if (some) closed_value(row, row > 0, !every, ok);
      closed = some;
      keep_largest(ok, closed);
      keep_previous(ok);
    }
    // The first value, from the guesses, is Newton alone: where the undamped steps did
    // not close it, the damped ones decide whether it stays open.
    for (std::size_t l = 0; row == 0 && l < count; ++l) {
      restart[l] = take[l] != 0 && ok[l] == 0 && lanes_[l]->rows.restart_position() != nullptr ? 1.0 : 0.0;
      restarts = restarts || restart[l] != 0;
    }
    keep_row(row, ok);
    for (std::size_t l = 0; l < count && !positions_and_rates_; ++l)
      if (ok[l] != 0) store(l, row, closed);
    if (restarts) restart_values(inputs_[row], restart, open);
    for (std::size_t l = 0; l < count; ++l) {
      Lane& lane = *lanes_[l];
      if (out_of_reach[l] != 0) {
        hand_over(l, row);
        // Where the gap starts only after an ok row (where the run continues from it).
        const double limit = lane.rows.on_branch() ? reach_[l].limit(inputs_[row - 1], inputs_[row]) : inputs_[row];
        lane.rows.unassembled_elsewhere(lane.table, row, limit, 0, reach_[l].distance(inputs_[row]));
        ++lane_values_;
        continue;
      }
      if (ok[l] != 0) {
        lane.last_in_lanes = true;
        ++lane_values_;
        continue;
      }
      if (open[l] != 0) {
        lane.rows.failed_elsewhere(lane.table, row, lane.kinematics.equation_group(worst_row_[l]), residual_[l]);
        ++lane_values_;
        continue;
      }
      hand_over(l, row);
      lane.rows.solve(lane.table, row);
      if (lane.table.status(row) != Status::unassembled) keep_measure(l, lane.table, row);
      if (lane.table.status(row) != Status::ok) continue;
      keep_largest(l, row);
      for (std::size_t i = 0; i < n_; ++i) {
        previous_[(3 * i) * kLanes + l] = lane.table.q_column(i)[row];
        previous_[(3 * i + 1) * kLanes + l] = lane.table.qd_column(i)[row];
        previous_[(3 * i + 2) * kLanes + l] = lane.table.qdd_column(i)[row];
      }
    }
  }
  count_values_solved(lane_values_);
}

bool DesignLanes::choose_lanes(std::size_t row, std::size_t count, double* take, double* restart,
                               double* out_of_reach) {
  bool any_restart = false;
  const double h = row > 0 ? inputs_[row] - inputs_[row - 1] : 0.0;
  for (std::size_t l = 0; l < kLanes; ++l) {
    Lane& lane = *lanes_[l];
    const Eigen::VectorXd* from = &lane.kinematics.guess();  // any finite position keeps a lane not solved quiet
    bool predicted = false, restarted = false;
    out_of_reach[l] = l < count && reach_[l].clearly_open(cos_inputs_[row], sin_inputs_[row]) ? 1.0 : 0.0;
    if (out_of_reach[l] != 0) {
      // Neither predicted nor restarted: solve() stores it as not assembling.
    } else if (l < count && row == 0) {
      // The first value from the guesses where the scalar run starts so (Newton alone);
      // else the scalar run's (the file's assembly carried to it).
      predicted = lane.kinematics.closed_form() == nullptr && lane.rows.restart_position() != nullptr;
    } else if (l < count && (lane.last_in_lanes || lane.rows.on_branch())) {
      // The scalar run's fast path: from the last row, ok, predicted by its rates.
      predicted = std::fabs(h) <= lane.kinematics.max_continuation_step();
    } else if (l < count) {
      const Eigen::VectorXd* position = lane.rows.restart_position();
      restarted = position != nullptr;
      if (restarted) from = position;
    }
    if (!predicted || row == 0)
      for (std::size_t i = 0; i < n_; ++i) start_[i * kLanes + l] = (*from)[Eigen::Index(i)];
    take[l] = predicted ? 1.0 : 0.0;
    restart[l] = restarted ? 1.0 : 0.0;
    any_restart = any_restart || restarted;
  }
  if (row > 0) predict(h, take);
  std::copy(start_.begin(), start_.end(), predicted_.begin());
  std::fill_n(closed_, kLanes, 0.0);
  closed_lanes_ = row > 0 ? close_loops(row, take) : 0;
  closed_form_values_ += closed_lanes_;
  return any_restart;
}

void DesignLanes::predict(double h, const double* predicted) {
  for (std::size_t i = 0; i < n_; ++i) {
    const double* q = previous_.data() + (3 * i) * kLanes;
    const double* qd = previous_.data() + (3 * i + 1) * kLanes;
    const double* qdd = previous_.data() + (3 * i + 2) * kLanes;
    double* start = start_.data() + i * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double value = solver::predict_second_order(q[l], qd[l], qdd[l], rate_, second_rate_, h);
      start[l] = predicted[l] != 0 ? value : start[l];
    }
  }
}

std::size_t DesignLanes::close_loops(std::size_t row, const double* predicted) {
  const double cos_input = cos_inputs_[row], sin_input = sin_inputs_[row];
  double* first_angle = start_.data() + closure_unknowns_[0] * kLanes;
  double* second_angle = start_.data() + closure_unknowns_[1] * kLanes;
  double moved = 0;
  for (std::size_t l = 0; l < kLanes; ++l) {
    const double u = closure_first_[l], v = closure_second_[l];
    // first e^(i alpha) + second e^(i beta) = w, the known terms' sum negated: the first
    // term P lies `along` times w along it and `across` times w across it (x and y of
    // the triangle |P| = |u|, |w - P| = |v|, over |w|: no root of |w|^2 needed).
    const double wx = -(closure_crank_[l] * cos_input + closure_fixed_x_[l]);
    const double wy = -(closure_crank_[l] * sin_input + closure_fixed_y_[l]);
    const double w_square = wx * wx + wy * wy, over_w_square = 1 / w_square;
    const double along = 0.5 * (u * u - v * v + w_square) * over_w_square;
    const double across_square = u * u * over_w_square - along * along;
    double sin_first, cos_first, sin_second, cos_second;
    simd::sincos_reduced(first_angle[l], sin_first, cos_first);
    simd::sincos_reduced(second_angle[l], sin_second, cos_second);
    // The branch of the predicted first term: its side of w.
    const double side = u * (wx * sin_first - wy * cos_first);
    const double across = std::copysign(std::sqrt(std::fabs(across_square)), side);
    const double px = along * wx - across * wy, py = along * wy + across * wx;
    // y^2 over the longer term's length squared: how far from folded in line.
    const double fold = across_square * w_square * closure_over_length_square_[l];
    // (& of the tests, not &&: no branches in a loop across lanes.)
    const bool closes = (predicted[l] != 0) & (closes_[l] != 0) & (fold > kFoldedTriangle * kFoldedTriangle) &
                        (std::fabs(first_angle[l]) <= simd::kSinCosLimit) &
                        (std::fabs(second_angle[l]) <= simd::kSinCosLimit);
    double usable = closes ? 1.0 : 0.0;
    // Clearly on its branch: the other is 2|y| away, an angle of about 2|y| / length.
    const double largest_square = std::min(kLargestCorrection * kLargestCorrection, 0.01 * fold);
    const double alpha = angle_near(first_angle[l], cos_first, sin_first, px * closure_over_first_[l],
                                    py * closure_over_first_[l], largest_square, usable);
    const double beta = angle_near(second_angle[l], cos_second, sin_second, (wx - px) * closure_over_second_[l],
                                   (wy - py) * closure_over_second_[l], largest_square, usable);
    first_angle[l] = usable != 0 ? alpha : first_angle[l];
    second_angle[l] = usable != 0 ? beta : second_angle[l];
    closed_[l] = usable;
    first_x_[l] = px;
    first_y_[l] = py;
    second_x_[l] = wx - px;
    second_y_[l] = wy - py;
    moved += usable;
  }
  return static_cast<std::size_t>(moved);
}

void DesignLanes::keep_previous(const double* ok) {
  for (std::size_t i = 0; i < n_; ++i) {
    const double* from[3] = {lanes(layout_.q(i)), lanes(layout_.qd(i)), lanes(layout_.qdd(i))};
    for (std::size_t k = 0; k < 3; ++k) {
      double* to = previous_.data() + (3 * i + k) * kLanes;
      const double* solved = from[k];
      for (std::size_t l = 0; l < kLanes; ++l) {
        const double value = solved[l], kept = to[l];  // both read: a select, not a masked load
        to[l] = ok[l] != 0 ? value : kept;
      }
    }
  }
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
    largest_phi(residual_);
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
    newton_step(pending);
    std::copy_n(residual_, kLanes, previous);
  }
  for (std::size_t l = 0; l < kLanes; ++l) ok[l] = failed[l] == 0 ? 1.0 : 0.0;
  // A predicted value stays on its branch (Workspace::predict_and_correct's test).
  if (check_branch) {
    for (std::size_t i = 0; i < n; ++i) {
      const double* q = lanes(layout_.q(i));
      const double* start = predicted_.data() + i * kLanes;
      const double* scale = column_scale_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l)
        ok[l] = std::fabs(q[l] - start[l]) / scale[l] > solver::kBranchTolerance ? 0.0 : ok[l];
    }
  }
  solve_rates(rate_);
  // The scalar run calls a position singular where the results are not all finite.
  double nonfinite[kLanes];
  nonfinite_results(nonfinite);
  for (std::size_t l = 0; l < kLanes; ++l) ok[l] = nonfinite[l] == 0.0 ? ok[l] : 0.0;
}

void DesignLanes::closed_value(std::size_t row, bool check_branch, bool merge, double* ok) {
  ++closed_rate_values_;
  const std::size_t first = closure_unknowns_[0], second = closure_unknowns_[1];
  const double* first_scale = column_scale_.data() + first * kLanes;
  const double* second_scale = column_scale_.data() + second * kLanes;
  const double cos_input = cos_inputs_[row], sin_input = sin_inputs_[row];
  const double rate = rate_, input_second_rate = second_rate_;
  // Each variable's e^(i angle), rate and second rate (the input, the first and second
  // unknowns): what the points' terms turn with. Written to local arrays only, so that
  // the loop runs across lanes (no store that might alias what it reads).
  double turn_x[3][kLanes], turn_y[3][kLanes], omega[3][kLanes], omega_rate[3][kLanes], regular[kLanes],
      ratios[kLanes], residuals[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) {
    // The loop: C + fixed + A + B = 0, A = first e^(i alpha), B = second e^(i beta), the
    // crank's term C = crank e^(i input). Its velocity equations: i (input' C + alpha' A +
    // beta' B) = 0, so alpha' A + beta' B = -input' C.
    const double ax = first_x_[l], ay = first_y_[l], bx = second_x_[l], by = second_y_[l];
    const double cx = closure_crank_[l] * cos_input, cy = closure_crank_[l] * sin_input;
    const double determinant = ax * by - ay * bx, over = 1 / determinant;
    const double alpha_rate = -rate * (cx * by - cy * bx) * over;
    const double beta_rate = -rate * (ax * cy - ay * cx) * over;
    // Differentiated once more: alpha'' A + beta'' B = -input'' C - i S, S = alpha'^2 A +
    // beta'^2 B + input'^2 C.
    const double sx = alpha_rate * alpha_rate * ax + beta_rate * beta_rate * bx + rate * rate * cx;
    const double sy = alpha_rate * alpha_rate * ay + beta_rate * beta_rate * by + rate * rate * cy;
    const double rx = -input_second_rate * cx + sy, ry = -input_second_rate * cy - sx;
    // Phi_q (rows: the loop's real and imaginary parts; columns i A, i B) column-scaled,
    // factorised with partial pivoting: its pivots' ratio, as factorise() finds it.
    const double m00 = std::fabs(ay * first_scale[l]), m10 = std::fabs(ax * first_scale[l]);
    const double pivot = m00 > m10 ? m00 : m10;
    const double other = std::fabs(determinant * first_scale[l] * second_scale[l]) / pivot;
    const double ratio = (pivot < other ? pivot : other) / (pivot < other ? other : pivot);
    regular[l] = ratio >= solver::kClearlyRegularPivotRatio ? 1.0 : 0.0;
    ratios[l] = ratio;
    // max |Phi| of the closed form's own terms (rounding: they close by construction).
    const double phi_x = std::fabs(cx + closure_fixed_x_[l] + ax + bx), phi_y = std::fabs(cy + closure_fixed_y_[l] + ay + by);
    residuals[l] = phi_x > phi_y ? phi_x : phi_y;
    turn_x[0][l] = cos_input, turn_y[0][l] = sin_input;
    turn_x[1][l] = ax * closure_over_first_[l], turn_y[1][l] = ay * closure_over_first_[l];
    turn_x[2][l] = bx * closure_over_second_[l], turn_y[2][l] = by * closure_over_second_[l];
    omega[0][l] = rate, omega[1][l] = alpha_rate, omega[2][l] = beta_rate;
    omega_rate[0][l] = input_second_rate;
    omega_rate[1][l] = (rx * by - ry * bx) * over;
    omega_rate[2][l] = (ax * ry - ay * rx) * over;
  }
  // The lanes on the closed form (closed_) take its numbers; the others keep solve_value's.
  const auto take_closed = [&](double* target, const double* value) {
    for (std::size_t l = 0; l < kLanes; ++l) target[l] = closed_[l] != 0 ? value[l] : target[l];
  };
  for (std::size_t i = 0; i < n_; ++i) take_closed(lanes(layout_.q(i)), start_.data() + i * kLanes);
  take_closed(lanes(layout_.qd(first)), omega[1]);
  take_closed(lanes(layout_.qd(second)), omega[2]);
  take_closed(lanes(layout_.qdd(first)), omega_rate[1]);
  take_closed(lanes(layout_.qdd(second)), omega_rate[2]);
  take_closed(pivot_ratio_, ratios);
  take_closed(residual_, residuals);
  double closed_ok[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) closed_ok[l] = regular[l];
  // The points: each term Z = factor e^(i variable) moves at i omega Z and accelerates at
  // (i omega' - omega^2) Z.
  std::fill(closed_points_.begin(), closed_points_.end(), 0.0);
  for (std::size_t t = 0; t < point_terms_.size(); ++t) {
    const int variable = point_terms_[t].variable;
    const std::size_t slot = variable < 0 ? 0 : std::size_t(variable) == first ? 1 : 2;
    const std::size_t at = layout_.point_output(point_terms_[t].point);
    const double* factor_x = point_term_factors_.data() + (2 * t) * kLanes;
    const double* factor_y = point_term_factors_.data() + (2 * t + 1) * kLanes;
    double* velocity_x = closed_points_.data() + (at + 2) * kLanes;
    double* velocity_y = velocity_x + kLanes;
    double* acceleration_x = closed_points_.data() + (at + 4) * kLanes;
    double* acceleration_y = acceleration_x + kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double zx = factor_x[l] * turn_x[slot][l] - factor_y[l] * turn_y[slot][l];
      const double zy = factor_x[l] * turn_y[slot][l] + factor_y[l] * turn_x[slot][l];
      const double w = omega[slot][l], w_rate = omega_rate[slot][l], w_square = w * w;
      velocity_x[l] -= w * zy;
      velocity_y[l] += w * zx;
      acceleration_x[l] -= w_rate * zy + w_square * zx;
      acceleration_y[l] += w_rate * zx - w_square * zy;
    }
  }
  // A predicted value stays on its branch (as solve_value tests it).
  if (check_branch) {
    for (std::size_t i = 0; i < n_; ++i) {
      const double* q = start_.data() + i * kLanes;
      const double* predicted = predicted_.data() + i * kLanes;
      const double* scale = column_scale_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l)
        closed_ok[l] = std::fabs(q[l] - predicted[l]) / scale[l] > solver::kBranchTolerance ? 0.0 : closed_ok[l];
    }
  }
  double nonfinite[kLanes] = {};  // x * 0 is 0 for finite x, NaN otherwise
  for (std::size_t k = 0; k < closed_points_.size(); k += kLanes)
    for (std::size_t l = 0; l < kLanes; ++l) nonfinite[l] += closed_points_[k + l] * 0.0;
  for (std::size_t l = 0; l < kLanes; ++l) {
    nonfinite[l] += (omega[1][l] + omega[2][l] + omega_rate[1][l] + omega_rate[2][l]) * 0.0;
    ok[l] = closed_[l] != 0 ? (nonfinite[l] == 0.0 ? closed_ok[l] : 0.0) : ok[l];
  }
  // The others' points from the tape's point stage (solve_value's), beside these.
  for (std::size_t p = 0; merge && p < layout_.point_dimensions.size(); ++p)
    for (std::size_t kind = 1; kind <= 2; ++kind)
      for (std::size_t c = 0; c < 2; ++c) {
        const double* tape = output(TapeLayout::kPointStage, layout_.point_output(p) + 2 * kind + c);
        double* value = closed_points_.data() + (layout_.point_output(p) + 2 * kind + c) * kLanes;
        for (std::size_t l = 0; l < kLanes; ++l) value[l] = closed_[l] != 0 ? value[l] : tape[l];
      }
}

void DesignLanes::restart_values(double input, const double* restart, double* open) {
  const std::size_t n = n_;
  const auto& e = k_.evaluator();
  std::fill_n(lanes(layout_.input()), kLanes, input);
  for (std::size_t i = 0; i < n; ++i) std::copy_n(start_.data() + i * kLanes, kLanes, lanes(layout_.q(i)));
  // Each lane is at a position it accepted (stepping: a step to take from it next) or at
  // a trial on its step (lambda_ times it); every evaluation serves both. start_ holds
  // the position accepted.
  double active[kLanes], stepping[kLanes], lambda[kLanes], norm[kLanes], halvings[kLanes], iterations[kLanes];
  double scalar[kLanes];  // 1: the scalar run solves the value (it closes, or needs least squares)
  for (std::size_t l = 0; l < kLanes; ++l) {
    active[l] = restart[l];
    stepping[l] = 1.0;
    lambda[l] = 1.0;
    norm[l] = INFINITY;
    halvings[l] = iterations[l] = 0.0;
    scalar[l] = 0.0;
  }
  const double rounding_factor = solver::kRoundingTolerance / solver::kNewtonTolerance;
  for (int evaluation = 0;; ++evaluation) {
    e.evaluate_stage_batch_from(TapeLayout::kPositionStage,
                                evaluation == 0 ? TapeLayout::kInputLevel : TapeLayout::kCoordinateLevel,
                                registers_.data());
    double trial_norm[kLanes];
    largest_phi(trial_norm);
    // The first evaluation is at the start (accepted as it is); later ones at trials,
    // accepted where they lower max |Phi| (a finite one), else the step is halved. Every
    // lane in selects, so that the loops run across lanes.
    const bool first = evaluation == 0;
    double accepted[kLanes];
    int stepping_lanes = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const bool is_active = active[l] != 0;
      const bool accept = is_active && (first || (trial_norm[l] <= DBL_MAX && trial_norm[l] < norm[l]));
      accepted[l] = accept ? 1.0 : 0.0;
      norm[l] = accept ? trial_norm[l] : norm[l];
      iterations[l] += accept && !first ? 1.0 : 0.0;
      const bool finite = norm[l] <= DBL_MAX, closes = norm[l] <= tolerance_[l];
      const bool stops = !finite || closes || iterations[l] == solver::kNewtonIterations;
      scalar[l] = accept && (closes || !finite) ? 1.0 : scalar[l];
      const bool halved = is_active && !accept;
      halvings[l] += halved ? 1.0 : 0.0;
      lambda[l] *= halved ? 0.5 : 1.0;
      active[l] = !is_active || (accept && stops) || (halved && halvings[l] == solver::kStepHalvings) ? 0.0 : 1.0;
      stepping[l] = active[l] != 0 && accept ? 1.0 : 0.0;
      stepping_lanes += stepping[l] != 0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double* q = lanes(layout_.q(i));
      const double* phi = output(TapeLayout::kPositionStage, layout_.phi(i));
      double* position = start_.data() + i * kLanes;
      double* kept_phi = phi_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) {
        position[l] = accepted[l] != 0 ? q[l] : position[l];
        kept_phi[l] = accepted[l] != 0 ? phi[l] : kept_phi[l];
      }
    }
    if (stepping_lanes > 0) {
      // A Newton step from each lane's accepted position (this evaluation's, for a lane
      // that just accepted one); the scalar solver's least-squares step is the scalar run's.
      factorise();
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t l = 0; l < kLanes; ++l) x_[i * kLanes + l] = -phi_[i * kLanes + l];
      lu_solve_lanes(lu_.data(), pivots_.data(), x_.data(), n);
      double nonfinite[kLanes] = {};  // x * 0 is 0 for finite x, NaN otherwise
      for (std::size_t i = 0; i < n; ++i) {
        double* step = step_.data() + i * kLanes;
        const double* x = x_.data() + i * kLanes;
        const double* scale = column_scale_.data() + i * kLanes;
        for (std::size_t l = 0; l < kLanes; ++l) {
          const double value = x[l] * scale[l];
          step[l] = stepping[l] != 0 ? value : step[l];
          nonfinite[l] += stepping[l] != 0 ? value * 0.0 : 0.0;
        }
      }
      for (std::size_t l = 0; l < kLanes; ++l) {
        const bool steps = stepping[l] != 0;
        const bool least_squares = steps && !(pivot_ratio_[l] > solver::kLeastSquaresPivotRatio);
        scalar[l] = least_squares ? 1.0 : scalar[l];
        active[l] = steps && (least_squares || nonfinite[l] != 0) ? 0.0 : active[l];
        lambda[l] = steps ? 1.0 : lambda[l];
        halvings[l] = steps ? 0.0 : halvings[l];
      }
    }
    int open_lanes = 0;
    for (std::size_t i = 0; i < n; ++i) {
      double* q = lanes(layout_.q(i));
      const double* from = start_.data() + i * kLanes;
      const double* step = step_.data() + i * kLanes;
      for (std::size_t l = 0; l < kLanes; ++l) q[l] = active[l] != 0 ? from[l] + lambda[l] * step[l] : from[l];
    }
    for (std::size_t l = 0; l < kLanes; ++l) open_lanes += active[l] != 0;
    if (open_lanes == 0) break;
  }
  for (std::size_t l = 0; l < kLanes; ++l) {
    // Stopped within rounding of closing counts as closed (solve_position's last test).
    const bool rounding = norm[l] <= rounding_factor * tolerance_[l];
    open[l] = restart[l] != 0 && scalar[l] == 0 && !rounding ? 1.0 : 0.0;
    residual_[l] = norm[l];
    // The equation whose |Phi| is largest (the first of equals), as solve_position names it.
    std::size_t worst = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (std::fabs(phi_[i * kLanes + l]) > std::fabs(phi_[worst * kLanes + l])) worst = i;
    worst_row_[l] = worst;
  }
}

void DesignLanes::store(std::size_t l, std::size_t row, bool closed) {
  MotionTable& table = lanes_[l]->table;
  const std::size_t rows = table.size();
  double* q = table.q_values();
  double* qd = table.qd_values();
  for (std::size_t i = 0; i < n_; ++i) {
    q[i * rows + row] = lanes(layout_.q(i))[l];
    qd[i * rows + row] = lanes(layout_.qd(i))[l];
  }
  table.loop_residuals()[row] = residual_[l];
  table.reciprocal_conditions()[row] = pivot_ratio_[l];
  for (std::size_t i = 0; i < n_; ++i) table.qdd_values()[i * rows + row] = lanes(layout_.qdd(i))[l];
  const std::vector<std::size_t>& dimensions = layout_.point_dimensions;
  for (std::size_t p = 0; p < dimensions.size(); ++p)
    for (std::size_t kind = 1; kind <= 2; ++kind)
      for (std::size_t c = 0; c < dimensions[p]; ++c) {
        const std::size_t column = kind * dimensions[p] + c;
        double* values = table.point_values() + (table.point_column(p, column) - table.point_values());
        values[row] = point_vector(closed, p, kind, c)[l];
      }
}

void DesignLanes::keep_row(std::size_t row, const double* ok) {
  if (positions_and_rates_) {
    double* kept = kept_.data() + 2 * n_ * row * kLanes;
    for (std::size_t i = 0; i < n_; ++i) {
      std::copy_n(lanes(layout_.q(i)), kLanes, kept + i * kLanes);
      std::copy_n(lanes(layout_.qd(i)), kLanes, kept + (n_ + i) * kLanes);
    }
    std::copy_n(ok, kLanes, kept_ok_.data() + row * kLanes);
  }
  if (n_ < 2) return;  // no measure
  const double* first = lanes(layout_.q(measure_unknowns_[0]));
  const double* second = lanes(layout_.q(measure_unknowns_[1]));
  for (std::size_t l = 0; l < kLanes; ++l) {
    // A value solved in the lanes assembles; the first of equal measures kept (as a scan
    // of the rows in order keeps it). A NaN offset: no measure.
    const double offset = measure_offset_[l], measure = angle_magnitude(second[l] - first[l] + offset);
    const bool less = (ok[l] != 0) & (offset == offset) & !(measure >= least_measure_[l]);
    least_measure_[l] = less ? measure : least_measure_[l];
    least_first_[l] = less ? first[l] : least_first_[l];
    least_second_[l] = less ? second[l] : least_second_[l];
  }
}

void DesignLanes::keep_measure(std::size_t l, const MotionTable& table, std::size_t row) {
  if (std::isnan(measure_offset_[l])) return;
  const double first = table.q_column(measure_unknowns_[0])[row], second = table.q_column(measure_unknowns_[1])[row];
  const double measure = angle_magnitude(second - first + measure_offset_[l]);
  if (measure >= least_measure_[l]) return;
  least_measure_[l] = measure;
  least_first_[l] = first;
  least_second_[l] = second;
}

bool DesignLanes::least_measure_angles(std::size_t l, double& first, double& second) const {
  const bool measured = !std::isnan(least_measure_[l]);
  first = measured ? least_first_[l] : NAN;
  second = measured ? least_second_[l] : NAN;
  return measured;
}

Eigen::VectorXd DesignLanes::position(std::size_t l, std::size_t row) const {
  if (!positions_and_rates_ || kept_ok_[row * kLanes + l] == 0) return lanes_[l]->table.q(row);
  Eigen::VectorXd q(static_cast<Eigen::Index>(n_));
  for (std::size_t i = 0; i < n_; ++i) q[Eigen::Index(i)] = kept_[(2 * n_ * row + i) * kLanes + l];
  return q;
}

void DesignLanes::rates_at_ok_rows(std::size_t l, std::size_t i, std::size_t rows, double* rates) const {
  const MotionTable& table = lanes_[l]->table;
  const double* column = table.qd_column(i);
  for (std::size_t row = 0; row < rows; ++row) {
    const bool kept = positions_and_rates_ && kept_ok_[row * kLanes + l] != 0;
    rates[row] = kept ? kept_[(2 * n_ * row + n_ + i) * kLanes + l] : table.status(row) == Status::ok ? column[row] : NAN;
  }
}

void DesignLanes::hand_over(std::size_t l, std::size_t row) {
  Lane& lane = *lanes_[l];
  if (!lane.last_in_lanes) return;
  lane.last_in_lanes = false;
  // The row before, the lanes' last: in full, as the scalar run reads it (its second
  // rates predict the next), from the lane's last row kept.
  MotionTable& table = lane.table;
  const std::size_t rows = table.size();
  for (std::size_t i = 0; i < n_; ++i) {
    table.q_values()[i * rows + row - 1] = previous_[(3 * i) * kLanes + l];
    table.qd_values()[i * rows + row - 1] = previous_[(3 * i + 1) * kLanes + l];
    table.qdd_values()[i * rows + row - 1] = previous_[(3 * i + 2) * kLanes + l];
  }
  lane.rows.solved_elsewhere(table, row - 1);
}

namespace {
// The largest so far and one more, as the study keeps the largest over rows (NaN at
// first: any length replaces it).
inline double larger(double largest, double length) { return !(length <= largest) ? length : largest; }
}  // namespace

const double* DesignLanes::point_vector(bool closed, std::size_t p, std::size_t kind, std::size_t c) {
  const std::size_t k = layout_.point_output(p) + kind * layout_.point_dimensions[p] + c;
  return closed ? closed_points_.data() + k * kLanes : output(TapeLayout::kPointStage, k);
}

void DesignLanes::keep_largest(const double* ok, bool closed) {
  for (std::size_t i = 0; i < n_; ++i) {
    const double* qd = lanes(layout_.qd(i));
    const double* qdd = lanes(layout_.qdd(i));
    double* largest_rate = largest_rate_.data() + i * kLanes;
    double* largest_second_rate = largest_second_rate_.data() + i * kLanes;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const double rate = std::fabs(qd[l]), second_rate = std::fabs(qdd[l]);
      largest_rate[l] = ok[l] != 0 && !(rate <= largest_rate[l]) ? rate : largest_rate[l];
      largest_second_rate[l] = ok[l] != 0 && !(second_rate <= largest_second_rate[l]) ? second_rate : largest_second_rate[l];
    }
  }
  const std::vector<std::size_t>& dimensions = layout_.point_dimensions;
  for (std::size_t p = 0; p < dimensions.size(); ++p) {
    const std::size_t d = dimensions[p];
    for (std::size_t kind = 1; kind <= 2; ++kind) {  // velocity, then acceleration
      double squares[kLanes] = {};
      for (std::size_t c = 0; c < d; ++c) {
        const double* v = point_vector(closed, p, kind, c);
        for (std::size_t l = 0; l < kLanes; ++l) squares[l] += v[l] * v[l];
      }
      double* largest = (kind == 1 ? largest_speed_ : largest_acceleration_).data() + p * kLanes;
      double* largest_square = (kind == 1 ? largest_speed_square_ : largest_acceleration_square_).data() + p * kLanes;
      // Squares that vector_length takes apart (std::hypot): flagged, then counted (a
      // count kept in the loop keeps it from vectorising).
      // Flags of the lanes' width, or-ed: a sum of doubles is added in order, lane by lane.
      std::int64_t unusual_lanes[kLanes];
      for (std::size_t l = 0; l < kLanes; ++l) {
        const bool normal = (squares[l] > 1e-300) & (squares[l] < 1e300);
        unusual_lanes[l] = (ok[l] != 0) & !normal;
        const bool larger_square = (ok[l] != 0) & normal & (squares[l] > largest_square[l]);
        largest_square[l] = larger_square ? squares[l] : largest_square[l];
      }
      std::int64_t unusual = 0;
      for (std::size_t l = 0; l < kLanes; ++l) unusual |= unusual_lanes[l];
      for (std::size_t l = 0; unusual > 0 && l < kLanes; ++l) {
        if (ok[l] == 0 || (squares[l] > 1e-300 && squares[l] < 1e300)) continue;
        double v[3] = {};
        for (std::size_t c = 0; c < d; ++c) v[c] = point_vector(closed, p, kind, c)[l];
        largest[l] = larger(largest[l], vector_length(v[0], v[1], v[2]));
      }
    }
  }
}

namespace {
double largest_of(double length, double square) { return square > 0 ? larger(length, std::sqrt(square)) : length; }
}  // namespace

double DesignLanes::largest_speed(std::size_t lane, std::size_t p) const {
  return largest_of(largest_speed_[p * kLanes + lane], largest_speed_square_[p * kLanes + lane]);
}

double DesignLanes::largest_acceleration(std::size_t lane, std::size_t p) const {
  return largest_of(largest_acceleration_[p * kLanes + lane], largest_acceleration_square_[p * kLanes + lane]);
}

void DesignLanes::keep_largest(std::size_t l, std::size_t row) {
  const MotionTable& table = lanes_[l]->table;
  for (std::size_t i = 0; i < n_; ++i) {
    largest_rate_[i * kLanes + l] = larger(largest_rate_[i * kLanes + l], std::fabs(table.qd_column(i)[row]));
    largest_second_rate_[i * kLanes + l] = larger(largest_second_rate_[i * kLanes + l], std::fabs(table.qdd_column(i)[row]));
  }
  for (std::size_t p = 0; p < table.point_count(); ++p) {
    const PointMotion point = table.point(row, p);
    largest_speed_[p * kLanes + l] = larger(largest_speed_[p * kLanes + l], point.speed());
    largest_acceleration_[p * kLanes + l] = larger(largest_acceleration_[p * kLanes + l], point.acceleration_magnitude());
  }
}

}  // namespace kinema
