// chains/spatial_chain: seed 000's robot arm as a chain of rotating frames — the angular
// velocity composed along the chain, the angular acceleration, and the velocities and
// accelerations of O2, A and B at the instant, as the seed prints them (and as finite
// differences of the positions in time give them, which corrects the seed's a_B); the
// seed's boxed v_B by meaning; a point sliding along the arm (Coriolis); bad input.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>

#include "engine/base/errors.hpp"
#include "readers/mechanism_file.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "chains/spatial_chain.hpp"

#include "tests/test_support.hpp"

namespace {

using GiNaC::ex;

const std::string kArm = kinema_test::sample("robot_arm_seed000.toml");

double at(const ex& e, const GiNaC::exmap& values) {
  const ex v = GiNaC::evalf(e.subs(values, GiNaC::subs_options::no_pattern));
  REQUIRE_MESSAGE(GiNaC::is_a<GiNaC::numeric>(v), e << " -> " << v);
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

// Each component against the seed's printed number (one unit of its last digit or 0.1 %).
void check_vector(const kinema::Vector3& v, const GiNaC::exmap& values, const std::vector<std::string>& printed) {
  for (std::size_t c = 0; c < 3; ++c) {
    CAPTURE(c);
    if (printed[c] == "0") CHECK(std::fabs(at(v[c], values)) < 1e-12);  // zero: exactly, not within one unit
    else CHECK_PRINTED(at(v[c], values), printed[c]);
  }
}

const kinema::ChainPointMotion& point(const kinema::SpatialKinematics& k, const std::string& name) {
  for (const auto& p : k.points)
    if (p.name == name) return p;
  FAIL("no point " << name);
  return k.points.front();
}

// Zero as a function of its symbols (trigonometric identities included, which normal()
// does not apply): at three sets of arbitrary values.
bool vanishes(const ex& e) {
  std::vector<ex> names;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) names.push_back(*it);
  for (int trial = 1; trial <= 3; ++trial) {
    GiNaC::exmap values;
    for (std::size_t i = 0; i < names.size(); ++i) values[names[i]] = 0.3 + 0.7 * std::sin(1.7 * trial + 2.9 * double(i));
    const ex v = GiNaC::evalf(e.subs(values, GiNaC::subs_options::no_pattern));
    if (!GiNaC::is_a<GiNaC::numeric>(v) || std::fabs(GiNaC::ex_to<GiNaC::numeric>(v).to_double()) > 1e-9) return false;
  }
  return true;
}

// The chain at time t: every variable at value + rate t + second_rate t^2 / 2.
GiNaC::exmap at_time(const kinema::SpatialKinematics& k, double t) {
  GiNaC::exmap values = k.instant();
  for (std::size_t i = 0; i < k.variables.size(); ++i) {
    values[k.variables[i].symbol] = k.values[i] + k.rates[i] * t + 0.5 * k.second_rates[i] * t * t;
    values[k.variables[i].rate] = k.rates[i] + k.second_rates[i] * t;
  }
  values[k.time] = t;
  return values;
}

// Velocities and accelerations of every point against central differences of its
// position in time, and the five named terms against the direct time derivatives.
void check_by_finite_differences(const kinema::SpatialKinematics& k) {
  const double h = 1e-4;
  const GiNaC::exmap now = at_time(k, 0), before = at_time(k, -h), after = at_time(k, h);
  for (const auto& p : k.points) {
    CAPTURE(p.name);
    for (std::size_t c = 0; c < 3; ++c) {
      CAPTURE(c);
      const double x0 = at(p.position[c], now), xm = at(p.position[c], before), xp = at(p.position[c], after);
      CHECK(at(p.velocity[c], now) == doctest::Approx((xp - xm) / (2 * h)).epsilon(1e-6).scale(1));
      CHECK(at(p.acceleration[c], now) == doctest::Approx((xp - 2 * x0 + xm) / (h * h)).epsilon(1e-5).scale(1));
      CHECK(vanishes(p.velocity[c] - kinema::time_derivative(p.position[c], k.motions())));
      CHECK(vanishes(p.acceleration[c] - kinema::time_derivative(kinema::time_derivative(p.position[c], k.motions()), k.motions())));
    }
  }
}

// The sleeve C of robot_arm_slider.toml at the instant: its relative velocity and
// acceleration and its Coriolis term as printed, and every point by finite differences.
void check_sleeve(const kinema::SpatialKinematics& k, const std::vector<std::string>& relative_velocity,
                  const std::vector<std::string>& relative_acceleration, const std::vector<std::string>& coriolis) {
  const GiNaC::exmap values = k.instant();
  const auto& c = point(k, "C");
  check_vector(c.relative_velocity, values, relative_velocity);
  check_vector(c.relative_acceleration, values, relative_acceleration);
  check_vector(c.coriolis, values, coriolis);
  check_by_finite_differences(k);
}

}  // namespace

TEST_CASE("spatial_chain: seed 000's arm at the instant of the figure") {
  const kinema::SpatialKinematics k = kinema::build_spatial_chain(kinema::read_mechanism_file(kArm));
  const GiNaC::exmap values = k.instant();
  REQUIRE(k.frames.size() == 3);
  CHECK(k.observer == "E0");
  const kinema::ChainFrameMotion& arm = k.frames[2];
  // w_E3/E0 = omega5 e2'' - omega4 e1' + omega1 E3^: one term per turning joint along the chain.
  CHECK(arm.angular_velocity_terms.size() == 3);
  check_vector(arm.angular_velocity, values, {"-1", "0.866025", "0.5"});
  check_vector(arm.angular_acceleration, values, {"-0.866025", "-1.5", "-0.866025"});
  // alpha term by term: each rate's change along its axis plus the axis carried round by
  // its frame; the parts sum to d/dt w for every frame.
  for (const kinema::ChainFrameMotion& f : k.frames) {
    CAPTURE(f.name);
    for (std::size_t c = 0; c < 3; ++c) {
      ex sum = 0;
      for (const auto& t : f.angular_velocity_terms) sum += t.rate_change[c] + t.carried[c];
      CHECK(vanishes(sum - f.angular_acceleration[c]));
      CHECK(vanishes(f.angular_acceleration[c] - kinema::time_derivative(f.angular_velocity[c], k.motions())));
    }
  }
  const auto& spin = arm.angular_velocity_terms.back();  // omega5 y_E2, carried by E2
  CHECK(spin.frame == "E2");
  kinema::Vector3 carried;
  std::copy(spin.carried.begin(), spin.carried.end(), carried.begin());
  check_vector(carried, values, {"-0.866025", "-0.5", "-0.866025"});
  check_vector(k.frames[1].angular_velocity, values, {"-1", "0", "1"});  // w_E2/E0 = -omega4 E1^ + omega1 E3^
  check_vector(k.frames[1].angular_acceleration, values, {"0", "-1", "0"});  // -omega1 omega4 E2^
  check_vector(point(k, "O2").velocity, values, {"-0.6", "0", "0"});
  check_vector(point(k, "A").velocity, values, {"-1.119615", "-0.3", "-0.519615"});
  check_vector(point(k, "B").velocity, values, {"-1.119615", "-0.2", "-0.69282"});
  check_vector(point(k, "O2").acceleration, values, {"0", "-0.6", "0"});
  check_vector(point(k, "A").acceleration, values, {"0.6", "-1.63923", "0.3"});
  // The seed leaves a_B as a formula whose last line carries omega1^2 L3 cos(alpha) where
  // a_O2 brings omega1^2 L1 cos(alpha): substituted as printed it gives -1.485641 for E2^.
  // Finite differences of B's position in time (below) give -1.985641.
  check_vector(point(k, "B").acceleration, values, {"0.4", "-1.985641", "0.5"});
  CHECK(std::fabs(at(point(k, "B").acceleration[1], values) - -1.485641) > 0.4);
  // The seed prints v_B = -1.12 E1^ - 0.2 E2^ - 0.69 E3^ m/s.
  check_vector(point(k, "B").velocity, values, {"-1.12", "-0.2", "-0.69"});
  check_by_finite_differences(k);
}

