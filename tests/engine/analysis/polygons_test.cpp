// Velocity and acceleration polygons (issue 13) against the analytic solution, for every
// planar sample at its file's values and a few more: each named point's image is its
// velocity and acceleration from eval; each loop's chain closes; each relative arrow is
// perpendicular to its link with length |omega| r, each normal part omega^2 r towards the
// link's start, each tangential part |alpha| r across it, each Coriolis part 2 |omega v_rel|
// across the line, each formula's value the arrow's length.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "engine/model.hpp"
#include "engine/analysis/polygons.hpp"

#include "tests/test_support.hpp"

namespace {

using kinema::PolygonArrow;

const PolygonArrow* find_arrow(const kinema::Polygon& polygon, const std::string& name) {
  for (const PolygonArrow& a : polygon.arrows)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace

TEST_CASE("polygons: every named point's image is its velocity and acceleration, every loop closes") {
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::PolygonBuilder builder(model);
    if (!model.system.frames.empty()) {
      CHECK_FALSE(builder.available());
      continue;
    }
    REQUIRE(builder.available());
    std::vector<double> inputs = model.system.input.values;
    const double step = model.system.input.dimension == kinema::Dimension::angle ? 0.7 : 0.1 * model.system.length_scale;
    if (!inputs.empty()) inputs.push_back(inputs.back() + step);
    if (inputs.empty()) inputs = {0.3, 0.3 + step};
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    int checked = 0;
    for (const kinema::MotionState& s : table) {
      const auto polygons = builder.polygons(s);
      if (s.status != kinema::Status::ok) {
        CHECK_FALSE(polygons);
        continue;
      }
      REQUIRE(polygons);
      ++checked;
      const auto& [velocity, acceleration] = *polygons;
      double fastest = 0, largest = 0;
      for (const kinema::PointMotion& p : s.points) {
        fastest = std::max(fastest, p.speed());
        largest = std::max(largest, p.acceleration_magnitude());
      }
      INFO(std::string(name) << " at input " << s.input);
      CHECK(velocity.closure_error <= 1e-9 * fastest + 1e-12);
      CHECK(acceleration.closure_error <= 1e-9 * largest + 1e-12);
      // Each named point: its image (polygon vertex) and its absolute arrow from the pole.
      for (std::size_t p = 0; p < model.system.points.size(); ++p) {
        const kinema::PointMotion& m = s.points[p];
        const std::complex<double> v(m.velocity[0], m.velocity[1]), a(m.acceleration[0], m.acceleration[1]);
        const std::string& point = model.system.points[p].name;
        INFO("point " << point);
        bool found = false;
        for (const kinema::PolygonVertex& vertex : velocity.vertices) {
          if (vertex.name != point) continue;
          found = true;
          CHECK(std::abs(vertex.at - v) <= 1e-9 * fastest);
        }
        for (const kinema::PolygonVertex& vertex : acceleration.vertices)
          if (vertex.name == point) CHECK(std::abs(vertex.at - a) <= 1e-9 * largest);
        if (std::abs(v) > 1e-9 * fastest) {
          CHECK(found);
          // Named v_P, or another point's arrow when the images coincide (a translating link).
          const PolygonArrow* absolute = find_arrow(velocity, "v_" + point);
          for (const PolygonArrow& arrow : velocity.arrows)
            if (!absolute && arrow.kind == PolygonArrow::Kind::absolute && std::abs(arrow.to - v) <= 1e-9 * fastest)
              absolute = &arrow;
          REQUIRE(absolute);
          CHECK(std::abs(absolute->from) <= 1e-9 * fastest);
          CHECK(absolute->length() == doctest::Approx(std::abs(v)).epsilon(1e-9));
        }
      }
      // A link's turning: across the link, omega from the rates of the solution.
      GiNaC::exmap rates{{model.system.input.rate, s.input_rate}};
      for (std::size_t j = 0; j < model.system.unknowns.size(); ++j) rates[model.system.unknowns[j].rate] = s.qd[j];
      for (const PolygonArrow& arrow : velocity.arrows) {
        if (arrow.turning.is_zero()) continue;
        INFO(arrow.name);
        const double omega = GiNaC::ex_to<GiNaC::numeric>(arrow.turning.subs(rates).evalf()).to_double();
        const std::complex<double> ratio = (arrow.to - arrow.from) / arrow.link;  // i omega
        CHECK(std::fabs(ratio.real()) <= 1e-9 * std::fabs(omega) + 1e-12);
        CHECK(ratio.imag() == doctest::Approx(omega).epsilon(1e-9));
      }
      // Every arrow: its formula gives its length.
      for (const auto* polygon : {&velocity, &acceleration})
        for (const PolygonArrow& arrow : polygon->arrows) {
          INFO(arrow.name);
          CHECK(arrow.length() == doctest::Approx(arrow.formula_value).epsilon(1e-9));
        }
    }
    CHECK(checked >= 1);
  }
}

TEST_CASE("polygons: the four-bar's polygon as a textbook draws it") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::PolygonBuilder builder(model);
  const double theta2 = 40 * M_PI / 180;
  const kinema::MotionTable table = kinema::solve_motion(model, {theta2});
  const kinema::MotionState s = table[0];
  const auto polygons = builder.polygons(s);
  REQUIRE(polygons);
  const auto& [velocity, acceleration] = *polygons;
  const double a = 0.040, b = 0.120, c = 0.080, p = 0.060, omega2 = 10;
  const double theta3 = s.q[0], theta4 = s.q[1], omega3 = s.qd[0], omega4 = s.qd[1], alpha3 = s.qdd[0],
               alpha4 = s.qdd[1];
  const auto polar = [](double r, double angle) { return std::polar(r, angle); };
  const std::complex<double> I(0, 1);
  // v_A = omega2 x r_A from the pole; v_BA = omega3 x r_AB across the coupler; v_B from the pole.
  const PolygonArrow* vA = find_arrow(velocity, "v_A");
  const PolygonArrow* vBA = find_arrow(velocity, "v_BA");
  const PolygonArrow* vB = find_arrow(velocity, "v_B");
  const PolygonArrow* vPA = find_arrow(velocity, "v_PA");
  REQUIRE(vA);
  REQUIRE(vBA);
  REQUIRE(vB);
  REQUIRE(vPA);
  CHECK(std::abs(vA->to - vA->from - I * omega2 * polar(a, theta2)) < 1e-12);
  CHECK(vA->length() == doctest::Approx(omega2 * a));
  CHECK(std::abs(vBA->from - vA->to) < 1e-12);  // from a's image to b's
  CHECK(std::abs(vBA->to - vBA->from - I * omega3 * polar(b, theta3)) < 1e-12);
  CHECK(std::abs(vB->to - I * omega4 * polar(c, theta4)) < 1e-12);
  CHECK(std::abs(vPA->to - vPA->from - I * omega3 * polar(p, theta3 + M_PI / 6)) < 1e-12);
  CHECK(vBA->kind == PolygonArrow::Kind::relative);
  CHECK(vBA->latex == "v_{BA}");
  // Acceleration: a^n_A, then a^n_BA towards A and a^t_BA across, a^n_B and a^t_B from the pole.
  const PolygonArrow* anBA = find_arrow(acceleration, "an_BA");
  const PolygonArrow* atBA = find_arrow(acceleration, "at_BA");
  const PolygonArrow* anB = find_arrow(acceleration, "an_B");
  const PolygonArrow* atB = find_arrow(acceleration, "at_B");
  REQUIRE(find_arrow(acceleration, "an_A"));
  CHECK_FALSE(find_arrow(acceleration, "at_A"));  // alpha2 = 0: no tangential part
  REQUIRE(anBA);
  REQUIRE(atBA);
  REQUIRE(anB);
  REQUIRE(atB);
  CHECK(std::abs(anBA->to - anBA->from + omega3 * omega3 * polar(b, theta3)) < 1e-9);
  CHECK(std::abs(atBA->to - atBA->from - I * alpha3 * polar(b, theta3)) < 1e-9);
  CHECK(std::abs(anBA->to - atBA->from) < 1e-9);  // chained: normal, then tangential
  CHECK(std::abs(anB->from) < 1e-12);             // from the pole
  CHECK(std::abs(anB->to + omega4 * omega4 * polar(c, theta4)) < 1e-9);
  CHECK(std::abs(atB->to - anB->to - I * alpha4 * polar(c, theta4)) < 1e-9);
  CHECK(anBA->latex == "a^{n}_{BA}");
  CHECK(anBA->formula_value == doctest::Approx(omega3 * omega3 * b));
}

TEST_CASE("polygons: a block sliding on a turning link has its Coriolis part 2 omega v_rel") {
  // Example 4.1 (R-TRR): the block B slides along the driver (AB = r), which turns at omega1.
  const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_1_r_trr.toml"));
  const kinema::PolygonBuilder builder(model);
  const kinema::MotionTable table = kinema::solve_motion(model, model.system.input.values);
  const kinema::MotionState s = table[0];
  const auto polygons = builder.polygons(s);
  REQUIRE(polygons);
  const auto& acceleration = polygons->second;
  const PolygonArrow* coriolis = nullptr;
  for (const PolygonArrow& a : acceleration.arrows)
    if (a.kind == PolygonArrow::Kind::coriolis) coriolis = &a;
  REQUIRE(coriolis);
  // 2 |omega1 * dr/dt| (r is the first unknown).
  REQUIRE(model.system.unknowns[0].name == "r");
  CHECK(coriolis->length() == doctest::Approx(2 * std::fabs(s.input_rate * s.qd[0])).epsilon(1e-9));
  CHECK(coriolis->name == "ac_BB'");
}
