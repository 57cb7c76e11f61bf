// Instant centres (issue 13) of every joints-and-links sample against the analytic
// solution: at each centre the two bodies' velocity fields agree (v_a(I) = v_b(I), each
// field from a joint of the body whose velocity eval gives, v(P) = v(J) + omega x (P - J));
// a centre at infinity is where the two bodies turn alike, across their relative
// velocity; the ratios omega_j / omega_driver from three centres equal the solved ones.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <map>

#include "engine/model.hpp"
#include "engine/analysis/instant_centres.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/toggles.hpp"
#include "engine/base/number_format.hpp"
#include "engine/symbolic/derivation.hpp"
#include "engine/constraints/expression_parts.hpp"

#include "tests/test_support.hpp"

namespace {

using Complex = std::complex<double>;

// Each body's velocity field from one of its joints whose velocity is known: a fixed
// pivot (0) or a named point (eval's).
std::map<std::size_t, std::pair<Complex, Complex>> body_references(const kinema::ConstraintSystem& system,
                                                                   const kinema::MotionState& s) {
  const kinema::SolvingPlan& plan = *system.plan;
  std::map<std::size_t, std::pair<Complex, Complex>> known;  // body -> (point, velocity)
  for (std::size_t b = 0; b < plan.bodies.size(); ++b) {
    for (const auto& [joint, local] : plan.bodies[b].points) {
      const kinema::SolvingPlan::Joint& j = plan.joints[joint];
      for (std::size_t p = 0; p < system.points.size(); ++p) {
        if (system.points[p].name != j.name) continue;
        const kinema::PointMotion& m = s.points[p];
        known[b] = {Complex(m.position[0], m.position[1]), Complex(m.velocity[0], m.velocity[1])};
      }
      if (!j.ground) continue;
      for (const auto& [pivot, at] : plan.bodies[0].points)  // ground's are world positions
        if (pivot == joint) known.emplace(b, std::pair{at, Complex()});
    }
  }
  return known;
}

// The Aronhold-Kennedy theorem: the three centres of any three bodies lie on one line
// (through a centre at infinity: parallel to its direction).
void check_kennedy(const kinema::InstantCentres& centres, double length_scale) {
  const std::size_t n = centres.bodies.size();
  int triples = 0;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      for (std::size_t c = b + 1; c < n; ++c) {
        const kinema::InstantCentre *ab = centres.find(a, b), *bc = centres.find(b, c), *ac = centres.find(a, c);
        if (!ab || !bc || !ac) continue;
        std::vector<const kinema::InstantCentre*> finite, infinite;
        for (const auto* centre : {ab, bc, ac}) (centre->at_infinity ? infinite : finite).push_back(centre);
        CAPTURE(centres.bodies[a] + centres.bodies[b] + centres.bodies[c]);
        if (finite.size() == 3) {
          const Complex u = finite[1]->at - finite[0]->at, v = finite[2]->at - finite[0]->at;
          const double size = std::max({std::abs(u), std::abs(v), length_scale});
          CHECK(std::fabs(u.real() * v.imag() - u.imag() * v.real()) <= 1e-7 * size * size);
        } else if (finite.size() == 2) {
          const Complex u = finite[1]->at - finite[0]->at, d = infinite[0]->at;
          CHECK(std::fabs(u.real() * d.imag() - u.imag() * d.real()) <= 1e-7 * std::max(std::abs(u), length_scale));
        }
        ++triples;
      }
  CHECK(triples == static_cast<int>(n * (n - 1) * (n - 2) / 6));
}

}  // namespace

