// `kinema codegen`: the compiled evaluator as a standalone C++ header (the
// standard library only), for controllers, simulations and microcontrollers.
//
// The header's numeric rules are the engine's own code: solver_source.inc is
// engine/numeric/solver.hpp's text (made at build time, see CMakeLists.txt), and
// the body of its `namespace kinema::solver` is pasted into the header as
// `namespace NAME::solver`. The Newton loop and the singularity test written
// here call that code the way Workspace (engine/numeric/workspace.cpp) does:
// same constants, same column scaling, same LU, same reciprocal condition.
#include "engine/printers/code/cpp_header.hpp"

#include "engine/printers/code/tape_emitter.hpp"
#include "engine/printers/printer.hpp"
#include "engine/base/user_text.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace kinema {
namespace {

/// engine/numeric/solver.hpp, as it was when kinema was built.
constexpr std::string_view kSolverSource =
#include "solver_source.inc"
    ;

struct SolverText {
  std::string includes;  ///< Its #include lines.
  std::string body;      ///< What lies between `namespace kinema::solver {` and its closing line.
};

SolverText solver_text() {
  constexpr std::string_view open = "\nnamespace kinema::solver {\n", close = "\n}  // namespace kinema::solver";
  const std::size_t begin = kSolverSource.find(open), end = kSolverSource.rfind(close);
  if (begin == std::string_view::npos || end == std::string_view::npos || end < begin + open.size()) {
    throw std::logic_error("engine/numeric/solver.hpp: no `namespace kinema::solver { ... }` to paste");
  }
  SolverText text;
  text.body = std::string(kSolverSource.substr(begin + open.size(), end + 1 - (begin + open.size())));
  std::istringstream lines{std::string(kSolverSource.substr(0, begin))};
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("#include <", 0) == 0) text.includes += line + "\n";
  return text;
}

std::string literal(double value) { return cpp_double_literal(value); }

}  // namespace

bool is_cpp_reserved(const std::string& name) {
  // C++ keywords and alternative tokens; the namespaces the standard keeps; and every
  // macro a program may have defined before the header (c_library_macros.inc).
  static const std::set<std::string> reserved = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
      "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
      "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
      "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
      "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
      "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
      "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq",
      "std", "posix", "linux", "unix", "i386",
#include "engine/printers/code/c_library_macros.inc"
  };
  if (reserved.count(name) > 0) return true;
  // Families of upper-case macros that other C libraries and headers add to (a header of
  // another platform may define more of them than glibc's): M_PI, FP_NAN, DBL_MAX, INT_MAX,
  // SIGINT, SEEK_SET, LC_ALL. A reserved name with "_" appended is taken as free (M_PI_).
  const bool upper = std::all_of(name.begin(), name.end(), [](char c) {
    return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
  });
  if (!upper) return false;
  for (const char* prefix : {"M_", "FP_", "FE_", "MATH_", "DBL_", "FLT_", "LDBL_", "DECIMAL_DIG", "INT", "UINT", "CHAR_",
                             "SCHAR_", "UCHAR_", "SHRT_", "USHRT_", "LONG_", "ULONG_", "LLONG_", "ULLONG_", "SIZE_",
                             "PTRDIFF_", "WCHAR_", "WINT_", "SIG_ATOMIC_", "SIG", "SEEK_", "LC_"})
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

std::string cpp_identifier(const std::string& text) {
  // Each run of other characters (a UTF-8 letter's bytes, "-", "__") becomes one "_":
  // a "__" anywhere, or "_" first, is the implementation's ("été" -> "mechanism_t_").
  std::string id;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      id += c;
    else if (id.empty() || id.back() != '_')
      id += '_';
  }
  if (id.empty() || id[0] == '_') {
    id = "mechanism" + id;
  } else if (std::isdigit(static_cast<unsigned char>(id[0]))) {
    id = "mechanism_" + id;
  }
  if (is_cpp_reserved(id)) id += "_";
  return id;
}

