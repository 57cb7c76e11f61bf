#include "engine/analysis/geometry.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "engine/base/units.hpp"
#include "engine/base/work_count.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "engine/symbolic/link_vectors.hpp"

namespace kinema {

ChainBodies chain_bodies(const ConstraintSystem& system) {
  ChainBodies bodies;
  const auto frame_named = [&](const std::string& name) {
    return std::any_of(system.frames.begin(), system.frames.end(), [&](const FrameObservable& f) { return f.name == name; });
  };
  for (const FrameObservable& frame : system.frames) {
    bodies.ground_frames.push_back(!frame_named(frame.parent));
    bodies.joints.push_back(frame.joint);
  }
  const auto point_index = [&](const std::string& name) {
    for (std::size_t p = 0; p < system.points.size(); ++p)
      if (system.points[p].name == name) return p;
    return system.points.size();
  };
  for (const PointObservable& point : system.points) bodies.point_frames.push_back(point.terms ? point.terms->frame : "");
  for (const EquationGroup& group : system.groups) {
    if (group.between.size() != 2) continue;
    const std::array<std::size_t, 2> ends{point_index(group.between[0]), point_index(group.between[1])};
    if (ends[0] < system.points.size() && ends[1] < system.points.size()) bodies.couplers.push_back(ends);
  }
  return bodies;
}

std::complex<double> ChainView::on_page(const std::array<double, 3>& p) const {
  const double t = theta * M_PI / 180, f = phi * M_PI / 180;
  return {p[0] * std::cos(f) + p[1] * std::sin(f),
          -p[0] * std::cos(t) * std::sin(f) + p[1] * std::cos(t) * std::cos(f) + p[2] * std::sin(t)};
}

ChainView chain_view(const ConstraintSystem& system, const std::vector<PlacedFrame>& frames,
                     const std::vector<std::array<double, 3>>& points) {
  using Place = std::array<double, 3>;
  const auto distance = [](const Place& a, const Place& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); };
  // Places: the observer's origin, the frames' origins, then the points.
  std::vector<Place> places{{0, 0, 0}};
  const auto origin_of = [&](const std::string& name) {
    for (std::size_t f = 0; f < frames.size(); ++f)
      if (frames[f].name == name) return 1 + f;
    return std::size_t(0);
  };
  for (const PlacedFrame& f : frames) places.push_back(f.origin);
  const std::size_t first_point = places.size();
  places.insert(places.end(), points.begin(), points.end());
  double size = 0;
  for (const Place& a : places)
    for (const Place& b : places) size = std::max(size, distance(a, b));
  if (!(size > 0)) return {};
  // The lines drawn: the bodies (as place indices) and the observer's axes.
  const ChainBodies bodies = chain_bodies(system);
  std::vector<std::array<std::size_t, 2>> bars;
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (!bodies.ground_frames[f]) bars.push_back({origin_of(frames[f].parent), 1 + f});
  if (!points.empty()) {
    for (std::size_t p = 0; p < points.size() && p < bodies.point_frames.size(); ++p)
      if (!bodies.point_frames[p].empty()) bars.push_back({origin_of(bodies.point_frames[p]), first_point + p});
    for (const auto& ends : bodies.couplers) bars.push_back({first_point + ends[0], first_point + ends[1]});
  }
  std::vector<std::array<Place, 2>> axes;
  for (int c = 0; c < 3; ++c) {
    Place tip{0, 0, 0};
    tip[c] = size;
    axes.push_back({Place{0, 0, 0}, tip});
  }
  const double same = 1e-6 * size;  // one place (a frame's origin on its parent's)
  // A place on a line in space (B on the x axis) is on it from every side: not counted.
  const auto off_line = [&](const Place& p, const Place& a, const Place& b) {
    Place d{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, r{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double t = dd > 0 ? std::clamp((r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) / dd, 0.0, 1.0) : 0.0;
    return distance(p, {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]}) > same;
  };
  const auto apart_seen = [&](const ChainView& view) {
    std::vector<std::complex<double>> seen;
    for (const Place& p : places) seen.push_back(view.on_page(p));
    const auto from_line = [](std::complex<double> p, std::complex<double> a, std::complex<double> b) {
      const std::complex<double> d = b - a;
      const double t = std::norm(d) > 0 ? std::clamp(std::real((p - a) * std::conj(d)) / std::norm(d), 0.0, 1.0) : 0.0;
      return std::abs(p - (a + t * d));
    };
    double nearest = std::numeric_limits<double>::infinity(), widest = 0;
    for (std::size_t i = 0; i < places.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (distance(places[i], places[j]) <= same) continue;
        nearest = std::min(nearest, std::abs(seen[i] - seen[j]));
        widest = std::max(widest, std::abs(seen[i] - seen[j]));
      }
      for (const auto& bar : bars)
        if (off_line(places[i], places[bar[0]], places[bar[1]]))
          nearest = std::min(nearest, from_line(seen[i], seen[bar[0]], seen[bar[1]]));
      for (const auto& axis : axes)
        if (off_line(places[i], axis[0], axis[1]))
          nearest = std::min(nearest, from_line(seen[i], view.on_page(axis[0]), view.on_page(axis[1])));
    }
    return widest > 0 && std::isfinite(nearest) ? nearest / widest : 0.0;
  };
  const ChainView usual;
  const double usual_score = apart_seen(usual);
  ChainView best = usual;
  double best_score = usual_score;
  for (const double theta : {50.0, 65.0, 80.0})
    for (int phi = 0; phi < 360; phi += 30) {
      const ChainView view{theta, double(phi)};
      const double score = apart_seen(view);
      if (score > 1.1 * usual_score && score > best_score) {
        best = view;
        best_score = score;
      }
    }
  return best;
}