TEST_CASE("instant centres: a vector-loop file's links known by the points on them") {
  // The four-bar: A on the crank (theta2), P on the coupler (theta3), B on the rocker (theta4).
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::MotionTable table = kinema::solve_motion(model, {40 * M_PI / 180, 200 * M_PI / 180});
  for (const kinema::MotionState& s : table) {
    const auto centres = kinema::instant_centres(kinema::MechanismGeometry(model), s);
    REQUIRE(centres);
    REQUIRE(centres->bodies == std::vector<std::string>{"1", "2", "3", "4"});
    CHECK(centres->centres.size() == 6);
    check_kennedy(*centres, model.system.length_scale);
    // The pins are where a textbook puts them: O2, A, B, O4 (d = 100 mm).
    const auto point = [&](const char* name) {
      for (std::size_t p = 0; p < model.system.points.size(); ++p)
        if (model.system.points[p].name == name) return Complex(s.points[p].position[0], s.points[p].position[1]);
      return Complex(NAN, NAN);
    };
    CHECK(std::abs(centres->find(0, 1)->at) < 1e-12);
    CHECK(std::abs(centres->find(1, 2)->at - point("A")) < 1e-12);
    CHECK(std::abs(centres->find(2, 3)->at - point("B")) < 1e-12);
    CHECK(std::abs(centres->find(0, 3)->at - Complex(0.1, 0)) < 1e-12);
    // I13 where O2-A meets O4-B (Kennedy), I24 on the ground line where A-B meets it.
    const Complex I13 = centres->find(0, 2)->at, I24 = centres->find(1, 3)->at;
    CHECK(std::fabs(std::imag((I13 - 0.0) / point("A"))) < 1e-9);
    CHECK(std::fabs(std::imag((I13 - Complex(0.1, 0)) / (point("B") - Complex(0.1, 0)))) < 1e-9);
    CHECK(std::fabs(I24.imag()) < 1e-12);
    REQUIRE(centres->ratios.size() == 2);
    for (const kinema::VelocityRatio& r : centres->ratios) CHECK(r.from_centres == doctest::Approx(r.analytic).epsilon(1e-9));
  }
  // A slider-crank's block is a body: ground 1, crank 2, rod 3, block 4 (numbered in the
  // gap the links leave), its centre with ground at infinity across the line y = e.
  const kinema::Model slider = kinema::load_model(kinema_test::sample("slider_crank.toml"));
  const kinema::MotionTable one = kinema::solve_motion(slider, slider.system.input.values);
  const auto centres = kinema::instant_centres(kinema::MechanismGeometry(slider), one[0]);
  REQUIRE(centres);
  CHECK(centres->bodies == std::vector<std::string>{"1", "2", "3", "4"});
  CHECK(centres->centres.size() == 6);
  REQUIRE(centres->find(0, 3));
  CHECK(centres->find(0, 3)->at_infinity);
  CHECK(std::fabs(centres->find(0, 3)->at.real()) < 1e-12);
  check_kennedy(*centres, slider.system.length_scale);
  // The crank-shaper: ground 1, crank 2, block 3 in the rocker's slot, rocker 4, link 5 and
  // ram 6: all 15 centres (issue 32: 3 of them before).
  const kinema::Model shaper = kinema::load_model(kinema_test::sample("crank_shaper.toml"));
  const kinema::MotionTable at = kinema::solve_motion(shaper, shaper.system.input.values);
  const auto all = kinema::instant_centres(kinema::MechanismGeometry(shaper), at[0]);
  REQUIRE(all);
  CHECK(all->bodies == std::vector<std::string>{"1", "2", "3", "4", "5", "6"});
  CHECK(all->centres.size() == 15);
  check_kennedy(*all, shaper.system.length_scale);
  // Example 4.2 as loops: blocks 2 (on link 3) and 5 (on the x axis), as the seed numbers them.
  const kinema::Model e42 = kinema::load_model(kinema_test::sample("example_4_2_r_rtr_rrt.toml"));
  const kinema::MotionTable e42_at = kinema::solve_motion(e42, e42.system.input.values);
  const auto e42_centres = kinema::instant_centres(kinema::MechanismGeometry(e42), e42_at[0]);
  REQUIRE(e42_centres);
  CHECK(e42_centres->bodies == std::vector<std::string>{"0", "1", "2", "3", "4", "5"});
  CHECK(e42_centres->centres.size() == 15);
}

