#include "engine/symbolic/loop_terms.hpp"

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

// True for an expression that changes with the input or an unknown.
bool moves(const ConstraintSystem& system, const GiNaC::ex& e) {
  bool moving = e.has(system.input.symbol);
  for (const Coordinate& q : system.unknowns) moving = moving || e.has(q.symbol);
  return moving;
}

// A link vector turning with a coordinate itself (theta3, not theta3 + beta): that
// coordinate (0: the input, k + 1: unknown k), else -1.
int angle_coordinate(const ConstraintSystem& system, const LinkVector& v) {
  int coordinate = -1;
  if (!v.polar) return coordinate;
  if (v.angle.is_equal(system.input.symbol) && system.input.dimension == Dimension::angle) coordinate = 0;
  for (std::size_t j = 0; j < system.unknowns.size(); ++j)
    if (v.angle.is_equal(system.unknowns[j].symbol)) coordinate = static_cast<int>(j) + 1;
  return coordinate;
}

// Numbers the links as the terms are classed.
class Classifier {
 public:
  Classifier(const ConstraintSystem& system, const PlanarLinkVectors& link_vectors)
      : system_(system), link_vectors_(link_vectors) {}
  LoopTerms classify();

 private:
  int link_of(std::size_t vector);
  int link_of_angle(std::size_t vector);
  const ConstraintSystem& system_;
  const PlanarLinkVectors& link_vectors_;
  LoopTerms out_;
};

// The link a term of fixed length turning with an angle is on (added when new), or -1.
int Classifier::link_of(std::size_t vector) {
  const ConstraintSystem& system = system_;
  const LinkVectorMotion& term = link_vectors_.vectors[vector];
  if (!term.link.polar || moves(system, term.link.length) || !moves(system, term.link.angle)) return -1;
  return link_of_angle(vector);
}

// The link turning with this vector's angle (added when new).
int Classifier::link_of_angle(std::size_t vector) {
  const LinkVectorMotion& term = link_vectors_.vectors[vector];
  if (!term.derived) return -1;  // drawn as a plain segment when GiNaC cannot differentiate the term
  for (std::size_t k = 0; k < out_.link_rates.size(); ++k)
    if (out_.link_rates[k].is_equal(term.angle_rate)) return static_cast<int>(k);
  out_.link_rates.push_back(term.angle_rate);
  out_.link_vectors.push_back(vector);
  out_.link_labels.push_back(link_label(system_, term.link.angle));
  return static_cast<int>(out_.link_rates.size() - 1);
}

LoopTerms Classifier::classify() {
  const ConstraintSystem& system = system_;
  const PlanarLinkVectors& link_vectors = link_vectors_;
  for (const PlanarLinkVectors::Chain& chain : link_vectors.chains) {
    if (!chain.group) continue;
    out_.loop_term_count.push_back(chain.vectors.size());
    for (std::size_t v : chain.vectors) {
      const LinkVectorMotion& term = link_vectors.vectors[v];
      // A term that moves is a link; one whose length moves is a slider's guide, along
      // the way the term moves as its length changes, the others held.
      const bool sliding = sliding_length(system, term.term).has_value();
      int guide_link = -1;
      const bool guide_turns = term.guide && moves(system, *term.guide);
      if (guide_turns && term.link.polar && moves(system, term.link.angle))
        guide_link = link_of_angle(v);
      out_.term_coordinates.push_back(angle_coordinate(system, term.link));
      out_.has_guide.push_back(term.guide.has_value());
      out_.guide_turns.push_back(guide_turns);
      out_.guide_links.push_back(guide_link);
      out_.kinds.push_back(!moves(system, term.term) ? LoopTermKind::ground
                           : sliding                 ? LoopTermKind::slider
                                                     : LoopTermKind::link);
      out_.term_links.push_back(link_of(v));
    }
  }
  for (const PlanarLinkVectors::Chain& chain : link_vectors.chains) {
    if (!chain.point) continue;
    const int link = link_of(chain.vectors.back());
    if (link >= 0) out_.points.push_back({*chain.point, chain.vectors.back(), link});
  }
  return out_;
}

}  // namespace

LoopTerms classify_loop_terms(const ConstraintSystem& system, const PlanarLinkVectors& link_vectors) {
  return Classifier(system, link_vectors).classify();
}

}  // namespace kinema
