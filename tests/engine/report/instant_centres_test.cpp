// Instant centres (issue 13) of every joints-and-links sample against the analytic
// solution: at each centre the two bodies' velocity fields agree (v_a(I) = v_b(I), each
// field from a joint of the body whose velocity eval gives, v(P) = v(J) + omega x (P - J));
// a centre at infinity is where the two bodies turn alike, across their relative
// velocity; the ratios omega_j / omega_driver from three centres equal the solved ones.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <map>

#include <kinema/engine/model.hpp>
#include <kinema/engine/report/instant_centres.hpp>

#include "test_support.hpp"

namespace {

using Complex = std::complex<double>;

// Each body's velocity field from one of its joints whose velocity is known: a fixed
// pivot (0) or a named point (eval's).
std::map<std::size_t, std::pair<Complex, Complex>> body_references(const kinema::ConstraintSystem& system,
                                                                   const kinema::MotionState& s) {
  const kinema::Linkage& linkage = *system.linkage;
  std::map<std::size_t, std::pair<Complex, Complex>> known;  // body -> (point, velocity)
  for (std::size_t b = 0; b < linkage.frames.bodies.size(); ++b) {
    for (const auto& [joint, local] : linkage.frames.bodies[b].points) {
      const kinema::Joint& j = linkage.joints[joint];
      for (std::size_t p = 0; p < system.points.size(); ++p) {
        if (system.points[p].name != j.name) continue;
        const kinema::PointMotion& m = s.points[p];
        known[b] = {Complex(m.position[0], m.position[1]), Complex(m.velocity[0], m.velocity[1])};
      }
      if (!j.ground) continue;
      for (const auto& [pivot, at] : linkage.frames.bodies[0].points)  // ground's are world positions
        if (pivot == joint) known.emplace(b, std::pair{at, Complex()});
    }
  }
  return known;
}

}  // namespace

TEST_CASE("instant centres: every joints-and-links sample, each centre where the bodies' velocities agree") {
  int samples = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    if (!model.system.linkage) {
      if (model.system.frames.empty()) {
        const kinema::MotionTable t = kinema::analyse(model, {model.system.input.values.empty() ? 0.3 : model.system.input.values[0]});
        CHECK_FALSE(kinema::instant_centres(model.system, t[0]));
      }
      continue;
    }
    ++samples;
    CAPTURE(std::string(name));
    std::vector<double> inputs = model.system.input.values;
    if (inputs.empty()) inputs = {0.3};
    inputs.push_back(inputs.back() + (model.system.input.dimension == kinema::Dimension::angle ? 0.5 : 0.05 * model.system.length_scale));
    const kinema::MotionTable table = kinema::analyse(model, inputs);
    for (const kinema::MotionState& s : table) {
      if (s.status != kinema::Status::ok) continue;
      CAPTURE(s.input);
      const auto centres = kinema::instant_centres(model.system, s);
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
      for (const kinema::VelocityRatio& r : centres->ratios) {
        CAPTURE(centres->bodies[r.body]);
        CHECK(r.from_centres == doctest::Approx(r.analytic).epsilon(1e-7).scale(1));
      }
      CHECK(centres->ratios.size() >= 1);
    }
  }
  CHECK(samples >= 6);
}
