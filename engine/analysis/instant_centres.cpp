#include "engine/analysis/instant_centres.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "engine/base/work_count.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/base/units.hpp"

namespace kinema {

namespace {

using Complex = std::complex<double>;

double cross(Complex u, Complex v) { return u.real() * v.imag() - u.imag() * v.real(); }

// The line through two centres (a point and a direction); nullopt when both are at
// infinity or they coincide (no line).
struct Line {
  Complex through, along;
};

std::optional<Line> line_through(const InstantCentre& p, const InstantCentre& q, double length_scale) {
  if (p.at_infinity && q.at_infinity) return std::nullopt;
  if (p.at_infinity) return Line{q.at, p.at};
  if (q.at_infinity) return Line{p.at, q.at};
  const Complex d = q.at - p.at;
  if (std::abs(d) <= 1e-9 * length_scale) return std::nullopt;
  return Line{p.at, d / std::abs(d)};
}

std::string centre_name(const std::vector<std::string>& bodies, std::size_t a, std::size_t b) {
  return "I" + bodies[a] + bodies[b];
}

// omega_j / omega_d = (I_dj - I_0d) / (I_dj - I_0j), from three centres on one line.
void add_ratios(InstantCentres& result, double length_scale) {
  const std::size_t n = result.bodies.size();
  const double driver_omega = result.angular_velocities[result.driver];
  const InstantCentre* ground_driver = result.find(0, result.driver);
  if (std::fabs(driver_omega) > 0 && ground_driver && !ground_driver->at_infinity) {
    for (std::size_t j = 1; j < n; ++j) {
      if (j == result.driver) continue;
      const InstantCentre *dj = result.find(result.driver, j), *ground_j = result.find(0, j);
      if (!dj || !ground_j) continue;
      if (!dj->at_infinity && !ground_j->at_infinity && std::abs(dj->at - ground_j->at) <= 1e-9 * length_scale)
        continue;
      // A centre with the driver at infinity: they turn alike; with ground: j translates.
      const double ratio = dj->at_infinity         ? 1.0
                           : ground_j->at_infinity ? 0.0
                                                   : std::real((dj->at - ground_driver->at) / (dj->at - ground_j->at));
      result.ratios.push_back({j, ratio, result.angular_velocities[j] / driver_omega});
    }
  }
}

// A body of a vector-loop file as centres_from_points finds it: its link (MechanismGeometry's
// numbering; -1 for a slider block), the rate it turns with, its name, a point on it with that
// point's velocity, and its angular velocity now.
struct PointBody {
  int link = -1;
  GiNaC::ex rate;
  std::string name;
  Complex point, velocity;
  std::size_t order = 0;  ///< The driver, then the unknowns in file order.
  double omega = 0;
  int slider_term = -1;  ///< A block: its slider's term (link vector).
};

// The driver's link first (0), then the unknowns' in file order (j + 1), then any other:
// by the coordinate whose rate a link's rate holds.
std::size_t body_order(const ConstraintSystem& system, const GiNaC::ex& rate) {
  std::size_t order = system.unknowns.size() + 1;
  for (std::size_t j = system.unknowns.size(); j-- > 0;)
    if (rate.has(system.unknowns[j].rate)) order = j + 1;
  if (rate.has(system.input.rate)) order = 0;
  return order;
}

bool has_body(const std::vector<PointBody>& bodies, int link) {
  for (const PointBody& b : bodies)
    if (b.link == link) return true;
  return false;
}

// The body of link `link` known by a point on it and that point's velocity, unless it is
// one already or its angular velocity is not known now.
void add_link_body(const MechanismGeometry& geometry, const std::vector<std::optional<double>>& omegas, int link,
                   Complex point, Complex velocity, std::vector<PointBody>& bodies) {
  if (has_body(bodies, link) || !omegas[link]) return;
  const GiNaC::ex& rate = geometry.link_rates()[link];
  bodies.push_back({link, rate, geometry.link_labels()[link], point, velocity, body_order(geometry.system(), rate),
                    *omegas[link]});
}

// A vector-loop file names no links: a point whose formula ends in a link vector of fixed
// length turning with an angle is on that link (docs/outputs.md: "points that lie on a link
// term belong to that link").
std::vector<PointBody> bodies_of_points(const MechanismGeometry& geometry, const MotionState& s,
                                        const std::vector<std::optional<double>>& omegas) {
  std::vector<PointBody> bodies;
  for (const PointOnLink& on : geometry.points_on_links(s)) {
    const PointMotion& m = s.points[on.point];
    add_link_body(geometry, omegas, on.link, on.at, {m.velocity[0], m.velocity[1]}, bodies);
  }
  return bodies;
}

// The loops' links no point ends on, known by a joint whose velocity is known (a named
// point, or a ground one), and the slider blocks (at their sliding points, turning with
// their guides): every body of the mechanism, as a course counts them. A block is added
// without a name (number_bodies names it).
void add_drawn_bodies(const MechanismGeometry& geometry, const MotionState& s, const std::vector<DrawingSegment>& segments,
                      const std::vector<std::optional<double>>& omegas, std::vector<PointBody>& bodies) {
  const double length_scale = geometry.system().length_scale;
  std::vector<std::pair<Complex, Complex>> known;  // position, velocity
  for (const PointMotion& m : s.points) known.push_back({{m.position[0], m.position[1]}, {m.velocity[0], m.velocity[1]}});
  known.push_back({0, 0});
  for (const DrawingSegment& g : segments)
    if (g.kind == DrawingSegment::Kind::ground) {
      known.push_back({g.from, 0});
      known.push_back({g.to, 0});
    }
  const auto velocity_at = [&](Complex p) -> std::optional<Complex> {
    for (const auto& [at, v] : known)
      if (std::abs(at - p) <= 1e-9 * length_scale) return v;
    return std::nullopt;
  };
  for (const DrawingSegment& g : segments) {
    if (g.kind != DrawingSegment::Kind::link || g.link < 0 || has_body(bodies, g.link)) continue;
    for (const Complex end : {g.from, g.to})
      if (const auto v = velocity_at(end)) {
        add_link_body(geometry, omegas, g.link, end, *v, bodies);
        break;
      }
  }
  // A link that is only a slider's guide (Example 4.1's crank 1), known by the term's
  // other end when that lies on the guide line.
  for (const DrawingSegment& g : segments) {
    if (g.kind != DrawingSegment::Kind::slider || g.guide_link < 0) continue;
    const Complex other = std::abs(g.block - g.to) <= 1e-9 * length_scale ? g.from : g.to;
    const auto v = velocity_at(other);
    if (!v || std::fabs(cross(other - g.block, g.along)) > 1e-9 * length_scale) continue;
    add_link_body(geometry, omegas, g.guide_link, other, *v, bodies);
  }
  for (const DrawingSegment& g : segments) {
    if (g.kind != DrawingSegment::Kind::slider || (!g.fixed_guide && g.guide_link < 0)) continue;
    const std::optional<double> w = g.fixed_guide ? std::optional<double>(0.0) : omegas[g.guide_link];
    const auto v = velocity_at(g.block);
    if (!w || !v) continue;
    bodies.push_back({-1, 0, "", g.block, *v, geometry.system().unknowns.size() + 2, *w, static_cast<int>(g.term)});
  }
}

// Names the blocks with the numbers the links leave free (Example 4.2: links 1, 3, 4,
// blocks 2, 5) and sorts the bodies by number where all are numbered, else driver first;
// returns ground's name: "1", or "0" where a link is "1".
std::string number_bodies(std::vector<PointBody>& bodies) {
  bool one_taken = false;
  for (const PointBody& b : bodies) one_taken = one_taken || b.name == "1";
  const std::string ground = one_taken ? "0" : "1";
  std::vector<std::string> used = {ground};
  for (const PointBody& b : bodies) used.push_back(b.name);
  int next = 1;
  for (PointBody& b : bodies) {
    if (!b.name.empty()) continue;
    while (std::find(used.begin(), used.end(), std::to_string(next)) != used.end()) ++next;
    b.name = std::to_string(next);
    used.push_back(b.name);
  }
  const auto number = [](const std::string& name) {
    return !name.empty() && name.find_first_not_of("0123456789") == std::string::npos ? std::stoi(name) : -1;
  };
  bool numbered = true;
  for (const PointBody& b : bodies) numbered = numbered && number(b.name) >= 0;
  std::stable_sort(bodies.begin(), bodies.end(), [&](const PointBody& a, const PointBody& b) {
    return numbered ? number(a.name) < number(b.name) : a.order < b.order;
  });
  return ground;
}

// Body b of the result (0 is ground, at rest at the origin): a point on it and its velocity.
Complex body_point(const std::vector<PointBody>& bodies, std::size_t b) {
  return b == 0 ? Complex() : bodies[b - 1].point;
}
Complex body_velocity(const std::vector<PointBody>& bodies, std::size_t b) {
  return b == 0 ? Complex() : bodies[b - 1].velocity;
}

// Ground and the bodies: names, rates, the driver (angular velocities not yet).
InstantCentres named_bodies(const ConstraintSystem& system, const std::vector<PointBody>& bodies,
                            const std::string& ground) {
  InstantCentres result;
  result.bodies.push_back(ground);
  result.rates.push_back(0);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    result.bodies.push_back(bodies[b].name);
    result.rates.push_back(bodies[b].rate);
    if (bodies[b].rate.is_equal(system.input.rate)) result.driver = b + 1;
  }
  return result;
}

// The fastest-turning body's angular velocity: two bodies' that differ by a
// kCentreParallelTolerance of it turn alike.
double fastest_turning(const InstantCentres& result) {
  double fastest = 0;
  for (double w : result.angular_velocities) fastest = std::max(fastest, std::fabs(w));
  return fastest;
}

double fastest_point(const MotionState& s) {
  double fastest = 0;
  for (const PointMotion& m : s.points) fastest = std::max(fastest, m.speed());
  return fastest;
}

std::string found_by(const InstantCentres& result, std::size_t a, std::size_t b) {
  return "velocities of the points on " + result.bodies[a] + " and " + result.bodies[b];
}

// The construction from the bodies' numbers: each pair's centre from their velocities,
// v_a(I) = v_b(I) with v(P) = v_A + i omega (P - A); where the two turn alike, at infinity
// across their relative velocity.
InstantCentres centres_of_bodies(const ConstraintSystem& system, const MotionState& s,
                                 const std::vector<PointBody>& bodies, const std::string& ground) {
  InstantCentres result = named_bodies(system, bodies, ground);
  result.angular_velocities.push_back(0);
  for (const PointBody& b : bodies) result.angular_velocities.push_back(b.omega);
  const std::size_t n = result.bodies.size();
  const double fastest = fastest_point(s), turning = fastest_turning(result);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      const double wa = result.angular_velocities[a], wb = result.angular_velocities[b];
      const Complex A = body_point(bodies, a), B = body_point(bodies, b), I(0, 1);
      const Complex va = body_velocity(bodies, a), vb = body_velocity(bodies, b);
      const std::string how = found_by(result, a, b);
      if (std::fabs(wa - wb) <= kCentreParallelTolerance * turning) {
        // Uniform where they turn alike: v_b(P) - v_a(P) = v_b(B) - v_a(A) + i omega (A - B).
        const Complex relative = vb - va + I * wa * (A - B);
        if (std::abs(relative) <= 1e-12 * fastest) {  // moving as one: no centre
          result.moving_as_one.push_back({a, b});
          continue;
        }
        result.centres.push_back({a, b, true, I * relative / std::abs(relative), how, {}, std::nullopt, {}});
        continue;
      }
      const Complex at = (vb - va + I * (wa * A - wb * B)) / (I * (wa - wb));
      result.centres.push_back({a, b, false, at, how, {}, std::nullopt, {}});
    }
  }
  return result;
}

