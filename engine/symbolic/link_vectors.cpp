#include "engine/symbolic/link_vectors.hpp"

#include "engine/constraints/differentiate.hpp"
#include "engine/symbolic/derivation.hpp"

namespace kinema {

LinkVectorMotion link_vector_motion(const ConstraintSystem& system, const GiNaC::ex& term) {
  using GiNaC::ex;
  using GiNaC::I;
  LinkVectorMotion m;
  m.term = term;
  m.link = split_link_vector(term);
  const ex& length = m.link.length;
  m.textbook = m.link.polar && !length.has(I) && !m.link.angle.has(I);
  if (m.link.polar) {
    m.length_rate = time_derivative(system, length);
    m.angle_rate = time_derivative(system, m.link.angle);
    m.length_second_rate = time_derivative(system, m.length_rate);
    m.angle_second_rate = time_derivative(system, m.angle_rate);
  }
  if (m.textbook) {
    const ex direction = GiNaC::exp(I * m.link.angle);
    const ex &w = m.angle_rate, &s = m.length_rate;
    m.parts = {I * w * length * direction,     s * direction,
               -w * w * length * direction,    I * m.angle_second_rate * length * direction,
               2 * I * w * s * direction,      m.length_second_rate * direction};
    m.magnitudes = {w * length, s, w * w * length, m.angle_second_rate * length, 2 * w * s, m.length_second_rate};
  } else {  // a vector of fixed direction (x + I*e, I*r6) or of no link form: its derivatives whole
    const ex velocity = time_derivative(system, term);
    m.parts = {0, velocity, 0, 0, 0, time_derivative(system, velocity)};
    m.magnitudes = {0, 0, 0, 0, 0, 0};
  }
  m.derived = true;
  return m;
}

std::optional<GiNaC::ex> sliding_length(const ConstraintSystem& system, const GiNaC::ex& term) {
  if (term.has(system.input.symbol) && system.input.dimension == Dimension::length) return system.input.symbol;
  for (const Coordinate& q : system.unknowns)
    if (q.dimension == Dimension::length && term.has(q.symbol)) return q.symbol;
  return std::nullopt;
}

namespace {

// A term's motion, or the term alone where GiNaC cannot differentiate it.
LinkVectorMotion motion_or_term(const ConstraintSystem& system, const GiNaC::ex& term) {
  try {
    return link_vector_motion(system, term);
  } catch (const std::exception&) {
    LinkVectorMotion alone;
    alone.term = term;
    alone.link = split_link_vector(term);
    alone.parts.fill(0);
    alone.magnitudes.fill(0);
    return alone;
  }
}

}  // namespace

PlanarLinkVectors planar_link_vectors(const ConstraintSystem& system) {
  PlanarLinkVectors found;
  if (!system.frames.empty()) return found;
  for (std::size_t g = 0; g < system.groups.size(); ++g) {
    const EquationGroup& group = system.groups[g];
    if (!group.vector) continue;
    PlanarLinkVectors::Chain chain{g, std::nullopt, {}};
    for (const GiNaC::ex& term : group.terms) {
      LinkVectorMotion m = motion_or_term(system, term);
      if (const auto length = sliding_length(system, term)) {
        try {  // a guide GiNaC cannot differentiate is drawn along the term itself
          m.guide = partial(term, GiNaC::ex_to<GiNaC::symbol>(*length));
        } catch (const std::exception&) {
        }
      }
      chain.vectors.push_back(found.vectors.size());
      found.vectors.push_back(m);
    }
    found.chains.push_back(chain);
  }
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    if (system.points[p].written_terms.empty()) continue;
    PlanarLinkVectors::Chain chain{std::nullopt, p, {}};
    for (const GiNaC::ex& term : system.points[p].written_terms) {
      chain.vectors.push_back(found.vectors.size());
      found.vectors.push_back(motion_or_term(system, term));
    }
    found.chains.push_back(chain);
  }
  return found;
}

}  // namespace kinema
