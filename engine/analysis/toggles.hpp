// Toggle positions: where det Phi_q = 0 on the loop equations, the input at its limit
// (the mechanism folds: its rates are not defined there). Solved as one system in (q,
// theta) — Phi(q, theta) = 0 and det(Phi_q) = 0 — by Newton from positions spread over the
// input's range, each refined to machine precision, so that a toggle is where the
// equations put it, not the nearest value of a sweep.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <vector>

#include "engine/model.hpp"
#include "engine/numeric/workspace.hpp"

namespace kinema {

struct Toggle {
  double input = 0;  ///< SI (a crank's angle in [0, 2 pi)).
  Eigen::VectorXd q;
  /// A limit position: the unknown is at a maximum there (its rate goes from positive to
  /// negative as the input grows), else a minimum. False for a toggle.
  bool maximum = false;
};

/// The toggle positions of a crank-driven mechanism over a turn (none for other inputs),
/// in increasing input angle, each once.
std::vector<Toggle> find_toggles(const Model& model);

/// The limit positions of unknown `j` of a crank-driven mechanism over a turn: where its
/// rate is 0 (a slider's dead centres), solved the same way from Phi = 0 and dq_j/dtheta = 0.
std::vector<Toggle> find_limit_positions(const Model& model, std::size_t j);
/// The same for several unknowns at once (one sweep of the turn shared by all): the limit
/// positions of unknowns[w] in element w. `whole_turn`, where given, is set to whether every
/// value of the turn assembled (else the crank does not pass from each limit to the next).
std::vector<std::vector<Toggle>> find_limit_positions(const Model& model, const std::vector<std::size_t>& unknowns,
                                                      bool* whole_turn = nullptr);

/// The limit positions of unknown `unknown` in rows [0, rows) of a solved turn, given
/// g[row] = dq/dtheta of that unknown (NaN where the row has none): each sign change of g
/// between neighbouring rows refined as a root of dq/dtheta, q solved at each trial on
/// `workspace` (the model's); a row where g is 0 is one. What find_limit_positions does
/// after its sweep, for a caller that has solved the turn already (a design study).
/// `known`, where given, returns the root between two rows' inputs where it is known in
/// closed form (NaN where not: that bracket is refined as above); such a limit's q is
/// the nearer row's.
using KnownLimit = std::function<double(double from, double to)>;
std::vector<Toggle> limit_positions_in_turn(const MotionTable& turn, std::size_t rows, const double* g,
                                            std::size_t unknown, Workspace& workspace, const KnownLimit& known = {});
/// The same from the rows' inputs and a row's position as `position` gives it (rows kept
/// elsewhere than in a table: a design study's lanes).
using RowPosition = std::function<Eigen::VectorXd(std::size_t row)>;
std::vector<Toggle> limit_positions_in_turn(const double* inputs, const RowPosition& position, std::size_t rows,
                                            const double* g, std::size_t unknown, Workspace& workspace,
                                            const KnownLimit& known = {});

}  // namespace kinema