// Each body's angular velocity and point as the drawing stage gives them (result.tape_bodies
// says which of the tape's each body is; ground, 0, is at rest at the origin).
void read_tape_bodies(InstantCentres& result, const TapeLayout& layout, const std::vector<double>& values,
                      std::vector<Complex>& points) {
  points.assign(1, 0);
  result.angular_velocities.assign(1, 0);
  for (std::size_t b = 1; b < result.tape_bodies.size(); ++b) {
    const double* body = values.data() + layout.centre_body_output(result.tape_bodies[b]);
    result.angular_velocities.push_back(body[0]);
    points.push_back({body[1], body[2]});
  }
}

// Every pair's centre as the drawing stage gives it: N / (i D), at infinity across N where
// the two turn alike, none where N is 0 too (moving as one); each named `how`.
void add_tape_centres(InstantCentres& result, const TapeLayout& layout, const std::vector<double>& values,
                      const MotionState& s, const std::function<std::string(std::size_t, std::size_t)>& how) {
  const std::size_t n = result.bodies.size();
  const double fastest = fastest_point(s), turning = fastest_turning(result);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      const std::size_t ta = result.tape_bodies[a], tb = result.tape_bodies[b];
      const double* pair = values.data() + layout.centre_pair_output(std::min(ta, tb), std::max(ta, tb));
      const double sign = ta < tb ? 1.0 : -1.0;  // the tape's pair the other way round: both negated
      const Complex N(sign * pair[0], sign * pair[1]);
      const double D = sign * pair[2];
      if (std::fabs(D) <= kCentreParallelTolerance * turning) {
        if (std::abs(N) <= 1e-12 * fastest) {  // moving as one: no centre
          result.moving_as_one.push_back({a, b});
          continue;
        }
        result.centres.push_back({a, b, true, Complex(-N.imag(), N.real()) / std::abs(N), how(a, b), {}, std::nullopt, {}});
        continue;
      }
      result.centres.push_back({a, b, false, {N.imag() / D, -N.real() / D}, how(a, b), {}, std::nullopt, {}});
    }
  }
}

