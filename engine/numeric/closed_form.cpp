#include "engine/numeric/closed_form.hpp"

#include <cmath>

#include "engine/numeric/dyad_positions.hpp"
#include "engine/base/units.hpp"

namespace kinema {

bool closed_form_position(const SolvingPlan& frames, double input, const std::vector<int>& signs,
                          Eigen::VectorXd& q, std::uint32_t& dyad) {
  std::vector<BodyPose> poses;
  const std::size_t placed = place_dyads(frames, input, poses, signs.empty() ? nullptr : &signs);
  if (placed < frames.dyads.size()) {
    dyad = static_cast<std::uint32_t>(placed);
    return false;
  }
  const Eigen::VectorXd near = q;
  unknowns_from_poses(frames, poses, q.data());
  for (const SolvingPlan::Body& body : frames.bodies) {
    if (body.unknown < 0) continue;
    double& angle = q[body.unknown];
    angle += 2 * kPi * std::round((near[body.unknown] - angle) / (2 * kPi));
  }
  return true;
}

}  // namespace kinema
