#include "engine/analysis/geometry.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/work_count.hpp"
#include "engine/symbolic/complex_parts.hpp"
#include "engine/symbolic/derivation.hpp"
#include "engine/symbolic/expression_parts.hpp"
#include "loops/dyad_positions.hpp"

namespace kinema {

std::string link_label(const ConstraintSystem& system, const GiNaC::ex& angle) {
  std::string name, rate;
  for (std::size_t j = system.unknowns.size(); j-- > 0;)
    if (angle.has(system.unknowns[j].symbol)) {
      name = system.unknowns[j].name;
      rate = system.unknowns[j].rate.get_name();
    }
  if (angle.has(system.input.symbol)) {
    name = system.input.name;
    rate = system.input.rate.get_name();
  }
  // The digits the name ends in, else those of its rate's name (phi turning at omega1: 1).
  const auto number = [](const std::string& n) {
    const auto digits = n.find_last_not_of("0123456789");
    return digits != std::string::npos && digits + 1 < n.size() ? n.substr(digits + 1) : std::string();
  };
  if (!number(name).empty()) return number(name);
  return !number(rate).empty() ? number(rate) : name;
}

namespace {

double number_at(const GiNaC::ex& e, const GiNaC::exmap& values) {
  const GiNaC::ex v = GiNaC::evalf(e.subs(values, GiNaC::subs_options::no_pattern));
  return GiNaC::is_a<GiNaC::numeric>(v) ? GiNaC::ex_to<GiNaC::numeric>(v).to_double() : 0.0;
}

}  // namespace

std::vector<PlacedFrame> placed_frames(const ConstraintSystem& system, const MotionState& s) {
  count_work(Work::drawing);
  GiNaC::exmap values;
  for (const SystemParameter& p : system.parameters) values[p.symbol] = p.value;
  values[system.input.symbol] = s.input;
  for (std::size_t i = 0; i < system.unknowns.size(); ++i) values[system.unknowns[i].symbol] = s.q[Eigen::Index(i)];
  std::vector<PlacedFrame> frames;
  for (const FrameObservable& f : system.frames) {
    PlacedFrame placed{f.name, f.parent, {}, {}};
    for (std::size_t r = 0; r < 3; ++r) {
      placed.origin[r] = number_at(f.origin[r], values);
      for (std::size_t c = 0; c < 3; ++c) placed.axes[c][r] = number_at(f.rotation[3 * r + c], values);
    }
    frames.push_back(placed);
  }
  return frames;
}

int MechanismGeometry::link_of(const ConstraintSystem& system, const GiNaC::ex& term) {
  const LinkVector link = split_link_vector(term);
  if (!link.polar) return -1;
  const auto moves = [&](const GiNaC::ex& e) {
    bool moving = e.has(system.input.symbol);
    for (const Coordinate& q : system.unknowns) moving = moving || e.has(q.symbol);
    return moving;
  };
  if (moves(link.length) || !moves(link.angle)) return -1;
  return link_of_angle(system, link.angle);
}

int MechanismGeometry::link_of_angle(const ConstraintSystem& system, const GiNaC::ex& angle) {
  const GiNaC::ex rate = time_derivative(system, angle);
  for (std::size_t k = 0; k < link_rates_.size(); ++k)
    if (link_rates_[k].is_equal(rate)) return static_cast<int>(k);
  link_rates_.push_back(rate);
  link_labels_.push_back(link_label(system, angle));
  return static_cast<int>(link_rates_.size() - 1);
}

MechanismGeometry::MechanismGeometry(const ConstraintSystem& system) {
  count_work(Work::drawing);
  std::vector<GiNaC::ex> inputs, outputs, guides;
  const auto moves = [&](const GiNaC::ex& e) {
    bool moving = e.has(system.input.symbol);
    for (const Coordinate& q : system.unknowns) moving = moving || e.has(q.symbol);
    return moving;
  };
  for (const SystemParameter& parameter : system.parameters) {
    inputs.push_back(parameter.symbol);
    parameter_values_.push_back(parameter.value);
  }
  inputs.push_back(system.input.symbol);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.symbol);
  for (const EquationGroup& group : system.groups) {
    if (!group.vector) continue;
    loop_term_count_.push_back(group.terms.size());
    for (const GiNaC::ex& term : group.terms) {
      outputs.push_back(real_part_of(term));
      outputs.push_back(imag_part_of(term));
      // A term that moves is a link; one whose length moves is a slider's guide.
      bool moving = term.has(system.input.symbol);
      bool sliding = moving && system.input.dimension == Dimension::length;
      std::optional<GiNaC::ex> length;  // the length that slides: the first in the term
      if (sliding) length = system.input.symbol;
      for (const Coordinate& q : system.unknowns) {
        if (!term.has(q.symbol)) continue;
        moving = true;
        if (q.dimension == Dimension::length && !length) length = q.symbol;
        sliding = sliding || q.dimension == Dimension::length;
      }
      // A slider's guide: the way the term moves as its length changes, the others held.
      int guide_output = -1, guide_link = -1;
      bool guide_turns = false;
      if (sliding && length) {
        try {
          const GiNaC::ex along = term.diff(GiNaC::ex_to<GiNaC::symbol>(*length));
          guide_output = static_cast<int>(guides.size());
          guides.push_back(real_part_of(along));
          guides.push_back(imag_part_of(along));
          guide_turns = moves(along);
          const LinkVector v = split_link_vector(term);
          if (guide_turns && v.polar && moves(v.angle)) guide_link = link_of_angle(system, v.angle);
        } catch (const std::exception&) {
          guide_output = -1;
        }
      }
      // A link vector turning with a coordinate itself (theta3, not theta3 + beta).
      int coordinate = -1;
      if (const LinkVector v = split_link_vector(term); v.polar) {
        if (v.angle.is_equal(system.input.symbol) && system.input.dimension == Dimension::angle) coordinate = 0;
        for (std::size_t j = 0; j < system.unknowns.size(); ++j)
          if (v.angle.is_equal(system.unknowns[j].symbol)) coordinate = static_cast<int>(j) + 1;
      }
      term_coordinates_.push_back(coordinate);
      guide_outputs_.push_back(guide_output);
      guide_turns_.push_back(guide_turns);
      guide_links_.push_back(guide_link);
      kinds_.push_back(!moving ? DrawingSegment::Kind::ground
                               : sliding ? DrawingSegment::Kind::slider : DrawingSegment::Kind::link);
      int link = -1;
      try {  // drawn as a plain segment when GiNaC cannot differentiate the term alone
        link = link_of(system, term);
      } catch (const std::exception&) {
      }
      term_links_.push_back(link);
    }
  }
  if (system.frames.empty()) {
    for (std::size_t p = 0; p < system.points.size(); ++p) {
      if (system.points[p].written_terms.empty()) continue;
      const GiNaC::ex& last = system.points[p].written_terms.back();
      try {  // a term GiNaC cannot differentiate (a power of 0): the point is just not drawn on a link
        const int link = link_of(system, last);
        if (link < 0) continue;
        const GiNaC::ex x = real_part_of(last), y = imag_part_of(last);
        points_.push_back({p, link});
        outputs.push_back(x);
        outputs.push_back(y);
      } catch (const std::exception&) {
        continue;
      }
    }
  }
  outputs.insert(outputs.end(), guides.begin(), guides.end());
  tape_ = CompiledExpressions(inputs, outputs);
}