// The same centres read from the model's drawing stage (centre_formulas.hpp), the bodies
// the construction found matched to the tape's by link or slider. Nullopt where a body is
// not on the tape. `points` gets each body's point as the tape gives it.
std::optional<InstantCentres> centres_from_tape(const MechanismGeometry& geometry, const MotionState& s,
                                                const std::vector<PointBody>& bodies, const std::string& ground,
                                                std::vector<Complex>& points) {
  const TapeLayout& layout = geometry.layout();
  const std::vector<double> values = geometry.drawing_values(s);
  if (values.size() != layout.drawing_output_count()) return std::nullopt;
  InstantCentres result = named_bodies(geometry.system(), bodies, ground);
  result.tape_bodies.push_back(0);
  for (const PointBody& body : bodies) {
    std::size_t found = 0;
    for (std::size_t t = 0; t < layout.centre_bodies.size(); ++t) {
      const CentreBody& c = layout.centre_bodies[t];
      if (body.link >= 0 ? c.link == body.link && c.slider_term < 0 : c.slider_term == body.slider_term) found = t + 1;
    }
    if (found == 0) return std::nullopt;
    result.tape_bodies.push_back(found);
  }
  read_tape_bodies(result, layout, values, points);
  add_tape_centres(result, layout, values, s,
                   [&result](std::size_t a, std::size_t b) { return found_by(result, a, b); });
  return result;
}

