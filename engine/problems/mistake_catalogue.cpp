#include "engine/problems/mistake_catalogue.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>

#include "engine/analysis/diagnostics.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/numeric/workspace.hpp"

namespace kinema {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ResultRow columns_of(const Model& model, const MotionTable& table) {
  const ConstraintSystem& system = model.system;
  ResultRow values(result_column_count(system));
  result_values(system, OutputScale(system), table, 0, values.data());
  return values;
}

std::vector<std::size_t> point_dimensions(const ConstraintSystem& system) {
  std::vector<std::size_t> dimensions;
  for (const PointObservable& p : system.points) dimensions.push_back(p.components.size());
  return dimensions;
}

// Where each column is, by name.
std::map<std::string, std::size_t> column_index(const ConstraintSystem& system) {
  std::map<std::string, std::size_t> index;
  const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system));
  for (std::size_t c = 0; c < columns.size(); ++c) index[columns[c].name] = c;
  return index;
}

// A row of NaN, the shape of the correct one.
MistakenRow blank_row(const SolvedRow& correct, std::string detail) {
  return {std::move(detail), ResultRow(correct.values.size(), kNaN)};
}

// The mechanism solved at the point, or nothing where it has no rates (a mistaken
// mechanism that cannot be assembled makes no answer).
std::optional<SolvedRow> try_solve(const EvaluationPoint& point) {
  try {
    return solve_row(point);
  } catch (const Error&) {
    return std::nullopt;
  }
}

// --- sign or sense reversed: every value negated.
std::vector<MistakenRow> sign_reversed(const EvaluationPoint&, const SolvedRow& correct) {
  MistakenRow row{"", correct.values};
  for (double& v : row.values) v = -v;
  return {row};
}

// --- the number of one unit written for the other: each column in `unit` converted by `factor`.
std::vector<MistakenRow> unit_confused(const EvaluationPoint& point, const SolvedRow& correct,
                                       bool (*in_unit)(const std::string&), double factor) {
  const ConstraintSystem& system = point.model->system;
  const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system));
  MistakenRow row = blank_row(correct, "");
  bool any = false;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (!in_unit(columns[c].unit)) continue;
    row.values[c] = correct.values[c] * factor;
    any = true;
  }
  if (!any) return {};
  return {row};
}

bool in_radians(const std::string& unit) { return unit == "rad/s" || unit == "rad/s^2"; }
bool in_degrees(const std::string& unit) { return unit == "deg"; }

std::vector<MistakenRow> degrees_for_radians(const EvaluationPoint& point, const SolvedRow& correct) {
  return unit_confused(point, correct, in_radians, 180.0 / kPi);
}

std::vector<MistakenRow> radians_for_degrees(const EvaluationPoint& point, const SolvedRow& correct) {
  return unit_confused(point, correct, in_degrees, kPi / 180.0);
}

// --- the driver's rate written in rpm, its number used as rad/s.
std::vector<MistakenRow> rpm_as_rad_per_s(const EvaluationPoint& point, const SolvedRow&) {
  const std::string& text = point.rate_text;
  const std::size_t end = text.find_last_not_of(' ');
  if (end == std::string::npos || end < 2 || text.compare(end - 2, 3, "rpm") != 0) return {};
  EvaluationPoint mistaken = point;
  mistaken.rate = point.rate * 60.0 / (2.0 * kPi);  // the rpm number itself
  const std::optional<SolvedRow> solved = try_solve(mistaken);
  if (!solved) return {};
  const std::string number = format_significant(mistaken.rate, 6);
  return {{number + " rpm used as " + number + " rad/s", solved->values}};
}

// Each dyad's assembly flipped alone, then all of them (joints and links solved in closed form).
std::vector<std::vector<int>> flipped_signs(const SolvingPlan& plan) {
  std::vector<int> sketch;
  for (const SolvingPlan::Dyad& dyad : plan.dyads) sketch.push_back(dyad.sign);
  std::vector<std::vector<int>> flips;
  for (std::size_t k = 0; k < sketch.size(); ++k) {
    flips.push_back(sketch);
    flips.back()[k] = -sketch[k];
  }
  if (sketch.size() > 1) {
    flips.push_back(sketch);
    for (int& sign : flips.back()) sign = -sign;
  }
  return flips;
}

