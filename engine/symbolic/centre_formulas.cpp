#include "engine/symbolic/centre_formulas.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>

#include "engine/constraints/complex_parts.hpp"
#include "engine/symbolic/loop_terms.hpp"

namespace kinema {

using GiNaC::ex;

namespace {

using Complex = std::complex<double>;

// A point whose velocity is known: a named point, or a ground one (at rest).
struct KnownPoint {
  ex x, y, vx = 0, vy = 0;
  bool ground = false;
  Complex sampled;  ///< At the made-up motion of Sample.
};

// Formulas at one made-up motion: the parameters at their values, the input and the
// unknowns at values that close no loop. Two ends of loop terms are one point wherever
// the loop closes when they agree there or differ by the loop's sum.
class Sample {
 public:
  explicit Sample(const ConstraintSystem& system) : scale_(system.length_scale) {
    for (const SystemParameter& p : system.parameters) values_[p.symbol] = p.value;
    double u = 0.37;
    const auto made_up = [&](Dimension d) {
      u = std::fmod(u * 7.31 + 0.113, 1.0);  // spread, not round: no accidental coincidence
      return (0.3 + u) * (d == Dimension::length ? scale_ : 1.0);
    };
    values_[system.input.symbol] = made_up(system.input.dimension);
    for (const Coordinate& q : system.unknowns) values_[q.symbol] = made_up(q.dimension);
  }
  std::optional<Complex> at(const ex& e) const {
    try {
      const ex v = GiNaC::evalf(e.subs(values_));
      if (!GiNaC::is_a<GiNaC::numeric>(v)) return std::nullopt;
      const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(v);
      return Complex(n.real().to_double(), n.imag().to_double());
    } catch (const std::exception&) {
      return std::nullopt;  // a formula with no value there (a pole): no point known by it
    }
  }
  bool same(Complex p, Complex q, Complex loop) const {
    const double tolerance = 1e-9 * std::max({scale_, std::abs(p), std::abs(q)});
    return std::abs(p - q) <= tolerance || std::abs(p - q - loop) <= tolerance || std::abs(p - q + loop) <= tolerance;
  }

 private:
  double scale_;
  GiNaC::exmap values_;
};

// A body with a point on it whose velocity is known, and how fast it turns.
struct Body {
  CentreBody id;
  ex omega;
  KnownPoint point;
};

// A loop term's two ends as known points (tail, then head = tail + term), where both are.
struct Ends {
  KnownPoint tail, head;
};

class BodyFinder {
 public:
  BodyFinder(const ConstraintSystem& system, const Derivation& derivation)
      : link_vectors_(derivation.link_vectors), terms_(classify_loop_terms(system, derivation.link_vectors)),
        sample_(system) {
    for (std::size_t p = 0; p < system.points.size(); ++p) {
      const std::vector<ex>& at = system.points[p].position;
      named_.emplace_back();
      const std::vector<ex>& velocity = derivation.points[p].velocity;
      if (at.size() != 2 || velocity.size() != 2) continue;
      const auto sampled = sample_.at(at[0] + GiNaC::I * at[1]);
      if (sampled) named_.back() = KnownPoint{at[0], at[1], velocity[0], velocity[1], false, *sampled};
    }
  }

  std::vector<Body> bodies() {
    // As the construction finds them (instant_centres.cpp): the links with a named point,
    // the others by their terms' ends, the guides by their pivots, then the blocks.
    for (const LoopTerms::OnLink& on : terms_.points)
      if (named_[on.point]) add({on.link, -1}, link_omega(on.link), *named_[on.point]);
    each_term([&](std::size_t term, const Ends& ends) {
      const int link = terms_.term_links[term];
      if (link >= 0) add({link, -1}, link_omega(link), ends.tail);
    });
    each_term([&](std::size_t term, const Ends& ends) {
      const int guide = terms_.guide_links[term];
      if (terms_.kinds[term] == LoopTermKind::slider && guide >= 0)
        add({guide, -1}, link_omega(guide), block_at_tail(ends) ? ends.head : ends.tail);
    });
    each_term([&](std::size_t term, const Ends& ends) {
      if (terms_.kinds[term] != LoopTermKind::slider || !terms_.has_guide[term]) return;
      const bool fixed = !terms_.guide_turns[term];
      const int guide = terms_.guide_links[term];
      if (!fixed && guide < 0) return;
      add({-1, static_cast<int>(term)}, fixed ? ex(0) : link_omega(guide), block_at_tail(ends) ? ends.tail : ends.head);
    });
    return bodies_;
  }

  // A joints-and-links file's bodies as its SolvingPlan numbers them: a link by the
  // coordinate whose rate it turns at (the driver's, or its angle's); a block by its point,
  // a joint on it (its rate tells it from neither ground nor its guide; a slider's own joint
  // is no named point, the pin at its place is).
  void number_as_plan(const ConstraintSystem& system, std::vector<Body>& bodies) const {
    if (!system.plan) return;
    const SolvingPlan& plan = *system.plan;
    for (Body& body : bodies) {
      if (body.id.slider_term < 0) {
        for (std::size_t b = 1; b < plan.bodies.size(); ++b) {
          const bool driven = b == plan.driver_body && plan.driver_slider < 0;
          const int unknown = plan.bodies[b].unknown;
          if (unknown < 0 && !driven) continue;
          const ex rate = driven ? ex(system.input.rate) : ex(system.unknowns[std::size_t(unknown)].rate);
          if ((body.omega - rate).expand().is_zero()) body.id.plan_body = static_cast<int>(b);
        }
        continue;
      }
      for (const SolvingPlan::Slider& slider : plan.sliders)
        for (const auto& on_block : plan.bodies[slider.block].points)
          for (std::size_t p = 0; p < system.points.size(); ++p)
            if (system.points[p].name == plan.joints[on_block.first].name && named_[p] &&
                sample_.same(named_[p]->sampled, body.point.sampled, 0))
              body.id.plan_body = static_cast<int>(slider.block);
    }
  }