// A centre at infinity is seen from the block of the two (rate 0, not ground), else from
// the moving body, else from both: the mean of their points (the tape's).
void see_from_bodies(InstantCentre& centre, const InstantCentres& result, const std::vector<Complex>& points) {
  const auto block = [&](std::size_t b) { return b != 0 && result.rates[b].is_zero(); };
  centre.seen_bodies = block(centre.b) || centre.a == 0 ? std::vector<std::size_t>{centre.b}
                       : block(centre.a)                ? std::vector<std::size_t>{centre.a}
                                                        : std::vector<std::size_t>{centre.a, centre.b};
  Complex sum = 0;
  for (std::size_t b : centre.seen_bodies) sum += points[b];
  centre.seen_from = sum / double(centre.seen_bodies.size());
}

// Centres away from the joints: on the two Kennedy lines (through I_ab and I_bc for
// another body b) that cross there most squarely. A centre at infinity is seen from its
// bodies (see_from_bodies).
void mark_kennedy_lines(InstantCentres& result, const std::vector<Complex>& points, const MotionState& s,
                        double length_scale) {
  const std::size_t n = result.bodies.size();
  std::vector<Complex> joints = {0};
  for (const PointMotion& m : s.points) joints.push_back({m.position[0], m.position[1]});
  for (InstantCentre& centre : result.centres) {
    if (centre.at_infinity) {
      see_from_bodies(centre, result, points);
      continue;
    }
    bool joint = false;
    for (const auto& j : joints) joint = joint || std::abs(j - centre.at) <= 1e-9 * length_scale;
    if (joint) continue;
    std::vector<std::pair<Line, std::size_t>> lines;
    for (std::size_t b = 0; b < n; ++b) {
      if (b == centre.a || b == centre.b) continue;
      const InstantCentre *ab = result.find(centre.a, b), *bc = result.find(b, centre.b);
      if (!ab || !bc) continue;
      if (const auto l = line_through(*ab, *bc, length_scale)) lines.push_back({*l, b});
    }
    double best = 1e-6;
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (std::size_t j = i + 1; j < lines.size(); ++j) {
        const double sine = std::fabs(cross(lines[i].first.along, lines[j].first.along));
        if (sine <= best) continue;
        best = sine;
        const std::size_t b1 = lines[i].second, b2 = lines[j].second;
        centre.kennedy = {std::minmax(centre.a, b1), std::minmax(b1, centre.b), std::minmax(centre.a, b2),
                          std::minmax(b2, centre.b)};
      }
  }
}

// The pairs of bodies the result has no centre for, and whether every centre it has is finite.
bool list_missing_and_check_finite(InstantCentres& result) {
  const std::size_t n = result.bodies.size();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (!result.find(a, b)) result.not_found.push_back({a, b});
  std::vector<std::pair<std::size_t, std::size_t>> as_one;  // a pin's pair moving as one has its pin
  for (const auto& pair : result.moving_as_one)
    if (!result.find(pair.first, pair.second)) as_one.push_back(pair);
  result.moving_as_one = as_one;
  for (const InstantCentre& c : result.centres)
    if (!std::isfinite(c.at.real()) || !std::isfinite(c.at.imag())) return false;
  return true;
}

