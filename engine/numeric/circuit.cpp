#include "engine/numeric/circuit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/numeric/closed_form.hpp"
#include "engine/numeric/workspace.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

std::uint64_t assembly_bits(const std::vector<int>& signs) {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < signs.size() && k < 64; ++k)
    if (signs[k] < 0) bits |= std::uint64_t{1} << k;
  return bits;
}

std::vector<int> assembly_signs(std::uint64_t bits, std::size_t dyads) {
  std::vector<int> signs(dyads);
  for (std::size_t k = 0; k < dyads; ++k) signs[k] = ((bits >> k) & 1u) != 0 ? -1 : 1;
  return signs;
}

struct CircuitRow {
  CircuitRow(double x, int d, const std::vector<int>& signs, bool at_toggle = false, std::uint32_t toggle_dyad = 0)
      : input(x), assembly(assembly_bits(signs)), dyad(toggle_dyad), direction(static_cast<signed char>(d)),
        toggle(at_toggle) {}
  double input;
  std::uint64_t assembly;
  std::uint32_t dyad;  ///< toggle: the dyad at its toggle.
  signed char direction;
  bool toggle;
};

// Where the rows go: along the grid in the input's direction until a dyad cannot close;
// there the toggle, found by bisection, then back on the grid with that dyad's sign
// changed. Between rows the mechanism is followed in substeps of at most
// Kinematics::max_continuation_step (2 deg, or 1 % of the length scale), whatever the
// grid's step: a coarse step would jump over the range where a dyad cannot close, and
// would take a far position's signs from a straight-line guess. At each substep the signs
// are those nearest the position extrapolated along the path (so a change point, where
// two assemblies cross, is passed as in a sweep).
Circuit::Stop walk(const Kinematics& kinematics, const CircuitSettings& settings, std::vector<CircuitRow>& rows,
                   std::uint32_t& stuck_dyad) {
  const SolvingPlan& frames = *kinematics.closed_form();
  const double scale = kinematics.length_scale(), substep = kinematics.max_continuation_step();
  const bool angle_input = frames.driver_slider < 0;
  std::vector<BodyPose> poses;
  std::size_t failing = 0;
  const auto closes = [&](double x, const std::vector<int>& signs) {
    failing = place_dyads(frames, x, poses, &signs);
    return failing == frames.dyads.size();
  };
  std::vector<int> signs;
  for (const SolvingPlan::Dyad& d : frames.dyads) signs.push_back(d.sign);
  const std::vector<int> start_signs = signs;
  const double start = settings.start, step = settings.step;
  if (!closes(start, signs)) {
    stuck_dyad = static_cast<std::uint32_t>(failing);
    return Circuit::Stop::start_open;
  }
  int direction = settings.rate < 0 ? -1 : 1;
  const int start_direction = direction;
  Eigen::VectorXd q = kinematics.guess(), previous_q;
  std::uint32_t unused = 0;
  closed_form_position(frames, start, signs, q, unused);
  rows.push_back({start, direction, signs});
  // The path so far: the last position reached (a row or a substep) and the one before.
  double here = start, previous_x = start;
  bool have_previous = false, at_toggle = false;
  // Substeps are bounded too: a slider's range can be long next to its substep.
  std::size_t substeps_left = settings.max_rows * 64;
  long grid = 0;  // the grid index the next row steps from
  for (;;) {
    if (rows.size() >= settings.max_rows) return Circuit::Stop::too_many_rows;
    const long next = grid + direction;
    double target = start + static_cast<double>(next) * step;
    bool last = false;
    if (angle_input && std::fabs(target - start) >= 2 * kPi) {  // a whole turn without a toggle
      target = start + direction * 2 * kPi;
      last = true;
    }
    // To the target in equal substeps, each on the signs continuity gives.
    const double span = std::fabs(target - here);
    const double count = std::ceil(span / substep);
    if (!(count <= static_cast<double>(substeps_left))) return Circuit::Stop::too_many_rows;
    const long substeps = std::max(1L, static_cast<long>(count));
    substeps_left -= static_cast<std::size_t>(substeps);
    const double from = here;
    double failed_at = target;  // the substep where a dyad could not close
    bool reached = true;
    for (long k = 1; k <= substeps; ++k) {
      const double x = k == substeps ? target : from + (target - from) * (static_cast<double>(k) / substeps);
      std::vector<int> trial = signs;
      if (have_previous && !at_toggle) {
        // A straight line through two positions a hair apart (a row next to a toggle)
        // says nothing a whole substep on: the signs stay as they are then.
        const double covered = std::fabs(here - previous_x);
        if (covered > 0 && 4 * covered >= std::fabs(x - here)) {
          const Eigen::VectorXd predicted = q + (q - previous_q) * (std::fabs(x - here) / covered);
          trial = signs_nearest(frames, x, predicted.data(), scale, &signs);
          if (!closes(x, trial)) trial = signs;
        }
      }
      if (!closes(x, trial)) {
        reached = false;
        failed_at = x;
        break;
      }
      signs = trial;
      previous_q = q;
      previous_x = here;
      have_previous = true;
      closed_form_position(frames, x, signs, q, unused);
      here = x;
      at_toggle = false;
    }
    if (reached) {
      rows.push_back({target, direction, signs});
      grid = next;
      if (last || (rows.size() > 2 && next == 0 && direction == start_direction && signs == start_signs))
        return Circuit::Stop::closed;
      continue;
    }
    // A toggle between the position reached and the next substep: the last value where
    // the dyads still close.
    double a = here, b = failed_at;
    std::size_t toggle_dyad = failing;
    for (int i = 0; i < 200 && a != b; ++i) {
      const double middle = 0.5 * (a + b);
      if (middle == a || middle == b) break;
      if (closes(middle, signs)) a = middle;
      else {
        b = middle;
        toggle_dyad = failing;
      }
    }
    if (at_toggle && std::fabs(a - here) <= 1e-12 * (std::fabs(a) + step)) {
      stuck_dyad = static_cast<std::uint32_t>(toggle_dyad);
      return Circuit::Stop::locked;
    }
    previous_q = q;
    previous_x = here;
    closed_form_position(frames, a, signs, q, unused);
    here = a;
    rows.push_back({a, direction, signs, true, static_cast<std::uint32_t>(toggle_dyad)});
    signs[toggle_dyad] = -signs[toggle_dyad];
    direction = -direction;
    rows.back().direction = direction;  // the toggle row moves on the way out of it
    at_toggle = true;
    // The grid value next to the toggle in the new direction.
    const double r = (a - start) / step;
    // A start at a toggle: the circuit closes there, on the way out as it began.
    if (rows.size() > 2 && std::fabs(r) <= 1e-9 && direction == start_direction && signs == start_signs)
      return Circuit::Stop::closed;
    grid = direction > 0 ? static_cast<long>(std::floor(r + 1e-9)) : static_cast<long>(std::ceil(r - 1e-9));
  }
}

}  // namespace