TEST_CASE("spatial_chain: v_B is the seed's boxed formula, by meaning") {
  const kinema::SpatialKinematics k = kinema::build_spatial_chain(kinema::read_mechanism_file(kArm));
  GiNaC::symtab names;
  for (const auto& p : k.parameters) names[p.symbol.get_name()] = p.symbol;
  for (const auto& v : k.variables) {
    names[v.symbol.get_name()] = v.symbol;
    names[v.rate.get_name()] = v.rate;
  }
  GiNaC::parser read(names);
  // -omega1 (L2 sin a + L1 cos a) E1^ + [(omega1 - omega5 cos a) L3 - omega4 L2 cos a] E2^
  //   - [omega5 L3 sin a + omega4 L2 sin a] E3^, at the instant (every joint angle 0, beta = 90 deg).
  const ex seed[3] = {read("-omega1*(L2*sin(alpha) + L1*cos(alpha))"),
                      read("(omega1 - omega5*cos(alpha))*L3 - omega4*L2*cos(alpha)"),
                      read("-(omega5*L3*sin(alpha) + omega4*L2*sin(alpha))")};
  GiNaC::exmap instant;
  for (const auto& v : k.variables) instant[v.symbol] = 0;
  instant[names["beta"]] = GiNaC::Pi / 2;
  const auto& b = point(k, "B");
  for (std::size_t c = 0; c < 3; ++c) {
    CAPTURE(c);
    CHECK(vanishes(b.velocity[c].subs(instant) - seed[c]));
  }
  // And it is not the same as a wrong sign on one term (the comparison can fail).
  CHECK_FALSE(vanishes(b.velocity[1].subs(instant) - read("(omega1 + omega5*cos(alpha))*L3 - omega4*L2*cos(alpha)")));
}

TEST_CASE("spatial_chain: a point sliding along the arm has its Coriolis and relative terms") {
  const kinema::SpatialKinematics k =
      kinema::build_spatial_chain(kinema::read_mechanism_file(kinema_test::sample("robot_arm_slider.toml")));
  // v_rel = 0.5 e1 = 0.5 E1^ at the instant; Coriolis 2 w x v_rel = 2 (-1, 0.866, 0.5) x (0.5, 0, 0).
  check_sleeve(k, {"0.5", "0", "0"}, {"0.2", "0", "0"}, {"0", "0.5", "-0.866025"});
}

TEST_CASE("spatial_chain: bad frames, axes, points and formulas are refused with file:line") {
  const std::string arm = kinema_test::read_file(kArm);
  const auto error_of = [](const std::string& text) -> std::string {
    try {
      kinema::build_spatial_chain(kinema::read_mechanism_text(text, "arm.toml"));
    } catch (const kinema::InputError& error) {
      return error.what();
    }
    return "";
  };
  CHECK(error_of(kinema_test::replaced(R"(["y", "theta5"])", R"(["w", "theta5"])", arm))
            .find("axis \"w\" is not one of the frame's axes x, y, z") != std::string::npos);
  // A direction vector (the zero vector among them) is not an axis: axes are named.
  CHECK(error_of(kinema_test::replaced(R"(["y", "theta5"])", R"([[0, 0, 0], "theta5"])", arm))
            .find("arm.toml:31: frame \"E3\": a turn's axis is named") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(E3 = { parent = "E2")", R"(E3 = { parent = "E7")", arm))
            .find("its parent \"E7\" is not a frame of the file") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(E2 = { parent = "E1")", R"(E2 = { parent = "E3")", arm))
            .find("a cycle of parents") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(A = { frame = "E3" })", R"(A = { frame = "E9" })", arm))
            .find("point \"A\": frame \"E9\" does not exist") != std::string::npos);
  const std::string unknown = error_of(kinema_test::replaced("\"L3*sin(beta)\"", "\"L4*sin(beta)\"", arm));
  CHECK(unknown.find("arm.toml:") == 0);
  CHECK(unknown.find("L4") != std::string::npos);
  CHECK(error_of(kinema_test::replaced("[points]", "[links]\n[points]", arm))
            .find("unknown key \"links\" in the top level of a spatial chain") != std::string::npos);
  // A length as a turn (audit 2026-11-24): a parameter, a formula of lengths, a length variable.
  CHECK(error_of(kinema_test::replaced(R"(["z", "theta1"])", R"(["z", "L1"])", arm))
            .find("arm.toml:29: frame \"E1\" turn angle \"L1\" is a length, but a turn is an angle") !=
        std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(["y", "theta5"])", R"(["y", "2*L2*L3/L1"])", arm))
            .find("arm.toml:31: frame \"E3\" turn angle \"2*L2*L3/L1\" is a length") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(theta5 = { value = "0 deg")", R"(theta5 = { value = "0 m")",
                                       kinema_test::replaced("\"1 rad/s\", rate_name = \"omega5\"",
                                                             "\"1 m/s\", rate_name = \"omega5\"", arm)))
            .find("arm.toml:31: frame \"E3\" turn angle \"theta5\" is a length") != std::string::npos);
  // An angle formula of lengths that divide out is an angle.
  CHECK(error_of(kinema_test::replaced(R"(["y", "theta5"])", R"(["y", "theta5 + L3/L1"])", arm)).empty());
  // A joint's letter (drawings) is a name, and reaches the system's frame.
  CHECK(error_of(kinema_test::replaced(R"(["y", "theta5"]] })", R"(["y", "theta5"]], joint = "A B" })", arm))
            .find("arm.toml:31:") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(["y", "theta5"]] })", R"(["y", "theta5"]], joint = 3 })", arm))
            .find("arm.toml:31:") != std::string::npos);
  const kinema::ConstraintSystem lettered = kinema::build_spatial_system(
      kinema::read_mechanism_text(kinema_test::replaced(R"(["y", "theta5"]] })", R"(["y", "theta5"]], joint = "W" })", arm), "arm.toml"));
  CHECK(lettered.frames.back().name == "E3");
  CHECK(lettered.frames.back().joint == "W");
}

