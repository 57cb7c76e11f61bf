// The mechanism as the user described it: names, numbers in SI, and the
// formulas as written, each with the file line it came from (for messages).
// Nothing here is symbolic yet and nothing is derived: the front ends (loops/,
// linkages/, chains/) turn it into a ConstraintSystem.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/source_location.hpp"
#include "engine/base/units.hpp"

namespace kinema {

/// A named constant: a quantity ("150 mm") or a formula of earlier parameters ("CD + CE").
struct Parameter {
  std::string name;
  std::string text;          ///< As written.
  std::optional<Quantity> quantity;  ///< Set when written as a quantity.
  std::string formula;       ///< Set when written as a formula.
  SourceLocation where;
  bool generated = false;    ///< Made by kinema from a joints file's sketch, not written.
  /// Generated: the parameters of the file its value was worked out from (those the sketch's
  /// places, lengths and angles are written with, and those they follow); empty where it is
  /// a constant whatever they are.
  std::vector<std::string> follows;
};

/// A coordinate whose value the loops determine (angle or slider length).
struct Unknown {
  std::string name;
  Dimension dimension = Dimension::angle;  ///< angle or length
  double guess = 0.0;        ///< SI starting value: picks the assembly branch.
  std::string rate_name;     ///< Printed name of the first time derivative (e.g. omega3).
  std::string second_rate_name;  ///< Printed name of the second (e.g. alpha3).
  std::string latex_name;    ///< Optional LaTeX spelling (later printers).
  SourceLocation where;
};

/// The driver coordinate: crank angle or slider length, with its motion.
struct Input {
  std::string name;
  Dimension dimension = Dimension::angle;  ///< angle or length
  std::vector<double> values;  ///< SI values from the file (may be empty: CLI gives them).
  double rate = 0.0;           ///< SI; negative = clockwise / retracting.
  double second_rate = 0.0;    ///< SI.
  /// The rate and second rate as the file wrote them ("60 rpm"), for documents to show
  /// (empty: not given, the second rate then 0).
  std::string rate_text, second_rate_text;
  std::string rate_name;
  std::string second_rate_name;
  SourceLocation where;
};

/// A vector loop, = 0: either complex ("a*exp(I*theta2) + ...") or two scalar formulas.
struct Loop {
  std::string name;
  std::string complex_formula;  ///< Empty when x_formula / y_formula are given.
  std::string x_formula;
  std::string y_formula;
  SourceLocation where;
};

/// A named point whose position is a complex formula x + I*y.
struct Point {
  std::string name;
  std::string formula;
  SourceLocation where;
  bool is_joint = false;  ///< A joints-and-links file's joint, written as a point by its front end.
};

/// A joint of a mechanism described as drawn (joints and links, docs/mechanism-files.md "Joints and
/// links"): a pin between two links, or a slider of one link (the block) on a line
/// fixed in another (the guide; "ground" for a fixed guide).
struct Joint {
  enum class Kind { pin, slider };
  std::string name;
  Kind kind = Kind::pin;
  bool ground = false;              ///< A pin of ground (a fixed pivot).
  std::string x, y;                 ///< Sketch position: quantities or formulas of parameters.
  std::string guide;                ///< Slider: the link whose line it slides on ("ground", a link name).
  /// Slider: direction of the line in the sketch (quantity or formula); default, for a
  /// guide link that lists the slider: from the guide's first joint to the slider.
  std::string angle;
  /// Slider: the point of the line its coordinate is measured from (default: the guide's
  /// first joint when the guide lists the slider, else the slider's own place).
  std::string through_x, through_y;
  std::string coordinate;           ///< Slider: name of its coordinate along the line (default s_<joint>).
  std::string rate_name, second_rate_name;
  /// The middle joint of a dyad may state its assembly: "left of B-D" or "right of B-D"
  /// (the side of the line from joint B to joint D it is on at the driver's sketch value);
  /// empty: the sketch's side.
  std::string assembly;
  SourceLocation where;
};

/// A rigid body and the joints on it. Its angle is the direction from its first joint to
/// its second (a slider block's: its line's direction).
struct Link {
  std::string name;
  std::vector<std::string> joints;
  std::string angle_name;  ///< Default theta<name> (theta3) or theta_<name>.
  std::string rate_name, second_rate_name;
  /// Distances between its joints as written ("C-D" = "CD"); the others come from the sketch.
  std::vector<std::pair<std::pair<std::string, std::string>, std::string>> lengths;
  /// Angles at its first joint from its second to another joint as written (D = "180 deg").
  std::vector<std::pair<std::string, std::string>> angles;
  SourceLocation where;
};

/// A named point on a link (a coupler point), at its sketch position.
struct LinkPoint {
  std::string name;
  std::string link;
  std::string x, y;
  SourceLocation where;
};

/// The joints-and-links form; linkages/linkage_loops.hpp turns it into vector loops.
struct Linkage {
  std::vector<Joint> joints;
  std::vector<Link> links;
  std::vector<LinkPoint> points;
  std::string driver_link;    ///< A crank: its angle is the input (one of driver_link, driver_slider).
  std::string driver_slider;  ///< A slider joint: its coordinate is the input.
  SourceLocation driver_where;
};

/// A joint variable of a spatial chain (a frame's turning, a point's travel): a function
/// of time with the value, rate and constant second rate it has at t = 0 (SI).
struct ChainVariable {
  std::string name;
  Dimension dimension = Dimension::angle;  ///< angle or length
  double value = 0.0, rate = 0.0, second_rate = 0.0;
  std::string rate_name, second_rate_name;  ///< Empty: omega/alpha (angles) or v/a (lengths) and the name's digits.
  /// Found by the closures (a closed loop): value is only its guess (the assembly branch); no rates given.
  bool unknown = false;
  SourceLocation where;
};

/// A closed spatial loop: two points of the chain a fixed distance apart (a coupler
/// with a spherical joint at each end), one equation.
struct ChainClosure {
  std::string name, from, to;
  std::string length;  ///< A quantity or a formula of parameters.
  SourceLocation where;
};

/// A turn of a frame relative to its parent, applied in order, each about an axis of
/// the frame as turned so far (the first: the parent's): "x", "y", "z" or "-x", ...
struct FrameTurn {
  std::string axis;
  std::string angle;  ///< A quantity or a formula of parameters and variables.
  SourceLocation where;
};

/// A frame of a spatial chain: its origin in its parent's axes, and its turns.
struct ChainFrame {
  std::string name, parent;
  std::array<std::string, 3> origin{"0", "0", "0"};
  std::vector<FrameTurn> turns;
  std::string joint;  ///< The letter the drawings give the joint at its origin ("A"); may be empty.
  SourceLocation where;
};

/// A point at `at` in a frame's axes (a formula of variables: a point that moves in its frame).
struct ChainPoint {
  std::string name, frame;
  std::array<std::string, 3> at{"0", "0", "0"};
  SourceLocation where;
};

/// A spatial chain of rotating frames (docs/mechanism-files.md, "Spatial chains"); the observer is the frame
/// the first frame's parent names, which no entry defines.
struct SpatialChain {
  std::string observer;
  /// The driven variable that is the input of the commands (eval's --sweep in its units);
  /// empty: time. The other driven variables follow it (docs/mechanism-files.md, "Spatial chains").
  std::string input;
  SourceLocation input_where;  ///< Of the file's `input = "..."`; no line: given on the command line.
  std::vector<ChainVariable> variables;
  std::vector<ChainFrame> frames;
  std::vector<ChainPoint> points;
  std::vector<ChainClosure> closures;
};

/// What a problem asks for (the optional [problem] table, docs/problems.md): a quantity
/// to find, named as eval's output columns name it (checked against them by
/// engine/problems, which knows the columns).
struct ProblemFind {
  std::string name;
  SourceLocation where;
};

/// An input value the answers are asked at, as written ("30 deg"; read against the
/// driver by engine/problems).
struct ProblemAt {
  std::string text;
  SourceLocation where;
};

/// A parameter (or the driver's value or rate) a problem set varies: drawn on the grid
/// low, low + step, ... up to high (SI).
struct ProblemVary {
  std::string name;
  double low = 0.0, high = 0.0, step = 0.0;
  Dimension dimension = Dimension::number;
  std::string unit;  ///< The unit the range is written in ("m"), shown where the file gives no other.
  SourceLocation where;
};

/// What every variant of a problem set must meet (the [problem.conditions] table).
struct ProblemConditions {
  std::string grashof;  ///< A four-bar's class ("crank-rocker"); empty: any.
  std::optional<double> min_transmission_angle;  ///< rad: the transmission angle stays within [this, pi - this].
  bool assembles = true;  ///< Every asked value assembles (answers need it; false is refused).
  std::optional<double> toggle_margin;  ///< rad: asked values at least this far from any toggle of the crank.
  std::optional<double> min_answer;     ///< Every answer at least this large (output units, absolute).
  SourceLocation grashof_where, transmission_where, toggle_where, min_answer_where;
};

/// Most values a problem is asked at, and most quantities it asks for: each variant's sheet
/// and key give every one at every value, and each value is solved for every draw.
constexpr std::size_t kMaxProblemAt = 24;
constexpr std::size_t kMaxProblemFind = 24;

/// The [problem] table: what a problem asks and, for a problem set, what varies.
struct Problem {
  std::string statement;
  std::vector<ProblemFind> find;
  std::vector<ProblemAt> at;  ///< Empty: the file's input values.
  std::vector<ProblemVary> vary;
  ProblemConditions conditions;
  double relative_tolerance = 0.01;  ///< Used when sig_figs is 0.
  int sig_figs = 0;
  SourceLocation where;
};

struct Mechanism {
  std::string title;
  std::string description;
  std::string source_file;  ///< Path as given (for messages).
  std::vector<Parameter> parameters;
  Input input;
  std::vector<Unknown> unknowns;
  std::vector<Loop> loops;
  std::vector<Point> points;
  OutputUnits output;
  /// Set for a file written as joints and links (then parameters, input, unknowns, loops
  /// and points are what linkage_loops derived from it).
  std::optional<Linkage> linkage;
  /// Set for a file written as a spatial chain of frames (then input, unknowns and loops are empty).
  std::optional<SpatialChain> chain;
  /// Set when the file has a [problem] table (kinema problems).
  std::optional<Problem> problem;
};

}  // namespace kinema
