// Design studies (issue 36): every figure of every design equals what a separate model
// with_parameters and its own analysis give (the four-bar's figures, the strokes' time
// ratio, the solved table's largest values), designs that do not assemble included; a
// study derives and compiles nothing per design and solves each value once; what it
// refuses it names.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/design_study.hpp"
#include "engine/analysis/toggles.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/base/work_count.hpp"
#include "engine/model.hpp"
#include "engine/numeric/design_lanes.hpp"
#include "engine/numeric/sweep.hpp"
#include "engine/numeric/workspace.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

using kinema::Designs;
using kinema::Model;
using kinema::MotionTable;
using kinema::StudyFigure;
using kinema::StudyResults;

namespace {

constexpr double kDeg = kinema::kPi / 180;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

Model sample_model(const std::string& name) {
  return kinema::make_model(kinema::read_mechanism_file(kinema_test::sample(name)), kinema::DerivationScope::evaluation);
}

// A turn of the crank in 1-deg steps from `first` (the rows four_bar_figures solves).
std::vector<double> turn_from(double first) {
  std::vector<double> inputs;
  for (int k = 0; k <= 360; ++k) inputs.push_back(first + k * kinema::kPi / 180);
  return inputs;
}

// Both NaN, or equal to `tolerance` relative.
void check_figure(double study, double expected, double tolerance, const std::string& what) {
  INFO(what << ": study " << study << ", separate " << expected);
  if (std::isnan(expected)) {
    CHECK(std::isnan(study));
  } else {
    CHECK(std::fabs(study - expected) <= tolerance * std::max(1.0, std::fabs(expected)));
  }
}

// The largest |x| over the rows whose status is ok (NaN with none).
double largest_over_ok_rows(const MotionTable& t, const std::function<double(std::size_t)>& value) {
  double largest = kNaN;
  for (std::size_t r = 0; r < t.size(); ++r)
    if (t.status(r) == kinema::Status::ok && !(std::fabs(value(r)) <= largest)) largest = std::fabs(value(r));
  return largest;
}

// The time ratio of a separate model's unknown j (its limit positions found as
// find_limit_positions finds them); NaN without exactly two.
double separate_time_ratio(const Model& design, std::size_t j) {
  const std::vector<kinema::Toggle> limits = kinema::find_limit_positions(design, j);
  if (limits.size() != 2) return kNaN;
  kinema::Strokes s;
  for (const kinema::Toggle& limit : limits) s.limit_inputs.push_back(limit.input * 180 / kinema::kPi);
  kinema::set_strokes(s, design.system.input.rate_value);
  return s.time_ratio;
}

// Design i of the study against with_parameters(model, design i) and its own analysis of
// the same inputs: every figure the study gives.
void check_design(const Model& model, const Designs& designs, std::size_t i, const std::vector<double>& inputs,
                  const StudyResults& study, double separate_time_ratio_value) {
  std::vector<std::pair<std::string, double>> values;
  for (std::size_t k = 0; k < designs.names.size(); ++k) values.emplace_back(designs.names[k], designs.values[k][i]);
  const Model design = kinema::with_parameters(model, values);
  const MotionTable table = kinema::solve_motion(design, inputs);
  INFO("design " << i);
  const std::optional<kinema::FourBarFigures> four_bar = kinema::four_bar_figures(design);
  CHECK(std::string(kinema::grashof_name(study.grashof[i])) == (four_bar ? four_bar->grashof : "n/a"));
  check_figure(study.min_transmission_angle[i] / kDeg, four_bar ? four_bar->least_transmission : kNaN, 1e-9,
               "least transmission angle");
  check_figure(study.time_ratio[i], separate_time_ratio_value, 1e-9, "time ratio");
  std::uint32_t failed = 0;
  for (std::size_t r = 0; r < table.size(); ++r) failed += table.status(r) == kinema::Status::unassembled;
  CHECK(study.failed_values[i] == failed);
  CHECK(study.assembles[i] == (failed == 0));
  for (std::size_t j = 0; j < table.unknown_count(); ++j) {
    check_figure(study.max_rate[j][i], largest_over_ok_rows(table, [&](std::size_t r) { return table.qd(r)[j]; }), 1e-12,
                 "max rate " + std::to_string(j));
    check_figure(study.max_second_rate[j][i],
                 largest_over_ok_rows(table, [&](std::size_t r) { return table.qdd(r)[j]; }), 1e-12,
                 "max second rate " + std::to_string(j));
  }
  for (std::size_t p = 0; p < table.point_count(); ++p) {
    check_figure(study.max_speed[p][i], largest_over_ok_rows(table, [&](std::size_t r) { return table.point(r, p).speed(); }),
                 1e-12, "max speed " + std::to_string(p));
    check_figure(study.max_acceleration[p][i],
                 largest_over_ok_rows(table, [&](std::size_t r) { return table.point(r, p).acceleration_magnitude(); }),
                 1e-12, "max acceleration " + std::to_string(p));
  }
}

}  // namespace

