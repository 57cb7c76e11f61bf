// The derivation as readable text (GiNaC's default print context).
#include <sstream>

#include <kinema/engine/symbolic/expression_parts.hpp>
#include <kinema/engine/printers/printers.hpp>
#include <kinema/engine/symbolic/trig_simplify.hpp>

namespace kinema {
namespace {

using GiNaC::ex;

// "numerator/denominator" instead of GiNaC's x^(-1) factors.
std::string fraction(const ex& e) {
  const ex nd = e.numer_denom();
  const ex numerator = nd.op(0), denominator = nd.op(1);
  if (denominator.is_equal(1)) return to_text(numerator);
  auto grouped = [](const ex& part) {
    const bool simple = GiNaC::is_a<GiNaC::symbol>(part) || GiNaC::is_a<GiNaC::numeric>(part) ||
                        GiNaC::is_a<GiNaC::function>(part) || GiNaC::is_a<GiNaC::power>(part);
    return simple ? to_text(part) : "(" + to_text(part) + ")";
  };
  return grouped(numerator) + "/" + grouped(denominator);
}

std::string joined(const std::vector<std::string>& items) {
  std::string result;
  for (const auto& item : items) result += (result.empty() ? "" : ", ") + item;
  return result;
}

}  // namespace

void print_derivation_text(std::ostream& out, const Mechanism& m, const Derivation& d) {
  const LoopClosure& c = d.closure;
  const std::size_t n = c.unknowns.size();
  std::vector<std::string> unknowns, rates, second_rates, rows;
  for (std::size_t i = 0; i < n; ++i) {
    unknowns.push_back(m.unknowns[i].name);
    rates.push_back(d.rates[i].get_name());
    second_rates.push_back(d.second_rates[i].get_name());
  }
  for (const Loop& loop : m.loops) {
    rows.push_back(loop.name + ".x");
    rows.push_back(loop.name + ".y");
  }

  out << m.title << "\n\n";
  out << "input:    " << m.input.name << " (rate " << d.input_rate.get_name() << ", second rate "
      << d.input_second_rate.get_name() << ")\n";
  out << "unknowns: q = [" << joined(unknowns) << "]\n";
  out << "rates:    qd = [" << joined(rates) << "], qdd = [" << joined(second_rates) << "]\n";

  out << "\n1. Loop-closure equations Phi(q, " << m.input.name << ") = 0\n";
  for (std::size_t k = 0; k < m.loops.size(); ++k) {
    out << "\n  loop " << m.loops[k].name << ":  " << to_text(c.loop_vectors[k]) << " = 0\n";
    out << "    x:  " << to_text(c.equations[2 * k]) << " = 0\n";
    out << "    y:  " << to_text(c.equations[2 * k + 1]) << " = 0\n";
  }

  out << "\n2. Jacobian Phi_q (rows " << joined(rows) << "; columns " << joined(unknowns) << ")\n\n";
  for (std::size_t i = 0; i < n; ++i) {
    out << "  " << rows[i] << ":  [ ";
    for (std::size_t j = 0; j < n; ++j) out << (j ? ",  " : "") << to_text(d.jacobian(i, j));
    out << " ]\n";
  }
  out << "\n  Phi_" << m.input.name << " = [ ";
  for (std::size_t i = 0; i < n; ++i) out << (i ? ",  " : "") << to_text(d.input_jacobian(i, 0));
  out << " ]\n";

  out << "\n3. Velocity equations  Phi_q * [" << joined(rates) << "] = -Phi_" << m.input.name << " * "
      << d.input_rate.get_name() << "\n\n";
  for (std::size_t i = 0; i < n; ++i) {
    ex left = 0;
    for (std::size_t j = 0; j < n; ++j) left += d.jacobian(i, j) * d.rates[j];
    out << "  " << rows[i] << ":  " << to_text(left) << " = " << to_text(-d.input_jacobian(i, 0) * d.input_rate)
        << "\n";
  }

  out << "\n4. Acceleration equations  Phi_q * [" << joined(second_rates)
      << "] = -(Phi_q * qd)_q * qd - 2 (Phi_q * qd)_" << m.input.name << " * "
      << d.input_rate.get_name() << " - Phi_" << m.input.name << m.input.name << " * "
      << d.input_rate.get_name() << "^2 - Phi_" << m.input.name << " * " << d.input_second_rate.get_name()
      << "\n\n";
  for (std::size_t i = 0; i < n; ++i) {
    ex left = 0;
    for (std::size_t j = 0; j < n; ++j) left += d.jacobian(i, j) * d.second_rates[j];
    out << "  " << rows[i] << ":  " << to_text(left) << " = " << to_text(combine_trig_products(d.acceleration_rhs[i]))
        << "\n";
  }

  out << "\n5. Solved rates (Cramer's rule, block by block)\n";
  for (const RateBlock& block : d.blocks) {
    std::vector<std::string> loops;
    for (std::size_t k : block.loops) loops.push_back(m.loops[k].name);
    out << "\n  from loop " << joined(loops) << ":\n";
    for (std::size_t j : block.unknowns) out << "    " << rates[j] << " = " << fraction(d.solved_rates[j]) << "\n";
    for (std::size_t j : block.unknowns)
      out << "    " << second_rates[j] << " = " << fraction(d.solved_second_rates[j]) << "\n";
  }

  if (!m.points.empty()) {
    out << "\n6. Points\n";
    for (std::size_t p = 0; p < m.points.size(); ++p) {
      out << "\n  " << m.points[p].name << " = " << to_text(c.point_positions[p]) << "\n";
      out << "    x   = " << to_text(c.point_x[p]) << "\n";
      out << "    y   = " << to_text(c.point_y[p]) << "\n";
      out << "    vx  = " << to_text(d.point_velocity_x[p]) << "\n";
      out << "    vy  = " << to_text(d.point_velocity_y[p]) << "\n";
      out << "    ax  = " << to_text(combine_trig_products(d.point_acceleration_x[p])) << "\n";
      out << "    ay  = " << to_text(combine_trig_products(d.point_acceleration_y[p])) << "\n";
    }
  }
}

}  // namespace kinema