std::vector<PointOnLink> MechanismGeometry::points_on_links(const MotionState& state) const {
  std::vector<PointOnLink> found;
  if (state.status != Status::ok || points_.empty()) return found;
  std::vector<double> inputs(parameter_values_);
  inputs.push_back(state.input);
  for (Eigen::Index i = 0; i < state.q.size(); ++i) inputs.push_back(state.q[i]);
  std::vector<double> values(tape_.output_count()), registers = tape_.make_workspace();
  if (inputs.size() != tape_.input_count()) return found;
  tape_.evaluate(inputs.data(), values.data(), registers);
  const double* xy = values.data() + 2 * kinds_.size();  // after the loops' terms
  for (const auto& [point, link] : points_) {
    const PointMotion& m = state.points[point];
    const std::complex<double> at(m.position[0], m.position[1]), term(xy[0], xy[1]);
    xy += 2;
    if (std::isfinite(term.real()) && std::isfinite(term.imag())) found.push_back({point, link, at - term, at});
  }
  return found;
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
  std::vector<double> inputs(parameter_values_);
  inputs.push_back(state.input);
  for (Eigen::Index i = 0; i < state.q.size(); ++i) inputs.push_back(state.q[i]);
  std::vector<double> values(tape_.output_count()), registers = tape_.make_workspace();
  if (inputs.size() != tape_.input_count()) return {};
  tape_.evaluate(inputs.data(), values.data(), registers);
  std::vector<std::complex<double>> named;
  double size = 0;
  for (const PointMotion& p : state.points) {
    if (p.position.size() < 2) continue;
    named.push_back({p.position[0], p.position[1]});
    size = std::max(size, std::abs(named.back()));
  }
  const double* guide_xy = values.data() + 2 * (kinds_.size() + points_.size());
  std::vector<DrawingSegment> segments;
  std::size_t first = 0;  // the loop's first term
  for (std::size_t count : loop_term_count_) {
    std::vector<std::complex<double>> terms;
    std::vector<DrawingSegment::Kind> kinds(kinds_.begin() + first, kinds_.begin() + first + count);
    for (std::size_t k = 0; k < count; ++k) terms.push_back({values[2 * (first + k)], values[2 * (first + k) + 1]});
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
      g.kind = kinds_[term];
      g.link = term_links_[term];
      g.coordinate = term_coordinates_[term];
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
      g.block = grounded(g.to) && !grounded(g.from) ? g.from : g.to;
      g.along = g.to - g.from;
      if (guide_outputs_[term] >= 0) {
        const std::complex<double> d(guide_xy[guide_outputs_[term]], guide_xy[guide_outputs_[term] + 1]);
        if (std::abs(d) > 0 && std::isfinite(std::abs(d))) g.along = d;
        g.fixed_guide = !guide_turns_[term];
        g.guide_link = guide_links_[term];
      }
      if (std::abs(g.along) > 0) g.along /= std::abs(g.along);
    }
    first += count;
  }
  // Blocks numbered in the gaps the links leave.
  std::vector<std::string> used(link_labels_);
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