TEST_CASE("spatial_chain: derive prints the composition of angular velocities and each term of v and a, as seed 000") {
  const auto result = kinema_test::run_kinema({"derive", kArm});
  REQUIRE(result.exit_status == 0);
  // The terms by their labels; the formulas' term order is GiNaC's (their meaning is
  // tested on the library above), the numbers at the instant the seed's.
  CHECK(result.out.find("    w_E3/E0 = omega1 z_E0 - omega4 x_E2 + omega5 y_E2\n      = [") != std::string::npos);
  CHECK(result.out.find("] = (-1, 0.866025, 0.5)\n    alpha_E3/E0 = d/dt w, term by term: d/dt(rate) axis + w_frame x "
                        "(rate axis)\n") != std::string::npos);
  // The axes carried round by E2: w_E2/E0 x (-omega4 x_E2) and w_E2/E0 x (omega5 y_E2), as the seed names them.
  CHECK(result.out.find("      w_E2/E0 x (-omega4 x_E2) = [0, -omega1*omega4, 0] = (0, -1, 0)\n") != std::string::npos);
  CHECK(result.out.find("      w_E2/E0 x (omega5 y_E2) = [") != std::string::npos);
  CHECK(result.out.find("] = (-0.866025, -0.5, -0.866025)\n") != std::string::npos);
  CHECK(result.out.find("] = (-0.866025, -1.5, -0.866025)\n") != std::string::npos);
  const auto v_e2 = result.out.find("    v_E2 (its origin) = [");
  REQUIRE(v_e2 != std::string::npos);
  CHECK(result.out.substr(v_e2, result.out.find('\n', v_e2) - v_e2).find("] = (-0.6, 0, 0)") != std::string::npos);
  // Each of the five terms of a_B on its own line, and the sum: seed 000's numbers.
  for (const char* term : {"    alpha x r = ", "    w x (w x r) = ", "    2 w x v_rel = ", "    a_rel = "})
    CHECK(result.out.find(term) != std::string::npos);
  const auto b = result.out.find("    a_B = ");
  REQUIRE(b != std::string::npos);
  CHECK(result.out.substr(b, result.out.find('\n', b) - b).find("= (0.4, -1.98564, 0.5)") != std::string::npos);
  // eval gives the same at t = 0, and another instant on request.
  const auto csv = kinema_test::run_kinema({"eval", kArm, "--format", "csv", "--at", "0", "--at", "0.5"});
  REQUIRE(csv.exit_status == 0);
  CHECK(csv.out.find("\n0,1,0,ok,") != std::string::npos);
  CHECK(csv.out.find("\n0.5,1,0,ok,") != std::string::npos);
}

TEST_CASE("spatial_chain: the RSSR four-bar closes its loop over a turn - rates by finite differences") {
  // Its input is the crank angle at 1 rad/s: finite differences in the angle (rad) are in time (s).
  const kinema::Model model = kinema::load_model(kinema_test::sample("rssr_spatial_four_bar.toml"));
  REQUIRE(model.system.unknowns.size() == 1);  // theta4: theta2 is the input
  CHECK(model.system.groups.back().kind == "closure");
  std::vector<double> times;
  const double h = 1e-3;
  for (int k = 0; k <= 6283; ++k) times.push_back(k * h);
  const kinema::MotionTable t = kinema::solve_motion(model, times);
  const double scale = model.kinematics.length_scale();
  for (std::size_t r = 1; r + 1 < t.size(); r += 37) {
    CAPTURE(times[r]);
    REQUIRE(t.status(r) == kinema::Status::ok);
    REQUIRE(t.status(r - 1) == kinema::Status::ok);
    REQUIRE(t.status(r + 1) == kinema::Status::ok);
    CHECK(t.loop_residual(r) < 1e-9 * scale);
    for (Eigen::Index i = 0; i < t.q(r).size(); ++i) {
      const double slope = (t.q(r + 1)[i] - t.q(r - 1)[i]) / (2 * h);
      const double curvature = (t.q(r + 1)[i] - 2 * t.q(r)[i] + t.q(r - 1)[i]) / (h * h);
      CHECK(t.qd(r)[i] == doctest::Approx(slope).epsilon(1e-5).scale(1));
      CHECK(t.qdd(r)[i] == doctest::Approx(curvature).epsilon(1e-3).scale(1));
    }
    for (std::size_t p = 0; p < t.point_count(); ++p) {
      const auto a = t.point(r - 1, p), m = t.point(r, p), b = t.point(r + 1, p);
      for (std::size_t c = 0; c < 3; ++c) {
        CHECK(m.velocity[c] == doctest::Approx((b.position[c] - a.position[c]) / (2 * h)).epsilon(1e-5).scale(scale));
        CHECK(m.acceleration[c] ==
              doctest::Approx((b.position[c] - 2 * m.position[c] + a.position[c]) / (h * h)).epsilon(1e-3).scale(scale));
      }
    }
    // The coupler keeps its length: |B - C| = 80 mm.
    const auto b = t.point(r, 0), c = t.point(r, 1);
    CHECK(std::hypot(b.position[0] - c.position[0], b.position[1] - c.position[1], b.position[2] - c.position[2]) ==
          doctest::Approx(0.080).epsilon(1e-10));
  }
}

TEST_CASE("spatial_chain: closures and their variables are counted and named") {
  const std::string rssr = kinema_test::read_file(kinema_test::sample("rssr_spatial_four_bar.toml"));
  const auto error_of = [](const std::string& text) -> std::string {
    try {
      kinema::make_model(kinema::read_mechanism_text(text, "rssr.toml"));
    } catch (const kinema::InputError& error) {
      return error.what();
    }
    return "";
  };
  CHECK(error_of(kinema_test::replaced(R"(BC = { between = ["B", "C"], length = "BC" })", "", rssr))
            .find("1 variable(s) with a guess (found by the closures) but 0 closure(s)") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(between = ["B", "C"])", R"(between = ["B", "X"])", rssr))
            .find("rssr.toml:31: closure \"BC\": there is no point \"X\" in [points]") != std::string::npos);
  CHECK(error_of(kinema_test::replaced(R"(guess = "47 deg")", R"(guess = "47 deg", rate = "1 rad/s")", rssr))
            .find("has a guess, so the closures find it") != std::string::npos);
}

TEST_CASE("spatial_chain: through the commands, a bad chain is bad input with file:line, and nothing is written") {
  const std::string arm = kinema_test::read_file(kArm);
  const std::string directory = kinema_test::fresh_directory("spatial_bad");
  const std::string output = directory + "/out.csv";
  struct Case {
    std::string from, to, message;
  };
  for (const Case& c : std::vector<Case>{
           {R"(["y", "theta5"])", R"(["w", "theta5"])", "axis \"w\" is not one of the frame's axes x, y, z"},
           {R"(["y", "theta5"])", R"([[0, 0, 0], "theta5"])", "a turn's axis is named, \"x\", \"y\" or \"z\""},
           {R"(E3 = { parent = "E2")", R"(E3 = { parent = "E7")", "its parent \"E7\" is not a frame of the file"},
           {R"(A = { frame = "E3" })", R"(A = { frame = "E9" })", "point \"A\": frame \"E9\" does not exist"},
           {"[points]", "[links]\n[points]", "unknown key \"links\" in the top level of a spatial chain"},
           {"\"L3*sin(beta)\"", "\"L4*sin(beta)\"", "L4"}}) {
    CAPTURE(c.message);
    const std::string file = kinema_test::write_temporary("spatial_bad.toml", kinema_test::replaced(c.from, c.to, arm));
    for (const char* command : {"eval", "derive"}) {
      const auto result = kinema_test::run_kinema({command, file, "-o", output});
      CHECK(result.exit_status == 2);
      CHECK(result.err.find("spatial_bad.toml:") != std::string::npos);
      CHECK(result.err.find(c.message) != std::string::npos);
      CHECK_FALSE(std::filesystem::exists(output));
    }
  }
}