TEST_CASE("instant centres: every vector-loop sample, each centre where the two links' velocities agree") {
  int with_centres = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::ConstraintSystem& system = model.system;
    if (system.plan || !system.frames.empty()) continue;
    CAPTURE(std::string(name));
    std::vector<double> inputs = system.input.values;
    if (inputs.empty()) inputs = {0.3};
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    for (const kinema::MotionState& s : table) {
      if (s.status != kinema::Status::ok) continue;
      const auto centres = kinema::instant_centres(kinema::MechanismGeometry(model), s);
      if (!centres) continue;  // no point of the file lies on a link
      ++with_centres;
      check_kennedy(*centres, system.length_scale);
      double fastest = 0;
      for (const kinema::PointMotion& p : s.points) fastest = std::max(fastest, p.speed());
      // Every point on a link (its formula's last term a link vector of fixed length):
      // its velocity is omega x (P - I) about the link's centre with ground.
      for (std::size_t p = 0; p < system.points.size(); ++p) {
        const GiNaC::ex last = system.points[p].written_terms.back();
        for (std::size_t b = 1; b < centres->bodies.size(); ++b) {
          const GiNaC::ex angle_rate = centres->rates[b];
          // On body b: the last term turns at its rate and has a fixed length.
          const kinema::LinkVector link = kinema::split_link_vector(last);
          if (!link.polar || !kinema::time_derivative(system, link.angle).is_equal(angle_rate)) continue;
          bool fixed = true;
          for (const kinema::Coordinate& q : system.unknowns) fixed = fixed && !link.length.has(q.symbol);
          if (!fixed || link.length.has(system.input.symbol)) continue;
          const kinema::InstantCentre* ground = centres->find(0, b);
          REQUIRE(ground);
          const kinema::PointMotion& m = s.points[p];
          const Complex at(m.position[0], m.position[1]), v(m.velocity[0], m.velocity[1]);
          CAPTURE(system.points[p].name);
          if (ground->at_infinity) {
            CHECK(std::fabs(centres->angular_velocities[b]) <= 1e-12);
          } else {
            CHECK(std::abs(v - Complex(0, centres->angular_velocities[b]) * (at - ground->at)) <= 1e-9 * fastest);
          }
        }
      }
      for (const kinema::VelocityRatio& r : centres->ratios)
        CHECK(r.from_centres == doctest::Approx(r.analytic).epsilon(1e-7).scale(1));
    }
  }
  CHECK(with_centres >= 6);
}

TEST_CASE("instant centres: every joints-and-links sample, each centre where the bodies' velocities agree") {
  int samples = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.plan) continue;
    ++samples;
    CAPTURE(std::string(name));
    std::vector<double> inputs = model.system.input.values;
    if (inputs.empty()) inputs = {0.3};
    inputs.push_back(inputs.back() + (model.system.input.dimension == kinema::Dimension::angle ? 0.5 : 0.05 * model.system.length_scale));
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    for (const kinema::MotionState& s : table) {
      if (s.status != kinema::Status::ok) continue;
      CAPTURE(s.input);
      const auto centres = kinema::instant_centres(kinema::MechanismGeometry(model), s);
      REQUIRE(centres);
      const std::size_t n = centres->bodies.size();
      // Every centre found: n (n - 1) / 2 of them.
      CHECK(centres->centres.size() == n * (n - 1) / 2);
      CHECK(centres->not_found.empty());
      const auto references = body_references(model.system, s);
      double fastest = 0;
      for (const kinema::PointMotion& p : s.points) fastest = std::max(fastest, p.speed());
      const auto field = [&](std::size_t b, Complex at) {
        const auto& [point, velocity] = references.at(b);
        return velocity + Complex(0, centres->angular_velocities[b]) * (at - point);
      };
      for (const kinema::InstantCentre& c : centres->centres) {
        CAPTURE(c.found_by);
        CAPTURE(centres->bodies[c.a] + centres->bodies[c.b]);
        REQUIRE(references.count(c.a));
        REQUIRE(references.count(c.b));
        const double wa = centres->angular_velocities[c.a], wb = centres->angular_velocities[c.b];
        if (!c.at_infinity) {
          CHECK(std::abs(field(c.a, c.at) - field(c.b, c.at)) <= 1e-7 * fastest);
        } else {
          // The bodies turn alike and their relative velocity is across the direction.
          CHECK(std::fabs(wa - wb) <= 1e-9 * (std::fabs(wa) + std::fabs(wb) + 1));
          const Complex relative = field(c.a, 0) - field(c.b, 0);
          CHECK(std::fabs(std::real(relative * std::conj(c.at))) <= 1e-7 * fastest);
        }
      }
      check_kennedy(*centres, model.system.length_scale);
      // A secondary centre is on both lines it was found on (each through two known centres).
      for (const kinema::InstantCentre& c : centres->centres) {
        if (c.kennedy.empty()) {
          CHECK((c.found_by.rfind("pin ", 0) == 0 || c.found_by.rfind("slider ", 0) == 0));
          continue;
        }
        REQUIRE(c.kennedy.size() == 4);
        for (std::size_t line = 0; line < 2; ++line) {
          const kinema::InstantCentre* p = centres->find(c.kennedy[2 * line].first, c.kennedy[2 * line].second);
          const kinema::InstantCentre* q = centres->find(c.kennedy[2 * line + 1].first, c.kennedy[2 * line + 1].second);
          REQUIRE(p);
          REQUIRE(q);
          if (c.at_infinity || (p->at_infinity && q->at_infinity)) continue;
          // The direction of the line: p to q, or a centre at infinity's own.
          const Complex along = p->at_infinity ? p->at : q->at_infinity ? q->at : q->at - p->at;
          const Complex through = p->at_infinity ? q->at : p->at;
          const Complex to = c.at - through;
          CHECK(std::fabs(along.real() * to.imag() - along.imag() * to.real()) <=
                1e-7 * std::abs(along) * std::max(std::abs(to), model.system.length_scale));
        }
      }
      for (const kinema::VelocityRatio& r : centres->ratios) {
        CAPTURE(centres->bodies[r.body]);
        CHECK(r.from_centres == doctest::Approx(r.analytic).epsilon(1e-7).scale(1));
      }
      CHECK(centres->ratios.size() >= 1);
    }
  }
  CHECK(samples >= 6);
}