std::vector<PlacedFrame> placed_frames(const Model& model, const MotionState& s) {
  count_work(Work::drawing);
  const std::vector<double> values = model.kinematics.drawing_values(s);
  const TapeLayout& layout = model.kinematics.layout();
  std::vector<PlacedFrame> frames;
  for (std::size_t f = 0; f < model.system.frames.size(); ++f) {
    PlacedFrame placed{model.system.frames[f].name, model.system.frames[f].parent, {}, {}};
    if (!values.empty()) {
      const double* v = values.data() + layout.frame_placement_output(f);
      // + 0.0: -sin(0) is -0.0 on the tape and 0 in GiNaC; a drawing shows no signed zero.
      for (std::size_t r = 0; r < 3; ++r) {
        placed.origin[r] = v[r] + 0.0;
        for (std::size_t c = 0; c < 3; ++c) placed.axes[c][r] = v[3 + 3 * r + c] + 0.0;
      }
    }
    frames.push_back(placed);
  }
  return frames;
}

MechanismGeometry::MechanismGeometry(const Model& model)
    : system_(&model.system), kinematics_(&model.kinematics),
      terms_(classify_loop_terms(model.system, model.derivation.link_vectors)) {
  count_work(Work::drawing);
}

std::vector<PointOnLink> MechanismGeometry::points_on_links(const MotionState& state) const {
  std::vector<PointOnLink> found;
  if (state.status != Status::ok || terms_.points.empty()) return found;
  const std::vector<double> values = kinematics_->drawing_values(state);
  if (values.empty()) return found;
  for (const LoopTerms::OnLink& on : terms_.points) {
    const double* xy = values.data() + kinematics_->layout().link_vector_output(on.vector) + TapeLayout::kVectorPositionAt;
    const PointMotion& m = state.points[on.point];
    const std::complex<double> at(m.position[0], m.position[1]), term(xy[0], xy[1]);
    if (std::isfinite(term.real()) && std::isfinite(term.imag())) found.push_back({on.point, on.link, on.vector, at - term, at});
  }
  return found;
}

std::vector<std::optional<double>> MechanismGeometry::link_angular_velocities(const MotionState& state) const {
  std::vector<std::optional<double>> omegas(terms_.link_rates.size());
  if (state.status != Status::ok) return omegas;
  const std::vector<double> values = kinematics_->drawing_values(state);
  if (values.empty()) return omegas;
  for (std::size_t k = 0; k < omegas.size(); ++k) {
    const double* w = values.data() + kinematics_->layout().link_vector_output(terms_.link_vectors[k]) +
                      TapeLayout::kVectorAngleRateAt;
    if (std::isfinite(w[0]) && w[1] == 0) omegas[k] = w[0];
  }
  return omegas;
}