TEST_CASE("spatial_chain: each frame's angular velocity and acceleration are eval columns (CSV, JSON, table)") {
  // Seed 000's w_E3/E0 and alpha_E3/E0 at the instant, in every format.
  const nlohmann::json doc = kinema_test::eval_json("robot_arm_seed000.toml");
  REQUIRE(doc["frames"] == nlohmann::json({"E1", "E2", "E3"}));
  const auto& e3 = doc["results"][0]["frames"]["E3"];
  const char* w[] = {"-1", "0.866025", "0.5"};
  const char* alpha[] = {"-0.866025", "-1.5", "-0.866025"};
  for (std::size_t c = 0; c < 3; ++c) {
    CHECK_PRINTED(e3["angular_velocity"][c].get<double>(), w[c]);
    CHECK_PRINTED(e3["angular_acceleration"][c].get<double>(), alpha[c]);
  }
  CHECK(doc["results"][0]["frames"]["E2"]["angular_acceleration"] == nlohmann::json({0.0, -1.0, 0.0}));
  const auto csv = kinema_test::run_kinema({"eval", kArm, "--format", "csv"});
  REQUIRE(csv.exit_status == 0);
  CHECK(csv.out.find(",E3_omega_x [rad/s],E3_omega_y [rad/s],E3_omega_z [rad/s],E3_alpha_x [rad/s^2],") !=
        std::string::npos);
  CHECK(csv.out.find(",-1,0.866025403784,0.5,-0.866025403784,-1.5,-0.866025403784,\n") != std::string::npos);
  const auto table = kinema_test::run_kinema({"eval", kArm});
  REQUIRE(table.exit_status == 0);
  CHECK(table.out.find("  E3      (-1, 0.866025, 0.5)                     (-0.866025, -1.5, -0.866025)\n") !=
        std::string::npos);

  // Over the RSSR's turn, in SIMD blocks and one by one alike: the rocker turns about
  // its y axis (w = omega4 y), and alpha is the derivative of w in time.
  const kinema::Model model = kinema::load_model(kinema_test::sample("rssr_spatial_four_bar.toml"));
  REQUIRE(model.system.frames.size() == 2);
  std::vector<double> times;
  const double h = 1e-3;
  for (int k = 0; k <= 3000; ++k) times.push_back(k * h);
  for (bool simd : {true, false}) {
    CAPTURE(simd);
    const kinema::MotionTable t = kinema::solve_motion(model, times, kinema_test::with_rates(1, 0, 1, simd));
    if (simd) CHECK(t.batch_rows() > 0);
    REQUIRE(t.frame_count() == 2);
    for (std::size_t r = 1; r + 1 < t.size(); r += 101) {
      CAPTURE(times[r]);
      REQUIRE(t.status(r) == kinema::Status::ok);
      const kinema::FrameMotion rocker = t.frame(r, 1), before = t.frame(r - 1, 1), after = t.frame(r + 1, 1);
      CHECK(rocker.angular_velocity[0] == 0);
      CHECK(rocker.angular_velocity[2] == 0);
      CHECK(rocker.angular_velocity[1] == doctest::Approx(t.qd(r)[0]).epsilon(1e-12));
      CHECK(rocker.angular_acceleration[1] ==
            doctest::Approx((after.angular_velocity[1] - before.angular_velocity[1]) / (2 * h)).epsilon(1e-5).scale(1));
      CHECK(t[r].frames.size() == 2);
      CHECK(t[r].frames[1].angular_velocity[1] == rocker.angular_velocity[1]);
    }
  }
}

TEST_CASE("spatial_chain: a driven variable as the input (--input, or input = in the file) - the others follow it") {
  // theta1 at 30 deg with omega1 = 1 rad/s is the arm at t = pi/6 s: the same positions,
  // velocities, accelerations and angular velocities.
  const nlohmann::json by_angle = kinema_test::eval_json("robot_arm_seed000.toml", {"--input", "theta1", "--at", "30"});
  char sixth[32];
  std::snprintf(sixth, sizeof sixth, "%.17g", M_PI / 6);
  const nlohmann::json by_time = kinema_test::eval_json("robot_arm_seed000.toml", {"--at", sixth});
  REQUIRE(by_angle["input"]["name"] == "theta1");
  REQUIRE(by_angle["input"]["kind"] == "angle");
  const auto& a = by_angle["results"][0];
  const auto& t = by_time["results"][0];
  REQUIRE(a["status"] == "ok");
  CHECK(a["input"].get<double>() == doctest::Approx(30));
  for (const char* name : {"theta4", "theta5"}) {
    CAPTURE(name);
    CHECK(a["coordinates"][name]["value"].get<double>() == doctest::Approx(30).epsilon(1e-12));
    CHECK(a["coordinates"][name]["rate"].get<double>() == doctest::Approx(1).epsilon(1e-12));
  }
  for (const char* p : {"O2", "A", "B"})
    for (const char* part : {"position", "velocity", "acceleration"})
      for (std::size_t c = 0; c < 3; ++c) {
        CAPTURE(p);
        CAPTURE(part);
        CHECK(a["points"][p][part][c].get<double>() ==
              doctest::Approx(t["points"][p][part][c].get<double>()).epsilon(1e-9).scale(1));
      }
  for (const char* part : {"angular_velocity", "angular_acceleration"})
    for (std::size_t c = 0; c < 3; ++c)
      CHECK(a["frames"]["E3"][part][c].get<double>() ==
            doctest::Approx(t["frames"]["E3"][part][c].get<double>()).epsilon(1e-9).scale(1));
  // Twice the input's rate: the whole chain twice as fast (rates x2, second rates x4).
  kinema::Mechanism arm = kinema::read_mechanism_file(kArm);
  arm.chain->input = "theta1";
  const kinema::Model model = kinema::make_model(arm);
  const kinema::MotionTable fast = kinema::solve_motion(model, {0.0}, kinema_test::with_rates(2, 0));
  REQUIRE(fast.status(0) == kinema::Status::ok);
  CHECK(fast.qd(0)[1] == doctest::Approx(2));
  CHECK(fast.point(0, 2).acceleration[1] == doctest::Approx(4 * -1.98564064606));

  // derive at the input's value, with the seed's numbers.
  const auto derived = kinema_test::run_kinema({"derive", kArm, "--input", "theta1"});
  REQUIRE(derived.exit_status == 0);
  CHECK(derived.out.find("At the instant (theta1 = 0 deg, theta4 = 0 deg, theta5 = 0 deg)") != std::string::npos);
  CHECK(derived.out.find("] = (-0.866025, -1.5, -0.866025)\n") != std::string::npos);

  // The RSSR's file makes its crank angle the input: a turn is --sweep 0:360:1 in degrees.
  const nlohmann::json rssr = kinema_test::eval_json("rssr_spatial_four_bar.toml", {"--sweep", "0:360:90"});
  CHECK(rssr["input"]["name"] == "theta2");
  REQUIRE(rssr["results"].size() == 5);
  CHECK(rssr["results"][4]["coordinates"]["theta4"]["value"].get<double>() ==
        doctest::Approx(rssr["results"][0]["coordinates"]["theta4"]["value"].get<double>()).epsilon(1e-9));

  // Bad inputs, on the command line and in the file.
  struct Case {
    std::vector<std::string> arguments;
    std::string message;
  };
  const std::string rssr_file = kinema_test::sample("rssr_spatial_four_bar.toml");
  for (const Case& c : std::vector<Case>{
           {{"eval", kArm, "--input", "theta9"},
            ": --input theta9: no such variable; the input is one of the driven variables of [variables] (theta1, "
            "theta4, theta5)"},
           {{"eval", rssr_file, "--input", "theta4"}, ": --input theta4: this variable is found by the closures"},
           {{"derive", kinema_test::sample("four_bar.toml"), "--input", "theta3"}, "--input theta3 is for spatial chains"},
           {{"eval", kinema_test::write_temporary("still.toml", kinema_test::replaced(R"(theta1 = { value = "0 deg", rate = "1 rad/s")",
                                                                                    R"(theta1 = { value = "0 deg", rate = "0 rad/s")",
                                                                                    kinema_test::read_file(kArm))),
             "--input", "theta1"},
            "it has no rate, so the other driven variables cannot follow it"},
           {{"eval", kinema_test::write_temporary("input_number.toml", kinema_test::replaced("title =", "input = 42\ntitle =",
                                                                                         kinema_test::read_file(kArm)))},
            "input_number.toml:14: input must name a driven variable of [variables]"},
           {{"eval", kinema_test::write_temporary("input_unknown.toml", kinema_test::replaced("title =", "input = \"phi\"\ntitle =",
                                                                                          kinema_test::read_file(kArm)))},
            "input_unknown.toml:14: input \"phi\": no such variable"}}) {
    CAPTURE(c.message);
    const auto result = kinema_test::run_kinema(c.arguments);
    CHECK(result.exit_status == 2);
    CHECK(result.err.find(c.message) != std::string::npos);
  }
}

