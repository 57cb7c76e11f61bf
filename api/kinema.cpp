// The library facade (<kinema/kinema.hpp>) over the engine. It sits above the engine as
// the command line does (cli/), in a folder of its own so that api/kinema/ is exactly
// what is installed and what a program's include path holds. It computes nothing: the
// engine loads (load_model), solves (solve_motion) and words the failures (describe_failure);
// here its results are copied out under their names.
#include <kinema/kinema.hpp>

#include <algorithm>

#include "api/engine_access.hpp"
#include "engine/base/errors.hpp"
#include "engine/input_value.hpp"
#include "engine/model.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/analysis/sensitivities.hpp"
#include "readers/mechanism_file.hpp"

namespace kinema {


namespace {

const char* si_unit(Dimension dimension) {
  switch (dimension) {
    case Dimension::angle: return "rad";
    case Dimension::length: return "m";
    default: return "s";
  }
}

Names names_of(const ConstraintSystem& system) {
  Names names;
  names.input = system.input.name;
  names.input_rate = system.input.rate.get_name();
  names.input_second_rate = system.input.second_rate.get_name();
  names.input_unit = si_unit(system.input.dimension);
  for (const Coordinate& q : system.unknowns) {
    names.unknowns.push_back(q.name);
    names.rates.push_back(q.rate.get_name());
    names.second_rates.push_back(q.second_rate.get_name());
  }
  for (const PointObservable& p : system.points) names.points.push_back(p.name);
  for (const FrameObservable& f : system.frames) names.frames.push_back(f.name);
  return names;
}

std::string list_of(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

// Where `name` is in `names`; an Error naming what there is instead when it is not.
std::size_t index_of(const std::vector<std::string>& names, const std::string& name, const std::string& source,
                     const char* what) {
  const auto found = std::find(names.begin(), names.end(), name);
  if (found != names.end()) return std::size_t(found - names.begin());
  throw Error(source + ": no " + what + " named \"" + name + "\" (there are: " + list_of(names) + ")");
}

SolutionStatus status_of(Status status) {
  switch (status) {
    case Status::ok: return SolutionStatus::ok;
    case Status::singular: return SolutionStatus::singular;
    default: return SolutionStatus::unassembled;
  }
}

PointResult point_result(const PointMotion& motion) {
  return {motion.dimension, motion.position, motion.velocity, motion.acceleration};
}

}  // namespace

MechanismModel::MechanismModel(const std::string& path)
    // The facade prints no formulas: the evaluation scope derives what solving needs.
    : MechanismModel(std::make_shared<const Engine>(Engine{std::make_shared<const Model>(load_model(path, DerivationScope::evaluation))})) {}

MechanismModel MechanismModel::from_toml(const std::string& text, const std::string& name) {
  return MechanismModel(
      std::make_shared<const Engine>(Engine{std::make_shared<const Model>(make_model(read_mechanism_text(text, name), DerivationScope::evaluation))}));
}

MechanismModel::MechanismModel(std::shared_ptr<const Engine> engine)
    : engine_(std::move(engine)), names_(std::make_shared<const Names>(names_of(engine_->model->system))) {}

MechanismModel::MechanismModel(std::shared_ptr<const Engine> engine, std::shared_ptr<const Names> names)
    : engine_(std::move(engine)), names_(std::move(names)) {}

MechanismModel MechanismModel::with_parameters(const std::vector<std::pair<std::string, std::string>>& values) const {
  const Model& model = *engine_->model;
  std::vector<std::pair<std::string, double>> si;
  for (const auto& [name, text] : values) si.emplace_back(name, parse_parameter_value(model.system, name, text));
  auto copy = std::make_shared<const Model>(kinema::with_parameters(model, si));
  return MechanismModel(std::make_shared<const Engine>(Engine{std::move(copy)}), names_);  // the same names
}

std::vector<double> MechanismModel::sensitivity(const std::string& column, const std::string& parameter,
                                                const std::vector<double>& values) const {
  const Model& model = *engine_->model;
  const Sensitivities derivatives(model, sensitivity_columns(model.system, {column + ":" + parameter}));
  const MotionTable table = solve_motion(model, values);
  std::vector<double> result(table.size());
  derivatives.rows(table, 0, table.size(), result.data(), true);  // one column: one value a row
  return result;
}

MechanismModel EngineAccess::facade(std::shared_ptr<const Model> model) {
  return MechanismModel(std::make_shared<const MechanismModel::Engine>(MechanismModel::Engine{std::move(model)}));
}

const Model& EngineAccess::model(const MechanismModel& facade) { return *facade.engine_->model; }

const std::string& MechanismModel::title() const { return engine_->model->system.title; }

Solution MechanismModel::solve(const std::string& value) const { return solve(std::vector<std::string>{value}).front(); }

Solution MechanismModel::solve(double value) const { return solve(std::vector<double>{value}).front(); }

std::vector<Solution> MechanismModel::solve(const std::vector<std::string>& values) const {
  std::vector<double> si;
  for (const std::string& value : values) si.push_back(parse_input_value(engine_->model->system, value));
  return solve(si);
}

std::vector<Solution> MechanismModel::solve(const std::vector<double>& values) const {
  const ConstraintSystem& system = engine_->model->system;
  check_input_range(system, values);
  const MotionTable table = solve_motion(*engine_->model, values);
  std::vector<Solution> solutions;
  solutions.reserve(table.size());
  for (std::size_t row = 0; row < table.size(); ++row) {
    Solution& s = solutions.emplace_back(Solution());
    s.names_ = names_;
    s.source_ = system.source_file;
    s.input_ = table.input(row);
    s.input_rate_ = table.input_rate(row);
    s.input_second_rate_ = table.input_second_rate(row);
    s.status_ = status_of(table.status(row));
    if (s.status_ != SolutionStatus::ok) {
      s.message_ = system.source_file + ": " + describe_failure(system, s.input_, table.failure(row));
    }
    if (s.status_ == SolutionStatus::unassembled) continue;
    for (std::size_t i = 0; i < table.unknown_count(); ++i) s.values_.push_back(table.q_column(i)[row]);
    if (s.status_ != SolutionStatus::ok) continue;
    for (std::size_t i = 0; i < table.unknown_count(); ++i) {
      s.rates_.push_back(table.qd_column(i)[row]);
      s.second_rates_.push_back(table.qdd_column(i)[row]);
    }
    for (std::size_t p = 0; p < table.point_count(); ++p) s.points_.push_back(point_result(table.point(row, p)));
    for (std::size_t f = 0; f < table.frame_count(); ++f) {
      const FrameMotion frame = table.frame(row, f);
      s.frames_.push_back({frame.angular_velocity, frame.angular_acceleration});
    }
  }
  return solutions;
}

namespace {

// The number of variable `name` of kind `what`: the input's own, or the unknown's at its
// place in `names`; an Error when the solution has no such numbers (`values` is empty).
double named_value(const Solution& s, const std::string& name, const std::string& input_name, double input_value,
                   const std::vector<std::string>& names, const std::vector<double>& values, const char* what,
                   const std::string& source) {
  if (name == input_name) return input_value;
  const std::size_t i = index_of(names, name, source, what);
  if (values.empty()) throw Error(name + " is not known here: " + s.message());
  return values[i];
}

}  // namespace

double Solution::value(const std::string& name) const {
  return named_value(*this, name, names_->input, input_, names_->unknowns, values_, "coordinate", source_);
}

double Solution::rate(const std::string& name) const {
  return named_value(*this, name, names_->input_rate, input_rate_, names_->rates, rates_, "rate", source_);
}

double Solution::second_rate(const std::string& name) const {
  return named_value(*this, name, names_->input_second_rate, input_second_rate_, names_->second_rates, second_rates_,
                     "second rate", source_);
}

const PointResult& Solution::point(const std::string& name) const {
  const std::size_t i = index_of(names_->points, name, source_, "point");
  if (points_.empty()) throw Error("point " + name + " is not known here: " + message_);
  return points_[i];
}

const FrameResult& Solution::frame(const std::string& name) const {
  const std::size_t i = index_of(names_->frames, name, source_, "frame");
  if (frames_.empty()) throw Error("frame " + name + " is not known here: " + message_);
  return frames_[i];
}

}  // namespace kinema