// Starting guesses around a solved position: each angle a quarter turn on at a time, each
// length as it is or reversed; every combination where they are few, else one unknown at a time.
std::vector<Eigen::VectorXd> starting_guesses(const ConstraintSystem& system, const Eigen::VectorXd& q) {
  constexpr std::size_t kMaxAssemblyGuesses = 4096;
  std::vector<std::vector<double>> options;
  std::size_t combinations = 1;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double v = q[i];
    if (system.unknowns[std::size_t(i)].dimension == Dimension::angle) {
      options.push_back({v, v + kPi / 2, v + kPi, v - kPi / 2});
    } else {
      options.push_back({v, -v});
    }
    combinations = std::min(combinations * options.back().size(), kMaxAssemblyGuesses + 1);
  }
  std::vector<Eigen::VectorXd> guesses;
  if (combinations <= kMaxAssemblyGuesses) {
    for (std::size_t k = 1; k < combinations; ++k) {
      Eigen::VectorXd guess = q;
      std::size_t rest = k;
      for (std::size_t i = 0; i < options.size(); ++i) {
        guess[Eigen::Index(i)] = options[i][rest % options[i].size()];
        rest /= options[i].size();
      }
      guesses.push_back(guess);
    }
    return guesses;
  }
  for (std::size_t i = 0; i < options.size(); ++i) {
    for (std::size_t o = 1; o < options[i].size(); ++o) {
      guesses.push_back(q);
      guesses.back()[Eigen::Index(i)] = options[i][o];
    }
  }
  return guesses;
}

// Two solved positions are one assembly when every point is in the same place (or, with no
// points, every coordinate is the same, angles to whole turns).
bool same_assembly(const ConstraintSystem& system, const MotionState& a, const MotionState& b, double tolerance) {
  if (!system.points.empty() && a.points.size() == b.points.size()) {
    for (std::size_t p = 0; p < a.points.size(); ++p)
      for (std::size_t c = 0; c < 3; ++c)
        if (std::abs(a.points[p].position[c] - b.points[p].position[c]) > tolerance) return false;
    return true;
  }
  for (Eigen::Index i = 0; i < a.q.size(); ++i) {
    double d = a.q[i] - b.q[i];
    if (system.unknowns[std::size_t(i)].dimension == Dimension::angle) d = std::remainder(d, 2 * kPi);
    if (std::abs(d) > tolerance) return false;
  }
  return true;
}

// "theta3 = 112.4 deg, theta4 = 160.2 deg": an assembly said by its unknowns.
std::string assembly_words(const ConstraintSystem& system, const MotionState& state) {
  const OutputScale scale(system);
  std::string words;
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
    const Coordinate& q = system.unknowns[i];
    words += (words.empty() ? "" : ", ") + q.name + " = " +
             format_significant(scale.coordinate(q.dimension, state.q[Eigen::Index(i)]), 4) + " " +
             scale.coordinate_unit(q.dimension);
  }
  return words;
}

// Positions of the other assemblies at the point: the dyads' other signs where the model is
// solved in closed form, else Newton from starting guesses around the correct position.
std::vector<Eigen::VectorXd> other_positions(const EvaluationPoint& point, const SolvedRow& correct) {
  const Model& model = *point.model;
  std::vector<Eigen::VectorXd> positions;
  if (const SolvingPlan* plan = model.kinematics.closed_form()) {
    for (const std::vector<int>& signs : flipped_signs(*plan)) {
      std::vector<BodyPose> poses;
      if (place_dyads(*plan, point.at, poses, &signs) != plan->dyads.size()) continue;
      Eigen::VectorXd q(correct.state.q.size());
      unknowns_from_poses(*plan, poses, q.data());
      positions.push_back(q);
    }
    return positions;
  }
  Workspace workspace(model);
  for (Eigen::VectorXd q : starting_guesses(model.system, correct.state.q))
    if (workspace.solve_position(point.at, q)) positions.push_back(q);
  return positions;
}