namespace {

// Over a turn of a sample (24 inputs), the centres read from the model's drawing stage (the
// formulas the page's sliders run for other dimensions) against the construction
// (constructed_instant_centres): the same bodies, every body read from the tape, the same
// centres, found by the same joints or lines, each where the construction puts it (1e-9 relative), at infinity where it does,
// in its direction. `by_lines` for a construction by joints and Kennedy lines: its
// directions are a slider's line's or a Kennedy line's (either way along it), its centres
// at infinity seen from a point of the same line where they are a slider's (else from a
// point on a Kennedy line, the tape's from its bodies). Counts the centres compared; `rows`
// the states with centres.
int compare_tape_with_construction(const kinema::Model& model, bool by_lines, int& rows) {
  const kinema::ConstraintSystem& system = model.system;
  std::vector<double> inputs;
  const double start = system.input.values.empty() ? 0.3 : system.input.values[0];
  const double span = system.input.dimension == kinema::Dimension::angle ? 2 * M_PI : system.length_scale;
  for (int k = 0; k < 24; ++k) inputs.push_back(start + k * span / 24);
  const kinema::MotionTable table = kinema::solve_motion(model, inputs);
  const kinema::MechanismGeometry geometry(model);
  int compared = 0;
  rows = 0;
  for (const kinema::MotionState& s : table) {
    const auto built = kinema::constructed_instant_centres(geometry, s);
    const auto read = kinema::instant_centres(geometry, s);
    REQUIRE(built.has_value() == read.has_value());
    if (!built) continue;
    CAPTURE(s.input);
    ++rows;
    CHECK(read->bodies == built->bodies);
    CHECK(read->tape_bodies.size() == read->bodies.size());
    double size = system.length_scale, fastest_turning = 0;
    for (const kinema::PointMotion& m : s.points) size = std::max(size, std::hypot(m.position[0], m.position[1]));
    for (double w : built->angular_velocities) fastest_turning = std::max(fastest_turning, std::fabs(w));
    for (const kinema::InstantCentre& want : built->centres) {
      CAPTURE(built->bodies[want.a] + built->bodies[want.b]);
      const double wa = built->angular_velocities[want.a], wb = built->angular_velocities[want.b];
      const kinema::InstantCentre* read_centre = read->find(want.a, want.b);
      // Two bodies moving as one (Example 4.1 at 90 deg: crank, block and link 3 turn alike,
      // the block at rest on the crank) have no centre on the tape, any point in the course's.
      if (!read_centre && std::fabs(wa - wb) <= 1e-9 * fastest_turning) continue;
      REQUIRE(read_centre);
      const kinema::InstantCentre& got = *read_centre;
      CHECK(read->angular_velocities[want.b] == doctest::Approx(built->angular_velocities[want.b]).epsilon(1e-12));
      // Two bodies at rest relative to each other but for rounding (a slider-crank's rod
      // and block at 90 deg: both omega ~1e-17) have a centre 0/0, rounding either way.
      if (!want.at_infinity && std::fabs(wa - wb) <= 1e-9 * fastest_turning) continue;
      REQUIRE(got.at_infinity == want.at_infinity);
      // By the same joints or lines, but where two bodies move as one and Kennedy cannot
      // reach it from the centres the tape has (by the velocities then).
      if (got.found_by.rfind("velocities of", 0) != 0 || read->not_found.empty()) CHECK(got.found_by == want.found_by);
      const bool slider = want.found_by.rfind("slider ", 0) == 0;
      const Complex at = by_lines && want.at_infinity && std::real(got.at * std::conj(want.at)) < 0 ? -got.at : got.at;
      CHECK(std::abs(at - want.at) <= 1e-9 * (want.at_infinity ? 1.0 : std::max(size, std::abs(want.at))));
      if (want.at_infinity && (!by_lines || slider)) {
        REQUIRE(got.seen_from.has_value());
        // Seen from a point on the same line (the tape may know a body by another point).
        CHECK(std::fabs(std::imag((*got.seen_from - *want.seen_from) * std::conj(want.at))) <= 1e-9 * size);
      }
      ++compared;
    }
  }
  return compared;
}

}  // namespace