namespace {

// The order to lay a loop's terms end to end from the origin: its ground vectors at the
// origin (first or last), then as many corners as can be on named points; ties keep the
// order written (the first permutation).
std::vector<std::size_t> drawing_order(const std::vector<std::complex<double>>& terms,
                                       const std::vector<DrawingSegment::Kind>& kinds,
                                       const std::vector<std::complex<double>>& named, double tolerance) {
  std::vector<std::size_t> order(terms.size()), best;
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  best = order;
  if (order.size() > 7) return best;  // 8! orders: keep the written one
  int best_score = -1;
  do {
    int score = 0;
    for (std::size_t k = 0; k < order.size() && kinds[order[k]] == DrawingSegment::Kind::ground; ++k) score += 2;
    for (std::size_t k = order.size(); k-- > 0 && kinds[order[k]] == DrawingSegment::Kind::ground;) score += 2;
    std::complex<double> at = 0;
    for (std::size_t k = 0; k + 1 < order.size(); ++k) {
      at += terms[order[k]];
      for (const auto& p : named)
        if (std::abs(p - at) <= tolerance) {
          ++score;
          break;
        }
    }
    if (score > best_score) {
      best_score = score;
      best = order;
    }
  } while (std::next_permutation(order.begin(), order.end()));
  return best;
}

}  // namespace

std::vector<DrawingSegment> MechanismGeometry::segments(const MotionState& state) const {
  const std::vector<double> values = kinematics_->drawing_values(state);
  if (values.empty()) return {};
  const TapeLayout& layout = kinematics_->layout();
  const auto vector_at = [&](std::size_t k, std::size_t at) {
    const double* v = values.data() + layout.link_vector_output(k) + at;
    return std::complex<double>(v[0], v[1]);
  };
  std::vector<std::complex<double>> named;
  double size = 0;
  for (const PointMotion& p : state.points) {
    if (p.position.size() < 2) continue;
    named.push_back({p.position[0], p.position[1]});
    size = std::max(size, std::abs(named.back()));
  }
  std::vector<DrawingSegment> segments;
  std::size_t first = 0;  // the loop's first term
  for (std::size_t count : terms_.loop_term_count) {
    std::vector<std::complex<double>> terms;
    std::vector<DrawingSegment::Kind> kinds(terms_.kinds.begin() + first, terms_.kinds.begin() + first + count);
    for (std::size_t k = 0; k < count; ++k) terms.push_back(vector_at(first + k, TapeLayout::kVectorPositionAt));
    for (const auto& v : terms) size = std::max(size, std::abs(v));
    const std::size_t begin = segments.size();
    std::complex<double> at = 0;
    std::vector<std::size_t> term_of;  // per segment of this loop: its term
    for (std::size_t k : drawing_order(terms, kinds, named, 1e-9 * std::max(size, 1e-30))) {
      const std::size_t term = first + k;
      term_of.push_back(term);
      DrawingSegment& g = segments.emplace_back();
      g.from = at;
      g.to = at + terms[k];
      g.term = term;
      g.loop_start = term_of.size() == 1;
      g.kind = terms_.kinds[term];
      g.link = terms_.term_links[term];
      g.coordinate = terms_.term_coordinates[term];
      if (g.coordinate >= 0) {
        g.angle = g.coordinate == 0 ? state.input : state.q[g.coordinate - 1];
        g.angle_at = std::real(terms[k] * std::polar(1.0, -g.angle)) >= 0 ? g.from : g.to;
      }
      at += terms[k];
    }
    // A slider's point: the end of its term that is not on the ground side (the origin or a
    // ground vector's end); its guide along d(term)/d(length) through it.
    const auto grounded = [&](std::complex<double> p) {
      if (std::abs(p) <= 1e-9 * size) return true;
      for (std::size_t j = begin; j < segments.size(); ++j)
        if (segments[j].kind == DrawingSegment::Kind::ground &&
            (std::abs(segments[j].from - p) <= 1e-9 * size || std::abs(segments[j].to - p) <= 1e-9 * size))
          return true;
      return false;
    };
    for (std::size_t j = begin; j < segments.size(); ++j) {
      DrawingSegment& g = segments[j];
      if (g.kind != DrawingSegment::Kind::slider) continue;
      const std::size_t term = term_of[j - begin];
      g.block_at_from = grounded(g.to) && !grounded(g.from);
      g.block = g.block_at_from ? g.from : g.to;
      g.along = g.to - g.from;
      if (terms_.has_guide[term]) {
        const std::complex<double> d = vector_at(term, TapeLayout::kVectorGuideAt);
        g.guide_from_tape = std::abs(d) > 0 && std::isfinite(std::abs(d));
        if (g.guide_from_tape) g.along = d;
        g.fixed_guide = !terms_.guide_turns[term];
        g.guide_link = terms_.guide_links[term];
      }
      if (std::abs(g.along) > 0) g.along /= std::abs(g.along);
    }
    first += count;
  }
  // Pins: where a link vector ends, a block is, or a turning guide ends (in any loop).
  const auto pinned = [&](std::complex<double> p) {
    const auto at = [&](std::complex<double> q) { return std::abs(q - p) <= 1e-9 * std::max(size, 1e-30); };
    for (const DrawingSegment& g : segments) {
      const bool ends_here = at(g.from) || at(g.to);
      if (g.kind == DrawingSegment::Kind::link && ends_here) return true;
      if (g.kind == DrawingSegment::Kind::slider && (at(g.block) || (!g.fixed_guide && ends_here))) return true;
    }
    return false;
  };
  for (DrawingSegment& g : segments) {
    g.pin_at_from = pinned(g.from);
    g.pin_at_to = pinned(g.to);
  }
  // Blocks numbered in the gaps the links leave.
  std::vector<std::string> used(terms_.link_labels);
  used.push_back(std::find(used.begin(), used.end(), "1") != used.end() ? "0" : "1");
  int next = 1;
  for (DrawingSegment& g : segments) {
    if (g.kind != DrawingSegment::Kind::slider) continue;
    while (std::find(used.begin(), used.end(), std::to_string(next)) != used.end()) ++next;
    g.block_label = std::to_string(next);
    used.push_back(g.block_label);
  }
  return segments;
}

