// The derivation in readable text (GiNaC's default print context).
#include "engine/printers/printer.hpp"
#include "engine/printers/textbook_form.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/problem_scale.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/constraints/solving_plan.hpp"

#include <cmath>

namespace kinema {
namespace {

using GiNaC::ex;

std::string joined(const std::vector<std::string>& items) {
  std::string result;
  for (const auto& item : items) result += (result.empty() ? "" : ", ") + item;
  return result;
}

// The solving order of a joints-and-links file: mobility, driver, dyads, the loops found.
void print_structure(std::ostream& out, const ConstraintSystem& system) {
  out << "\n0. Structure (joints and links)\n";
  out << "  mobility (Gruebler): " << mobility_text(*system.plan) << "\n";
  for (const std::string& line : structure_lines(*system.plan)) out << "  " << line << "\n";
  std::vector<std::string> loops;
  for (const EquationGroup& group : system.groups) loops.push_back(group.name);
  out << "  independent loops (one per joint outside a spanning tree from ground): " << joined(loops) << "\n";
}

// The velocities and accelerations group by group, in the method asked for.
void print_method(std::ostream& out, const ConstraintSystem& system, const DyadDerivation& derivation) {
  const DerivationMethod method = derivation.method;
  const TextbookForm textbook(system);
  const auto text = [&](const ex& e) { return textbook(e, TextbookForm::Style::text); };
  out << "\n1. Velocities and accelerations, group by group (" << method_name(method) << ")\n";
  for (const MethodStep& step : derivation.steps) {
    out << "\n  " << step.heading << "\n";
    if (!step.note.empty()) out << "    (" << step.note << ")\n";
    for (const bool acceleration : {false, true}) {
      out << "    " << (acceleration ? "acceleration" : "velocity") << ":\n";
      for (const MethodRelation& r : acceleration ? step.acceleration : step.velocity) {
        switch (r.kind) {
          case MethodRelation::Kind::statement: out << "      " << r.text << "\n"; break;
          case MethodRelation::Kind::component:
            if (r.text != "position") out << "        " << r.text << ":  " << text(r.left) << " = " << text(r.right) << "\n";
            break;
          case MethodRelation::Kind::solution: out << "        " << text(r.left) << " = " << text(r.right) << "\n"; break;
        }
      }
    }
  }
}

// A spatial chain as seed 000 works it out (engine/analysis/chain_instant): angular
// velocities composed along the chain, angular accelerations, and each point's velocity
// and acceleration term by term, at the instant, as formulas and as numbers.
void print_chain(std::ostream& out, const ConstraintSystem& system, const ChainAtInstant& chain) {
  const OutputScale scale(system);
  const ProblemScale problem(system);
  std::string values;
  for (const auto& [q, value] : chain.values)
    values += (values.empty() ? "" : ", ") + q.name + " = " +
              format_at_scale(scale.coordinate(q.dimension, value), problem.of(q.dimension, 0)) + " " +
              scale.coordinate_unit(q.dimension);
  TextbookForm textbook(system);
  textbook.set_exact_floats(true);  // the chain's floats carry the digits they need
  const auto text = [&](const ex& e) { return textbook(e, TextbookForm::Style::text); };
  const auto vector = [&](const ChainVector& v) {
    std::string formula = "[", number = "(";
    for (std::size_t c = 0; c < 3; ++c) {
      formula += (c ? ", " : "") + text(v.formula[c]);
      // Shown with its vector's components: round-off beside them is 0.
      number += (c ? ", " : "") + format_at_scale(v.value[c], largest_magnitude(v.value.data(), 3));
    }
    return formula + "] = " + number + ")";
  };
  const std::string& o = chain.observer;
  out << "\nAt the instant" << (system.input.dimension == Dimension::time ? " t = 0" : "") << " (" << values
      << "); vectors in the basis of " << chain.basis
      << (chain.basis == o ? "" : " (components along its axes x_" + chain.basis + ", y_" + chain.basis + ", z_" + chain.basis + ")")
      << " (SI: rad/s, m/s and their per-second rates)\n";
  out << "\n1. Angular velocities (the relative turnings summed along the chain) and accelerations\n";
  for (const ChainFrameAtInstant& f : chain.frames) {
    std::string sum;
    for (const AngularVelocityTerm& t : f.terms) {
      const bool minus = is_negative_term(t.rate);
      sum += (sum.empty() ? (minus ? "-" : "") : (minus ? " - " : " + ")) + text(minus ? -t.rate : t.rate) + " " +
             t.axis + "_" + t.frame;
    }
    out << "\n  " << f.name << " (parent " << f.parent << ")\n";
    out << "    w_" << f.name << "/" << o << " = " << (sum.empty() ? "0" : sum) << "\n";
    out << "      = " << vector(f.angular_velocity) << "\n";
    out << "    alpha_" << f.name << "/" << o << " = d/dt w, term by term: d/dt(rate) axis + w_frame x (rate axis)\n";
    for (std::size_t k = 0; k < f.terms.size(); ++k) {
      const AngularVelocityTerm& t = f.terms[k];
      const std::string axis = t.axis + "_" + t.frame, rate = text(t.rate);
      out << "      d/dt(" << rate << ") " << axis << " = " << vector(f.acceleration_parts[k].first) << "\n";
      if (t.frame != o) {
        out << "      w_" << t.frame << "/" << o << " x (" << rate << " " << axis
            << ") = " << vector(f.acceleration_parts[k].second) << "\n";
      }
    }
    out << "      = " << vector(f.angular_acceleration) << "\n";
  }
  out << "\n2. Points: v = v_F + w x r + v_rel;  a = a_F + alpha x r + w x (w x r) + 2 w x v_rel + a_rel\n";
  for (const ChainPointAtInstant& p : chain.points) {
    out << "\n  " << p.name << " (in " << p.frame << ")\n";
    for (const auto* part : {&p.velocity, &p.acceleration}) {
      for (const ChainVector& v : *part) {
        std::string name;
        switch (v.term) {
          case ChainTerm::position: name = "r_" + p.name + "/" + p.frame; break;
          case ChainTerm::frame_velocity: name = "v_" + p.frame + " (its origin)"; break;
          case ChainTerm::transport: name = "w x r"; break;
          case ChainTerm::relative_velocity: name = "v_rel"; break;
          case ChainTerm::velocity: name = "v_" + p.name; break;
          case ChainTerm::frame_acceleration: name = "a_" + p.frame + " (its origin)"; break;
          case ChainTerm::tangential: name = "alpha x r"; break;
          case ChainTerm::centripetal: name = "w x (w x r)"; break;
          case ChainTerm::coriolis: name = "2 w x v_rel"; break;
          case ChainTerm::relative_acceleration: name = "a_rel"; break;
          case ChainTerm::acceleration: name = "a_" + p.name; break;
          default: break;
        }
        out << "    " << name << " = " << vector(v) << "\n";
      }
    }
  }
}

class DerivationTextPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::derivation; }
  const char* name() const override { return "text"; }
  ViewNeeds needs(const PrintJob& job) const override { return derivation_needs(job, !is_driven_chain(job.model.system)); }