namespace {

// Issue 32's arm at non-zero joint angles (30, -20, 50 deg; alpha 60 deg, beta 90 deg).
const char* const kArmAtAnotherInstant = R"toml(title = "arm at another instant"
[parameters]
L1 = "1.2 m"
L2 = "0.6 m"
L3 = "0.2 m"
alpha = "60 deg"
beta = "90 deg"
[variables]
theta1 = { value = "30 deg", rate = "1.5 rad/s", second_rate = "0.4 rad/s^2" }
theta4 = { value = "-20 deg", rate = "-0.7 rad/s", second_rate = "-1.1 rad/s^2" }
theta5 = { value = "50 deg", rate = "2.2 rad/s", second_rate = "0.9 rad/s^2" }
[frames]
E1 = { parent = "E0", turns = [["z", "theta1"]] }
E2 = { parent = "E1", origin = ["0 m", "L1*cos(alpha)", "L1*sin(alpha)"], turns = [["x", "alpha - Pi/2"], ["-x", "theta4"]] }
E3 = { parent = "E2", origin = ["0 m", "L2", "0 m"], turns = [["y", "theta5"]] }
[points]
O2 = { frame = "E2" }
A = { frame = "E3" }
B = { frame = "E3", at = ["L3*sin(beta)", "L3*cos(beta)", "0 m"] }
)toml";

// The "name = [f1, f2, f3] = (...)" line of `derive` that starts with `start`: its three
// formulas as printed, read back.
std::vector<ex> printed_vector(const std::string& out, const std::string& start, GiNaC::parser& read) {
  const auto at = out.find(start);
  REQUIRE_MESSAGE(at != std::string::npos, start);
  const auto open = out.find("= [", at) + 3;
  const std::string list = out.substr(open, out.find("] = (", open) - open);
  std::vector<ex> components;
  int depth = 0;
  std::size_t from = 0;
  for (std::size_t i = 0; i <= list.size(); ++i) {
    if (i < list.size() && (list[i] == '(' || list[i] == '[')) ++depth;
    if (i < list.size() && (list[i] == ')' || list[i] == ']')) --depth;
    if (i == list.size() || (depth == 0 && list[i] == ',')) {
      components.push_back(read(list.substr(from, i - from)));
      from = i + 1;
    }
  }
  REQUIRE(components.size() == 3);
  return components;
}

}  // namespace

TEST_CASE("spatial_chain: an input variable with a second rate is refused, never printed at the wrong instant") {
  // Issue 32's arm: theta1 accelerates (alpha1 = 0.4 rad/s^2). As the input, one rate for
  // every value could not carry theta4 and theta5 along the file's motion: the old run
  // printed alpha4 = -1.28667 and alpha5 = 1.48667 rad/s^2 at theta1 = 30 deg (the file's
  // instant, where the file gives -1.1 and 0.9), each gaining omega_i alpha1 / omega1.
  const std::string arm = kinema_test::write_temporary("accelerating_arm.toml", kArmAtAnotherInstant);
  const auto eval_json = [](const std::string& path, std::vector<std::string> extra) {
    extra.insert(extra.begin(), {"eval", path, "--format", "json"});
    const auto result = kinema_test::run_kinema(extra);
    REQUIRE(result.exit_status == 0);
    return nlohmann::json::parse(result.out);
  };
  // The time run is the file's motion: at t = 0 its own second rates.
  const nlohmann::json by_time = eval_json(arm, {"--at", "0"});
  const auto& row = by_time["results"][0];
  REQUIRE(row["status"] == "ok");
  CHECK(row["coordinates"]["theta4"]["second_rate"].get<double>() == doctest::Approx(-1.1).epsilon(1e-12));
  CHECK(row["coordinates"]["theta5"]["second_rate"].get<double>() == doctest::Approx(0.9).epsilon(1e-12));
  CHECK_PRINTED(row["points"]["B"]["acceleration"][0].get<double>(), "-0.1100");
  for (const char* command : {"eval", "derive", "latex", "codegen"}) {
    CAPTURE(command);
    std::vector<std::string> arguments{command, arm, "--input", "theta1"};
    if (std::string(command) == "codegen") arguments.insert(arguments.end(), {"-o", kinema_test::fresh_directory("arm_input") + "/arm.hpp"});
    const auto refused = kinema_test::run_kinema(arguments);
    CHECK(refused.exit_status == 2);
    CHECK(refused.out.empty());
    CHECK(refused.err.find("--input theta1: it has a second rate (0.4 rad/s^2)") != std::string::npos);
    CHECK(refused.err.find("keep time as the input") != std::string::npos);
  }
  // The library refuses it as the program does.
  kinema::Mechanism mechanism = kinema::read_mechanism_file(arm);
  mechanism.chain->input = "theta1";
  CHECK_THROWS_AS(kinema::make_model(mechanism), kinema::InputError);
  // Without the second rate the input run is the time run at the instant the input has its value.
  const std::string steady = kinema_test::write_temporary(
      "steady_arm.toml", kinema_test::replaced(R"(rate = "1.5 rad/s", second_rate = "0.4 rad/s^2")", R"(rate = "1.5 rad/s")",
                                               kinema_test::read_file(arm)));
  const nlohmann::json at_angle = eval_json(steady, {"--input", "theta1", "--at", "45"});
  const nlohmann::json at_time = eval_json(steady, {"--at", "0.174532925199432957"});  // 15 deg at 1.5 rad/s
  for (const char* name : {"theta4", "theta5"})
    for (const char* part : {"value", "rate", "second_rate"})
      CHECK(at_angle["results"][0]["coordinates"][name][part].get<double>() ==
            doctest::Approx(at_time["results"][0]["coordinates"][name][part].get<double>()).epsilon(1e-12));
  for (std::size_t c = 0; c < 3; ++c)
    CHECK(at_angle["results"][0]["points"]["B"]["acceleration"][c].get<double>() ==
          doctest::Approx(at_time["results"][0]["points"]["B"]["acceleration"][c].get<double>()).epsilon(1e-10));
}