// --- the other assembly (branch, circuit): every assembly other than the file's at the point.
std::vector<MistakenRow> other_assembly(const EvaluationPoint& point, const SolvedRow& correct) {
  const Model& model = *point.model;
  const double tolerance = 1e-6 * model.kinematics.length_scale();
  Workspace workspace(model);
  std::vector<MotionState> found{correct.state};
  std::vector<MistakenRow> rows;
  for (const Eigen::VectorXd& q : other_positions(point, correct)) {
    MotionState state = workspace.motion(point.at, point.rate, point.second_rate, q);
    if (state.status != Status::ok) continue;
    const bool seen = std::any_of(found.begin(), found.end(), [&](const MotionState& other) {
      return same_assembly(model.system, state, other, tolerance);
    });
    if (seen) continue;
    rows.push_back({assembly_words(model.system, state), row_of(model, state)});
    found.push_back(std::move(state));
  }
  return rows;
}

// The Coriolis parts (complex, SI) of each loop and of each point's written vectors at a
// state, from the model's drawing stage; nullopt for a system with no Coriolis term or no
// drawing stage.
struct CoriolisParts {
  Eigen::VectorXd equations;  ///< Per equation row: the loop's Coriolis sum, x and y.
  std::vector<std::optional<std::complex<double>>> points;  ///< Per point; nullopt without written vectors.
  std::vector<double> drawing;  ///< The drawing stage's values at the state.
};

bool has_coriolis_term(const PlanarLinkVectors& vectors) {
  return std::any_of(vectors.vectors.begin(), vectors.vectors.end(), [](const LinkVectorMotion& v) {
    return v.derived && v.textbook && !v.parts[coriolis].is_zero();
  });
}

// Vector k's part p off the drawing stage's values.
std::complex<double> vector_part(const TapeLayout& layout, const std::vector<double>& drawing, std::size_t k,
                                 std::size_t p) {
  const double* v = drawing.data() + layout.link_vector_output(k) + TapeLayout::kVectorPartsAt + 2 * p;
  return {v[0], v[1]};
}

std::optional<CoriolisParts> coriolis_parts(const Model& model, const MotionState& state) {
  const PlanarLinkVectors& vectors = model.derivation.link_vectors;
  if (!has_coriolis_term(vectors)) return std::nullopt;
  CoriolisParts parts{Eigen::VectorXd::Zero(Eigen::Index(model.system.equations.size())),
                      std::vector<std::optional<std::complex<double>>>(model.system.points.size()),
                      model.kinematics.drawing_values(state)};
  if (parts.drawing.empty()) return std::nullopt;
  const TapeLayout& layout = model.kinematics.layout();
  for (const PlanarLinkVectors::Chain& chain : vectors.chains) {
    std::complex<double> sum = 0;
    for (std::size_t k : chain.vectors) sum += vector_part(layout, parts.drawing, k, coriolis);
    if (chain.group) {
      // A planar loop's two rows are the x and y of its vector sum (loops/planar_system).
      const std::vector<std::size_t>& rows = model.system.groups[*chain.group].equations;
      parts.equations[Eigen::Index(rows[0])] += sum.real();
      parts.equations[Eigen::Index(rows[1])] += sum.imag();
    } else if (chain.point) {
      parts.points[*chain.point] = sum;
    }
  }
  return parts;
}

// A point's acceleration as the sum of its written vectors' parts, its Coriolis parts
// counted `factor` times.
std::complex<double> point_acceleration(const Model& model, const std::vector<double>& drawing,
                                        const PlanarLinkVectors::Chain& chain, double factor) {
  const TapeLayout& layout = model.kinematics.layout();
  std::complex<double> a = 0;
  for (std::size_t k : chain.vectors) {
    a += vector_part(layout, drawing, k, normal) + vector_part(layout, drawing, k, tangential) +
         factor * vector_part(layout, drawing, k, coriolis) + vector_part(layout, drawing, k, relative);
  }
  return a;
}