TEST_CASE("design study: a four-bar's figures per design equal separate with_parameters models' (one does not assemble)") {
  const Model model = sample_model("four_bar.toml");
  // crank-rocker (the file's), a longer coupler, a double-rocker, a double-crank, and a
  // non-Grashof triple rocker that cannot be assembled over part of the turn.
  Designs designs{{"a", "b", "c", "d"},
                  {{0.040, 0.040, 0.100, 0.060, 0.050},
                   {0.120, 0.130, 0.040, 0.090, 0.070},
                   {0.080, 0.085, 0.080, 0.080, 0.045},
                   {0.100, 0.100, 0.120, 0.030, 0.060}}};
  const std::vector<double> inputs = turn_from(model.system.input.values.front());
  kinema::StudyOptions options;
  options.threads = 2;
  const StudyResults study = kinema::run_design_study(model, designs, inputs, options);
  const std::size_t rocker = kinema::four_bar_loop(model.system)->rocker.unknown;
  for (std::size_t i = 0; i < designs.size(); ++i) {
    std::vector<std::pair<std::string, double>> values;
    for (std::size_t k = 0; k < designs.names.size(); ++k) values.emplace_back(designs.names[k], designs.values[k][i]);
    check_design(model, designs, i, inputs, study, separate_time_ratio(kinema::with_parameters(model, values), rocker));
  }
  CHECK(kinema::grashof_name(study.grashof[0]) == std::string("crank-rocker"));
  CHECK(kinema::grashof_name(study.grashof[4]) == std::string("non-Grashof triple rocker"));
  CHECK(study.assembles[0] == 1);
  CHECK(study.failed_values[4] > 0);  // the design the comparison is meant to include
  // The crank-rocker's time ratio from the closed form: the rocker is at its limits where
  // crank and coupler are in line, extended (a + b) and folded (b - a).
  const double a = 0.040, b = 0.120, c = 0.080, d = 0.100;
  const double extended = std::acos(((a + b) * (a + b) + d * d - c * c) / (2 * (a + b) * d));
  const double folded = std::acos(((b - a) * (b - a) + d * d - c * c) / (2 * (b - a) * d)) + kinema::kPi;
  const double stroke = folded - extended;
  CHECK(study.time_ratio[0] ==
        doctest::Approx(std::max(stroke, 2 * kinema::kPi - stroke) / std::min(stroke, 2 * kinema::kPi - stroke)).epsilon(1e-9));
}

TEST_CASE("design study: a slider-crank's figures equal separate models', its time ratio slider_strokes'") {
  const Model model = sample_model("slider_crank.toml");
  const Designs designs = kinema::design_grid({"a", "e"}, {{0.040, 0.050, 0.060}, {0.0, 0.010, 0.030}});
  REQUIRE(designs.size() == 9);
  const std::vector<double> inputs = turn_from(0);
  const StudyResults study = kinema::run_design_study(model, designs, inputs);
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const Model design = kinema::with_parameters(model, {{"a", designs.values[0][i]}, {"e", designs.values[1][i]}});
    const std::vector<kinema::Strokes> strokes = kinema::slider_strokes(design);
    check_design(model, designs, i, inputs, study, strokes.empty() ? kNaN : strokes.front().time_ratio);
  }
  CHECK(study.time_ratio[1 * 3 + 0] == doctest::Approx(1.0).epsilon(1e-9));  // no offset: both strokes half a turn
  CHECK(study.time_ratio[1 * 3 + 2] > 1.02);
}

TEST_CASE("design study: formula parameters follow the varied ones, as with_parameters has them") {
  const Model model = sample_model("problem_4_4_joints.toml");  // EF = "CE", Lc = "CD"
  const Designs designs{{"CE", "CD"}, {{0.229, 0.231, 0.232}, {0.369, 0.370, 0.372}}};
  const std::vector<double> inputs = turn_from(0);
  const StudyResults study = kinema::run_design_study(model, designs, inputs);
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const Model design = kinema::with_parameters(model, {{"CE", designs.values[0][i]}, {"CD", designs.values[1][i]}});
    const std::vector<kinema::Strokes> strokes = kinema::slider_strokes(design);
    check_design(model, designs, i, inputs, study, strokes.empty() ? kNaN : strokes.front().time_ratio);
  }
}

TEST_CASE("design study: nothing derived or compiled per design, each value solved once, any thread count") {
  const Model model = sample_model("four_bar.toml");
  const std::vector<double> inputs = turn_from(0);
  const auto work = [] {
    return std::vector<std::uint64_t>{kinema::work_done_in_process(kinema::Work::tape_compile),
                                      kinema::work_done_in_process(kinema::Work::differentiation),
                                      kinema::work_done_in_process(kinema::Work::formula_read),
                                      kinema::work_done_in_process(kinema::Work::dyad_derivation)};
  };
  const auto study_work = [&](std::size_t designs, unsigned threads, StudyResults& results) {
    std::vector<double> b;
    for (std::size_t i = 0; i < designs; ++i) b.push_back(0.110 + 0.02 * double(i) / double(designs));
    kinema::StudyOptions options;
    options.threads = threads;
    const std::vector<std::uint64_t> before = work();
    const std::uint64_t solved_before = kinema::values_solved_in_process();
    results = kinema::run_design_study(model, Designs{{"b"}, {b}}, inputs, options);
    CHECK(kinema::values_solved_in_process() - solved_before == designs * inputs.size());
    std::vector<std::uint64_t> done = work();
    for (std::size_t w = 0; w < done.size(); ++w) done[w] -= before[w];
    return done;
  };
  StudyResults few, many, many_on_one;
  const std::vector<std::uint64_t> for_two = study_work(2, 2, few);
  const std::vector<std::uint64_t> for_forty = study_work(40, 2, many);
  CHECK(for_forty == for_two);          // the same work, however many designs
  // Nothing differentiated, read or derived at all; one small tape compiled for the study
  // (the four-bar's side lengths from the parameters), not one a design.
  CHECK(for_forty[0] <= 1);
  CHECK(std::vector<std::uint64_t>(for_forty.begin() + 1, for_forty.end()) == std::vector<std::uint64_t>(3, 0));
  study_work(40, 1, many_on_one);
  for (std::size_t i = 0; i < 40; ++i) {  // threads share out designs, each solved alone: the same numbers
    CHECK(many.max_rate[1][i] == many_on_one.max_rate[1][i]);
    CHECK(many.time_ratio[i] == many_on_one.time_ratio[i]);
  }
}