TEST_CASE("spatial_chain: an RSSR that cannot turn fully reports its limit positions where the closed form puts them") {
  // With a 45 mm crank the coupler cannot reach between theta2 = 228.987 and 256.837 deg:
  // there |B - C|^2 = u^2 + dy^2 + 4100 - sqrt((100 u)^2 + 4000^2) (its least value over the
  // rocker angle, u = 45 cos theta2 - 60, dy = 45 sin theta2 - 30, in mm) exceeds 80^2.
  const auto least_squared_distance = [](double degrees) {
    const double t = degrees * M_PI / 180, u = 45 * std::cos(t) - 60, dy = 45 * std::sin(t) - 30;
    return u * u + dy * dy + 4100 - std::hypot(100 * u, 4000.0) - 6400;
  };
  double low = 220, high = 235;
  for (int k = 0; k < 60; ++k) (least_squared_distance(0.5 * (low + high)) < 0 ? low : high) = 0.5 * (low + high);
  const double limit = low;
  CHECK(limit == doctest::Approx(228.987).epsilon(1e-5));
  const std::string file = kinema_test::write_temporary(
      "rssr45.toml", kinema_test::replaced(R"(AB = "20 mm")", R"(AB = "45 mm")",
                                           kinema_test::read_file(kinema_test::sample("rssr_spatial_four_bar.toml"))));
  const auto result = kinema_test::run_kinema({"eval", file, "--sweep", "0:360:10", "--format", "csv"});
  REQUIRE(result.exit_status == 0);
  CHECK(result.out.find("\n220,1,0,ok,") != std::string::npos);
  for (const char* row : {"\n230,1,0,unassembled,", "\n240,1,0,unassembled,", "\n250,1,0,unassembled,"})
    CHECK(result.out.find(row) != std::string::npos);
  char near[64];
  std::snprintf(near, sizeof near, "the motion stops near theta2 = %.6g deg", limit);
  CHECK(result.err.find(near) != std::string::npos);
  // Approaching the limit Phi_q vanishes like the square root of the distance to it (the
  // coupler's length is extreme in theta4 there): omega4 grows as 1/sqrt, tenfold for a
  // hundredth of the distance, and the reciprocal condition falls with it.
  const kinema::Model model = kinema::load_model(file);
  const double degree = M_PI / 180;
  const kinema::MotionTable at = kinema::solve_motion(model, {(limit - 1) * degree, (limit - 1e-2) * degree, (limit - 1e-4) * degree});
  for (std::size_t r = 0; r < 3; ++r) REQUIRE(at.status(r) == kinema::Status::ok);
  CHECK(std::fabs(at.qd(2)[0] / at.qd(1)[0]) == doctest::Approx(10).epsilon(0.02));
  CHECK(at.reciprocal_condition(2) < at.reciprocal_condition(1) / 5);
  CHECK(at.reciprocal_condition(1) < at.reciprocal_condition(0) / 5);
  // At the limit itself (to the rounding of the closed form) the position is singular:
  // one equation, one unknown, its Phi_q against the length scale.
  const kinema::MotionTable there = kinema::solve_motion(model, {(limit - 1e-2) * degree, limit * degree});
  CHECK(there.status(1) == kinema::Status::singular);
  char exact[32];
  std::snprintf(exact, sizeof exact, "%.17g", limit);
  const auto table = kinema_test::run_kinema({"eval", file, "--at", "228.9", "--at", exact});
  CHECK(table.exit_status == 4);  // a requested value is singular
  CHECK(table.err.find("singular position at theta2 = 228.987 deg") != std::string::npos);
}

TEST_CASE("spatial_chain: derive --basis gives the vectors along a frame's axes - the LaTeX form carries them exactly") {
  const kinema::Model model = kinema::load_model(kArm);
  const kinema::ChainAtInstant observer = kinema::chain_at_instant(model.system);
  const kinema::ChainAtInstant arm = kinema::chain_at_instant(model.system, "E3");
  CHECK(observer.basis == "E0");
  CHECK(arm.basis == "E3");
  // w_E3/E0 along E3's axes: E3 = E2 at the instant, y_E2 = (0, sin a, -cos a), z_E2 =
  // (0, cos a, sin a): (-1, 0.866 sin a - 0.5 cos a, 0.866 cos a + 0.5 sin a) = (-1, 0.5, 0.866).
  const auto& w = arm.frames[2].angular_velocity.value;
  CHECK(w[0] == doctest::Approx(-1));
  CHECK_PRINTED(w[1], "0.5");
  CHECK_PRINTED(w[2], "0.866025");
  // B is fixed in E3 at (L3 sin beta, L3 cos beta, 0) = (0.2, 0, 0): so it reads in E3's basis.
  const auto& b = arm.points[2];
  REQUIRE(b.name == "B");
  CHECK(b.velocity[0].term == kinema::ChainTerm::position);
  CHECK(b.velocity[0].value[0] == doctest::Approx(0.2));
  CHECK(std::fabs(b.velocity[0].value[1]) < 1e-12);
  // A change of basis keeps every vector's length (and is not the identity here).
  for (std::size_t p = 0; p < arm.points.size(); ++p)
    for (auto part : {&kinema::ChainPointAtInstant::velocity, &kinema::ChainPointAtInstant::acceleration})
      for (std::size_t k = 0; k < (arm.points[p].*part).size(); ++k) {
        const auto& u = (arm.points[p].*part)[k].value;
        const auto& v = (observer.points[p].*part)[k].value;
        CHECK(std::hypot(u[0], u[1], u[2]) == doctest::Approx(std::hypot(v[0], v[1], v[2])).epsilon(1e-12).scale(1));
      }
  CHECK(std::fabs(arm.points[2].velocity.back().value[1] - observer.points[2].velocity.back().value[1]) > 0.1);

  const auto text = kinema_test::run_kinema({"derive", kArm, "--basis", "E3"});
  REQUIRE(text.exit_status == 0);
  CHECK(text.out.find("vectors in the basis of E3 (components along its axes x_E3, y_E3, z_E3)") != std::string::npos);
  CHECK(text.out.find("] = (-1, 0.5, 0.866025)\n") != std::string::npos);
  for (const auto& [arguments, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"derive", kArm, "--basis", "E7"}, "--basis E7: there is no frame \"E7\" in the chain; the frames are E0, E1, E2, E3"},
           {{"latex", kinema_test::sample("four_bar.toml"), "--basis", "E1"}, "this file is not a chain of frames"},
           {{"derive", kinema_test::sample("rssr_spatial_four_bar.toml"), "--basis", "crank"},
            "this chain closes a loop and is printed as its equations"}}) {
    CAPTURE(message);
    const auto result = kinema_test::run_kinema(arguments);
    CHECK(result.exit_status == 2);
    CHECK(result.err.find(message) != std::string::npos);
  }

  // derive --format latex: w and alpha as sums of turnings about unit axes, each point's
  // terms, results boxed; the "% kinema vector:" comment of v_B read back is the seed's
  // boxed formula (beta = 90 deg put in, as the seed does).
  const auto latex = kinema_test::run_kinema({"derive", "--format", "latex", kArm});
  REQUIRE(latex.exit_status == 0);
  CHECK(latex.out.find("\\boldsymbol{\\omega}_{\\text{E3/E0}} &= \\omega_{1}\\,\\hat{\\mathbf{z}}_{\\text{E0}} - "
                       "\\omega_{4}\\,\\hat{\\mathbf{x}}_{\\text{E2}} + \\omega_{5}\\,\\hat{\\mathbf{y}}_{\\text{E2}}") !=
        std::string::npos);
  CHECK(latex.out.find("\\boxed{(-1.11962,\\ -0.2,\\ -0.69282)\\,\\mathrm{m/s}}") != std::string::npos);
  CHECK(latex.out.find("\\boxed{(0.4,\\ -1.98564,\\ 0.5)\\,\\mathrm{m/s^2}}") != std::string::npos);
  const auto at = latex.out.find("% kinema vector: v_B = [");
  REQUIRE(at != std::string::npos);
  const std::string list = latex.out.substr(at + 24, latex.out.find("]\n", at) - at - 24);
  GiNaC::symtab names;
  for (const auto& p : model.system.parameters) names[p.symbol.get_name()] = p.symbol;
  for (const auto& q : model.system.unknowns) names[q.rate.get_name()] = q.rate;
  GiNaC::parser read(names, true);
  std::vector<ex> components;
  for (std::size_t from = 0, comma; from < list.size(); from = comma + 2) {
    comma = list.find(", ", from);
    if (comma == std::string::npos) comma = list.size();
    components.push_back(read(list.substr(from, comma - from)));
  }
  REQUIRE(components.size() == 3);
  const ex seed[3] = {read("-omega1*(L2*sin(alpha) + L1*cos(alpha))"),
                      read("(omega1 - omega5*cos(alpha))*L3 - omega4*L2*cos(alpha)"),
                      read("-(omega5*L3*sin(alpha) + omega4*L2*sin(alpha))")};
  for (std::size_t c = 0; c < 3; ++c) {
    CAPTURE(c);
    CHECK(vanishes(components[c] - seed[c]));
  }
}