  void print(std::ostream& out, const PrintJob& job) const override {
    const ConstraintSystem& system = job.model.system;
    const Derivation& d = full_derivation(job.model.derivation);
    const Driver& input = system.input;
    const std::size_t n = system.unknowns.size();
    std::vector<std::string> unknowns, rates, second_rates, rows;
    for (const Coordinate& q : system.unknowns) {
      unknowns.push_back(q.name);
      rates.push_back(q.rate.get_name());
      second_rates.push_back(q.second_rate.get_name());
    }
    for (const Equation& equation : system.equations) rows.push_back(system.groups[equation.group].name + "." + equation.component);

    out << system.title << "\n\n";
    out << "input:    " << input.name << " (rate " << input.rate.get_name() << ", second rate "
        << input.second_rate.get_name() << ")\n";
    out << "unknowns: q = [" << joined(unknowns) << "]\n";
    out << "rates:    qd = [" << joined(rates) << "], qdd = [" << joined(second_rates) << "]\n";

    // A spatial chain driven by its joints alone in the seed's form; a closed loop as loops.
    if (is_driven_chain(system)) {
      print_chain(out, system, *analysis_of(job).chain);
      return;
    }
    if (system.plan) print_structure(out, system);
    if (job.method != DerivationMethod::loops) {
      print_method(out, system, *analysis_of(job).dyads);
      return;
    }

    const TextbookForm textbook(system);
    const auto text = [&](const ex& e) { return textbook(e, TextbookForm::Style::text); };
    out << "\n1. Loop-closure equations Phi(q, " << input.name << ") = 0\n";
    for (const EquationGroup& group : system.groups) {
      out << "\n  " << group.kind << " " << group.name << ":";
      if (group.vector) {
        const std::string written = textbook.loop_vector(group, TextbookForm::Style::text);
        out << "  " << (written.empty() ? text(*group.vector) : written) << " = 0";
      }
      out << "\n";
      for (std::size_t row : group.equations) {
        out << "    " << system.equations[row].component << ":  "
            << textbook.equation(system, row, TextbookForm::Style::text) << " = 0\n";
      }
    }

    out << "\n2. Jacobian Phi_q (rows " << joined(rows) << "; columns " << joined(unknowns) << ")\n\n";
    for (std::size_t i = 0; i < n; ++i) {
      out << "  " << rows[i] << ":  [ ";
      for (std::size_t j = 0; j < n; ++j) out << (j ? ",  " : "") << text(d.jacobian(i, j));
      out << " ]\n";
    }
    out << "\n  Phi_" << input.name << " = [ ";
    for (std::size_t i = 0; i < n; ++i) out << (i ? ",  " : "") << text(d.input_jacobian(i, 0));
    out << " ]\n";

    out << "\n3. Velocity equations  Phi_q * [" << joined(rates) << "] = -Phi_" << input.name << " * "
        << input.rate.get_name() << "\n\n";
    for (std::size_t i = 0; i < n; ++i) {
      ex left = 0;
      for (std::size_t j = 0; j < n; ++j) left += d.jacobian(i, j) * system.unknowns[j].rate;
      out << "  " << rows[i] << ":  " << text(left) << " = " << text(-d.input_jacobian(i, 0) * input.rate) << "\n";
    }

    out << "\n4. Acceleration equations  Phi_q * [" << joined(second_rates)
        << "] = -(Phi_q * qd)_q * qd - 2 (Phi_q * qd)_" << input.name << " * " << input.rate.get_name()
        << " - Phi_" << input.name << input.name << " * " << input.rate.get_name() << "^2 - Phi_" << input.name
        << " * " << input.second_rate.get_name() << "\n\n";
    for (std::size_t i = 0; i < n; ++i) {
      ex left = 0;
      for (std::size_t j = 0; j < n; ++j) left += d.jacobian(i, j) * system.unknowns[j].second_rate;
      out << "  " << rows[i] << ":  " << text(left) << " = " << text(d.acceleration_rhs_combined[i]) << "\n";
    }

    out << "\n5. Solved rates (Cramer's rule, block by block)\n";
    for (const SolvingBlock& block : d.blocks) {
      std::vector<std::string> groups;
      for (std::size_t k : block.groups) groups.push_back(system.groups[k].name);
      out << "\n  from " << system.groups[block.groups.front()].kind << " " << joined(groups) << ":\n";
      for (std::size_t j : block.unknowns) {
        out << "    " << rates[j] << " = "
            << textbook.solved(d.solved_rates[j], system.unknowns[j].symbol, TextbookForm::Style::text) << "\n";
      }
      for (std::size_t j : block.unknowns)
        out << "    " << second_rates[j] << " = "
            << textbook.solved(d.solved_second_rates[j], system.unknowns[j].symbol, TextbookForm::Style::text) << "\n";
    }

    if (!system.points.empty()) {
      out << "\n6. Points\n";
      auto label = [](const std::string& name) { return name + std::string(name.size() < 4 ? 4 - name.size() : 1, ' '); };
      for (std::size_t p = 0; p < system.points.size(); ++p) {
        const PointObservable& point = system.points[p];
        out << "\n  " << point.name;
        if (point.written) out << " = " << text(*point.written);
        out << "\n";
        const auto& components = point.components;
        for (std::size_t c = 0; c < components.size(); ++c)
          out << "    " << label(components[c]) << "= " << text(point.position[c]) << "\n";
        for (std::size_t c = 0; c < components.size(); ++c)
          out << "    " << label("v" + components[c]) << "= " << text(d.points[p].velocity[c]) << "\n";
        for (std::size_t c = 0; c < components.size(); ++c)
          out << "    " << label("a" + components[c]) << "= " << text(d.points[p].acceleration_combined[c]) << "\n";
      }
    }
  }
};

}  // namespace

const Printer& derivation_text_printer() {
  static const DerivationTextPrinter printer;
  return printer;
}

}  // namespace kinema