// The state with every Coriolis term counted `factor` times (0: omitted, 2: doubled). The
// acceleration equations are Phi_q qdd + (terms without qdd, the Coriolis sum C among them)
// = 0, so counting C f times moves qdd by Phi_q^-1 (1 - f) C; each point's acceleration is
// then its written vectors' parts with its own Coriolis parts counted f times.
std::optional<MotionState> coriolis_counted(const Model& model, const MotionState& state, double factor) {
  const std::optional<CoriolisParts> parts = coriolis_parts(model, state);
  if (!parts) return std::nullopt;
  Workspace workspace(model);
  Eigen::VectorXd phi, phi_theta;
  Eigen::MatrixXd phi_q;
  workspace.position_system(state.input, state.q, phi, phi_q, phi_theta);
  MotionState mistaken = state;
  mistaken.qdd += phi_q.fullPivLu().solve((1.0 - factor) * parts->equations);
  const std::vector<double> drawing = model.kinematics.drawing_values(mistaken);
  if (drawing.empty()) return std::nullopt;
  for (auto& point : mistaken.points) point.acceleration = {kNaN, kNaN, kNaN};  // a point without vectors: no value
  for (const PlanarLinkVectors::Chain& chain : model.derivation.link_vectors.chains) {
    if (!chain.point) continue;
    const std::complex<double> a = point_acceleration(model, drawing, chain, factor);
    mistaken.points[*chain.point].acceleration = {a.real(), a.imag(), 0.0};
  }
  return mistaken;
}

std::vector<MistakenRow> coriolis_row(const EvaluationPoint& point, const SolvedRow& correct, double factor) {
  const std::optional<MotionState> state = coriolis_counted(*point.model, correct.state, factor);
  if (!state) return {};
  return {{"", row_of(*point.model, *state)}};
}

// --- the Coriolis term of a slider on a turning link left out, or counted twice.
std::vector<MistakenRow> coriolis_omitted(const EvaluationPoint& point, const SolvedRow& correct) {
  return coriolis_row(point, correct, 0.0);
}

std::vector<MistakenRow> coriolis_doubled(const EvaluationPoint& point, const SolvedRow& correct) {
  return coriolis_row(point, correct, 2.0);
}

// --- a relative velocity given for the absolute one: a point's velocity relative to each
// other point (v_P - v_Q), and a slider's velocity along its guide (its v_rel).
std::vector<MistakenRow> relative_for_absolute(const EvaluationPoint& point, const SolvedRow& correct) {
  const ConstraintSystem& system = point.model->system;
  const std::map<std::string, std::size_t> index = column_index(system);
  const ResultRow& v = correct.values;
  const auto column = [&](const std::string& name) {
    const auto found = index.find(name);
    return found == index.end() ? std::optional<std::size_t>() : found->second;
  };
  std::vector<MistakenRow> rows;
  for (const PointObservable& q : system.points) {  // every point's velocity relative to q
    MistakenRow row = blank_row(correct, "relative to " + q.name);
    for (const PointObservable& p : system.points) {
      if (&p == &q) continue;
      double squares = 0;
      for (const std::string& c : p.components) {
        const std::size_t pc = *column(p.name + "_v" + c), qc = *column(q.name + "_v" + c);
        row.values[pc] = v[pc] - v[qc];
        squares += row.values[pc] * row.values[pc];
      }
      row.values[*column(p.name + "_speed")] = std::sqrt(squares);
    }
    rows.push_back(std::move(row));
  }
  MistakenRow sliding = blank_row(correct, "the slider's velocity along its guide");
  for (const GuidePoint& g : guide_points(system)) {  // a slider on a moving guide: its v_rel
    const std::string& s = system.plan->joints[system.plan->sliders[g.slider].joint].name;
    const std::string& p = system.points[g.point].name;
    const std::size_t x = *column(p + "_vx"), y = *column(p + "_vy");
    sliding.values[x] = v[*column(s + "_vrel_x")];
    sliding.values[y] = v[*column(s + "_vrel_y")];
    sliding.values[*column(p + "_speed")] = std::hypot(sliding.values[x], sliding.values[y]);
  }
  rows.push_back(std::move(sliding));
  return rows;
}