TEST_CASE("spatial_chain: every spatial sample through the engine: v, a and alpha are finite differences of p and w") {
  for (const char* sample : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    if (model.system.frames.empty()) continue;
    CAPTURE(sample);
    // Three instants h apart in time: the input moves at its rate (time at 1 s/s).
    const auto& input = model.system.input;
    const double rate = input.rate_value, h = 1e-4;
    REQUIRE(rate != 0);
    const double start = input.values.front();
    for (double t : {0.0, 0.3, 1.1}) {
      CAPTURE(t);
      const kinema::MotionTable s =
          kinema::solve_motion(model, {start + rate * (t - h), start + rate * t, start + rate * (t + h)},
                          kinema_test::with_rates(rate, 0));
      for (std::size_t r = 0; r < 3; ++r) REQUIRE(s.status(r) == kinema::Status::ok);
      const double scale = model.kinematics.length_scale();
      for (std::size_t p = 0; p < s.point_count(); ++p) {
        const auto a = s.point(0, p), m = s.point(1, p), b = s.point(2, p);
        for (std::size_t c = 0; c < 3; ++c) {
          CHECK(m.velocity[c] == doctest::Approx((b.position[c] - a.position[c]) / (2 * h)).epsilon(1e-6).scale(scale));
          CHECK(m.acceleration[c] ==
                doctest::Approx((b.position[c] - 2 * m.position[c] + a.position[c]) / (h * h)).epsilon(1e-4).scale(scale));
        }
      }
      for (std::size_t f = 0; f < s.frame_count(); ++f) {
        const auto a = s.frame(0, f), m = s.frame(1, f), b = s.frame(2, f);
        for (std::size_t c = 0; c < 3; ++c) {
          CHECK(m.angular_acceleration[c] ==
                doctest::Approx((b.angular_velocity[c] - a.angular_velocity[c]) / (2 * h)).epsilon(1e-6).scale(1));
        }
      }
    }
  }
}

TEST_CASE("spatial_chain: a point moving in its frame by a formula of time t") {
  // The sleeve of robot_arm_slider.toml moved by s(t) = 0.1 + 0.05 sin(2t) m instead of a variable.
  const std::string text = kinema_test::replaced(R"(C = { frame = "E3", at = ["s", "0 m", "0 m"] })",
                                                 R"x(C = { frame = "E3", at = ["0.1 + 0.05*sin(2*t)", "0 m", "0 m"] })x",
                                                 kinema_test::read_file(kinema_test::sample("robot_arm_slider.toml")));
  const kinema::SpatialKinematics k = kinema::build_spatial_chain(kinema::read_mechanism_text(text, "timed.toml"));
  // At t = 0: v_rel = 0.05*2*cos(0) e1 = (0.1, 0, 0); a_rel = -0.05*4*sin(0) = 0; Coriolis 2 w x v_rel.
  check_sleeve(k, {"0.1", "0", "0"}, {"0", "0", "0"}, {"0", "0.1", "-0.173205"});
  // Through the engine (time is the input): C's v and a are finite differences of its position.
  const std::string file = kinema_test::write_temporary("timed.toml", text);
  const kinema::Model model = kinema::load_model(file);
  const double h = 1e-4;
  for (double t : {0.0, 0.7}) {
    const kinema::MotionTable s = kinema::solve_motion(model, {t - h, t, t + h}, kinema_test::with_rates(1, 0));
    const std::size_t p = 2;  // A, B, C
    REQUIRE(model.system.points[p].name == "C");
    const auto a = s.point(0, p), m = s.point(1, p), b = s.point(2, p);
    for (std::size_t i = 0; i < 3; ++i) {
      CHECK(m.velocity[i] == doctest::Approx((b.position[i] - a.position[i]) / (2 * h)).epsilon(1e-6).scale(1));
      CHECK(m.acceleration[i] == doctest::Approx((b.position[i] - 2 * m.position[i] + a.position[i]) / (h * h)).epsilon(1e-4).scale(1));
    }
  }
  // derive prints it at the instant with numbers (t = 0), not NaN.
  const auto derived = kinema_test::run_kinema({"derive", file});
  REQUIRE(derived.exit_status == 0);
  CHECK(derived.out.find("nan") == std::string::npos);
  CHECK(derived.out.find("    v_rel = [0.1*cos(2*t)") == std::string::npos);  // t put in: the instant's formula
  // A joint variable as the input cannot also have formulas of time.
  const auto refused = kinema_test::run_kinema({"eval", file, "--input", "theta1"});
  CHECK(refused.exit_status == 2);
  CHECK(refused.err.find("--input theta1: the chain has formulas of time t; keep time as its input") != std::string::npos);
}