std::vector<LetteredCorner> MechanismGeometry::lettered_corners(const MotionState& state,
                                                                const std::vector<DrawingSegment>& segments) const {
  if (segments.empty()) return {};
  // The one-letter named points where the state places them.
  std::vector<std::pair<char, std::complex<double>>> named;
  double size = 0;
  for (std::size_t p = 0; p < state.points.size() && p < system_->points.size(); ++p) {
    const std::string& name = system_->points[p].name;
    if (state.points[p].position.size() < 2) continue;
    const std::complex<double> at(state.points[p].position[0], state.points[p].position[1]);
    if (!std::isfinite(std::abs(at))) continue;
    size = std::max(size, std::abs(at));
    if (name.size() == 1 && std::isupper(static_cast<unsigned char>(name[0]))) named.push_back({name[0], at});
  }
  for (const DrawingSegment& g : segments) size = std::max({size, std::abs(g.from), std::abs(g.to)});
  const double tolerance = 1e-9 * std::max(size, 1e-30);
  const auto point_at = [&](std::complex<double> at) -> char {
    for (const auto& [letter, p] : named)
      if (std::abs(p - at) <= tolerance) return letter;
    return 0;
  };
  // A term's ends as its length's name gives them: "AB*exp(I*phi)" or "I*AC", the one
  // parameter of the term named by two capital letters.
  const auto ends_named = [&](const GiNaC::ex& term) -> std::string {
    std::string ends;
    int named_lengths = 0;
    for (const SystemParameter& parameter : system_->parameters) {
      const std::string& name = parameter.symbol.get_name();
      const bool two_letters = name.size() == 2 && std::isupper(static_cast<unsigned char>(name[0])) &&
                               std::isupper(static_cast<unsigned char>(name[1])) && name[0] != name[1];
      if (two_letters && term.has(parameter.symbol)) {
        ends = name;
        ++named_lengths;
      }
    }
    return named_lengths == 1 ? ends : std::string();
  };
  std::vector<const EquationGroup*> loops;
  for (const EquationGroup& g : system_->groups)
    if (g.kind == "loop") loops.push_back(&g);
  if (loops.size() != terms_.loop_term_count.size()) return {};
  std::vector<std::pair<std::complex<double>, char>> lettered;
  bool contradicted = false;
  std::size_t first = 0;  // the loop's first term
  for (std::size_t s = 0, l = 0; s < segments.size() && l < loops.size() && !contradicted; ++l) {
    // The loop's segments in the order drawn (corners on named points; segments()).
    const std::size_t count = terms_.loop_term_count[l];
    const std::size_t begin = s;
    while (s < segments.size() && (s == begin || !segments[s].loop_start)) ++s;
    if (loops[l]->terms.size() != count || s - begin != count) {
      first += count;
      continue;
    }
    // Corner k: where drawn segment k starts (segment k - 1 ends).
    std::vector<std::complex<double>> corners;
    std::vector<std::string> ends;
    for (std::size_t k = begin; k < s; ++k) {
      corners.push_back(segments[k].from);
      ends.push_back(segments[k].term >= first && segments[k].term < first + count
                         ? ends_named(loops[l]->terms[segments[k].term - first])
                         : std::string());
    }
    first += count;
    std::vector<char> letter(count, 0);
    for (std::size_t k = 0; k < count; ++k) letter[k] = point_at(corners[k]);
    // A term's two ends carry its two letters: one end known gives the other.
    for (bool changed = true; changed && !contradicted;) {
      changed = false;
      for (std::size_t k = 0; k < count; ++k) {
        if (ends[k].empty()) continue;
        char& start = letter[k];
        char& end = letter[(k + 1) % count];
        const auto other = [&](char c) { return c == ends[k][0] ? ends[k][1] : c == ends[k][1] ? ends[k][0] : char(0); };
        if (start != 0 && end == 0 && other(start) != 0) end = other(start), changed = true;
        if (end != 0 && start == 0 && other(end) != 0) start = other(end), changed = true;
        // Named otherwise: the file's letters mean something else; nothing is lettered.
        if ((start != 0 && other(start) == 0) || (end != 0 && other(end) == 0) || (start != 0 && start == end))
          contradicted = true;
      }
    }
    for (std::size_t k = 0; k < count; ++k)
      if (letter[k] != 0 && point_at(corners[k]) == 0) lettered.push_back({corners[k], letter[k]});
  }
  if (contradicted) return {};
  std::vector<LetteredCorner> found;
  for (const auto& corner : lettered) {
    // (No structured binding: a lambda below uses them, which C++17 clang refuses.)
    const std::complex<double> at = corner.first;
    const char letter = corner.second;
    // One letter a place and one place a letter, else none.
    const bool clash = std::any_of(lettered.begin(), lettered.end(), [&](const auto& o) {
      return (std::abs(o.first - at) <= tolerance) != (o.second == letter);
    });
    const bool again = std::any_of(found.begin(), found.end(), [&](const LetteredCorner& c) { return c.letter[0] == letter; });
    if (clash || again) continue;
    for (std::size_t s = 0; s < segments.size(); ++s) {  // a corner drawn: a segment's end
      if (std::abs(segments[s].from - at) <= tolerance) {
        found.push_back({std::string(1, letter), s, false, segments[s].from});
        break;
      }
      if (std::abs(segments[s].to - at) <= tolerance) {
        found.push_back({std::string(1, letter), s, true, segments[s].to});
        break;
      }
    }
  }
  return found;
}