// A vector-loop file's centres are read from the model's drawing stage: over a turn of
// every sample they are the construction from the numbers the bodies were found by (a
// point on each and its velocity), seen from their points.
TEST_CASE("instant centres: a vector-loop file's centres from the tape are the construction from the bodies' velocities") {
  int compared = 0, samples = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (model.system.plan || !model.system.frames.empty()) continue;
    CAPTURE(std::string(name));
    int rows = 0;
    compared += compare_tape_with_construction(model, false, rows);
    if (rows > 0) ++samples;
  }
  CHECK(samples >= 7);
  CHECK(compared >= 500);
}

// A joints-and-links file's centres are read from the drawing stage too (the loops kinema
// finds for it, their bodies matched to its links and blocks): over a turn of every sample
// they are the course's construction, pins, sliders and Kennedy lines from the bodies'
// poses, found by the same joints and lines.
TEST_CASE("instant centres: a joints-and-links file's centres from the tape are the construction by pins, sliders and Kennedy") {
  int compared = 0, samples = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.plan) continue;
    CAPTURE(std::string(name));
    REQUIRE(!kinema::MechanismGeometry(model).layout().centre_bodies.empty());
    int rows = 0;
    compared += compare_tape_with_construction(model, true, rows);
    CHECK(rows >= 12);  // most of a turn assembles
    if (rows > 0) ++samples;
  }
  CHECK(samples >= 4);
  CHECK(compared >= 300);
}