// Kennedy: I_ac on the line I_ab I_bc and on the line I_ad I_dc; of all such pairs of
// lines the one that crosses most squarely. Repeated until no centre is added. With
// `given` (the tape's centres) each centre is put where that has it, found by the lines
// the construction chose: where it stands is read, not constructed.
void complete_by_kennedy(InstantCentres& result, double length_scale, const InstantCentres* given = nullptr) {
  const std::size_t n = result.bodies.size();
  for (bool found = true; found;) {
    found = false;
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t c = a + 1; c < n; ++c) {
        if (result.find(a, c)) continue;
        std::vector<std::pair<Line, std::size_t>> lines;
        for (std::size_t b = 0; b < n; ++b) {
          if (b == a || b == c) continue;
          const InstantCentre *ab = result.find(a, b), *bc = result.find(b, c);
          if (!ab || !bc) continue;
          if (const auto l = line_through(*ab, *bc, length_scale)) lines.push_back({*l, b});
        }
        double best = 0;
        std::optional<InstantCentre> chosen;
        for (std::size_t i = 0; i < lines.size(); ++i) {
          for (std::size_t j = i + 1; j < lines.size(); ++j) {
            const Line &p = lines[i].first, &q = lines[j].first;
            const double sine = std::fabs(cross(p.along, q.along));
            const std::size_t b1 = lines[i].second, b2 = lines[j].second;
            const std::vector<std::pair<std::size_t, std::size_t>> kennedy = {
                std::minmax(a, b1), std::minmax(b1, c), std::minmax(a, b2), std::minmax(b2, c)};
            std::string how;
            for (std::size_t k = 0; k < 4; ++k)
              how += (k == 0 ? "" : k == 2 ? ", " : " ") + centre_name(result.bodies, kennedy[k].first, kennedy[k].second);
            if (sine <= 1e-9) {  // parallel lines: a centre at infinity, unless they are one line
              if (std::fabs(cross(q.through - p.through, p.along)) > 1e-9 * length_scale && !chosen)
                chosen = InstantCentre{a, c, true, p.along, how, kennedy, p.through, {}};
              continue;
            }
            if (sine <= best + 1e-9) continue;  // a tie (lines that are one) to the first pair, however rounded
            best = sine;
            const double t = cross(q.through - p.through, q.along) / cross(p.along, q.along);
            chosen = InstantCentre{a, c, false, p.through + t * p.along, how, kennedy, std::nullopt, {}};
          }
        }
        if (chosen && given) {
          const InstantCentre* there = given->find(a, c);
          if (!there) continue;  // the two move as one
          chosen->at_infinity = there->at_infinity;
          chosen->at = there->at;
          chosen->seen_from = there->seen_from;
          chosen->seen_bodies = there->seen_bodies;
        }
        if (chosen) {
          result.centres.push_back(*chosen);
          found = true;
        }
      }
    }
  }
}

