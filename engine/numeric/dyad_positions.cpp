#include "engine/numeric/dyad_positions.hpp"
#include "engine/base/units.hpp"

#include <cmath>

namespace kinema {
namespace {

using Complex = std::complex<double>;

Complex turn(double angle) { return std::polar(1.0, angle); }

Complex point_on(const SolvingPlan& frames, std::size_t body, std::size_t joint) {
  for (const auto& [j, v] : frames.bodies[body].points)
    if (j == joint) return v;
  return {};
}

Complex world(const SolvingPlan& frames, const std::vector<BodyPose>& poses, std::size_t body, std::size_t joint) {
  return poses[body].origin + point_on(frames, body, joint) * turn(poses[body].angle);
}

// The angle of a body that slides on (or guides) a placed body: fixed by that one.
double angle_through_slider(const SolvingPlan& frames, const std::vector<BodyPose>& poses,
                            const SolvingPlan::Slider& s, std::size_t body) {
  return body == s.block ? poses[s.guide].angle + frames.bodies[s.block].offset
                         : poses[s.block].angle - frames.bodies[s.block].offset;
}

// What one outer joint says of the inner joint J of link `body`: on a circle (a pin to
// a placed body) or on a line (a slider on or through a placed body).
struct Locus {
  bool circle = true;
  Complex center;  // circle: centre; line: a point
  double radius = 0;
  Complex along;   // line: unit direction
  double angle = 0;  // line: the link's angle (known)
};

Locus locus(const SolvingPlan& frames, const std::vector<BodyPose>& poses, int edge, std::size_t body,
            std::size_t inner_joint) {
  Locus l;
  if (edge >= 0) {
    const SolvingPlan::Pin& pin = frames.pins[std::size_t(edge)];
    const std::size_t other = pin.a == body ? pin.b : pin.a;
    l.center = world(frames, poses, other, pin.joint);
    l.radius = std::abs(point_on(frames, body, inner_joint) - point_on(frames, body, pin.joint));
    return l;
  }
  const SolvingPlan::Slider& s = frames.sliders[std::size_t(-1 - edge)];
  l.circle = false;
  l.angle = angle_through_slider(frames, poses, s, body);
  if (body == s.block) {
    const BodyPose& g = poses[s.guide];
    const Complex through = g.origin + s.through * turn(g.angle);
    l.center = through + (point_on(frames, body, inner_joint) - point_on(frames, body, s.joint)) * turn(l.angle);
    l.along = turn(g.angle + s.direction);
  } else {  // the link is the guide; the block is placed
    const Complex q = world(frames, poses, s.block, s.joint);
    l.center = q + (point_on(frames, body, inner_joint) - s.through) * turn(l.angle);
    l.along = -turn(l.angle + s.direction);
  }
  return l;
}

// A link placed from its inner joint J and its outer joint's locus.
void place_link(const SolvingPlan& frames, std::vector<BodyPose>& poses, const Locus& l, int edge, std::size_t body,
                std::size_t inner_joint, Complex j) {
  BodyPose& pose = poses[body];
  if (l.circle) {
    const std::size_t outer_joint = frames.pins[std::size_t(edge)].joint;
    const Complex in_body = point_on(frames, body, inner_joint) - point_on(frames, body, outer_joint);
    pose.angle = std::arg(j - l.center) - std::arg(in_body);
  } else {
    pose.angle = l.angle;
  }
  pose.origin = j - point_on(frames, body, inner_joint) * turn(pose.angle);
  pose.placed = true;
}

// Roots of s^2 + 2 p s + c = 0: -p + sign * sqrt(p^2 - c); false when there are none.
bool root(double p, double c, int sign, double& s) {
  const double discriminant = p * p - c;
  const double scale = p * p + std::fabs(c) + 1e-300;
  if (discriminant < -1e-12 * scale) return false;
  s = -p + sign * std::sqrt(std::max(discriminant, 0.0));
  return true;
}

bool place_dyad(const SolvingPlan& frames, std::vector<BodyPose>& poses, const SolvingPlan::Dyad& d, int sign) {
  if (d.inner >= 0) {
    const std::size_t j = frames.pins[std::size_t(d.inner)].joint;
    const Locus a = locus(frames, poses, d.outer_first, d.first, j);
    const Locus b = locus(frames, poses, d.outer_second, d.second, j);
    Complex at;
    if (a.circle && b.circle) {
      const Complex between = b.center - a.center;
      const double distance = std::abs(between);
      if (distance == 0 || a.radius == 0) return false;
      const double cosine = (a.radius * a.radius + distance * distance - b.radius * b.radius) / (2 * a.radius * distance);
      if (std::fabs(cosine) > 1 + 1e-12) return false;
      at = a.center + a.radius * turn(std::arg(between) + sign * std::acos(std::max(-1.0, std::min(1.0, cosine))));
    } else if (a.circle != b.circle) {
      const Locus& circle = a.circle ? a : b;
      const Locus& line = a.circle ? b : a;
      const Complex from = line.center - circle.center;
      double s = 0;
      if (!root(std::real(from * std::conj(line.along)), std::norm(from) - circle.radius * circle.radius, sign, s)) return false;
      at = line.center + s * line.along;
    } else {  // two lines
      const double cross = std::imag(std::conj(a.along) * b.along);
      if (std::fabs(cross) < 1e-12) return false;
      const double s = std::imag(std::conj(b.center - a.center) * b.along) / cross;
      at = a.center + s * a.along;
    }
    place_link(frames, poses, a, d.outer_first, d.first, j, at);
    place_link(frames, poses, b, d.outer_second, d.second, j, at);
    return true;
  }
  // RTR: the inner joint is a slider, both outer joints pins.
  const SolvingPlan::Slider& s = frames.sliders[std::size_t(-1 - d.inner)];
  if (d.outer_first < 0 || d.outer_second < 0) return false;
  const auto outer_of = [&](std::size_t body) {
    const int edge = body == d.first ? d.outer_first : d.outer_second;
    const SolvingPlan::Pin& pin = frames.pins[std::size_t(edge)];
    return std::pair<std::size_t, Complex>{pin.joint, world(frames, poses, pin.a == body ? pin.b : pin.a, pin.joint)};
  };
  const auto [guide_pin, guide_at] = outer_of(s.guide);
  const auto [block_pin, block_at] = outer_of(s.block);
  const double offset = frames.bodies[s.block].offset;
  const Complex m = (s.through - point_on(frames, s.guide, guide_pin)) -
                    (point_on(frames, s.block, s.joint) - point_on(frames, s.block, block_pin)) * turn(offset);
  const Complex between = block_at - guide_at, along = turn(s.direction);
  double travel = 0;
  if (!root(std::real(m * std::conj(along)), std::norm(m) - std::norm(between), sign, travel)) return false;
  const Complex in_guide = m + travel * along;
  if (std::abs(in_guide) == 0) return false;
  BodyPose& g = poses[s.guide];
  g.angle = std::arg(between) - std::arg(in_guide);
  g.origin = guide_at - point_on(frames, s.guide, guide_pin) * turn(g.angle);
  g.placed = true;
  BodyPose& k = poses[s.block];
  k.angle = g.angle + offset;
  k.origin = block_at - point_on(frames, s.block, block_pin) * turn(k.angle);
  k.placed = true;
  return true;
}

void place_driver(const SolvingPlan& frames, double input, std::vector<BodyPose>& poses) {
  poses.assign(frames.bodies.size(), BodyPose{});
  poses[0].placed = true;
  if (frames.driver_slider >= 0) {
    const SolvingPlan::Slider& s = frames.sliders[std::size_t(frames.driver_slider)];
    BodyPose& block = poses[s.block];
    block.angle = frames.bodies[s.block].offset;
    const Complex at = s.through + input * turn(s.direction);
    block.origin = at - point_on(frames, s.block, s.joint) * turn(block.angle);
    block.placed = true;
    return;
  }
  BodyPose& crank = poses[frames.driver_body];
  crank.angle = input;
  for (const SolvingPlan::Pin& pin : frames.pins) {
    if ((pin.a == 0 && pin.b == frames.driver_body) || (pin.b == 0 && pin.a == frames.driver_body)) {
      crank.origin = point_on(frames, 0, pin.joint) - point_on(frames, frames.driver_body, pin.joint) * turn(input);
      break;
    }
  }
  crank.placed = true;
}

}  // namespace

std::size_t place_dyads(const SolvingPlan& frames, double input, std::vector<BodyPose>& poses,
                        const std::vector<int>* signs) {
  place_driver(frames, input, poses);
  for (std::size_t k = 0; k < frames.dyads.size(); ++k) {
    const int sign = signs ? (*signs)[k] : frames.dyads[k].sign;
    if (!place_dyad(frames, poses, frames.dyads[k], sign)) return k;
  }
  return frames.dyads.size();
}

bool joint_position(const SolvingPlan& frames, const std::vector<BodyPose>& poses, std::size_t joint,
                    std::complex<double>& at) {
  for (std::size_t b = 0; b < frames.bodies.size(); ++b) {
    if (!poses[b].placed) continue;
    for (const auto& [j, v] : frames.bodies[b].points) {
      if (j != joint) continue;
      at = poses[b].origin + v * turn(poses[b].angle);
      return true;
    }
  }
  return false;
}

void unknowns_from_poses(const SolvingPlan& frames, const std::vector<BodyPose>& poses, double* q) {
  for (std::size_t b = 0; b < frames.bodies.size(); ++b)
    if (frames.bodies[b].unknown >= 0) q[frames.bodies[b].unknown] = poses[b].angle;
  for (const SolvingPlan::Slider& s : frames.sliders) {
    if (s.unknown < 0) continue;
    const BodyPose& g = poses[s.guide];
    const Complex through = g.origin + s.through * turn(g.angle);
    q[s.unknown] = std::real((world(frames, poses, s.block, s.joint) - through) * std::conj(turn(g.angle + s.direction)));
  }
}

std::vector<int> signs_nearest(const SolvingPlan& frames, double input, const double* q, double length_scale,
                               const std::vector<int>* current) {
  std::vector<int> signs;
  std::vector<BodyPose> poses;
  place_driver(frames, input, poses);
  // Nearer by more than rounding: at a toggle the two positions differ in the last bits.
  const double tie = current ? 1e-9 : 0.0;
  for (const SolvingPlan::Dyad& d : frames.dyads) {
    double best = INFINITY;
    const int first = current ? (*current)[signs.size()] : d.sign;
    int chosen = first;
    std::vector<BodyPose> kept;
    for (int sign : {first, -first}) {
      std::vector<BodyPose> trial = poses;
      if (!place_dyad(frames, trial, d, sign)) continue;
      // The unknowns this dyad placed: its links' angles and the coordinates of sliders
      // now between placed bodies.
      double miss = 0;
      for (std::size_t b : {d.first, d.second}) {
        const int u = frames.bodies[b].unknown;
        if (u >= 0) miss += std::fabs(std::remainder(trial[b].angle - q[u], 2 * kPi));
      }
      for (const SolvingPlan::Slider& s : frames.sliders) {
        if (s.unknown < 0 || !trial[s.guide].placed || !trial[s.block].placed) continue;
        if (s.guide != d.first && s.guide != d.second && s.block != d.first && s.block != d.second) continue;
        const BodyPose& g = trial[s.guide];
        const Complex through = g.origin + s.through * turn(g.angle);
        const double travel =
            std::real((world(frames, trial, s.block, s.joint) - through) * std::conj(turn(g.angle + s.direction)));
        miss += std::fabs(travel - q[s.unknown]) / length_scale;
      }
      if (miss + tie < best) {
        best = miss;
        chosen = sign;
        kept = trial;
      }
    }
    signs.push_back(chosen);
    if (kept.empty()) {  // cannot close here: the rest as they were
      for (std::size_t k = signs.size(); k < frames.dyads.size(); ++k) signs.push_back(frames.dyads[k].sign);
      return signs;
    }
    poses = kept;
  }
  return signs;
}

std::vector<int> dyad_signs(const SolvingPlan& frames, const std::vector<BodyPose>& configuration) {
  std::vector<int> signs;
  for (const SolvingPlan::Dyad& d : frames.dyads) {
    // Each dyad from the configuration's own placed bodies, so that an earlier dyad's
    // rounding does not decide a later one's side.
    double best = INFINITY;
    int chosen = 1;
    for (int sign : {1, -1}) {
      std::vector<BodyPose> trial = configuration;
      trial[d.first].placed = trial[d.second].placed = false;
      if (!place_dyad(frames, trial, d, sign)) continue;
      double miss = 0;
      for (std::size_t b : {d.first, d.second}) {
        miss += std::abs(trial[b].origin - configuration[b].origin) +
                std::abs(std::remainder(trial[b].angle - configuration[b].angle, 2 * kPi));
      }
      if (miss < best) {
        best = miss;
        chosen = sign;
      }
    }
    signs.push_back(chosen);
  }
  return signs;
}

}  // namespace kinema