std::vector<DrawnDimension> MechanismGeometry::dimensions(const std::vector<DrawingSegment>& segments) const {
  std::vector<const EquationGroup*> loops;
  for (const EquationGroup& g : system_->groups)
    if (g.kind == "loop") loops.push_back(&g);
  if (loops.size() != terms_.loop_term_count.size()) return {};
  // Each term's formula by its index among the link vectors.
  std::vector<GiNaC::ex> formulas;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (loops[l]->terms.size() != terms_.loop_term_count[l]) return {};
    formulas.insert(formulas.end(), loops[l]->terms.begin(), loops[l]->terms.end());
  }
  // The length parameter p with c p = e for c one of 1, -1, i, -i.
  const auto one_length = [&](const GiNaC::ex& e) -> std::optional<std::size_t> {
    for (std::size_t k = 0; k < system_->parameters.size(); ++k) {
      const SystemParameter& p = system_->parameters[k];
      if (p.dimension != Dimension::length || !e.has(p.symbol)) continue;
      const GiNaC::ex ratio = GiNaC::normal(e / p.symbol);
      for (const GiNaC::ex& c : {GiNaC::ex(1), GiNaC::ex(-1), GiNaC::ex(GiNaC::I), GiNaC::ex(-GiNaC::I)})
        if ((ratio - c).is_zero()) return k;
      return std::nullopt;
    }
    return std::nullopt;
  };
  GiNaC::exmap unknowns_zero;
  for (const Coordinate& q : system_->unknowns) unknowns_zero[q.symbol] = 0;
  GiNaC::exmap values;
  for (const SystemParameter& p : system_->parameters) values[p.symbol] = p.value;
  std::vector<DrawnDimension> found;
  for (const DrawingSegment& g : segments) {
    if (g.term >= formulas.size()) continue;
    const GiNaC::ex& term = formulas[g.term];
    if (g.kind == DrawingSegment::Kind::ground) {
      if (const auto k = one_length(term)) found.push_back({g.from, g.to, *k});
    } else if (g.kind == DrawingSegment::Kind::slider && g.fixed_guide) {
      const GiNaC::ex constant = term.subs(unknowns_zero);
      const auto k = one_length(constant);
      if (!k) continue;
      const GiNaC::ex number = GiNaC::evalf(constant.subs(values));
      if (!GiNaC::is_a<GiNaC::numeric>(number)) continue;
      const std::complex<double> c(GiNaC::ex_to<GiNaC::numeric>(GiNaC::real_part(number)).to_double(),
                                   GiNaC::ex_to<GiNaC::numeric>(GiNaC::imag_part(number)).to_double());
      // The term runs from `from` to `to`; its ground end is the one without the block.
      if (g.block_at_from) found.push_back({g.to, g.to - c, *k});
      else found.push_back({g.from, g.from + c, *k});
    }
  }
  return found;
}