// A vector-loop file's pins: the pinned ends of its drawn vectors, each joining the bodies
// whose parts end there (a link's vectors; ground's vectors and the origin; a block's point;
// a turning guide's end on its link). Where two of them have the same velocity there, the
// pin is their centre whatever their rates: moved there (the velocities' N / (i D) loses
// digits as the two come to turn alike), or added where the velocities gave none (they turn
// alike: the four-bar's coupler and rocker at theta2 = 0, a rocker at rest at its limit).
void place_pins(InstantCentres& result, const std::vector<PointBody>& bodies, const std::vector<DrawingSegment>& segments,
                const MotionState& s, double length_scale) {
  const auto same = [&](Complex p, Complex q) { return std::abs(p - q) <= 1e-9 * length_scale; };
  const auto body_of = [&](int link, int slider_term) -> std::optional<std::size_t> {
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (link >= 0 ? bodies[b].link == link : bodies[b].slider_term == slider_term) return b + 1;
    return std::nullopt;
  };
  std::vector<Complex> pins;
  for (const DrawingSegment& g : segments) {
    if (g.pin_at_from) pins.push_back(g.from);
    if (g.pin_at_to) pins.push_back(g.to);
    if (g.kind == DrawingSegment::Kind::slider) pins.push_back(g.block);
  }
  const double fastest = fastest_point(s);
  std::vector<Complex> done;
  for (const Complex p : pins) {
    if (std::any_of(done.begin(), done.end(), [&](Complex q) { return same(p, q); })) continue;
    done.push_back(p);
    std::vector<std::size_t> there;
    const auto add = [&](std::optional<std::size_t> b) {
      if (b && std::find(there.begin(), there.end(), *b) == there.end()) there.push_back(*b);
    };
    if (same(p, 0)) add(0);
    for (const DrawingSegment& g : segments) {
      const bool ends_here = same(g.from, p) || same(g.to, p);
      if (g.kind == DrawingSegment::Kind::ground && ends_here) add(0);
      if (g.kind == DrawingSegment::Kind::link && g.link >= 0 && ends_here) add(body_of(g.link, -1));
      if (g.kind != DrawingSegment::Kind::slider) continue;
      if (same(g.block, p)) add(body_of(-1, static_cast<int>(g.term)));
      const Complex other = same(g.block, g.from) ? g.to : g.from;
      if (!g.fixed_guide && g.guide_link >= 0 && same(other, p)) add(body_of(g.guide_link, -1));
    }
    // Body b's velocity at p (ground at rest).
    const auto velocity = [&](std::size_t b) {
      return b == 0 ? Complex() : bodies[b - 1].velocity + Complex(0, bodies[b - 1].omega) * (p - bodies[b - 1].point);
    };
    for (std::size_t i = 0; i < there.size(); ++i)
      for (std::size_t j = i + 1; j < there.size(); ++j) {
        const auto [a, b] = std::minmax(there[i], there[j]);
        if (std::abs(velocity(a) - velocity(b)) > 1e-9 * fastest) continue;  // not joined here after all
        InstantCentre* centre = nullptr;
        for (InstantCentre& c : result.centres)
          if (c.a == a && c.b == b) centre = &c;
        if (!centre) {
          result.centres.push_back({a, b, false, p, "the pin joining " + result.bodies[a] + " and " + result.bodies[b], {},
                                    std::nullopt, {}});
          centre = &result.centres.back();
        }
        centre->at_infinity = false;
        centre->at = p;
        centre->seen_from.reset();
        centre->seen_bodies.clear();
        centre->pin = true;
      }
  }
}

// A vector-loop file's centres: its bodies found from the points and the drawing, each
// centre from two bodies' velocities, read from the tape or (from_tape false) constructed
// from the numbers the bodies were found by; each pin's at the pin.
std::optional<InstantCentres> centres_from_points(const MechanismGeometry& geometry, const MotionState& s,
                                                  bool from_tape) {
  const ConstraintSystem& system = geometry.system();
  const std::vector<std::optional<double>> omegas = geometry.link_angular_velocities(s);
  std::vector<PointBody> bodies = bodies_of_points(geometry, s, omegas);
  if (bodies.empty()) return std::nullopt;
  const std::vector<DrawingSegment> segments = geometry.segments(s);
  add_drawn_bodies(geometry, s, segments, omegas, bodies);
  const std::string ground = number_bodies(bodies);
  std::vector<Complex> points = {0};
  for (const PointBody& b : bodies) points.push_back(b.point);
  std::optional<InstantCentres> result =
      from_tape ? centres_from_tape(geometry, s, bodies, ground, points)
                : std::optional<InstantCentres>(centres_of_bodies(system, s, bodies, ground));
  if (!result) return std::nullopt;
  place_pins(*result, bodies, segments, s, system.length_scale);
  std::sort(result->centres.begin(), result->centres.end(),
            [](const InstantCentre& p, const InstantCentre& q) { return std::pair(p.a, p.b) < std::pair(q.a, q.b); });
  if (!list_missing_and_check_finite(*result)) return std::nullopt;
  mark_kennedy_lines(*result, points, s, system.length_scale);
  if (result->driver != 0) add_ratios(*result, system.length_scale);
  return result;
}

// A joints-and-links mechanism's bodies (ground, then its links) by name, with the rates
// they turn at (0 for ground and the blocks) and the driver.
InstantCentres plan_bodies(const ConstraintSystem& system) {
  const SolvingPlan& plan = *system.plan;
  InstantCentres result;
  result.driver = plan.driver_body;
  bool zero_named = false;
  for (const SolvingPlan::Link& link : plan.links) zero_named = zero_named || link.name == "0";
  result.bodies.push_back(zero_named ? "g" : "0");
  for (std::size_t b = 1; b < plan.bodies.size(); ++b) result.bodies.push_back(plan.links[b - 1].name);
  for (std::size_t b = 0; b < plan.bodies.size(); ++b) {
    const SolvingPlan::Body& body = plan.bodies[b];
    result.rates.push_back(body.unknown >= 0                                   ? GiNaC::ex(system.unknowns[body.unknown].rate)
                           : b == plan.driver_body && plan.driver_slider < 0 ? GiNaC::ex(system.input.rate)
                                                                              : GiNaC::ex(0));
  }
  return result;
}