// docs/mechanism-files.md: in a chain a number is metres in an origin or a point's place and radians in a
// turn (Pi/2 is a number), and a parameter written without a unit is such a number.
TEST_CASE("spatial_chain: a bare number is metres in an origin or point and radians in a turn") {
  const auto chain = [](const std::string& parameter, const std::string& origin, const std::string& turn,
                        const std::string& at) {
    const std::string text = "title = \"numbers\"\n[parameters]\nk = \"" + parameter +
                             "\"\n[variables]\ntheta1 = { value = \"20 deg\", rate = \"1 rad/s\" }\n[frames]\n"
                             "E1 = { parent = \"E0\", origin = [\"" + origin + "\", \"0 m\", \"0 m\"], turns = [[\"z\", \"theta1\"], [\"x\", \"" +
                             turn + "\"]] }\n[points]\nB = { frame = \"E1\", at = [\"0 m\", \"" + at + "\", \"0 m\"] }\n";
    return kinema::build_spatial_chain(kinema::read_mechanism_text(text, "numbers.toml"));
  };
  const kinema::SpatialKinematics with_units = chain("0.5 m", "0.25 m", "0.5 rad", "0.75 m");
  const GiNaC::exmap units_instant = with_units.instant();
  for (const auto& [parameter, origin, turn, at_y] : std::vector<std::array<std::string, 4>>{
           {"0.5 m", "0.25", "0.5", "0.75"}, {"0.5", "k/2", "k", "1.5*k"}, {"0.5 m", "0.5*k", "1/2", "3/4"}}) {
    CAPTURE(origin);
    CAPTURE(turn);
    const kinema::SpatialKinematics bare = chain(parameter, origin, turn, at_y);
    const GiNaC::exmap instant = bare.instant();
    for (std::size_t c = 0; c < 3; ++c) {
      CHECK(at(point(bare, "B").position[c], instant) == doctest::Approx(at(point(with_units, "B").position[c], units_instant)));
      CHECK(at(point(bare, "B").acceleration[c], instant) ==
            doctest::Approx(at(point(with_units, "B").acceleration[c], units_instant)));
    }
  }
}

// Issue 33: 26 frames in a row turning by one variable took 20 s and 1.1 GB in eval before
// a size check refused them; 100 in derive, 30 in latex, 200 in codegen never ended. The
// turns along a chain and the frames are counted before any symbolic work.
TEST_CASE("spatial_chain: a chain of too many turns in a row or too many frames is refused before the work") {
  const auto chain = [](int frames, int turns_per_frame) {
    std::string text = "title = \"deep\"\n[variables]\ntheta1 = { value = \"10 deg\", rate = \"1 rad/s\" }\n[frames]\n";
    for (int i = 1; i <= frames; ++i) {
      text += "E" + std::to_string(i) + " = { parent = \"E" + std::to_string(i - 1) + "\", origin = [\"0.1 m\", \"0 m\", \"0 m\"], turns = [";
      for (int t = 0; t < turns_per_frame; ++t) text += std::string(t ? ", " : "") + "[\"" + "xyz"[(i + t) % 3] + "\", \"theta1\"]";
      text += "] }\n";
    }
    return text + "[points]\nP = { frame = \"E" + std::to_string(frames) + "\", at = [\"0.1 m\", \"0 m\", \"0 m\"] }\n";
  };
  struct Case {
    std::string command;
    int frames, turns_per_frame;
    std::string message;
  };
  for (const Case& c : std::vector<Case>{
           {"eval", 26, 1, "deep_26.toml:19: frame \"E15\" is 15 turns from the observer"},
           {"derive", 100, 1, "deep_100.toml:69: the chain has more than 64 frames"},
           {"latex", 30, 1, "frame \"E15\" is 15 turns from the observer"},
           {"codegen", 200, 0, "the chain has more than 64 frames"},
           {"eval", 8, 2, "deep_8.toml:12: frame \"E8\" is 16 turns from the observer"}}) {
    CAPTURE(c.message);
    const std::string path = kinema_test::write_temporary("deep_" + std::to_string(c.frames) + ".toml", chain(c.frames, c.turns_per_frame));
    std::vector<std::string> arguments{c.command, path};
    if (c.command == "codegen") arguments.insert(arguments.end(), {"-o", kinema_test::fresh_directory("deep") + "/deep.hpp"});
    const auto result = kinema_test::run_kinema_bounded(arguments);
    CHECK(result.exit_status == 2);
    CHECK(result.err.find(c.message) != std::string::npos);
    CHECK(result.err.find("kinema derives chains of up to") != std::string::npos);
    CHECK(result.peak_kilobytes < 2 * 1024 * 1024);
  }
  // 14 turns in a row (7 frames of two) are derived.
  const auto fourteen = kinema_test::run_kinema_bounded({"eval", kinema_test::write_temporary("deep_7.toml", chain(7, 2))}, 60);
  CHECK(fourteen.exit_status == 0);
}


TEST_CASE("spatial_chain: derive at non-zero joint angles - exact angles stay exact, no round-off, formulas as printed "
          "give eval's numbers") {
  const std::string path = kinema_test::write_temporary("arm_another_instant.toml", kArmAtAnotherInstant);
  const auto derived = kinema_test::run_kinema({"derive", path});
  REQUIRE(derived.exit_status == 0);
  const std::string& out = derived.out;
  // No round-off printed as a coefficient (2.71051e-20*L3*omega5*sin(2*alpha) was).
  CHECK(out.find("e-1") == std::string::npos);
  CHECK(out.find("e-2") == std::string::npos);
  // theta1 = 30 deg is Pi/6: E2's x axis is (cos 30, sin 30, 0) exactly.
  CHECK(out.find("      = [-sqrt(3)*omega4/2, -omega4/2, omega1] = (0.606218, 0.35, 1.5)\n") != std::string::npos);

  // Every frame's w and alpha and every point's v and a, as printed, read back and
  // evaluated at the file's values, give eval's numbers to the printed 6 digits.
  GiNaC::symtab names;
  GiNaC::exmap values;
  const auto name = [&](const std::string& n, double v) {
    const GiNaC::realsymbol s(n);
    names[n] = s;
    values[s] = v;
  };
  name("L1", 1.2), name("L2", 0.6), name("L3", 0.2), name("alpha", M_PI / 3), name("beta", M_PI / 2);
  name("omega1", 1.5), name("omega4", -0.7), name("omega5", 2.2), name("alpha1", 0.4), name("alpha4", -1.1), name("alpha5", 0.9);
  GiNaC::parser read(names, true);
  const auto eval = kinema_test::run_kinema({"eval", path, "--format", "json"});
  REQUIRE(eval.exit_status == 0);
  const nlohmann::json result = nlohmann::json::parse(eval.out)["results"][0];
  const auto check = [&](const std::string& start, const nlohmann::json& expected) {
    CAPTURE(start);
    const std::vector<ex> formulas = printed_vector(out, start, read);
    for (std::size_t c = 0; c < 3; ++c) {
      CAPTURE(c);
      CAPTURE(formulas[c]);
      const double want = expected[c].get<double>();
      CHECK(std::fabs(at(formulas[c], values) - want) <= 5e-7 * std::fabs(want) + 1e-12);
    }
  };
  for (const char* f : {"E1", "E2", "E3"}) {
    const std::string frame = f;
    check("    w_" + frame + "/E0 = ", result["frames"][frame]["angular_velocity"]);
    const auto alpha = out.find("    alpha_" + frame + "/E0 = ");
    REQUIRE(alpha != std::string::npos);
    // alpha's sum is the last "      = [" line before the next frame or section.
    const auto next = out.find("\n  E", alpha) < out.find("\n2. ", alpha) ? out.find("\n  E", alpha) : out.find("\n2. ", alpha);
    const auto sum = out.rfind("\n      = [", next);
    check(out.substr(sum, next - sum), result["frames"][frame]["angular_acceleration"]);
  }
  for (const char* p : {"O2", "A", "B"}) {
    const std::string point = p;
    check("    v_" + point + " = [", result["points"][point]["velocity"]);
    check("    a_" + point + " = [", result["points"][point]["acceleration"]);
  }
}