namespace {

double distance_to_segment(std::complex<double> p, std::complex<double> a, std::complex<double> b) {
  const std::complex<double> d = b - a;
  const double t = std::norm(d) > 0 ? std::clamp(std::real((p - a) * std::conj(d)) / std::norm(d), 0.0, 1.0) : 0.0;
  return std::abs(p - (a + t * d));
}

}  // namespace

double arrows_distance(std::complex<double> first_from, std::complex<double> first, std::complex<double> second_from,
                       std::complex<double> second) {
  const std::complex<double> first_to = first_from + first, second_to = second_from + second;
  double nearest = std::min(distance_to_segment(first_to, second_from, second_to), distance_to_segment(second_to, first_from, first_to));
  if (first_from == second_from) return nearest;
  const auto side = [](std::complex<double> p, std::complex<double> q, std::complex<double> r) {
    return std::imag((q - p) * std::conj(r - p));
  };
  if (side(first_from, first_to, second_from) * side(first_from, first_to, second_to) < 0 &&
      side(second_from, second_to, first_from) * side(second_from, second_to, first_to) < 0)
    return 0;  // they cross
  return std::min({nearest, distance_to_segment(first_from, second_from, second_to),
                   distance_to_segment(second_from, first_from, first_to)});
}

double angle_mark_radius(double radians, double symbol, double arm, double smallest, double largest, double on_arm) {
  const double half = std::fabs(radians) / 2;
  const double fits = half > 0 ? symbol / std::sin(std::min(half, kPi / 2)) : largest;
  double r = std::clamp(fits, smallest, largest);
  if (arm > 0) r = std::min(r, on_arm * arm);
  return r;
}

std::optional<LinkageDrawing> linkage_drawing(const ConstraintSystem& system, const MotionState& state) {
  count_work(Work::drawing);
  if (!system.plan || !system.plan->closed_form || state.status == Status::unassembled) return std::nullopt;
  const SolvingPlan& plan = *system.plan;
  const SolvingPlan& frames = plan;
  // The poses of this position: placed on the signs nearest its unknowns.
  const std::vector<int> signs = signs_nearest(frames, state.input, state.q.data(), system.length_scale);
  std::vector<BodyPose> poses;
  if (place_dyads(frames, state.input, poses, &signs) < frames.dyads.size()) return std::nullopt;
  LinkageDrawing drawing;
  for (const auto& [joint, at] : frames.bodies[0].points) drawing.ground_pivots.push_back({plan.joints[joint].name, at});
  for (const SolvingPlan::Slider& s : frames.sliders)
    if (s.guide == 0) drawing.guides.push_back({s.through, std::polar(1.0, s.direction)});
  for (std::size_t b = 1; b < frames.bodies.size(); ++b) {
    LinkageDrawing::Link link;
    link.block = frames.bodies[b].guide >= 0;
    link.angle = poses[b].angle;
    link.name = plan.links[b - 1].name;
    for (const auto& [joint, v] : frames.bodies[b].points)
      link.joints.push_back({plan.joints[joint].name, poses[b].origin + v * std::polar(1.0, poses[b].angle)});
    link.origin = poses[b].origin;
    if (frames.bodies[b].unknown >= 0) {
      link.coordinate = frames.bodies[b].unknown + 1;
      link.coordinate_angle = state.q[Eigen::Index(frames.bodies[b].unknown)];
    } else if (b == frames.driver_body && frames.driver_slider < 0) {
      link.coordinate = 0;
      link.coordinate_angle = state.input;
    }
    drawing.links.push_back(link);
  }
  return drawing;
}

}  // namespace kinema