// The primary centres: each pin's at its joint, each slider's at infinity across its line
// (seen from its joint), where `place` puts them (nullopt: none).
void add_primary_centres(const SolvingPlan& plan, InstantCentres& result,
                         const std::function<std::optional<InstantCentre>(bool slider, std::size_t k)>& place) {
  const auto add = [&](std::size_t a, std::size_t b, std::optional<InstantCentre> centre, const std::string& how, bool pin) {
    if (a > b) std::swap(a, b);
    if (a == b || result.find(a, b) || !centre) return;
    centre->a = a;
    centre->b = b;
    centre->found_by = how;
    centre->pin = pin;
    result.centres.push_back(*centre);
  };
  for (std::size_t k = 0; k < plan.pins.size(); ++k)
    add(plan.pins[k].a, plan.pins[k].b, place(false, k), "pin " + plan.joints[plan.pins[k].joint].name, true);
  for (std::size_t k = 0; k < plan.sliders.size(); ++k)
    add(plan.sliders[k].block, plan.sliders[k].guide, place(true, k), "slider " + plan.joints[plan.sliders[k].joint].name,
        false);
}

// A joints-and-links mechanism's centres as a course constructs them, from the bodies'
// poses: the primary ones at the joints, the others by Kennedy.
std::optional<InstantCentres> constructed_plan_centres(const MechanismGeometry& geometry, const MotionState& s) {
  const ConstraintSystem& system = geometry.system();
  const SolvingPlan& plan = *system.plan;
  const std::vector<int> signs = signs_nearest(plan, s.input, s.q.data(), system.length_scale);
  std::vector<BodyPose> poses;
  if (place_dyads(plan, s.input, poses, &signs) < plan.dyads.size()) return std::nullopt;
  InstantCentres result = plan_bodies(system);
  const std::function<double(std::size_t)> omega = [&](std::size_t b) -> double {
    const SolvingPlan::Body& body = plan.bodies[b];
    if (b == 0) return 0.0;
    if (body.unknown >= 0) return s.qd[body.unknown];
    if (body.guide >= 0) return omega(static_cast<std::size_t>(body.guide));
    return b == plan.driver_body && plan.driver_slider < 0 ? s.input_rate : 0.0;
  };
  for (std::size_t b = 0; b < plan.bodies.size(); ++b) result.angular_velocities.push_back(omega(b));
  const auto world = [&](std::size_t b, std::size_t joint) {
    for (const auto& [j, local] : plan.bodies[b].points)
      if (j == joint) return b == 0 ? local : poses[b].origin + local * std::polar(1.0, poses[b].angle);
    return Complex();
  };
  add_primary_centres(plan, result, [&](bool slider, std::size_t k) -> std::optional<InstantCentre> {
    if (!slider) return InstantCentre{0, 0, false, world(plan.pins[k].a, plan.pins[k].joint), "", {}, std::nullopt, {}};
    const SolvingPlan::Slider& sl = plan.sliders[k];
    const double line = (sl.guide == 0 ? 0.0 : poses[sl.guide].angle) + sl.direction;
    return InstantCentre{0, 0, true, std::polar(1.0, line + kPi / 2), "", {}, world(sl.block, sl.joint), {}};
  });
  complete_by_kennedy(result, system.length_scale);
  return result;
}