std::vector<std::string> cpp_identifiers(const std::vector<std::string>& names, const std::set<std::string>& taken) {
  std::set<std::string> used = taken;
  std::vector<std::string> ids;
  for (const std::string& name : names) {
    const std::string base = cpp_identifier(name);
    // int and int_, a_b and a__b: one C++ name for two of the file's; the later is
    // numbered (int_2, a_b_2: never a "__").
    std::string id = base;
    for (int k = 2; !used.insert(id).second; ++k)
      id = base + (base.back() == '_' ? "" : "_") + std::to_string(k);
    ids.push_back(id);
  }
  return ids;
}

namespace {

/// What the header's text depends on, worked out once from the model.
struct HeaderShape {
  std::size_t n = 0, points = 0, frames = 0, parameters = 0, point_values = 0;
  std::size_t point_dimension = 2;  ///< The points of one system share their space.
  std::string point_components;     ///< "x, y, vx, vy, ax, ay" (planar).
  std::vector<std::string> members;  ///< The parameters' member names.
  std::vector<std::string> inputs;   ///< Tape input names, in TapeLayout's order.
};

HeaderShape header_shape(const Model& model) {
  const ConstraintSystem& m = model.system;
  const Kinematics& k = model.kinematics;
  const TapeLayout& layout = k.layout();
  HeaderShape h;
  h.n = k.unknown_count();
  h.points = k.point_count();
  h.frames = k.frame_count();
  h.parameters = m.parameters.size();
  h.point_values = layout.point_output_count();
  if (h.points) h.point_dimension = layout.point_dimensions.front();
  for (const char* prefix : {"", "v", "a"})
    for (std::size_t c = 0; c < h.point_dimension; ++c)
      h.point_components += std::string(h.point_components.empty() ? "" : ", ") + prefix + "xyz"[c];
  // A member may not be named as its struct.
  std::vector<std::string> parameter_names;
  for (const SystemParameter& p : m.parameters) parameter_names.push_back(p.symbol.get_name());
  h.members = cpp_identifiers(parameter_names, {"Parameters"});
  h.inputs.resize(layout.input_register_count());
  for (std::size_t p = 0; p < h.parameters; ++p) h.inputs[layout.parameter(p)] = "p." + h.members[p];
  h.inputs[layout.input()] = "theta";
  h.inputs[layout.rate()] = "theta_rate";
  h.inputs[layout.second_rate()] = "theta_second_rate";
  for (std::size_t i = 0; i < h.n; ++i) {
    h.inputs[layout.q(i)] = "q[" + std::to_string(i) + "]";
    h.inputs[layout.qd(i)] = "qd[" + std::to_string(i) + "]";
    h.inputs[layout.qdd(i)] = "qdd[" + std::to_string(i) + "]";
  }
  return h;
}

/// The opening comment (what the header holds and where its rules come from), the
/// includes and kinema's solver, verbatim.
void write_opening(std::ostream& out, const ConstraintSystem& m, const HeaderShape& h, const std::string& name) {
  const SolverText solver = solver_text();
  // Text from the user on one line with no control or bidirectional characters: a line
  // break would end the comment, U+202E fails -Werror=bidi-chars.
  out << "// Generated by `kinema codegen` from " << one_line(m.source_file) << ": "
      << one_line(m.title) << ".\n"
      << "// Do not edit; regenerate instead. Depends on the standard library only. All\n"
      << "// values SI (m, rad, s). Unknowns q in this order:";
  for (const Coordinate& u : m.unknowns) out << " " << u.name;
  out << ".\n// Points (" << h.point_components << " each):";
  for (const PointObservable& p : m.points) out << " " << p.name;
  if (h.frames > 0) {
    out << ".\n// Frames (wx, wy, wz, alphax, alphay, alphaz each, relative to the observer in its\n// basis):";
    for (const FrameObservable& f : m.frames) out << " " << f.name;
  }
  out << ".\n//\n"
      << "// The numeric rules are kinema's own code: namespace " << name << "::solver below is\n"
      << "// kinema's engine/numeric/solver.hpp (its constants, LU, Newton, singular values\n"
      << "// and reciprocal condition), and solve_position and evaluate use it as the engine\n"
      << "// does, on Phi_q with the same column scaling: the header and `kinema eval` call\n"
      << "// the same positions singular.\n"
      << "#pragma once\n\n"
      << solver.includes << "\nnamespace " << name << " {\n\n"
      << "/// kinema's engine/numeric/solver.hpp (namespace kinema::solver there), verbatim.\n"
      << "namespace solver {\n"
      << solver.body << "}  // namespace solver\n\n"
      ;
}

/// Sizes, scales, the Parameters struct, the starting guesses and Status.
void write_constants(std::ostream& out, const Model& model, const HeaderShape& h) {
  const ConstraintSystem& m = model.system;
  const Kinematics& k = model.kinematics;
  const std::size_t n = h.n, points = h.points, frames = h.frames, parameters = h.parameters;
  const std::vector<std::string>& members = h.members;
  out << "constexpr int unknown_count = " << n << ";\n"
      << "constexpr int point_count = " << points << ";\n"
      << "constexpr int frame_count = " << frames << ";\n"
      << "/// Typical length of the mechanism (m): Newton's tolerances are relative to it.\n"
      << "constexpr double length_scale = " << literal(k.length_scale()) << ";\n"
      << "/// Scale of each column of Phi_q (length_scale for a length unknown, 1 for an\n"
      << "/// angle): the LU and the singularity test see Phi_q with its columns so scaled.\n"
      << "constexpr double column_scale[" << n << "] = {";
  for (std::size_t i = 0; i < n; ++i) out << (i ? ", " : "") << literal(k.column_scale()[i]);
  out << "};\n\n"
      << "/// The mechanism's parameters (SI); change them for design studies.\n"
      << "struct Parameters {\n";
  for (std::size_t i = 0; i < parameters; ++i) {
    out << "  double " << members[i] << " = " << literal(k.parameter_values()[i]) << ";  // "
        << one_line(m.parameters[i].text) << "\n";
  }
  if (parameters == 0) out << "  int unused = 0;\n";
  out << "};\n\n"
      << "/// Starting guesses from the mechanism file: they pick the assembly branch.\n"
      << "inline void initial_guess(double q[" << n << "]) {\n";
  for (std::size_t i = 0; i < n; ++i) out << "  q[" << i << "] = " << literal(m.unknowns[i].guess) << ";\n";
  out << "}\n\n"
      << "/// What evaluate found at an input value.\n"
      << "enum class Status {\n"
      << "  ok,          ///< Position, rates, second rates and points.\n"
      << "  singular,    ///< Position solved, Phi_q singular (toggle, dead centre): rates undefined.\n"
      << "  unassembled  ///< The loops cannot be closed there (from this q): no position.\n"
      << "};\n\n"
      ;
}

/// The model's three tape stages as functions (detail::position_system,
/// acceleration_rhs, point_motion) and the sizes of their outputs.
void write_tape_functions(std::ostream& out, const Model& model, const HeaderShape& h) {
  const TapeLayout& layout = model.kinematics.layout();
  const CompiledExpressions& tape = model.kinematics.evaluator();
  const std::vector<std::string>& inputs = h.inputs;
  const std::size_t n = h.n, frames = h.frames, point_values = h.point_values;
  const std::string& point_components = h.point_components;
  auto targets = [](const std::string& array, std::size_t count) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < count; ++i) names.push_back(array + "[" + std::to_string(i) + "]");
    return names;
  };
  auto unused_guard = [&](const std::string& indent) {
    out << indent << "(void)p; (void)theta; (void)theta_rate; (void)theta_second_rate;\n"
        << indent << "(void)q; (void)qd; (void)qdd;\n";
  };
  out << "namespace detail {\n\n"
      << "// Phi (n), Phi_q (n*n, column-major) and Phi_theta (n) at (theta, q).\n"
      << "inline void position_system(const Parameters& p, double theta, const double* q, double* out) {\n"
      << "  const double theta_rate = 0, theta_second_rate = 0;\n  const double* qd = nullptr;\n"
      << "  const double* qdd = nullptr;\n";
  unused_guard("  ");
  write_tape_stage_cpp(out, tape, inputs, TapeLayout::kPositionStage, targets("out", layout.position_output_count()), "  ");
  out << "}\n\n"
      << "// gamma (n): Phi_q * qdd = gamma.\n"
      << "inline void acceleration_rhs(const Parameters& p, double theta, double theta_rate,\n"
      << "                             double theta_second_rate, const double* q, const double* qd,\n"
      << "                             double* out) {\n  const double* qdd = nullptr;\n";
  unused_guard("  ");
  write_tape_stage_cpp(out, tape, inputs, TapeLayout::kAccelerationStage, targets("out", n), "  ");
  out << "}\n\n"
      << "// " << point_components << " of each point, then wx, wy, wz, alphax, alphay, alphaz of\n"
      << "// each frame.\n"
      << "inline void point_motion(const Parameters& p, double theta, double theta_rate,\n"
      << "                         double theta_second_rate, const double* q, const double* qd,\n"
      << "                         const double* qdd, double* out) {\n";
  unused_guard("  ");
  write_tape_stage_cpp(out, tape, inputs, TapeLayout::kPointStage, targets("out", layout.observable_output_count()),
                       "  ");
  out << "}\n\n"
      << "constexpr std::size_t n = " << n << ";\n"
      << "constexpr std::size_t system_size = n + n * n + n;  ///< position_system's output.\n"
      << "constexpr std::size_t point_values = " << point_values << ";  ///< point_motion's output: points,\n"
      << "constexpr std::size_t frame_values = " << 6 * frames << ";  ///< then frames.\n";
}

