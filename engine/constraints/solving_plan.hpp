// How a mechanism of joints and links is solved, as the engine and the views need it,
// in terms of no front end: its joints and links by name, the solving order (the driver,
// then dyads of a kind — RRR, RRT, RTR, TRT, ... — each with its joints, as Pyslvs'
// topo_config lists them), and the numbers the closed-form dyad positions
// (engine/numeric/dyad_positions) and the drawings need: bodies, sliders and pins in
// each body's frame. A front end that finds the dyads fills it in; the constraint system
// carries it.
#pragma once

#include <complex>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/source_location.hpp"

namespace kinema {

struct SolvingPlan {
  /// A pin or a slider, in file order.
  struct Joint {
    std::string name;
    bool slider = false;
    bool ground = false;  ///< A pin of ground (a fixed pivot).
    SourceLocation where;
  };
  /// A moving link (body b is links[b - 1]; body 0 is ground).
  struct Link {
    std::string name;
    /// Its angle's name (theta3, theta_crank, or as the file names it); a slider block's
    /// angle is its guide's, and this names its own column.
    std::string angle_name;
    SourceLocation where;
  };
  /// One step of the solving order (Assur groups).
  struct Step {
    /// "driver"; a dyad's joint kinds in order ("RRR", "RRT", "RTR", "TRR", "TRT", ...);
    /// "group" for links that form no dyad (solved together by Newton on their loops).
    std::string kind;
    std::vector<std::string> links;
    std::vector<std::string> joints;  ///< A dyad: outer, inner, outer; the driver: its ground joint.
    std::string assembly;  ///< A dyad whose inner joint states its assembly: "C left of B-D"; empty: the sketch's.
  };
  /// A body's joints where they are in its frame (origin at its first joint, x along its
  /// angle); ground's are world positions. SI.
  struct Body {
    std::vector<std::pair<std::size_t, std::complex<double>>> points;
    int guide = -1;       ///< A slider block: its guide's body (its angle is the guide's + offset).
    double offset = 0.0;
    int unknown = -1;     ///< Index of its angle among the unknowns (-1: ground, driver, block).
    /// Where the sketch has it (its first joint; its angle): the assemblies are read there.
    std::complex<double> sketch_origin;
    double sketch_angle = 0.0;
  };
  struct Slider {
    std::size_t joint = 0, guide = 0, block = 0;
    std::complex<double> through;  ///< On the guide, in its frame: where the coordinate is 0.
    double direction = 0.0;        ///< The line's angle to the guide's angle.
    int unknown = -1;              ///< Index of its coordinate among the unknowns (-1: the driver).
  };
  struct Pin {
    std::size_t joint = 0, a = 0, b = 0;  ///< The two bodies it joins.
  };
  /// A dyad of the steps (in order): its links (bodies), its three joints' edges (pins:
  /// index into pins; sliders: -1 - index into sliders), and its assembly sign in the sketch.
  struct Dyad {
    std::size_t first = 0, second = 0;
    int outer_first = 0, inner = 0, outer_second = 0;
    /// Of the two assemblies; settled (engine/numeric/dyad_positions, settle_assemblies)
    /// from the sketch or the assembly the file states.
    int sign = 1;
    /// An assembly stated on the inner joint, as written ("left of B-D"; empty: the
    /// sketch's): the side of the line from joint `from` to joint `to` it is on.
    std::string stated;
    bool left = true;
    std::size_t from = 0, to = 0;
  };

  std::vector<Joint> joints;
  std::vector<Link> links;
  std::vector<Step> steps;  ///< Solving order.
  int body_count = 0;   ///< Ground and the links (Grübler's n).
  int joint_count = 0;  ///< One-degree-of-freedom joints (Grübler's j).

  std::vector<Body> bodies;  ///< 0 = ground, then the links.
  std::vector<Slider> sliders;
  std::vector<Pin> pins;
  std::vector<Dyad> dyads;
  std::size_t driver_body = 0;
  int driver_slider = -1;    ///< Index into sliders when the driver is a slider.
  double sketch_input = 0.0;  ///< The driver's value in the sketch.
  bool closed_form = false;  ///< Every link is in a dyad (else Newton alone).

  /// The joint of an edge as the dyads give it (pins: index into pins; sliders: -1 - index).
  std::size_t edge_joint(int edge) const {
    return edge >= 0 ? pins[std::size_t(edge)].joint : sliders[std::size_t(-1 - edge)].joint;
  }
};

// The plan in words, once for every printer and message: Grübler's count and the
// solving order (driver, dyads, links that form no dyad).

/// "3(n - 1) - 2j = 3*5 - 2*7 = 1 (n = 6 bodies with ground, j = 7 joints)".
std::string mobility_text(const SolvingPlan& plan);

/// One line per step: "driver: link 1 (A)", "dyad 1, RRR: links 2, 3; joints B, C, D",
/// "not a dyad: links 5, 6, 7, solved together by Newton on their loops".
std::vector<std::string> structure_lines(const SolvingPlan& plan);

/// "dyad 1 (RRR: links 2, 3; joints B, C, D)": the k-th dyad in solving order.
std::string describe_dyad(const SolvingPlan& plan, std::size_t k);

}  // namespace kinema