// The same centres read from the model's drawing stage (centre_formulas.hpp: the tape's
// bodies say which of the plan's they are), found by the joints and the Kennedy lines the
// construction would choose. Nullopt where a body is not on the tape.
std::optional<InstantCentres> plan_centres_from_tape(const MechanismGeometry& geometry, const MotionState& s) {
  const TapeLayout& layout = geometry.layout();
  const std::vector<double> values = geometry.drawing_values(s);
  if (values.size() != layout.drawing_output_count()) return std::nullopt;
  InstantCentres result = plan_bodies(geometry.system());
  result.tape_bodies.assign(1, 0);
  for (std::size_t b = 1; b < result.bodies.size(); ++b) {
    std::size_t found = 0;
    for (std::size_t t = 0; t < layout.centre_bodies.size(); ++t)
      if (layout.centre_bodies[t].plan_body == static_cast<int>(b)) found = t + 1;
    if (found == 0) return std::nullopt;
    result.tape_bodies.push_back(found);
  }
  std::vector<Complex> points;
  read_tape_bodies(result, layout, values, points);
  // At rest (an input rate of 0) the velocities the tape's centres come from are all 0:
  // constructed from the poses instead (pins, sliders, Kennedy).
  if (fastest_turning(result) == 0 && fastest_point(s) == 0) return std::nullopt;
  InstantCentres tape = result;
  add_tape_centres(tape, layout, values, s, [](std::size_t, std::size_t) { return std::string(); });
  for (InstantCentre& centre : tape.centres)
    if (centre.at_infinity) see_from_bodies(centre, tape, points);
  const SolvingPlan& plan = *geometry.system().plan;
  // A pin is the centre of the two bodies it joins whatever their rates: where it is on the
  // drawing stage (the tape's N / (i D) is 0 / 0 where they turn alike, and loses digits as
  // they come to). A slider's centre where the tape has it, else as constructed (the block
  // at rest on its guide at a limit position: moving as one for the instant).
  if (layout.linkage_joint_count != plan.joints.size()) return std::nullopt;
  std::optional<std::optional<InstantCentres>> constructed;
  add_primary_centres(plan, result, [&](bool slider, std::size_t k) -> std::optional<InstantCentre> {
    if (!slider) {
      const double* at = values.data() + layout.linkage_joint_output(plan.pins[k].joint);
      return InstantCentre{0, 0, false, {at[0], at[1]}, "", {}, std::nullopt, {}};
    }
    const SolvingPlan::Slider& sl = plan.sliders[k];
    if (const InstantCentre* there = tape.find(sl.block, sl.guide)) return *there;
    if (!constructed) constructed = constructed_plan_centres(geometry, s);
    const InstantCentre* built = *constructed ? (*constructed)->find(sl.block, sl.guide) : nullptr;
    if (!built) return std::nullopt;
    InstantCentre across = *built;  // seen from the bodies' points, as the tape's are
    if (across.at_infinity) see_from_bodies(across, tape, points);
    return across;
  });
  result.moving_as_one = tape.moving_as_one;
  complete_by_kennedy(result, geometry.system().length_scale, &tape);
  // Where two bodies move as one (no centre of theirs) Kennedy may not reach a centre the
  // tape has: found by the velocities, as a vector-loop file's.
  for (const InstantCentre& centre : tape.centres)
    if (!result.find(centre.a, centre.b)) {
      result.centres.push_back(centre);
      result.centres.back().found_by = found_by(result, centre.a, centre.b);
    }
  return result;
}

// The pairs not found, in order, and the ratios; nullopt where a centre is not finite.
std::optional<InstantCentres> finish_plan_centres(InstantCentres result, double length_scale) {
  if (!list_missing_and_check_finite(result)) return std::nullopt;
  std::sort(result.centres.begin(), result.centres.end(),
            [](const InstantCentre& p, const InstantCentre& q) { return std::pair(p.a, p.b) < std::pair(q.a, q.b); });
  add_ratios(result, length_scale);
  return result;
}

}  // namespace

const InstantCentre* InstantCentres::find(std::size_t a, std::size_t b) const {
  if (a > b) std::swap(a, b);
  for (const InstantCentre& c : centres)
    if (c.a == a && c.b == b) return &c;
  return nullptr;
}

std::optional<InstantCentres> constructed_instant_centres(const MechanismGeometry& geometry, const MotionState& s) {
  const ConstraintSystem& system = geometry.system();
  if (s.status != Status::ok || !system.frames.empty()) return std::nullopt;
  if (!system.plan) return centres_from_points(geometry, s, false);
  if (!system.plan->closed_form) return std::nullopt;
  std::optional<InstantCentres> result = constructed_plan_centres(geometry, s);
  return result ? finish_plan_centres(std::move(*result), system.length_scale) : std::nullopt;
}

std::optional<InstantCentres> instant_centres(const MechanismGeometry& geometry, const MotionState& s) {
  count_work(Work::drawing);
  const ConstraintSystem& system = geometry.system();
  if (s.status != Status::ok || !system.frames.empty()) return std::nullopt;
  if (!system.plan) return centres_from_points(geometry, s, true);
  if (!system.plan->closed_form) return std::nullopt;
  // Read from the tape; constructed only where the tape holds no centres (a drawing
  // formula it could not take).
  std::optional<InstantCentres> result = plan_centres_from_tape(geometry, s);
  if (!result) result = constructed_plan_centres(geometry, s);
  return result ? finish_plan_centres(std::move(*result), system.length_scale) : std::nullopt;
}

}  // namespace kinema