TEST_CASE("instant centres: a joints-and-links file at rest has the centres it has in motion") {
  // The centres depend on the positions alone; at an input rate of 0 every velocity the
  // tape's centres are read from is 0, and the pins must not vanish with them.
  int compared = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.plan || !model.system.plan->closed_form) continue;
    CAPTURE(std::string(name));
    std::vector<double> inputs = model.system.input.values;
    if (inputs.empty()) inputs = {0.3};
    kinema::MotionOptions at_rest;
    at_rest.rate = 0.0;
    at_rest.second_rate = 0.0;
    const kinema::MotionTable moving = kinema::solve_motion(model, inputs), resting = kinema::solve_motion(model, inputs, at_rest);
    const kinema::MechanismGeometry geometry(model);
    for (std::size_t r = 0; r < moving.size(); ++r) {
      if (moving.status(r) != kinema::Status::ok || resting.status(r) != kinema::Status::ok) continue;
      const auto in_motion = kinema::instant_centres(geometry, moving[r]), still = kinema::instant_centres(geometry, resting[r]);
      REQUIRE(in_motion);
      REQUIRE(still);
      CHECK(still->centres.size() == in_motion->centres.size());
      for (const kinema::InstantCentre& c : in_motion->centres) {
        const kinema::InstantCentre* same = still->find(c.a, c.b);
        REQUIRE(same);
        CHECK(same->at_infinity == c.at_infinity);
        if (!c.at_infinity) CHECK(std::abs(same->at - c.at) <= 1e-9 * model.system.length_scale);
        ++compared;
      }
    }
  }
  CHECK(compared >= 20);
}

namespace {

// Where the pins' centres are asked: theta = 0 (the four-bar's coupler and rocker turn alike
// there), the file's values, and every limit position of every unknown over a turn (a
// rocker or a slider at rest for the instant).
std::vector<double> pin_test_inputs(const kinema::Model& model) {
  std::vector<double> inputs = {0.0};
  inputs.insert(inputs.end(), model.system.input.values.begin(), model.system.input.values.end());
  if (model.system.input.dimension != kinema::Dimension::angle) return inputs;
  std::vector<std::size_t> all(model.system.unknowns.size());
  for (std::size_t j = 0; j < all.size(); ++j) all[j] = j;
  for (const std::vector<kinema::Toggle>& limits : kinema::find_limit_positions(model, all))
    for (const kinema::Toggle& limit : limits) inputs.push_back(limit.input);
  return inputs;
}

}  // namespace