// --- another link's rate: each angular rate (rad/s) given as each other one, and each
// angular second rate (rad/s^2) as each other one.
std::vector<MistakenRow> another_link_rate(const EvaluationPoint& point, const SolvedRow& correct) {
  const ConstraintSystem& system = point.model->system;
  const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system));
  std::vector<MistakenRow> rows;
  for (std::size_t other = 0; other < columns.size(); ++other) {
    if (!in_radians(columns[other].unit)) continue;
    MistakenRow row = blank_row(correct, columns[other].name + "'s value");
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (c != other && columns[c].unit == columns[other].unit) row.values[c] = correct.values[other];
    rows.push_back(std::move(row));
  }
  return rows;
}

// --- a length in mm taken as m (a thousand times too large) or in m as mm (too small):
// the mechanism solved with each length parameter the file writes so scaled.
std::vector<MistakenRow> length_unit_slip(const EvaluationPoint& point, const SolvedRow&) {
  const Model& model = *point.model;
  const OutputScale scale(model.system);
  std::vector<MistakenRow> rows;
  for (const SystemParameter& p : model.system.parameters) {
    if (p.dimension != Dimension::length || !p.written || p.formula) continue;
    const std::string name = p.symbol.get_name();
    const std::string value = format_significant(p.value / scale.length, 6) + " " + scale.length_unit;
    for (const auto& [factor, words] : {std::pair{1000.0, " a thousand times too large (mm taken as m)"},
                                        std::pair{0.001, " a thousand times too small (m taken as mm)"}}) {
      try {
        const Model scaled = with_parameters(model, {{name, p.value * factor}});
        EvaluationPoint mistaken = point;
        mistaken.model = &scaled;
        if (const std::optional<SolvedRow> solved = try_solve(mistaken))
          rows.push_back({name + " (" + value + ")" + words, solved->values});
      } catch (const Error&) {  // a parameter with_parameters cannot set: that slip is not evaluated
      }
    }
  }
  return rows;
}

}  // namespace

SolvedRow solve_row(const EvaluationPoint& point) {
  const Model& model = *point.model;
  MotionOptions options;
  options.rate = point.rate;
  options.second_rate = point.second_rate;
  const MotionTable table = solve_motion(model, {point.at}, options);
  const MotionState state = table[0];
  if (state.status == Status::singular) throw SingularPositionError(describe_failure(model.system, state));
  if (state.status != Status::ok) throw AssemblyError(describe_failure(model.system, state));
  return {state, columns_of(model, table)};
}

ResultRow row_of(const Model& model, const MotionState& state) {
  const ConstraintSystem& system = model.system;
  MotionTable table({state.input}, system.unknowns.size(), point_dimensions(system), state.input_rate,
                    state.input_second_rate, system.frames.size());
  table.set(0, state);
  return columns_of(model, table);
}

const std::vector<Mistake>& mistake_catalogue() {
  static const std::vector<Mistake> catalogue = {
      {"sign_reversed", "sign or sense reversed", sign_reversed},
      {"degrees_for_radians", "degrees given for radians", degrees_for_radians},
      {"radians_for_degrees", "radians given for degrees", radians_for_degrees},
      {"rpm_as_rad_per_s", "the driver's rate in rpm used as rad/s", rpm_as_rad_per_s},
      {"other_assembly", "the other assembly (branch) of the mechanism", other_assembly},
      {"coriolis_omitted", "the Coriolis term 2 omega x v_rel left out", coriolis_omitted},
      {"coriolis_doubled", "the Coriolis term 2 omega x v_rel counted twice", coriolis_doubled},
      {"relative_for_absolute", "a relative velocity given for the absolute velocity", relative_for_absolute},
      {"another_link_rate", "the rate of another link", another_link_rate},
      {"length_mm_as_m", "a length in mm taken as m (or in m as mm)", length_unit_slip},
  };
  return catalogue;
}

}  // namespace kinema