Circuit solve_circuit(const Kinematics& kinematics, const CircuitSettings& settings) {
  if (!(settings.step > 0) || !std::isfinite(settings.step)) {
    throw InputError("the circuit's step must be a positive number");
  }
  if (kinematics.closed_form() == nullptr) {  // e.g. a joints file's copy by with_parameters
    throw InputError("a circuit is walked dyad by dyad: it needs a model whose links are solved in closed form");
  }
  Circuit circuit;
  std::vector<CircuitRow> rows;
  circuit.stop = walk(kinematics, settings, rows, circuit.dyad);
  if (circuit.stop != Circuit::Stop::closed) return circuit;
  std::vector<double> inputs;
  for (const CircuitRow& row : rows) inputs.push_back(row.input);
  MotionTable& table = circuit.table;
  table = MotionTable(inputs, kinematics.unknown_count(), kinematics.layout().point_dimensions, settings.rate,
                      settings.second_rate, kinematics.frame_count());
  table.make_circuit();
  const SolvingPlan& frames = *kinematics.closed_form();
  Workspace workspace(kinematics);
  Eigen::VectorXd q = kinematics.guess();
  MotionState state;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const CircuitRow& row = rows[r];
    std::uint32_t dyad = 0;
    closed_form_position(frames, row.input, assembly_signs(row.assembly, frames.dyads.size()), q, dyad);
    Eigen::VectorXd polished = q;
    // Newton only polishes the closed form; at a toggle (Phi_q singular) the closed form stands.
    if (workspace.solve_position(row.input, polished) && (polished - q).norm() < 1e-6 * (1 + q.norm())) q = polished;
    workspace.motion_into(row.input, row.direction * settings.rate, row.direction * settings.second_rate, q, state);
    if (row.toggle) {
      ++circuit.toggles;
      state.status = Status::singular;
      state.failure = Failure{};
      state.failure.kind = Failure::Kind::circuit_toggle;
      state.failure.group = row.dyad;
      state.qd.resize(0);
      state.qdd.resize(0);
      state.points.clear();
    }
    table.set(r, state);
    table.set_circuit_row(r, row.direction, row.assembly);
  }
  return circuit;
}

}  // namespace kinema