// Issue 45: a pin joining two bodies is their instant centre whatever their rates. At
// theta = 0 and at every limit position, every pin's centre is found, at the pin (where the
// closed-form drawing puts the joint), for every joints-and-links sample; and the
// vector-loop four-bar's four pins are where a textbook puts them (O2, A, B, O4).
TEST_CASE("instant centres: every pin's centre is at its pin at theta = 0 and at the limit positions") {
  int pins = 0, alike = 0, at_rest = 0;
  std::size_t as_one = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.plan || !model.system.plan->closed_form) continue;
    CAPTURE(std::string(name));
    const kinema::SolvingPlan& plan = *model.system.plan;
    const kinema::MechanismGeometry geometry(model);
    for (const double input : pin_test_inputs(model)) {
      CAPTURE(input);
      const kinema::MotionTable table = kinema::solve_motion(model, {input});
      if (table.status(0) != kinema::Status::ok) continue;
      const auto centres = kinema::instant_centres(geometry, table[0]);
      REQUIRE(centres);
      const std::optional<kinema::LinkageDrawing> drawing = kinema::linkage_drawing(model.system, table[0]);
      REQUIRE(drawing);
      const auto joint_at = [&](const std::string& joint) {
        for (const auto& link : drawing->links)
          for (const auto& j : link.joints)
            if (j.name == joint) return j.at;
        for (const auto& j : drawing->ground_pivots)
          if (j.name == joint) return j.at;
        FAIL("no joint " << joint << " drawn");
        return Complex();
      };
      double turning = 0;
      for (double w : centres->angular_velocities) turning = std::max(turning, std::fabs(w));
      for (const kinema::SolvingPlan::Pin& pin : plan.pins) {
        CAPTURE(plan.joints[pin.joint].name);
        const kinema::InstantCentre* centre = centres->find(pin.a, pin.b);
        REQUIRE(centre);
        CHECK(!centre->at_infinity);
        CHECK(centre->pin);
        CHECK(std::abs(centre->at - joint_at(plan.joints[pin.joint].name)) <= 1e-9 * model.system.length_scale);
        const double wa = centres->angular_velocities[pin.a], wb = centres->angular_velocities[pin.b];
        alike += std::fabs(wa - wb) <= kinema::kCentreParallelTolerance * turning;
        at_rest += std::min(pin.a, pin.b) == 0 && std::fabs(wa - wb) <= 1e-9 * turning;
        ++pins;
      }
      // What is left unfound is two bodies at rest relative to each other (Problem 4.4's
      // links 3, 4 and 5 at its slider's limits), said so: any point is their centre.
      CHECK(centres->moving_as_one == centres->not_found);
      for (const auto& [a, b] : centres->moving_as_one)
        CHECK(std::fabs(centres->angular_velocities[a] - centres->angular_velocities[b]) <= 1e-9 * turning);
      as_one += centres->moving_as_one.size();
    }
  }
  CHECK(pins >= 100);
  CHECK(alike >= 1);    // bodies joined by a pin turning alike: the velocities give no centre
  CHECK(at_rest >= 1);  // a link at rest at its limit position
  CHECK(as_one >= 2);   // I04 and I35 of Problem 4.4 at its slider's limits

  // The vector-loop four-bar: at theta2 = 0 the coupler and the rocker turn alike.
  const kinema::Model four_bar = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::MechanismGeometry geometry(four_bar);
  int checked = 0;
  for (const double input : pin_test_inputs(four_bar)) {
    CAPTURE(input);
    const kinema::MotionTable table = kinema::solve_motion(four_bar, {input});
    REQUIRE(table.status(0) == kinema::Status::ok);
    const kinema::MotionState& s = table[0];
    const auto centres = kinema::instant_centres(geometry, s);
    REQUIRE(centres);
    REQUIRE(centres->bodies == std::vector<std::string>{"1", "2", "3", "4"});
    const auto point = [&](const char* name) {
      for (std::size_t p = 0; p < four_bar.system.points.size(); ++p)
        if (four_bar.system.points[p].name == name) return Complex(s.points[p].position[0], s.points[p].position[1]);
      return Complex(NAN, NAN);
    };
    const std::pair<std::pair<std::size_t, std::size_t>, Complex> pin_places[] = {
        {{0, 1}, 0.0}, {{1, 2}, point("A")}, {{2, 3}, point("B")}, {{0, 3}, Complex(0.1, 0)}};  // d = 100 mm
    for (const auto& [bodies, at] : pin_places) {
      CAPTURE(bodies.first);
      CAPTURE(bodies.second);
      const kinema::InstantCentre* centre = centres->find(bodies.first, bodies.second);
      REQUIRE(centre);
      CHECK(!centre->at_infinity);
      CHECK(centre->pin);
      CHECK(std::abs(centre->at - at) <= 1e-12);
      ++checked;
    }
    CHECK(centres->not_found.empty());
    // Where the coupler and the rocker turn alike (theta2 = 0) I34 is at B all the same.
    if (input == 0.0) CHECK(std::fabs(s.qd[0] - s.qd[1]) <= 1e-12 * std::fabs(s.input_rate));
  }
  CHECK(checked >= 12);
  // The worked solution's table of centres at theta2 = 0: I34 at B, none not found.
  const std::string tex = kinema_test::write_temporary("four_bar_at_0.tex", "");
  REQUIRE(kinema_test::run_kinema({"latex", kinema_test::sample("four_bar.toml"), "--at", "0", "-o", tex}).exit_status == 0);
  const std::string latex = kinema_test::read_file(tex);
  CHECK(latex.find("not found") == std::string::npos);
  CHECK(latex.find("$I_{34}$ & $") != std::string::npos);
  // And Problem 4.4's at its slider's limit: I04 any point, as the two move as one.
  const auto limits = kinema::slider_strokes(kinema::load_model(kinema_test::sample("problem_4_4_joints.toml")));
  REQUIRE(limits.size() == 1);
  const std::string at_limit = kinema_test::write_temporary("six_bar_at_limit.tex", "");
  REQUIRE(kinema_test::run_kinema({"latex", kinema_test::sample("problem_4_4_joints.toml"), "--at",
                                   kinema::format_round_trip(limits[0].limit_inputs[0]), "-o", at_limit})
              .exit_status == 0);
  const std::string six = kinema_test::read_file(at_limit);
  CHECK(six.find("not found") == std::string::npos);
  CHECK(six.find("$I_{04}$ & \\multicolumn{2}{c}{any point} & the two move as one for the instant") != std::string::npos);
}
