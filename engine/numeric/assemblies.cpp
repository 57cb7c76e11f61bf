#include "engine/numeric/assemblies.hpp"

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/base/units.hpp"

namespace kinema {
namespace {

using Point2 = std::complex<double>;

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) {
  throw InputError(where.str() + ": " + message);
}

// The sign of dyad k whose inner joint states its assembly: of the two assemblies at the
// driver's sketch value (the other dyads on `signs`), the one that puts the joint on the
// side stated.
int stated_sign(const SolvingPlan& plan, std::size_t k, const std::vector<int>& signs) {
  const SolvingPlan::Dyad& d = plan.dyads[k];
  const std::size_t j = plan.edge_joint(d.inner);
  const SolvingPlan::Joint& joint = plan.joints[j];
  const SolvingPlan::Step& step = plan.steps[k + 1];
  const std::string what = "joint \"" + joint.name + "\": assembly = \"" + d.stated + "\"";
  const std::string side = d.left ? "left" : "right";
  const std::string& from = plan.joints[d.from].name;
  const std::string& to = plan.joints[d.to].name;
  int chosen = 0, choices = 0;
  for (int sign : {1, -1}) {
    std::vector<int> trial = signs;
    trial[k] = sign;
    std::vector<BodyPose> poses;
    if (place_dyads(plan, plan.sketch_input, poses, &trial) <= k) continue;
    Point2 a, b, c;
    if (!joint_position(plan, poses, d.from, a) || !joint_position(plan, poses, d.to, b)) {
      fail(joint.where, what + ": " + from + " and " + to + " must be placed with or before this dyad (" + step.kind +
                            ": " + step.joints[0] + ", " + joint.name + ", " + step.joints[2] + ")");
    }
    joint_position(plan, poses, j, c);
    const double cross = std::imag(std::conj(b - a) * (c - a));
    if (std::fabs(cross) <= 1e-9 * std::norm(b - a)) continue;  // on the line: that assembly says neither side
    if ((cross > 0) == d.left) {
      chosen = sign;
      ++choices;
    }
  }
  if (choices != 1) {
    fail(joint.where, what + ": " + (choices == 0 ? std::string("neither") : std::string("each")) +
                          " assembly of the dyad puts " + joint.name + " " + side + " of " + from + "-" + to +
                          ", so it does not choose one; name two joints the two assemblies put " + joint.name +
                          " on either side of (such as the dyad's outer joints " + step.joints[0] + "-" +
                          step.joints[2] + ")");
  }
  return chosen;
}

// The unknowns' guesses at the stated assemblies (angles to the nearest turn of the
// sketch's), so that the loops written out agree.
void guess_stated_assemblies(ConstraintSystem& system, const std::vector<int>& signs) {
  const SolvingPlan& plan = *system.plan;
  std::vector<BodyPose> poses;
  const std::size_t placed = place_dyads(plan, plan.sketch_input, poses, &signs);
  if (placed < plan.dyads.size()) {
    fail(plan.joints[plan.edge_joint(plan.dyads[placed].inner)].where,
         "with the assemblies stated, dyad " + std::to_string(placed + 1) + " cannot close at the driver's sketch value; "
         "state another assembly or correct the sketch");
  }
  std::vector<double> q(system.unknowns.size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = system.unknowns[i].guess;
  unknowns_from_poses(plan, poses, q.data());
  for (std::size_t i = 0; i < q.size(); ++i) {
    Coordinate& u = system.unknowns[i];
    u.guess = u.dimension == Dimension::angle ? u.guess + std::remainder(q[i] - u.guess, 2 * kPi) : q[i];
  }
}

}  // namespace

void settle_assemblies(ConstraintSystem& system) {
  if (!system.plan || !system.plan->closed_form) return;
  SolvingPlan& plan = *system.plan;
  std::vector<BodyPose> sketch(plan.bodies.size());
  sketch[0].placed = true;
  for (std::size_t b = 1; b < plan.bodies.size(); ++b) {
    sketch[b].origin = plan.bodies[b].sketch_origin;
    sketch[b].angle = plan.bodies[b].sketch_angle;
    sketch[b].placed = true;
  }
  std::vector<int> signs = dyad_signs(plan, sketch);
  bool changed = false;
  for (std::size_t k = 0; k < plan.dyads.size(); ++k) {
    if (!plan.dyads[k].stated.empty()) {
      const int chosen = stated_sign(plan, k, signs);
      changed = changed || chosen != signs[k];
      signs[k] = chosen;
    }
  }
  for (std::size_t k = 0; k < plan.dyads.size(); ++k) plan.dyads[k].sign = signs[k];
  if (changed) guess_stated_assemblies(system, signs);
}

}  // namespace kinema
