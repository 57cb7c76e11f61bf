#include <kinema/engine/report/geometry.hpp>

#include <cmath>

#include <kinema/engine/symbolic/complex_parts.hpp>
#include <kinema/engine/symbolic/derivation.hpp>
#include <kinema/engine/symbolic/expression_parts.hpp>
#include <kinema/loops/dyad_positions.hpp>

namespace kinema {

std::string link_label(const ConstraintSystem& system, const GiNaC::ex& angle) {
  std::string name;
  for (std::size_t j = system.unknowns.size(); j-- > 0;)
    if (angle.has(system.unknowns[j].symbol)) name = system.unknowns[j].name;
  if (angle.has(system.input.symbol)) name = system.input.name;
  const auto digits = name.find_last_not_of("0123456789");
  return digits != std::string::npos && digits + 1 < name.size() ? name.substr(digits + 1) : name;
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
  const GiNaC::ex rate = time_derivative(system, link.angle);
  for (std::size_t k = 0; k < link_rates_.size(); ++k)
    if (link_rates_[k].is_equal(rate)) return static_cast<int>(k);
  link_rates_.push_back(rate);
  link_labels_.push_back(link_label(system, link.angle));
  return static_cast<int>(link_rates_.size() - 1);
}

MechanismGeometry::MechanismGeometry(const ConstraintSystem& system) {
  std::vector<GiNaC::ex> inputs, outputs;
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
      for (const Coordinate& q : system.unknowns) {
        if (!term.has(q.symbol)) continue;
        moving = true;
        sliding = sliding || q.dimension == Dimension::length;
      }
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

std::vector<DrawingSegment> MechanismGeometry::segments(const MotionState& state) const {
  std::vector<double> inputs(parameter_values_);
  inputs.push_back(state.input);
  for (Eigen::Index i = 0; i < state.q.size(); ++i) inputs.push_back(state.q[i]);
  std::vector<double> values(tape_.output_count()), registers = tape_.make_workspace();
  if (inputs.size() != tape_.input_count()) return {};
  tape_.evaluate(inputs.data(), values.data(), registers);
  std::vector<DrawingSegment> segments;
  const double* xy = values.data();  // x, y of each term in turn
  std::size_t term = 0;
  for (std::size_t count : loop_term_count_) {
    std::complex<double> at = 0;
    for (std::size_t k = 0; k < count; ++k, ++term, xy += 2) {
      const std::complex<double> v(xy[0], xy[1]);
      segments.push_back({at, at + v, kinds_[term], term_links_[term]});
      at += v;
    }
  }
  return segments;
}

std::optional<LinkageDrawing> linkage_drawing(const ConstraintSystem& system, const MotionState& state) {
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
    drawing.links.push_back(link);
  }
  return drawing;
}

}  // namespace kinema