TEST_CASE("design study: a caller's cancellation stops every thread at its next designs; not asked, the same numbers") {
  // Python's Ctrl-C (issue 49): the module's hook asks the interpreter between batches.
  const Model model = sample_model("four_bar.toml");
  const std::vector<double> inputs = turn_from(0);
  std::vector<double> b;
  for (std::size_t i = 0; i < 4000; ++i) b.push_back(0.110 + 0.02 * double(i) / 4000.0);
  const Designs designs{{"b"}, {b}};
  for (const bool lanes : {true, false}) {
    INFO("across designs: " << lanes);
    kinema::StudyOptions options;
    options.threads = 2;
    options.across_designs = lanes;
    const StudyResults plain = kinema::run_design_study(model, designs, inputs, options);
    std::atomic<std::size_t> asked{0};
    options.cancelled = [&] { return ++asked > 3; };
    const std::uint64_t solved_before = kinema::values_solved_in_process();
    CHECK_THROWS_AS(kinema::run_design_study(model, designs, inputs, options), kinema::Cancelled);
    // A batch (32 designs at most) is solved only after a question answered no: three of
    // them, far from the 4,000 designs; each thread stops at its first yes.
    CHECK(kinema::values_solved_in_process() - solved_before <= 3 * 32 * inputs.size());
    CHECK(asked <= 3 + 2);
    // An exception of the hook's own is what comes out.
    options.cancelled = [] () -> bool { throw std::runtime_error("interrupted"); };
    CHECK_THROWS_WITH_AS(kinema::run_design_study(model, designs, inputs, options), "interrupted", std::runtime_error);
    // A hook that never cancels: the numbers of the study without one, bit for bit.
    options.cancelled = [] { return false; };
    const StudyResults polled = kinema::run_design_study(model, designs, inputs, options);
    const auto same_bits = [](const std::vector<double>& x, const std::vector<double>& y) {  // NaN included
      return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
    };
    for (std::size_t j = 0; j < plain.max_rate.size(); ++j) CHECK(same_bits(polled.max_rate[j], plain.max_rate[j]));
    for (std::size_t p = 0; p < plain.max_speed.size(); ++p) CHECK(same_bits(polled.max_speed[p], plain.max_speed[p]));
    CHECK(same_bits(polled.min_transmission_angle, plain.min_transmission_angle));
    CHECK(same_bits(polled.time_ratio, plain.time_ratio));
    CHECK(polled.failed_values == plain.failed_values);
  }
}

TEST_CASE("design study: a grid's size is counted, and refused past the bound, from its axes' sizes alone") {
  CHECK(kinema::design_grid_size({2, 3, 4}) == 24);
  CHECK(kinema::design_grid_size({}) == 0);
  CHECK(kinema::design_grid_size({1000, 0, 100000}) == 0);
  CHECK_THROWS_WITH_AS(kinema::design_grid_size({1000, 1000, 2}),
                       "a design study of 1000 x 1000 x 2 designs: more than the 1000000 a study may have; vary fewer "
                       "parameters or give larger steps",
                       kinema::InputError);
  const std::size_t huge = std::size_t(1) << 40;  // would overflow a plain product
  CHECK_THROWS_AS(kinema::design_grid_size({huge, huge, huge}), kinema::InputError);
}

TEST_CASE("design study: only the figures asked for") {
  const Model model = sample_model("four_bar.toml");
  kinema::StudyOptions options;
  options.figures = kinema::study_figure_bit(StudyFigure::grashof);
  const std::uint64_t solved_before = kinema::values_solved_in_process();
  const StudyResults study = kinema::run_design_study(model, Designs{{"a"}, {{0.04, 0.09}}}, turn_from(0), options);
  CHECK(kinema::values_solved_in_process() == solved_before);  // a class needs no solving
  CHECK(study.grashof.size() == 2);
  CHECK(study.max_rate.empty());
  CHECK(study.time_ratio.empty());
  CHECK(kinema::grashof_name(study.grashof[0]) == std::string("crank-rocker"));
  CHECK(kinema::grashof_name(study.grashof[1]) == std::string("non-Grashof triple rocker"));  // 90 + 120 > 100 + 80
}

TEST_CASE("design study: a grid is every combination, the first name slowest") {
  const Designs grid = kinema::design_grid({"b", "c"}, {{1, 2}, {10, 20, 30}});
  CHECK(grid.values[0] == std::vector<double>{1, 1, 1, 2, 2, 2});
  CHECK(grid.values[1] == std::vector<double>{10, 20, 30, 10, 20, 30});
}