/// solve_position: the pasted solver's Newton on the header's position_system, as the
/// Workspace runs it on the tape: the same text for every mechanism.
void write_newton(std::ostream& out) {
  out << R"(
/// The storage of one LU of the scaled Phi_q (solver::Factorisation points into it).
struct Factors {
  double lu[n * n], inverse_pivots[n];
  std::size_t pivots[n];
  solver::Factorisation view() { return {lu, pivots, inverse_pivots}; }
};

/// solver::newton's view of position_system at one input: a trial is evaluated beside
/// q's system and copied in when it is taken.
class Stage {
 public:
  Stage(const Parameters& p, double theta, const double* q) : p_(p), theta_(theta) {
    position_system(p_, theta_, q, system_);
  }
  double residual() const { return solver::max_magnitude(system_, n); }
  void step(double* step) {
    solver::newton_step(system_, column_scale, length_scale, factors_.view(), a_, v_, b_, step, n);
  }
  double try_at(const double* trial) {
    position_system(p_, theta_, trial, trial_);
    return solver::max_magnitude(trial_, n);
  }
  void accept() {
    for (std::size_t i = 0; i < system_size; ++i) system_[i] = trial_[i];
  }

 private:
  const Parameters& p_;
  double theta_;
  double system_[system_size], trial_[system_size];
  Factors factors_;
  double a_[n * n], v_[n * n], b_[n];
};

}  // namespace detail

