// The joints-and-links front end's working state, shared by the files that each do one
// of its jobs (linkages/: link_graph, driver, coordinates, link_vectors, loop_sums, dyads,
// plan_export, sketch_numbers); linkage_loops.cpp runs them in order. Internal: only
// linkages/ includes it.
#pragma once

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <complex>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/user_text.hpp"
#include "engine/constraints/formula_reader.hpp"
#include "engine/constraints/solving_plan.hpp"
#include "linkages/loop_terms.hpp"
#include "readers/mechanism.hpp"

namespace kinema::linkage_detail {

using Point2 = std::complex<double>;

// A given length may differ from the sketch by this much (relative): sketches are
// drawn to a few digits (Example 4.1 gives x_B = y_B = 0.256 m for |BC| = 0.3 m);
// more than this is a typo in one of the two.
constexpr double kSketchTolerance = 0.01;

inline bool is_identifier(const std::string& text) {
  if (text.empty() || !std::isalpha(static_cast<unsigned char>(text[0]))) return false;
  return std::all_of(text.begin(), text.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// Angle in (-pi, pi].
inline double wrapped(double angle) {
  angle = std::remainder(angle, 2 * kPi);
  return angle <= -kPi ? angle + 2 * kPi : angle;
}

/// What the front end derives beside the declarations it adds to the mechanism.
struct LinkageTerms {
  std::vector<TermSum> loops, points;
  SolvingPlan plan;
  std::vector<TermSum> ground;  ///< Each ground joint's position (not a point: no columns).
};

class LinkageWriter {
 public:
  /// Adds to `mechanism` the parameters the loops need, the input's names and the unknowns.
  explicit LinkageWriter(Mechanism& mechanism) : m_(mechanism), linkage_(*mechanism.linkage) {}

  /// The loops, points and solving plan found by write().
  LinkageTerms terms() && { return {std::move(loops_), std::move(points_), std::move(plan_), std::move(ground_)}; }

  void write() {
    evaluate_parameters();
    place_joints();
    make_bodies();
    make_edges();
    check_connected();
    check_mobility();
    choose_driver();
    reserve_names();
    orient_bodies();
    name_coordinates();
    write_loops();
    write_points();
    decompose();
    export_plan();
  }

 private:
  struct Body {
    std::string name;            // "ground" or the link's name
    const Link* link = nullptr;  // nullptr for ground
    std::vector<std::size_t> joints;
    int slider = -1;             // joint index of the slider it is the block of
    std::string angle;           // formula of its angle ("0" for ground; a block: its guide's) ...
    double offset = 0;           // ... plus this constant (a block: its line's angle to its guide)
    double angle0 = 0;           // in the sketch (offset included)
    bool oriented = false;
    int parent_edge = -1;
    int parent = -1;
    std::size_t depth = 0;
  };
  struct Edge {
    std::size_t joint;
    std::size_t a, b;  // pin: the two bodies; slider: a = guide, b = block
    bool slider = false;
    bool in_tree = false;
  };
  // Where a joint is on a body: ground's points as written, a link's from its first joint.
  struct Path {
    std::vector<std::pair<int, std::vector<Term>>> steps;  // (tree edge, its terms) from ground
  };

  Mechanism& m_;
  const Linkage& linkage_;
  SolvingPlan plan_;
  std::vector<TermSum> loops_, points_, ground_;
  std::map<std::string, double> values_;  // parameters, SI
  GiNaC::exmap symbol_values_;            // the file's parameters by their symbols in reader_
  std::set<std::string> taken_;           // symbol names
  std::map<std::string, std::string> generated_;  // parameters made here, by the name wanted
  std::map<std::string, std::set<std::string>> parameter_follows_;  // a name and the file's parameters it follows
  std::map<std::string, std::size_t> file_parameters_;  // the file's own, by name: index into m_.parameters
  FormulaReader reader_;
  std::vector<Point2> at_;                // joints in the sketch
  std::vector<Body> bodies_;              // 0 = ground
  std::map<std::string, std::size_t> body_index_;
  std::map<std::string, std::size_t> joint_index_;
  std::vector<Edge> edges_;
  std::vector<std::array<std::size_t, 5>> dyad_edges_;  // first, second, outer edges and inner edge
  std::vector<std::string> slider_coordinate_;  // per joint (sliders)
  std::vector<double> slider_value0_;
  std::size_t driver_body_ = 0;
  int driver_slider_ = -1;

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw InputError(where.str() + ": " + message);
  }

  // sketch_numbers.cpp: the sketch's numbers and the parameters made for the loops
  void evaluate_parameters();
  double evaluate(const std::string& formula, const SourceLocation& where, const std::string& what);
  double value_of(const std::string& text, Dimension dimension, const SourceLocation& where, const std::string& what);
  std::string fresh_name(const std::string& wanted);
  std::string add_parameter(const std::string& wanted, double value, Dimension dimension, const SourceLocation& where,
                            const std::set<std::string>& follows = {});
  // The file's parameters a number of the sketch was worked out from (Parameter::follows).
  std::set<std::string> text_follows(const std::string& text);
  std::set<std::string> joint_follows(std::size_t j);
  std::set<std::string> body_follows(const Body& body, std::size_t depth = 0);
  Operand as_factor(const std::string& text, const std::string& wanted, Dimension dimension,
                        const SourceLocation& where, const std::string& what);

  // link_graph.cpp: bodies and joints as a graph, connected, mobility 1
  void place_joints();
  void make_bodies();
  std::string body_list(const std::vector<std::size_t>& bodies) const;
  void make_edges();
  void check_connected();
  void check_mobility();

  // driver.cpp
  void choose_driver();

  // coordinates.cpp: link angles along the tree, slider coordinates, the unknowns
  std::string default_angle_name(const Body& body) const;
  void reserve_names();
  void orient_bodies();
  const Body* listing_guide(std::size_t j) const;
  double slider_direction(std::size_t j);
  void orient(std::size_t b, int depth);
  void name_coordinates();
  Point2 through0(std::size_t j);

  // link_vectors.cpp: a joint's vector on its body as loop terms
  const std::string* given_length(const Body& body, const std::string& a, const std::string& b) const;
  double length_value(const Body& body, std::size_t ja, std::size_t jb);
  Operand length_factor(const Body& body, std::size_t ja, std::size_t jb);
  double offset(const Body& body, std::size_t j, double d_first_j);
  Term rotated(const Operand& factor, const std::string& angle, double beta, const std::string& beta_name,
               const SourceLocation& where, const std::string& written = "", const std::set<std::string>& follows = {});
  std::vector<Term> body_vector(std::size_t b, std::size_t j);
  std::vector<Term> ground_point(const std::string& x, const std::string& y, const std::string& name,
                                 const SourceLocation& where);
  std::vector<Term> through_vector(std::size_t j);
  Term travel(std::size_t j);

  // loop_sums.cpp: the loops and points as sums of terms
  Path position(std::size_t b, std::size_t j);
  Path reference(std::size_t b);
  static std::vector<Term> flatten(const Path& path, std::size_t from);
  std::string cycle_name(const Path& a, const Path& b, std::size_t common, std::size_t closing) const;
  void write_loops();
  void write_points();

  // dyads.cpp: the solving order
  void decompose();

  // plan_export.cpp: the solving plan and the assemblies stated
  void export_plan();
  void check_assembly_joints() const;
  void state_assemblies();
};

}  // namespace kinema::linkage_detail
