// Closed-form positions of a joints-and-links mechanism, dyad by dyad (the method of
// seeds 002 and 004): the driver at the input value, then each dyad from what is
// already placed — two circles (RRR), a circle and a line (RRT, TRR), two lines (TRT),
// or a link turning through a slider (RTR) — on the assembly sign of the sketch.
// No iteration and no path: a value far from the last one (a list, a periodic angle,
// the row after a gap) lands on the same branch as the sketch.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "engine/constraints/solving_plan.hpp"

namespace kinema {

/// Where each body is: the world position of its frame's origin (its first joint) and
/// its angle. Ground is at 0 with angle 0.
struct BodyPose {
  std::complex<double> origin;
  double angle = 0.0;
  bool placed = false;
};

/// Places the driver at `input` and every dyad on its sign (frames.dyads[k].sign, or
/// `signs` when given). Returns the number of dyads placed: all of them, or the index
/// of the first that cannot close (its circles or lines do not meet).
std::size_t place_dyads(const SolvingPlan& frames, double input, std::vector<BodyPose>& poses,
                        const std::vector<int>* signs = nullptr);

/// Where a joint is: on the first placed body that carries it (false when none is placed).
bool joint_position(const SolvingPlan& frames, const std::vector<BodyPose>& poses, std::size_t joint,
                    std::complex<double>& at);

/// The unknowns (link angles, slider coordinates, in the order of the loops) of placed bodies.
void unknowns_from_poses(const SolvingPlan& frames, const std::vector<BodyPose>& poses, double* q);

/// The signs of the dyads whose positions at `input` are nearest the unknowns q (link
/// angles to whole turns, slider coordinates relative to `length_scale`): the signs of a
/// solved position, or of a predicted one. Dyads that cannot close keep frames' signs.
/// With `current` (the signs a path is on), a dyad whose two positions are equally near
/// (at a toggle they are one) keeps its current sign rather than the sketch's.
std::vector<int> signs_nearest(const SolvingPlan& frames, double input, const double* q, double length_scale,
                               const std::vector<int>* current = nullptr);

/// The sign of each dyad in a configuration (the sketch's): the one of the two
/// solutions that lies nearer its links' poses.
std::vector<int> dyad_signs(const SolvingPlan& frames, const std::vector<BodyPose>& configuration);

}  // namespace kinema