/// Damped Newton-Raphson (solver::newton) from q (the previous solution or
/// initial_guess) at input theta; q is updated in place. Stays on q's assembly branch
/// for small steps of theta. False when the loops cannot be closed there.
inline bool solve_position(const Parameters& p, double theta, double q[unknown_count]) {
  using detail::n;
  detail::Stage stage(p, theta, q);
  double step[n], trial[n];
  return solver::newton(stage, q, step, trial, n, length_scale);
}

/// Everything at one input value.
struct Motion {
  double q[unknown_count], qd[unknown_count], qdd[unknown_count];
)";
}

/// Motion (one input value's results) and evaluate().
void write_evaluate(std::ostream& out, const HeaderShape& h, const std::string& name) {
  const std::size_t points = h.points, frames = h.frames;
  const std::string& point_components = h.point_components;
  const std::size_t point_dimension = h.point_dimension;
  out << "  double points[" << (points ? points : 1) << "][" << 3 * point_dimension << "];  ///< "
      << point_components << "\n";
  out << "  double frames[" << (frames ? frames : 1) << "][6];  ///< wx, wy, wz, alphax, alphay, alphaz\n";
  out << R"(  /// Of Phi_q with its columns scaled; below solver::kSingularThreshold: singular.
  double reciprocal_condition;
};