std::optional<LinkageDrawing> linkage_drawing(const ConstraintSystem& system, const MotionState& state) {
  count_work(Work::drawing);
  if (!system.linkage || !system.linkage->frames.closed_form || state.status == Status::unassembled) return std::nullopt;
  const Linkage& linkage = *system.linkage;
  const LinkageFrames& frames = linkage.frames;
  // The poses of this position: placed on the signs nearest its unknowns.
  const std::vector<int> signs = signs_nearest(frames, state.input, state.q.data(), system.length_scale);
  std::vector<BodyPose> poses;
  if (place_dyads(frames, state.input, poses, &signs) < frames.dyads.size()) return std::nullopt;
  LinkageDrawing drawing;
  for (const auto& [joint, at] : frames.bodies[0].points) drawing.ground_pivots.push_back({linkage.joints[joint].name, at});
  for (const LinkageFrames::Slider& s : frames.sliders)
    if (s.guide == 0) drawing.guides.push_back({s.through, std::polar(1.0, s.direction)});
  for (std::size_t b = 1; b < frames.bodies.size(); ++b) {
    LinkageDrawing::Link link;
    link.block = frames.bodies[b].guide >= 0;
    link.angle = poses[b].angle;
    link.name = linkage.links[b - 1].name;
    for (const auto& [joint, v] : frames.bodies[b].points)
      link.joints.push_back({linkage.joints[joint].name, poses[b].origin + v * std::polar(1.0, poses[b].angle)});
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