TEST_CASE("design study: refuses an unknown name (listing the file's), one kinema made, a name twice, lists apart, NaN") {
  const Model model = sample_model("four_bar.toml");
  const std::vector<double> inputs = turn_from(0);
  const auto message = [&](const Designs& designs) {
    try {
      kinema::run_design_study(model, designs, inputs);
    } catch (const kinema::InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  CHECK(message({{"bb"}, {{0.1}}}).find("no parameter named \"bb\" (there are: a, b, c, d, p, delta)") != std::string::npos);
  CHECK(message({{"b", "b"}, {{0.1}, {0.1}}}).find("\"b\" is given twice") != std::string::npos);
  CHECK(message({{"b", "c"}, {{0.1, 0.2}, {0.1}}}).find("1 values of \"c\" but 2 of \"b\"") != std::string::npos);
  CHECK(message({{"b"}, {{0.1, kNaN}}}).find("in design 1 is not a finite number") != std::string::npos);
  // A joints file's parameters that kinema took from its sketch are not the file's to vary.
  const Model joints = sample_model("triple_rocker_circuit.toml");
  const auto joints_message = [&](const std::string& name) {
    try {
      kinema::run_design_study(joints, Designs{{name}, {{0.1}}}, inputs);
    } catch (const kinema::InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  CHECK(joints_message("x_D").find("no parameter named \"x_D\" that the file writes: kinema made it") != std::string::npos);
}

namespace {

// Every figure of two studies of the same designs, equal to tolerance(i) relative for
// design i (both NaN where one is).
void check_same_figures(const StudyResults& lanes, const StudyResults& alone,
                        const std::function<double(std::size_t)>& tolerance) {
  const std::size_t count = alone.assembles.size();
  for (std::size_t i = 0; i < count; ++i) {
    INFO("design " << i);
    const double t = tolerance(i);
    CHECK(lanes.grashof[i] == alone.grashof[i]);
    CHECK(lanes.assembles[i] == alone.assembles[i]);
    CHECK(lanes.failed_values[i] == alone.failed_values[i]);
    check_figure(lanes.min_transmission_angle[i], alone.min_transmission_angle[i], t, "least transmission angle");
    check_figure(lanes.time_ratio[i], alone.time_ratio[i], t, "time ratio");
    for (std::size_t j = 0; j < alone.max_rate.size(); ++j) {
      check_figure(lanes.max_rate[j][i], alone.max_rate[j][i], t, "max rate " + std::to_string(j));
      check_figure(lanes.max_second_rate[j][i], alone.max_second_rate[j][i], t, "max second rate " + std::to_string(j));
    }
    for (std::size_t p = 0; p < alone.max_speed.size(); ++p) {
      check_figure(lanes.max_speed[p][i], alone.max_speed[p][i], t, "max speed " + std::to_string(p));
      check_figure(lanes.max_acceleration[p][i], alone.max_acceleration[p][i], t, "max acceleration " + std::to_string(p));
    }
  }
}

// The least reciprocal condition of design i's ok values (its own model's analysis).
double least_condition(const Model& model, const Designs& designs, std::size_t i, const std::vector<double>& inputs) {
  std::vector<std::pair<std::string, double>> values;
  for (std::size_t k = 0; k < designs.names.size(); ++k) values.emplace_back(designs.names[k], designs.values[k][i]);
  const MotionTable table = kinema::solve_motion(kinema::with_parameters(model, values), inputs);
  double least = 1;
  for (std::size_t r = 0; r < table.size(); ++r)
    if (table.status(r) == kinema::Status::ok) least = std::min(least, table.reciprocal_condition(r));
  return least;
}

// The study solved with designs across lanes and with each design alone (the scalar run).
std::pair<StudyResults, StudyResults> both_ways(const Model& model, const Designs& designs,
                                                const std::vector<double>& inputs) {
  kinema::StudyOptions options;
  options.threads = 2;
  StudyResults lanes = kinema::run_design_study(model, designs, inputs, options);
  options.across_designs = false;
  StudyResults alone = kinema::run_design_study(model, designs, inputs, options);
  return {std::move(lanes), std::move(alone)};
}

}  // namespace

TEST_CASE("design study across lanes: the scalar run's figures, designs that fail part of the turn mixed in") {
  const Model model = sample_model("four_bar.toml");
  // 7 x 7 couplers and rockers (two batches of lanes, the second part full): crank-rockers,
  // and non-Grashof designs (a + b > c + d) that do not assemble near 0 deg, their lanes
  // handed to the scalar run there and back after, and designs near a change point
  // (a + b = c + d, b - c = 0.06).
  const Designs designs = kinema::design_grid({"b", "c"}, {{0.100, 0.110, 0.120, 0.127, 0.130, 0.135, 0.140},
                                                           {0.061, 0.066, 0.071, 0.079, 0.086, 0.091, 0.099}});
  const std::vector<double> inputs = turn_from(0);
  const auto [lanes, alone] = both_ways(model, designs, inputs);
  const std::size_t values = designs.size() * inputs.size();
  std::size_t failing = 0;
  for (std::size_t i = 0; i < designs.size(); ++i)
    failing += alone.failed_values[i] > 0 && alone.failed_values[i] < inputs.size();
  CHECK(failing >= 3);  // what the comparison is meant to include
  CHECK(alone.lane_values == 0);
  // Nearly every value in the lanes, those that do not assemble too (out of the loop's
  // reach, or Newton from the last position, its steps halved, lane by lane): not the few
  // next to a gap, where the four-bar nears a limit position and Phi_q is not clearly
  // regular, nor where a gap ends (Newton from the last position closes: the scalar run
  // solves that value).
  CHECK(double(lanes.lane_values) >= 0.95 * double(values));
  CHECK(lanes.lane_values + failing <= values);
  // 1e-12 where every value is clearly regular. A value close to a limit position (next to
  // a gap) is closed by Newton to its tolerance, 1e-14 of the length scale, which there
  // leaves the position free by that over the least singular value: the scalar run's own
  // answer is fixed only to that, so where the run started from rows rounded otherwise
  // (the lanes') it may differ by as much, the rates more. There: 1e-12 over the least
  // reciprocal condition (a least condition of 1e-4 allows 1e-8; of 0.05, next to a gap
  // the scalar run enters from the file's assembly and the lanes by Newton from the last
  // position, 2e-11).
  std::size_t near_limits = 0;
  check_same_figures(lanes, alone, [&](std::size_t i) {
    const double condition = least_condition(model, designs, i, inputs);
    near_limits += condition < 1e-2;
    return 1e-12 / std::min(1.0, condition);
  });
  CHECK(near_limits < designs.size() / 2);  // most compared to 1e-12
}

TEST_CASE("design study across lanes: a slider-crank (a length unknown, each lane its own scale) as the scalar run") {
  const Model model = sample_model("slider_crank.toml");
  std::vector<double> a, e;
  for (int k = 0; k < 40; ++k) a.push_back(0.030 + 0.001 * k);
  for (int k = 0; k < 3; ++k) e.push_back(0.010 * k);
  const Designs designs = kinema::design_grid({"a", "e"}, {a, e});
  const std::vector<double> inputs = turn_from(0);
  const auto [lanes, alone] = both_ways(model, designs, inputs);
  // Every value after the first in lanes (the first is the file's assembly carried from
  // the guesses' own value, the scalar run's).
  CHECK(lanes.lane_values >= designs.size() * (inputs.size() - 1));
  check_same_figures(lanes, alone, [](std::size_t) { return 1e-12; });
}

TEST_CASE("design lanes: a value out of the loop's reach stored as the scalar run stores it, without Newton") {
  // Two non-Grashof couplers and rockers of the sample (a + b > c + d): each has a gap
  // near 0 deg that the reach tells; a design near a change point and a crank-rocker
  // (b = 0.12, c = 0.08) never leave it.
  const Model base = kinema::with_parameters(sample_model("four_bar.toml"), {});
  const std::vector<double> inputs = turn_from(0);
  const std::vector<std::pair<double, double>> designs{{0.140, 0.061}, {0.135, 0.066}, {0.130, 0.071}, {0.120, 0.080}};
  const auto& input = base.system.input;
  kinema::DesignLanes lanes(base.kinematics, inputs, input.rate_value, input.second_rate_value);
  const std::optional<kinema::FourBarLoop> loop = kinema::four_bar_loop(base.system);
  REQUIRE(loop);
  std::vector<Model> separate;
  std::vector<kinema::LoopReach> reaches;
  for (std::size_t l = 0; l < designs.size(); ++l) {
    separate.push_back(kinema::with_parameters(base, {{"b", designs[l].first}, {"c", designs[l].second}}));
    lanes.set_design(l, separate.back().kinematics.parameter_values().data());
    // a*exp(I*theta2), the ground's - d, b*exp(I*theta3) and - c*exp(I*theta4).
    const kinema::LoopReach reach(0.04, -0.1, 0, designs[l].first, -designs[l].second);
    CHECK(reach.ever_open() == (l < 2));
    lanes.set_reach(l, reach);
    reaches.push_back(reach);
  }
  lanes.solve(designs.size());
  std::size_t out_of_reach = 0, unassembled = 0;
  for (std::size_t l = 0; l < designs.size(); ++l) {
    const MotionTable alone = kinema::solve_motion(separate[l], inputs);
    const MotionTable& table = lanes.table(l);
    for (std::size_t r = 0; r < inputs.size(); ++r) {
      INFO("design " << l << ", row " << r);
      REQUIRE(table.status(r) == alone.status(r));
      const kinema::Failure& got = table.failure(r);
      const kinema::Failure& expected = alone.failure(r);
      CHECK(got.kind == expected.kind);
      if (table.status(r) != kinema::Status::unassembled) {
        for (std::size_t i = 0; i < table.unknown_count(); ++i)
          CHECK(table.q(r)[Eigen::Index(i)] == doctest::Approx(alone.q(r)[Eigen::Index(i)]).epsilon(1e-9));
        continue;
      }
      ++unassembled;
      // Continuation stops within its least step (1e-7 of its largest) of where the loop
      // stops closing; Newton leaves at least the distance out of reach open.
      if (expected.kind == kinema::Failure::Kind::branch_stops) {
        CHECK(got.from == expected.from);
        CHECK(std::fabs(got.stopped_at - expected.stopped_at) <= 1e-6);
      }
      if (expected.kind == kinema::Failure::Kind::group_open) {
        CHECK(got.group == expected.group);
        CHECK(got.from_guesses == expected.from_guesses);
        CHECK(got.residual <= expected.residual * (1 + 1e-12) * std::sqrt(2.0));
      }
      // Told by the reach, not Newton: its distance and its limit exactly.
      const kinema::LoopReach& reach = reaches[l];
      out_of_reach += got.kind == kinema::Failure::Kind::branch_stops ? got.stopped_at == reach.limit(got.from, inputs[r])
                                                                      : got.residual == reach.distance(inputs[r]);
    }
  }
  // The reach decided nearly all of the gaps' values (two designs' gaps of tens of values
  // each): Newton only those within its margin.
  CHECK(unassembled >= 30);
  CHECK(double(out_of_reach) >= 0.9 * double(unassembled));
}

namespace {

// Lanes of the sample four-bar's designs (b, c), each with its loop's closure and reach,
// solved over `inputs`, beside each design's separate model.
struct ClosedLanes {
  std::vector<Model> separate;
  std::unique_ptr<kinema::DesignLanes> lanes;
};
ClosedLanes closed_lanes(const std::vector<std::pair<double, double>>& designs, const std::vector<double>& inputs,
                         bool positions_and_rates_only = false) {
  const Model base = kinema::with_parameters(sample_model("four_bar.toml"), {});
  const auto& input = base.system.input;
  ClosedLanes run;
  run.lanes = std::make_unique<kinema::DesignLanes>(base.kinematics, inputs, input.rate_value, input.second_rate_value);
  const std::optional<kinema::FourBarLoop> loop = kinema::four_bar_loop(base.system);
  REQUIRE(loop);
  // A, B and P of the sample: a*exp(I*theta2); c*exp(I*theta4) (d does not move);
  // a*exp(I*theta2) and p*exp(I*(theta3 + delta)).
  const std::optional<std::vector<kinema::MovingPointTerm>> terms = kinema::moving_point_terms(base.system);
  REQUIRE(terms);
  REQUIRE(terms->size() == 4);
  std::vector<kinema::ClosedPointTerm> closed_terms;
  for (const kinema::MovingPointTerm& term : *terms) closed_terms.push_back({term.point, term.variable});
  run.lanes->set_point_terms(closed_terms);
  for (std::size_t l = 0; l < designs.size(); ++l) {
    run.separate.push_back(kinema::with_parameters(base, {{"b", designs[l].first}, {"c", designs[l].second}}));
    run.lanes->set_design(l, run.separate.back().kinematics.parameter_values().data());
    // a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d.
    const kinema::LoopClosure closure{0.04, -0.1, 0, designs[l].first, -designs[l].second,
                                      loop->coupler.unknown, loop->rocker.unknown};
    run.lanes->set_reach(l, kinema::LoopReach(closure.crank, closure.fixed_x, closure.fixed_y, closure.first, closure.second));
    run.lanes->set_closure(l, closure);
    run.lanes->set_angle_measure(l, loop->coupler.unknown, loop->rocker.unknown, 0.0);
    // The points' moving terms, their factors length e^(i offset) at the design's values.
    GiNaC::exmap values;
    for (const kinema::SystemParameter& p : run.separate.back().system.parameters) values[p.symbol] = p.value;
    std::vector<double> factors;
    for (const kinema::MovingPointTerm& term : *terms) {
      const double length = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(term.length.subs(values))).to_double();
      const double offset = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(term.offset.subs(values))).to_double();
      factors.push_back(length * std::cos(offset));
      factors.push_back(length * std::sin(offset));
    }
    run.lanes->set_point_term_values(l, factors.data());
  }
  run.lanes->set_positions_and_rates_only(positions_and_rates_only);
  run.lanes->solve(designs.size());
  return run;
}

// Every lane's rows against its design's scalar run: the same statuses; positions equal
// to 1e-12 relative where Phi_q is clearly regular, 1e-12 over the reciprocal condition
// nearer a toggle (the scalar run's Newton stops within 1e-14 of the length scale, which
// leaves its position free by that over the least singular value: the closed form's is
// the exact one to rounding); rates and second rates equal to the same tolerance to
// those the scalar solver gives at the lanes' position (from the scalar run's position
// they differ by what that freedom makes of them, 1e-11 relative in second rates where
// the condition is 0.3). The count of ok values and of those nearer a toggle.
std::pair<std::size_t, std::size_t> check_closed_lanes(const ClosedLanes& run, const std::vector<double>& inputs) {
  std::size_t ok_values = 0, near_toggles = 0;
  for (std::size_t l = 0; l < run.separate.size(); ++l) {
    const Model& design = run.separate[l];
    const MotionTable alone = kinema::solve_motion(design, inputs);
    const MotionTable& table = run.lanes->table(l);
    kinema::Workspace workspace(design);
    for (std::size_t r = 0; r < inputs.size(); ++r) {
      INFO("design " << l << ", row " << r);
      REQUIRE(table.status(r) == alone.status(r));
      if (alone.status(r) != kinema::Status::ok) continue;
      ++ok_values;
      const double condition = alone.reciprocal_condition(r);
      near_toggles += condition < 1e-2;
      const double tolerance = condition < 1e-2 ? 1e-12 / condition : 1e-12;
      const auto same = [&](const Eigen::VectorXd& got, const Eigen::VectorXd& expected) {
        for (Eigen::Index i = 0; i < expected.size(); ++i)
          CHECK(std::fabs(got[i] - expected[i]) <= tolerance * std::max(1.0, std::fabs(expected[i])));
      };
      same(table.q(r), alone.q(r));
      const kinema::MotionState there =
          workspace.motion(inputs[r], design.system.input.rate_value, design.system.input.second_rate_value, table.q(r));
      same(table.qd(r), there.qd);
      same(table.qdd(r), there.qdd);
    }
  }
  return {ok_values, near_toggles};
}

}  // namespace

TEST_CASE("design lanes: positions from the loop's closed form equal the scalar run's (Grashof or not)") {
  // Crank-rockers (Grashof), non-Grashof designs with gaps near 0 deg (their lanes handed
  // to Newton and the scalar run there) and designs near a change point (a + b = c + d
  // within 1 mm), every value compared.
  const std::vector<std::pair<double, double>> designs{{0.120, 0.080}, {0.100, 0.099}, {0.110, 0.066}, {0.140, 0.061},
                                                       {0.135, 0.066}, {0.130, 0.071}, {0.127, 0.079}, {0.129, 0.0695}};
  const std::vector<double> inputs = turn_from(0);
  const ClosedLanes run = closed_lanes(designs, inputs);
  const auto [ok_values, near_toggles] = check_closed_lanes(run, inputs);
  CHECK(ok_values >= designs.size() * inputs.size() * 3 / 4);  // what the comparison is meant to include
  // The closed form started nearly every value after each run's first (from the guesses).
  CHECK(double(run.lanes->closed_form_values()) >= 0.95 * double(ok_values - designs.size()));
  // The largest rates kept in the lanes as values are solved: the table's ok rows' largest.
  for (std::size_t l = 0; l < designs.size(); ++l) {
    const MotionTable& table = run.lanes->table(l);
    for (std::size_t i = 0; i < table.unknown_count(); ++i) {
      const auto j = Eigen::Index(i);
      CHECK(run.lanes->largest_rate(l, i) == largest_over_ok_rows(table, [&](std::size_t r) { return table.qd(r)[j]; }));
      CHECK(run.lanes->largest_second_rate(l, i) ==
            largest_over_ok_rows(table, [&](std::size_t r) { return table.qdd(r)[j]; }));
    }
  }
  // A study's lanes keep positions and rates only: the same statuses, positions, rates
  // and largest figures (the scalar run, going on from the lanes' last rows, as before),
  // and the least transmission measure of a scan of the rows that assemble.
  const ClosedLanes light = closed_lanes(designs, inputs, true);
  for (std::size_t l = 0; l < designs.size(); ++l) {
    const MotionTable& full = run.lanes->table(l);
    const MotionTable& table = light.lanes->table(l);
    std::vector<std::vector<double>> rates(full.unknown_count(), std::vector<double>(inputs.size()));
    for (std::size_t i = 0; i < full.unknown_count(); ++i) light.lanes->rates_at_ok_rows(l, i, inputs.size(), rates[i].data());
    double least = kNaN, coupler = kNaN, rocker = kNaN;
    for (std::size_t r = 0; r < inputs.size(); ++r) {
      INFO("design " << l << ", row " << r);
      REQUIRE(table.status(r) == full.status(r));
      CHECK(light.lanes->position(l, r) == full.q(r));
      for (std::size_t i = 0; i < full.unknown_count(); ++i) {
        if (full.status(r) == kinema::Status::ok) {
          CHECK(rates[i][r] == full.qd(r)[Eigen::Index(i)]);
        } else {
          CHECK(std::isnan(rates[i][r]));
        }
      }
      if (full.status(r) == kinema::Status::unassembled) continue;
      // a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d: theta4 - theta3, its
      // lengths of unlike signs.
      const double measure = kinema::angle_magnitude(full.q(r)[1] - full.q(r)[0]);
      if (!(measure >= least)) least = measure, coupler = full.q(r)[0], rocker = full.q(r)[1];
    }
    double kept_coupler = kNaN, kept_rocker = kNaN;
    CHECK(light.lanes->least_measure_angles(l, kept_coupler, kept_rocker) == !std::isnan(least));
    CHECK(kept_coupler == coupler);
    CHECK(kept_rocker == rocker);
    for (std::size_t i = 0; i < full.unknown_count(); ++i) {
      CHECK(light.lanes->largest_rate(l, i) == run.lanes->largest_rate(l, i));
      CHECK(light.lanes->largest_second_rate(l, i) == run.lanes->largest_second_rate(l, i));
    }
    for (std::size_t p = 0; p < full.point_count(); ++p) {
      CHECK(light.lanes->largest_speed(l, p) == run.lanes->largest_speed(l, p));
      CHECK(light.lanes->largest_acceleration(l, p) == run.lanes->largest_acceleration(l, p));
    }
  }
}

TEST_CASE("design lanes: values nearing a toggle leave the closed form to Newton, as the scalar run solves them") {
  // Non-Grashof designs run towards where their loop stops closing (coupler and rocker
  // folding into line), halving the distance each value down to 1e-9 of it: there the
  // closed form's two branches meet and the lanes go back to Newton from the prediction.
  const std::vector<std::pair<double, double>> designs{{0.140, 0.061}, {0.135, 0.066}};
  const kinema::LoopReach reach(0.04, -0.1, 0, 0.140, -0.061);
  const std::vector<double> turn = turn_from(0);
  std::size_t r = 0;
  while (r + 1 < turn.size() && !(reach.distance(turn[r]) <= 0 && reach.distance(turn[r + 1]) > 0)) ++r;
  REQUIRE(r + 1 < turn.size());
  const double limit = reach.limit(turn[r], turn[r + 1]);
  std::vector<double> inputs;
  for (int k = 0; k <= 30; ++k) inputs.push_back(limit + (turn[r] - 30 * kDeg - limit) * std::ldexp(1.0, -k));
  const ClosedLanes run = closed_lanes(designs, inputs);
  const auto [ok_values, near_toggles] = check_closed_lanes(run, inputs);
  CHECK(near_toggles >= 5);  // what the comparison is meant to include
  CHECK(run.lanes->closed_form_values() + 5 <= ok_values);
  CHECK(run.lanes->closed_form_values() >= 10);
}

TEST_CASE("design lanes: rates, second rates and points from the loop's closed form equal the scalar run's") {
  // A grid of couplers and rockers (crank-rockers, non-Grashof designs with gaps, designs
  // near change points): each value the closed form solved (no tape, no LU: the loop's
  // velocity and acceleration equations at its position, the points from their terms)
  // against the scalar run's, every rate, second rate and point velocity and acceleration.
  std::vector<std::pair<double, double>> designs;
  for (const double b : {0.100, 0.112, 0.124, 0.136})
    for (const double c : {0.062, 0.075, 0.088, 0.099}) designs.emplace_back(b, c);
  const std::vector<double> inputs = turn_from(0);
  const ClosedLanes run = closed_lanes(designs, inputs);
  // Nearly every value after the first (from the guesses) solved in closed form.
  CHECK(double(run.lanes->closed_rate_values()) >= 0.9 * double(inputs.size() - 1));
  std::size_t compared = 0;
  for (std::size_t l = 0; l < designs.size(); ++l) {
    const MotionTable alone = kinema::solve_motion(run.separate[l], inputs);
    const MotionTable& table = run.lanes->table(l);
    // 1e-9 relative to the size of each vector (both unknowns' rates, a point's velocity),
    // or where that vanishes (a rocker at rest, its pivot's point) to a thousandth of its
    // largest over the run.
    const auto same = [&](const std::function<Eigen::VectorXd(const MotionTable&, std::size_t)>& of, const char* what) {
      double largest = 0;
      for (std::size_t r = 0; r < inputs.size(); ++r)
        if (alone.status(r) == kinema::Status::ok) largest = std::max(largest, of(alone, r).cwiseAbs().maxCoeff());
      for (std::size_t r = 0; r < inputs.size(); ++r) {
        if (alone.status(r) != kinema::Status::ok) continue;
        const Eigen::VectorXd expected = of(alone, r), got = of(table, r);
        INFO("design " << l << ", row " << r << ", " << what << ": " << got.transpose() << " against " << expected.transpose());
        CHECK((got - expected).cwiseAbs().maxCoeff() <= 1e-9 * std::max(expected.cwiseAbs().maxCoeff(), 1e-3 * largest));
      }
    };
    same([](const MotionTable& t, std::size_t r) { return Eigen::VectorXd(t.qd(r)); }, "rates");
    same([](const MotionTable& t, std::size_t r) { return Eigen::VectorXd(t.qdd(r)); }, "second rates");
    for (std::size_t p = 0; p < alone.point_count(); ++p) {
      same([p](const MotionTable& t, std::size_t r) -> Eigen::VectorXd {
        const kinema::PointMotion m = t.point(r, p);
        return Eigen::Vector2d(m.velocity[0], m.velocity[1]);
      }, "velocity");
      same([p](const MotionTable& t, std::size_t r) -> Eigen::VectorXd {
        const kinema::PointMotion m = t.point(r, p);
        return Eigen::Vector2d(m.acceleration[0], m.acceleration[1]);
      }, "acceleration");
    }
    for (std::size_t r = 0; r < inputs.size(); ++r) compared += alone.status(r) == kinema::Status::ok;
  }
  CHECK(compared >= designs.size() * inputs.size() / 2);  // what the comparison is meant to include
}

TEST_CASE("design lanes: points with a sliding length are not given in closed form") {
  // The slider-crank's piston B = x + I*e moves with the length x: no term that turns.
  CHECK_FALSE(kinema::moving_point_terms(sample_model("slider_crank.toml").system).has_value());
  CHECK(kinema::moving_point_terms(sample_model("four_bar.toml").system).has_value());
}

TEST_CASE("design study across lanes: a design's figures bit for bit whichever designs share its lanes") {
  // Crank-rockers and non-Grashof designs whose values leave the closed form near their
  // gaps: a lane's value is the closed form's or Newton's by its own state alone, so the
  // same designs batched otherwise (five fewer before them) give the same numbers.
  const Model model = sample_model("four_bar.toml");
  const Designs all = kinema::design_grid({"b", "c"}, {{0.100, 0.110, 0.120, 0.127, 0.130, 0.135, 0.140, 0.125},
                                                       {0.061, 0.066, 0.071, 0.079, 0.086, 0.091, 0.099, 0.075}});
  constexpr std::size_t kDropped = 5;
  Designs later = all;
  for (std::vector<double>& values : later.values) values.erase(values.begin(), values.begin() + kDropped);
  const std::vector<double> inputs = turn_from(0);
  kinema::StudyOptions options;
  const StudyResults whole = kinema::run_design_study(model, all, inputs, options);
  const StudyResults part = kinema::run_design_study(model, later, inputs, options);
  const auto same = [&](const std::vector<double>& a, const std::vector<double>& b, const char* what) {
    for (std::size_t i = 0; i < b.size(); ++i) {
      INFO(what << ", design " << i + kDropped);
      CHECK(std::memcmp(&a[i + kDropped], &b[i], sizeof(double)) == 0);
    }
  };
  same(whole.min_transmission_angle, part.min_transmission_angle, "least transmission angle");
  same(whole.time_ratio, part.time_ratio, "time ratio");
  for (std::size_t j = 0; j < whole.max_rate.size(); ++j) {
    same(whole.max_rate[j], part.max_rate[j], "max rate");
    same(whole.max_second_rate[j], part.max_second_rate[j], "max second rate");
  }
  for (std::size_t p = 0; p < whole.max_speed.size(); ++p) {
    same(whole.max_speed[p], part.max_speed[p], "max speed");
    same(whole.max_acceleration[p], part.max_acceleration[p], "max acceleration");
  }
}

TEST_CASE("design study across lanes: a design that never assembles has no least transmission angle, whatever its lane held") {
  // Ground 100 mm, crank 40 mm: coupler 20 mm and rocker 30 mm never close the loop (the
  // ground is longer than the other three together). Such designs in the first batch of
  // lanes (design 5, 21: lanes not used before) and in the second (design 38: lane 6, which
  // design 6 used), on one thread: designs 0-31, then 32-39, in the same lanes.
  const Model model = sample_model("four_bar.toml");
  Designs designs{{"b", "c"}, {{}, {}}};
  const auto add = [&](double b, double c) { designs.values[0].push_back(b); designs.values[1].push_back(c); };
  for (std::size_t i = 0; i < 40; ++i) {
    const bool never = i == 5 || i == 21 || i == 38;
    add(never ? 0.020 : 0.110 + 0.0005 * double(i), never ? 0.030 : 0.080);
  }
  kinema::StudyOptions options;
  options.threads = 1;
  const StudyResults lanes = kinema::run_design_study(model, designs, turn_from(0), options);
  options.across_designs = false;
  const StudyResults alone = kinema::run_design_study(model, designs, turn_from(0), options);
  std::size_t never = 0;
  for (std::size_t i = 0; i < designs.size(); ++i) {
    INFO("design " << i);
    if (designs.values[0][i] != 0.020) {
      CHECK(std::isfinite(lanes.min_transmission_angle[i]));
      continue;
    }
    ++never;
    CHECK_FALSE(alone.assembles[i]);
    CHECK_FALSE(lanes.assembles[i]);
    CHECK(std::isnan(alone.min_transmission_angle[i]));
    CHECK(std::isnan(lanes.min_transmission_angle[i]));
  }
  CHECK(never == 3);
  CHECK(lanes.lane_values > 0);
}
