// Geometry for drawings: each term of each planar loop as a segment from the
// end of the terms before it, evaluated at a solved position by the model's tape
// (no GiNaC per drawing, nothing derived again), and classed as ground, link or slider.
#pragma once

#include <array>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/symbolic/loop_terms.hpp"

namespace kinema {

struct DrawingSegment {
  using Kind = LoopTermKind;
  std::complex<double> from, to;  ///< SI.
  Kind kind = Kind::link;
  int link = -1;  ///< A link vector of fixed length: its link (MechanismGeometry::link_labels), else -1.
  /// A slider's term: the slider point (its end away from the ground side) and the guide it
  /// moves on, the line through `block` along d(term)/d(length) (unit), the way the point moves
  /// when the length changes with the other coordinates held. fixed_guide when that direction
  /// does not turn (a guide on the ground); else guide_link is the link it turns with, or -1.
  std::complex<double> block, along;
  bool fixed_guide = false;
  int guide_link = -1;
  /// A slider's block number: in the gaps the links' numbers leave (ground first: 1, or 0
  /// when a link is 1), as the instant centres number it.
  std::string block_label;
  /// A link vector whose angle is a coordinate (the input or an unknown): that coordinate
  /// (0: the input, k + 1: unknown k), its value, and the joint it is measured at (the end
  /// the vector length*e^{i angle} starts from: `from`, or `to` for a term written negated).
  int coordinate = -1;
  double angle = 0;
  std::complex<double> angle_at;
  /// The link vector (drawing stage) this segment draws; a loop's first segment starts at
  /// the origin, each next at the end of the one before (the web page lays out re-solved
  /// rows from the tape's link vectors in this order).
  std::size_t term = 0;
  bool loop_start = false;
  bool block_at_from = false;  ///< A slider's block is at `from` (else at `to`).
  bool guide_from_tape = false;  ///< `along` is the drawing stage's guide (else to - from).
  /// A pin is drawn at this end: an end of a link vector, a block's point, an end of a
  /// turning guide; a ground vector's pinned ends are fixed pivots. The foot of a fixed
  /// guide (a slider's end on a ground vector) is no joint.
  bool pin_at_from = false, pin_at_to = false;
};

/// A corner of a loop the file letters by its lengths' names but not as a point (Problem
/// 4.4's pivots A and D, from AB and CD): drawn at `segment`'s end (`at_to`, else its
/// start), where it is at the state it was found at.
struct LetteredCorner {
  std::string letter;
  std::size_t segment = 0;
  bool at_to = false;
  std::complex<double> at;  ///< SI.
};

/// A fixed length of a vector-loop drawing that one parameter of the file gives (DEF's
/// La and I*Lb, a slider guide's offset Lc or e): drawn from `from` to `to` (SI), labelled
/// with system.parameters[parameter]'s name.
struct DrawnDimension {
  std::complex<double> from, to;
  std::size_t parameter = 0;
};

/// A named point on a link: its formula's last term is a link vector of fixed length
/// turning with that link, drawn from `from` (the point that term starts at) to the point.
struct PointOnLink {
  std::size_t point = 0;
  int link = 0;
  std::size_t vector = 0;  ///< The link vector (drawing stage) its formula ends with.
  std::complex<double> from, at;  ///< SI.
};

/// A joints-and-links mechanism as drawn: its links with their joints where they are,
/// ground pivots and fixed guides (SI, world positions).
struct LinkageDrawing {
  struct Joint {
    std::string name;
    std::complex<double> at;
  };
  struct Link {
    std::vector<Joint> joints;
    bool block = false;  ///< A slider block (drawn as a block turned by `angle`).
    double angle = 0;
    std::string name;  ///< As the file names it.
    /// The coordinate that is its angle (0: the input, i + 1: unknown i; -1: none), measured
    /// at `origin` (its first joint) from the x direction; coordinate_angle its value (rad).
    int coordinate = -1;
    double coordinate_angle = 0;
    std::complex<double> origin;
  };
  struct Guide {
    std::complex<double> through, along;  ///< A point of a fixed guide line and its unit direction.
  };
  std::vector<Link> links;
  std::vector<Joint> ground_pivots;
  std::vector<Guide> guides;
};

/// The drawing at a state whose position is known, for a joints-and-links mechanism
/// placed in closed form; nullopt for anything else.
std::optional<LinkageDrawing> linkage_drawing(const ConstraintSystem& system, const MotionState& state);

/// How near two arrows come (drawing units; each drawn from its start, `first` and
/// `second` as drawn): from each tip to the other arrow, where heads meet shafts or heads;
/// for arrows from two starts, also from each start to the other arrow (0 where they
/// cross). Two arrows from one point meet there by design: that is not counted.
double arrows_distance(std::complex<double> first_from, std::complex<double> first, std::complex<double> second_from,
                       std::complex<double> second);

/// The radius of the arc marking an angle of `radians` at its vertex (drawing units): as
/// wide as its symbol needs to stand between the angle's arms (`symbol`: the symbol's
/// reach from its centre with a margin) where that is between `smallest` and `largest`;
/// never wider than `largest` (a small angle's symbol then stands beside its arc, not
/// between arms a long way out), nor than `on_arm` times `arm`, the length of the drawn
/// link whose angle it is (0: none known), so that the arc ends on that link.
double angle_mark_radius(double radians, double symbol, double arm, double smallest, double largest, double on_arm);

/// A frame of a spatial chain where a state puts it: its origin and axes (observer basis, SI).
struct PlacedFrame {
  std::string name, parent;
  std::array<double, 3> origin{};
  std::array<std::array<double, 3>, 3> axes{};  ///< x, y, z axes, each as a unit vector.
};

/// What a spatial chain is drawn with besides its frames: a frame whose parent is no frame
/// (the observer) is a ground pivot, drawn fixed, not joined to the observer's origin; each
/// point stands on its frame's body (a bar from the frame's origin); each distance closure
/// is the coupler between its two points.
struct ChainBodies {
  std::vector<bool> ground_frames;                   ///< Of each of system.frames.
  std::vector<std::string> joints;                   ///< Of each frame: its origin's letter, or "".
  std::vector<std::string> point_frames;             ///< Of each of system.points: its frame.
  std::vector<std::array<std::size_t, 2>> couplers;  ///< Indices into system.points.
};
ChainBodies chain_bodies(const ConstraintSystem& system);

/// A direction a spatial chain is seen from, as tikz-3dplot's \tdplotsetmaincoords{theta}{phi}
/// (degrees): turned by phi about z, then tilted by theta about the new x.
struct ChainView {
  double theta = 65, phi = 120;
  /// Where the view puts a point on the page (its x right, y up; same units as the point).
  std::complex<double> on_page(const std::array<double, 3>& p) const;
};

/// The view, among theta 50, 65, 80 and phi every 30 degrees, in which the chain's places
/// (the observer's origin, the frames' origins, the points at `points`, in system.points'
/// order; none where unknown) are seen farthest apart, from each other and from the lines
/// drawn that do not end at them (the bodies of ChainBodies, the observer's axes), for the
/// drawing's size: a joint seen beside another, or on a link, reads as joined to it. The
/// usual view (65, 120) unless another does 10 % better.
ChainView chain_view(const ConstraintSystem& system, const std::vector<PlacedFrame>& frames,
                     const std::vector<std::array<double, 3>>& points);

/// Every frame of a spatial chain at a state whose position is known, in the file's order
/// (the frames' formulas as the model's tape evaluates them).
std::vector<PlacedFrame> placed_frames(const Model& model, const MotionState& state);

/// The loops' terms of a vector-loop file as segments, and its named points on links, at
/// a state: each term as the model derived and compiled it (its link vectors and their
/// guides, TapeLayout::kDrawingStage), classed and numbered by classify_loop_terms.
class MechanismGeometry {
 public:
  /// Reads the model's link vectors and tape; the model must outlive it.
  explicit MechanismGeometry(const Model& model);
  /// The system of the model it reads.
  const ConstraintSystem& system() const { return *system_; }
  /// The loops' segments at a state whose position is known (status not unassembled). A loop's
  /// terms are laid end to end from the origin in the order, among those that close it, that
  /// puts its ground vectors at the origin and its corners on the most named points (the
  /// written order when it does so already): r e^{i phi} - AC - BC e^{i phi3} is drawn
  /// A -> B -> C -> A, not through B - AC.
  std::vector<DrawingSegment> segments(const MotionState& state) const;
  /// The loops' corners the file letters without naming them as points: a term whose one
  /// two-capital-letter length names its ends ("AB*exp(I*phi)", "I*AC") carries those letters
  /// to its two corners, a corner known (a one-letter named point there, or a letter from the
  /// next term) giving the other: Problem 4.4's AB and CD make the origin A and the pivot D.
  /// None where the names disagree (a named point a term's letters do not fit); only
  /// corners drawn (a segment's end) and not a named point; one letter a place. `segments`
  /// are segments(state).
  std::vector<LetteredCorner> lettered_corners(const MotionState& state, const std::vector<DrawingSegment>& segments) const;
  /// The ground lengths one length parameter gives: a ground term that is that parameter
  /// (times 1, -1, i or -i), along its segment; a fixed guide's offset, a slider term's
  /// constant part that is one, from the term's ground end towards the guide. `segments`
  /// are segments(state).
  std::vector<DrawnDimension> dimensions(const std::vector<DrawingSegment>& segments) const;
  /// The named points that lie on a link, at a state that is ok.
  std::vector<PointOnLink> points_on_links(const MotionState& state) const;
  /// Each link's number, as DrawingSegment::link and PointOnLink::link index them.
  const std::vector<std::string>& link_labels() const { return terms_.link_labels; }
  /// Each link's angular rate (omega3), indexed as link_labels.
  const std::vector<GiNaC::ex>& link_rates() const { return terms_.link_rates; }
  /// Each link's angular velocity at a state that is ok (rad/s, link_rates as the model's
  /// tape evaluates them), indexed as link_labels; nullopt where it is not a finite real
  /// number, and for every link where the drawing stage gives no values.
  std::vector<std::optional<double>> link_angular_velocities(const MotionState& state) const;
  /// The model's drawing stage's outputs at a state (Kinematics::drawing_values), and where they are.
  std::vector<double> drawing_values(const MotionState& state) const { return kinematics_->drawing_values(state); }
  const TapeLayout& layout() const { return kinematics_->layout(); }

 private:
  const ConstraintSystem* system_ = nullptr;  ///< The model's.
  const Kinematics* kinematics_ = nullptr;    ///< The model's.
  LoopTerms terms_;
};

}  // namespace kinema