/// Position (Newton from q, updated), then velocity and acceleration from one LU of
/// Phi_q, and the points. Status::ok: all of motion is set. Status::singular: the
/// position (motion.q) and motion.reciprocal_condition are set, the rest is NaN.
/// Status::unassembled: all of motion is NaN.
inline Status evaluate(const Parameters& p, double theta, double theta_rate, double theta_second_rate,
                       double q[unknown_count], Motion& motion) {
  using detail::n;
  for (std::size_t i = 0; i < n; ++i) motion.q[i] = motion.qd[i] = motion.qdd[i] = NAN;
  for (auto& point : motion.points)
    for (double& value : point) value = NAN;
  for (auto& frame : motion.frames)
    for (double& value : frame) value = NAN;
  motion.reciprocal_condition = NAN;
  if (!solve_position(p, theta, q)) return Status::unassembled;
  for (std::size_t i = 0; i < n; ++i) motion.q[i] = q[i];
  double system[detail::system_size];
  detail::position_system(p, theta, q, system);
  // One factorisation of Phi_q: the singularity test, then velocity and acceleration.
  detail::Factors f;
  solver::factorise(system, column_scale, f.view(), n);
  double scaled[n * n];
  motion.reciprocal_condition = solver::reciprocal_condition(f.lu, n, length_scale, [&] {
    solver::scaled_phi_q(system, column_scale, scaled, n);
    return &scaled[0];
  });
  if (motion.reciprocal_condition < solver::kSingularThreshold) return Status::singular;
  for (std::size_t i = 0; i < n; ++i) motion.qd[i] = -system[n + n * n + i] * theta_rate;
  solver::solve(f.view(), column_scale, motion.qd, n);
  detail::acceleration_rhs(p, theta, theta_rate, theta_second_rate, q, motion.qd, motion.qdd);
  solver::solve(f.view(), column_scale, motion.qdd, n);
)";
  if (points > 0 && frames == 0) {
    out << "  detail::point_motion(p, theta, theta_rate, theta_second_rate, q, motion.qd, motion.qdd,\n"
        << "                       &motion.points[0][0]);\n";
  } else if (frames > 0) {  // one output, points then frames
    out << "  double observed[detail::point_values + detail::frame_values];\n"
        << "  detail::point_motion(p, theta, theta_rate, theta_second_rate, q, motion.qd, motion.qdd, observed);\n";
    if (points > 0)
      out << "  for (std::size_t k = 0; k < detail::point_values; ++k) (&motion.points[0][0])[k] = observed[k];\n";
    out << "  for (std::size_t k = 0; k < detail::frame_values; ++k)\n"
        << "    (&motion.frames[0][0])[k] = observed[detail::point_values + k];\n";
  }
  out << R"(  // Rates that overflow are a singular position all the same.
  if (!solver::all_finite(motion.qd, n) || !solver::all_finite(motion.qdd, n) ||
      !solver::all_finite(&motion.points[0][0], detail::point_values) ||
      !solver::all_finite(&motion.frames[0][0], detail::frame_values)) {
    for (std::size_t i = 0; i < n; ++i) motion.qd[i] = motion.qdd[i] = NAN;
    for (auto& point : motion.points)
      for (double& value : point) value = NAN;
    for (auto& frame : motion.frames)
      for (double& value : frame) value = NAN;
    return Status::singular;
  }
  return Status::ok;
}

}  // namespace )" << name << "\n";
}

}  // namespace

void write_cpp_header(std::ostream& out, const Model& model, const std::string& name) {
  const HeaderShape shape = header_shape(model);
  write_opening(out, model.system, shape, name);
  write_constants(out, model, shape);
  write_tape_functions(out, model, shape);
  write_newton(out);
  write_evaluate(out, shape, name);
}

}  // namespace kinema

namespace kinema {
namespace {

class CppHeaderPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::code; }
  const char* name() const override { return "cpp"; }
  void print(std::ostream& out, const PrintJob& job) const override {
    write_cpp_header(out, job.model, job.code_namespace);
  }
};

}  // namespace

const Printer& cpp_header_printer() {
  static const CppHeaderPrinter printer;
  return printer;
}

}  // namespace kinema