 private:
  ex link_omega(int link) const { return real_part_of(terms_.link_rates[std::size_t(link)]); }

  void add(CentreBody id, const ex& omega, const KnownPoint& point) {
    for (const Body& b : bodies_)
      if (b.id.link == id.link && b.id.slider_term == id.slider_term) return;
    bodies_.push_back({id, omega, point});
  }

  // A slider's block is at the end away from the ground side (MechanismGeometry::segments).
  static bool block_at_tail(const Ends& ends) { return ends.head.ground && !ends.tail.ground; }

  // Each loop term both of whose ends are known points, with them.
  template <class Visit>
  void each_term(Visit visit) const {
    std::size_t first = 0;
    for (std::size_t count : terms_.loop_term_count) {
      std::vector<KnownPoint> known;
      std::vector<Complex> terms;
      for (std::size_t k = 0; k < count; ++k) terms.push_back(sample_.at(link_vectors_.vectors[first + k].term).value_or(NAN));
      Complex loop = 0;
      for (Complex t : terms) loop += t;
      for (const auto& n : named_)
        if (n) known.push_back(*n);
      add_ground_points(first, count, terms, known);
      for (std::size_t k = 0; k < count; ++k)
        if (const auto ends = ends_of(terms[k], loop, known)) visit(first + k, *ends);
      first += count;
    }
  }

  // The origin and the ends of a loop's ground terms laid from it, first or last: each sum
  // of some of them, and its negative.
  void add_ground_points(std::size_t first, std::size_t count, const std::vector<Complex>& terms,
                         std::vector<KnownPoint>& known) const {
    std::vector<std::size_t> ground;
    for (std::size_t k = 0; k < count; ++k)
      if (terms_.kinds[first + k] == LoopTermKind::ground) ground.push_back(k);
    if (ground.size() > 4) ground.resize(4);
    for (unsigned subset = 0; subset < (1u << ground.size()); ++subset) {
      ex sum = 0;
      Complex sampled = 0;
      for (std::size_t g = 0; g < ground.size(); ++g)
        if (subset & (1u << g)) {
          sum += link_vectors_.vectors[first + ground[g]].term;
          sampled += terms[ground[g]];
        }
      for (const double sign : {1.0, -1.0}) {
        if (subset == 0 && sign < 0) continue;
        const ex at = sign * sum;
        known.push_back({real_part_of(at), imag_part_of(at), 0, 0, true, sign * sampled});
      }
    }
  }

  // A term's tail and head among the known points (named first, as the construction looks).
  std::optional<Ends> ends_of(Complex term, Complex loop, const std::vector<KnownPoint>& known) const {
    if (!std::isfinite(std::abs(term)) || !std::isfinite(std::abs(loop))) return std::nullopt;
    for (const KnownPoint& tail : known)
      for (const KnownPoint& head : known)
        if (&tail != &head && sample_.same(head.sampled, tail.sampled + term, loop)) {
          Ends ends{tail, head};
          // An end that is also a ground point is on the ground side.
          for (const KnownPoint& g : known) {
            if (!g.ground) continue;
            ends.tail.ground = ends.tail.ground || sample_.same(g.sampled, tail.sampled, loop);
            ends.head.ground = ends.head.ground || sample_.same(g.sampled, head.sampled, loop);
          }
          return ends;
        }
    return std::nullopt;
  }

  const PlanarLinkVectors& link_vectors_;
  const LoopTerms terms_;
  const Sample sample_;
  std::vector<std::optional<KnownPoint>> named_;  ///< Per point: a planar one's.
  std::vector<Body> bodies_;
};

}  // namespace

std::vector<ex> centre_stage(const ConstraintSystem& system, const Derivation& derivation,
                             std::vector<CentreBody>& ids) {
  ids.clear();
  if (!system.frames.empty()) return {};
  BodyFinder finder(system, derivation);
  std::vector<Body> bodies = finder.bodies();
  finder.number_as_plan(system, bodies);
  std::vector<ex> out, cx = {0}, cy = {0}, omega = {0};
  for (const Body& b : bodies) {
    ids.push_back(b.id);
    out.insert(out.end(), {b.omega, b.point.x, b.point.y});
    // c = v_P - i omega P: the body's velocity at the origin, whichever point P it is known by.
    cx.push_back(b.point.vx + b.omega * b.point.y);
    cy.push_back(b.point.vy - b.omega * b.point.x);
    omega.push_back(b.omega);
  }
  for (std::size_t a = 0; a < omega.size(); ++a)
    for (std::size_t b = a + 1; b < omega.size(); ++b)
      out.insert(out.end(), {cx[b] - cx[a], cy[b] - cy[a], omega[a] - omega[b]});
  return out;
}

}  // namespace kinema
